"""Save, load and show trees: btplan JSON, BehaviorTree.CPP v4 XML, graphviz DOT, ASCII.

`dump(tree, fmt)` and `load_tree(text, fmt)` are what the commands call; each format
lives in its own module and heavy or optional work stays there.
"""

from __future__ import annotations

from btplan.bt.formats.btcpp import dump_xml, load_xml
from btplan.bt.formats.saved import dump_json, json_schema, load_json
from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError

DUMP_FORMATS = ("xml", "json")
LOAD_FORMATS = ("json", "xml")


def dump(tree: BehaviorTree, fmt: str, with_status: bool = False) -> str:
    """The tree as text in `fmt`; `with_status` adds each node's last status."""
    if fmt == "json":
        return dump_json(tree, with_status)
    if fmt == "xml":
        return dump_xml(tree)
    raise InputError(f"unknown tree format {fmt!r}", hint=f"use one of {', '.join(DUMP_FORMATS)}")


def load_tree(text: str, fmt: str, path: str = "<tree>") -> BehaviorTree:
    """Parse a saved tree; bad input raises InputError located in `path`."""
    if fmt == "json":
        return load_json(text, path)
    if fmt == "xml":
        return load_xml(text, path)
    raise InputError(f"cannot read trees in format {fmt!r}",
                     hint=f"use one of {', '.join(LOAD_FORMATS)}")


__all__ = ["DUMP_FORMATS", "LOAD_FORMATS", "dump", "json_schema", "load_tree"]
