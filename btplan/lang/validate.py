"""Check a domain's located syntax and build its frozen model, pointing at every mistake.

Both readers (.bt and PDDL) end here, so both languages get the same checks and the
same messages: unknown names with a "did you mean", wrong arity, wrong types, unbound
variables, duplicates, and postconditions that contradict each other. Problems are
checked against the built domain in `problem_check`, with the helpers shared here.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.lang.names import check_unique, suggest
from btplan.lang.report import Report
from btplan.lang.syntax import (
    ActionSyntax,
    DomainSyntax,
    LiteralSyntax,
    Name,
    Number,
    PredicateSyntax,
    TypedSyntax,
)
from btplan.lang.types import TypeTable
from btplan.model import (
    EQUALITY,
    ROOT_TYPE,
    WILDCARD,
    ActionTemplate,
    Domain,
    Literal,
    Parameter,
    Predicate,
    TypedName,
)


def article(noun: str) -> str:
    """`a block`, `an object`: messages read as sentences."""
    return f"{'an' if noun[:1].lower() in 'aeiou' else 'a'} {noun}"


# --- domain ---------------------------------------------------------------------------


def build_domain(syntax: DomainSyntax, report: Report | None = None) -> Domain:
    """Validate a domain and build its model (equalities in `pre` move to constraints).

    Mistakes go to `report` when one is given (the caller raises them later); otherwise
    they are raised together before returning.
    """
    own = report is None
    report = report or Report()
    types = TypeTable.from_syntax(syntax.types)  # everything else depends on the types
    constants = typed_names(syntax.constants, types, "constant", report)
    constant_types = {c.name: c.type for c in constants}
    predicates = _predicates(syntax, types, report)
    functions = _predicates(syntax, types, report, syntax.functions)
    check_unique((a.name for a in syntax.actions), "action", report)
    built = (
        report.attempt(_action, a, types, predicates, constant_types, report, functions)
        for a in syntax.actions
    )
    actions = tuple(a for a in built if a is not None)
    if own:
        report.raise_errors()
    return Domain(
        name=syntax.name.text,
        requirements=tuple(r.text for r in syntax.requirements),
        types=types.definitions(),
        constants=constants,
        predicates=tuple(predicates.values()),
        actions=actions,
        functions=tuple(functions.values()),
    )


def typed_names(
    entries: tuple[TypedSyntax, ...], types: TypeTable, what: str, report: Report
) -> tuple[TypedName, ...]:
    """A constants or objects list with resolved types; duplicate names and unknown types go
    into `report` (an unknown type reads as the root), so every mistake shows in one pass."""
    check_unique((e.name for e in entries), what, report)
    return tuple(TypedName(name=e.name.text, type=_resolve(types, e.type, report)) for e in entries)


def _resolve(types: TypeTable, name: Name | None, report: Report) -> str:
    """The type's name; an unknown type is reported and read as the root, so that the
    mistake is reported once rather than at every use."""
    return report.attempt(types.resolve, name) or ROOT_TYPE


def _predicates(
    syntax: DomainSyntax,
    types: TypeTable,
    report: Report,
    declared: tuple[PredicateSyntax, ...] | None = None,
) -> dict[str, Predicate]:
    """The predicates (or, given `declared`, the functions) of a domain, checked."""
    declared = syntax.predicates if declared is None else declared
    check_unique((p.name for p in declared), "predicate", report)
    table: dict[str, Predicate] = {}
    for decl in declared:
        check_unique((p.name for p in decl.parameters), "parameter", report)
        for p in decl.parameters:
            if p.refined:
                report.add(p.name.at.error("only action parameters can be 'refined'"))
        params = tuple(
            Parameter(name=p.name.text, type=_resolve(types, p.type, report))
            for p in decl.parameters
        )
        table[decl.name.text] = Predicate(name=decl.name.text, parameters=params)
    return table


def _action(
    syntax: ActionSyntax,
    types: TypeTable,
    predicates: Mapping[str, Predicate],
    constants: Mapping[str, str],
    report: Report,
    functions: Mapping[str, Predicate] | None = None,
) -> ActionTemplate:
    check_unique((p.name for p in syntax.parameters), "parameter", report)
    params = []
    for p in syntax.parameters:
        if p.name.text in constants:
            raise p.name.at.error(
                f"parameter '{p.name.text}' has the name of a constant", "rename the parameter"
            )
        if p.name.text == WILDCARD:
            raise p.name.at.error("'_' is the wildcard and cannot name a parameter")
        type_name = _resolve(types, p.type, report)
        params.append(Parameter(name=p.name.text, type=type_name, refined=p.refined))
    scope = {p.name: p.type for p in params}
    scope.update({c: t for c, t in constants.items() if c not in scope})
    context = _LiteralChecker(types, predicates, scope, syntax.name.text, set(constants))

    where = _checked(context, syntax.where, "where", report)
    pre: list[Literal] = []
    for checked in _checked(context, syntax.pre, "pre", report):
        # equalities are static: they restrict bindings, they are not run-time conditions
        (where if checked.predicate == EQUALITY else pre).append(checked)
    post = _checked(context, syntax.post, "post", report)
    cost_term = None
    if syntax.cost_term is not None:
        terms = _LiteralChecker(types, functions or {}, scope, syntax.name.text, set(constants))
        cost_term = report.attempt(terms.check, syntax.cost_term, "cost")
    report.attempt(
        check_contradictions,
        syntax.post,
        "postconditions",
        "this action would make it both true and false",
    )
    report.attempt(
        check_contradictions, syntax.pre, "preconditions", "this action could never run"
    )
    return ActionTemplate(
        name=syntax.name.text,
        parameters=tuple(params),
        constraints=tuple(where),
        preconditions=tuple(pre),
        effects=tuple(post),
        cost=_cost(syntax.cost),
        cost_term=cost_term,
        duration=report.attempt(_duration, syntax.duration) or 1,
    )


def _checked(
    context: _LiteralChecker, literals: tuple[LiteralSyntax, ...], part: str, report: Report
) -> list[Literal]:
    """Each literal checked on its own, so that one mistake does not hide the next."""
    found = (report.attempt(context.check, lit, part) for lit in literals)
    return [lit for lit in found if lit is not None]


def _cost(number: Number | None) -> float:
    if number is None:
        return 1.0
    return float(number.text)


def _duration(number: Number | None) -> int:
    if number is None:
        return 1
    if "." in number.text or int(number.text) < 1:
        raise number.at.error("a duration is a whole number of ticks, at least 1")
    return int(number.text)


def written(literal: Literal) -> str:
    """The literal as btplan's language writes it. Only messages need the writers, so
    they are imported here: a well-formed `btplan plan` starts without them."""
    from btplan.lang.writers import bt_literal

    return bt_literal(literal)


def check_contradictions(literals: tuple[LiteralSyntax, ...], what: str, why: str) -> None:
    """Refuse a list that asks for a literal and its negation (`what` names the list, `why` is
    the hint), at the second of the two: no state could satisfy it."""
    seen: dict[tuple[str, tuple[str, ...]], LiteralSyntax] = {}
    for lit in literals:
        key = (lit.predicate.text, tuple(a.text for a in lit.args))
        other = seen.get(key)
        if other is not None and other.positive != lit.positive:
            raise lit.at.error(
                f"contradictory {what}: "
                f"'{written(other.literal())}' and '{written(lit.literal())}'",
                why,
            )
        seen[key] = lit


class _LiteralChecker:
    """Checks the literals of one action against its parameters and the constants."""

    def __init__(
        self,
        types: TypeTable,
        predicates: Mapping[str, Predicate],
        scope: Mapping[str, str],
        action: str,
        constants: set[str],
    ) -> None:
        self.types = types
        self.predicates = predicates
        self.scope = scope
        self.action = action
        self.constants = constants
        self.pddl = False  # set from the first literal: messages quote the file's own syntax

    def _shown(self, literal: Literal) -> str:
        if self.pddl:
            from btplan.lang.writers import pddl_literal

            return pddl_literal(literal, frozenset(set(self.scope) - self.constants))
        return written(literal)

    def _variable(self, name: str) -> str:
        return f"?{name}" if self.pddl and name in self.scope and name not in self.constants \
            else name

    def check(self, lit: LiteralSyntax, part: str) -> Literal:
        self.pddl = written_in_pddl(lit.at.span.path, lit.at.line_text)
        if lit.is_equality:
            if part == "post":
                raise lit.at.error(
                    "an equality cannot be a postcondition",
                    "equalities belong in :precondition" if self.pddl
                    else "equalities belong under 'where:' or 'pre:'",
                )
            left, right = (self._arg_type(arg, lit, part) for arg in lit.args)
            if not self.types.related(left, right):
                verdict = "always true" if not lit.positive else "never true"
                first, second = (self._variable(a.text) for a in lit.args)
                raise lit.at.error(
                    f"'{self._shown(lit.literal())}' is {verdict}: {first} is {article(left)} "
                    f"and {second} is {article(right)}"
                )
            return lit.literal()
        predicate = check_predicate(lit, self.predicates)
        for arg, param in zip(lit.args, predicate.parameters):
            if arg.text == WILDCARD:
                if part not in ("post", "pre") or lit.positive:
                    raise arg.at.error(
                        "the wildcard '_' is only allowed in a negative postcondition "
                        "or precondition",
                        "write e.g. 'post: not near(_), near(l)' or 'pre: not blocks(_, t)'",
                    )
                continue
            arg_type = self._arg_type(arg, lit, part)
            if not self.types.related(arg_type, param.type):
                raise arg.at.error(
                    f"'{arg.text}' is {article(arg_type)}, "
                    f"but {predicate.name} expects {article(param.type)} here"
                )
        return lit.literal()

    def _arg_type(self, arg: Name, lit: LiteralSyntax, part: str) -> str:
        if arg.text in self.scope:
            return self.scope[arg.text]
        params = [self._variable(p) for p in sorted(set(self.scope) - self.constants)]
        hint = suggest(arg.text, self.scope) or (
            f"the parameters of {self.action} are {', '.join(params)}"
            if params
            else f"{self.action} has no parameters"
        )
        if part == "post":
            raise arg.at.error(
                f"unbound variable '{arg.text}' in a postcondition of {self.action}", hint
            )
        raise arg.at.error(
            f"'{arg.text}' is neither a parameter of {self.action} nor a constant", hint
        )


def written_in_pddl(path: str, line_text: str | None) -> bool:
    """Whether a place is in a PDDL text: by suffix, else (standard input) by its look."""
    if path.lower().endswith(".pddl"):
        return True
    return not path.lower().endswith(".bt") and (line_text or "").lstrip().startswith("(")


def check_predicate(lit: LiteralSyntax, predicates: Mapping[str, Predicate]) -> Predicate:
    """The declared predicate of a literal, with the right number of arguments."""
    name = lit.predicate.text
    predicate = predicates.get(name)
    if predicate is None:
        raise lit.predicate.at.error(f"unknown predicate '{name}'", suggest(name, predicates))
    if len(lit.args) != predicate.arity:
        params = ", ".join(f"{p.name}: {p.type}" for p in predicate.parameters)
        raise lit.predicate.at.error(
            f"{name} takes {predicate.arity} argument{'s' if predicate.arity != 1 else ''}, "
            f"got {len(lit.args)}",
            f"declared as {name}({params})",
        )
    return predicate
