"""The values a state allows for a parameter (`Objects.values`, read by grounding), the
same as reading every atom of the predicate, in any state asked in turn."""

from __future__ import annotations

import random

from btplan.model import Atom
from btplan.grounding import Objects


def scan(state: frozenset[Atom], predicate: str, args: list[str | None],
         at: tuple[int, ...]) -> set[str]:
    """What `values` answers, read from every atom."""
    out: set[str] = set()
    for atom in state:
        if atom.predicate != predicate or len(atom.args) != len(args):
            continue
        if all(want is None or want == got for want, got in zip(args, atom.args)):
            seen = {atom.args[i] for i in at}
            if len(seen) == 1:
                out |= seen
    return out


def test_values_agree_with_reading_every_atom() -> None:
    state = frozenset({Atom("road", ("a", "b")), Atom("road", ("b", "c")),
                       Atom("road", ("c", "c")), Atom("road", ("a", "c")),
                       Atom("at", ("a",)), Atom("road", ("a", "b", "x"))})
    table = Objects(None)  # type: ignore[arg-type]  # values and atoms read no task
    for args, at in [(["a", None], (1,)), ([None, "c"], (0,)), ([None, None], (0, 1)),
                     ([None, None], (0,)), (["c", None], (1,)), (["d", None], (1,))]:
        assert set(table.values(state, "road", args, at)) == scan(state, "road", args, at)
    assert set(table.values(state, "road", [None, None], (0, 1))) == {"c"}  # road(c, c)


def test_a_new_state_is_indexed_anew() -> None:
    rng = random.Random(0)
    places = ["p0", "p1", "p2", "p3"]
    table = Objects(None)  # type: ignore[arg-type]
    for _ in range(20):
        state = frozenset(Atom("road", (rng.choice(places), rng.choice(places)))
                          for _ in range(6))
        for first in [*places, None]:
            args = [first, None]
            assert set(table.values(state, "road", args, (1,))) == scan(
                state, "road", args, (1,))
