"""The disturbance spec language: what parses, what it means, and where errors point."""

from __future__ import annotations

import pytest

from btplan.errors import InputError, Span
from btplan.model import ActionTemplate, Domain, Parameter, Predicate, Problem, Task, TypedName
from btplan.worlds.disturb import Target, When, check_specs, parse_scenario, parse_spec


def task() -> Task:
    domain = Domain(
        name="d",
        predicates=(Predicate(name="holding", parameters=(Parameter(name="o"),)),
                    Predicate(name="hand_empty")),
        actions=(ActionTemplate(name="Pick", parameters=(Parameter(name="o"),)),),
    )
    problem = Problem(name="p", domain="d", objects=(TypedName(name="cube"),))
    return Task(domain=domain, problem=problem)


@pytest.mark.parametrize("text, kind, target, when", [
    ("undo@5", "undo", None, When(((5, 5),))),
    ("help:Pick(cube)@3", "help", Target("Pick", ("cube",)), When(((3, 3),))),
    ("clear:holding(cube)@10", "clear", Target("holding", ("cube",)), When(((10, 10),))),
    ("set:hand_empty@p=0.05", "set", Target("hand_empty", ()), When((), 0.05)),
    ("fail:Pick@2", "fail", Target("Pick", None), When(((2, 2),))),
    (" set : hand_empty() @ 3..9, 12, p=0.5", "set", Target("hand_empty", ()),
     When(((3, 9), (12, 12)), 0.5)),
    ("undo:Pick@4..", "undo", Target("Pick", None), When(((4, None),))),
])
def test_specs_parse_to_kind_target_and_timing(text: str, kind: str, target: Target | None,
                                                when: When) -> None:
    spec = parse_spec(text)
    assert (spec.kind, spec.target, spec.when) == (kind, target, when)


def test_timing_covers_ticks_and_ranges() -> None:
    when = parse_spec("undo@2,5..6,9..").when
    assert [t for t in range(1, 12) if when.covers(t)] == [2, 5, 6, 9, 10, 11]
    assert str(when) == "2,5..6,9.."


@pytest.mark.parametrize("text, column, words", [
    ("unod@5", 1, "did you mean 'undo'"),
    ("set@5", 4, "needs a fact"),
    ("fail@5", 5, "needs an action"),
    ("set:x(a@5", 8, "expected ',' or ')'"),
    ("help:Pick(cube)", 16, "expected '@'"),
    ("undo@0", 6, "counted from 1"),
    ("undo@5..3", 9, "before it starts"),
    ("set:a@p=1.5", 9, "between 0 and 1"),
    ("undo@5 x", 8, "unexpected 'x'"),
    ("undo@p=0.1,p=0.2", 12, "only one probability"),
])
def test_spec_errors_point_at_the_column(text: str, column: int, words: str) -> None:
    with pytest.raises(InputError) as caught:
        parse_spec(text)
    error = caught.value
    assert error.span == Span("--disturb", 1, column)
    assert words in str(error)
    assert error.source_line == text


def test_scenario_files_skip_comments_and_locate_errors() -> None:
    specs = parse_scenario("# a scenario\n\n  undo@5   # the cube is taken\nset:hand_empty@7\n", "s.dist")
    assert [s.text for s in specs] == ["undo@5", "set:hand_empty@7"]
    assert specs[0].span == Span("s.dist", 3, 3)
    with pytest.raises(InputError) as caught:
        parse_scenario("undo@5\n   set:hand_empty@q\n", "s.dist")
    assert caught.value.span == Span("s.dist", 2, 19)
    assert caught.value.source_line == "   set:hand_empty@q"


@pytest.mark.parametrize("text, words", [
    ("help:Pikc(cube)@1", "unknown action 'Pikc' (did you mean 'Pick'?)"),
    ("set:holdin(cube)@1", "unknown predicate 'holdin' (did you mean 'holding'?)"),
    ("set:holding(cueb)@1", "unknown object 'cueb' (did you mean 'cube'?)"),
    ("set:holding(cube, cube)@1", "holding takes 1 argument, not 2"),
    ("help:Pick()@1", "Pick takes 1 argument, not 0"),
])
def test_specs_are_checked_against_the_task(text: str, words: str) -> None:
    with pytest.raises(InputError) as caught:
        check_specs([parse_spec(text)], task())
    assert words in str(caught.value)
    assert caught.value.span == Span("--disturb", 1, 1)


def test_valid_specs_pass_the_task_check() -> None:
    check_specs([parse_spec(t) for t in ("undo@1", "fail:Pick@2", "set:hand_empty@3",
                                         "help:Pick(cube)@4")], task())
