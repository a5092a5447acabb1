"""The expressions of a binding file: a goal field's value, a condition's test.

    msg.data == l                      a condition over the latest message on a topic
    (o + ':' + t) in split(msg.data, ',')
    hypot(msg.x - x[l], msg.y - y[l]) < 0.2
    id[o]                              a goal field from a lookup table of the file

A small language checked when the file is read: names are the action's or predicate's
parameters, the file's lookup tables, and `msg` (a condition's latest message, or the
service's response); literals, arithmetic, comparisons, `and`/`or`/`not`, `in`,
subscripts, attributes of `msg`, and the functions of FUNCTIONS. Nothing else is
evaluated: no other name, no other call, no attribute but a message's fields.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["FUNCTIONS", "Expression", "ExpressionError"]

FUNCTIONS: dict[str, Callable[..., Any]] = {
    "abs": abs, "min": min, "max": max, "len": len, "hypot": math.hypot, "round": round,
    "split": lambda text, sep=",": [part.strip() for part in str(text).split(sep)],
    "str": str, "int": int, "float": float,
}

_NODES = (ast.Expression, ast.BoolOp, ast.BinOp, ast.UnaryOp, ast.Compare, ast.Call,
          ast.Name, ast.Load, ast.Constant, ast.Attribute, ast.Subscript, ast.Tuple,
          ast.List, ast.And, ast.Or, ast.Not, ast.USub, ast.UAdd, ast.Add, ast.Sub,
          ast.Mult, ast.Div, ast.FloorDiv, ast.Mod, ast.Eq, ast.NotEq, ast.Lt, ast.LtE,
          ast.Gt, ast.GtE, ast.In, ast.NotIn, ast.IfExp)


class ExpressionError(ValueError):
    """An expression that is not of the binding language, or names what is not there."""


class Expression:
    """One checked expression, evaluated against names given at run time."""

    def __init__(self, text: str, names: set[str], message_fields: set[str] | None = None
                 ) -> None:
        """`names`: the names it may use (parameters, tables, and `msg` for a condition);
        `message_fields`: the dotted field paths of `msg` (None: not checked)."""
        self.text = text
        try:
            tree = ast.parse(text.strip(), mode="eval")
        except SyntaxError as error:
            raise ExpressionError(f"{text!r} is not an expression: {error.msg}") from None
        for node in ast.walk(tree):
            if not isinstance(node, _NODES):
                raise ExpressionError(f"{text!r}: {type(node).__name__} is not allowed here")
            if isinstance(node, ast.Name) and node.id not in names and node.id not in FUNCTIONS:
                known = ", ".join(sorted(names)) or "none"
                raise ExpressionError(f"{text!r}: unknown name {node.id!r} (known: {known})")
            if isinstance(node, ast.Call) and not (
                    isinstance(node.func, ast.Name) and node.func.id in FUNCTIONS):
                raise ExpressionError(f"{text!r}: only {', '.join(sorted(FUNCTIONS))} "
                                      "may be called")
            if isinstance(node, ast.Attribute):
                path = _field_path(node)
                if path is None:
                    raise ExpressionError(f"{text!r}: attributes are a message's fields only "
                                          "(msg.field.subfield)")
                if message_fields is not None and path not in message_fields:
                    raise ExpressionError(f"{text!r}: the message has no field {path!r} "
                                          f"(fields: {', '.join(sorted(message_fields))})")
        self._code = compile(tree, "<binding>", "eval")

    def __call__(self, names: Mapping[str, Any]) -> Any:
        scope = dict(FUNCTIONS)
        scope.update(names)
        return eval(self._code, {"__builtins__": {}}, scope)  # noqa: S307 (checked above)


def _field_path(node: ast.Attribute) -> str | None:
    """`msg.a.b` as "a.b"; None when the chain is not rooted at `msg`."""
    parts: list[str] = []
    current: ast.expr = node
    while isinstance(current, ast.Attribute):
        parts.append(current.attr)
        current = current.value
    if isinstance(current, ast.Name) and current.id == "msg" and not any(
            p.startswith("_") for p in parts):
        return ".".join(reversed(parts))
    return None
