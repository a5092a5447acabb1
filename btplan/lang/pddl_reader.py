"""Read PDDL (STRIPS with typing, negative preconditions, equality and action costs).

btplan/lang/sexpr.py finds the lists and tokens; the meaning is given here, so that any
construct or requirement outside the supported fragment is refused by name, at its
place, instead of being misread. Competition files are read as the competitions meant
them: an effect that deletes and adds the same atom leaves it true (deletes apply
first), `(either a b)` in a predicate's parameters types them by the nearest common
ancestor (a predicate's types only check facts), and `(increase (total-cost) N)` gives
the action's cost; with `:action-costs`, an action without it costs nothing.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from btplan.lang.pddl_types import implicit_types, merged, typed, typed_list
from btplan.lang.sexpr import Group, Item, Word, expect_group, expect_word, place, read_items
from btplan.lang.syntax import (
    ActionSyntax,
    DomainSyntax,
    LiteralSyntax,
    Name,
    Number,
    ParameterSyntax,
    PredicateSyntax,
    ProblemSyntax,
    Source,
    TypedSyntax,
)
from btplan.limits import shorten
from btplan.model import EQUALITY, ROOT_TYPE

SUPPORTED = (":strips", ":typing", ":negative-preconditions", ":equality", ":action-costs")
TOTAL_COST = "total-cost"

NEEDS = {
    "or": ":disjunctive-preconditions",
    "imply": ":disjunctive-preconditions",
    "exists": ":existential-preconditions",
    "forall": ":universal-preconditions",
    "when": ":conditional-effects",
    "increase": ":numeric-fluents",
    "decrease": ":numeric-fluents",
    "assign": ":numeric-fluents",
    "scale-up": ":numeric-fluents",
    "scale-down": ":numeric-fluents",
}
"""Constructs outside the fragment, and the requirement a domain would need for them."""

FRAGMENT = "btplan reads PDDL with " + ", ".join(SUPPORTED) + " and constants"


Units = list[DomainSyntax | ProblemSyntax]


def read_pddl(text: str, path: str) -> Units:
    """Parse PDDL text (a domain, a problem, or both) into located syntax."""
    units: Units = []
    for item in read_items(text, path):
        define = expect_group(item, "a '(define ...)' form")
        expect_word(define.items[0] if define.items else None, define, "define", "'define'")
        kind = define.items[1] if len(define.items) > 1 else None
        if isinstance(kind, Group) and kind.head() == "domain":
            units.append(_domain(define))
        elif isinstance(kind, Group) and kind.head() == "problem":
            units.append(_problem(define))
        else:
            raise place(kind, define).error("expected '(domain NAME)' or '(problem NAME)'")
    return units


# --- small helpers ---------------------------------------------------------------------


def _name(word: Word) -> Name:
    return Name(word.text, word.at)


def _sections(define: Group) -> Iterator[tuple[str, Group]]:
    for item in define.items[2:]:
        group = expect_group(item, "a section such as '(:predicates ...)'", define)
        head = group.items[0] if group.items else None
        if not isinstance(head, Word) or head.kind != "KEYWORD":
            raise place(head, group).error("expected a section keyword such as ':action'")
        yield head.text, group


def _requirements(group: Group) -> tuple[Name, ...]:
    names = []
    for item in group.items[1:]:
        if not isinstance(item, Word) or item.kind != "KEYWORD":
            raise item.at.error("expected a requirement such as ':strips'")
        if item.text not in SUPPORTED:
            raise item.at.error(f"requirement '{shorten(item.text)}' is not supported", FRAGMENT)
        names.append(_name(item))
    return tuple(names)


# --- domain ----------------------------------------------------------------------------


def _domain(define: Group) -> DomainSyntax:
    header = define.items[1]
    assert isinstance(header, Group)
    name = expect_word(
        header.items[1] if len(header.items) > 1 else None, header, None, "the domain's name"
    )
    requirements: list[Name] = []
    types: list[TypedSyntax] = []
    constants: list[TypedSyntax] = []
    predicates: list[PredicateSyntax] = []
    functions: list[PredicateSyntax] = []
    action_groups: list[Group] = []
    for key, group in _sections(define):
        if key == ":requirements":
            requirements.extend(_requirements(group))
        elif key == ":types":
            types.extend(typed(group.items[1:]))
        elif key == ":constants":
            constants.extend(typed(group.items[1:]))
        elif key == ":predicates":
            parents = {t.name.text: t.type.text if t.type else ROOT_TYPE for t in types}
            predicates.extend(_predicate(g, group, parents) for g in group.items[1:])
        elif key == ":functions":
            functions.extend(_functions(group))
        elif key == ":action":
            action_groups.append(group)
        else:
            raise group.items[0].at.error(f"section '{shorten(key)}' is not supported", FRAGMENT)
    constant_names = {c.name.text for c in constants}
    free = ":action-costs" in {r.text for r in requirements}
    return DomainSyntax(
        _name(name),
        requirements=tuple(requirements),
        types=(*merged(types), *implicit_types(types)),
        constants=tuple(constants),
        predicates=tuple(predicates),
        actions=tuple(_action(g, constant_names, free) for g in action_groups),
        functions=tuple(f for f in functions if f.name.text != TOTAL_COST),
    )


def _functions(section: Group) -> list[PredicateSyntax]:
    """`(:functions (total-cost) - number (road-length ?a ?b - place) - number)`."""
    found: list[PredicateSyntax] = []
    items = section.items[1:]
    index = 0
    while index < len(items):
        item = items[index]
        if isinstance(item, Word) and item.text == "-":
            kind = items[index + 1] if index + 1 < len(items) else None
            if not isinstance(kind, Word) or kind.text != "number":
                raise place(kind, section).error("a function's type must be 'number'")
            index += 2
            continue
        found.append(_predicate(item, section, None))
        index += 1
    return found


def _predicate(
    item: Item, section: Group, parents: Mapping[str, str | None] | None
) -> PredicateSyntax:
    group = expect_group(item, "a predicate such as '(on ?x ?y)'", section)
    head = expect_word(group.items[0] if group.items else None, group, None, "a predicate name")
    params = tuple(
        ParameterSyntax(Name(w.text[1:], w.at), _name(t) if t else None)
        for w, t in typed_list(group.items[1:], "VARIABLE", parents)
    )
    return PredicateSyntax(_name(head), params)


def _action(group: Group, constants: set[str], free: bool) -> ActionSyntax:
    name = expect_word(
        group.items[1] if len(group.items) > 1 else None, group, None, "the action's name"
    )
    fields: dict[str, Item] = {}
    items = group.items[2:]
    for index in range(0, len(items), 2):
        key = items[index]
        if not isinstance(key, Word) or key.kind != "KEYWORD":
            raise key.at.error("expected ':parameters', ':precondition' or ':effect'")
        if key.text not in (":parameters", ":precondition", ":effect"):
            raise key.at.error(f"'{shorten(key.text)}' is not supported in an action", FRAGMENT)
        if index + 1 >= len(items):
            raise key.at.error(f"'{key.text}' needs a value")
        fields[key.text] = items[index + 1]
    params_group = fields.get(":parameters")
    variables = (
        typed_list(expect_group(params_group, "a parameter list", group).items, "VARIABLE")
        if params_group is not None
        else []
    )
    renames = _parameter_names([w.text for w, _ in variables], constants)
    params = tuple(
        ParameterSyntax(Name(renames.get(w.text, w.text), w.at), _name(t) if t else None)
        for w, t in variables
    )
    pre = fields.get(":precondition")
    post = fields.get(":effect")
    increases: list[Group] = []
    effects = _literals(post, group, increases) if post is not None else ()
    cost, term = _cost(increases, group, free)
    return ActionSyntax(
        _name(name),
        params,
        pre=_renamed(_literals(pre, group), renames) if pre is not None else (),
        post=_renamed(_delete_then_add(effects), renames),
        cost=cost,
        cost_term=_renamed((term,), renames)[0] if term is not None else None,
    )


def _delete_then_add(effects: tuple[LiteralSyntax, ...]) -> tuple[LiteralSyntax, ...]:
    """Drop the deletes of atoms the same effect adds: PDDL applies deletes first."""
    added = {(e.predicate.text, tuple(a.text for a in e.args)) for e in effects if e.positive}
    return tuple(
        e for e in effects
        if e.positive or (e.predicate.text, tuple(a.text for a in e.args)) not in added
    )


def _cost(
    increases: list[Group], action: Group, free: bool
) -> tuple[Number | None, LiteralSyntax | None]:
    """The action's cost from `(increase (total-cost) N)` or `(increase (total-cost) (f ?x))`."""
    if len(increases) > 1:
        raise increases[1].at.error("an action may increase total-cost once", FRAGMENT)
    if not increases:
        return (Number("0", action.at) if free else None), None
    increase = increases[0]
    target = increase.items[1] if len(increase.items) == 3 else None
    if not isinstance(target, Group) or target.head() != TOTAL_COST or len(target.items) != 1:
        raise increase.at.error(
            "only '(increase (total-cost) ...)' is supported: numeric fluents are not", FRAGMENT)
    amount = increase.items[2]
    if isinstance(amount, Word):
        if amount.kind != "NUMBER" or amount.text.startswith("-"):
            raise amount.at.error("an action's cost is a number, at least 0")
        return Number(amount.text, amount.at), None
    return None, _atom(amount)


