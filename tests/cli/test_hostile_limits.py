"""Each reader's limits, through the CLI: absurd depth and size exit 2 with a located
message, numbers past Python's own limits are input errors, and an error in a huge line
shows only a short excerpt around the caret (limits in btplan/limits.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from hostile import DOMAINS, GOLDEN, PICK_PLACE, YOUBOT, assert_clean, error_lines, invoke

from btplan.limits import (
    EXCERPT_WIDTH,
    MAX_INPUT_BYTES,
    MAX_MESSAGE,
    MAX_NESTING,
    MAX_TREE_DEPTH,
    MAX_TYPE_DEPTH,
    abridge,
    excerpt,
    shorten,
)

DEEP = 10_000
def saved_chain(depth: int) -> str:
    """A saved JSON tree `depth` nodes deep: Inverters down to one action."""
    node: dict[str, object] = {"type": "Action", "ident": "a"}
    for _ in range(depth - 1):
        node = {"type": "Inverter", "children": [node]}
    return json.dumps({"format": "btplan-tree", "version": 1, "root": node})


def deep_inputs() -> dict[str, tuple[str, str]]:
    """10,000 levels in each language: (file name, text)."""
    sequence = "<Sequence>" * DEEP + "<AlwaysSuccess/>" + "</Sequence>" * DEEP
    return {
        "json": ("deep.json", '{"format": "btplan-tree", "version": 1, "root": '
                 + '{"type": "Inverter", "children": [' * DEEP + '{"type": "Action", '
                 '"ident": "a"}' + "]}" * DEEP + "}"),
        "bt": ("deep.bt", "domain d { predicates { p(" + "(" * DEEP + ")" * DEEP + ") } }"),
        "pddl": ("deep.pddl", "(define (domain d) (:predicates (p)) (:action a :parameters () "
                 ":precondition " + "(and " * DEEP + "(p)" + ")" * DEEP + " :effect (p)))"),
        "xml": ("deep.xml", '<root BTCPP_format="4"><BehaviorTree ID="Main">' + sequence
                + "</BehaviorTree></root>"),
    }


def command(kind: str, path: Path) -> list[str]:
    if kind in ("json", "xml"):
        return ["export", "dot", str(path)]
    return ["check", str(path)]


@pytest.mark.parametrize("kind", ["json", "bt", "pddl", "xml"])
def test_ten_thousand_levels_of_nesting_exit_2(tmp_path: Path, kind: str) -> None:
    name, text = deep_inputs()[kind]
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    result = invoke(command(kind, path))
    assert_clean(result)
    assert result.exit_code == 2
    (message,) = error_lines(result)
    assert message.startswith(f"error: {path}:1:")
    assert "nested more than" in message or "deep" in message


def test_ten_thousand_levels_of_toml_arrays_exit_2(tmp_path: Path) -> None:
    scene = tmp_path / "deep.toml"
    scene.write_text("[world]\nbounds = " + "[" * DEEP + "]" * DEEP + "\n", encoding="utf-8")
    result = invoke(["run", YOUBOT, "--sim", "pybullet", "--scenario", str(scene), "--quiet"])
    assert_clean(result)
    assert result.exit_code == 2
    assert error_lines(result) == [
        f"error: {scene}:2:{10 + MAX_NESTING}: brackets nested more than {MAX_NESTING} levels "
        "deep (btplan reads no deeper; see 'Hostile input' in docs/reliability.md)"]


@pytest.mark.parametrize("fmt", ["json", "dot", "ascii", "xml"])
def test_a_tree_at_the_depth_limit_is_read_and_written(tmp_path: Path, fmt: str) -> None:
    """The limit leaves room for every later recursive step (export, schema, round trip)."""
    tree = tmp_path / "limit.json"
    tree.write_text(saved_chain(MAX_TREE_DEPTH), encoding="utf-8")
    result = invoke(["export", fmt, str(tree)])
    assert_clean(result)
    assert result.exit_code == 0, result.output
    tree.write_text(saved_chain(MAX_TREE_DEPTH + 1), encoding="utf-8")
    deeper = invoke(["export", fmt, str(tree)])
    assert deeper.exit_code == 2
    assert f"the tree is nested more than {MAX_TREE_DEPTH} nodes deep" in deeper.stderr


def test_an_input_larger_than_the_limit_is_refused_before_reading(tmp_path: Path) -> None:
    big = tmp_path / "big.bt"
    with big.open("wb") as handle:
        handle.truncate(MAX_INPUT_BYTES + 1)  # sparse: nothing is written to disk
    result = invoke(["check", str(big)])
    assert result.exit_code == 2
    assert error_lines(result) == [
        f"error: {big}:1:1: this input is larger than {MAX_INPUT_BYTES // 2**20} MiB, the most "
        "btplan reads (split it, or check that it is the file you meant)"]


def test_standard_input_is_read_up_to_the_limit_only() -> None:
    result = invoke(["check", "-"], stdin=b"#" * (MAX_INPUT_BYTES + 10))
    assert result.exit_code == 2
    assert "larger than" in result.stderr


def one_line_files() -> dict[str, tuple[str, str, list[str]]]:
    """A 30 KB line with a mistake in its middle, per reader: (name, text, command)."""
    pad = "x" * 15_000
    return {
        "bt": ("long.bt", f"domain d {{ predicates {{ {pad} ] {pad} }} }}", ["check"]),
        "pddl": ("long.pddl", f"(define (domain d) (:predicates ({pad}) ] ({pad})))", ["check"]),
        "json": ("long.json", '{"format": "btplan-tree", "version": 1, "name": "' + pad
                 + '", "root": {"type": "Nope"}, "pad": "' + pad + '"}', ["export", "dot"]),
        "xml": ("long.xml", f'<root BTCPP_format="4"><!-- {pad} --><Bad <!-- {pad} --></root>',
                ["export", "dot"]),
        "scenario": ("long.dist", f"undo@1 {pad} {pad}", ["run", PICK_PLACE, "--scenario"]),
    }


@pytest.mark.parametrize("kind", ["bt", "pddl", "json", "scenario", "xml"])
def test_an_error_in_a_huge_line_shows_a_short_excerpt(tmp_path: Path, kind: str) -> None:
    name, text, args = one_line_files()[kind]
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    result = invoke([*args, str(path)])
    assert_clean(result)
    assert result.exit_code == 2
    assert len(result.stderr) < 800, result.stderr
    lines = result.stderr.splitlines()
    shown, caret = lines[-2], lines[-1]
    assert shown.startswith("  ") and caret.strip() == "^"
    assert len(shown) <= 2 + EXCERPT_WIDTH + 6


def test_an_error_in_a_huge_scene_line_shows_a_short_excerpt(tmp_path: Path) -> None:
    scene = tmp_path / "long.toml"
    name = "n" * 30_000
    scene.write_text(f'[world]\nbounds = [0, 1, 0, 1]\n[[cube]]\nname = "{name}"\nat = "here"\n')
    result = invoke(["run", YOUBOT, "--sim", "pybullet", "--scenario", str(scene), "--quiet"])
    assert_clean(result)
    assert result.exit_code == 2
    assert len(result.stderr) < 800, result.stderr


def test_the_excerpt_keeps_the_caret_on_the_mistake() -> None:
    line = "a" * 500 + "!" + "b" * 500
    shown, column = excerpt(line, 501)
    assert shown[column - 1] == "!"
    assert shown.startswith("...") and shown.endswith("...")
    assert len(shown) == EXCERPT_WIDTH + 6
    assert excerpt("short (", 7) == ("short (", 7)
    start, column = excerpt("!" + "x" * 300, 1)
    assert column == 1 and start.startswith("!x") and start.endswith("...")
    end, column = excerpt("x" * 300 + "!", 301)
    assert end[column - 1] == "!" and end.endswith("!")


def test_the_excerpt_neutralises_terminal_controls() -> None:
    shown, column = excerpt("ab\x1b[2J\rcd!", 10)
    assert "\x1b" not in shown and "\r" not in shown
    assert shown[column - 1] == "!"


def test_echoed_values_are_shortened() -> None:
    assert shorten("x" * 1000) == "x" * 37 + "..."
    assert shorten("short") == "short"
    cut = abridge("section '" + "x" * 3000 + "' is not supported")
    assert len(cut) == MAX_MESSAGE and cut.endswith("' is not supported")
    assert abridge("short") == "short"


@pytest.mark.parametrize(("name", "text"), [
    ("section.pddl", "(define (domain d) (:" + "x" * 3000 + "))"),
    ("predicate.bt", "domain d { predicates { p } action A() { pre: " + "q" * 3000 + " } }"),
])
def test_a_message_quoting_a_huge_name_stays_short(tmp_path: Path, name: str, text: str) -> None:
    """Found by the property tests (long profile): a 3,000-character keyword was echoed."""
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    result = invoke(["check", str(path)])
    assert_clean(result)
    assert result.exit_code == 2
    assert len(result.stderr) < 2 * MAX_MESSAGE + 2 * EXCERPT_WIDTH + 200


@pytest.mark.parametrize(("name", "text"), [
    ("big.json", '{"format": "btplan-tree", "version": 1, "root": {"type": "Retry", '
                 '"attempts": ' + "9" * 5000 + ', "children": []}}'),
    ("big.dist", "undo@" + "9" * 5000),
])
def test_numbers_past_pythons_digit_limit_are_input_errors(tmp_path: Path, name: str,
                                                           text: str) -> None:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    args = ["export", "dot"] if name.endswith(".json") else ["run", PICK_PLACE, "--scenario"]
    result = invoke([*args, str(path)])
    assert_clean(result)
    assert result.exit_code == 2
    assert ":1:" in error_lines(result)[0]


@pytest.mark.parametrize("value", ["9" * 5000, "nan", "inf", "1e400", "-inf", "1e300"])
def test_scene_numbers_must_be_finite(tmp_path: Path, value: str) -> None:
    """1e300 once reached the world, where speed x tick duration overflowed in round()."""
    scene = tmp_path / "scene.toml"
    scene.write_text((DOMAINS / "scenes" / "youbot.toml").read_text(encoding="utf-8").replace(
        "tick_seconds = 0.1", f"tick_seconds = {value}").replace(
        "start = [0.0, 0.0, 0.0]", f"start = [{value}, 0.0, 0.0]"), encoding="utf-8")
    result = invoke(["run", YOUBOT, "--sim", "pybullet", "--scenario", str(scene), "--quiet"])
    assert_clean(result)
    assert result.exit_code == 2


@pytest.mark.parametrize("kind", ["billion laughs", "external", "internal"])
def test_xml_entities_are_never_expanded(tmp_path: Path, kind: str) -> None:
    secret = tmp_path / "secret.txt"
    secret.write_text("Secret", encoding="utf-8")
    if kind == "external":
        doctype = f'<!DOCTYPE root [<!ENTITY e SYSTEM "file://{secret}">]>'
    elif kind == "internal":
        doctype = '<!DOCTYPE root [<!ENTITY e "Secret">]>'
    else:
        doctype = ('<!DOCTYPE root [<!ENTITY a "aaaaaaaaaa">'
                   + "".join(f'<!ENTITY {chr(98 + i)} "{("&" + chr(97 + i) + ";") * 10}">'
                             for i in range(8)) + "]>")
    entity = "&i;" if kind == "billion laughs" else "&e;"
    tree = tmp_path / "entity.xml"
    tree.write_text(GOLDEN.joinpath("bt_figure7.xml").read_text(encoding="utf-8").replace(
        '<root BTCPP_format="4"', doctype + '<root BTCPP_format="4"', 1).replace(
        'name="', f'name="{entity}', 1), encoding="utf-8")
    result = invoke(["export", "dot", str(tree)])
    assert_clean(result)
    assert result.exit_code == 2
    assert "a DOCTYPE is not allowed" in error_lines(result)[0]
    # the excerpt may echo the declaration itself, never an expansion of it
    assert result.output.count("Secret") == (1 if kind == "internal" else 0)


def test_a_port_declared_twice_in_an_xml_model_is_read_cleanly(tmp_path: Path) -> None:
    """Found by the property tests (long profile): a KeyError once escaped the reader.

    Groot2 shows such a model, so the reader is forgiving too: the tree converts."""
    text = GOLDEN.joinpath("bt_figure7.xml").read_text(encoding="utf-8")
    port = '<input_port name="l" type="std::string"/>'
    tree = tmp_path / "twice.xml"
    tree.write_text(text.replace(port, port + port, 1), encoding="utf-8")
    result = invoke(["export", "json", str(tree)])
    assert_clean(result)
    assert result.exit_code == 0


def type_chain(n: int, language: str) -> str:
    """A domain whose types form one chain t0 < t1 < ... < t(n-1) < object."""
    if language == "pddl":
        types = " ".join(f"t{i} - t{i + 1}" for i in range(n - 1))
        return (f"(define (domain d) (:requirements :typing) (:types {types})"
                " (:predicates (p ?x - t0)))")
    lines = "\n".join(f"t{i} : t{i + 1}" for i in range(n - 1))
    return f"domain d {{ types {{ {lines}\nt{n - 1} }} predicates {{ p(x: t0) }} }}"


@pytest.mark.parametrize("language", ["bt", "pddl"])
def test_a_type_chain_deeper_than_the_limit_exits_2(tmp_path: Path, language: str) -> None:
    """A flat list of 2,000 types in one chain once took hours to check (a cubic walk)."""
    path = tmp_path / f"chain.{language}"
    path.write_text(type_chain(MAX_TYPE_DEPTH - 1, language), encoding="utf-8")
    assert invoke(["check", str(path)]).exit_code == 0  # with object, exactly the limit
    path.write_text(type_chain(MAX_TYPE_DEPTH, language), encoding="utf-8")
    assert invoke(["check", str(path)]).exit_code == 2
    path.write_text(type_chain(2000, language), encoding="utf-8")
    result = invoke(["check", str(path)])
    assert_clean(result)
    assert result.exit_code == 2
    assert f"the type hierarchy is more than {MAX_TYPE_DEPTH} levels deep" in result.stderr
