"""Property: any text fed to either reader ends in models or in our own located error.

Mutated copies of real domains reach deep into the grammar and the checks; random text
covers the lexer. A traceback of any other kind, or a hang, fails the test.
"""

from __future__ import annotations

from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from btplan.errors import InputError
from btplan.lang import parse_bt
from btplan.lang.generators import generate
from btplan.lang.pddl_reader import read_pddl
from btplan.lang.problem_check import build_problem
from btplan.lang.syntax import DomainSyntax, ProblemSyntax
from btplan.lang.validate import build_domain

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
BT_SEEDS = [(DOMAINS / n).read_text() for n in ("pick_place.bt", "blocksworld.bt")]
PDDL_SEEDS = ["\n".join(generate("logistics", packages=2)), "\n".join(generate("gripper", balls=2))]
PIECES = [
    "(",
    ")",
    "{",
    "}",
    ",",
    ":",
    "not ",
    "_",
    "==",
    "!=",
    "?x",
    " - ",
    "\n",
    "#",
    ";",
    "and",
    "domain",
    "problem",
    "for",
    "action",
    "pre:",
    "post:",
    "where:",
    "refined",
    "\x00",
    "é",
    "1.5",
    "(:requirements :adl)",
    "(or (a) (b))",
    "(and",
    "object",
    "-",
    "=",
]

FUZZ = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])


@st.composite
def mutated(draw: st.DrawFn, seeds: list[str]) -> str:
    text = draw(st.sampled_from(seeds))
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(text)))
        kind = draw(st.sampled_from(["delete", "insert", "duplicate"]))
        if kind == "delete":
            text = text[:at] + text[at + draw(st.integers(1, 20)) :]
        elif kind == "insert":
            piece = draw(st.one_of(st.sampled_from(PIECES), st.text(max_size=5)))
            text = text[:at] + piece + text[at:]
        else:
            start = draw(st.integers(0, len(text)))
            text = text[:at] + text[start : start + draw(st.integers(1, 60))] + text[at:]
    return text


def assert_located(error: InputError, text: str) -> None:
    assert error.span is not None, error
    lines = text.split("\n")
    assert 1 <= error.span.line <= len(lines), error
    assert error.span.column >= 1, error
    assert error.source_line == lines[error.span.line - 1], error
    assert "Token(" not in error.message and "__ANON" not in error.message, error


def read_bt_text(text: str) -> None:
    try:
        parse_bt(text, "fuzz.bt")
    except InputError as error:
        assert_located(error, text)


def read_pddl_text(text: str) -> None:
    try:
        units = read_pddl(text, "fuzz.pddl")
        domains = [build_domain(u) for u in units if isinstance(u, DomainSyntax)]
        for problem in (u for u in units if isinstance(u, ProblemSyntax)):
            for domain in domains:
                if domain.name == problem.domain.text:
                    build_problem(problem, domain)
    except InputError as error:
        assert_located(error, text)


@FUZZ
@given(mutated(BT_SEEDS))
def test_mutated_bt_text(text: str) -> None:
    read_bt_text(text)


@FUZZ
@given(mutated(PDDL_SEEDS))
def test_mutated_pddl_text(text: str) -> None:
    read_pddl_text(text)


@FUZZ
@given(st.lists(st.sampled_from([*PIECES, "a", "b", " "]), max_size=40).map("".join))
def test_random_token_soup_in_both_readers(text: str) -> None:
    read_bt_text(text)
    read_pddl_text(text)


@FUZZ
@given(st.text(max_size=60))
def test_arbitrary_unicode_in_both_readers(text: str) -> None:
    read_bt_text(text)
    read_pddl_text(text)
