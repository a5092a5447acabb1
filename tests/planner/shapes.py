"""Tree shapes as nested tuples, easy to compare, where the shipped domains live, and small
generated tasks and atoms written as text."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from btplan.bt import Action, Condition, Fallback, Node, Sequence
from btplan.bt.decorators import Inverter
from btplan.lang import load as load_paths
from btplan.lang.generators import generate
from btplan.model import Atom, Task

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


def shape(node: Node) -> Any:
    """('?', ...) for Fallback, ('->', ...) for Sequence, 'pred(args)' or '[Act(args)]'."""
    if isinstance(node, Fallback):
        return ("?", *[shape(c) for c in node.children])
    if isinstance(node, Sequence):
        return ("->", *[shape(c) for c in node.children])
    if isinstance(node, Inverter):
        return ("not", shape(node.children[0]))
    if isinstance(node, Action):
        return f"[{node.name}]"
    if isinstance(node, Condition):
        return node.name
    raise AssertionError(f"unexpected node {node!r}")


def generated(tmp_path: Path, name: str, seed: int, **size: int) -> Task:
    """A generated PDDL problem of domain `name`, written to `tmp_path` and loaded."""
    domain, problem = generate(name, seed=seed, **size)
    (tmp_path / "domain.pddl").write_text(domain)
    (tmp_path / "problem.pddl").write_text(problem)
    return load_paths([str(tmp_path / "domain.pddl"), str(tmp_path / "problem.pddl")])


def atom(text: str) -> Atom:
    """`on(a, b)` as an Atom."""
    name, _, rest = text.partition("(")
    return Atom(name, tuple(a.strip() for a in rest.rstrip(")").split(",") if a.strip()))
