"""Check a problem against its domain and build its model, pointing at every mistake.

A problem's checks need the domain's model (its types, predicates and constants), so
they run after the domain is built; the messages follow the domain's checks.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.lang.names import suggest
from btplan.lang.report import Report
from btplan.lang.syntax import LiteralSyntax, ProblemSyntax
from btplan.lang.types import TypeTable
from btplan.lang.validate import (
    article,
    check_contradictions,
    check_predicate,
    typed_names,
    written,
)
from btplan.model import Domain, FunctionValue, Literal, Predicate, Problem, Task


def build_problem(syntax: ProblemSyntax, domain: Domain, report: Report | None = None) -> Problem:
    """Validate a problem against its (already valid) domain and build its model."""
    own = report is None
    report = report or Report()
    if syntax.domain.text != domain.name:
        report.add(
            syntax.domain.at.error(
                f"problem '{syntax.name.text}' is for domain '{syntax.domain.text}', "
                f"but the domain given is '{domain.name}'"
            )
        )
    types = TypeTable.from_domain(domain)
    objects = typed_names(syntax.objects, types, "object", report)
    constants = {c.name for c in domain.constants}
    for entry in syntax.objects:
        if entry.name.text in constants:
            report.add(
                entry.name.at.error(
                    f"'{entry.name.text}' is already a constant of domain '{domain.name}'"
                )
            )
    known = {c.name: c.type for c in domain.constants}
    known.update({o.name: o.type for o in objects})
    # objects of an unknown type were reported once; their facts are not checked for type
    unknown = {o.name.text for o in syntax.objects if o.type and o.type.text not in types.parents}
    facts = _FactChecker(types, domain.predicate_map, known, unknown)
    init = []
    for lit in syntax.init:
        if not lit.positive:
            report.add(
                lit.at.error(
                    "initial facts are positive",
                    "leave out what is false: it is false by default",
                )
            )
        else:
            init.append(report.attempt(facts.check, lit, "initial fact"))
    terms = _FactChecker(types, {f.name: f for f in domain.functions}, known, unknown)
    values = []
    for term, number in syntax.values:
        checked = report.attempt(terms.check, term, "function value")
        if checked is not None:
            values.append(FunctionValue(
                function=checked.predicate, args=checked.args, value=float(number.text)))
    goal = _checked_goal(syntax.goal, facts, report)
    _warn_unreachable(syntax.goal, init, domain, report)
    if own:
        report.raise_errors()
    return Problem(
        name=syntax.name.text,
        domain=syntax.domain.text,
        objects=objects,
        init=tuple(dict.fromkeys(x for x in init if x is not None)),
        goal=goal,
        values=tuple(values),
    )


def check_goal(goal: tuple[LiteralSyntax, ...], task: Task, report: Report) -> tuple[Literal, ...]:
    """A goal given on its own, checked as a problem's goal is: against the domain's
    predicates and the task's objects and constants, and for literals that contradict."""
    known = dict(task.object_types)
    facts = _FactChecker(TypeTable.from_domain(task.domain), task.domain.predicate_map, known,
                         set())
    return _checked_goal(goal, facts, report)


def _checked_goal(goal: tuple[LiteralSyntax, ...], facts: _FactChecker, report: Report
                  ) -> tuple[Literal, ...]:
    """The goal's literals that pass `facts`; what does not, and literals that contradict
    each other, go to `report`."""
    checked = [report.attempt(facts.check, lit, "goal") for lit in goal]
    report.attempt(check_contradictions, goal, "goal conditions", "no state satisfies both")
    return tuple(x for x in checked if x is not None)


def _warn_unreachable(
    goal: tuple[LiteralSyntax, ...], init: list[Literal | None], domain: Domain, report: Report
) -> None:
    """Warn about goals on static predicates that are false from the start.

    No action changes such a predicate, so no plan can reach them; this is legal input,
    but planning is certain to fail, and the place of the goal is known only here.
    """
    facts = {(x.predicate, x.args) for x in init if x is not None}
    for lit in goal:
        name = lit.predicate.text
        if name not in domain.predicate_map or name in domain.changed_predicates:
            continue
        holds = (name, tuple(a.text for a in lit.args)) in facts
        if holds != lit.positive:
            report.warn(
                lit.at.error(
                    f"the goal '{written(lit.literal())}' can never hold",
                    f"no action changes '{name}', and it is "
                    f"{'false' if lit.positive else 'true'} initially",
                )
            )


class _FactChecker:
    """Checks ground literals (initial facts, goals) against objects and constants."""

    def __init__(
        self,
        types: TypeTable,
        predicates: Mapping[str, Predicate],
        known: Mapping[str, str],
        untyped: set[str],
    ) -> None:
        self.types = types
        self.predicates = predicates
        self.known = known
        self.untyped = untyped

    def check(self, lit: LiteralSyntax, what: str) -> Literal:
        if lit.is_equality:
            raise lit.at.error(f"an equality cannot be {article(what)}")
        predicate = check_predicate(lit, self.predicates)
        for arg, param in zip(lit.args, predicate.parameters):
            if arg.text not in self.known:
                raise arg.at.error(
                    f"unknown object '{arg.text}' in {article(what)}",
                    suggest(arg.text, self.known) or "declare it under 'objects'",
                )
            arg_type = self.known[arg.text]
            if arg.text not in self.untyped and not self.types.is_subtype(arg_type, param.type):
                raise arg.at.error(
                    f"'{arg.text}' is {article(arg_type)}, "
                    f"but {predicate.name} expects {article(param.type)} here"
                )
        return lit.literal()
