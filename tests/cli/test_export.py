"""`btplan export`: conversions between saved formats, the schema, and clean failures."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from btplan.cli import app

runner = CliRunner()
GOLDEN = Path(__file__).resolve().parents[1] / "golden"
FIGURE7_JSON = (GOLDEN / "bt_figure7.json").read_text(encoding="utf-8")
FIGURE7_XML = (GOLDEN / "bt_figure7.xml").read_text(encoding="utf-8")


def test_json_to_xml_gives_the_btcpp_document(tmp_path: Path) -> None:
    src = tmp_path / "tree.json"
    src.write_text(FIGURE7_JSON, encoding="utf-8")
    result = runner.invoke(app, ["export", "xml", str(src)])
    assert result.exit_code == 0, result.output
    assert result.stdout == FIGURE7_XML


def test_xml_back_to_json_through_a_file(tmp_path: Path) -> None:
    src, out = tmp_path / "tree.xml", tmp_path / "again.json"
    src.write_text(FIGURE7_XML, encoding="utf-8")
    result = runner.invoke(app, ["export", "json", str(src), "-o", str(out)])
    assert result.exit_code == 0 and result.stdout == ""
    assert out.read_text(encoding="utf-8") == FIGURE7_JSON


def test_standard_input_is_sniffed() -> None:
    result = runner.invoke(app, ["export", "dot", "-"], input=FIGURE7_XML)
    assert result.exit_code == 0
    assert result.stdout.startswith('digraph "Main" {') and 'label="?"' in result.stdout
    ascii_view = runner.invoke(app, ["export", "ascii", "-"], input=FIGURE7_JSON)
    assert "[MoveTo(cube, tau_cube)]" in ascii_view.stdout


def test_schema_is_printed_for_json() -> None:
    result = runner.invoke(app, ["export", "json", "--schema"])
    assert result.exit_code == 0
    assert json.loads(result.stdout)["title"] == "SavedTree"
    wrong = runner.invoke(app, ["export", "xml", "--schema"])
    assert wrong.exit_code == 2 and "--schema describes the JSON format" in wrong.stderr


def test_bad_tree_exits_2_with_place_and_caret_and_writes_nothing(tmp_path: Path) -> None:
    src, out = tmp_path / "tree.json", tmp_path / "out.xml"
    src.write_text(FIGURE7_JSON.replace('"ident": "Pick"', '"ident": 7'), encoding="utf-8")
    result = runner.invoke(app, ["export", "xml", str(src), "-o", str(out)])
    assert result.exit_code == 2
    first, line, caret = result.stderr.splitlines()[:3]
    assert first.startswith(f"error: {src}:") and "ident" in first
    assert '"ident": 7' in line and caret.strip() == "^"
    assert line.index("7") == caret.index("^")
    assert not out.exists()
    assert "Traceback" not in result.output


def test_missing_file_and_unknown_format_are_usage_errors(tmp_path: Path) -> None:
    missing = runner.invoke(app, ["export", "xml", str(tmp_path / "none.json")])
    assert missing.exit_code == 2 and "no such file" in missing.stderr
    unknown = runner.invoke(app, ["export", "png", "x.json"])
    assert unknown.exit_code == 2
    odd = tmp_path / "tree.txt"
    odd.write_text("tree", encoding="utf-8")
    sniff = runner.invoke(app, ["export", "xml", str(odd)])
    assert sniff.exit_code == 2 and "JSON or XML" in sniff.stderr
