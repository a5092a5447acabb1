"""OMPL's plans repeat: seeded per run, and bounded by iterations rather than the clock."""

from __future__ import annotations

import time

import pytest

pytest.importorskip("ompl")

from btplan.worlds.pybullet import motion  # noqa: E402

BOUNDS = (-2.0, 2.0, -2.0, 2.0)


def door(x: float, y: float) -> bool:
    return abs(x) > 0.5 or abs(y) < 0.3  # a wall with a door at y = 0


def wall(x: float, y: float) -> bool:
    return abs(x) > 0.5  # no door: the two halves are not connected


def through_door() -> tuple[motion.Pose2, ...]:
    plan = motion.plan_se2((-1.5, 1.0, 0.0), (1.5, -1.0, 0.0), door, BOUNDS, 3000)
    assert plan is not None
    return plan.path


def test_seeding_again_repeats_a_plan_whatever_was_planned_before() -> None:
    """A worker runs many seeds one after the other: each run's plans must depend on its
    own seed only, not on the solves of the runs before it in the same process."""
    motion.seed_rng(7)
    first = through_door()
    for _ in range(3):
        through_door()  # another run's solves
    motion.seed_rng(7)
    assert through_door() == first
    motion.seed_rng(8)
    assert through_door() != first


def test_a_solve_stops_after_its_iterations_however_slow_the_checks_are() -> None:
    """With no way through, the planner gives up after the same work, and so the same
    collision checks, whether each check is fast or slow (a loaded machine)."""
    checked: list[tuple[float, float]] = []

    def counted(x: float, y: float) -> bool:
        checked.append((x, y))
        return wall(x, y)

    def slow(x: float, y: float) -> bool:
        time.sleep(0.0002)
        return counted(x, y)

    motion.seed_rng(3)
    assert motion.plan_se2((-1.5, 1.0, 0.0), (1.5, -1.0, 0.0), counted, BOUNDS, 100) is None
    fast_checks = list(checked)
    checked.clear()
    motion.seed_rng(3)
    assert motion.plan_se2((-1.5, 1.0, 0.0), (1.5, -1.0, 0.0), slow, BOUNDS, 100) is None
    assert checked == fast_checks and len(fast_checks) > 100
    checked.clear()
    motion.seed_rng(3)
    assert motion.plan_se2((-1.5, 1.0, 0.0), (1.5, -1.0, 0.0), counted, BOUNDS, 200) is None
    assert len(checked) > len(fast_checks)  # more iterations, more work


def test_work_counts_the_checks_of_the_termination_condition() -> None:
    work = motion.Work(2)
    assert [work(), work(), work()] == [False, False, True] and work.used == 3
