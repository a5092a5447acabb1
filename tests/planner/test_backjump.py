"""Starting an attempt over without the choice a failure is blamed on, and the
whole-goal search when backchaining gives up.

Small hand-written cases: a trap where the cheaper achiever of the goal leads to a dead
end that only running it reveals, the culprits read off hand-built trees, and Sussman's
anomaly planned by the whole-goal search when backchaining is given no expansions.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.acting.offline import load, plan
from btplan.bt import Action, Condition, Fallback
from btplan.bt import Sequence as SequenceNode
from btplan.errors import BudgetExceededError, NoAchieverError, PlanningError
from btplan.model import Atom, GroundLiteral, Task
from btplan.planner import PlannerOptions
from btplan.planner.backjump import achiever_choice, enclosing_choices, running_choices
from tests.planner.shapes import DOMAINS
from tests.planner.test_classic import replay, validate

# g by a1 (needs p and q, two steps away) or by a2 (needs r, three steps away): a1 ranks
# first, but making p deletes s and q, and q needs s: after make-p, q is lost for good.
TRAP_DOMAIN = """
(define (domain trap)
  (:requirements :strips)
  (:predicates (g) (p) (q) (r) (s) (r1) (r2))
  (:action a1 :parameters () :precondition (and (p) (q)) :effect (g))
  (:action a2 :parameters () :precondition (r) :effect (g))
  (:action make-p :parameters () :precondition () :effect (and (p) (not (s)) (not (q))))
  (:action make-q :parameters () :precondition (s) :effect (q))
  (:action make-r :parameters () :precondition (r1) :effect (r))
  (:action make-r1 :parameters () :precondition (r2) :effect (r1))
  (:action make-r2 :parameters () :precondition () :effect (r2)))
"""
TRAP_PROBLEM = "(define (problem trap1) (:domain trap) (:init (s)) (:goal (g)))"
# One achiever per condition, no re-expansion, no dead-end look-ahead, no mutexes: the
# pieces that would otherwise steer around the trap before it is walked into.
BARE = {"max_alternatives": 1, "refine_more": False, "avoid_dead_ends": False,
        "mutexes": False, "search_stuck": False}


def trap(tmp_path: Path) -> Task:
    (tmp_path / "domain.pddl").write_text(TRAP_DOMAIN)
    (tmp_path / "problem.pddl").write_text(TRAP_PROBLEM)
    return load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))


def test_without_retries_the_trap_is_a_dead_end(tmp_path: Path) -> None:
    with pytest.raises(NoAchieverError, match="no action can make q"):
        plan(trap(tmp_path), options=PlannerOptions(retries=0, **BARE))


def test_a_retry_without_the_blamed_choice_finds_the_other_way(tmp_path: Path) -> None:
    task = trap(tmp_path)
    result = plan(task, options=PlannerOptions(retries=1, **BARE))
    assert [str(a) for a in result.executed] == ["make-r2()", "make-r1()", "make-r()", "a2()"]
    assert result.stats.retries == 1
    validate(task, result.executed)
    assert [str(a) for a in replay(task, result)] == [str(a) for a in result.executed]


def test_a_failure_says_which_choices_were_given_up(tmp_path: Path) -> None:
    # Without a2, g has one achiever: the retry has nothing else to try.
    task = trap(tmp_path)
    only = TRAP_DOMAIN.replace("(:action a2 :parameters () :precondition (r) :effect (g))", "")
    (tmp_path / "domain.pddl").write_text(only)
    task = load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))
    with pytest.raises(NoAchieverError) as caught:
        plan(task, options=PlannerOptions(retries=3, **BARE))
    assert "1 attempts started over without a choice that failed (g() by a1())" in str(caught.value)


def lit(name: str, *args: str) -> GroundLiteral:
    return GroundLiteral(Atom(name, args), True)


def test_culprits_are_the_achiever_sequences_around_a_node_innermost_first() -> None:
    inner_pre = Condition("s", ())
    inner = SequenceNode([inner_pre, Action("make-q", ())])
    outer = SequenceNode([Condition("p", ()), Fallback([Condition("q", ()), inner]),
                          Action("a1", ())])
    root = Fallback([Condition("g", ()), outer])
    assert achiever_choice(outer) == (lit("g"), ("a1", ()))
    assert achiever_choice(root) is None  # a Fallback, not an achiever sequence
    assert enclosing_choices(inner_pre) == [(lit("q"), ("make-q", ())), (lit("g"), ("a1", ()))]
    assert running_choices(root, ("make-q", ())) == [(lit("q"), ("make-q", ())),
                                                     (lit("g"), ("a1", ()))]


def test_the_whole_goal_is_searched_for_when_backchaining_gives_up() -> None:
    task = load(str(DOMAINS / "planner_sussman.bt"))
    with pytest.raises(BudgetExceededError):
        plan(task, max_expansions=0, last_resort=False)
    result = plan(task, max_expansions=0)
    assert result.stats.whole_goal and result.stats.expansions == 0
    validate(task, result.executed)
    assert [str(a) for a in replay(task, result)] == [str(a) for a in result.executed]


def test_the_whole_goal_is_not_searched_for_when_h2_proves_it_never_holds(
        tmp_path: Path) -> None:
    # Making p destroys q and what q needs: p and q never hold together.
    (tmp_path / "domain.pddl").write_text(TRAP_DOMAIN)
    (tmp_path / "problem.pddl").write_text(
        "(define (problem both) (:domain trap) (:init (s)) (:goal (and (p) (q))))")
    task = load(str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl"))
    with pytest.raises(PlanningError, match=r"no plan exists: p\(\) and q\(\) can never hold"):
        plan(task)


def test_a_time_limit_that_runs_out_is_named_as_the_user_gave_it() -> None:
    # A limit far shorter than any tick: the first tick's check stops planning.
    task = load(str(DOMAINS / "planner_sussman.bt"))
    with pytest.raises(BudgetExceededError, match=r"^time limit of 1e-09 s reached after"):
        plan(task, timeout=1e-9, options=PlannerOptions())
    # With the last resort on, backchaining has a share of it, and the message says so.
    with pytest.raises(BudgetExceededError,
                       match=r"^backchaining's share \(8e-10 s\) of the 1e-09 s time limit"):
        plan(task, timeout=1e-9)
