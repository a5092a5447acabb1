"""Property: whatever bytes a reader is given, the CLI ends in exit 0, 1 or 2 with clean
messages; never a traceback, never a hang.

Every reader is driven through the real command: .bt and PDDL through `check`, saved
JSON and BT.CPP XML trees through `export`, scenes through `run --sim pybullet`,
disturbance files and specs through `run`. Inputs are mutated copies of what btplan
ships (domains/, tests/golden/, plans exported from the domains, domains/scenes/) and
plain random bytes. Inputs stay under a few tens of KB and every reader is linear, so a
hang would show as a test that never ends; the `long` profile adds a deadline.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import pytest
from hostile import DOMAINS, GOLDEN, PICK_PLACE, YOUBOT, assert_clean, budget, invoke
from hypothesis import event, given
from hypothesis import strategies as st

from btplan.lang import load
from btplan.lang.generators import generate
from btplan.lang.writers import pddl_domain, pddl_problem

PIECES = [
    *(c.encode() for c in "(){}[]<>\"',:;=@#?-.\\/&!*+"),
    b"\n", b"\r", b"\t", b" ", b"\x00", b"\xff", b"\xc3", "é".encode(), "\u202e".encode(),
    b"\x1b[2J", b"not ", b"..", b"p=", b"nan", b"inf", b"-1", b"0", b"1e999", b"0.5",
    b"9" * 5000, b"(" * 150, b"[" * 150, b"{" * 150, b"(and " * 120, b"<Sequence>" * 150,
    b"x" * 3000, b"&e;", b'<!DOCTYPE root [<!ENTITY e "x">]>', b"</", b"/>", b"<!--", b"-->",
    b"true", b"false", b"null", b"{}", b"[]", b'"type": "Parallel"', b'"children": []',
    b'"success": 99', b'"attempts": 0', b"[[event]]", b"[[cube]]", b"[[region]]",
    b'name = "x"', b"when = \"near(x)\"", b"domain", b"problem", b"action", b"types",
    b"(:requirements :adl)", b"(:types a b - c)", b"\\u0000", b"\\ud800", b"\"\"\"", b"'''",
]
"""Fragments that reach the corners of every reader: brackets, quotes, nesting bombs,
numbers past float and int limits, control characters, entities, keywords."""


WORD = re.compile(rb"[A-Za-z_][A-Za-z0-9_\-]*|-?[0-9]+(?:\.[0-9]+)?")
EDITS = ["word", "word", "word", "line", "line", "cut", "insert", "insert", "duplicate", "byte",
         "end"]
"""Word swaps and line edits mostly keep the syntax, so the checks behind it are reached;
byte edits reach the lexers."""


@st.composite
def mutated(draw: st.DrawFn, seeds: list[bytes]) -> bytes:
    """A shipped input with a few edits: swap a word for another of the input, cut or
    repeat a line, insert a fragment, cut, repeat, overwrite or truncate bytes."""
    data = draw(st.sampled_from(seeds))
    for _ in range(draw(st.integers(1, 4))):
        at = draw(st.integers(0, len(data)))
        edit = draw(st.sampled_from(EDITS))
        words = list(WORD.finditer(data))
        lines = data.split(b"\n")
        if edit == "word" and words:
            target = words[draw(st.integers(0, len(words) - 1))]
            other = draw(st.sampled_from(sorted({m.group() for m in words})))
            data = data[:target.start()] + other + data[target.end():]
        elif edit == "line" and len(lines) > 1:
            index = draw(st.integers(0, len(lines) - 1))
            repeat = draw(st.booleans())
            lines[index:index + 1] = [lines[index]] * 2 if repeat else []
            data = b"\n".join(lines)
        elif edit == "cut":
            data = data[:at] + data[at + draw(st.integers(1, 60)):]
        elif edit == "insert":
            piece = draw(st.one_of(st.sampled_from(PIECES), st.binary(min_size=1, max_size=8)))
            data = data[:at] + piece + data[at:]
        elif edit == "duplicate":
            start = draw(st.integers(0, len(data)))
            data = data[:at] + data[start:start + draw(st.integers(1, 300))] + data[at:]
        elif edit == "byte":
            data = data[:at] + bytes([draw(st.integers(0, 255))]) + data[at + 1:]
        elif edit == "end":
            data = data[:at]
    return data


# --- what is mutated: copies of what btplan ships ----------------------------------------


@cache
def bt_seeds() -> list[bytes]:
    return [p.read_bytes() for p in sorted(DOMAINS.glob("*.bt"))]


@cache
def pddl_seeds() -> list[bytes]:
    """The shipped domains written as PDDL, and the generators' PDDL."""
    seeds = []
    for name in ("blocksworld", "gripper", "logistics", "planner_sussman"):
        task = load([str(DOMAINS / f"{name}.bt")])
        seeds.append((pddl_domain(task.domain) + "\n" + pddl_problem(task.problem)).encode())
    seeds.append("\n".join(generate("logistics", packages=2)).encode())
    return seeds


