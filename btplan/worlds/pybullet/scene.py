"""The scene file: walls, cubes, regions and scripted events, editable without code.

Scenes are TOML (read with the standard library's tomllib). Every mistake a user can
make in one is reported as an InputError naming the file, the line where it can be
found, and what was expected, never as a KeyError from deep inside the world.
"""

from __future__ import annotations

import math
import re
import sys
import tomllib
from dataclasses import dataclass
from difflib import get_close_matches
from pathlib import Path
from typing import Any

from btplan.errors import InputError, Span
from btplan.io import read_text
from btplan.limits import (
    MAX_SCENE_ITEMS,
    MAX_SCENE_MAGNITUDE,
    MAX_TICK,
    TOML_BRACKETS,
    check_nesting,
    located,
    shorten,
)

Point = tuple[float, float]


@dataclass(frozen=True, slots=True)
class Box:
    """A static wall or piece of furniture: an axis-aligned box on the floor, or, with
    `z` above 0, a board whose underside is at that height (a shelf the arm must reach
    under; the base and its folded arm stay clear of anything lower than 1 m)."""

    name: str
    center: Point
    size: Point
    height: float = 0.4
    z: float = 0.0


@dataclass(frozen=True, slots=True)
class CubeSpec:
    """A movable cube; `at` is None for a cube that an event brings in later."""

    name: str
    at: Point | None
    color: tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class Region:
    """An axis-aligned area on the floor; `aside` regions are where obstacles may be put."""

    name: str
    low: Point
    high: Point
    aside: bool = False
    color: tuple[float, float, float] = (0.9, 0.9, 0.2)

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """Whether (x, y) lies inside, at least `margin` metres from every edge.

        A negative margin widens it: the samplers keep spots to put things aside that far off.
        """
        return (self.low[0] + margin <= x <= self.high[0] - margin
                and self.low[1] + margin <= y <= self.high[1] - margin)

    @property
    def center(self) -> Point:
        """The middle of the region: the point `near(region)` is measured to."""
        return ((self.low[0] + self.high[0]) / 2, (self.low[1] + self.high[1]) / 2)


@dataclass(frozen=True, slots=True)
class Event:
    """A scripted change made by an external agent.

    It fires at `tick`, or `delay` ticks after the `count`-th time the literal `when`
    (an atom such as `holding(green)`, optionally prefixed by `not`) becomes true.
    `do` is `move` (the agents' pusher pushes `cube` along the floor to `to`; a cube not
    in the scene is first set down at `origin`, outside it), `remove` (the pusher pushes it
    to `to`, or away from the robot, and it leaves the scene once past the bounds), `slip`
    (the robot's grip fails and the cube falls), `knock` (`cube` is set on whatever is
    under `origin`, a shelf board or the floor, and knocked towards `to`: it slides off and
    falls where the physics takes it) or `teleport` (`cube` jumps to `to`, or out of the
    scene without `to`: tests).
    """

    name: str
    do: str
    cube: str
    to: Point | None = None
    tick: int | None = None
    when: str | None = None
    count: int = 1
    delay: int = 0
    origin: Point | None = None


@dataclass(frozen=True, slots=True)
class Scene:
    """Everything the PyBullet world builds; units are metres, radians and seconds."""

    path: str
    bounds: tuple[float, float, float, float]
    start: tuple[float, float, float]
    walls: tuple[Box, ...] = ()
    cubes: tuple[CubeSpec, ...] = ()
    regions: tuple[Region, ...] = ()
    events: tuple[Event, ...] = ()
    tick_seconds: float = 0.1
    speed: float = 1.0
    robot_radius: float = 0.4
    cube_size: float = 0.05
    near: float = 0.7

    def region(self, name: str) -> Region | None:
        """The region called `name`, or None (a cube, a sampled pose, or no such thing)."""
        return next((r for r in self.regions if r.name == name), None)