def _parameter_names(variables: list[str], constants: set[str]) -> dict[str, str]:
    """`?x` becomes `x`, unless that is a constant's name: then `x_` (PDDL keeps them apart)."""
    renames: dict[str, str] = {}
    for variable in variables:
        name = variable[1:]
        while name in constants or name in renames.values():
            name += "_"
        renames.setdefault(variable, name)
    return renames


def _renamed(
    literals: tuple[LiteralSyntax, ...], renames: dict[str, str]
) -> tuple[LiteralSyntax, ...]:
    return tuple(
        LiteralSyntax(
            lit.predicate,
            tuple(Name(renames.get(a.text, a.text), a.at) for a in lit.args),
            lit.positive,
            lit.at,
        )
        for lit in literals
    )


def _literals(
    item: Item, parent: Group, increases: list[Group] | None = None
) -> tuple[LiteralSyntax, ...]:
    """Flatten a conjunction into literals; iterative, so deep nesting cannot overflow.

    In an effect (`increases` given), `(increase ...)` terms are set aside there.
    """
    out: list[LiteralSyntax] = []
    stack: list[Item] = [item]
    while stack:
        current = expect_group(stack.pop(), "a condition in parentheses", parent)
        head = current.head()
        if not current.items:
            continue
        if head == "and":
            stack.extend(reversed(current.items[1:]))
        elif head == "increase" and increases is not None:
            increases.append(current)
        elif head == "not":
            if len(current.items) != 2:
                raise current.at.error("'not' takes exactly one condition")
            inner = expect_group(current.items[1], "a condition after 'not'", current)
            literal = _atom(inner)
            out.append(LiteralSyntax(literal.predicate, literal.args, False, literal.at))
        else:
            out.append(_atom(current))
    return tuple(out)


