"""Write models back as text, in the .bt language or in PDDL.

Generated problems are built as models and written out with these, and reading the
text back must give the same models: the round trip is how the readers are tested on
problems of any size.
"""

from __future__ import annotations

from collections.abc import Iterable

from btplan.errors import InputError
from btplan.model import (
    EQUALITY,
    ROOT_TYPE,
    WILDCARD,
    ActionTemplate,
    Domain,
    Literal,
    Parameter,
    Problem,
    TypedName,
)

INDENT = "    "


# --- the .bt language ------------------------------------------------------------------


def bt_literal(literal: Literal) -> str:
    """A literal as the .bt language writes it: `on(a, b)`, `not clear(a)`, `hand_empty`
    without parentheses, `x == y` for an equality. Messages quote literals this way."""
    if literal.predicate == EQUALITY:
        op = "==" if literal.positive else "!="
        return f"{literal.args[0]} {op} {literal.args[1]}"
    atom = literal.predicate + (f"({', '.join(literal.args)})" if literal.args else "")
    return atom if literal.positive else f"not {atom}"


def _bt_parameters(parameters: Iterable[Parameter]) -> str:
    return ", ".join(f"{p.name}: {p.type}" + (" refined" if p.refined else "") for p in parameters)


def _bt_typed_lines(entries: Iterable[TypedName]) -> list[str]:
    """`a, b : t` per type, in first-seen order of the types."""
    groups: dict[str, list[str]] = {}
    for entry in entries:
        groups.setdefault(entry.type, []).append(entry.name)
    return [f"{INDENT * 2}{', '.join(names)} : {type_}" for type_, names in groups.items()]


def _bt_block(title: str, lines: list[str]) -> list[str]:
    if not lines:
        return []
    return [f"{INDENT}{title} {{", *lines, f"{INDENT}}}", ""]


def bt_domain(domain: Domain) -> str:
    """The domain in the .bt language."""
    types = [
        f"{INDENT * 2}{t.name}" + (f" : {t.parent}" if t.parent not in (None, ROOT_TYPE) else "")
        for t in domain.types
        if not (t.name == ROOT_TYPE and t.parent is None)
    ]
    predicates = [
        f"{INDENT * 2}{p.name}" + (f"({_bt_parameters(p.parameters)})" if p.parameters else "")
        for p in domain.predicates
    ]
    lines = [f"domain {domain.name} {{"]
    lines += _bt_block("types", types)
    lines += _bt_block("constants", _bt_typed_lines(domain.constants))
    lines += _bt_block("predicates", predicates)
    for action in domain.actions:
        lines += _bt_action(action)
    if lines[-1] == "":
        lines.pop()
    lines.append("}")
    return "\n".join(lines) + "\n"


def _bt_action(action: ActionTemplate) -> list[str]:
    lines = [f"{INDENT}action {action.name}({_bt_parameters(action.parameters)}) {{"]
    for label, literals in (
        ("where", action.constraints),
        ("pre", action.preconditions),
        ("post", action.effects),
    ):
        if literals:
            lines.append(
                f"{INDENT * 2}{label + ':':6} {', '.join(bt_literal(x) for x in literals)}"
            )
    if action.cost_term is not None:
        raise InputError(
            f"cannot be written in .bt: the cost of {action.name} is read from "
            f"'{action.cost_term.predicate}'", hint="keep the domain in PDDL")
    if action.cost != 1.0:
        lines.append(f"{INDENT * 2}cost: {action.cost:g}")
    if action.duration != 1:
        lines.append(f"{INDENT * 2}duration: {action.duration}")
    return [*lines, f"{INDENT}}}", ""]


def bt_problem(problem: Problem) -> str:
    """The problem in the .bt language, one initial fact per line."""
    lines = [f"problem {problem.name} for {problem.domain} {{"]
    lines += _bt_block("objects", _bt_typed_lines(problem.objects))
    lines += _bt_block("init", [f"{INDENT * 2}{bt_literal(x)}" for x in problem.init])
    lines += _bt_block("goal", [f"{INDENT * 2}{bt_literal(x)}" for x in problem.goal])
    if lines[-1] == "":
        lines.pop()
    lines.append("}")
    return "\n".join(lines) + "\n"


# --- PDDL ------------------------------------------------------------------------------


