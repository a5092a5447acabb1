"""Build btplan nodes from a BT.CPP XML document: built-ins, custom nodes, SubTrees.

Every built-in node of BT.CPP 4 becomes the engine node with its semantics; a custom
node is what its TreeNodesModel says, or, unless `strict`, what its shape suggests
(no child: an action; one: a decorator; more: a control), with one warning per ID.
Every node remembers its tag and attributes (`Origin`) so the export writes it back
as it was read. Each tree instance gets its own blackboard, remapped as BT.CPP does.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from difflib import get_close_matches

from btplan.bt.actions import (
    Constant,
    ScriptAction,
    ScriptCondition,
    SetBlackboard,
    Sleep,
    UnsetBlackboard,
    WasEntryUpdated,
)
from btplan.bt.blackboard import Blackboard, Ports, pointer
from btplan.bt.btcpp_composites import BtcppFallback, BtcppParallel, BtcppSequence
from btplan.bt.controls import (
    AsyncFallback,
    AsyncSequence,
    IfThenElse,
    ParallelAll,
    SequenceWithMemory,
    Switch,
    TryCatch,
    WhileDoElse,
)
from btplan.bt.custom import BoundAction, BoundCondition, Opaque
from btplan.bt.decorators import ForceFailure, ForceSuccess, Inverter, Retry, Timeout
from btplan.bt.formats.btcpp_catalog import BUILTINS, EXPLICIT_TAGS, PRE_POST, BuiltinSpec
from btplan.bt.formats.btcpp_files import ImportedTrees, XmlDocument, short
from btplan.bt.formats.btcpp_models import ModelEntry, ModelPort
from btplan.bt.formats.xmlparse import Element
from btplan.bt.guard import guard
from btplan.bt.leaves import Action, Condition
from btplan.bt.loops import (
    BoardRetry,
    Delay,
    KeepRunningUntilFailure,
    Loop,
    Precondition,
    Repeat,
    RunOnce,
    WhenUpdated,
)
from btplan.bt.node import Node, Origin
from btplan.bt.script import Script, ScriptSyntaxError
from btplan.bt.status import FAILURE, SUCCESS
from btplan.bt.subtree import SubTree
from btplan.bt.tree import BehaviorTree

_TAG = re.compile(r"[^\W\d][\w\-]*")
TICK_MS = 100
"""Milliseconds per tick when a BT.CPP time crosses to btplan (btplan acts at 10 Hz)."""
MAX_NODES = 200_000
"""Most nodes a document may expand to once every SubTree is instantiated."""
MAX_NESTING = 150
"""Deepest nesting of nodes, SubTrees expanded; the builder recurses once per level."""


def ticks(msec: int) -> int:
    """A BT.CPP time in milliseconds as whole ticks of TICK_MS, rounded up so that a short
    wait is not dropped: 150 ms is 2 ticks, 0 ms is none."""
    return math.ceil(msec / TICK_MS)


class _Builder:
    def __init__(self, doc: XmlDocument, strict: bool) -> None:
        self.doc = doc
        self.strict = strict
        self.out = ImportedTrees(doc)
        self.count = 0
        self.depth = 0

    # --- which ID is what ---------------------------------------------------------------

    def ident(self, element: Element) -> str:
        if element.tag in EXPLICIT_TAGS:
            ident = element.attrs.get("ID")
            if not ident:
                raise self.doc.error(element, f"<{element.tag}> needs an ID attribute")
            if not _TAG.fullmatch(ident):
                raise self.doc.error(element, f"ID={short(ident)!r} cannot be written as a tag",
                                     "BT.CPP's compact form needs a name made of letters, "
                                     "digits, '_' and '-'")
            return ident
        return element.tag

    def prescan(self) -> None:
        """Declare every undeclared custom ID once, from how it is used everywhere."""
        found: dict[str, tuple[Element, int, list[tuple[str, str]]]] = {}
        stack = [c for tree in reversed(self.doc.trees.values()) for c in reversed(tree.children)]
        while stack:  # depth first in document order, so strict mode names the first one
            element = stack.pop()
            stack.extend(reversed(element.children))
            ident = self.ident(element)
            if ident in BUILTINS or ident in self.doc.models:
                continue
            if self.strict:
                known = sorted(set(BUILTINS) | set(self.doc.models))
                near = get_close_matches(ident, known, n=1)
                raise self.doc.error(element, f"unknown node <{short(ident)}>",
                                     f"did you mean {near[0]!r}?" if near else
                                     "declare it in <TreeNodesModel> or give --model FILE")
            first, most, ports = found.get(ident, (element, 0, []))
            for key, value in element.attrs.items():
                if key not in ("name", "ID") and not key.startswith("_") and key not in dict(ports):
                    ports.append((key, value))
            explicit = element.tag in EXPLICIT_TAGS
            shape = -1 - EXPLICIT_TAGS.index(element.tag) if explicit else len(element.children)
            found[ident] = (first, shape if explicit or most < 0 else max(most, shape), ports)
        for ident in sorted(found):
            element, shape, ports = found[ident]
            if shape < 0:  # the explicit form names the kind
                kind = EXPLICIT_TAGS[-1 - shape]
            else:
                kind = "Action" if shape == 0 else "Decorator" if shape == 1 else "Control"
                article = "an" if kind == "Action" else "a"
                self.doc.warn(element, f"{short(ident)} is not declared; read as {article} "
                              f"{kind.lower()} from its shape")
            model_ports = [ModelPort("inout" if pointer(v, k) else "input", k, (("name", k),))
                           for k, v in ports]
            self.doc.models[ident] = ModelEntry(kind, ident, model_ports, inferred=True,
                                                origin="inferred")

    # --- trees --------------------------------------------------------------------------

    def tree_root(self, tree_id: str, board: Blackboard, chain: tuple[str, ...]) -> Node:
        element = self.doc.trees[tree_id]
        if len(element.children) != 1:
            raise self.doc.error(element, "a <BehaviorTree> has exactly one child, not "
                                 f"{len(element.children)}")
        root = self.node(element.children[0], board, chain)
        self.out.roots.setdefault(tree_id, root)
        return root

    def node(self, element: Element, board: Blackboard, chain: tuple[str, ...]) -> Node:
        self.depth += 1
        try:
            return self._node(element, board, chain)
        finally:
            self.depth -= 1

    def _node(self, element: Element, board: Blackboard, chain: tuple[str, ...]) -> Node:
        if self.depth > MAX_NESTING:
            raise self.doc.error(element, f"the tree is nested more than {MAX_NESTING} deep "
                                 "once its SubTrees are expanded")
        self.count += 1
        if self.count > MAX_NODES:
            raise self.doc.error(element, f"the trees expand to more than {MAX_NODES:,} nodes",
                                 "SubTrees are instantiated once per use")
        ident = self.ident(element)
        attrs = {k: v for k, v in element.attrs.items()
                 if not (element.tag in EXPLICIT_TAGS and k == "ID")}
        name = attrs.get("name", "")
        scripts = {k: self.script(element, k, v) for k, v in attrs.items() if k in PRE_POST}
        ports = {k: v for k, v in attrs.items()
                 if k != "name" and not k.startswith("_")}
        if ident == "SubTree":
            node = self.subtree(element, attrs, name, board, chain)
        elif ident in BUILTINS:
            node = self.builtin(element, ident, ports, name, board, chain)
        else:
            node = self.custom(element, ident, ports, name, board, chain)
        self.out.used.add(ident)
        node.origin = Origin(ident, tuple(attrs.items()))
        guard(node, scripts, board)
        return node

    def script(self, element: Element, attr: str, code: str) -> Script:
        try:
            return Script(code)
        except ScriptSyntaxError as error:
            start = max(0, error.offset - 30)
            window = ("..." if start else "") + short(code[start:], 60)
            hint = f"at character {error.offset + 1} of {window!r}"
            raise self.doc.error(element, f"in {attr}: {error.message}", hint) from None

    def children(self, element: Element, board: Blackboard, chain: tuple[str, ...]) -> list[Node]:
        return [self.node(child, board, chain) for child in element.children]

    # --- SubTree ------------------------------------------------------------------------

    def subtree(self, element: Element, attrs: dict[str, str], name: str, board: Blackboard,
                chain: tuple[str, ...]) -> Node:
        tree_id = attrs.get("ID", "")
        if not tree_id:
            raise self.doc.error(element, "<SubTree> needs an ID attribute")
        if element.children:
            raise self.doc.error(element, "a <SubTree> has no children")
        if tree_id not in self.doc.trees:
            near = get_close_matches(tree_id, sorted(self.doc.trees), n=1)
            raise self.doc.error(element, f"no <BehaviorTree ID=\"{short(tree_id)}\"> for this "
                                 "SubTree", f"did you mean {near[0]!r}?" if near else None)
        if tree_id in chain:
            raise self.doc.error(element, f"SubTree {short(tree_id)} calls itself",
                                 " -> ".join(short(t, 30) for t in (*chain, tree_id)))
        flag = attrs.get("_autoremap", "false").strip().lower()
        if flag not in ("true", "false", "1", "0"):
            raise self.doc.error(element, f"_autoremap={short(flag)!r} is not true or false")
        remap: dict[str, str] = {}
        literals: dict[str, str] = {}
        model = self.doc.models.get(tree_id)
        for port in model.ports if model is not None and model.kind == "SubTree" else []:
            default = dict(port.attrs).get("default")
            if default is not None:
                literals[port.name] = default
        for key, value in attrs.items():
            if key in ("ID", "name") or key.startswith("_"):
                continue
            target = pointer(value, key)
            if target is None:
                literals[key] = value
            else:
                remap[key] = target
                literals.pop(key, None)
        child_board = Blackboard(board, remap, flag in ("true", "1"))
        for key, value in literals.items():
            child_board.set(key, value)
        root = self.tree_root(tree_id, child_board, (*chain, tree_id))
        return SubTree(root, tree_id, child_board, name)

    # --- built-in nodes -----------------------------------------------------------------

    def check_shape(self, element: Element, ident: str, spec: BuiltinSpec,
                    ports: dict[str, str]) -> None:
        for key in ports:
            if spec.port(key) is None:
                names = ", ".join(p.name for p in spec.ports) or "none"
                raise self.doc.error(element, f"<{ident}> has no attribute {short(key)!r}",
                                     f"its ports: {names}")
        n = len(element.children)
        low, high = spec.min_children, spec.max_children
        if high == 0 and n:
            raise self.doc.error(element, f"<{ident}> is a leaf and has no children")
        if low == high == 1 and n != 1:
            raise self.doc.error(element, f"<{ident}> needs exactly one child, not {n}")
        if n < low or (high is not None and n > high):
            want = f"{low}" if low == high else f"{low} to {high}" if high else f"at least {low}"
            raise self.doc.error(element, f"<{ident}> needs {want} children, not {n}")

    def number(self, element: Element, ports: dict[str, str], key: str, default: str) -> int:
        value = ports.get(key, default)
        if pointer(value, key) is not None:
            raise self.doc.error(element, f"{key}={short(value)!r}: btplan needs a number here",
                                 "a blackboard value is only read for Repeat, "
                                 "RetryUntilSuccessful, Switch, RunOnce, Precondition, Loop "
                                 "and leaves")
        try:
            return int(value.strip())
        except ValueError:
            raise self.doc.error(element, f"{key}={short(value)!r} is not a whole number"
                                 ) from None

    def builtin(self, element: Element, ident: str, ports: dict[str, str], name: str,
                board: Blackboard, chain: tuple[str, ...]) -> Node:
        spec = BUILTINS[ident]
        self.check_shape(element, ident, spec, ports)
        defaults = {p.name: p.default for p in spec.ports if p.default is not None}
        io = Ports(f"{ident} {name!r}" if name else ident, ports, board, defaults)
        kids = self.children(element, board, chain)
        one = kids[0] if kids else None
        simple: dict[str, Callable[[], Node]] = {
                  "Sequence": lambda: BtcppSequence(kids, name, memory=True),
                  "ReactiveSequence": lambda: BtcppSequence(kids, name),
                  "Fallback": lambda: BtcppFallback(kids, name, memory=True),
                  "ReactiveFallback": lambda: BtcppFallback(kids, name),
                  "SequenceWithMemory": lambda: SequenceWithMemory(kids, name),
                  "AsyncSequence": lambda: AsyncSequence(kids, name),
                  "AsyncFallback": lambda: AsyncFallback(kids, name),
                  "ParallelAll": lambda: ParallelAll(kids, io, name),
                  "IfThenElse": lambda: IfThenElse(kids, name),
                  "WhileDoElse": lambda: WhileDoElse(kids, name),
                  "TryCatch": lambda: TryCatch(kids, io, name),
                  "Inverter": lambda: Inverter(one, name),
                  "ForceSuccess": lambda: ForceSuccess(one, name),
                  "ForceFailure": lambda: ForceFailure(one, name),
                  "KeepRunningUntilFailure": lambda: KeepRunningUntilFailure(one, name),
                  "Repeat": lambda: Repeat(one, io, name),
                  "RunOnce": lambda: RunOnce(one, io, name),
                  "SkipUnlessUpdated": lambda: WhenUpdated(one, io, False, name),
                  "WaitValueUpdate": lambda: WhenUpdated(one, io, True, name),
                  "AlwaysSuccess": lambda: Constant(SUCCESS, name),
                  "AlwaysFailure": lambda: Constant(FAILURE, name),
                  "SetBlackboard": lambda: SetBlackboard(io, name),
                  "UnsetBlackboard": lambda: UnsetBlackboard(io, name),
                  "WasEntryUpdated": lambda: WasEntryUpdated(io, name)}
        if ident in simple:
            return simple[ident]()
        if ident.startswith("Switch"):
            return Switch(kids, int(ident[6:]), io, name)
        if ident.startswith("Loop"):
            return Loop(one, io, ident[4:], name)
        if ident in ("Script", "ScriptCondition", "Precondition"):
            port = "if" if ident == "Precondition" else "code"
            if port not in ports or pointer(ports[port], port) is not None:
                raise self.doc.error(element, f"<{ident}> needs its script in {port}=\"...\"")
            script = self.script(element, port, ports[port])
            if ident == "Precondition":
                return Precondition(one, io, script, name)
            return (ScriptAction if ident == "Script" else ScriptCondition)(script, io, name)
        return self.timed(element, ident, ports, name, kids, board)

    def timed(self, element: Element, ident: str, ports: dict[str, str], name: str,
              kids: list[Node], board: Blackboard) -> Node:
        if ident == "Parallel":
            return BtcppParallel(kids, self.number(element, ports, "success_count", "-1"),
                                 self.number(element, ports, "failure_count", "1"), name)
        if ident == "RetryUntilSuccessful":
            if pointer(ports.get("num_attempts", ""), "num_attempts") is not None:
                return BoardRetry(kids[0], Ports(f"{ident} {name!r}" if name else ident,
                                                 ports, board, {}), name)
            attempts = self.number(element, ports, "num_attempts", "1")
            if attempts < 1 and attempts != -1:
                raise self.doc.error(element, f"num_attempts={attempts} is not supported",
                                     "give at least 1, or -1 to retry for ever")
            return Retry(kids[0], attempts=attempts, name=name)
        if ident == "Timeout":
            msec = self.number(element, ports, "msec", str(TICK_MS))
            if msec < 1:
                raise self.doc.error(element, f"msec={msec} leaves no time to run")
            return Timeout(kids[0], ticks=ticks(msec), name=name)
        if ident == "Delay":
            return Delay(kids[0], ticks(max(self.number(element, ports, "delay_msec", "0"), 0)),
                         name)
        return Sleep(ticks(max(self.number(element, ports, "msec", "0"), 0)), name)

    # --- custom nodes -------------------------------------------------------------------

    def custom(self, element: Element, ident: str, ports: dict[str, str], name: str,
               board: Blackboard, chain: tuple[str, ...]) -> Node:
        entry = self.doc.models[ident]
        if entry.kind in ("Action", "Condition"):
            if element.children:
                raise self.doc.error(element, f"the {entry.kind} {short(ident)} cannot have "
                                     "children")
            declared = entry.port_names()
            if not entry.inferred:
                for key in ports:
                    if key not in declared:
                        raise self.doc.error(element, f"{short(ident)} has no port {short(key)!r}",
                                             "declare it in <TreeNodesModel> or remove it")
            names = tuple(ports)
            args = tuple(ports[k] for k in names)
            bound = any(pointer(v, k) is not None for k, v in ports.items())
            if entry.kind == "Action":
                return (BoundAction(ident, args, names, board, name) if bound
                        else Action(ident, args, names, name))
            return (BoundCondition(ident, args, names, board, name) if bound
                    else Condition(ident, args, names, name))
        if entry.kind == "Decorator" and len(element.children) != 1:
            raise self.doc.error(element, f"the decorator {short(ident)} needs exactly one child")
        if entry.kind == "SubTree":
            raise self.doc.error(element, f"{short(ident)} is a tree: call it with "
                                 f"<SubTree ID=\"{short(ident)}\"/>")
        return Opaque(ident, entry.kind, self.children(element, board, chain), name)


def build_tree(doc: XmlDocument, strict: bool = False,
               enums: Mapping[str, int] | None = None) -> BehaviorTree:
    """The main tree of `doc`, ticking on its own blackboard; every other tree of the
    document is instantiated too (as BT.CPP checks them all) for the export.

    `enums` are the scripting enums BT.CPP would have registered in C++ (`RED` -> 1).
    """
    builder = _Builder(doc, strict)
    builder.prescan()
    board = builder.out.board
    board.enums.update(enums or {})
    root = builder.tree_root(doc.main, board, (doc.main,))
    for tree_id in doc.trees:
        if tree_id not in builder.out.roots:
            builder.tree_root(tree_id, Blackboard(enums=board.enums), (tree_id,))
    tree = BehaviorTree(root, name=doc.main)
    tree.imported = builder.out
    return tree


__all__ = ["MAX_NESTING", "MAX_NODES", "TICK_MS", "ImportedTrees", "build_tree", "ticks"]
