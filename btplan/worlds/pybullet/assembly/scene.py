"""The scene file of a two-arm assembly: the table, the arms, places, the fixture, parts.

The initial poses are not in it: where each part lies and which way its opening faces
come from the problem's `lies(p, s, f)` facts, so that the same problem runs in the
symbolic world and here, and a test changes a pose by changing a fact. The scene only
says what things look like and where the named places are.
"""

from __future__ import annotations

import math
import re
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
    TOML_BRACKETS,
    check_nesting,
    shorten,
)

Point = tuple[float, float]
Vec = tuple[float, float, float]


@dataclass(frozen=True, slots=True)
class ArmSpec:
    """A Panda fixed on the table top at (x, y), turned by `yaw`."""

    name: str
    base: Vec


@dataclass(frozen=True, slots=True)
class Place:
    """A named area of the table top; `below` is the floor around the table."""

    name: str
    low: Point
    high: Point
    color: Vec
    below: bool = False

    def contains(self, x: float, y: float) -> bool:
        """Whether (x, y) lies in the place's rectangle, edges included; height is not looked at."""
        return self.low[0] <= x <= self.high[0] and self.low[1] <= y <= self.high[1]

    @property
    def center(self) -> Point:
        """The middle of the place: where a part knocked below the table lands.

        Free spots of a table place are tried nearest it first.
        """
        return ((self.low[0] + self.high[0]) / 2, (self.low[1] + self.high[1]) / 2)


@dataclass(frozen=True, slots=True)
class PartSpec:
    """A box `size` = (length, width, height); its opening is the top face, drawn dark."""

    name: str
    size: Vec
    color: Vec


@dataclass(frozen=True, slots=True)
class Event:
    """An external agent's act: `flip` turns `part` over and lays it in place `to`,
    `knock` pushes it (as it lies) to `to`, e.g. off the table to the floor.

    It fires at `tick`, or `delay` ticks after the literal `when` became true `count` times.
    """

    name: str
    do: str
    part: str
    to: str
    tick: int | None = None
    when: str | None = None
    count: int = 1
    delay: int = 0


@dataclass(frozen=True, slots=True)
class AssemblyScene:
    """Everything the assembly world builds; metres, radians, seconds; the table top is z = 0."""

    path: str
    table: Vec                       # length (x), depth (y), height
    fixture: Vec                     # centre x, y and the height of its top
    fixture_size: Point
    handover: Vec                    # where the giver holds a part out to the taker
    arms: tuple[ArmSpec, ...]
    places: tuple[Place, ...]
    parts: tuple[PartSpec, ...]
    events: tuple[Event, ...] = ()
    tick_seconds: float = 0.1

    def place(self, name: str) -> Place | None:
        """The place called `name`, or None when the scene has no such place."""
        return next((p for p in self.places if p.name == name), None)

    def part(self, name: str) -> PartSpec | None:
        """The part called `name`, or None when the scene has no such part."""
        return next((p for p in self.parts if p.name == name), None)


KEYS: dict[str, tuple[str, ...]] = {
    "": ("assembly", "arm", "place", "part", "event"),
    "assembly": ("table", "fixture", "fixture_size", "handover", "tick_seconds"),
    "arm": ("name", "base"),
    "place": ("name", "min", "max", "color", "below"),
    "part": ("name", "size", "color"),
    "event": ("name", "do", "part", "to", "tick", "when", "count", "delay"),
}
DO = ("flip", "knock")


def is_assembly_scene(path: Path) -> bool:
    """Whether a scene file describes a two-arm assembly (it has an [assembly] table)."""
    try:
        return any(line.strip() == "[assembly]" for line in read_text(str(path)).split("\n"))
    except InputError:
        return False


def load_assembly_scene(path: str | Path) -> AssemblyScene:
    """Read and check an assembly scene; raises InputError pointing at the line to fix."""
    where = str(path)
    text = read_text(where)
    check_nesting(text, where, TOML_BRACKETS)
    try:
        data = tomllib.loads(text)
    except (tomllib.TOMLDecodeError, ValueError) as error:
        found = re.search(r"\(at line (\d+), column (\d+)\)", str(error))
        line, column = (int(found.group(1)), int(found.group(2))) if found else (1, 1)
        lines = text.split("\n")
        raise InputError(f"bad TOML: {shorten(str(error), 200)}", Span(where, line, column),
                         source_line=lines[line - 1] if 0 < line <= len(lines) else None
                         ) from None
    return _Reader(where, text).scene(data)


