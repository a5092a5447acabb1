"""`btplan run --groot [PORT]` and `--btlog FILE.btlog`, as a user runs them.

The live server is watched with btview's Groot2 client (a BT.CPP monitor written by
others, installed from PyPI) while a real `btplan run` process grows its tree."""

from __future__ import annotations

import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

from typer.testing import CliRunner

from btplan.cli import app
from btplan.cli.monitors import with_default_ports
from btplan.monitor.btlog import read_btlog
from peers import free_port, shape

ROOT = Path(__file__).resolve().parents[2]
OBSTACLE = str(ROOT / "domains" / "pick_place_obstacle.bt")
EXAMPLE2 = str(ROOT / "examples" / "example2.dist")
runner = CliRunner()


def btplan(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-m", "btplan", *args], cwd=ROOT, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def test_groot_without_a_port_takes_groot2_s_default() -> None:
    assert with_default_ports(["run", "d.bt", "--groot"]) == ["run", "d.bt", "--groot", "1667"]
    assert with_default_ports(["run", "--groot", "-q", "d.bt"]) == [
        "run", "--groot", "1667", "-q", "d.bt"]
    assert with_default_ports(["run", "--groot", "1700", "d.bt"]) == [
        "run", "--groot", "1700", "d.bt"]


def test_a_growing_tree_is_watched_live_by_a_groot2_client() -> None:
    from btview.client import Groot2Client

    port = free_port()
    run = btplan("run", OBSTACLE, "--scenario", EXAMPLE2, "--groot", str(port),
                 "--hz", "10", "-q")
    client = Groot2Client("127.0.0.1", port, timeout_ms=500)
    uuids: list[str] = []
    sizes: list[int] = []
    running: set[int] = set()
    board: dict[str, object] | None = None
    try:
        deadline = time.monotonic() + 120
        while run.poll() is None and time.monotonic() < deadline:
            try:
                tree = client.fetch_tree()
                fetched = client.tree_uuid  # the UUID the tree came with
                polled = client.poll()
                board = client.fetch_blackboard(["MainTree"]) or board
            except Exception:  # noqa: BLE001 (not serving yet, or the run just ended)
                time.sleep(0.05)
                continue
            if not uuids or fetched != uuids[-1]:
                uuids.append(fetched)
                sizes.append(len(tree.by_uid))
            if polled is not None:
                running.update(uid for uid, state in polled.statuses.items()
                               if state.status.name == "RUNNING")
            time.sleep(0.05)
        out, err = run.communicate(timeout=60)
    finally:
        client.close()
        if run.poll() is None:
            run.kill()
    assert run.returncode == 0, err
    assert len(uuids) >= 2 and sizes == sorted(sizes) and sizes[-1] > sizes[0]  # it grew
    assert running  # statuses were seen
    assert board is not None and "facts" in board["MainTree"]  # type: ignore[operator]
    with socket.socket() as again:  # the port is free once the run has ended (as a
        again.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # server binds it)
        again.bind(("127.0.0.1", port))


def test_a_port_in_use_is_bad_input_in_one_line() -> None:
    port = free_port()
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", port))
        taken.listen()
        run = btplan("run", OBSTACLE, "--groot", str(port), "-q")
        _, err = run.communicate(timeout=60)
    assert run.returncode == 2
    assert f"--groot {port}: cannot listen" in err and "Traceback" not in err


def test_a_btlog_without_its_suffix_is_refused() -> None:
    result = runner.invoke(app, ["run", OBSTACLE, "--btlog", "run.log", "-q"])
    assert result.exit_code == 2 and "must end in .btlog" in result.output


def test_the_replay_file_holds_the_final_tree_and_every_transition(tmp_path: Path) -> None:
    log = tmp_path / "example2.btlog"
    result = runner.invoke(app, ["run", OBSTACLE, "--scenario", EXAMPLE2, "--btlog",
                                 str(log), "-q"])
    assert result.exit_code == 0, result.output
    xml, _, transitions = read_btlog(log.read_bytes())
    uids = {int(uid) for _, uid in shape(xml)}
    assert {uid for _, uid, _ in transitions} <= uids
    assert max(uids) == len(uids) > 20  # grown: the blocked path's subtree is in it
    assert {status for _, _, status in transitions} >= {0, 1, 2, 3}


def test_an_interrupted_run_still_leaves_its_replay_file(tmp_path: Path) -> None:
    log = tmp_path / "kept.btlog"
    run = btplan("run", OBSTACLE, "--keep", "--hz", "20", "--btlog", str(log), "-q")
    time.sleep(3)
    run.send_signal(signal.SIGINT)
    _, err = run.communicate(timeout=60)
    assert run.returncode == 130, err
    xml, _, transitions = read_btlog(log.read_bytes())
    assert transitions and shape(xml)
    assert not list(tmp_path.glob(".*.tmp"))
