"""`btplan sweep`: the same rows whatever ran them, dead workers retried, Ctrl-C keeps rows."""

from __future__ import annotations

import os
import signal
import stat
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from btplan.cli import app
from btplan.sweep import Job, pool
from btplan.sweep.output import read_rows, sort_rows
from btplan.sweep.runs import TIMED, Row
from btplan.sweep.stats import median_interval, wilson

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
OBSTACLE = str(DOMAINS / "pick_place_obstacle.bt")
JOB = Job((OBSTACLE,), "obstacle")
RUNS = [(m, r, s) for r in (0.0, 0.2) for m in ("btplan", "repair") for s in range(3)]
runner = CliRunner()


def untimed(rows: list[Row]) -> list[dict[str, Any]]:
    return [{k: v for k, v in r.items() if k not in TIMED} for r in sort_rows(rows)]


@pytest.fixture(scope="module")
def serial_rows() -> list[Row]:
    rows: list[Row] = []
    pool.run_serial(JOB, RUNS, rows.append)
    return rows


def test_one_and_two_local_workers_give_the_same_rows(serial_rows: list[Row]) -> None:
    rows: list[Row] = []
    pool.run_local(JOB, list(reversed(RUNS)), rows.append, 2)
    assert untimed(rows) == untimed(serial_rows)
    assert len(rows) == len(RUNS) and not any(r["error"] for r in rows)
    assert {r["method"] for r in rows} == {"btplan", "repair"}


@pytest.mark.slow
def test_a_local_ray_gives_the_same_rows(serial_rows: list[Row]) -> None:
    pytest.importorskip("ray")
    rows: list[Row] = []
    pool.run_ray(JOB, RUNS, rows.append, None, 2)  # ray.init(num_cpus=2)
    assert untimed(rows) == untimed(serial_rows)


