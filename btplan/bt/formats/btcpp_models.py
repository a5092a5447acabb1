"""TreeNodesModel entries: what a custom node is (kind) and which ports it declares.

They come from the tree file, from files it includes, from `--model` files (a Groot2
palette or any XML with a TreeNodesModel), or are inferred from how a node is used. The
export writes them back, so Groot2 can show every node.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

from btplan.bt.formats.xmlparse import Element

KINDS = ("Action", "Condition", "Control", "Decorator", "SubTree")
PORT_TAGS = {"input_port": "input", "output_port": "output", "inout_port": "inout"}


@dataclass(frozen=True, slots=True)
class ModelPort:
    """One port a TreeNodesModel declares: direction, name, its attributes as written (kept
    so the export writes them back unchanged) and its description text."""
    direction: str  # input, output, inout
    name: str
    attrs: tuple[tuple[str, str], ...]  # as written: name, type, default, ...
    description: str = ""


@dataclass(slots=True)
class ModelEntry:
    """One custom node type; `inferred` when no model declared it."""

    kind: str
    ident: str
    ports: list[ModelPort] = field(default_factory=list)
    attrs: tuple[tuple[str, str], ...] = ()
    inferred: bool = False
    origin: str = ""  # "file", "model" or "inferred"

    def port_names(self) -> tuple[str, ...]:
        """The declared port names, in order: a node a model declares (not one inferred from
        use) may carry no other attribute."""
        return tuple(p.name for p in self.ports)


def read_models(models: Element) -> tuple[list[ModelEntry], list[Element]]:
    """The entries of one <TreeNodesModel>, and the elements that are not entries."""
    entries: list[ModelEntry] = []
    odd: list[Element] = []
    for element in models.children:
        ident = element.attrs.get("ID", "")
        if element.tag not in KINDS or not ident:
            odd.append(element)
            continue
        ports = [ModelPort(PORT_TAGS[p.tag], p.attrs.get("name", ""), tuple(p.attrs.items()),
                           p.text.strip())
                 for p in element.children if p.tag in PORT_TAGS and p.attrs.get("name")]
        entries.append(ModelEntry(element.tag, ident, ports, tuple(element.attrs.items())))
    return entries, odd


def _attrs(pairs: tuple[tuple[str, str], ...]) -> str:
    return "".join(f" {k}={quoteattr(v)}" for k, v in pairs)


def write_models(entries: list[ModelEntry], pad: str = "  ") -> list[str]:
    """The <TreeNodesModel> element, entries sorted by ID for stable output."""
    out = [f"{pad}<TreeNodesModel>"]
    for entry in sorted(entries, key=lambda e: e.ident):
        attrs = entry.attrs or (("ID", entry.ident),)
        if not entry.ports:
            out.append(f"{pad}  <{entry.kind}{_attrs(attrs)}/>")
            continue
        out.append(f"{pad}  <{entry.kind}{_attrs(attrs)}>")
        for port in entry.ports:
            tag = f"{port.direction}_port"
            if port.description:
                out.append(f"{pad}    <{tag}{_attrs(port.attrs)}>{escape(port.description)}"
                           f"</{tag}>")
            else:
                out.append(f"{pad}    <{tag}{_attrs(port.attrs)}/>")
        out.append(f"{pad}  </{entry.kind}>")
    out.append(f"{pad}</TreeNodesModel>")
    return out


__all__ = ["KINDS", "ModelEntry", "ModelPort", "read_models", "write_models"]
