"""Grounding by relaxed reachability: the old model's actions that can ever run, no more."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from btplan.lang.generators import GENERATORS
from btplan.lang.loader import load
from btplan.model import Task
from btplan.classical.heuristic import RelaxedModel

DOOR = """(define (domain door) (:requirements :strips :typing :negative-preconditions)
  (:types room key)
  (:predicates (in ?r - room) (link ?a ?b - room) (open ?a ?b - room) (has ?k - key)
               (opens ?k - key ?a ?b - room) (at ?k - key ?r - room) (bent ?k - key))
  (:action walk :parameters (?a ?b - room)
    :precondition (and (in ?a) (link ?a ?b) (open ?a ?b))
    :effect (and (not (in ?a)) (in ?b)))
  (:action unlock :parameters (?k - key ?a ?b - room)
    :precondition (and (in ?a) (has ?k) (opens ?k ?a ?b) (not (bent ?k)) (not (= ?a ?b)))
    :effect (and (open ?a ?b)))
  (:action take :parameters (?k - key ?r - room)
    :precondition (and (in ?r) (at ?k ?r))
    :effect (and (has ?k) (not (at ?k ?r)))))
"""
ROOMS = """(define (problem rooms) (:domain door)
  (:objects r1 r2 r3 r4 - room k1 k2 k3 - key)
  (:init (in r1) (link r1 r2) (link r2 r3) (link r3 r4) (open r1 r2) (open r2 r3)
         (at k1 r2) (at k2 r4) (at k3 r1) (bent k3) (opens k1 r2 r2) (opens k2 r3 r4)
         (opens k3 r3 r4))
  (:goal (in r4)))
"""


def keys(model: RelaxedModel) -> list[tuple[str, tuple[str, ...]]]:
    return [a.key for a in model.actions]


def runnable(task: Task) -> list[tuple[str, tuple[str, ...]]]:
    """The old model's actions whose positive preconditions h_add reaches."""
    old = RelaxedModel(task, ground=task.instantiate, reach=False)
    cost = old.costs(task.initial_state)
    return [a.key for a in old.actions if all(
        cost.get(p.atom, math.inf) < math.inf for p in a.preconditions if p.positive)]


@pytest.mark.parametrize("name,size", [("blocksworld", 4), ("gripper", 3), ("logistics", 2),
                                       ("assembly", 3)])
def test_generated_domains_keep_the_runnable_actions(name: str, size: int) -> None:
    domain, problem = GENERATORS[name](size, seed=1)
    task = Task(domain=domain, problem=problem)
    new = RelaxedModel(task, ground=task.instantiate)
    assert keys(new) == runnable(task)
    assert new.costs(task.initial_state) == RelaxedModel(
        task, ground=task.instantiate, reach=False).costs(task.initial_state)


def test_actions_that_can_never_run_are_not_grounded(tmp_path: Path) -> None:
    (tmp_path / "domain.pddl").write_text(DOOR)
    (tmp_path / "p.pddl").write_text(ROOMS)
    task = load([str(tmp_path / "domain.pddl"), str(tmp_path / "p.pddl")])
    new = keys(RelaxedModel(task, ground=task.instantiate))
    old = keys(RelaxedModel(task, ground=task.instantiate, reach=False))
    assert new == runnable(task)
    # k2 lies behind the door only k2 opens (k3 is bent, k1 opens nothing): taking k1
    # and k3 is reachable, taking k2 and walking through never
    assert ("take", ("k1", "r2")) in new and ("take", ("k3", "r1")) in new
    assert ("take", ("k2", "r4")) in old and ("take", ("k2", "r4")) not in new
    assert ("walk", ("r3", "r4")) in old and ("walk", ("r3", "r4")) not in new
    # a static negation and an equality still filter
    assert not any(key[0] == "unlock" for key in new) and len(new) < len(old)


def test_only_offline_planning_leaves_unreachable_groundings_out(tmp_path: Path) -> None:
    # an outside agent could hand the robot k2 or open r3-r4, which no action reaches:
    # an index for acting must keep the achievers that need them
    from btplan.planner.achievers import AchieverIndex

    (tmp_path / "domain.pddl").write_text(DOOR)
    (tmp_path / "p.pddl").write_text(ROOMS)
    task = load([str(tmp_path / "domain.pddl"), str(tmp_path / "p.pddl")])
    acting = keys(AchieverIndex(task).relaxed)
    offline = keys(AchieverIndex(task, reachable_only=True).relaxed)
    assert ("walk", ("r3", "r4")) in acting and ("walk", ("r3", "r4")) not in offline
    assert set(offline) < set(acting)
