"""Writing models back as text: .bt keeps everything, PDDL refuses what it cannot say."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.errors import InputError
from btplan.lang import load, parse_bt
from btplan.lang.writers import bt_domain, bt_problem, pddl_domain, pddl_problem

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


@pytest.mark.parametrize("name", ["pick_place.bt", "blocksworld.bt", "gripper.bt", "logistics.bt"])
def test_bt_round_trip_of_the_bundled_domains(name: str) -> None:
    task = load([str(DOMAINS / name)])
    text = bt_domain(task.domain) + "\n" + bt_problem(task.problem)
    again = parse_bt(text, "again.bt")
    assert again.domain == task.domain
    assert again.problems == (task.problem,)


def test_pick_place_keeps_refined_where_wildcard_and_durations() -> None:
    text = bt_domain(load([str(DOMAINS / "pick_place.bt")]).domain)
    assert "action MoveTo(l: location, t: trajectory refined) {" in text
    assert "where: route(l, t)" in text
    assert "post:  not near(_), near(l)" in text
    assert "duration: 3" in text
    assert "object : location" in text


def test_pddl_refuses_what_it_cannot_express() -> None:
    task = load([str(DOMAINS / "pick_place.bt")])
    with pytest.raises(InputError) as caught:
        pddl_domain(task.domain)
    assert caught.value.message.startswith("cannot be written as PDDL")
    assert caught.value.hint == "write it with --format bt"


def test_pddl_problem_of_a_bundled_domain_reads_back(tmp_path: Path) -> None:
    task = load([str(DOMAINS / "blocksworld.bt")], problem="sussman")
    (tmp_path / "d.pddl").write_text(pddl_domain(task.domain))
    (tmp_path / "p.pddl").write_text(pddl_problem(task.problem))
    again = load([str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")])
    assert again.problem == task.problem
    assert again.domain.actions == task.domain.actions
    assert again.domain.requirements == (":strips", ":typing")


def test_pddl_refuses_costs_and_durations_rather_than_dropping_them() -> None:
    domain = parse_bt(
        "domain d { predicates { p } action A() { post: p  cost: 2 } }", "d.bt"
    ).domain
    assert domain is not None
    with pytest.raises(InputError) as caught:
        pddl_domain(domain)
    assert caught.value.message == "cannot be written as PDDL: the cost or duration of A"