_TOML_AT = re.compile(r"\(at line (\d+), column (\d+)\)")
DO = ("move", "remove", "slip", "knock", "teleport")
KEYS: dict[str, tuple[str, ...]] = {
    "": ("world", "robot", "wall", "cube", "region", "event"),
    "world": ("bounds", "tick_seconds", "speed", "cube_size"),
    "robot": ("start", "radius", "near"),
    "wall": ("name", "center", "size", "height", "z"),
    "cube": ("name", "at", "color"),
    "region": ("name", "min", "max", "aside", "color"),
    "event": ("name", "when", "tick", "count", "delay", "do", "cube", "to", "from"),
}
"""The keys each table may have; anything else is a typo worth reporting."""
_LITERAL = re.compile(r"^\s*(not\s+)?[A-Za-z_]\w*\s*(\(\s*(\w+\s*(,\s*\w+\s*)*)?\))?\s*$")


MAX_CUBE_SIZE = 0.07
"""The widest cube the Panda's fingers close on (they open 0.04 m each, less a margin)."""


def load_scene(path: str | Path) -> Scene:
    """Read and check a scene file; raises InputError with the place to fix.

    Size and nesting are checked before tomllib, which recurses into nested arrays and
    tables (btplan/limits.py).
    """
    where = str(path)
    text = read_text(where)
    check_nesting(text, where, TOML_BRACKETS)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        found = _TOML_AT.search(str(error))
        line, col = (int(found.group(1)), int(found.group(2))) if found else (1, 1)
        lines = text.split("\n")  # tomllib counts lines as "\n" does
        source = lines[line - 1] if 0 < line <= len(lines) else None
        message = _TOML_AT.sub("", str(error)).strip()
        raise InputError(f"bad TOML: {message}", Span(where, line, col), source_line=source) from None
    except ValueError:  # an integer past Python's digit limit for int()
        digits = re.search(r"\d{%d,}" % (sys.get_int_max_str_digits() + 1), text)
        raise located(text, where, digits.start() if digits else 0,
                      "bad TOML: a number with too many digits") from None
    return _Reader(where, text).scene(data)


