"""Scene files: what a user writes, and the located errors for what they get wrong."""

from __future__ import annotations

from pathlib import Path

import pytest
from sim_scenes import OPEN_ROOM, YOUBOT_SCENE, write_scene

from btplan.errors import InputError
from btplan.limits import MAX_SCENE_ITEMS
from btplan.worlds.pybullet.agents import parse_literal
from btplan.worlds.pybullet.scene import load_scene


def test_the_youbot_scene_loads_with_its_walls_cubes_regions_and_events() -> None:
    scene = load_scene(YOUBOT_SCENE)
    assert [c.name for c in scene.cubes] == ["green", "blue", "red", "yellow"]
    assert scene.region("goal") is not None and scene.region("storage").aside  # type: ignore[union-attr]
    assert [e.do for e in scene.events] == ["move", "move", "remove"]
    assert scene.cubes[2].at is None  # red only arrives with an event


def test_bad_toml_points_at_the_line(tmp_path: Path) -> None:
    path = write_scene(tmp_path, OPEN_ROOM + "\n[[cube]]\nname = green\n")
    with pytest.raises(InputError) as caught:
        load_scene(path)
    assert caught.value.span is not None and caught.value.span.line == OPEN_ROOM.count("\n") + 3
    assert "bad TOML" in caught.value.message


def test_an_event_on_an_unknown_cube_names_the_known_ones(tmp_path: Path) -> None:
    event = '\n[[event]]\nname = "e"\ntick = 3\ndo = "remove"\ncube = "purple"\n'
    with pytest.raises(InputError) as caught:
        load_scene(write_scene(tmp_path, OPEN_ROOM + event))
    assert "unknown cube 'purple'" in caught.value.message
    assert caught.value.hint is not None and "green" in caught.value.hint
    assert caught.value.source_line == 'cube = "purple"'


def test_an_event_needs_a_tick_or_a_condition(tmp_path: Path) -> None:
    event = '\n[[event]]\nname = "e"\ndo = "remove"\ncube = "red"\n'
    with pytest.raises(InputError, match="exactly one of 'tick' or 'when'"):
        load_scene(write_scene(tmp_path, OPEN_ROOM + event))


def test_points_must_be_pairs_of_numbers(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="'at' must be a list of 2 numbers"):
        load_scene(write_scene(tmp_path, OPEN_ROOM.replace("[2.0, 1.0]", '["a", 1.0]')))


def test_a_missing_file_is_an_input_error(tmp_path: Path) -> None:
    with pytest.raises(InputError, match="no such file"):
        load_scene(tmp_path / "nope.toml")


@pytest.mark.parametrize(("text", "expected"), [
    ("holding(green)", (True, "holding", ("green",))),
    ("not near(goal)", (False, "near", ("goal",))),
    ("hand_empty", (True, "hand_empty", ())),
])
def test_event_conditions_are_written_as_in_the_domain(text: str, expected: object) -> None:
    assert parse_literal(text, None) == expected


def test_an_unreadable_event_condition_is_located(tmp_path: Path) -> None:
    event = '\n[[event]]\nname = "e"\nwhen = "holding(green"\ndo = "remove"\ncube = "red"\n'
    with pytest.raises(InputError) as caught:
        load_scene(write_scene(tmp_path, OPEN_ROOM + event))
    error = caught.value
    assert "cannot read the condition" in error.message
    assert error.span is not None and error.span.line == OPEN_ROOM.count("\n") + 4
    assert error.source_line == 'when = "holding(green"'


def test_a_misspelt_key_is_reported_with_the_likely_one(tmp_path: Path) -> None:
    text = OPEN_ROOM.replace('name = "green"', 'name = "green"\ncolour = [0, 1, 0]')
    with pytest.raises(InputError) as caught:
        load_scene(write_scene(tmp_path, text))
    assert caught.value.message == "unknown key 'colour' in [cube]"
    assert caught.value.hint == "did you mean 'color'?"
    assert caught.value.source_line == "colour = [0, 1, 0]"


@pytest.mark.parametrize(("extra", "message"), [
    ('\n[[event]]\nname = "e"\ntick = 2\ndelay = "soon"\ndo = "remove"\ncube = "red"\n',
     "'delay' must be a whole number of at least 0"),
    ('\n[[event]]\nname = "e"\ntick = 2\ncount = 0\ndo = "remove"\ncube = "red"\n',
     "'count' must be a whole number of at least 1"),
])
def test_event_numbers_are_checked(tmp_path: Path, extra: str, message: str) -> None:
    with pytest.raises(InputError, match=message):
        load_scene(write_scene(tmp_path, OPEN_ROOM + extra))


