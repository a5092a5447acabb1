"""Ctrl-C and SIGTERM on a real `btplan` process: what a stopped run leaves behind.

Each test starts the command, waits until the trace shows the work under way (a line,
or a finished action), sends a real signal, and reads what is left on disk and stderr.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
WAIT = 300.0  # seconds a child may take to get going on a loaded machine; not a measurement


def start(args: list[str], cwd: Path) -> subprocess.Popen[str]:
    env = {**os.environ, "COLUMNS": "200"}
    return subprocess.Popen([sys.executable, "-m", "btplan", *args], cwd=cwd, env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for(trace: Path, ready: Callable[[dict[str, Any]], bool],
             child: subprocess.Popen[str]) -> None:
    """Poll the streamed trace until a line satisfies `ready` (the child must still run)."""
    give_up = time.monotonic() + WAIT
    while time.monotonic() < give_up:
        assert child.poll() is None, child.communicate()
        if trace.exists():
            complete = trace.read_text().split("\n")[:-1]  # a line being written may be cut
            if any(ready(json.loads(line)) for line in complete):
                return
        time.sleep(0.05)
    child.kill()
    raise AssertionError("the run never got going")


def stopped(child: subprocess.Popen[str], signum: int) -> tuple[int, str]:
    child.send_signal(signum)
    _, err = child.communicate(timeout=WAIT)
    return child.returncode, err


def parse_trace(trace: Path) -> list[dict[str, Any]]:
    text = trace.read_text()
    assert text.endswith("\n"), "the last line is torn"
    records = [json.loads(line) for line in text.splitlines()]
    assert [r["tick"] for r in records] == list(range(1, len(records) + 1))
    return records


def check_left_behind(tmp_path: Path, code: int, err: str, expected: int) -> list[dict[str, Any]]:
    assert code == expected, err
    assert "Traceback" not in err
    records = parse_trace(tmp_path / "tr.jsonl")
    finished = [a for r in records for a in r["finished"]]
    plan = (tmp_path / "p.plan").read_text().splitlines()
    assert finished and len(plan) == len(finished)
    assert plan[0] == "(" + finished[0].replace("(", " ").replace(",", "").rstrip(")").lower() + ")"
    assert "interrupted" in err and f"ticks               {len(records)}" in err
    return records


def test_ctrl_c_during_a_symbolic_run_keeps_the_trace_the_plan_and_a_summary(
        tmp_path: Path) -> None:
    child = start(["run", str(DOMAINS / "pick_place.bt"), "--rate", "10", "-q",
                   "--trace", "tr.jsonl", "--plan-out", "p.plan"], tmp_path)
    wait_for(tmp_path / "tr.jsonl", lambda r: bool(r["finished"]), child)
    code, err = stopped(child, signal.SIGINT)
    records = check_left_behind(tmp_path, code, err, 130)
    assert records[-1]["status"] != "SUCCESS"  # stopped before the goal
    running = [n["name"] for n in records[-1]["nodes"]
               if n["kind"] == "Action" and n["status"] == "RUNNING"]
    halted_row = next(line for line in err.splitlines() if line.startswith(" halted"))
    assert all(name in halted_row for name in running)  # the tree was halted


def test_sigterm_exits_143_with_the_same_guarantees(tmp_path: Path) -> None:
    child = start(["run", str(DOMAINS / "pick_place.bt"), "--rate", "10", "-q",
                   "--trace", "tr.jsonl", "--plan-out", "p.plan"], tmp_path)
    wait_for(tmp_path / "tr.jsonl", lambda r: bool(r["finished"]), child)
    code, err = stopped(child, signal.SIGTERM)
    check_left_behind(tmp_path, code, err, 143)


@pytest.mark.slow
def test_ctrl_c_during_a_pybullet_run_also_closes_the_recording(tmp_path: Path) -> None:
    pytest.importorskip("pybullet")
    child = start(["run", str(DOMAINS / "youbot.bt"), "--sim", "pybullet", "-q",
                   "--trace", "tr.jsonl", "--plan-out", "p.plan", "--record", "run.gif"],
                  tmp_path)
    wait_for(tmp_path / "tr.jsonl", lambda r: bool(r["finished"]), child)
    code, err = stopped(child, signal.SIGINT)
    check_left_behind(tmp_path, code, err, 130)
    from PIL import Image

    with Image.open(tmp_path / "run.gif") as movie:
        assert movie.format == "GIF" and movie.n_frames >= 1


def test_ctrl_c_during_planning_writes_nothing_and_says_how_far_it_got(tmp_path: Path) -> None:
    generated = subprocess.run(
        [sys.executable, "-m", "btplan", "generate", "blocksworld", "--blocks", "40",
         "--format", "bt", "-o", "bw.bt"], cwd=tmp_path, capture_output=True, text=True)
    assert generated.returncode == 0, generated.stderr
    child = start(["plan", "bw.bt", "-o", "t.json", "--plan-out", "p.plan",
                   "--trace-expansions", "steps"], tmp_path)
    # planning writes nothing until it is done: wait until the child is past start-up
    while child.poll() is None and not _busy(child.pid):
        time.sleep(0.05)
    code, err = stopped(child, signal.SIGINT)
    assert code == 130, err
    assert "interrupted" in err and "nothing written" in err and "Traceback" not in err
    assert "expansions and" in err  # how far it got
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bw.bt"]


def _busy(pid: int) -> bool:
    """True once the child has spent two seconds of CPU time (past imports and parsing)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except OSError:
        return True
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK") > 2.0


