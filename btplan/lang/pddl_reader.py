"""Read PDDL (STRIPS with typing, negative preconditions and equality) into located syntax.

btplan/lang/sexpr.py finds the lists and tokens; the meaning is given here, so that any
construct or requirement outside the supported fragment is refused by name, at its
place, instead of being misread.
"""

from __future__ import annotations

from collections.abc import Iterator

from btplan.lang.sexpr import Group, Item, Word, expect_group, expect_word, place, read_items
from btplan.lang.syntax import (
    ActionSyntax,
    DomainSyntax,
    LiteralSyntax,
    Name,
    ParameterSyntax,
    PredicateSyntax,
    ProblemSyntax,
    TypedSyntax,
)
from btplan.limits import shorten
from btplan.model import EQUALITY, ROOT_TYPE

SUPPORTED = (":strips", ":typing", ":negative-preconditions", ":equality")

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


def _typed_list(items: tuple[Item, ...], kind: str) -> list[tuple[Word, Word | None]]:
    """`a b - t c` -> [(a, t), (b, t), (c, None)]; `kind` is NAME or VARIABLE."""
    out: list[tuple[Word, Word | None]] = []
    pending: list[Word] = []
    index = 0
    while index < len(items):
        item = items[index]
        if isinstance(item, Word) and item.text == "-":
            type_item = items[index + 1] if index + 1 < len(items) else None
            if isinstance(type_item, Group) and type_item.head() == "either":
                raise type_item.at.error("'either' types are not supported", FRAGMENT)
            if not isinstance(type_item, Word) or type_item.kind != "NAME":
                raise (type_item or item).at.error("expected a type name after '-'")
            if not pending:
                raise item.at.error("a type after '-' must follow the names it types")
            out.extend((w, type_item) for w in pending)
            pending = []
            index += 2
            continue
        if not isinstance(item, Word) or item.kind != kind:
            expected = "a variable such as ?x" if kind == "VARIABLE" else "a name"
            raise item.at.error(f"expected {expected}")
        pending.append(item)
        index += 1
    out.extend((w, None) for w in pending)
    return out


def _typed(items: tuple[Item, ...]) -> tuple[TypedSyntax, ...]:
    return tuple(
        TypedSyntax(_name(w), _name(t) if t else None) for w, t in _typed_list(items, "NAME")
    )


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
    action_groups: list[Group] = []
    for key, group in _sections(define):
        if key == ":requirements":
            requirements.extend(_requirements(group))
        elif key == ":types":
            types.extend(_typed(group.items[1:]))
        elif key == ":constants":
            constants.extend(_typed(group.items[1:]))
        elif key == ":predicates":
            predicates.extend(_predicate(g, group) for g in group.items[1:])
        elif key == ":action":
            action_groups.append(group)
        else:
            raise group.items[0].at.error(f"section '{shorten(key)}' is not supported", FRAGMENT)
    constant_names = {c.name.text for c in constants}
    return DomainSyntax(
        _name(name),
        requirements=tuple(requirements),
        types=(*types, *_implicit_types(types)),
        constants=tuple(constants),
        predicates=tuple(predicates),
        actions=tuple(_action(g, constant_names) for g in action_groups),
    )


def _implicit_types(declared: list[TypedSyntax]) -> list[TypedSyntax]:
    """Parents named only after '-' (`truck car - vehicle`): PDDL declares them too."""
    names = {t.name.text for t in declared} | {ROOT_TYPE}
    implicit: dict[str, TypedSyntax] = {}
    for entry in declared:
        if entry.type is not None and entry.type.text not in names:
            implicit.setdefault(entry.type.text, TypedSyntax(entry.type, None))
    return list(implicit.values())


def _predicate(item: Item, section: Group) -> PredicateSyntax:
    group = expect_group(item, "a predicate such as '(on ?x ?y)'", section)
    head = expect_word(group.items[0] if group.items else None, group, None, "a predicate name")
    params = tuple(
        ParameterSyntax(Name(w.text[1:], w.at), _name(t) if t else None)
        for w, t in _typed_list(group.items[1:], "VARIABLE")
    )
    return PredicateSyntax(_name(head), params)


def _action(group: Group, constants: set[str]) -> ActionSyntax:
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
        _typed_list(expect_group(params_group, "a parameter list", group).items, "VARIABLE")
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
    return ActionSyntax(
        _name(name),
        params,
        pre=_renamed(_literals(pre, group), renames) if pre is not None else (),
        post=_renamed(_literals(post, group), renames) if post is not None else (),
    )


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


def _literals(item: Item, parent: Group) -> tuple[LiteralSyntax, ...]:
    """Flatten a conjunction into literals; iterative, so deep nesting cannot overflow."""
    out: list[LiteralSyntax] = []
    stack: list[Item] = [item]
    while stack:
        current = expect_group(stack.pop(), "a condition in parentheses", parent)
        head = current.head()
        if not current.items:
            continue
        if head == "and":
            stack.extend(reversed(current.items[1:]))
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


def _problem(define: Group) -> ProblemSyntax:
    header = define.items[1]
    assert isinstance(header, Group)
    name = expect_word(
        header.items[1] if len(header.items) > 1 else None, header, None, "the problem's name"
    )
    domain: Word | None = None
    objects: list[TypedSyntax] = []
    init: list[LiteralSyntax] = []
    goal: tuple[LiteralSyntax, ...] = ()
    for key, group in _sections(define):
        if key == ":domain":
            domain = expect_word(
                group.items[1] if len(group.items) > 1 else None, group, None, "the domain's name"
            )
        elif key == ":requirements":
            _requirements(group)
        elif key == ":objects":
            objects.extend(_typed(group.items[1:]))
        elif key == ":init":
            for fact in group.items[1:]:
                init.extend(_literals(fact, group))
        elif key == ":goal":
            if len(group.items) != 2:
                raise group.at.error("':goal' takes one condition", "join several with (and ...)")
            goal = _literals(group.items[1], group)
        else:
            raise group.items[0].at.error(f"section '{shorten(key)}' is not supported", FRAGMENT)
    if domain is None:
        raise define.at.error("the problem does not say its domain", "add '(:domain NAME)'")
    return ProblemSyntax(_name(name), _name(domain), tuple(objects), tuple(init), goal)
