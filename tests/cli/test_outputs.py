"""Output files: a normal file's mode, checked before any work, at most one on stdout."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterator
from pathlib import Path

import pytest
from typer.testing import CliRunner

from btplan.cli import app

DOMAINS = Path(__file__).resolve().parents[2] / "domains"
PICK = str(DOMAINS / "pick_place.bt")
runner = CliRunner()


@pytest.fixture
def umask_022() -> Iterator[None]:
    previous = os.umask(0o022)
    yield
    os.umask(previous)


def mode(path: Path) -> int:
    return stat.S_IMODE(path.stat().st_mode)


def test_every_command_writes_files_0644_under_umask_022(tmp_path: Path, umask_022: None) -> None:
    tree, plan, xml = tmp_path / "t.json", tmp_path / "p.plan", tmp_path / "t.xml"
    trace, run_plan, pddl = tmp_path / "tr.jsonl", tmp_path / "run.plan", tmp_path / "bw.pddl"
    steps = tmp_path / "steps"
    commands = [
        ["plan", PICK, "-o", str(tree), "--plan-out", str(plan), "--trace-expansions", str(steps)],
        ["export", "xml", str(tree), "-o", str(xml)],
        ["run", PICK, "-q", "--trace", str(trace), "--plan-out", str(run_plan)],
        ["generate", "blocksworld", "-o", str(pddl)],
    ]
    for args in commands:
        result = runner.invoke(app, args)
        assert result.exit_code == 0, result.output
    written = [tree, plan, xml, trace, run_plan, pddl, *sorted(steps.iterdir())]
    assert len(written) == 14
    assert {p.name: oct(mode(p)) for p in written} == {p.name: "0o644" for p in written}


def test_an_existing_file_keeps_its_mode(tmp_path: Path, umask_022: None) -> None:
    tree = tmp_path / "t.json"
    tree.write_text("old")
    tree.chmod(0o640)
    result = runner.invoke(app, ["plan", PICK, "-o", str(tree)])
    assert result.exit_code == 0, result.output
    assert tree.read_text() != "old" and mode(tree) == 0o640


def test_the_umask_is_honoured(tmp_path: Path) -> None:
    previous = os.umask(0o077)
    try:
        result = runner.invoke(app, ["generate", "gripper", "-o", str(tmp_path / "g.pddl")])
    finally:
        os.umask(previous)
    assert result.exit_code == 0 and mode(tmp_path / "g.pddl") == 0o600


def read_only_folder(tmp_path: Path) -> Path:
    """A folder this process cannot write in (root ignores modes: use /proc/self then)."""
    folder = tmp_path / "locked"
    folder.mkdir()
    folder.chmod(0o500)
    if os.access(folder, os.W_OK):
        if os.path.isdir("/proc/self") and not os.access("/proc/self", os.W_OK):
            return Path("/proc/self")
        pytest.skip("no folder here is read-only for this user")
    return folder


BAD = {
    "a folder": (lambda tmp: str(tmp / "existing"), "is a folder, not a file"),
    "a missing parent": (lambda tmp: str(tmp / "nowhere" / "x"), "does not exist"),
    "a file as parent": (lambda tmp: str(tmp / "good.json" / "x"), "is not a folder"),
    "no permission": (lambda tmp: str(read_only_folder(tmp) / "x"), "no permission to write"),
}

COMMANDS = {
    "plan -o": lambda bad, good: ["plan", PICK, "-o", bad, "--plan-out", good],
    "plan --plan-out": lambda bad, good: ["plan", PICK, "-o", good, "--plan-out", bad],
    "run --trace": lambda bad, good: ["run", PICK, "--plan-out", good, "--trace", bad],
    "run --plan-out": lambda bad, good: ["run", PICK, "--trace", good, "--plan-out", bad],
    "export -o": lambda bad, good: ["export", "xml", "TREE", "-o", bad],
    "generate -o": lambda bad, good: ["generate", "logistics", "-o", bad],
}


@pytest.mark.parametrize("case", sorted(BAD))
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_bad_output_path_exits_2_before_any_file_is_touched(
        tmp_path: Path, case: str, command: str) -> None:
    (tmp_path / "existing").mkdir()
    (tmp_path / "good.json").write_text("keep")
    tree = tmp_path / "tree.json"
    tree.write_text(runner.invoke(app, ["plan", PICK, "-f", "json"]).stdout)
    make, message = BAD[case]
    bad = make(tmp_path)
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")}
    good = str(tmp_path / "good.json")
    args = [str(tree) if a == "TREE" else a for a in COMMANDS[command](bad, good)]
    result = runner.invoke(app, args)
    assert result.exit_code == 2, result.output
    flag = command.split()[1]
    (line,) = result.stderr.strip().splitlines()
    assert flag in line and bad in line and message in line
    assert (tmp_path / "good.json").read_text() == "keep"
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*")} == before


def test_two_outputs_on_stdout_are_refused_naming_both_flags() -> None:
    result = runner.invoke(app, ["plan", PICK, "--plan-out", "-"])
    assert result.exit_code == 2
    assert "-o/--output and --plan-out both write to standard output" in result.stderr
    result = runner.invoke(app, ["run", PICK, "--trace", "-", "--plan-out", "-"])
    assert result.exit_code == 2
    assert "--trace and --plan-out both write to standard output" in result.stderr


def test_two_outputs_to_one_file_are_refused(tmp_path: Path) -> None:
    same = str(tmp_path / "same")
    result = runner.invoke(app, ["plan", PICK, "-o", same, "--plan-out", same])
    assert result.exit_code == 2 and "both write to" in result.stderr
    assert not Path(same).exists()


def test_a_file_where_the_expansion_folder_goes_is_refused(tmp_path: Path) -> None:
    (tmp_path / "steps").write_text("")
    result = runner.invoke(app, ["plan", PICK, "--trace-expansions", str(tmp_path / "steps")])
    assert result.exit_code == 2 and "--trace-expansions" in result.stderr
    assert "is a file, not a folder" in result.stderr


def test_a_failed_plan_writes_nothing(tmp_path: Path) -> None:
    out, plan, steps = tmp_path / "t.json", tmp_path / "p.plan", tmp_path / "steps"
    result = runner.invoke(app, ["plan", PICK, "--max-expansions", "1", "-o", str(out),
                                 "--plan-out", str(plan), "--trace-expansions", str(steps)])
    assert result.exit_code == 1
    assert list(tmp_path.iterdir()) == []


def test_the_plan_alone_can_go_to_stdout(tmp_path: Path) -> None:
    result = runner.invoke(app, ["plan", PICK, "-o", str(tmp_path / "t.json"), "--plan-out", "-"])
    assert result.exit_code == 0
    assert result.stdout.splitlines()[0] == "(moveto cube tau_cube)"


def test_the_old_spelling_of_output_still_works(tmp_path: Path) -> None:
    out = tmp_path / "t.json"
    result = runner.invoke(app, ["plan", PICK, "--out", str(out)])
    assert result.exit_code == 0 and out.exists()
    assert "--out " not in runner.invoke(app, ["plan", "--help"]).stdout


def test_a_link_is_written_through_and_a_pipe_is_not_replaced(tmp_path: Path) -> None:
    import threading

    real = tmp_path / "real.pddl"
    real.write_text("old")
    link = tmp_path / "link.pddl"
    link.symlink_to(real)
    result = runner.invoke(app, ["generate", "gripper", "-o", str(link)])
    assert result.exit_code == 0 and link.is_symlink()
    assert real.read_text().startswith("(define")

    pipe = tmp_path / "pipe"
    os.mkfifo(pipe)
    received: list[bytes] = []
    reader = threading.Thread(target=lambda: received.append(pipe.read_bytes()))
    reader.start()
    result = runner.invoke(app, ["generate", "gripper", "-o", str(pipe)])
    reader.join()
    assert result.exit_code == 0 and stat.S_ISFIFO(pipe.stat().st_mode)
    assert received[0].startswith(b"(define")


@pytest.mark.parametrize("command", [
    ["plan", "{domain}", "-o", "{domain}"],
    ["plan", "{domain}", "--plan-out", "{link}"],
    ["run", "{domain}", "-q", "--trace", "{domain}"],
    ["run", "{link}", "-q", "--plan-out", "{domain}"],
    ["sweep", "{domain}", "--seeds", "0:1", "--rates", "0", "-q", "-o", "{domain}"],
])
def test_an_output_that_is_an_input_is_refused_before_any_work(
        tmp_path: Path, command: list[str]) -> None:
    """Compared by device and inode: a link to the input is the input too."""
    domain = tmp_path / "pp.bt"
    domain.write_text(Path(PICK).read_text())
    before = domain.read_bytes()
    (tmp_path / "link.bt").symlink_to(domain)
    args = [a.format(domain=domain, link=tmp_path / "link.bt") for a in command]
    result = runner.invoke(app, args)
    assert result.exit_code == 2, result.output
    assert "is the input file" in result.output and "Traceback" not in result.output
    assert domain.read_bytes() == before


def test_an_exported_tree_cannot_overwrite_the_tree_it_reads(tmp_path: Path) -> None:
    tree = tmp_path / "t.json"
    assert runner.invoke(app, ["plan", PICK, "-o", str(tree)]).exit_code == 0
    before = tree.read_bytes()
    result = runner.invoke(app, ["export", "json", str(tree), "-o", str(tree)])
    assert result.exit_code == 2 and "is the input file" in result.output
    assert tree.read_bytes() == before


def test_dev_stdout_redirected_to_a_file_gets_the_plan(tmp_path: Path) -> None:
    """The shell's file behind /dev/stdout is written in place, not renamed over."""
    import subprocess
    import sys

    target = tmp_path / "o.txt"
    with target.open("w") as out:
        done = subprocess.run([sys.executable, "-m", "btplan", "run", PICK, "-q",
                               "--plan-out", "/dev/stdout"], stdout=out,
                              stderr=subprocess.PIPE, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert target.read_text().splitlines() == [
        "(moveto cube tau_cube)", "(pick cube)", "(moveto goal tau_goal)", "(place cube goal)"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o.txt"]


@pytest.mark.parametrize("alias", ["/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"])
def test_dev_stdout_counts_as_standard_output_in_the_one_stdout_rule(alias: str) -> None:
    result = runner.invoke(app, ["run", PICK, "-q", "--trace", "-", "--plan-out", alias])
    assert result.exit_code == 2
    assert "both write to standard output" in result.output


def test_a_legal_long_name_is_written_and_no_temporary_file_is_left(tmp_path: Path) -> None:
    """A name of 250 bytes is legal; the temporary name beside it must fit too."""
    target = tmp_path / ("x" * 245 + ".json")
    result = runner.invoke(app, ["plan", PICK, "-o", str(target), "-q"])
    assert result.exit_code == 0, result.output
    assert [p.name for p in tmp_path.iterdir()] == [target.name]


def test_a_trace_that_fills_the_disk_stops_the_run_at_a_line_boundary(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """The fourth line gets half written, then the disk is full: the torn half is cut
    away, the run stops at the next tick with its summary, and the command exits 2
    naming the flag and the path."""
    import errno

    trace = tmp_path / "tr.jsonl"
    real_write = os.write
    lines = {"n": 0}

    def full_disk(fd: int, data: bytes | memoryview) -> int:
        if os.path.realpath(f"/proc/self/fd/{fd}") != str(trace):
            return real_write(fd, data)
        lines["n"] += 1
        if lines["n"] == 4:
            real_write(fd, bytes(data[: len(data) // 2]))
        if lines["n"] >= 4:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real_write(fd, data)

    monkeypatch.setattr(os, "write", full_disk)
    result = runner.invoke(app, ["run", PICK, "-q", "--trace", str(trace)])
    assert result.exit_code == 2, result.output
    assert f"--trace {trace}: cannot write: No space left on device" in result.output
    assert "btplan run" in result.output and "Traceback" not in result.output
    text = trace.read_text()
    assert text.endswith("\n") and len(text.splitlines()) == 3


@pytest.mark.parametrize("flag", ["--trace-expansions", "-o", "--plan-out"])
def test_a_loop_of_links_as_an_output_is_bad_input(tmp_path: Path, flag: str) -> None:
    (tmp_path / "a").symlink_to(tmp_path / "b")
    (tmp_path / "b").symlink_to(tmp_path / "a")
    result = runner.invoke(app, ["plan", PICK, flag, str(tmp_path / "a")])
    assert result.exit_code == 2 and "is a loop of symbolic links" in result.output


def test_a_dangling_link_as_the_expansion_folder_is_bad_input(tmp_path: Path) -> None:
    (tmp_path / "steps").symlink_to(tmp_path / "missing" / "steps")
    result = runner.invoke(app, ["plan", PICK, "-o", str(tmp_path / "t.json"),
                                 "--trace-expansions", str(tmp_path / "steps")])
    assert result.exit_code == 2
    assert "is a link to a folder that does not exist" in result.output
    assert not (tmp_path / "t.json").exists()


def test_a_trace_pipe_without_a_reader_does_not_hold_up_a_stop(tmp_path: Path) -> None:
    """open() of a named pipe waits for a reader through every signal; the trace waits in
    short looks instead, and a stop request (SIGTERM) ends the wait."""
    from btplan.cli.outputs import LineStream
    from btplan.errors import Interrupted

    pipe = tmp_path / "trace.fifo"
    os.mkfifo(pipe)
    asked: list[bool] = []

    def stop() -> bool:
        asked.append(True)
        return len(asked) >= 3

    with pytest.raises(Interrupted, match="waiting for a reader"):
        LineStream(str(pipe), stop).__enter__()
    assert len(asked) == 3


def test_a_trace_pipe_with_a_reader_gets_every_line(tmp_path: Path) -> None:
    import threading

    from btplan.cli.outputs import LineStream

    pipe = tmp_path / "trace.fifo"
    os.mkfifo(pipe)
    got: list[str] = []
    reader = threading.Thread(target=lambda: got.extend(pipe.read_text().splitlines()))
    reader.start()
    with LineStream(str(pipe), lambda: False) as stream:
        stream.write_line('{"tick": 1}')
        stream.write_line('{"tick": 2}')
    reader.join()
    assert got == ['{"tick": 1}', '{"tick": 2}']


def test_a_full_disk_when_the_tree_is_written_is_exit_2_and_keeps_the_old_file(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import errno

    import btplan.io

    tree = tmp_path / "t.json"
    tree.write_text("the old tree\n")

    def full_disk(path: str, chunks: object) -> None:
        raise OSError(errno.ENOSPC, "No space left on device")

    # every file output goes through it (the tree as it is made, the others whole)
    monkeypatch.setattr(btplan.io, "write_chunks_atomic", full_disk)
    result = runner.invoke(app, ["plan", PICK, "-q", "-o", str(tree)])
    assert result.exit_code == 2, result.output
    assert "No space left on device; nothing was replaced" in result.output
    assert tree.read_text() == "the old tree\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.json"]


def test_the_expansion_folder_may_not_overwrite_an_input_or_an_output(tmp_path: Path) -> None:
    steps = tmp_path / "steps"
    steps.mkdir()
    domain = steps / "expansion_001.json"
    domain.write_text(Path(PICK).read_text())
    result = runner.invoke(app, ["plan", str(domain), "-q", "--trace-expansions", str(steps)])
    assert result.exit_code == 2 and "would overwrite" in result.output
    other = runner.invoke(app, ["plan", PICK, "-q", "-o", str(steps / "expansion_002.dot"),
                                "--trace-expansions", str(steps)])
    assert other.exit_code == 2 and "would overwrite" in other.output


def test_one_sigterm_ends_a_plan_whose_input_pipe_has_no_writer(tmp_path: Path) -> None:
    """open() of a named pipe blocks until a writer comes, and Python retries it after
    every signal handler; while inputs are read, the handler ends the reading instead."""
    import signal
    import subprocess
    import sys
    import time

    pipe = tmp_path / "domain.fifo"
    os.mkfifo(pipe)
    planning = subprocess.Popen([sys.executable, "-m", "btplan", "plan", str(pipe)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5)  # started, and blocked in open()
    planning.send_signal(signal.SIGTERM)
    try:
        _, err = planning.communicate(timeout=20)
    finally:
        if planning.poll() is None:
            planning.kill()
    # 143 and its message once btplan has started; -15 (the default action) before
    assert planning.returncode in (143, -signal.SIGTERM), err
    if planning.returncode == 143:
        assert "interrupted while reading the input" in err and "Traceback" not in err