class _Reader:
    """Turns the TOML tables into a Scene, locating errors by the key's first line."""

    def __init__(self, path: str, text: str) -> None:
        self.path = path
        self.lines = text.split("\n")

    def fail(self, message: str, key: str, hint: str | None = None) -> InputError:
        for number, line in enumerate(self.lines, 1):
            column = line.find(key)
            if column >= 0 and key:
                return InputError(message, Span(self.path, number, column + 1), hint, line)
        return InputError(message, Span(self.path, 1, 1), hint)

    def numbers(self, value: object, n: int, key: str) -> tuple[float, ...]:
        if not (isinstance(value, list) and len(value) == n and all(
                _finite(v) and abs(v) <= MAX_SCENE_MAGNITUDE for v in value)):
            raise self.fail(f"'{key}' must be a list of {n} numbers", key,
                            f"finite ones, at most {MAX_SCENE_MAGNITUDE:g} in size")
        return tuple(float(v) for v in value)

    def scalar(self, table: dict[str, Any], key: str, default: float, whole: bool = False,
               least: float = 0.0) -> float:
        """A number (an integer if `whole`) of at least `least`, or the default when absent."""
        value = table.get(key, default)
        kinds = int if whole else int | float
        most = MAX_TICK if whole else MAX_SCENE_MAGNITUDE
        if not (_finite(value) and isinstance(value, kinds) and least <= value <= most):
            what = "a whole number" if whole else "a number"
            raise self.fail(f"'{key}' must be {what} of at least {least:g}", key,
                            f"and at most {most:.0f}; got {shorten(repr(value))}")
        return float(value)

    def known(self, table: object, kind: str) -> dict[str, Any]:
        """The table itself, after checking it is one and has no unknown keys."""
        if not isinstance(table, dict):
            raise self.fail(f"'{kind}' must be a table", kind)
        allowed = KEYS[kind]
        for key in sorted(table):
            if key not in allowed:
                near = get_close_matches(key, allowed, n=1)
                where = f"[{kind}]" if kind else "the scene"
                raise self.fail(f"unknown key '{shorten(key)}' in {where}", key,
                                f"did you mean '{near[0]}'?" if near else
                                f"expected one of {', '.join(allowed)}")
        return table

    def tables(self, data: dict[str, Any], kind: str) -> list[dict[str, Any]]:
        items = data.get(kind, [])
        if not isinstance(items, list):
            raise self.fail(f"write [[{kind}]] for each {kind}", kind)
        if len(items) > MAX_SCENE_ITEMS:
            raise self.fail(f"a scene holds at most {MAX_SCENE_ITEMS} [[{kind}]] tables, "
                            f"not {len(items)}", f"[[{kind}]]")
        return [self.known(t, kind) for t in items]

    def point(self, value: object, key: str) -> Point:
        x, y = self.numbers(value, 2, key)
        return (x, y)

    def color(self, table: dict[str, Any]) -> tuple[float, float, float]:
        r, g, b = self.numbers(table.get("color", [0.6, 0.6, 0.6]), 3, "color")
        if not all(0.0 <= c <= 1.0 for c in (r, g, b)):
            raise self.fail("'color' is red, green and blue, each between 0 and 1", "color",
                            f"got {[r, g, b]}")
        return (r, g, b)

    def name(self, table: dict[str, Any], kind: str) -> str:
        name = table.get("name")
        if not isinstance(name, str) or not name:
            raise self.fail(f"every [[{kind}]] needs a name", f"[[{kind}]]")
        return name

    def scene(self, data: dict[str, Any]) -> Scene:
        self.known(data, "")
        world = self.known(data.get("world", {}), "world")
        robot = self.known(data.get("robot", {}), "robot")
        if "bounds" not in world:
            raise self.fail("the scene needs [world] bounds = [x_min, x_max, y_min, y_max]", "[world]")
        x0, x1, y0, y1 = self.numbers(world["bounds"], 4, "bounds")
        if x0 >= x1 or y0 >= y1:
            raise self.fail("'bounds' must be [x_min, x_max, y_min, y_max], each min below "
                            "its max", "bounds")
        sx, sy, syaw = self.numbers(robot.get("start", [0.0, 0.0, 0.0]), 3, "start")
        cubes = tuple(self.cube(t) for t in self.tables(data, "cube"))
        scene = Scene(
            path=self.path,
            bounds=(x0, x1, y0, y1),
            start=(sx, sy, syaw),
            walls=tuple(self.wall(t) for t in self.tables(data, "wall")),
            cubes=cubes,
            regions=tuple(self.region(t) for t in self.tables(data, "region")),
            events=tuple(self.event(t, {c.name for c in cubes}) for t in self.tables(data, "event")),
            tick_seconds=self.scalar(world, "tick_seconds", 0.1, least=0.001),
            speed=self.scalar(world, "speed", 1.0, least=0.01),
            robot_radius=self.scalar(robot, "radius", 0.4, least=0.05),
            cube_size=self.scalar(world, "cube_size", 0.05, least=0.01),
            near=self.scalar(robot, "near", 0.7, least=0.05),
        )
        if scene.cube_size > MAX_CUBE_SIZE:
            raise self.fail(f"cubes of {scene.cube_size:g} m do not fit between the fingers "
                            f"(at most {MAX_CUBE_SIZE:.2f} m)", "cube_size",
                            "lower [world] cube_size")
        self.check_names(scene)
        self.check_cubes(scene)
        return scene

    def wall(self, t: dict[str, Any]) -> Box:
        size = self.point(t.get("size"), "size")
        if min(size) <= 0:
            raise self.fail("a wall's 'size' must be positive", "size", f"got {list(size)}")
        return Box(self.name(t, "wall"), self.point(t.get("center"), "center"), size,
                   self.scalar(t, "height", 0.4, least=0.01), self.scalar(t, "z", 0.0))

    def cube(self, t: dict[str, Any]) -> CubeSpec:
        at = self.point(t["at"], "at") if "at" in t else None
        return CubeSpec(self.name(t, "cube"), at, self.color(t))

    def region(self, t: dict[str, Any]) -> Region:
        low, high = self.point(t.get("min"), "min"), self.point(t.get("max"), "max")
        if low[0] >= high[0] or low[1] >= high[1]:
            raise self.fail(f"region '{shorten(str(t.get('name')))}': min must be below max", "min")
        return Region(self.name(t, "region"), low, high, bool(t.get("aside", False)), self.color(t))

    def event(self, t: dict[str, Any], cubes: set[str]) -> Event:
        name = self.name(t, "event")
        shown = shorten(name)
        do = t.get("do")
        if do not in DO:
            raise self.fail(f"event '{shown}': 'do' must be one of {', '.join(DO)}", "do",
                            f"got {shorten(repr(do))}")
        cube = t.get("cube")
        if cube not in cubes:
            raise self.fail(f"event '{shown}': unknown cube {shorten(repr(cube))}", f'"{cube}"',
                            f"cubes are {shorten(', '.join(sorted(cubes)), 200)}")
        if ("tick" in t) == ("when" in t):
            raise self.fail(f"event '{shown}': give exactly one of 'tick' or 'when'", name)
        when = t.get("when")
        if when is not None and not (isinstance(when, str) and _LITERAL.match(when)):
            raise self.fail(f"event '{shown}': cannot read the condition {shorten(repr(when))}",
                            str(when),
                            "write it as in the domain, e.g. holding(green) or not near(goal)")
        to = self.point(t["to"], "to") if "to" in t else None
        origin = self.point(t["from"], "from") if "from" in t else None
        if do == "move" and to is None:
            raise self.fail(f"event '{shown}': a move needs 'to = [x, y]'", name)
        if do == "knock" and (to is None or origin is None or to == origin):
            raise self.fail(f"event '{shown}': a knock needs 'from = [x, y]' (where the cube "
                            "sits) and a different 'to = [x, y]' (the way it is knocked)", name)
        tick = int(self.scalar(t, "tick", 0, whole=True)) if "tick" in t else None
        count = int(self.scalar(t, "count", 1, whole=True, least=1))
        delay = int(self.scalar(t, "delay", 0, whole=True))
        return Event(name, do, cube, to, tick, when, count, delay, origin)

    def check_cubes(self, scene: Scene) -> None:
        """Every placed cube inside the world, clear of the walls and of the other cubes:
        a scene that puts one elsewhere fails as input, not later as a failed run."""
        x0, x1, y0, y1 = scene.bounds
        half = scene.cube_size / 2
        placed = [c for c in scene.cubes if c.at is not None]
        for i, cube in enumerate(placed):
            assert cube.at is not None
            x, y = cube.at
            at = f'"{cube.name}"'
            if not (x0 + half <= x <= x1 - half and y0 + half <= y <= y1 - half):
                raise self.fail(f"cube '{shorten(cube.name)}' at {list(cube.at)} is outside the "
                                f"world's bounds {list(scene.bounds)}", at)
            for wall in scene.walls:
                if wall.z >= scene.cube_size:
                    continue  # a board above the floor: a cube may lie under it
                (cx, cy), (sx, sy) = wall.center, wall.size
                if abs(x - cx) < sx / 2 + half and abs(y - cy) < sy / 2 + half:
                    raise self.fail(f"cube '{shorten(cube.name)}' at {list(cube.at)} is inside "
                                    f"the wall '{shorten(wall.name)}'", at)
            for other in placed[i + 1:]:
                assert other.at is not None
                if (abs(x - other.at[0]) < scene.cube_size
                        and abs(y - other.at[1]) < scene.cube_size):
                    raise self.fail(f"cubes '{shorten(cube.name)}' and '{shorten(other.name)}' "
                                    f"overlap at {list(cube.at)} and {list(other.at)}",
                                    f'"{other.name}"')

    def check_names(self, scene: Scene) -> None:
        seen: set[str] = set()
        for name in [c.name for c in scene.cubes] + [r.name for r in scene.regions]:
            if name in seen:
                raise self.fail(f"the name '{shorten(name)}' is used twice", f'"{name}"')
            seen.add(name)


def _finite(value: object) -> bool:
    """A TOML number that is a usable float: not a bool, nan, inf, or an integer past float."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        return False
    try:
        return math.isfinite(value)
    except OverflowError:
        return False
