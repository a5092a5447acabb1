"""A BT.CPP XML document as files put it together: trees, includes, models, version 3.

`read_document` parses the tree file, follows `<include path=...>` relative to the
including file (refusing cycles), reads each file's TreeNodesModel and then the
`--model` files, converts version 3 files with the renames of BT.CPP's own v3->v4
converter, and picks the tree to execute. Nothing here builds nodes (`btcpp_read`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from btplan.bt.blackboard import Blackboard
from btplan.bt.formats.btcpp_catalog import PRE_POST
from btplan.bt.formats.btcpp_models import ModelEntry, read_models
from btplan.bt.formats.locate import line_at
from btplan.bt.formats.xmlparse import Element, parse_xml
from btplan.bt.node import Node
from btplan.errors import InputError, Span
from btplan.io import STDIO, read_text

MAX_INCLUDES = 200
"""Most files one document may include, directly or not."""


def short(text: str, limit: int = 60) -> str:
    """A name from the input, cut so that a hostile one cannot flood a message."""
    return text if len(text) <= limit else text[: limit - 3] + "..."


@dataclass
class XmlDocument:
    """Everything a tree file and its includes declare."""

    trees: dict[str, Element] = field(default_factory=dict)
    models: dict[str, ModelEntry] = field(default_factory=dict)
    texts: dict[str, str] = field(default_factory=dict)
    main: str = ""
    warnings: list[str] = field(default_factory=list)
    version: int = 4

    def error(self, element: Element, message: str, hint: str | None = None) -> InputError:
        """An InputError at `element`'s file, line and column, quoting that line, for the
        caller to raise (reading stops there)."""
        return InputError(message, Span(element.path, element.line, element.column), hint,
                          line_at(self.texts.get(element.path, ""), element.line))

    def warn(self, element: Element, message: str) -> None:
        """Keep a `path:line:column: message` warning about something read but not obeyed;
        reading goes on."""
        self.warnings.append(f"{element.path}:{element.line}:{element.column}: {message}")


def _to_v4(element: Element, doc: XmlDocument) -> None:
    """Apply BT.CPP's v3->v4 renames to one node element and its children, in place."""
    tag, attrs = element.tag, element.attrs
    if tag == "SequenceStar" or (tag == "Control" and attrs.get("ID") == "SequenceStar"):
        element.tag = "SequenceWithMemory" if tag == "SequenceStar" else tag
        if tag == "Control":
            attrs["ID"] = "SequenceWithMemory"
    elif tag == "RetryUntilSuccesful":
        element.tag = "RetryUntilSuccessful"
    elif tag == "SubTreePlus":
        element.tag = "SubTree"
        element.attrs = {("_autoremap" if k == "__autoremap" else k): v for k, v in attrs.items()}
    elif tag == "SubTree":
        renamed: dict[str, str] = {}
        for key, value in attrs.items():
            if key == "__shared_blackboard":
                if value.strip().lower() in ("1", "true", "yes", "t"):
                    renamed["_autoremap"] = "1"
            elif key in ("ID", "name") or (value.startswith("{") and value.endswith("}")):
                renamed[key] = value
            else:
                renamed[key] = "{" + value + "}"
        element.attrs = renamed
    elif tag == "Parallel":
        names = {"success_threshold": "success_count", "failure_threshold": "failure_count"}
        element.attrs = {names.get(k, k): v for k, v in attrs.items()}
    for key in element.attrs:
        if key in PRE_POST:
            doc.warn(element, f"attribute {key} of a version 3 file is a script in version 4")
    for child in element.children:
        _to_v4(child, doc)


def _version(root: Element, doc: XmlDocument) -> int:
    raw = root.attrs.get("BTCPP_format")
    if raw is None:
        doc.warn(root, "no BTCPP_format: read as version 3 and written back as version 4")
        return 3
    if raw.strip() in ("3", "4"):
        return int(raw)
    raise doc.error(root, f"BTCPP_format={short(raw)!r} is not 3 or 4")


