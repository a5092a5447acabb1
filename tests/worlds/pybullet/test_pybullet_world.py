"""The PyBullet world on its own: geometric conditions, OMPL paths, refinement, skills."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from sim_scenes import YOUBOT_SCENE, figure7_tree, write_scene, youbot_task

from btplan.bt import RUNNING, SUCCESS, BehaviorTree
from btplan.model import Atom
from btplan.worlds.pybullet import PyBulletWorld, open_world
from btplan.worlds.pybullet.geometry import clearance, distance

TASK = youbot_task()
MOVE = TASK.domain.action_map["MoveTo"]
PLACE = TASK.domain.action_map["Place"]


def param(template: object, name: str) -> object:
    return next(p for p in template.parameters if p.name == name)  # type: ignore[attr-defined]


@pytest.fixture
def room(tmp_path: Path) -> Iterator[PyBulletWorld]:
    world = open_world(TASK, write_scene(tmp_path), seed=3)
    yield world
    world.close()


@pytest.fixture
def youbot() -> Iterator[PyBulletWorld]:
    world = open_world(TASK, str(YOUBOT_SCENE), seed=3)
    yield world
    world.close()


def trajectory_to(world: PyBulletWorld, target: str) -> str:
    (name,) = world.refine(MOVE, {"l": target}, param(MOVE, "t"))  # type: ignore[arg-type]
    return name


def test_conditions_are_read_from_the_scene(room: PyBulletWorld) -> None:
    assert room.check(("hand_empty", ()))
    assert not room.check(("near", ("green",)))
    assert not room.check(("on", ("green", "goal")))
    assert not room.check(("near", ("red",)))  # red is not in the scene
    facts = room.facts()
    assert Atom("hand_empty", ()) in facts and Atom("near", ("green",)) not in facts


def test_a_refined_trajectory_is_a_collision_free_ompl_path_to_the_target(
        youbot: PyBulletWorld) -> None:
    name = trajectory_to(youbot, "green")
    traj = youbot.state.trajectories[name]
    assert traj.path[0][:2] == youbot.state.base[:2]
    assert distance(traj.path[-1], youbot.state.location("green")) <= youbot.scene.near
    walls_and_cubes = youbot.state.floor_cubes("green")
    assert all(youbot.state.sim.base_free(x, y, walls_and_cubes) for x, y, _ in traj.path)
    assert not youbot.check(("blocks", ("_", name))) and youbot.check(("route", ("green", name)))
    assert youbot.routes.plan_seconds and youbot.routes.plan_seconds[-1] < 5


def test_the_same_question_gets_the_same_trajectory(youbot: PyBulletWorld) -> None:
    assert trajectory_to(youbot, "goal") == trajectory_to(youbot, "goal")


def test_a_cube_in_the_doorway_blocks_the_only_way_and_a_pose_aside_is_sampled(
        youbot: PyBulletWorld) -> None:
    to_green, to_goal = trajectory_to(youbot, "green"), trajectory_to(youbot, "goal")
    assert youbot.check(("blocks", ("_", to_goal))) and youbot.check(("blocks", ("blue", to_goal)))
    assert Atom("blocks", ("blue", to_goal)) in youbot.facts()
    # Place's target is refined when the condition does not fix it: a pose off every path.
    (pose,) = youbot.refine(PLACE, {"c": "blue"}, param(PLACE, "l"))  # type: ignore[arg-type]
    spot = youbot.state.poses[pose]
    storage = youbot.scene.region("storage")
    assert storage is not None and storage.contains(*spot)
    keep = youbot.scene.robot_radius + youbot.scene.cube_size
    for name in (to_green, to_goal):
        assert clearance(spot, youbot.state.trajectories[name].path) > keep


def test_a_pose_gone_stale_is_sampled_again_under_its_name(youbot: PyBulletWorld) -> None:
    """RefineActions again: a pose another cube now occupies gets a fresh spot."""
    (pose,) = youbot.refine(PLACE, {"c": "blue"}, param(PLACE, "l"))  # type: ignore[arg-type]
    first = youbot.state.poses[pose]
    youbot.state.put("red", first)  # someone put red exactly there
    assert youbot.refine(PLACE, {"c": "blue"}, param(PLACE, "l")) == [pose]  # same name
    youbot.routes.refresh_pose(pose)
    fresh = youbot.state.poses[pose]
    assert distance(fresh, first) > 0.1 and youbot.routes.refreshed == 1
    storage = youbot.scene.region("storage")
    assert storage is not None and storage.contains(*fresh)
    youbot.routes.refresh_pose(pose)  # still good: kept
    assert youbot.state.poses[pose] == fresh and youbot.routes.refreshed == 1
    # A path planned since that runs over the pose makes it stale too.
    to_pose = trajectory_to(youbot, pose)
    assert youbot.state.trajectories[to_pose].target == pose  # its own path does not count
    youbot.routes.refresh_pose(pose)
    assert youbot.state.poses[pose] == fresh


def test_blocks_is_checked_again_every_time_so_a_moved_cube_blocks_a_path(
        room: PyBulletWorld) -> None:
    name = trajectory_to(room, "green")
    path = room.state.trajectories[name].path
    assert not room.check(("blocks", ("_", name)))
    middle = path[len(path) // 2]
    room.state.put("red", (middle[0], middle[1]))
    assert room.check(("blocks", ("_", name))) and room.check(("blocks", ("red", name)))
    room.state.put("red", None)
    assert not room.check(("blocks", ("_", name)))


def test_a_path_the_robot_drove_off_is_joined_from_where_it_stands_not_planned_again(
        room: PyBulletWorld) -> None:
    name = trajectory_to(room, "goal")
    traj = room.state.trajectories[name]
    before, solves = traj.path, len(room.routes.plan_seconds)
    beside = before[len(before) // 2]
    room.state.move_base((beside[0], beside[1] + 0.3, 0.0))  # far from the start, near the path
    assert not room.check(("blocks", ("_", name)))
    assert len(room.routes.plan_seconds) == solves and room.routes.joined == 1
    assert traj.path[0] == room.state.base and traj.path[-1] == before[-1]
    assert all(room.state.sim.base_free(x, y, []) for x, y, _ in traj.path)
    assert max(distance(a, b) for a, b in zip(traj.path, traj.path[1:])) <= 0.05 + 1e-9
    room.state.move_base((beside[0], beside[1] + 1.2, 0.0))  # too far from every waypoint
    assert not room.check(("blocks", ("_", name)))
    assert len(room.routes.plan_seconds) == solves + 1 and room.routes.joined == 1
    assert traj.path[0] == room.state.base


def test_a_path_to_a_cube_that_moved_a_little_is_extended_to_the_new_approach_pose(
        room: PyBulletWorld) -> None:
    name = trajectory_to(room, "green")
    traj = room.state.trajectories[name]
    solves = len(room.routes.plan_seconds)
    room.state.put("green", (2.2, 1.1))
    assert not room.check(("blocks", ("_", name)))
    assert len(room.routes.plan_seconds) == solves and room.routes.joined == 1
    green = room.state.location("green")
    assert distance(traj.path[-1], green) <= room.scene.near and traj.goal == traj.path[-1]
    assert all(room.state.sim.base_free(x, y, []) for x, y, _ in traj.path)
    room.state.put("green", (4.0, -1.0))  # moved far: planned again
    assert not room.check(("blocks", ("_", name)))
    assert len(room.routes.plan_seconds) == solves + 1 and room.routes.joined == 1
    assert distance(traj.path[-1], room.state.location("green")) <= room.scene.near


SHELF = """
[[wall]]
name = "shelf"
center = [3.0, -1.2]
size = [0.4, 0.4]
height = 0.04
z = 0.6
"""

KNOCK = """
[[event]]
name = "cat"
do = "knock"
cube = "red"
from = [3.0, -1.1]
to = [3.0, 0.0]
tick = 2
"""


def test_a_cube_knocked_off_a_shelf_falls_and_comes_to_rest_on_the_floor(tmp_path: Path) -> None:
    from sim_scenes import OPEN_ROOM

    world = open_world(TASK, write_scene(tmp_path, OPEN_ROOM + SHELF, KNOCK), seed=3)
    try:
        (agents,) = world.scene_agents()
        assert agents.act(world, 1) == [] and not world.state.present("red")
        (news,) = agents.act(world, 2)
        assert news.description.startswith("cat: red knocked off")
        assert world.state.sim.cube_position("red")[2] > 0.64  # on the board
        assert world.outside_changes == 1
        for _ in range(3 * 240):  # three simulated seconds
            world.state.sim.step()
        x, y, _ = world.state.sim.cube_position("red")
        assert world.state.resting("red") and world.state.present("red")
        assert abs(x - 3.0) < 0.2 and -0.95 < y < 0.0  # off the board's edge, the way it went
    finally:
        world.close()


def test_a_knock_needs_where_the_cube_sits_and_where_it_goes(tmp_path: Path) -> None:
    from btplan.errors import InputError

    with pytest.raises(InputError, match="a knock needs 'from"):
        open_world(TASK, write_scene(tmp_path, events=KNOCK.replace("to = [3.0, 0.0]\n", "")))


def test_the_figure7_tree_runs_the_skills_over_many_ticks(room: PyBulletWorld) -> None:
    tree = BehaviorTree(figure7_tree(trajectory_to(room, "green"), trajectory_to(room, "goal")))
    statuses = [tree.tick(room) for _ in range(200)]
    assert SUCCESS in statuses
    done = statuses.index(SUCCESS)
    assert done > 20 and all(s is RUNNING for s in statuses[:done])
    assert [a.name for a in room.executed] == ["MoveTo", "Pick", "MoveTo", "Place"]
    assert room.check(("on", ("green", "goal"))) and room.check(("hand_empty", ()))
    region = room.scene.region("goal")
    assert region is not None and region.contains(*room.state.location("green"))


def test_a_halted_move_stops_the_base_where_it_is(room: PyBulletWorld) -> None:
    key = ("MoveTo", ("green", trajectory_to(room, "green")))
    assert room.start(key) is RUNNING
    for _ in range(5):  # it turns on the spot first, then drives
        room.step(key)
    stopped = room.state.base
    room.halt(key)
    assert [a.key for a in room.halted] == [key]
    assert room.state.base == stopped and stopped[:2] != room.scene.start[:2]
    assert room.check(("hand_empty", ()))


def test_pick_fails_out_of_reach_and_actions_are_logged_grounded(room: PyBulletWorld) -> None:
    from btplan.bt import FAILURE

    assert room.start(("Pick", ("green",))) is FAILURE
    assert [a.ipc() for a in room.failed] == ["(pick green)"]


def test_record_writes_a_gif_with_the_current_action_on_each_frame(tmp_path: Path) -> None:
    from PIL import Image

    movie = tmp_path / "run.gif"
    world = open_world(TASK, write_scene(tmp_path), seed=3, record=str(movie))
    try:
        tree = BehaviorTree(figure7_tree(trajectory_to(world, "green"), trajectory_to(world, "goal")))
        for _ in range(12):
            tree.tick(world)
    finally:
        world.close()
    with Image.open(movie) as image:
        assert image.format == "GIF" and image.size == (640, 400)
        assert image.n_frames == 6  # one frame every second action tick
        first = image.convert("RGB")
        # The label bar is drawn on top: black with white text.
        assert first.getpixel((400, 2)) == (0, 0, 0)
        assert any(first.getpixel((x, 10)) != (0, 0, 0) for x in range(6, 120))


def test_record_writes_an_mp4_with_the_encoder_of_the_sim_extra(tmp_path: Path) -> None:
    movie = tmp_path / "run.mp4"
    world = open_world(TASK, write_scene(tmp_path), seed=3, record=str(movie))
    try:
        tree = BehaviorTree(figure7_tree(trajectory_to(world, "green"), trajectory_to(world, "goal")))
        for _ in range(6):
            tree.tick(world)
        assert not movie.exists()  # written next to it, renamed at the end
    finally:
        world.close()
    data = movie.read_bytes()
    assert data[4:8] == b"ftyp" and len(data) > 1000
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".btplan-")] == []


def test_record_refuses_formats_it_cannot_write(tmp_path: Path) -> None:
    from btplan.errors import WorldError

    with pytest.raises(WorldError, match="use a .mp4 or .gif"):
        open_world(TASK, write_scene(tmp_path), record=str(tmp_path / "run.avi"))


def test_a_scene_without_a_location_of_the_problem_is_refused(tmp_path: Path) -> None:
    """Bad input located at the scene file, not a failure of the world."""
    from btplan.errors import InputError

    text = write_scene(tmp_path)
    Path(text).write_text(Path(text).read_text().replace('name = "goal"', 'name = "target"'))
    with pytest.raises(InputError, match="'goal' is a location in the problem but not in this "
                                         "scene") as caught:
        open_world(TASK, text)
    assert caught.value.span is not None and caught.value.span.path == text


def test_an_event_condition_must_be_a_predicate_of_the_domain(tmp_path: Path) -> None:
    from btplan.errors import InputError

    event = '\n[[event]]\nname = "e"\nwhen = "holdng(green)"\ndo = "remove"\ncube = "red"\n'
    with pytest.raises(InputError) as caught:
        open_world(TASK, write_scene(tmp_path, events=event))
    assert "is not a condition of the domain" in caught.value.message
    assert caught.value.hint == "did you mean 'holding'?"
    assert caught.value.source_line == 'when = "holdng(green)"'


def test_a_cube_put_on_the_path_ahead_stops_a_running_move(room: PyBulletWorld) -> None:
    from btplan.bt import FAILURE

    name = trajectory_to(room, "goal")
    key = ("MoveTo", ("goal", name))
    assert room.start(key) is RUNNING
    path = room.state.trajectories[name].path
    ahead = path[int(len(path) * 0.6)]
    room.state.put("red", (ahead[0], ahead[1]))
    assert room.check(("blocks", ("red", name)))
    assert room.step(key) is FAILURE
    assert [a.key for a in room.failed] == [key]


PLAN_ONE = """
import sys
from btplan.lang import load
from btplan.worlds.pybullet import open_world
task = load([sys.argv[1]], None)
move = task.domain.action_map["MoveTo"]
world = open_world(task, seed=int(sys.argv[2]))
world.state.move_base((1.0, -1.5, 0.0))  # the way to the goal now bends through the doorway
(name,) = world.refine(move, {"l": "goal"}, move.parameters[1])
print(repr(world.state.trajectories[name].path))
world.close()
"""


@pytest.mark.slow
def test_a_seed_fixes_the_planned_path() -> None:
    """Each plan in a fresh interpreter, as the CLI and a sweep's workers run them."""
    import subprocess
    import sys

    from sim_scenes import YOUBOT

    def plan(seed: int) -> str:
        done = subprocess.run([sys.executable, "-c", PLAN_ONE, str(YOUBOT), str(seed)],
                              capture_output=True, text=True, check=True)
        return done.stdout

    first = plan(7)
    assert first.startswith("((1.0, -1.5, 0.0),")
    assert plan(7) == first
    assert plan(8) != first


def test_a_base_path_starts_or_ends_facing_due_west() -> None:
    import math

    from btplan.worlds.pybullet.motion import ompl_yaw, plan_se2

    west = math.atan2(0.0, -1.0)  # exactly pi, as a pose facing a target west of it gets
    assert ompl_yaw(west) == -math.pi and ompl_yaw(-math.pi) == -math.pi
    assert ompl_yaw(3 * math.pi / 2) == -math.pi / 2

    def free(x: float, y: float) -> bool:
        return abs(x) > 0.5 or abs(y) < 0.3  # a wall with a door at y = 0

    bounds = (-2.0, 2.0, -2.0, 2.0)
    there = plan_se2((-1.5, 1.0, 0.0), (1.5, -1.0, west), free, bounds, 5000)
    back = plan_se2((1.5, -1.0, west), (-1.5, 1.0, 0.0), free, bounds, 5000)
    assert there is not None and back is not None
    assert there.path[-1] == (1.5, -1.0, west) and back.path[0] == (1.5, -1.0, west)