def test_robot_sizes_must_be_positive(tmp_path: Path) -> None:
    text = OPEN_ROOM.replace("start = [0.0, 0.0, 0.0]", "start = [0.0, 0.0, 0.0]\nradius = -1")
    with pytest.raises(InputError, match="'radius' must be a number of at least 0.05"):
        load_scene(write_scene(tmp_path, text))


@pytest.mark.parametrize(("old", "new", "expected"), [
    ("bounds = [-1.0, 7.0, -2.0, 2.0]", "bounds = [7.0, -1.0, -2.0, 2.0]",
     "'bounds' must be [x_min, x_max, y_min, y_max], each min below its max"),
    ("bounds = [-1.0, 7.0, -2.0, 2.0]", "bounds = [-1e300, 1e300, -2.0, 2.0]",
     "'bounds' must be a list of 4 numbers"),
    ("start = [0.0, 0.0, 0.0]", "start = [nan, 0.0, 0.0]", "'start' must be a list of 3 numbers"),
    ("start = [0.0, 0.0, 0.0]", "start = [0.0, 0.0, 0.0]\nradius = inf",
     "'radius' must be a number of at least 0.05"),
    ("[world]", "[world]\nspeed = 1e300", "'speed' must be a number of at least 0.01"),
    ("[world]", "[world]\ntick_seconds = " + "9" * 400,
     "'tick_seconds' must be a number of at least 0.001"),
])
def test_scene_numbers_are_finite_and_of_a_sensible_size(tmp_path: Path, old: str, new: str,
                                                         expected: str) -> None:
    """Past these, PyBullet loses precision and speed x tick duration overflows."""
    with pytest.raises(InputError, match=expected.replace("[", r"\[").replace("]", r"\]")):
        load_scene(write_scene(tmp_path, OPEN_ROOM.replace(old, new)))


def test_a_wall_has_a_positive_size(tmp_path: Path) -> None:
    wall = '\n[[wall]]\nname = "w"\ncenter = [3.0, 0.0]\nsize = [0.0, 1.0]\n'
    with pytest.raises(InputError, match="a wall's 'size' must be positive"):
        load_scene(write_scene(tmp_path, OPEN_ROOM + wall))


def test_a_scene_holds_a_bounded_number_of_things(tmp_path: Path) -> None:
    """Each thing becomes a PyBullet body that every motion is checked against."""
    walls = "".join(f'\n[[wall]]\nname = "w{i}"\ncenter = [3.0, 0.0]\nsize = [0.1, 0.1]\n'
                    for i in range(MAX_SCENE_ITEMS + 1))
    with pytest.raises(InputError, match=f"at most {MAX_SCENE_ITEMS}"):
        load_scene(write_scene(tmp_path, OPEN_ROOM + walls))


WALLED = OPEN_ROOM + """
[[wall]]
name = "pillar"
center = [3.0, -1.0]
size = [0.4, 0.4]
"""


@pytest.mark.parametrize(("old", "new", "message", "line"), [
    ("at = [2.0, 1.0]", "at = [9.0, 1.0]",
     "cube 'green' at [9.0, 1.0] is outside the world's bounds", '"green"'),
    ("at = [2.0, 1.0]", "at = [3.1, -1.0]", "cube 'green' at [3.1, -1.0] is inside the wall "
     "'pillar'", '"green"'),
    ('name = "blue"\n', 'name = "blue"\nat = [2.02, 1.01]\n',
     "cubes 'green' and 'blue' overlap", '"blue"'),
    ('name = "red"\n', 'name = "red"\ncolor = [1.0, 2.0, 0.0]\n',
     "'color' is red, green and blue, each between 0 and 1", "color"),
])
def test_a_scene_that_places_a_cube_where_none_can_be_is_bad_input(
        tmp_path: Path, old: str, new: str, message: str, line: str) -> None:
    """Refused with the place to fix, not found later as a run that fails."""
    text = WALLED.replace(old, new, 1)
    with pytest.raises(InputError) as caught:
        load_scene(write_scene(tmp_path, text))
    assert message in str(caught.value)
    assert caught.value.span is not None
    assert line in text.split("\n")[caught.value.span.line - 1]


def test_cubes_too_wide_for_the_fingers_are_refused_at_cube_size(tmp_path: Path) -> None:
    text = OPEN_ROOM.replace("bounds = [-1.0, 7.0, -2.0, 2.0]",
                             "bounds = [-1.0, 7.0, -2.0, 2.0]\ncube_size = 0.2")
    with pytest.raises(InputError) as caught:
        load_scene(write_scene(tmp_path, text))
    assert "do not fit between the fingers" in str(caught.value)
    assert caught.value.span is not None
    assert "cube_size" in text.split("\n")[caught.value.span.line - 1]

