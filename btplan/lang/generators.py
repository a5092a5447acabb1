"""Generate planning problems of any size: blocksworld, gripper, logistics, assembly.

They give tests and benchmarks problems of growing size with known structure. Each
generator builds models from an explicit seed, so the same arguments always give the
same text; `render` writes them as PDDL or in the .bt language.
"""

from __future__ import annotations

import itertools
import random
from collections.abc import Callable
from typing import Literal as Choice

from btplan.lang.writers import bt_domain, bt_problem, pddl_domain, pddl_problem
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

Format = Choice["pddl", "bt"]


def lit(text: str) -> Literal:
    """`"not on(x, y)"` -> Literal; a compact way to write the classic domains here."""
    positive = not text.startswith("not ")
    body = text[4:] if not positive else text
    name, _, rest = body.partition("(")
    args = tuple(a.strip() for a in rest.rstrip(")").split(",") if a.strip())
    return Literal(predicate=name.strip(), args=args, positive=positive)


def lits(text: str) -> tuple[Literal, ...]:
    """`"a(x); not b(y)"` -> literals; `;` separates them because `,` separates arguments."""
    return tuple(lit(t.strip()) for t in text.split(";") if t.strip())


def params(text: str) -> tuple[Parameter, ...]:
    """`"x: block, y: block"` -> parameters."""
    out = []
    for item in text.split(","):
        if item.strip():
            name, _, type_ = item.partition(":")
            out.append(Parameter(name=name.strip(), type=type_.strip() or ROOT_TYPE))
    return tuple(out)


def action(name: str, parameters: str, pre: str, post: str) -> ActionTemplate:
    """An action template from compact text: `parameters` as `params` reads them, `pre` and
    `post` as `lits` does (`;` between literals)."""
    return ActionTemplate(
        name=name, parameters=params(parameters), preconditions=lits(pre), effects=lits(post)
    )


def predicate(name: str, parameters: str = "") -> Predicate:
    """A predicate from its name and compact parameters (`"x: block"`); none by default."""
    return Predicate(name=name, parameters=params(parameters))


def types(*pairs: tuple[str, str]) -> tuple[TypeDef, ...]:
    """A domain's type definitions: the root `object` first, then each (name, parent) pair."""
    return (TypeDef(name=ROOT_TYPE, parent=None), *(TypeDef(name=n, parent=p) for n, p in pairs))


def typed(names: list[str], type_: str) -> list[TypedName]:
    """`names`, all of type `type_`: the objects of a generated problem."""
    return [TypedName(name=n, type=type_) for n in names]


# --- blocksworld -----------------------------------------------------------------------

BLOCKSWORLD = Domain(
    name="blocksworld",
    types=types(("block", ROOT_TYPE)),
    predicates=(
        predicate("on", "x: block, y: block"),
        predicate("on_table", "x: block"),
        predicate("clear", "x: block"),
        predicate("holding", "x: block"),
        predicate("hand_empty"),
    ),
    actions=(
        action(
            "pick_up",
            "x: block",
            "clear(x); on_table(x); hand_empty",
            "holding(x); not on_table(x); not clear(x); not hand_empty",
        ),
        action(
            "put_down",
            "x: block",
            "holding(x)",
            "on_table(x); clear(x); hand_empty; not holding(x)",
        ),
        action(
            "stack",
            "x: block, y: block",
            "holding(x); clear(y)",
            "on(x, y); clear(x); hand_empty; not holding(x); not clear(y)",
        ),
        action(
            "unstack",
            "x: block, y: block",
            "on(x, y); clear(x); hand_empty",
            "holding(x); clear(y); not on(x, y); not clear(x); not hand_empty",
        ),
    ),
)
"""The classic four-operator blocksworld, typed."""


def random_towers(blocks: list[str], rng: random.Random) -> list[list[str]]:
    """Split the blocks, shuffled, into towers listed bottom first."""
    order = list(blocks)
    rng.shuffle(order)
    towers: list[list[str]] = []
    for block in order:
        if towers and rng.random() < 0.6:
            towers[-1].append(block)
        else:
            towers.append([block])
    return towers


