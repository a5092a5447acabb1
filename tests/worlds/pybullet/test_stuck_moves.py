"""Moves that could get stuck: a start the planner's footprint rejects, a target no
approach pose reaches. Each must give a path, or fail at once, never loop."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from sim_scenes import YOUBOT_SCENE, youbot_task

from btplan.bt import FAILURE
from btplan.worlds.pybullet import PyBulletWorld, motion, open_world
from btplan.worlds.pybullet.geometry import distance

TASK = youbot_task()
MOVE = TASK.domain.action_map["MoveTo"]
BESIDE_THE_DOORWAY = (4.112582378088986, -0.1503822796254765, -2.2845806886476243)
"""Where a shove run's robot stopped (repair, seed 9), its path having grazed the doorway's
south wall: the centre lies 0.4498 m from the wall's corner, the disc's radius is 0.45."""


def door(x: float, y: float) -> bool:
    return abs(x) > 0.5 or abs(y) < 0.3  # a wall with a door at y = 0


def test_escape_finds_the_nearest_valid_state_along_a_line_of_rejected_ones() -> None:
    start = (0.45, 0.33, 0.0)  # in the wall's margin, beside the door
    free = motion.escape(start, door, 0.15)
    assert free is not None and door(free[0], free[1])
    assert distance(free, start) == pytest.approx(0.04)  # 3 cm down, or 5 cm across
    steps = 4  # the line every centimetre, before the state found
    line = [(start[0] + (free[0] - start[0]) * k / steps,
             start[1] + (free[1] - start[1]) * k / steps) for k in range(steps)]
    assert not any(door(x, y) for x, y in line)  # nothing valid was jumped over
    assert motion.escape((0.0, 1.0, 0.0), door, 0.15) is None  # deep in the wall: no escape


@pytest.fixture
def youbot() -> Iterator[PyBulletWorld]:
    world = open_world(TASK, str(YOUBOT_SCENE), seed=9)
    assert isinstance(world, PyBulletWorld)
    yield world
    world.close()


def trajectory_to(world: PyBulletWorld, target: str) -> str:
    param = next(p for p in MOVE.parameters if p.name == "t")
    (name,) = world.refine(MOVE, {"l": target}, param)
    return name


def test_a_move_planned_from_beside_the_doorway_wall_leaves_it_first(
        youbot: PyBulletWorld) -> None:
    state = youbot.state
    state.put("blue", None)
    state.move_base(BESIDE_THE_DOORWAY)
    assert not state.sim.base_free(BESIDE_THE_DOORWAY[0], BESIDE_THE_DOORWAY[1], [])
    name = trajectory_to(youbot, "goal")
    path = state.trajectories[name].path
    assert path and path[0] == state.base and youbot.stats()["paths_escaped"] == 1
    assert distance(path[-1], state.location("goal")) < 1.0
    head = [q for q in path if not state.sim.base_free(q[0], q[1], [])]
    assert head == list(path[:len(head)]) and len(head) <= 3  # a few centimetres out, then free
    assert not youbot.check(("blocks", ("_", name)))


def test_a_move_to_a_cube_no_pose_reaches_fails_at_once_and_says_why(
        youbot: PyBulletWorld) -> None:
    """Green pushed out of the scene's bounds (as the scene's pusher did in a shove run):
    the move used to drive its old path from where that began, then again, for hundreds
    of ticks; it must fail on its first tick, where it stands."""
    name = trajectory_to(youbot, "green")
    state = youbot.state
    state.put("green", (4.5, -3.8))
    start = state.base
    assert youbot.start(("MoveTo", ("green", name))) is FAILURE
    assert state.base == start
    assert youbot.reasons[-1][1] == "no free pose next to green to drive to"


def test_a_way_without_a_path_is_blocked_by_no_cube_and_its_move_says_why(
        youbot: PyBulletWorld) -> None:
    """From inside a wall no path leads anywhere. `not blocks(_, t)` used to be false
    then while the facts named no blocker: the planner found no achiever and the run
    ended stuck. Only cubes block; the move fails at once, with the reason."""
    state = youbot.state
    state.move_base((4.0, -1.8, 0.0))  # the middle of the doorway's south wall
    name = trajectory_to(youbot, "green")
    assert not state.trajectories[name].path
    assert not youbot.check(("blocks", ("_", name)))
    assert not any(a.predicate == "blocks" and a.args[1] == name for a in youbot.facts())
    assert youbot.start(("MoveTo", ("green", name))) is FAILURE
    assert youbot.reasons[-1][1] == "no path from here to green"
