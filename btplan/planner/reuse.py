"""What planning builds from a domain, kept for the next planning call on the same domain.

An acting run plans again and again in one domain (before acting, when stuck, each
time from the state of then), and a library caller plans many goals of one problem.
Each call indexed the effects, grounded the domain into the relaxed model and, when
asked, computed the h^2 mutexes anew: on BTPG's RoboWaiter single goals, 5 of the 6
ms of a call (bench/fixed_cost.py). None of them depends on the goal. The effect index
depends on the domain alone; the grounded actions on the problem's objects and action
costs; the relaxed model also on its static facts (or, grounded by reachability, on
its whole initial state); the mutexes on its whole initial state. A later call whose
task agrees on what a model depends on gets the same model, built once: the models
are read-only once built, but for memos that give the same answers whoever asks.

Kept with the domain object (`Domain.kept`), so they go when it does (a domain read
again from its file is another one), for its last KEPT problems and initial states,
so that a run planning from many states does not keep a model for each.
"""

from __future__ import annotations

from collections import OrderedDict
from collections.abc import Callable, Hashable, Sequence

from btplan.model import ActionTemplate, Atom, Domain, GroundAction, GroundLiteral, Literal, Task
from btplan.classical import RelaxedModel
from btplan.classical import Mutexes

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any, TypeVar

    from btplan.classical import PackedActions
    from btplan.planner.candidates import Partials, Tables, Way

    K = TypeVar("K", bound=Hashable)
    V = TypeVar("V")

KEPT = 4
"""Problems (objects and costs), relaxed models and initial states kept per domain."""

Effects = dict[tuple[str, bool], list[tuple[ActionTemplate, int, Literal]]]


class Grounded:
    """One relaxed model, what is derived from it, and its mutexes per initial state."""

    def __init__(self, reach: bool) -> None:
        self.reach = reach
        """Whether the model holds only the groundings reachable from the initial state."""
        self.relaxed: RelaxedModel | None = None
        self.packed: PackedActions | None = None
        self.packed_bytes: int | None = None
        self.tables: Tables | None = None
        """The relaxed model's groundings tabled per template (candidates.py)."""
        self.ways: dict[GroundLiteral, list[Way]] = {}
        """Per condition, its ways, each with what `tables` answered for it (candidates.py)."""
        self._mutexes: OrderedDict[frozenset[Atom], Mutexes] = OrderedDict()
        self._profiles: OrderedDict[frozenset[Atom], dict[int, Any]] = OrderedDict()

    def mutexes(self, initial: frozenset[Atom], actions: Callable[[], Sequence[GroundAction]],
                domain: Domain) -> Mutexes:
        """The mutexes from `initial`, over `actions` (asked for when first needed)."""
        return _kept(self._mutexes, initial, lambda: Mutexes(actions, initial, domain))

    def profiles(self, initial: frozenset[Atom]) -> dict[int, Any]:
        """What ranking reads from each achiever (achievers.py's profiles, by the
        identity of their action), for the problem's groundings and the mutexes from
        `initial`: the same whichever run asks, so that each run does not take its
        achievers apart again. Typed loosely: this module sits beneath achievers.py."""
        return _kept(self._profiles, initial, dict)


class Problem:
    """The models of the problems with one set of objects and action costs."""

    def __init__(self) -> None:
        self.made: dict[tuple[str, tuple[str, ...]], GroundAction] = {}
        """The grounded actions, by template name and arguments."""
        self._grounded: OrderedDict[Hashable, Grounded] = OrderedDict()
        self.partials: Partials = {}
        """How each condition unifies with the effects of the domain's index (candidates.py)."""

    def grounded(self, task: Task, reach: bool) -> Grounded:
        """The relaxed model's place for `task`, grounded by reachability or not."""
        initial = task.initial_state
        if reach:
            key: Hashable = (True, initial)
        else:
            changing = task.domain.changed_predicates
            key = (False, frozenset([a for a in initial if a.predicate not in changing]))
        return _kept(self._grounded, key, lambda: Grounded(reach))


class Kept:
    """The models of one domain: its effect index, and those of its last problems."""

    def __init__(self, domain: Domain) -> None:
        self.effects: Effects = {}
        """Each template's effects by (predicate, sign): the achievers of a condition."""
        for template in domain.actions:
            for number, effect in enumerate(template.effects):
                key = (effect.predicate, effect.positive)
                self.effects.setdefault(key, []).append((template, number, effect))
        self._problems: OrderedDict[Hashable, Problem] = OrderedDict()

    def problem(self, task: Task) -> Problem:
        """The models of `task`'s objects and action costs."""
        key = (frozenset(task.object_types.items()), frozenset(task.function_values.items()))
        return _kept(self._problems, key, Problem)


def kept_for(domain: Domain) -> Kept:
    """The models kept for `domain` (in `Domain.kept`), made on first use."""
    found = domain.kept.get(__name__)
    if found is None:
        found = domain.kept[__name__] = Kept(domain)
    assert isinstance(found, Kept)
    return found


def _kept(table: OrderedDict[K, V], key: K, make: Callable[[], V]) -> V:
    """`table[key]`, made when missing; the least recently used entry goes beyond KEPT."""
    found = table.get(key)
    if found is None:
        found = table[key] = make()
        if len(table) > KEPT:
            table.popitem(last=False)
    else:
        table.move_to_end(key)
    return found
