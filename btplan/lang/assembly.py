"""Generate k-part assemblies for the two-armed robot of the paper's Yumi scenario.

The paper's point with that scenario is that backchaining scales to long plans and
finds regrasp and handover chains by itself. These problems let a benchmark grow k:
every part lies at a random spot with its opening up or down (down needs a handover),
and must be mounted after one or two random earlier parts. The domain is the one of
`domains/yumi.bt`, except that its static relations are preconditions rather than
`where` constraints, so that the .bt and the PDDL text describe the same model, and
the handover has no `giver != taker`: an arm never holds a part while free, so handing
to itself never applies, and the constraint would keep pyperplan (no negative
preconditions) from reading the problems it is compared on.
"""

from __future__ import annotations

import random

from btplan.model import (
    ROOT_TYPE,
    ActionTemplate,
    Domain,
    Literal,
    Parameter,
    Predicate,
    Problem,
    TypeDef,
    TypedName,
)

ARMS = ("left", "right")
PLACES = ("left_side", "right_side", "middle")
REACH = (("left", "left_side"), ("left", "middle"), ("right", "right_side"), ("right", "middle"))
BASE = "base"


def _lit(text: str) -> Literal:
    positive = not text.startswith("not ")
    name, _, rest = (text if positive else text[4:]).partition("(")
    args = tuple(a.strip() for a in rest.rstrip(")").split(",") if a.strip())
    return Literal(predicate=name.strip(), args=args, positive=positive)


def _lits(text: str) -> tuple[Literal, ...]:
    return tuple(_lit(t.strip()) for t in text.split(";") if t.strip())


def _params(text: str) -> tuple[Parameter, ...]:
    pairs = (item.split(":") for item in text.split(","))
    return tuple(Parameter(name=n.strip(), type=t.strip()) for n, t in pairs)


def _action(name: str, params: str, pre: str, post: str) -> ActionTemplate:
    return ActionTemplate(name=name, parameters=_params(params),
                          preconditions=_lits(pre), effects=_lits(post))


ASSEMBLY = Domain(
    name="assembly",
    types=(
        TypeDef(name=ROOT_TYPE, parent=None),
        *(TypeDef(name=n, parent=ROOT_TYPE) for n in ("arm", "spot", "face", "grasp", "item")),
        TypeDef(name="part", parent="item"),
        TypeDef(name="fixture", parent="item"),
    ),
    constants=(
        TypedName(name="up", type="face"), TypedName(name="down", type="face"),
        TypedName(name="away", type="grasp"), TypedName(name="toward", type="grasp"),
    ),
    predicates=(
        Predicate(name="lies", parameters=_params("p: part, s: spot, f: face")),
        Predicate(name="holds", parameters=_params("a: arm, p: part, g: grasp")),
        Predicate(name="free", parameters=_params("a: arm")),
        Predicate(name="mounted", parameters=_params("i: item")),
        Predicate(name="reaches", parameters=_params("a: arm, s: spot")),
        Predicate(name="grasp_of", parameters=_params("f: face, g: grasp")),
        Predicate(name="turned", parameters=_params("g: grasp, h: grasp")),
        Predicate(name="needs", parameters=_params("p: part, q: item, r: item")),
        Predicate(name="mounts", parameters=_params("a: arm")),
    ),
    actions=(
        _action("pick", "p: part, a: arm, s: spot, f: face, g: grasp",
                "reaches(a, s); grasp_of(f, g); lies(p, s, f); free(a)",
                "holds(a, p, g); not lies(p, s, f); not free(a)"),
        _action("place", "p: part, a: arm, s: spot, f: face, g: grasp",
                "reaches(a, s); grasp_of(f, g); holds(a, p, g)",
                "lies(p, s, f); free(a); not holds(a, p, g)"),
        _action("handover", "p: part, giver: arm, taker: arm, g: grasp, h: grasp",
                "turned(g, h); holds(giver, p, g); free(taker)",
                "holds(taker, p, h); free(giver); not holds(giver, p, g); not free(taker)"),
        _action("insert", "p: part, a: arm, q: item, r: item",
                "needs(p, q, r); mounts(a); mounted(q); mounted(r); holds(a, p, away)",
                "mounted(p); free(a); not holds(a, p, away)"),
    ),
)
"""The Yumi domain with static relations as preconditions (PDDL has no `where`)."""


def assembly(parts: int, seed: int = 0) -> tuple[Domain, Problem]:
    """k parts at random spots and faces, each needing one or two random earlier parts.

    The goal lists every part, in random order: the tree must find the mounting order
    from the `needs` relation, not from the goal's order.
    """
    if parts < 1:
        raise ValueError("an assembly needs at least one part")
    rng = random.Random(seed)
    names = [f"part{i}" for i in range(1, parts + 1)]
    order = list(names)
    rng.shuffle(order)
    init = [_lit(f"free({a})") for a in ARMS]
    init += [_lit(f"reaches({a}, {s})") for a, s in REACH]
    init += _lits("grasp_of(up, away); grasp_of(down, toward)")
    init += _lits("turned(away, toward); turned(toward, away)")
    init.append(_lit(f"mounted({BASE})"))
    init += [_lit(f"mounts({a})") for a in ARMS]
    for i, part in enumerate(order):
        earlier = rng.sample(order[:i], min(i, rng.choice((1, 2)))) if i else [BASE]
        q, r = sorted(earlier)[0], sorted(earlier)[-1]
        init.append(_lit(f"needs({part}, {q}, {r})"))
    for part in names:
        init.append(_lit(f"lies({part}, {rng.choice(PLACES)}, {rng.choice(('up', 'down'))})"))
    goal = list(names)
    rng.shuffle(goal)
    objects = [TypedName(name=a, type="arm") for a in ARMS]
    objects += [TypedName(name=s, type="spot") for s in PLACES]
    objects.append(TypedName(name=BASE, type="fixture"))
    objects += [TypedName(name=p, type="part") for p in names]
    problem = Problem(
        name=f"assembly_{parts}_s{seed}",
        domain=ASSEMBLY.name,
        objects=tuple(objects),
        init=tuple(init),
        goal=tuple(_lit(f"mounted({p})") for p in goal),
    )
    return ASSEMBLY, problem
