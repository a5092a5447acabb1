"""Saved trees: the pydantic models of btplan's JSON tree format, and the exact round trip.

This is what `btplan plan --format json` prints (written by saved_out.py, which needs
no pydantic) and `btplan export` reads back. The models are the schema (`btplan export
json --schema`); `to_model`/`from_model` convert to and from live nodes without loss, so dump -> load -> dump gives the same text.
Fields that hold their default are left out of the JSON to keep files readable.
"""

from __future__ import annotations

import json
import re
import sys
from typing import Literal

from pydantic import BaseModel, ConfigDict, Field, ValidationError, model_validator

from btplan.bt.composites import Fallback, Sequence
from btplan.bt.decorators import Decorator, ForceFailure, ForceSuccess, Inverter, Retry, Timeout
from btplan.bt.formats.locate import line_at, locate
from btplan.bt.formats.saved_out import dump_json, tree_data
from btplan.bt.leaves import Action, Condition
from btplan.bt.node import Node
from btplan.bt.parallel import Parallel
from btplan.bt.status import Status
from btplan.bt.tree import BehaviorTree
from btplan.errors import InputError, Span
from btplan.limits import (
    JSON_BRACKETS,
    MAX_JSON_NESTING,
    MAX_TREE_DEPTH,
    check_nesting,
    check_size,
    located,
    shorten,
)

FORMAT: Literal["btplan-tree"] = "btplan-tree"
VERSION: Literal[1] = 1

NodeType = Literal["Sequence", "Fallback", "Parallel", "Inverter", "ForceSuccess",
                   "ForceFailure", "Retry", "Timeout", "Condition", "Action"]
NODE_TYPES = ("Sequence", "Fallback", "Parallel", "Inverter", "ForceSuccess", "ForceFailure",
              "Retry", "Timeout", "Condition", "Action")
StatusName = Literal["SUCCESS", "FAILURE", "RUNNING"]
LEAVES = ("Condition", "Action")
DECORATORS = ("Inverter", "ForceSuccess", "ForceFailure", "Retry", "Timeout")


class SavedNode(BaseModel):
    """One node; which fields apply depends on `type` (checked after parsing)."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    type: NodeType
    name: str = Field("", description="instance name; for leaves, empty means ident(args)")
    memory: bool = Field(False, description="Sequence/Fallback: resume the RUNNING child "
                         "instead of restarting at the first child on every tick")
    ident: str = Field("", description="leaves: predicate or action template name")
    args: tuple[str, ...] = Field((), description="leaves: grounded arguments")
    ports: tuple[str, ...] = Field((), description="leaves: the parameter name of each argument")
    attempts: int = Field(1, ge=1, description="Retry: attempts before giving up")
    ticks: int = Field(1, ge=1, description="Timeout: ticks the child may stay RUNNING")
    success: int = Field(-1, description="Parallel: successes needed; negative counts "
                         "from the number of children (-1 = all)")
    failure: int = Field(1, description="Parallel: failures that make it fail")
    status: StatusName | None = Field(None, description="status of the last tick, if saved")
    children: tuple[SavedNode, ...] = ()

    @model_validator(mode="after")
    def _fits_its_type(self) -> SavedNode:
        if self.type in LEAVES:
            if not self.ident:
                raise ValueError(f"a {self.type} needs an 'ident'")
            if self.children:
                raise ValueError(f"a {self.type} has no children")
            if len(self.ports) != len(self.args):
                raise ValueError(f"{len(self.ports)} ports for {len(self.args)} args")
        elif self.ident or self.args or self.ports:
            raise ValueError(f"'ident', 'args' and 'ports' belong to leaves, not to a {self.type}")
        if self.type in DECORATORS and len(self.children) != 1:
            raise ValueError(f"a {self.type} has exactly one child, not {len(self.children)}")
        if self.memory and self.type not in ("Sequence", "Fallback"):
            raise ValueError("only a Sequence or Fallback has 'memory'")
        return self


class SavedTree(BaseModel):
    """A whole tree as btplan saves it."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    format: Literal["btplan-tree"] = Field(description="always 'btplan-tree'")
    version: Literal[1] = Field(description="format version, 1")
    name: str = "Main"
    root: SavedNode


