"""A sweep keeps every finished row on disk as it goes (btplan.sweep.journal)."""

from __future__ import annotations

import errno
import json
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.cli import app
from btplan.sweep.output import read_rows

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK = str(DOMAINS / "pick_place.bt")
runner = CliRunner()


def sweep(out: Path, *extra: str) -> list[str]:
    return ["sweep", PICK, "--seeds", "0:3", "--rates", "0", "--method", "btplan", "-j", "1",
            "-q", "-o", str(out), *extra]


def counted_runs(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str, float, int]]:
    from btplan.sweep import pool

    done: list[tuple[str, float, int]] = []
    real = pool.run_one

    def run_one(job: object, method: str, rate: float, seed: int) -> object:
        done.append((method, rate, seed))
        return real(job, method, rate, seed)  # type: ignore[arg-type]

    monkeypatch.setattr(pool, "run_one", run_one)
    return done


def test_a_final_write_that_fails_keeps_every_row_and_resume_writes_them(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from btplan.sweep import output

    out = tmp_path / "rows.csv"
    real = output.write_rows

    def full_disk(path: str, rows: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(output, "write_rows", full_disk)
    failed = runner.invoke(app, sweep(out))
    assert failed.exit_code == 2
    assert "No space left on device" in failed.output and "rows.csv.rows.jsonl" in failed.output
    kept = [json.loads(line) for line in (tmp_path / "rows.csv.rows.jsonl").read_text()
            .splitlines()]
    assert sorted(r["seed"] for r in kept) == [0, 1, 2]
    monkeypatch.setattr(output, "write_rows", real)
    runs = counted_runs(monkeypatch)
    again = runner.invoke(app, sweep(out, "--resume"))
    assert again.exit_code == 0, again.output
    assert runs == []  # nothing run twice
    assert sorted(r["seed"] for r in read_rows(str(out))) == [0, 1, 2]
    assert not (tmp_path / "rows.csv.rows.jsonl").exists()


def test_resume_runs_only_what_is_missing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch
                                          ) -> None:
    out = tmp_path / "rows.csv"
    assert runner.invoke(app, sweep(out)).exit_code == 0
    first = {r["seed"]: r for r in read_rows(str(out))}
    line = json.dumps({**first[1], "rate": float(first[1]["rate"])})
    (tmp_path / "rows.csv.rows.jsonl").write_text(line + "\n" + line[:20])  # a torn line
    refused = runner.invoke(app, sweep(out))
    assert refused.exit_code == 2 and "--resume" in refused.output
    runs = counted_runs(monkeypatch)
    resumed = runner.invoke(app, sweep(out, "--resume"))
    assert resumed.exit_code == 0, resumed.output
    assert sorted(seed for _, _, seed in runs) == [0, 2]
    assert sorted(r["seed"] for r in read_rows(str(out))) == [0, 1, 2]


def test_kill_9_keeps_the_finished_rows_and_the_workers_leave_quietly(tmp_path: Path) -> None:
    out = tmp_path / "rows.csv"
    journal = tmp_path / "rows.csv.rows.jsonl"
    child = subprocess.Popen(
        [sys.executable, "-m", "btplan", "sweep", PICK, "--seeds", "0:400", "--rates", "0",
         "--method", "btplan", "-j", "2", "-q", "-o", str(out)],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    give_up = time.monotonic() + 120
    while time.monotonic() < give_up:
        if journal.exists() and journal.read_text().count("\n") >= 3:
            break
        assert child.poll() is None, child.communicate()
        time.sleep(0.05)
    child.send_signal(signal.SIGKILL)
    _, err = child.communicate(timeout=60)  # ends when the orphaned workers have left
    assert "Traceback" not in err and "BrokenPipeError" not in err
    rows = [json.loads(line) for line in journal.read_text().splitlines(keepends=True)
            if line.endswith("\n")]
    assert len(rows) >= 3 and not out.exists()