def tower_facts(towers: list[list[str]]) -> list[Literal]:
    """The facts of `towers` (listed bottom first): each bottom block on the table, each other
    on the one below it, each top clear. The hand is left to the caller."""
    facts = []
    for tower in towers:
        facts.append(lit(f"on_table({tower[0]})"))
        facts.extend(lit(f"on({upper}, {lower})") for lower, upper in itertools.pairwise(tower))
        facts.append(lit(f"clear({tower[-1]})"))
    return facts


def blocksworld(blocks: int, seed: int = 0) -> tuple[Domain, Problem]:
    """Random initial towers and random goal towers; the goal lists every `on` of them."""
    if blocks < 1:
        raise ValueError("blocksworld needs at least one block")
    rng = random.Random(seed)
    names = [f"b{i}" for i in range(1, blocks + 1)]
    init = [*tower_facts(random_towers(names, rng)), lit("hand_empty")]
    goal: list[Literal] = []
    while not goal:
        goal_towers = random_towers(names, rng)
        goal = [x for x in tower_facts(goal_towers) if x.predicate == "on"]
        if blocks == 1:
            goal = [lit(f"on_table({names[0]})")]
    problem = Problem(
        name=f"blocksworld_{blocks}_s{seed}",
        domain=BLOCKSWORLD.name,
        objects=tuple(typed(names, "block")),
        init=tuple(init),
        goal=tuple(goal),
    )
    return BLOCKSWORLD, problem


# --- gripper ---------------------------------------------------------------------------

GRIPPER = Domain(
    name="gripper",
    types=types(("room", ROOT_TYPE), ("ball", ROOT_TYPE), ("gripper", ROOT_TYPE)),
    predicates=(
        predicate("at_robby", "r: room"),
        predicate("at", "b: ball, r: room"),
        predicate("free", "g: gripper"),
        predicate("carry", "b: ball, g: gripper"),
    ),
    actions=(
        action(
            "move", "from: room, to: room", "at_robby(from)", "at_robby(to); not at_robby(from)"
        ),
        action(
            "pick",
            "b: ball, r: room, g: gripper",
            "at(b, r); at_robby(r); free(g)",
            "carry(b, g); not at(b, r); not free(g)",
        ),
        action(
            "drop",
            "b: ball, r: room, g: gripper",
            "carry(b, g); at_robby(r)",
            "at(b, r); free(g); not carry(b, g)",
        ),
    ),
)
"""The gripper domain: a robot with two hands carries balls between rooms."""


def gripper(balls: int, seed: int = 0, rooms: int = 2) -> tuple[Domain, Problem]:
    """Balls start in random rooms and must each reach a different random room."""
    if balls < 1 or rooms < 2:
        raise ValueError("gripper needs at least one ball and two rooms")
    rng = random.Random(seed)
    room_names = [f"room{i}" for i in range(1, rooms + 1)]
    ball_names = [f"ball{i}" for i in range(1, balls + 1)]
    start = {b: rng.choice(room_names) for b in ball_names}
    target = {b: rng.choice([r for r in room_names if r != start[b]]) for b in ball_names}
    init = [lit(f"at_robby({rng.choice(room_names)})"), lit("free(left)"), lit("free(right)")]
    init += [lit(f"at({b}, {start[b]})") for b in ball_names]
    objects = typed(room_names, "room") + typed(ball_names, "ball")
    objects += typed(["left", "right"], "gripper")
    problem = Problem(
        name=f"gripper_{balls}_s{seed}",
        domain=GRIPPER.name,
        objects=tuple(objects),
        init=tuple(init),
        goal=tuple(lit(f"at({b}, {target[b]})") for b in ball_names),
    )
    return GRIPPER, problem


# --- logistics -------------------------------------------------------------------------

