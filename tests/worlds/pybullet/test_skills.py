"""Each skill on its own, in a small room: success, failure, and a halt at every tick.

A halted skill must leave the world consistent: a cube that is held stays held (and
`holding` says so), anything else is let go and comes to rest, and the arm is folded.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from sim_scenes import write_scene, youbot_task

from btplan.bt import FAILURE, RUNNING, SUCCESS
from btplan.worlds.pybullet import PyBulletWorld, open_world
from btplan.worlds.pybullet.geometry import distance
from btplan.worlds.pybullet.robot import CARRY

TASK = youbot_task()
MOVE = TASK.domain.action_map["MoveTo"]
SMALL = """
[world]
bounds = [-1.0, 3.0, -1.5, 1.5]

[robot]
start = [0.0, 0.0, 0.0]

[[region]]
name = "goal"
min = [-0.1, -0.9]
max = [0.7, -0.3]

[[cube]]
name = "green"
at = [0.6, 0.0]

[[cube]]
name = "blue"
at = [1.9, 0.8]

[[cube]]
name = "red"

[[cube]]
name = "yellow"
"""

Key = tuple[str, tuple[str, ...]]


@pytest.fixture
def room(tmp_path: Path) -> Iterator[PyBulletWorld]:
    world = open_world(TASK, write_scene(tmp_path, SMALL), seed=1)
    yield world
    world.close()


def run(world: PyBulletWorld, key: Key, limit: int = 200) -> tuple[object, int]:
    status, ticks = world.start(key), 1
    while status is RUNNING and ticks < limit:
        status, ticks = world.step(key), ticks + 1
    return status, ticks


def folded(world: PyBulletWorld) -> bool:
    joints = world.state.sim.robot.joints()
    return max(abs(a - b) for a, b in zip(joints, CARRY)) < 0.1


def consistent(world: PyBulletWorld, cube: str) -> bool:
    """Held and said to be held, or out of the hand, at rest, and said so; arm folded."""
    state = world.state
    holding = world.check(("holding", (cube,)))
    if holding != (not world.check(("hand_empty", ()))):
        return False
    if holding:
        return state.sim.robot.grip is not None and folded(world)
    z = state.sim.cube_position(cube)[2]
    return state.sim.robot.grip is None and z < state.scene.cube_size / 2 + 0.01 and folded(world)


def test_pick_lifts_the_cube_and_holding_is_read_from_the_fingers(room: PyBulletWorld) -> None:
    assert run(room, ("Pick", ("green",))) [0] is SUCCESS
    assert room.check(("holding", ("green",))) and not room.check(("hand_empty", ()))
    assert room.state.sim.cube_position("green")[2] > room.scene.cube_size / 2
    assert all(room.state.sim.robot.touching(room.state.sim.cubes["green"]))


def test_pick_fails_when_the_cube_is_taken_while_the_arm_reaches(room: PyBulletWorld) -> None:
    key = ("Pick", ("green",))
    assert room.start(key) is RUNNING
    room.step(key)
    room.state.put("green", None)  # an agent takes it
    status, _ = run_on(room, key)
    assert status is FAILURE and room.check(("hand_empty", ()))
    assert folded(room) and room.state.sim.robot.grip is None


def test_pick_fails_when_the_fingers_close_on_nothing(room: PyBulletWorld) -> None:
    key = ("Pick", ("green",))
    status = room.start(key)
    while status is RUNNING and room.state.sim.robot.tip()[2] > 0.06:
        status = room.step(key)  # until the hand is down at the cube
    x, y, _ = room.state.sim.cube_position("green")
    room.state.put("green", (x, y + 0.1))  # nudged away just before the fingers close
    status, _ = run_on(room, key)
    assert status is FAILURE and room.check(("hand_empty", ()))
    assert folded(room) and room.state.sim.robot.grip is None


def test_closing_the_world_halts_a_running_skill_safely(room: PyBulletWorld) -> None:
    key = ("Pick", ("green",))
    assert room.start(key) is RUNNING
    room.close()
    assert not room.running and [a.key for a in room.halted] == [key]


def test_pick_fails_on_a_cube_out_of_the_arms_reach(room: PyBulletWorld) -> None:
    assert run(room, ("Pick", ("blue",)))[0] is FAILURE


AGAINST_A_WALL = SMALL.replace("at = [0.6, 0.0]", "at = [0.875, 0.0]") + """
[[wall]]
name = "wall"
center = [1.0, 0.0]
size = [0.2, 2.0]
"""


def test_a_side_the_grasp_failed_from_is_not_offered_again(tmp_path: Path) -> None:
    from btplan.worlds.pybullet.samplers import approach_pose
    from btplan.worlds.pybullet.state import MISSED

    world = open_world(TASK, write_scene(tmp_path, AGAINST_A_WALL), seed=1)
    try:
        state = world.state
        first = approach_pose(state, "green")
        assert first is not None
        state.sim.set_robot(first)  # facing the cube, the hand's back to the wall's face
        assert world.check(("near", ("green",)))
        assert run(world, ("Pick", ("green",)))[0] is FAILURE
        assert not world.check(("near", ("green",))) and world.lessons == 1
        other = approach_pose(state, "green")
        assert other is not None and distance(other, first) > MISSED
        assert world.dead_ends() == []  # other sides are left to try
        for _ in range(16):  # flush against the wall, the hand fits on no side
            pose = approach_pose(state, "green")
            if pose is None:
                break
            state.sim.set_robot(pose)
            state.out_of_reach.pop("green")  # as MoveTo does at the end of its path
            assert run(world, ("Pick", ("green",)))[0] is FAILURE
        assert approach_pose(state, "green") is None
        assert world.dead_ends() == [
            f"the arm found no grasp of green from any of the {world.lessons} sides the base "
            "can stand on"]
        state.put("green", (0.3, 0.8))  # moved: every side is worth a try again
        assert state.missed_poses("green") == []
    finally:
        world.close()


def test_an_obstacle_in_hand_blocks_every_way_but_the_one_to_put_it_aside(
        room: PyBulletWorld) -> None:
    from btplan.worlds.pybullet.paths import Trajectory

    assert run(room, ("Pick", ("green",)))[0] is SUCCESS
    path = ((room.state.base[0], room.state.base[1], 0.0), (1.5, 0.5, 0.0))
    room.state.poses["pose1"] = (1.5, 0.5)
    for target in ("blue", "goal"):
        way = Trajectory(f"to_{target}", target, path, clearing={"green"})
        assert room.state.path_blockers(way) == {"green"}  # not yet put aside
    aside = Trajectory("to_pose1", "pose1", path, clearing={"green"})
    assert room.state.path_blockers(aside) == set()  # carried to where it goes


def test_place_puts_the_cube_down_where_on_reads_it(room: PyBulletWorld) -> None:
    assert run(room, ("Pick", ("green",)))[0] is SUCCESS
    assert run(room, ("Place", ("green", "goal")))[0] is SUCCESS
    assert room.check(("on", ("green", "goal"))) and room.check(("hand_empty", ()))
    assert room.state.sim.robot.grip is None


def test_place_fails_without_the_cube_in_hand(room: PyBulletWorld) -> None:
    assert run(room, ("Place", ("green", "goal")))[0] is FAILURE
    assert not room.check(("on", ("green", "goal")))


def test_a_slip_mid_carry_drops_the_cube_and_holding_turns_false(room: PyBulletWorld) -> None:
    (to_blue,) = room.refine(MOVE, {"l": "blue"}, MOVE.parameters[1])
    assert run(room, ("Pick", ("green",)))[0] is SUCCESS
    key = ("MoveTo", ("blue", to_blue))
    for _ in range(4):
        room.step(key) if room.running else room.start(key)
    room.state.sim.robot.slip()
    room.step(key)
    assert not room.check(("holding", ("green",))) and room.check(("hand_empty", ()))
    for _ in range(5):
        room.step(key)
    assert room.state.resting("green")


def run_on(world: PyBulletWorld, key: Key, limit: int = 200) -> tuple[object, int]:
    status, ticks = world.step(key), 1
    while status is RUNNING and ticks < limit:
        status, ticks = world.step(key), ticks + 1
    return status, ticks


def halts(tmp_path: Path, prepare: Callable[[PyBulletWorld], Key], cube: str) -> int:
    """Halt the skill after 1, 2, ... ticks (a fresh world each time) until it ends by itself."""
    folder = tmp_path / "halt"
    folder.mkdir(exist_ok=True)
    scene = write_scene(folder, SMALL)
    halted_at = 0
    for k in range(1, 200):
        world = open_world(TASK, scene, seed=1)
        try:
            key = prepare(world)
            status = world.start(key)
            for _ in range(k - 1):
                if status is not RUNNING:
                    break
                status = world.step(key)
            if status is not RUNNING:
                return halted_at
            world.halt(key)
            halted_at += 1
            assert not world.running
            assert consistent(world, cube), f"{key[0]} halted after {k} ticks"
        finally:
            world.close()
    raise AssertionError("the skill never ended")


def picked(world: PyBulletWorld) -> None:
    assert run(world, ("Pick", ("green",)))[0] is SUCCESS


@pytest.mark.slow
def test_halting_pick_at_every_tick_leaves_the_world_consistent(tmp_path: Path) -> None:
    assert halts(tmp_path, lambda w: ("Pick", ("green",)), "green") >= 5


@pytest.mark.slow
def test_halting_place_and_drop_at_every_tick_leaves_the_world_consistent(
        tmp_path: Path) -> None:
    def place(world: PyBulletWorld) -> Key:
        picked(world)
        return ("Place", ("green", "goal"))

    def drop(world: PyBulletWorld) -> Key:
        picked(world)
        return ("Drop", ("green",))

    assert halts(tmp_path, place, "green") >= 5
    assert halts(tmp_path, drop, "green") >= 5


@pytest.mark.slow
def test_halting_a_carry_at_every_tick_keeps_the_cube_in_hand(tmp_path: Path) -> None:
    def carry(world: PyBulletWorld) -> Key:
        picked(world)
        (to_blue,) = world.refine(MOVE, {"l": "blue"}, MOVE.parameters[1])
        return ("MoveTo", ("blue", to_blue))

    assert halts(tmp_path, carry, "green") >= 5


def test_ompl_plans_an_arm_motion_in_joint_space_around_a_forbidden_box() -> None:
    """Where the straight joint move collides, OMPL finds a way round (RealVectorStateSpace)."""
    from btplan.worlds.pybullet import motion
    from btplan.worlds.pybullet.arm import straight_free
    from btplan.worlds.pybullet.robot import LOWER, UPPER

    start = (-1.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0)
    goal = (1.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0)

    def free(q: tuple[float, ...]) -> bool:
        return not (abs(q[0]) < 0.3 and abs(q[1]) < 0.5)  # the first joints must swing round

    assert not straight_free(start, goal, free)
    plan = motion.plan_joints(start, goal, free, LOWER, UPPER, iterations=5000)
    assert plan is not None and plan.path[0] == start and plan.path[-1] == goal
    assert all(free(q) for q in plan.path)
    assert all(straight_free(a, b, free) for a, b in zip(plan.path, plan.path[1:]))


def test_a_spot_drop_could_not_reach_is_not_offered_again(
        room: PyBulletWorld, monkeypatch: pytest.MonkeyPatch) -> None:
    """Drop picked the same spot every time it was started, so a spot the arm cannot
    reach (beside a wall, over another cube) failed it every time until the run's ticks
    ran out; the spot that failed is remembered, and the next Drop puts the cube elsewhere."""
    from btplan.worlds.pybullet import arm, samplers

    assert run(room, ("Pick", ("green",)))[0] is SUCCESS
    first = samplers.drop_spot(room.state)
    assert first is not None
    solve = arm.solve

    def blocked_at_first(state: object, timings: object, target: tuple[float, ...],
                         yaw: float) -> tuple[float, ...] | None:
        if distance(target[:2], first) < 0.01:
            return None  # as if a wall stood between the arm and that spot
        return solve(state, timings, target, yaw)  # type: ignore[arg-type]

    monkeypatch.setattr(arm, "solve", blocked_at_first)
    drop = ("Drop", ("green",))
    assert run(room, drop)[0] is FAILURE and room.check(("holding", ("green",)))
    assert run(room, drop)[0] is SUCCESS and room.check(("hand_empty", ()))
    assert distance(room.state.location("green"), first) > 0.1
    assert room.lessons == 1


def test_a_pick_lets_go_of_a_cube_the_fingers_closed_on_but_did_not_lift(
        room: PyBulletWorld) -> None:
    """A shove run's pick halted as it lifted left red between closed fingers on the
    floor: `hand_empty` held, and every pick after it failed at once, to the tick limit."""
    key = ("Pick", ("green",))
    status = room.start(key)
    while status is RUNNING and room.state.held is None:
        status = room.step(key)
    assert status is RUNNING and not room.state.lifted("green")
    room.running.pop(key)  # what that halt left: a grasp on the floor
    assert room.state.held == "green" and room.check(("hand_empty", ()))
    assert run(room, key)[0] is SUCCESS
    assert room.check(("holding", ("green",)))
