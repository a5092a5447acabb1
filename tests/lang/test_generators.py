"""Generated problems: deterministic, valid, and read back as the same models in both languages."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.lang import collect
from btplan.lang.generators import GENERATORS, generate, render
from btplan.model import Atom, instantiate

SIZES = {"blocksworld": {"blocks": 8}, "gripper": {"balls": 6}, "logistics": {"packages": 5},
         "assembly": {"parts": 6}}


@pytest.mark.parametrize("name", sorted(GENERATORS))
@pytest.mark.parametrize("fmt", ["pddl", "bt"])
def test_generated_text_reads_back_as_the_same_models(tmp_path: Path, name: str, fmt: str) -> None:
    domain, problem = GENERATORS[name](seed=3, **SIZES[name])
    domain_text, problem_text = render(domain, problem, fmt)  # type: ignore[arg-type]
    (tmp_path / f"d.{fmt}").write_text(domain_text)
    (tmp_path / f"p.{fmt}").write_text(problem_text)
    read = collect([str(tmp_path / f"d.{fmt}"), str(tmp_path / f"p.{fmt}")])
    assert read.domains[0].model_copy(update={"requirements": ()}) == domain
    assert read.problems == (problem,)


@pytest.mark.parametrize("name", sorted(GENERATORS))
def test_the_same_seed_gives_the_same_text(name: str) -> None:
    first = generate(name, seed=7, **SIZES[name])
    assert generate(name, seed=7, **SIZES[name]) == first
    assert generate(name, seed=8, **SIZES[name]) != first


def test_blocksworld_initial_state_is_a_set_of_towers() -> None:
    _, problem = GENERATORS["blocksworld"](blocks=12, seed=5)
    facts = {(x.predicate, x.args) for x in problem.init}
    blocks = [o.name for o in problem.objects]
    for block in blocks:
        below = [f for f in facts if f[0] == "on" and f[1][0] == block]
        on_table = ("on_table", (block,)) in facts
        assert len(below) + on_table == 1  # every block rests on exactly one thing
        above = [f for f in facts if f[0] == "on" and f[1][1] == block]
        assert (("clear", (block,)) in facts) == (not above)
    assert problem.goal and all(g.predicate == "on" for g in problem.goal)


def test_a_generated_gripper_plan_reaches_the_goal() -> None:
    """The domain means what it says: a hand-made plan moves one ball."""
    domain, problem = GENERATORS["gripper"](balls=1, seed=0)
    state = frozenset(Atom(x.predicate, x.args) for x in problem.init)
    start = next(x.args[1] for x in problem.init if x.predicate == "at")
    robot = next(x.args[0] for x in problem.init if x.predicate == "at_robby")
    target = problem.goal[0].args[1]
    actions = domain.action_map
    steps = []
    if robot != start:
        steps.append(instantiate(actions["move"], (robot, start)))
    steps += [
        instantiate(actions["pick"], ("ball1", start, "left")),
        instantiate(actions["move"], (start, target)),
        instantiate(actions["drop"], ("ball1", target, "left")),
    ]
    for step in steps:
        assert step.applicable(state), step
        state = step.apply(state)
    assert Atom("at", ("ball1", target)) in state


@pytest.mark.parametrize("kind", ["blocksworld", "gripper", "logistics", "assembly"])
def test_no_generated_name_is_both_a_type_and_an_action(kind: str) -> None:
    """PDDL readers other than Fast Downward (unified-planning) refuse a name defined twice."""
    from btplan.lang import generators

    domain, _ = getattr(generators, kind)(4, seed=1)
    types = {t.name.lower() for t in domain.types}
    actions = {a.name.lower() for a in domain.actions}
    assert types & actions == set()
