"""Every script in examples/ runs and says what its docstring promises."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"

EXPECTED = {
    "plan_tree.py": ["4 expansions", ("the robot would do: MoveTo(cube, tau_cube), Pick(cube), "
                                      "MoveTo(goal, tau_goal), Place(cube, goal)")],
    "run_disturbed.py": ["calm: reached=True ticks=7 expansions=4",
                         "disturbed: reached=True", "expansions=4",
                         "tick 5: undid Pick(cube)"],
    "export_xml.py": ['BTCPP_format="4"', "<ReactiveFallback", '<Place o="sphere" l="aside"/>',
                      '<blocks o="_" t="tau_goal"/>', '<Action ID="Place">'],
    "my_robot.py": ["reached: True", "disturbed: @"],
    "custom_agent.py": ["reached: True",
                        "grew at not blocks(_, tau_goal) with Place(sphere, aside)",
                        "grew at holding(sphere) with Pick(sphere)"],
}


def run_example(name: str, *args: str) -> str:
    done = subprocess.run([sys.executable, str(EXAMPLES / name), *args],
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout


WHOLE = {"my_robot.py"}
"""Complete programs a user starts from (a whole fake robot); the others show one use of
the API each, in under 40 lines."""


def test_every_example_is_listed_and_short() -> None:
    scripts = sorted(p.name for p in EXAMPLES.glob("*.py"))
    assert scripts == sorted(EXPECTED)
    for name in sorted(set(scripts) - WHOLE):
        assert len((EXAMPLES / name).read_text().splitlines()) < 40, name


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_example_runs_and_prints_what_it_promises(name: str) -> None:
    out = run_example(name)
    for words in EXPECTED[name]:
        assert words in out, (name, words)


def test_the_xml_example_writes_a_file(tmp_path: Path) -> None:
    target = tmp_path / "tree.xml"
    assert run_example("export_xml.py", str(target)) == ""
    assert target.read_text().startswith("<")
