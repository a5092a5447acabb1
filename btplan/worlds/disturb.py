"""The disturbance spec language: what external agents do to a world, and when.

A spec is `KIND[:TARGET]@WHEN`, e.g. `undo@5`, `help:Pick(cube)@3`,
`clear:holding(cube)@10`, `set:blocked(tau_goal)@p=0.05`, `fail:MoveTo@2`.
It exists so that the four reactive properties of the paper's Problem 1 can be
provoked from a command line or a scenario file, and every mistake in it is reported
with the column (or file line) where it is, like any other input.
The full syntax is in docs/cli.md.
"""

from __future__ import annotations

import re
from collections.abc import Iterable
from dataclasses import dataclass
from difflib import get_close_matches

from btplan.errors import InputError, Span
from btplan.limits import MAX_TICK, check_size, shorten
from btplan.model import Task

KINDS = ("clear", "fail", "help", "set", "undo")
"""What an agent can do; a target names an action for undo/help/fail and a fact for set/clear."""

FACT_KINDS = frozenset({"set", "clear"})
ACTION_KINDS = frozenset({"undo", "help", "fail"})

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_\-]*")
_INT = re.compile(r"\d+")
_FLOAT = re.compile(r"(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?")


@dataclass(frozen=True, slots=True)
class When:
    """The ticks at which a spec may fire, and the chance that it does on each of them.

    `ranges` holds inclusive (first, last) pairs, `last` None meaning "until the end";
    no ranges means every tick. `probability` 1.0 means it always fires.
    """

    ranges: tuple[tuple[int, int | None], ...] = ()
    probability: float = 1.0

    def covers(self, tick: int) -> bool:
        """Whether `tick` lies in one of the ranges (every tick when there are none).

        The chance of firing is drawn by the agent, not here, from its own seeded stream.
        """
        if not self.ranges:
            return True
        return any(first <= tick and (last is None or tick <= last) for first, last in self.ranges)

    def __str__(self) -> str:
        parts = [_range_text(r) for r in self.ranges]
        if self.probability < 1.0 or not parts:
            parts.append(f"p={self.probability:g}")
        return ",".join(parts)


def _range_text(r: tuple[int, int | None]) -> str:
    first, last = r
    if last == first:
        return str(first)
    return f"{first}..{'' if last is None else last}"


@dataclass(frozen=True, slots=True)
class Target:
    """An action (`Pick`, `Pick(cube)`) or a fact (`holding(cube)`); `args` None means any."""

    name: str
    args: tuple[str, ...] | None = None

    def __str__(self) -> str:
        return self.name if self.args is None else f"{self.name}({', '.join(self.args)})"


@dataclass(frozen=True, slots=True)
class DisturbSpec:
    """One parsed spec; `text` is kept so that traces name the agent as the user wrote it."""

    kind: str
    target: Target | None
    when: When
    text: str
    span: Span | None = None
    source_line: str | None = None


class _Cursor:
    """A position in one spec, raising located errors relative to where the spec came from."""

    def __init__(self, text: str, origin: Span, source_line: str, offset: int) -> None:
        self.text, self.pos = text, 0
        self.origin, self.source_line, self.offset = origin, source_line, offset

    def fail(self, message: str, at: int | None = None, hint: str | None = None) -> InputError:
        column = self.origin.column + self.offset + (self.pos if at is None else at)
        span = Span(self.origin.path, self.origin.line, column)
        return InputError(message, span, hint, self.source_line)

    def skip_space(self) -> None:
        while self.pos < len(self.text) and self.text[self.pos] in " \t":
            self.pos += 1

    def peek(self, literal: str) -> bool:
        self.skip_space()
        return self.text.startswith(literal, self.pos)

    def take(self, literal: str) -> bool:
        if self.peek(literal):
            self.pos += len(literal)
            return True
        return False

    def expect(self, literal: str, what: str) -> None:
        if not self.take(literal):
            raise self.fail(f"expected {what}, found {self.rest_word()}")

    def match(self, pattern: re.Pattern[str], what: str) -> str:
        self.skip_space()
        found = pattern.match(self.text, self.pos)
        if not found:
            raise self.fail(f"expected {what}, found {self.rest_word()}")
        self.pos = found.end()
        return found.group(0)

    def rest_word(self) -> str:
        rest = self.text[self.pos:].strip()
        return f"'{rest.split()[0][:20]}'" if rest else "the end of the spec"

    def at_end(self) -> bool:
        self.skip_space()
        return self.pos >= len(self.text)


def parse_spec(text: str, origin: Span | None = None, source_line: str | None = None,
               offset: int = 0) -> DisturbSpec:
    """Parse one `KIND[:TARGET]@WHEN` spec; errors point at the offending column.

    `origin` is where the spec's line starts (a file line, or `--disturb` for a flag),
    `offset` the spec's column within `source_line`.
    """
    where = origin or Span("--disturb", 1, 1)
    cur = _Cursor(text, where, source_line if source_line is not None else text, offset)
    kind_at = len(text) - len(text.lstrip())
    kind = cur.match(_NAME, "a disturbance kind (" + ", ".join(KINDS) + ")")
    if kind not in KINDS:
        near = get_close_matches(kind, KINDS, n=1)
        raise cur.fail(f"unknown disturbance kind '{shorten(kind)}'", kind_at,
                       f"did you mean '{near[0]}'?" if near else "one of " + ", ".join(KINDS))
    target = _target(cur, kind) if cur.take(":") else None
    if target is None and kind in FACT_KINDS:
        raise cur.fail(f"'{kind}' needs a fact, as in '{kind}:holding(cube)@5'")
    if target is None and kind == "fail":
        raise cur.fail("'fail' needs an action, as in 'fail:MoveTo@5'")
    cur.expect("@", "'@' and when it happens (a tick such as @5, a range @3..9, or p=0.1)")
    when = _when(cur)
    span = Span(where.path, where.line, where.column + offset + kind_at)
    return DisturbSpec(kind, target, when, text.strip(), span, cur.source_line)