def _atom(group: Group) -> LiteralSyntax:
    head = group.items[0] if group.items else None
    if not isinstance(head, Word):
        raise place(head, group).error("expected a predicate name")
    if head.text in NEEDS or head.text in ("and", "not"):
        needs = NEEDS.get(head.text)
        reason = f"it needs the requirement {needs}" if needs else "it is nested too deeply"
        raise head.at.error(f"'{shorten(head.text)}' is not supported here: {reason}", FRAGMENT)
    if head.kind == "SYMBOL" and head.text in ("<", ">", "<=", ">="):
        raise head.at.error(f"numeric comparisons ('{head.text}') are not supported", FRAGMENT)
    if head.kind not in ("NAME", "SYMBOL") or (head.kind == "SYMBOL" and head.text != EQUALITY):
        raise head.at.error(f"expected a predicate name, not '{shorten(head.text)}'")
    args = []
    for arg in group.items[1:]:
        if isinstance(arg, Group):
            raise arg.at.error("expected an object or a variable, not a nested list", FRAGMENT)
        if arg.kind not in ("NAME", "VARIABLE"):
            raise arg.at.error(f"expected an object or a variable, not '{shorten(arg.text)}'")
        args.append(Name(arg.text, arg.at))
    if head.text == EQUALITY and len(args) != 2:
        raise head.at.error("'=' compares exactly two terms")
    return LiteralSyntax(Name(head.text, head.at), tuple(args), True, group.at)