class _Loader:
    def __init__(self, doc: XmlDocument, load: Callable[[str], str]) -> None:
        self.doc = doc
        self.load = load
        self.seen: set[str] = set()
        self.file_models: dict[str, ModelEntry] = {}

    def file(self, text: str, path: str, chain: tuple[str, ...]) -> Element:
        doc = self.doc
        doc.texts[path] = text
        root = parse_xml(text, path)
        if root.tag != "root":
            raise doc.error(root, f"expected <root>, found <{short(root.tag)}>",
                            "a BT.CPP file starts with <root BTCPP_format=\"4\">")
        version = _version(root, doc)
        if not chain:
            doc.version = version
        for element in root.children:
            if element.tag == "BehaviorTree":
                if version == 3:
                    for child in element.children:
                        _to_v4(child, doc)
                self.tree(element)
            elif element.tag == "TreeNodesModel":
                entries, _ = read_models(element)
                for entry in entries:
                    entry.origin = "file"
                    self.file_models.setdefault(entry.ident, entry)
            elif element.tag == "include":
                self.include(element, path, chain)
            else:
                doc.warn(element, f"<{short(element.tag)}> is not part of a BT.CPP file; ignored")
        return root

    def tree(self, element: Element) -> None:
        doc = self.doc
        ident = element.attrs.get("ID")
        if ident is None:
            ident = "MainTree"
            element.attrs = {"ID": ident, **element.attrs}
            doc.warn(element, "a <BehaviorTree> without ID is read as ID=\"MainTree\"")
        if ident in doc.trees:
            first = doc.trees[ident]
            raise doc.error(element, f"a second <BehaviorTree ID=\"{short(ident)}\">",
                            f"the first is at {first.path}:{first.line}")
        doc.trees[ident] = element

    def include(self, element: Element, path: str, chain: tuple[str, ...]) -> None:
        doc = self.doc
        if "ros_pkg" in element.attrs:
            raise doc.error(element, "<include ros_pkg=...> needs ROS to find the package",
                            "give the file's path relative to this file instead")
        target = element.attrs.get("path")
        if not target:
            raise doc.error(element, "<include> needs a path attribute")
        base = Path.cwd() if path in (STDIO, "<tree>") else Path(path).parent
        resolved = (base / target).resolve()
        name = str(base / target) if not Path(target).is_absolute() else target
        here = str(Path(path).resolve()) if path not in (STDIO, "<tree>") else path
        if str(resolved) in chain + (here,):
            raise doc.error(element, f"including {short(target)!r} makes a cycle",
                            " -> ".join(Path(p).name for p in (*chain, here, str(resolved))))
        if str(resolved) in self.seen:
            return
        if len(self.seen) >= MAX_INCLUDES:
            raise doc.error(element, f"more than {MAX_INCLUDES} included files")
        self.seen.add(str(resolved))
        try:
            text = self.load(str(resolved))
        except InputError as error:
            raise doc.error(element, f"cannot include {short(target)!r}: {error.message}") from None
        self.file(text, name, (*chain, here))


def _model_file(text: str, path: str, doc: XmlDocument) -> list[ModelEntry]:
    doc.texts[path] = text
    root = parse_xml(text, path)
    found = [root] if root.tag == "TreeNodesModel" else [
        e for e in root.children if e.tag == "TreeNodesModel"]
    if not found:
        raise doc.error(root, "no <TreeNodesModel> in this model file",
                        "give a Groot2 palette or a tree file that declares its nodes")
    entries: list[ModelEntry] = []
    for models in found:
        entries.extend(read_models(models)[0])
    return entries


def read_document(text: str, path: str, models: Sequence[tuple[str, str]] = (),
                  tree_id: str | None = None,
                  load: Callable[[str], str] = read_text) -> XmlDocument:
    """Parse a tree file with its includes and model files, and choose the main tree.

    `models` are (text, path) pairs of `--model` files, consulted after the file's own
    TreeNodesModel; `tree_id` overrides `main_tree_to_execute`.
    """
    doc = XmlDocument()
    loader = _Loader(doc, load)
    here = str(Path(path).resolve()) if path not in (STDIO, "<tree>") else path
    loader.seen.add(here)
    root = loader.file(text, path, ())
    doc.models.update(loader.file_models)
    for model_text, model_path in models:
        for entry in _model_file(model_text, model_path, doc):
            if entry.ident not in doc.models:
                entry.origin = "model"
                doc.models[entry.ident] = entry
    if not doc.trees:
        raise doc.error(root, "no <BehaviorTree> in this file")
    given = tree_id or root.attrs.get("main_tree_to_execute")
    if given:
        if given not in doc.trees:
            raise doc.error(root, f"no <BehaviorTree ID=\"{short(given)}\"> to execute",
                            "choose one of: " + ", ".join(short(t) for t in doc.trees))
        doc.main = given
    elif len(doc.trees) == 1:
        doc.main = next(iter(doc.trees))
    else:
        uncalled = [t for t in doc.trees if t not in _called(doc)]
        if len(uncalled) != 1:
            raise doc.error(root, "several trees and no main_tree_to_execute",
                            "choose one with --tree: " + ", ".join(short(t) for t in doc.trees))
        doc.main = uncalled[0]
        doc.warn(root, f"no main_tree_to_execute: executing {short(doc.main)}, the only "
                 "tree no SubTree calls")
    return doc


def _called(doc: XmlDocument) -> set[str]:
    """IDs of the trees some SubTree calls."""
    out: set[str] = set()
    stack = list(doc.trees.values())
    while stack:
        element = stack.pop()
        stack.extend(element.children)
        if element.tag == "SubTree" and "ID" in element.attrs:
            out.add(element.attrs["ID"])
    return out


__all__ = ["XmlDocument", "read_document", "short"]


@dataclass
class ImportedTrees:
    """What the export needs to write an imported document back node for node."""

    doc: XmlDocument
    roots: dict[str, Node] = field(default_factory=dict)
    board: Blackboard = field(default_factory=Blackboard)
    used: set[str] = field(default_factory=set)
