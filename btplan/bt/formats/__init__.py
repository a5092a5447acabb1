"""Save, load and show trees: btplan JSON, BehaviorTree.CPP v4 XML, graphviz DOT, ASCII.

`dump(tree, fmt)` and `load_tree(text, fmt)` are what the commands call; each format
lives in its own module and heavy or optional work stays there. A format's module is
imported when that format is used: BT.CPP's reader and the pydantic models of the
JSON reader are large, and `btplan plan` only writes one format.
"""

from __future__ import annotations

from collections.abc import Sequence

from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError

DUMP_FORMATS = ("xml", "dot", "json", "ascii")
LOAD_FORMATS = ("json", "xml")


def dump(tree: BehaviorTree, fmt: str, with_status: bool = False) -> str:
    """The tree as text in `fmt` (xml, dot, json, ascii).

    `with_status` adds each node's last status (json) or colours by it (dot, ascii);
    BT.CPP XML has no place for statuses and ignores it.
    """
    if fmt == "json":
        from btplan.bt.formats.saved_out import dump_json

        return dump_json(tree, with_status)
    if fmt == "xml":
        from btplan.bt.formats.btcpp import dump_xml

        return dump_xml(tree)
    statuses = None
    if with_status:
        from btplan.bt.trace import last_statuses

        statuses = last_statuses(tree.root)
    if fmt == "dot":
        from btplan.bt.formats.dot import dump_dot

        return dump_dot(tree, statuses)
    if fmt == "ascii":
        from btplan.bt.formats.text import dump_ascii

        return dump_ascii(tree, statuses)
    raise InputError(f"unknown tree format {fmt!r}", hint=f"use one of {', '.join(DUMP_FORMATS)}")


def load_tree(text: str, fmt: str, path: str = "<tree>",
              models: Sequence[tuple[str, str]] = (), tree_id: str | None = None,
              strict: bool = False) -> BehaviorTree:
    """Parse a saved tree; bad input raises InputError located in `path`.

    `models`, `tree_id` and `strict` apply to BT.CPP XML (see `load_xml`).
    """
    if fmt == "json":
        if models or tree_id or strict:
            raise InputError("--model, --tree and --strict apply to BT.CPP XML trees",
                             hint="a JSON tree holds one tree and declares its nodes")
        from btplan.bt.formats.saved import load_json

        return load_json(text, path)
    if fmt == "xml":
        from btplan.bt.formats.btcpp import load_xml

        return load_xml(text, path, models, tree_id, strict)
    raise InputError(f"cannot read trees in format {fmt!r}",
                     hint=f"use one of {', '.join(LOAD_FORMATS)}")


def json_schema() -> str:
    """The JSON schema of saved trees (`btplan export json --schema`)."""
    from btplan.bt.formats.saved import json_schema as schema

    return schema()


__all__ = ["DUMP_FORMATS", "LOAD_FORMATS", "dump", "json_schema", "load_tree"]