def to_model(tree: BehaviorTree, with_status: bool = False) -> SavedTree:
    """The saved form of a live tree; statuses only when asked (a snapshot for display)."""
    return SavedTree.model_validate(tree_data(tree, with_status))


_PLAIN: dict[str, type[Decorator]] = {
    "Inverter": Inverter, "ForceSuccess": ForceSuccess, "ForceFailure": ForceFailure}


def _build(saved: SavedNode) -> Node:
    children = [_build(c) for c in saved.children]
    node: Node
    if saved.type == "Condition":
        node = Condition(saved.ident, saved.args, saved.ports, name=saved.name)
    elif saved.type == "Action":
        node = Action(saved.ident, saved.args, saved.ports, name=saved.name)
    elif saved.type == "Sequence":
        node = Sequence(children, name=saved.name, memory=saved.memory)
    elif saved.type == "Fallback":
        node = Fallback(children, name=saved.name, memory=saved.memory)
    elif saved.type == "Parallel":
        node = Parallel(children, success=saved.success, failure=saved.failure, name=saved.name)
    elif saved.type == "Retry":
        node = Retry(children[0], attempts=saved.attempts, name=saved.name)
    elif saved.type == "Timeout":
        node = Timeout(children[0], ticks=saved.ticks, name=saved.name)
    else:
        node = _PLAIN[saved.type](children[0], name=saved.name)
    if saved.status is not None:
        node.status = Status(saved.status)
    return node


def from_model(saved: SavedTree) -> BehaviorTree:
    """A live tree from its saved form; saved statuses are restored as last statuses."""
    return BehaviorTree(_build(saved.root), name=saved.name)


def json_schema() -> str:
    """The JSON schema of saved trees, generated from the models."""
    return json.dumps(SavedTree.model_json_schema(), indent=2) + "\n"


def load_json(text: str, path: str = "<tree>") -> BehaviorTree:
    """Parse a saved tree; every problem becomes an InputError at the offending value.

    Size and nesting are checked before `json.loads`, which recurses: a tree deeper than
    MAX_TREE_DEPTH nodes is refused where it gets too deep (btplan/limits.py).
    """
    check_size(len(text), path)
    check_nesting(text, path, JSON_BRACKETS, MAX_JSON_NESTING,
                  f"the tree is nested more than {MAX_TREE_DEPTH} nodes deep")
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise InputError(f"not valid JSON: {error.msg}", Span(path, error.lineno, error.colno),
                         source_line=line_at(text, error.lineno)) from None
    except ValueError:  # an integer past Python's digit limit for int()
        digits = re.search(r"\d{%d,}" % (sys.get_int_max_str_digits() + 1), text)
        raise located(text, path, digits.start() if digits else 0,
                      "not valid JSON: a number with too many digits") from None
    try:
        saved = SavedTree.model_validate(data)
    except ValidationError as error:
        first = error.errors()[0]
        where = [step for step in first["loc"] if isinstance(step, (str, int))]
        line, column = locate(text, where)
        dotted = ".".join(shorten(str(s)) for s in where) or "tree"
        message = first["msg"].removeprefix("Value error, ")
        raise InputError(f"{dotted}: {message}", Span(path, line, column),
                         hint=_hint(error), source_line=line_at(text, line)) from None
    try:
        return from_model(saved)
    except ValueError as error:  # e.g. a Parallel threshold that cannot be met
        raise InputError(str(error), Span(path, 1, 1)) from None


def _hint(error: ValidationError) -> str | None:
    count = error.error_count()
    return f"and {count - 1} more problem(s)" if count > 1 else None


__all__ = ["SavedNode", "SavedTree", "dump_json", "from_model", "json_schema", "load_json",
           "to_model"]
