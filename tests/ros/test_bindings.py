"""The binding file is checked before anything starts: each mistake is bad input at its
table's line, naming what is wrong (`btplan check DOMAIN --ros FILE`)."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

import btplan
from btplan.cli import app
from btplan.errors import InputError
from btplan.ros.bindings import load_bindings
from btplan.ros.expressions import Expression, ExpressionError

ROOT = Path(__file__).resolve().parents[2]
DOMAIN = ROOT / "domains" / "pick_place_obstacle.bt"
GOOD = (ROOT / "examples" / "ros" / "example2.toml").read_text()
TASK = btplan.load(str(DOMAIN))


def error_of(text: str) -> str:
    with pytest.raises(InputError) as caught:
        load_bindings("b.toml", text, TASK.domain)
    error = caught.value
    assert error.span is not None and error.span.path == "b.toml"
    return f"{error.span.line}: {error}"


def test_the_example_bindings_check() -> None:
    bindings = load_bindings("b.toml", GOOD, TASK.domain)
    assert set(bindings.actions) == {"MoveTo", "Pick", "Place", "Drop"}
    assert bindings.goals["Place"]["nested_field.int16_value"]({"id": {"goal": 3},
                                                                "o": "cube", "l": "goal"}) == 3


@pytest.mark.parametrize(("change", "said"), [
    (("[actions.Drop]", "[actions.Dorp]"), "the domain has no action 'Dorp'"),
    (("[conditions.blocks]", "[conditions.blocked]"), "no predicate 'blocked'"),
    (("test_msgs/action/NestedMessage\"\nserver = \"/robot/pick\"",
      "test_msgs/action/Nested\"\nserver = \"/robot/pick\""), "has no type 'Nested'"),
    (("nested_field.int32_value\" = \"id[o]\" }\n\n[actions.Place]",
      "nested_field.int99_value\" = \"id[o]\" }\n\n[actions.Place]"), "no field 'nested_field.int99_value'"),
    (("when = \"msg.data == o\"", "when = \"msg.datum == o\""), "no field 'datum'"),
    (("when = \"msg.data == o\"", "when = \"msg.data == x\""), "unknown name 'x'"),
    (("when = \"msg.data == o\"", "when = \"__import__('os')\""), "only abs"),
    (("stale_after = 2.0\n\n[conditions.hand_empty]", "stale_after = -1\n\n[conditions.hand_empty]"),
     "greater than 0"),
])
def test_each_mistake_is_named_at_its_table(change: tuple[str, str], said: str) -> None:
    old, new = change
    assert old in GOOD
    message = error_of(GOOD.replace(old, new, 1))
    assert said in message


def test_a_condition_an_action_changes_must_be_bound() -> None:
    start = GOOD.index("[conditions.blocks]")
    assert "no binding for the condition 'blocks'" in error_of(GOOD[:start])


def test_expressions_allow_only_the_binding_language() -> None:
    assert Expression("hypot(msg.x - x[l], 0) < 1", {"x", "l", "msg"}, {"x"})(
        {"x": {"a": 1.0}, "l": "a", "msg": type("M", (), {"x": 1.5})()}) is True
    for bad in ("msg.__class__", "(lambda: 1)()", "open('f')", "[i for i in l]"):
        with pytest.raises(ExpressionError):
            Expression(bad, {"l", "msg"})


def test_check_reads_the_bindings_and_says_which_rclpy_runs(tmp_path: Path) -> None:
    runner = CliRunner()
    good = runner.invoke(app, ["check", str(DOMAIN), "--ros",
                               str(ROOT / "examples" / "ros" / "example2.toml")])
    assert good.exit_code == 0, good.output
    assert "4 actions and 5 conditions bound (rclpy" in good.output
    bad = tmp_path / "bad.toml"
    bad.write_text(GOOD.replace("[actions.Drop]", "[actions.Dorp]"))
    result = runner.invoke(app, ["check", str(DOMAIN), "--ros", str(bad)])
    assert result.exit_code == 2 and f"{bad}:" in result.output and "'Drop'" in result.output