class _Reader:
    def __init__(self, path: str, text: str) -> None:
        self.path, self.lines = path, text.split("\n")

    def fail(self, message: str, key: str, hint: str | None = None,
             table: str | None = None) -> InputError:
        """The error at the first line with `key`, after the line naming `table` if given."""
        start = next((n for n, line in enumerate(self.lines) if table is not None
                      and f'"{table}"' in line and "name" in line), 0)
        for number, line in enumerate(self.lines[start:], start + 1):
            column = line.find(key) if key else -1
            if column >= 0:
                return InputError(message, Span(self.path, number, column + 1), hint, line)
        return InputError(message, Span(self.path, 1, 1), hint)

    def known(self, table: object, kind: str) -> dict[str, Any]:
        if not isinstance(table, dict):
            raise self.fail(f"'{kind}' must be a table", kind)
        for key in sorted(table):
            if key not in KEYS[kind]:
                near = get_close_matches(key, KEYS[kind], n=1)
                raise self.fail(f"unknown key '{shorten(key)}' in [{kind}]", key,
                                f"did you mean '{near[0]}'?" if near else
                                f"expected one of {', '.join(KEYS[kind])}")
        return table

    def tables(self, data: dict[str, Any], kind: str) -> list[dict[str, Any]]:
        items = data.get(kind, [])
        if not isinstance(items, list) or len(items) > MAX_SCENE_ITEMS:
            raise self.fail(f"write [[{kind}]] for each {kind} (at most {MAX_SCENE_ITEMS})", kind)
        return [self.known(t, kind) for t in items]

    def numbers(self, value: object, n: int, key: str, table: str | None = None
                ) -> tuple[float, ...]:
        if not (isinstance(value, list) and len(value) == n and all(
                isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v)
                and abs(v) <= MAX_SCENE_MAGNITUDE for v in value)):
            raise self.fail(f"'{key}' must be a list of {n} numbers", key, table=table)
        return tuple(float(v) for v in value)

    def vec(self, table: dict[str, Any], key: str, default: list[float] | None = None) -> Vec:
        name = table.get("name")
        where = name if isinstance(name, str) else None
        if key not in table and default is None:
            raise self.fail(f"'{key}' is missing", "name", table=where)
        x, y, z = self.numbers(table.get(key, default), 3, key, where)
        return (x, y, z)

    def point(self, table: dict[str, Any], key: str) -> Point:
        x, y = self.numbers(table.get(key), 2, key)
        return (x, y)

    def name(self, table: dict[str, Any], kind: str) -> str:
        name = table.get("name")
        if not isinstance(name, str) or not name.isidentifier():
            raise self.fail(f"every [[{kind}]] needs a name (a word)", f"[[{kind}]]")
        return name

    def whole(self, table: dict[str, Any], key: str, default: int, least: int = 0) -> int:
        value = table.get(key, default)
        if not isinstance(value, int) or isinstance(value, bool) or not least <= value <= 10**9:
            raise self.fail(f"'{key}' must be a whole number of at least {least}", key)
        return value

    def scene(self, data: dict[str, Any]) -> AssemblyScene:
        self.known(data, "")
        top = self.known(data.get("assembly", {}), "assembly")
        tick = top.get("tick_seconds", 0.1)
        if not isinstance(tick, int | float) or isinstance(tick, bool) or not 0.001 <= tick <= 10:
            raise self.fail("'tick_seconds' must be a number from 0.001 to 10", "tick_seconds")
        fx, fy = self.point(top, "fixture") if "fixture" in top else (0.0, 0.0)
        size = self.vec(top, "fixture_size", [0.14, 0.07, 0.04])
        arms = tuple(ArmSpec(self.name(t, "arm"), self.vec(t, "base"))
                     for t in self.tables(data, "arm"))
        if len(arms) != 2:
            raise self.fail("an assembly scene has exactly two [[arm]] tables", "[[arm]]")
        parts = tuple(self.part(t) for t in self.tables(data, "part"))
        places = tuple(self.place(t) for t in self.tables(data, "place"))
        names = [a.name for a in arms] + [p.name for p in parts] + [p.name for p in places]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            raise self.fail(f"the name '{shorten(twice[0])}' is used twice", f'"{twice[0]}"')
        events = tuple(self.event(t, parts, places) for t in self.tables(data, "event"))
        return AssemblyScene(self.path, self.vec(top, "table", [1.6, 1.0, 0.6]),
                             (fx, fy, size[2]), (size[0], size[1]),
                             self.vec(top, "handover", [0.0, 0.0, 0.3]), arms, places, parts,
                             events, float(tick))

    def part(self, t: dict[str, Any]) -> PartSpec:
        size = self.vec(t, "size")
        if not (0.06 <= size[0] <= 0.3 and 0.01 <= size[1] <= 0.07 and 0.005 <= size[2] <= 0.1):
            raise self.fail("a part's size must be [0.06..0.3, 0.01..0.07, 0.005..0.1] metres",
                            "size", "the grippers open 8 cm across the width", t.get("name"))
        return PartSpec(self.name(t, "part"), size, self.vec(t, "color", [0.6, 0.6, 0.6]))

    def place(self, t: dict[str, Any]) -> Place:
        low, high = self.point(t, "min"), self.point(t, "max")
        if low[0] >= high[0] or low[1] >= high[1]:
            raise self.fail("a place's min must be below its max", "min", table=t.get("name"))
        return Place(self.name(t, "place"), low, high, self.vec(t, "color", [0.8, 0.8, 0.7]),
                     bool(t.get("below", False)))

    def event(self, t: dict[str, Any], parts: tuple[PartSpec, ...],
              places: tuple[Place, ...]) -> Event:
        name = t.get("name", "agent")
        do, part, to = t.get("do"), t.get("part"), t.get("to")
        if do not in DO:
            raise self.fail(f"event: 'do' must be one of {', '.join(DO)}", "do")
        if part not in {p.name for p in parts}:
            raise self.fail(f"event: unknown part {shorten(repr(part))}", "part")
        if to not in {p.name for p in places}:
            raise self.fail(f"event: unknown place {shorten(repr(to))}", "to")
        when = t.get("when")
        if ("tick" in t) == (when is not None) or (when is not None and not isinstance(when, str)):
            raise self.fail("event: give exactly one of 'tick' or 'when'", str(name))
        tick = self.whole(t, "tick", 0) if "tick" in t else None
        return Event(str(name), str(do), str(part), str(to), tick, when,
                     self.whole(t, "count", 1, 1), self.whole(t, "delay", 0))