def _target(cur: _Cursor, kind: str) -> Target:
    name = cur.match(_NAME, "an action name" if kind in ACTION_KINDS else "a fact")
    if not cur.take("("):
        return Target(name, None if kind in ACTION_KINDS else ())
    args: list[str] = []
    if not cur.take(")"):
        args.append(cur.match(_NAME, "an object name"))
        while cur.take(","):
            args.append(cur.match(_NAME, "an object name"))
        cur.expect(")", "',' or ')'")
    return Target(name, tuple(args))


def _when(cur: _Cursor) -> When:
    ranges: list[tuple[int, int | None]] = []
    probability: float | None = None
    while True:
        item_at = cur.pos
        if cur.take("p="):
            if probability is not None:
                raise cur.fail("only one probability is allowed", item_at)
            probability = _probability(cur)
        else:
            ranges.append(_range(cur))
        if not cur.take(","):
            break
    if not cur.at_end():
        raise cur.fail(f"unexpected {cur.rest_word()} after the timing")
    return When(tuple(ranges), 1.0 if probability is None else probability)


def _range(cur: _Cursor) -> tuple[int, int | None]:
    at = cur.pos
    first = _tick(cur, "a tick number, a range such as 3..9, or p=0.1")
    if first < 1:
        raise cur.fail("ticks are counted from 1", at)
    if not cur.take(".."):
        return (first, first)
    cur.skip_space()
    if not cur.text[cur.pos:cur.pos + 1].isdigit():
        return (first, None)
    last_at = cur.pos
    last = _tick(cur, "the last tick of the range")
    if last < first:
        raise cur.fail(f"the range ends at {last}, before it starts at {first}", last_at)
    return (first, last)


def _tick(cur: _Cursor, what: str) -> int:
    cur.skip_space()
    at = cur.pos
    digits = cur.match(_INT, what).lstrip("0") or "0"
    if len(digits) > len(str(MAX_TICK)) or int(digits) > MAX_TICK:
        raise cur.fail(f"a tick number is at most {MAX_TICK}", at)
    return int(digits)


def _probability(cur: _Cursor) -> float:
    at = cur.pos
    value = float(cur.match(_FLOAT, "a probability between 0 and 1"))
    if not 0.0 <= value <= 1.0:
        raise cur.fail(f"a probability is between 0 and 1, not {value:g}", at)
    return value


def parse_scenario(text: str, path: str) -> list[DisturbSpec]:
    """Parse a scenario file: one spec per line; `#` starts a comment; blank lines are skipped."""
    check_size(len(text), path)
    specs: list[DisturbSpec] = []
    for number, line in enumerate(text.splitlines(), start=1):
        body = line.split("#", 1)[0]
        if not body.strip():
            continue
        offset = len(body) - len(body.lstrip())
        specs.append(parse_spec(body.strip(), Span(path, number, 1), line, offset))
    return specs


def check_specs(specs: Iterable[DisturbSpec], task: Task) -> None:
    """Refuse specs that name actions, predicates or objects the task does not have.

    Checked up front so that a typo is a located error before the run, not a
    disturbance that silently never matches.
    """
    for spec in specs:
        if spec.target is not None:
            _check_target(spec, spec.target, task)


def _check_target(spec: DisturbSpec, target: Target, task: Task) -> None:
    if spec.kind in ACTION_KINDS:
        table = {a.name: len(a.parameters) for a in task.domain.actions}
        what = "action"
    else:
        table = {p.name: p.arity for p in task.domain.predicates}
        what = "predicate"
    if target.name not in table:
        near = get_close_matches(target.name, sorted(table), n=1)
        raise _spec_error(spec, f"unknown {what} '{shorten(target.name)}'",
                          f"did you mean '{near[0]}'?" if near else None)
    if target.args is None:
        return
    arity = table[target.name]
    if len(target.args) != arity:
        raise _spec_error(spec, f"{shorten(target.name)} takes {arity} "
                          f"argument{'s' * (arity != 1)}, "
                          f"not {len(target.args)}")
    objects = sorted(task.object_types)
    for arg in target.args:
        if arg not in task.object_types:
            near = get_close_matches(arg, objects, n=1)
            raise _spec_error(spec, f"unknown object '{shorten(arg)}'",
                              f"did you mean '{near[0]}'?" if near else None)


def _spec_error(spec: DisturbSpec, message: str, hint: str | None = None) -> InputError:
    return InputError(f"in disturbance '{shorten(spec.text)}': {message}", spec.span, hint,
                      spec.source_line)