def test_a_second_signal_exits_at_once(tmp_path: Path) -> None:
    """The first signal only asks to stop; the second one does not wait for the work."""
    script = (
        "import os, signal, time\n"
        "from btplan.cli.interrupts import Interrupts\n"
        "with Interrupts() as stop:\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"
        "    while not stop(): time.sleep(0.01)\n"
        "    print('asked to stop', flush=True)\n"
        "    os.kill(os.getpid(), signal.SIGINT)\n"
        "    time.sleep(60)\n"
        "    print('still here')\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=WAIT)
    assert done.returncode == 130
    assert done.stdout == "asked to stop\n"


def test_kill_9_keeps_every_finished_tick_and_the_plan_so_far(tmp_path: Path) -> None:
    child = start(["run", str(DOMAINS / "pick_place.bt"), "--rate", "10", "-q",
                   "--trace", "tr.jsonl", "--plan-out", "p.plan"], tmp_path)
    wait_for(tmp_path / "tr.jsonl", lambda r: bool(r["finished"]), child)
    child.kill()
    child.communicate(timeout=WAIT)
    records = parse_trace(tmp_path / "tr.jsonl")  # no torn line, ticks 1..n
    finished = [a for r in records for a in r["finished"]]
    planned = (tmp_path / "p.plan").read_text().splitlines()
    # The plan is written before the tick's trace line: a kill between the two leaves
    # the plan one tick ahead, never behind.
    assert len(finished) >= 1
    assert [a.split("(")[0].lower() for a in finished] == [
        line[1:].split()[0] for line in planned[:len(finished)]]
    assert len(finished) <= len(planned) <= len(finished) + 1


def test_a_signal_during_generate_writes_nothing(tmp_path: Path,
                                                monkeypatch: pytest.MonkeyPatch) -> None:
    from typer.testing import CliRunner

    from btplan.cli import app, generate

    real = generate.gripper

    def interrupted(*args: Any, **kwargs: Any) -> Any:
        os.kill(os.getpid(), signal.SIGTERM)  # a real signal, while the problem is made
        return real(*args, **kwargs)

    monkeypatch.setattr(generate, "gripper", interrupted)
    out = tmp_path / "g.pddl"
    result = CliRunner().invoke(app, ["generate", "gripper", "-o", str(out)])
    assert result.exit_code == 143 and "interrupted" in result.stderr
    assert not out.exists()


def test_an_inherited_ignored_sigint_stays_ignored(tmp_path: Path) -> None:
    """A background job of a script starts with SIGINT ignored; the run keeps it so, as
    GNU tools do, and goes on to the goal."""
    env = {**os.environ, "COLUMNS": "200"}
    child = subprocess.Popen(
        [sys.executable, "-m", "btplan", "run", str(DOMAINS / "pick_place.bt"), "--hz", "20",
         "-q", "--trace", "tr.jsonl"], cwd=tmp_path, env=env, stdout=subprocess.PIPE,
        stderr=subprocess.PIPE, text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    wait_for(tmp_path / "tr.jsonl", lambda r: r["tick"] >= 2, child)
    code, err = stopped(child, signal.SIGINT)
    assert code == 0, err
    assert "goal reached" in err and "interrupted" not in err
