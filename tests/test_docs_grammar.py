"""The examples of the grammar reference are real `.bt` and PDDL.

docs/reference/grammar.md shows each construct as a piece of one small domain, in
`text` blocks (which test_docs_examples.py does not run). Here every block is read: a
whole unit is parsed, the domain's and the problem's parts are put together into one
file that must check and plan, and so must the PDDL version of the same domain.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from btplan.lang import parse_bt

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "reference" / "grammar.md"
BLOCK = re.compile(r"^```text\n(.*?)^```", re.MULTILINE | re.DOTALL)

DOMAIN_PARTS = ("types", "constants", "predicates", "action")
PROBLEM_PARTS = ("objects", "init", "goal")
UNITS = ("domain", "problem")


def first_word(block: str) -> str:
    """The block's first word after its comments: what kind of piece it is."""
    for line in block.splitlines():
        code = line.split("#")[0].strip()
        if code:
            return re.split(r"[\s({]", code, maxsplit=1)[0] or code[:7]
    return ""


def pieces() -> dict[str, list[str]]:
    found: dict[str, list[str]] = {"unit": [], "domain": [], "problem": [], "pddl": []}
    for block in BLOCK.findall(PAGE.read_text()):
        word = first_word(block)
        if word in UNITS:
            found["unit"].append(block)
        elif word in DOMAIN_PARTS:
            found["domain"].append(block)
        elif word in PROBLEM_PARTS:
            found["problem"].append(block)
        elif block.startswith("(define"):
            found["pddl"].append(block)
        else:
            pytest.fail(f"a text block of grammar.md that is no piece of a file:\n{block}")
    return found


def btplan(*arguments: str, cwd: Path) -> None:
    done = subprocess.run([sys.executable, "-m", "btplan", *arguments], cwd=cwd,
                          env=dict(os.environ), capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]


def test_every_piece_kind_is_shown() -> None:
    found = pieces()
    shown = {first_word(b) for kind in ("domain", "problem") for b in found[kind]}
    assert shown == {*DOMAIN_PARTS, *PROBLEM_PARTS}
    assert found["unit"] and len(found["pddl"]) == 1


def test_the_whole_units_parse() -> None:
    parsed = [parse_bt(block, "grammar.md") for block in pieces()["unit"]]
    assert any(p.domain is not None for p in parsed) and any(p.problems for p in parsed)


def test_the_pieces_make_a_domain_that_plans(tmp_path: Path) -> None:
    found = pieces()
    text = ("domain courier {\n" + "\n".join(found["domain"]) + "}\n"
            "problem deliver for courier {\n" + "\n".join(found["problem"]) + "}\n")
    (tmp_path / "courier.bt").write_text(text)
    btplan("check", "courier.bt", cwd=tmp_path)
    btplan("plan", "courier.bt", "-q", "-o", "tree.json", cwd=tmp_path)
    btplan("run", "courier.bt", "-q", cwd=tmp_path)


def test_the_pddl_example_plans(tmp_path: Path) -> None:
    (tmp_path / "courier.pddl").write_text(pieces()["pddl"][0])
    btplan("check", "courier.pddl", cwd=tmp_path)
    btplan("plan", "courier.pddl", "-q", "-o", "tree.json", cwd=tmp_path)