def test_a_cluster_that_cannot_be_reached_is_one_line_with_a_hint(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    ray = pytest.importorskip("ray")

    def refused(**kwargs: Any) -> None:
        raise ConnectionError(f"Failed to connect to Ray cluster at {kwargs['address']}")

    monkeypatch.setattr(ray, "is_initialized", lambda: False)
    monkeypatch.setattr(ray, "init", refused)
    result = runner.invoke(app, ["sweep", OBSTACLE, "--seeds", "0:2", "--rates", "0", "-q",
                                 "--method", "btplan", "--ray", "head:6379",
                                 "-o", str(tmp_path / "r.csv")])
    assert result.exit_code != 0 and "Traceback" not in result.stderr
    assert result.stderr.count("\n") == 1
    assert "cannot start or reach Ray (Failed to connect to Ray cluster at head:6379)" in (
        result.stderr)
    assert "needs RAY_AUTH_MODE=token here too" in result.stderr


def test_a_killed_worker_loses_only_its_run_which_is_retried(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    marker = tmp_path / "killed"
    monkeypatch.setenv("BTPLAN_TEST_CRASH_MARKER", str(marker))
    monkeypatch.syspath_prepend(str(Path(__file__).parent))
    runs = [("repair", 0.2, s) for s in range(4)]
    rows: list[Row] = []
    pool.run_local(Job((OBSTACLE,), "crash_scenario:CRASH_ONCE"), runs, rows.append, 2)
    assert marker.exists()  # the run of seed 1 did kill its worker
    assert sorted(r["seed"] for r in rows) == [0, 1, 2, 3]
    assert not any(r["error"] for r in rows)
    calm: list[Row] = []
    pool.run_serial(Job((OBSTACLE,), "undo"), runs, calm.append)
    assert [r["ticks"] for r in sort_rows(rows)] == [r["ticks"] for r in sort_rows(calm)]


def test_a_run_that_kills_every_worker_becomes_an_error_row(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("BTPLAN_TEST_CRASH_MARKER", str(tmp_path / "x"))
    monkeypatch.syspath_prepend(str(Path(__file__).parent))
    rows: list[Row] = []
    pool.run_local(Job((OBSTACLE,), "crash_scenario:CRASH_ALWAYS"),
                   [("repair", 0.2, s) for s in range(3)], rows.append, 2)
    errors = {r["seed"]: r["error"] for r in rows}
    assert sorted(errors) == [0, 1, 2]
    assert errors[1].startswith("WorkerDied") and not errors[0] and not errors[2]


def test_the_cli_writes_sorted_rows_and_a_summary(tmp_path: Path) -> None:
    out = tmp_path / "rows.csv"
    result = runner.invoke(app, ["sweep", OBSTACLE, "--scenario", "obstacle", "--seeds", "0:3",
                                 "--rates", "0.2,0", "--method", "btplan,replan", "-j", "1",
                                 "-o", str(out), "-q"])
    assert result.exit_code == 0, result.output
    rows = read_rows(str(out))
    assert [(r["method"], r["rate"], r["seed"]) for r in rows] == [
        (m, r, s) for m in ("btplan", "replan") for r in (0.0, 0.2) for s in range(3)]
    assert all(r["success"] and r["planning_seconds"] > 0 for r in rows)
    assert "| obstacle | btplan | 0 | 3 | 100% [44%, 100%] | 7 [7, 7] |" in result.stderr


def _stop_after_two_runs(signum: int) -> None:
    """The signal arrives as Ctrl-C would (SIGINT: KeyboardInterrupt) or from `kill`."""
    if signum == signal.SIGINT:
        raise KeyboardInterrupt
    os.kill(os.getpid(), signum)


@pytest.mark.parametrize(("signum", "code"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_a_stopped_sweep_keeps_the_rows_already_done(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch, signum: int, code: int) -> None:
    serial, before = pool.run_serial, signal.getsignal(signal.SIGTERM)

    def stopped(job: Job, runs: list[pool.Run], on_row: pool.OnRow) -> None:
        serial(job, runs[:2], on_row)
        _stop_after_two_runs(signum)
        serial(job, runs[2:], on_row)  # never reached: the signal stops the sweep

    monkeypatch.setattr(pool, "run_serial", stopped)
    out = tmp_path / "rows.csv"
    result = runner.invoke(app, ["sweep", OBSTACLE, "--scenario", "obstacle", "--seeds", "0:5",
                                 "--rates", "0.1", "--method", "btplan", "-j", "1", "-o", str(out),
                                 "-q"])
    assert result.exit_code == code
    assert [r["seed"] for r in read_rows(str(out))] == [0, 1]
    assert "2 of 5 runs written" in result.stderr
    assert signal.getsignal(signal.SIGTERM) is before


@pytest.fixture
def umask_022() -> Iterator[None]:
    """The usual umask, so that an output's mode says whether it was left private."""
    before = os.umask(0o022)
    try:
        yield
    finally:
        os.umask(before)


def test_parquet_rows_read_back(tmp_path: Path, umask_022: None) -> None:
    pytest.importorskip("pyarrow")
    out = tmp_path / "rows.parquet"
    result = runner.invoke(app, ["sweep", OBSTACLE, "--scenario", "obstacle", "--seeds", "2",
                                 "--rates", "0", "--method", "repair", "-j", "1", "-o", str(out),
                                 "-q"])
    assert result.exit_code == 0, result.output
    assert [(r["method"], r["seed"], r["ticks"]) for r in read_rows(str(out))] == [
        ("repair", 0, 7), ("repair", 1, 7)]
    assert stat.S_IMODE(out.stat().st_mode) == 0o644  # as `open` makes it, not private


def test_the_plot_is_drawn_whole_with_the_usual_mode(tmp_path: Path, umask_022: None) -> None:
    pytest.importorskip("matplotlib")
    image = tmp_path / "rows.png"
    result = runner.invoke(app, ["sweep", OBSTACLE, "--scenario", "obstacle", "--seeds", "2",
                                 "--rates", "0,0.1", "--method", "btplan", "-j", "1", "-o",
                                 str(tmp_path / "rows.csv"), "--plot", str(image), "-q"])
    assert result.exit_code == 0, result.output
    assert image.read_bytes().startswith(b"\x89PNG")
    assert stat.S_IMODE(image.stat().st_mode) == 0o644
    assert sorted(p.name for p in tmp_path.iterdir()) == ["rows.csv", "rows.png"]


def test_missing_extras_and_bad_flags_are_one_clean_line(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    base = ["sweep", OBSTACLE, "--seeds", "0:2", "--rates", "0", "-j", "1", "-q"]
    monkeypatch.setitem(sys.modules, "pyarrow", None)
    result = runner.invoke(app, [*base, "-o", str(tmp_path / "r.parquet")])
    assert result.exit_code == 2
    assert "Parquet output needs pyarrow: pip install 'btplan[parquet]'" in result.stderr
    monkeypatch.setitem(sys.modules, "pyperplan", None)
    result = runner.invoke(app, [*base, "-o", str(tmp_path / "r.csv")])
    assert result.exit_code == 2
    assert "need pyperplan: pip install 'btplan[replan]'" in result.stderr
    result = runner.invoke(app, [*base, "--scenario", "obstacel", "-o", str(tmp_path / "r.csv"),
                                 "--method", "btplan"])
    assert result.exit_code == 2
    assert "unknown scenario 'obstacel' (did you mean 'obstacle'?)" in result.stderr
    result = runner.invoke(app, [*base, "--method", "btplan", "-o", str(tmp_path / "r.txt")])
    assert result.exit_code == 2 and "name it .csv or .parquet" in result.stderr
    csv_out = ["--method", "btplan", "-o", str(tmp_path / "r.csv")]
    result = runner.invoke(app, [*base, *csv_out, "--plot", str(tmp_path / "p.txt")])
    assert result.exit_code == 2 and "name it .png, .svg or .pdf" in result.stderr
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    result = runner.invoke(app, [*base, *csv_out, "--plot", str(tmp_path / "p.png")])
    assert result.exit_code == 2
    assert "--plot needs matplotlib: pip install 'btplan[bench]'" in result.stderr
    assert not list(tmp_path.iterdir())  # refused before any run: no rows written either


def test_intervals() -> None:
    m = median_interval(range(100))
    assert (m.value, m.low, m.high) == (49.5, 39, 60)  # ranks 40 and 61 of 100
    assert median_interval([5.0]).low == 5.0
    w = wilson(10, 10)
    assert w.value == 1.0 and 0.69 < w.low < 0.73 and w.high == pytest.approx(1.0)


def test_a_scenario_the_simulator_cannot_serve_is_refused_before_any_run(
        tmp_path: Path) -> None:
    out = tmp_path / "r.csv"
    result = runner.invoke(app, ["sweep", str(DOMAINS / "youbot.bt"), "--sim", "pybullet",
                                 "--scenario", "undo", "--seeds", "1", "--rates", "0.1",
                                 "--method", "btplan", "-o", str(out)])
    assert result.exit_code == 2
    assert "the scenario 'undo' runs in the symbolic world only" in result.stderr
    assert not out.exists()


@pytest.mark.slow
def test_a_pybullet_sweep_gives_the_same_rows_on_one_or_two_workers(tmp_path: Path) -> None:
    """OMPL is seeded per run and bounded by iterations: with `-j 1` both seeds run in this
    process one after the other (after whatever this process planned before), with
    `-j 2` each in a fresh worker, and the rows are the same."""
    pytest.importorskip("pybullet")

    def sweep(jobs: int) -> list[Row]:
        out = tmp_path / f"youbot{jobs}.csv"
        result = runner.invoke(app, ["sweep", str(DOMAINS / "youbot.bt"), "--sim", "pybullet",
                                     "--scenario", "shove", "--seeds", "0:2", "--rates",
                                     "0.02", "--method", "btplan", "--max-ticks", "300",
                                     "-j", str(jobs), "-o", str(out), "-q"])
        assert result.exit_code == 0, result.output
        return read_rows(str(out))

    one = sweep(1)
    assert untimed(sweep(2)) == untimed(one)
    assert not any(r["error"] for r in one) and all(r["planner_calls"] > 0 for r in one)
    assert all(r["scenario"] == "shove" and r["disturbances"] > 0 for r in one)


def test_a_run_past_the_timeout_becomes_an_error_row(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("BTPLAN_TEST_CRASH_MARKER", str(tmp_path / "stalled"))
    monkeypatch.syspath_prepend(str(Path(__file__).parent))
    out = tmp_path / "rows.csv"
    result = runner.invoke(app, ["sweep", OBSTACLE, "--scenario", "crash_scenario:STALL_ONCE",
                                 "--seeds", "0:3", "--rates", "0.2", "--method", "repair",
                                 "-j", "1", "--timeout", "10", "-o", str(out), "-q"])
    assert result.exit_code == 1  # some runs crashed
    errors = {r["seed"]: r["error"] for r in read_rows(str(out))}
    assert errors == {0: "", 1: "Timeout: the run took more than 10 s", 2: ""}


def test_a_shipped_domain_is_found_by_name(tmp_path: Path,
                                           monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["sweep", "pick_place_obstacle", "--scenario", "obstacle",
                                 "--seeds", "0:2", "--rates", "0", "--method", "btplan",
                                 "-j", "1", "-o", "rows.csv", "-q"])
    assert result.exit_code == 0, result.stderr
    assert [r["seed"] for r in read_rows(str(tmp_path / "rows.csv"))] == [0, 1]