@cache
def planned(fmt: str) -> list[bytes]:
    """Trees planned for shipped domains and saved in `fmt`, and the golden tree."""
    trees = [(GOLDEN / f"bt_figure7.{fmt}").read_bytes()]
    for name in ("pick_place.bt", "logistics.bt", "planner_invert.bt"):
        result = invoke(["plan", str(DOMAINS / name), "--format", fmt])
        assert result.exit_code == 0, result.output
        trees.append(result.stdout.encode())
    return trees


@cache
def scenario_seeds() -> list[bytes]:
    return [b"# agents\nundo@5\nhelp:Pick(cube)@3\nclear:holding(cube)@10..12\n"
            b"set:free(tau_goal)@p=0.05\nfail:MoveTo@2, 4\nundo:Place@1..,p=0.5\n"]


@cache
def scene_seeds() -> list[bytes]:
    return [(DOMAINS / "scenes" / "youbot.toml").read_bytes()]


@dataclass(frozen=True)
class Reader:
    suffix: str
    seeds: Callable[[], list[bytes]]
    args: Callable[[str, str], list[str]]
    """The command for an input file, and an output format drawn by the test."""


READERS = {
    "bt": Reader(".bt", bt_seeds, lambda path, fmt: ["check", path]),
    "pddl": Reader(".pddl", pddl_seeds, lambda path, fmt: ["check", path]),
    "json": Reader(".json", lambda: planned("json"), lambda path, fmt: ["export", fmt, path]),
    "xml": Reader(".xml", lambda: planned("xml"), lambda path, fmt: ["export", fmt, path]),
    "scenario": Reader(".dist", scenario_seeds, lambda path, fmt: [
        "run", PICK_PLACE, "--scenario", path, "--max-ticks", "30", "--quiet"]),
    "scene": Reader(".toml", scene_seeds, lambda path, fmt: [
        "run", YOUBOT, "--sim", "pybullet", "--scenario", path, "--max-ticks", "1", "--quiet"]),
}
SHARE = {"scene": 0.5}
"""Opening a PyBullet world takes a moment; the scene reader gets fewer examples."""
FORMATS = st.sampled_from(["json", "dot", "ascii", "xml"])


@pytest.fixture(scope="module")
def workdir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("hostile")


def feed(workdir: Path, reader: str, data: bytes, fmt: str) -> None:
    spec = READERS[reader]
    path = workdir / f"input{spec.suffix}"
    path.write_bytes(data)
    result = invoke(spec.args(str(path), fmt))
    event(f"exit {result.exit_code}")  # the mix shows with --hypothesis-show-statistics
    assert_clean(result)


@pytest.mark.parametrize("reader", sorted(READERS))
def test_mutated_shipped_inputs(workdir: Path, reader: str) -> None:
    @budget(SHARE.get(reader, 1.0))
    @given(data=mutated(READERS[reader].seeds()), fmt=FORMATS)
    def check(data: bytes, fmt: str) -> None:
        feed(workdir, reader, data, fmt)

    check()


@pytest.mark.parametrize("reader", sorted(READERS))
def test_random_bytes(workdir: Path, reader: str) -> None:
    @budget(SHARE.get(reader, 1.0) / 2)
    @given(data=st.binary(max_size=2048), fmt=FORMATS)
    def check(data: bytes, fmt: str) -> None:
        feed(workdir, reader, data, fmt)

    check()


@budget(0.5)
@given(data=st.one_of(st.binary(max_size=512),
                      st.deferred(lambda: mutated(bt_seeds() + planned("json")))),
       command=st.sampled_from([["check", "-"], ["export", "dot", "-"]]))
def test_standard_input_is_sniffed_safely(data: bytes, command: list[str]) -> None:
    assert_clean(invoke(command, stdin=data))


SPEC_SEEDS = [line for seed in scenario_seeds() for line in seed.decode().splitlines()[1:]]


@budget()
@given(spec=st.one_of(
    st.text(max_size=80),
    mutated([s.encode() for s in SPEC_SEEDS]).map(lambda b: b.decode("utf-8", "replace")),
))
def test_disturbance_specs_on_the_command_line(spec: str) -> None:
    spec = spec.replace("\x00", "")  # a command line cannot hold NUL
    assert_clean(invoke(["run", PICK_PLACE, f"--disturb={spec}", "--max-ticks", "30",
                         "--quiet"]))
