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


CORPUS = Path(__file__).resolve().parents[1] / "bt" / "corpus"


def test_a_real_style_tree_with_a_palette_strict_and_a_chosen_tree() -> None:
    nav, palette = str(CORPUS / "nav_recovery.xml"), str(CORPUS / "nav_palette.xml")
    inferred = runner.invoke(app, ["export", "xml", nav])
    assert inferred.exit_code == 0
    assert "RecoveryNode is not declared; read as a control from its shape" in inferred.stderr
    strict = runner.invoke(app, ["export", "dot", nav, "--strict"])
    assert strict.exit_code == 2 and "unknown node <RecoveryNode>" in strict.stderr
    declared = runner.invoke(app, ["export", "dot", nav, "--strict", "--model", palette])
    assert declared.exit_code == 0 and declared.stderr == ""
    assert 'label="RecoveryNode NavigateRecovery"' in declared.stdout
    chosen = runner.invoke(app, ["export", "ascii", str(CORPUS / "groot_v3.xml"),
                                 "--tree", "Dock"])
    assert chosen.exit_code == 0 and chosen.stdout.startswith("→* Sequence")
    as_json = runner.invoke(app, ["export", "json", str(CORPUS / "scripts.xml")])
    assert as_json.exit_code == 2 and "cannot be saved in btplan's JSON format" in as_json.stderr


def test_random_bytes_give_a_clean_error_never_a_traceback(tmp_path: Path) -> None:
    import random

    rng = random.Random(7)
    for i in range(20):
        src = tmp_path / f"fuzz{i}.xml"
        head = b'<root BTCPP_format="4"><BehaviorTree ID="T">' if i % 2 else b""
        src.write_bytes(head + bytes(rng.randrange(256) for _ in range(rng.randint(0, 300))))
        result = runner.invoke(app, ["export", "dot", str(src)])
        assert result.exit_code == 2, (i, result.output)
        assert "Traceback" not in result.output and "error:" in result.stderr
