"""The `btplan export` command: convert a saved tree (JSON or BT.CPP XML) to another format."""

from __future__ import annotations

from enum import Enum
from pathlib import Path
from typing import Annotated

import typer

from btplan.cli.console import escape
from btplan.cli.outputs import STDIO, Output, check_outputs, write_atomic
from btplan.cli.typer_app import app, guarded, stderr
from btplan.errors import InputError, Span
from btplan.io import read_text


class Format(str, Enum):
    """What `btplan export` converts a saved tree to: BehaviorTree.CPP XML, Graphviz dot,
    btplan's JSON, or a text drawing for the terminal."""
    xml = "xml"
    dot = "dot"
    json = "json"
    ascii = "ascii"


def input_format(path: str, text: str) -> str:
    """json or xml, from the file extension or else from the first character."""
    suffix = Path(path).suffix.lower() if path != STDIO else ""
    if suffix in (".json", ".xml"):
        return suffix[1:]
    first = text.lstrip()[:1]
    if first == "{":
        return "json"
    if first == "<":
        return "xml"
    raise InputError("cannot tell whether this tree is JSON or XML", Span(path, 1, 1),
                     hint="save it as .json or .xml")


EXAMPLES = """Examples:

  btplan export xml tree.json -o tree.xml            # BT.CPP v4, for Groot2
  btplan export dot tree.xml | dot -Tsvg > tree.svg
  btplan export ascii tree.json --status
  btplan export json --schema
"""


@app.command(epilog=EXAMPLES)
@guarded
def export(
    fmt: Annotated[Format, typer.Argument(metavar="FORMAT", help="xml, dot, json or ascii.")],
    tree: Annotated[str | None, typer.Argument(
        metavar="TREE", help="A saved tree (.json or BT.CPP .xml); '-' reads standard input.",
        show_default=False)] = None,
    out: Annotated[str, typer.Option(
        "-o", "--output", metavar="FILE", help="Write to FILE ('-': standard output).")] = STDIO,
    out_alias: Annotated[str | None, typer.Option("--out", hidden=True)] = None,
    schema: Annotated[bool, typer.Option(
        "--schema", help="Print the JSON schema of saved trees instead (json only).")] = False,
    status: Annotated[bool, typer.Option(
        "--status", help="Keep (json) or colour by (dot, ascii) the statuses saved in TREE.")
                      ] = False,
    model: Annotated[list[str] | None, typer.Option(
        "--model", metavar="FILE", help="XML with a TreeNodesModel (e.g. a Groot2 palette) "
        "declaring custom nodes; repeatable.")] = None,
    tree_id: Annotated[str | None, typer.Option(
        "--tree", metavar="ID", help="The BehaviorTree to execute (default: "
        "main_tree_to_execute, or the only tree).")] = None,
    strict: Annotated[bool, typer.Option(
        "--strict", help="Refuse custom nodes that no model declares instead of inferring "
        "them from their shape.")] = False,
) -> None:
    """Convert a saved tree: BT.CPP v4 XML, graphviz DOT, btplan JSON or a text view."""
    from btplan.bt.formats import dump, json_schema, load_tree  # only this command needs them

    out = out_alias if out_alias is not None else out
    check_outputs(Output("-o/--output", out),
                  inputs=[*([tree] if tree else []), *(model or [])])
    if schema:
        if fmt is not Format.json:
            raise InputError("--schema describes the JSON format", hint="use: export json --schema")
        write_atomic(out, json_schema())
        return
    if tree is None:
        raise InputError("missing TREE: a saved tree file, or '-' for standard input")
    text = read_text(tree)
    models = [(read_text(path), path) for path in model or []]
    loaded = load_tree(text, input_format(tree, text), tree, models, tree_id, strict)
    if loaded.imported is not None:
        for warning in loaded.imported.doc.warnings:
            stderr.print(f"[yellow]warning:[/] {escape(warning)}")
    write_atomic(out, dump(loaded, fmt.value, with_status=status))