LOGISTICS = Domain(
    name="logistics",
    types=types(
        ("physobj", ROOT_TYPE),
        ("place", ROOT_TYPE),
        ("city", ROOT_TYPE),
        ("package", "physobj"),
        ("vehicle", "physobj"),
        ("truck", "vehicle"),
        ("airplane", "vehicle"),
        ("location", "place"),
        ("airport", "place"),
    ),
    predicates=(
        predicate("in_city", "p: place, c: city"),
        predicate("at", "o: physobj, p: place"),
        predicate("in", "k: package, v: vehicle"),
    ),
    actions=(
        action(
            "load_truck",
            "k: package, t: truck, p: place",
            "at(t, p); at(k, p)",
            "in(k, t); not at(k, p)",
        ),
        action(
            "load_airplane",
            "k: package, a: airplane, p: airport",
            "at(k, p); at(a, p)",
            "in(k, a); not at(k, p)",
        ),
        action(
            "unload_truck",
            "k: package, t: truck, p: place",
            "at(t, p); in(k, t)",
            "at(k, p); not in(k, t)",
        ),
        action(
            "unload_airplane",
            "k: package, a: airplane, p: airport",
            "in(k, a); at(a, p)",
            "at(k, p); not in(k, a)",
        ),
        action(
            "drive_truck",
            "t: truck, from: place, to: place, c: city",
            "at(t, from); in_city(from, c); in_city(to, c)",
            "at(t, to); not at(t, from)",
        ),
        action(
            "fly_airplane",
            "a: airplane, from: airport, to: airport",
            "at(a, from)",
            "at(a, to); not at(a, from)",
        ),
    ),
)
"""Typed logistics: trucks drive within a city, airplanes fly between airports."""


def logistics(
    packages: int, seed: int = 0, cities: int = 2, locations: int = 2, airplanes: int = 1
) -> tuple[Domain, Problem]:
    """Each city has one airport, `locations - 1` other places and a truck."""
    if packages < 1 or cities < 1 or locations < 1 or airplanes < 1:
        raise ValueError("logistics needs at least one package, city, location and airplane")
    rng = random.Random(seed)
    city_names = [f"city{c}" for c in range(1, cities + 1)]
    places: dict[str, list[str]] = {
        c: [f"{c}_airport"] + [f"{c}_loc{i}" for i in range(1, locations)] for c in city_names
    }
    all_places = [p for c in city_names for p in places[c]]
    airports = [places[c][0] for c in city_names]
    trucks = [f"truck{i}" for i in range(1, cities + 1)]
    planes = [f"plane{i}" for i in range(1, airplanes + 1)]
    pkgs = [f"pkg{i}" for i in range(1, packages + 1)]
    init = [lit(f"in_city({p}, {c})") for c in city_names for p in places[c]]
    init += [lit(f"at({t}, {rng.choice(places[c])})") for t, c in zip(trucks, city_names)]
    init += [lit(f"at({a}, {rng.choice(airports)})") for a in planes]
    start = {k: rng.choice(all_places) for k in pkgs}
    init += [lit(f"at({k}, {start[k]})") for k in pkgs]
    goal = []
    for k in pkgs:
        choices = [p for p in all_places if p != start[k]] or all_places
        goal.append(lit(f"at({k}, {rng.choice(choices)})"))
    objects = typed(city_names, "city") + typed(airports, "airport")
    objects += typed([p for p in all_places if p not in airports], "location")
    objects += typed(trucks, "truck") + typed(planes, "airplane") + typed(pkgs, "package")
    problem = Problem(
        name=f"logistics_{packages}_s{seed}",
        domain=LOGISTICS.name,
        objects=tuple(objects),
        init=tuple(init),
        goal=tuple(goal),
    )
    return LOGISTICS, problem


def assembly(parts: int, seed: int = 0) -> tuple[Domain, Problem]:
    """k-part assemblies for two arms (btplan.lang.assembly, which uses nothing here)."""
    from btplan.lang.assembly import assembly as generate_assembly

    return generate_assembly(parts, seed)


GENERATORS: dict[str, Callable[..., tuple[Domain, Problem]]] = {
    "assembly": assembly,
    "blocksworld": blocksworld,
    "gripper": gripper,
    "logistics": logistics,
}


def render(domain: Domain, problem: Problem, fmt: Format = "pddl") -> tuple[str, str]:
    """(domain_text, problem_text) in PDDL or in the .bt language."""
    if fmt == "bt":
        return bt_domain(domain), bt_problem(problem)
    return pddl_domain(domain), pddl_problem(problem)


def generate(name: str, fmt: Format = "pddl", seed: int = 0, **size: int) -> tuple[str, str]:
    """(domain_text, problem_text) of a generated problem, e.g. generate("gripper", balls=6)."""
    domain, problem = GENERATORS[name](seed=seed, **size)
    return render(domain, problem, fmt)
