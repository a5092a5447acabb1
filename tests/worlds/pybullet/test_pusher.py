"""The scene's agents act through the pusher: cubes travel over the floor by contact.

No skill runs here: the test steps the physics itself, one tick's worth of substeps
after every call of the agents, as the skills would.
"""

from __future__ import annotations

import math
from pathlib import Path

from sim_scenes import OPEN_ROOM, write_scene, youbot_task

from btplan.worlds.pybullet import PyBulletWorld, open_world
from btplan.worlds.pybullet.scene import load_scene

TASK = youbot_task()
WALLED = OPEN_ROOM + """
[[wall]]
name = "post"
center = [3.5, 1.0]
size = [0.2, 0.6]
"""


def advance(world: PyBulletWorld, ticks: int, first: int = 1) -> list[str]:
    """Tick the agents and step the physics; returns what they reported."""
    said: list[str] = []
    sim = world.state.sim
    for tick in range(first, first + ticks):
        said += [d.description for a in world.scene_agents() for d in a.act(world, tick)]
        for _ in range(24):
            sim.step()
    return said


def at(world: PyBulletWorld, cube: str) -> tuple[float, float]:
    x, y, _ = world.state.sim.cube_position(cube)
    return (x, y)


def test_a_move_pushes_the_cube_by_contact_to_its_target(tmp_path: Path) -> None:
    events = """
[[event]]
name = "push green"
tick = 1
do = "move"
cube = "green"
to = [3.0, -1.0]
"""
    world = open_world(TASK, write_scene(tmp_path, events=events), seed=0)
    try:
        changes = world.outside_changes
        said = advance(world, 80)
        assert said[0] == "push green: the pusher sets off to push green to [3.0, -1.0]"
        assert said[1].startswith("push green: green pushed to")
        assert math.dist(at(world, "green"), (3.0, -1.0)) < 0.02
        assert world.state.resting("green")
        assert world.outside_changes > changes + 20   # counted, for the acting loop
    finally:
        world.close()


def test_a_cube_is_brought_in_from_outside_and_removed_out_of_the_scene(
        tmp_path: Path) -> None:
    events = """
[[event]]
name = "bring red"
tick = 1
do = "move"
cube = "red"
from = [4.5, -2.4]
to = [4.5, 0.0]

[[event]]
name = "take red"
tick = 40
do = "remove"
cube = "red"
to = [4.5, 2.5]
"""
    world = open_world(TASK, write_scene(tmp_path, events=events), seed=0)
    try:
        assert not world.state.present("red")
        said = advance(world, 38)
        assert world.state.present("red") and math.dist(at(world, "red"), (4.5, 0.0)) < 0.02
        said += advance(world, 60, 39)
        assert "take red: red pushed out of the scene" in said
        assert not world.state.present("red")
    finally:
        world.close()


def test_a_push_into_a_wall_is_given_up_where_the_cube_stands(tmp_path: Path) -> None:
    events = """
[[event]]
name = "push green through the post"
tick = 1
do = "move"
cube = "green"
to = [5.0, 1.0]
"""
    world = open_world(TASK, write_scene(tmp_path, WALLED, events), seed=0)
    try:
        said = advance(world, 80)
        assert any(s.startswith("push green through the post: green stuck at") for s in said)
        x, y = at(world, "green")
        assert 2.5 < x < 3.4 and abs(y - 1.0) < 0.1   # stopped against the post
    finally:
        world.close()


def test_from_is_read_from_the_scene_file(tmp_path: Path) -> None:
    events = """
[[event]]
name = "bring red"
tick = 1
do = "move"
cube = "red"
from = [4.5, -2.4]
to = [4.5, 0.0]
"""
    (event,) = load_scene(write_scene(tmp_path, events=events)).events
    assert event.origin == (4.5, -2.4) and event.to == (4.5, 0.0)


def test_a_shove_targets_only_spots_a_straight_push_reaches() -> None:
    from sim_scenes import YOUBOT_SCENE

    from btplan.worlds.pybullet.agents import _free_spot

    world = open_world(TASK, str(YOUBOT_SCENE), seed=0)
    try:
        state = world.state
        start = at(world, "green")  # west of the wall between the rooms (x 3.9 to 4.1)
        spots = [s for s in (_free_spot(state, "green", k / 40) for k in range(40)) if s]
        assert len(spots) > 20
        for x, y in spots:
            if x > 3.9 - state.scene.cube_size / 2:  # past the wall: through the doorway
                crossing = start[1] + (y - start[1]) * (3.9 - start[0]) / (x - start[0])
                assert abs(crossing) < 0.6
        assert any(x > 4.1 for x, _ in spots)  # the far room is still a target
    finally:
        world.close()


def test_a_pusher_that_ends_beside_the_robot_drives_out_round_the_cubes() -> None:
    """A shove run (repair, seed 8): the push ended 0.53 m from the robot, inside the
    0.62 m kept round it, so the way out had no valid start, and the pusher drove out in
    a straight line that shoved green, lying on it, out of the scene."""
    from sim_scenes import YOUBOT_SCENE

    from btplan.worlds.pybullet.pusher import RADIUS, Pusher

    world = open_world(TASK, str(YOUBOT_SCENE), seed=8)
    try:
        state = world.state
        state.put("blue", None)
        state.put("green", (4.54, -0.55))
        state.move_base((4.54, -0.02, -1.31))
        start, home = (4.53, 0.51), (4.51, -3.6)
        route = Pusher(state)._route(start, home)
        assert route != [home] and route[-1] == home
        assert math.dist(route[0], start) <= 0.3
        line = [start, *route]
        for a, b in zip(line, line[1:]):  # every leg keeps off green
            n = max(1, math.ceil(math.dist(a, b) / 0.02))
            assert all(math.dist((a[0] + (b[0] - a[0]) * k / n, a[1] + (b[1] - a[1]) * k / n),
                                 (4.54, -0.55)) > RADIUS for k in range(n + 1))
    finally:
        world.close()


def test_a_pusher_with_no_free_way_out_leaves_the_scene_without_driving_through_cubes(
        tmp_path: Path) -> None:
    """A shove run (repair, seed 12 at p = 0): with no free way out, the pusher drove out
    in a straight line and shoved green, lying on the line, 3 m into a corner where no
    base pose beside it is free; every later MoveTo(green) failed at once. Now it leaves
    the scene at once."""
    from btplan.worlds.pybullet.pusher import Push, Pusher
    from btplan.worlds.pybullet.sim import PARKED_Z

    world = open_world(TASK, write_scene(tmp_path), seed=0)
    try:
        state = world.state
        pusher = Pusher(state)
        robot = state.base
        # Beside the robot, deeper in the disc kept round it than an escape reaches.
        inside = (robot[0] + 0.1, robot[1])
        assert pusher._route(inside, (10.0, 0.0)) is None
        pusher._put(inside, 0.0)
        on_the_line = (inside[0] + 0.8, inside[1])  # on the straight way to the home at x = 10
        state.put("green", on_the_line)
        push = Push("shove", "green", (3.0, 0.0), False, (10.0, 0.0), 0.0, phase="back")
        pusher.push = push
        pusher._arrived(push)
        assert pusher.push is None
        for _ in range(48):
            state.sim.step()
        (_, _, z), _ = state.sim.p.getBasePositionAndOrientation(
            pusher.body, physicsClientId=state.sim.client)
        assert z < PARKED_Z / 2  # parked below the floor, not driving
        assert math.dist(at(world, "green"), on_the_line) < 0.005
    finally:
        world.close()
