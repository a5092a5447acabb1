"""Loading .bt files into tasks: the paper's Example 1 exactly as written, and file layouts."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from btplan.errors import InputError
from btplan.lang import collect, load, load_domain, load_problem, parse_bt
from btplan.model import Atom, GroundLiteral, Literal, Parameter, instantiate

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK_PLACE = str(DOMAINS / "pick_place.bt")

TINY = """
domain tiny {
    types { block }
    predicates { clear(b: block)  holding(b: block)  hand_empty }
    action Take(b: block, c: block) {
        pre: clear(b), hand_empty, b != c
        post: holding(b), not hand_empty, not clear(b)
        cost: 2.5
    }
}
"""
TINY_PROBLEMS = """
problem first for tiny { objects { a, b : block } init { clear(a) hand_empty } goal { holding(a) } }
problem second for tiny {
    objects { a : block }
    init { clear(a), hand_empty }
    goal { holding(a), not clear(a) }
}
"""


def test_pick_place_loads_as_the_paper_writes_it() -> None:
    task = load([PICK_PLACE])
    domain, problem = task.domain, task.problem
    assert domain.name == "pick_place" and problem.name == "cube_on_goal"
    assert [a.name for a in domain.actions] == ["MoveTo", "Pick", "Place"]
    move = domain.action_map["MoveTo"]
    assert move.parameters == (
        Parameter(name="l", type="location"),
        Parameter(name="t", type="trajectory", refined=True),
    )
    assert move.constraints == (Literal(predicate="route", args=("l", "t")),)
    assert [str(p) for p in move.preconditions] == ["free(t)"]
    assert [str(e) for e in move.effects] == ["not near(_)", "near(l)"]
    assert move.duration == 3
    pick = domain.action_map["Pick"]
    assert [str(p) for p in pick.preconditions] == ["near(o)", "hand_empty()"]
    assert [str(e) for e in pick.effects] == ["holding(o)", "not hand_empty()"]
    place = domain.action_map["Place"]
    assert [str(e) for e in place.effects] == ["on(o, l)", "hand_empty()", "not holding(o)"]
    assert domain.predicate_map["hand_empty"].arity == 0
    assert [c.name for c in domain.constants] == ["goal"]
    assert task.goal_literals == (GroundLiteral(Atom("on", ("cube", "goal"))),)
    assert Atom("route", ("goal", "tau_goal")) in task.initial_state
    assert len(task.initial_state) == 5


def test_pick_place_types_keep_trajectories_apart_from_locations() -> None:
    task = load([PICK_PLACE])
    assert task.objects_of("location") == ("cube", "goal")
    assert task.objects_of("object") == ("cube",)
    assert task.objects_of("trajectory") == ("tau_cube", "tau_goal")


def test_pick_place_grounds_into_a_working_action() -> None:
    task = load([PICK_PLACE])
    move = instantiate(task.domain.action_map["MoveTo"], ("cube", "tau_cube"))
    state = move.apply(task.initial_state | {Atom("near", ("goal",))})
    assert Atom("near", ("cube",)) in state and Atom("near", ("goal",)) not in state


def test_equalities_in_pre_become_constraints() -> None:
    take = parse_bt(TINY, "tiny.bt").domain.action_map["Take"]  # type: ignore[union-attr]
    assert take.constraints == (Literal(predicate="=", args=("b", "c"), positive=False),)
    assert [str(p) for p in take.preconditions] == ["clear(b)", "hand_empty()"]
    assert take.cost == 2.5 and take.duration == 1


def test_domain_and_problems_in_separate_files(tmp_path: Path) -> None:
    (tmp_path / "tiny.bt").write_text(TINY)
    (tmp_path / "p.bt").write_text(TINY_PROBLEMS)
    paths = [str(tmp_path / "tiny.bt"), str(tmp_path / "p.bt")]
    assert load(paths).problem.name == "first"
    second = load(paths, problem="second")
    assert [str(g) for g in second.goal_literals] == ["holding(a)", "not clear(a)"]
    assert load_domain(paths[0]).name == "tiny"
    assert [p.name for p in collect(paths).problems] == ["first", "second"]


def test_problem_only_file_is_checked_once_bound(tmp_path: Path) -> None:
    alone = parse_bt(TINY_PROBLEMS, "p.bt")
    assert alone.domain is None and [p.name for p in alone.problems] == ["first", "second"]
    domain = parse_bt(TINY, "tiny.bt").domain
    assert domain is not None
    assert alone.bind(domain)[0].objects[0].type == "block"


def test_unknown_problem_name_suggests_the_close_one(tmp_path: Path) -> None:
    (tmp_path / "all.bt").write_text(TINY + TINY_PROBLEMS)
    with pytest.raises(InputError) as caught:
        load([str(tmp_path / "all.bt")], problem="secnd")
    assert caught.value.hint == "did you mean 'second'?"


def test_standard_input_is_read_for_dash(monkeypatch: pytest.MonkeyPatch) -> None:
    text = Path(PICK_PLACE).read_text(encoding="utf-8")
    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO(text.encode())))
    assert load(["-"]).problem.name == "cube_on_goal"


def test_a_problem_needs_its_domain(tmp_path: Path) -> None:
    (tmp_path / "p.bt").write_text(TINY_PROBLEMS)
    with pytest.raises(InputError) as caught:
        load([str(tmp_path / "p.bt")])
    assert "which none of the inputs defines" in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 2


def test_problems_of_a_loaded_domain_share_it(tmp_path: Path) -> None:
    """Many problems of one domain read it once; their tasks share the one Domain object,
    and each is the task `load` makes of the two files."""
    (tmp_path / "tiny.bt").write_text(TINY)
    (tmp_path / "p.bt").write_text(TINY_PROBLEMS)
    domain = load_domain(str(tmp_path / "tiny.bt"))
    first = load_problem(domain, str(tmp_path / "p.bt"))
    second = load_problem(domain, str(tmp_path / "p.bt"), problem="second")
    assert first.domain is domain and second.domain is domain
    both = [str(tmp_path / "tiny.bt"), str(tmp_path / "p.bt")]
    assert second.goal_literals == load(both, problem="second").goal_literals
    assert first.problem == load(both).problem


def test_a_problem_for_another_domain_is_refused_where_it_names_it(tmp_path: Path) -> None:
    (tmp_path / "p.bt").write_text(TINY_PROBLEMS.replace("for tiny", "for tiney"))
    domain = load_domain(PICK_PLACE)
    with pytest.raises(InputError) as caught:
        load_problem(domain, str(tmp_path / "p.bt"))
    assert "'tiney'" in caught.value.message
    assert caught.value.span is not None and caught.value.span.line == 2