# --- problem ---------------------------------------------------------------------------


def read_goal(text: str, path: str) -> tuple[LiteralSyntax, ...]:
    """A goal written alone, as a problem's `:goal` condition: `(on a b)` or
    `(and (on a b) (not (clear c)))`."""
    items = read_items(text, path)
    if not items:
        raise Source(text, path).start().error("the goal is empty",
                                               "write a condition such as '(on a b)'")
    if len(items) > 1:
        raise items[1].at.error("a goal is one condition", "join several with (and ...)")
    goal = expect_group(items[0], "a condition in parentheses, such as '(on a b)'")
    return _literals(goal, goal)


def _problem(define: Group) -> ProblemSyntax:
    header = define.items[1]
    assert isinstance(header, Group)
    name = expect_word(
        header.items[1] if len(header.items) > 1 else None, header, None, "the problem's name"
    )
    domain: Word | None = None
    objects: list[TypedSyntax] = []
    init: list[LiteralSyntax] = []
    values: list[tuple[LiteralSyntax, Number]] = []
    goal: tuple[LiteralSyntax, ...] = ()
    for key, group in _sections(define):
        if key == ":domain":
            domain = expect_word(
                group.items[1] if len(group.items) > 1 else None, group, None, "the domain's name"
            )
        elif key == ":requirements":
            _requirements(group)
        elif key == ":objects":
            objects.extend(typed(group.items[1:]))
        elif key == ":init":
            for fact in group.items[1:]:
                if isinstance(fact, Group) and fact.head() == EQUALITY and _is_value(fact):
                    value = _value(fact)
                    if value is not None:
                        values.append(value)
                else:
                    init.extend(_literals(fact, group))
        elif key == ":metric":
            _metric(group)
        elif key == ":goal":
            if len(group.items) != 2:
                raise group.at.error("':goal' takes one condition", "join several with (and ...)")
            goal = _literals(group.items[1], group)
        else:
            raise group.items[0].at.error(f"section '{shorten(key)}' is not supported", FRAGMENT)
    if domain is None:
        raise define.at.error("the problem does not say its domain", "add '(:domain NAME)'")
    return ProblemSyntax(
        _name(name), _name(domain), tuple(objects), tuple(init), goal, tuple(values))


def _is_value(fact: Group) -> bool:
    return len(fact.items) == 3 and isinstance(fact.items[1], Group)


def _value(fact: Group) -> tuple[LiteralSyntax, Number] | None:
    """`(= (road-length a b) 12)`; the start value of total-cost is not kept."""
    term, number = fact.items[1], fact.items[2]
    assert isinstance(term, Group)
    if not isinstance(number, Word) or number.kind != "NUMBER":
        raise place(number, fact).error("expected a number")
    if term.head() == TOTAL_COST:
        return None
    return _atom(term), Number(number.text, number.at)


def _metric(group: Group) -> None:
    """Only `(:metric minimize (total-cost))`: the sum of action costs."""
    items = group.items[1:]
    term = items[1] if len(items) == 2 else None
    if (not items or not isinstance(items[0], Word) or items[0].text != "minimize"
            or not isinstance(term, Group) or term.head() != TOTAL_COST or len(term.items) != 1):
        raise group.at.error(
            "only '(:metric minimize (total-cost))' is supported", FRAGMENT)
