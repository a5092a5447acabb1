"""Memory that grows with what the problem needs: on a wide problem, the searches over
every grounding as bit masks (actions times atoms) are left out instead of taking
gigabytes (AchieverIndex.fits_search)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

import btplan
from btplan.acting.offline.whole_goal import SearchTurns, WholeGoalSearch
from btplan.planner import AchieverIndex, achievers

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
from limits import DOMAIN, problem  # noqa: E402  (the bench's wide gripper)


def wide(tmp_path: Path, balls: int) -> tuple[Path, Path]:
    domain, task = tmp_path / "d.pddl", tmp_path / f"p{balls}.pddl"
    domain.write_text(DOMAIN)
    task.write_text(problem(balls))
    return domain, task


def test_a_search_too_wide_for_its_budget_is_left_out_before_it_is_built(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(achievers, "SEARCH_BYTES", 1000)
    task = btplan.load(*map(str, wide(tmp_path, 40)))
    models = AchieverIndex(task)
    assert not models.fits_search()
    last = WholeGoalSearch(task, models, seed=0)
    assert last.resume(None) is None and "too wide to search whole" in last.why(None)
    assert not models.has_packed  # nothing was built
    turns = SearchTurns(last, started=0.0, limit=1.0, until=1e18)
    turns.first = 0.0
    assert turns.take() is None and turns.turns == 0


def test_the_same_problem_within_the_budget_is_searched(tmp_path: Path) -> None:
    task = btplan.load(*map(str, wide(tmp_path, 40)))
    models = AchieverIndex(task)
    assert models.fits_search()
    last = WholeGoalSearch(task, models, seed=0)
    assert [a.name for a in last.resume(None) or []] == ["pick", "move", "drop"]


@pytest.mark.slow
def test_ten_thousand_balls_take_a_few_hundred_megabytes_not_a_gigabyte(tmp_path: Path) -> None:
    """With a time limit, the whole-goal search used to get turns while backchaining ran,
    and its bit masks took 885 MB; backchaining alone needs about 215 MB."""
    domain, task = wide(tmp_path, 10_000)
    # A fresh parent whose only child is btplan: its children's peak is btplan's own.
    measure = ("import resource, subprocess, sys\n"
               "subprocess.run(sys.argv[1:], capture_output=True, check=False)\n"
               "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    done = subprocess.run([sys.executable, "-c", measure, sys.executable, "-m", "btplan",
                           "plan", str(domain), str(task), "-o", str(tmp_path / "tree.json"),
                           "--timeout", "5"], capture_output=True, text=True, check=True,
                          timeout=600)
    peak_mb = int(done.stdout) / 1024
    assert peak_mb < 500, f"{peak_mb:.0f} MB"