def _unwritable(what: str) -> InputError:
    return InputError(f"cannot be written as PDDL: {what}", hint="write it with --format bt")


def pddl_literal(literal: Literal, variables: frozenset[str] = frozenset()) -> str:
    """A literal as PDDL writes it, `(on ?x b)` or `(not (clear ?x))`, with `?` before the
    names in `variables`; the `_` wildcard has no PDDL form and raises an InputError."""
    if WILDCARD in literal.args:
        raise _unwritable(f"the wildcard in '{bt_literal(literal)}'")
    args = [f"?{a}" if a in variables else a for a in literal.args]
    atom = f"({' '.join([literal.predicate, *args])})"
    return atom if literal.positive else f"(not {atom})"


def _pddl_typed(names: Iterable[tuple[str, str]]) -> str:
    groups: dict[str, list[str]] = {}
    for name, type_ in names:
        groups.setdefault(type_, []).append(name)
    return " ".join(f"{' '.join(ns)} - {t}" for t, ns in groups.items())


def _pddl_and(literals: list[str]) -> str:
    if len(literals) == 1:
        return literals[0]
    return "(and " + " ".join(literals) + ")"


def pddl_requirements(domain: Domain) -> tuple[str, ...]:
    """The requirements a domain actually uses, from the supported four."""
    found = [":strips"]
    if any(t.name != ROOT_TYPE for t in domain.types):
        found.append(":typing")
    literals = [x for a in domain.actions for x in (*a.constraints, *a.preconditions)]
    if any(not x.positive and x.predicate != EQUALITY for x in literals):
        found.append(":negative-preconditions")
    if any(x.predicate == EQUALITY for x in literals):
        found.append(":equality")
    return tuple(found)


def pddl_domain(domain: Domain) -> str:
    """The domain in PDDL; `where` constraints become static preconditions."""
    roots = {t.name for t in domain.types if t.parent is None}
    if ROOT_TYPE not in roots:
        raise _unwritable(f"the type '{ROOT_TYPE}' is placed under another type")
    types = [(t.name, t.parent or ROOT_TYPE) for t in domain.types if t.name != ROOT_TYPE]
    lines = [
        f"(define (domain {domain.name})",
        f"  (:requirements {' '.join(pddl_requirements(domain))})",
    ]
    if types:
        lines.append(f"  (:types {_pddl_typed(types)})")
    if domain.constants:
        lines.append(f"  (:constants {_pddl_typed((c.name, c.type) for c in domain.constants)})")
    lines.append("  (:predicates")
    for p in domain.predicates:
        params = _pddl_typed((f"?{x.name}", x.type) for x in p.parameters)
        lines.append(f"    ({p.name}{' ' + params if params else ''})")
    lines[-1] += ")"
    for action in domain.actions:
        lines += _pddl_action(action)
    lines[-1] += ")"
    return "\n".join(lines) + "\n"


def _pddl_action(action: ActionTemplate) -> list[str]:
    if any(p.refined for p in action.parameters):
        raise _unwritable(f"the refined parameters of {action.name}")
    if action.cost != 1.0 or action.cost_term is not None or action.duration != 1:
        raise _unwritable(f"the cost or duration of {action.name}")
    names = frozenset(p.name for p in action.parameters)
    params = _pddl_typed((f"?{p.name}", p.type) for p in action.parameters)
    pre = [pddl_literal(x, names) for x in (*action.constraints, *action.preconditions)]
    post = [pddl_literal(x, names) for x in action.effects]
    lines = ["", f"  (:action {action.name}", f"    :parameters ({params})"]
    if pre:
        lines.append(f"    :precondition {_pddl_and(pre)}")
    lines.append(f"    :effect {_pddl_and(post) if post else '()'})")
    return lines


def pddl_problem(problem: Problem) -> str:
    """The problem in PDDL, one initial fact per line."""
    lines = [
        f"(define (problem {problem.name})",
        f"  (:domain {problem.domain})",
        f"  (:objects {_pddl_typed((o.name, o.type) for o in problem.objects)})",
        "  (:init",
        *[f"    {pddl_literal(x)}" for x in problem.init],
        "  )",
        f"  (:goal {_pddl_and([pddl_literal(x) for x in problem.goal]) if problem.goal else '(and)'}))",
    ]
    return "\n".join(lines) + "\n"
