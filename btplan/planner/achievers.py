"""Finding the grounded actions that make a condition true: GetAllActTemplatesFor.

The domain is indexed by the predicate and sign of each effect, so the achievers of
a condition are found without scanning every action (Algorithm 2, line 2). Each
matching effect is unified with the condition, the remaining parameters are bound
(`grounding.bindings`, or read from the relaxed model's groundings, candidates.py), and
the groundings are ranked best first. Each expansion looks achievers up again, in a new
state, so what does not depend on the state (the unification, the static checks, what
ranking reads from an action, mutex verdicts) is worked out once per task.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping

from btplan.model import (
    WILDCARD,
    ActionTemplate,
    Atom,
    GroundAction,
    GroundLiteral,
    Literal,
    Task,
    matches,
)
from btplan.planner.candidates import StaticBindings, Tables, Way
from btplan.planner.expand import circular, non_circular
from btplan.grounding import Objects, bindings
from btplan.classical import RelaxedModel
from btplan.classical import Mutexes
from btplan.planner.options import PlannerOptions
from btplan.planner.protocol import Refiner
from btplan.collector import building
from btplan.planner.reuse import Grounded, kept_for

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.classical import PackedActions
    from btplan.classical import SubgoalSearch

ALL = 1 << 30
"""A limit on achievers that keeps them all."""


SEARCH_BYTES = 256 << 20
"""The most memory the groundings as bit masks may take for the last-resort searches
(`fits_search`): a planner that needs two steps should not take a gigabyte because the
problem is wide."""


class _Shared:
    """What does not depend on the options: built once per task and shared; the models
    among them come from those kept for the domain (btplan/planner/reuse.py)."""

    def __init__(self, task: Task) -> None:
        self.kept = kept_for(task.domain)
        self.problem = self.kept.problem(task)
        self.objects: Objects | None = None
        self.made = self.problem.made
        self.grounded: Grounded | None = None
        """Where the relaxed model is kept: chosen by the first index that needs it."""
        self.relaxed: RelaxedModel | None = None
        self.mutexes: Mutexes | None = None
        self.search: SubgoalSearch | None = None
        self.packed_asked = False
        self.static: StaticBindings | None = None
        self.profiles: Profiles | None = None
        """Those kept with the mutexes they judge by (reuse.py), once asked for."""


class AchieverIndex:
    """Effects of the domain indexed by (predicate, sign), with a lazily built h_add model."""

    def __init__(
        self, task: Task, options: PlannerOptions | None = None, like: AchieverIndex | None = None,
        reachable_only: bool = False,
    ) -> None:
        """`like`: an index of the same task whose groundings, relaxed model and mutexes
        are shared (built once, however many planning attempts use them). Without it,
        they are those of an earlier index of the same domain whose task agrees on
        what each depends on (reuse.py), or built when first needed.

        `reachable_only`: the relaxed model keeps only the groundings relaxed-reachable
        from the initial state. Right only where nothing but the plan changes the state
        (offline planning): an outside agent can make true what no action reaches, and
        the achievers that need it must stay known."""
        self.task = task
        self.reachable_only = reachable_only
        self.options = options or PlannerOptions()
        self._shared: _Shared = like._shared if like is not None else _Shared(task)
        self._by_effect = self._shared.kept.effects
        self.objects = self._shared.objects or Objects(task)
        self._shared.objects = self.objects
        self.static = self._shared.static or StaticBindings(task, self.objects)
        self._shared.static = self.static

    def _grounded(self) -> Grounded:
        """Where the relaxed model of these indexes is kept: the first to need it says
        whether it is grounded by reachability."""
        shared = self._shared
        if shared.grounded is None:
            shared.grounded = shared.problem.grounded(self.task, self.reachable_only)
        return shared.grounded

    @property
    def relaxed(self) -> RelaxedModel:
        """The task's h_add model, built on first use and shared with every index made `like`
        this one; with `reachable_only`, only groundings reachable from the initial state."""
        shared = self._shared
        if shared.relaxed is None:
            grounded = self._grounded()
            if grounded.relaxed is None:
                grounded.relaxed = RelaxedModel(self.task, objects=self.objects,
                                                ground=self.ground, reach=grounded.reach)
            shared.relaxed = grounded.relaxed
        return shared.relaxed

    def ground(self, template: ActionTemplate, args: tuple[str, ...]) -> GroundAction:
        """`instantiate`, remembered: the same groundings come up on every expansion."""
        made = self._shared.made
        action = made.get((template.name, args))
        if action is None:
            action = made[(template.name, args)] = self.task.instantiate(template, args)
        return action

    @property
    def groundings(self) -> dict[tuple[str, tuple[str, ...]], GroundAction]:
        """What `ground` made, by action name and arguments, kept for the task's problem
        (reuse.py): a symbolic world grounding the actions it runs can share them, as the
        next planning call's worlds then find them made."""
        return self._shared.made

    def has_effect(self, condition: GroundLiteral) -> bool:
        """Whether any action template has an effect of this predicate and sign."""
        return bool(self._by_effect.get((condition.atom.predicate, condition.positive)))

    @property
    def mutexes(self) -> Mutexes:
        """h^2 mutexes from the initial state, computed when first asked a question that
        needs them (mutex.Mutexes), from the relaxed model's groundings."""
        shared = self._shared
        if shared.mutexes is None:
            shared.mutexes = self._grounded().mutexes(
                self.task.initial_state, lambda: self.relaxed.actions, self.task.domain)
        return shared.mutexes

    @property
    def subgoal_search(self) -> SubgoalSearch:
        """The last-resort search over the relaxed model's groundings, built on first use."""
        shared = self._shared
        if shared.search is None:
            from btplan.classical import SubgoalSearch  # the last resort: rarely needed

            relaxed = self.relaxed
            with building():
                shared.search = SubgoalSearch(relaxed.actions)
            shared.search.exclusive = lambda a, b: self.mutexes.exclusive(
                GroundLiteral(a), GroundLiteral(b))  # the mutexes built when first asked
        return shared.search

    @property
    def packed_bytes(self) -> int:
        """About how many bytes `packed` takes (or would): each action's masks are ints
        as long as its highest atom number, so actions times atoms, over two. A
        100-block blocksworld's 20,000 actions over 10,000 atoms took about 110 MB;
        gripper with 10,000 balls would take 1.6 GB."""
        grounded = self._grounded()
        if grounded.packed_bytes is None:
            actions = self.relaxed.actions
            atoms = len({a for action in actions for a in (*action.add, *action.delete)})
            grounded.packed_bytes = len(actions) * atoms // 2
        return grounded.packed_bytes

    def fits_search(self) -> bool:
        """Whether the search over every grounding (`subgoal_search`) fits SEARCH_BYTES;
        on a wider problem the last resorts are left out rather than the memory used up."""
        return self.has_packed or self.packed_bytes <= SEARCH_BYTES

    @property
    def has_packed(self) -> bool:
        """Whether `packed` is built already (by the search, or on its own) for these
        indexes (one an earlier planning call built is not counted: what a call does
        depends on its task alone)."""
        return self._shared.search is not None or self._shared.packed_asked

    @property
    def packed(self) -> PackedActions:
        """The relaxed model's groundings as bit masks (those the search holds: none that
        deletes by pattern), the search's own when it was built, else built on first use."""
        shared = self._shared
        if shared.search is not None:
            return shared.search.packed
        shared.packed_asked = True
        grounded = self._grounded()
        if grounded.packed is None:
            from btplan.classical import PackedActions

            relaxed = self.relaxed
            with building():
                grounded.packed = PackedActions([a for a in relaxed.actions
                                                 if not a.delete_patterns])
        return grounded.packed

    def achievers(
        self,
        condition: GroundLiteral,
        state: frozenset[Atom],
        refine: Refiner | None,
        limit: int | None = None,
    ) -> list[GroundAction]:
        """Grounded actions whose effects make `condition` hold, best first, bounded.

        Ranking (the paper leaves the order open; its Remark suggests cheap first):
        cost plus, with the heuristic on, the h_add estimate of the preconditions;
        then the number of preconditions that fail now; then the name, for ties.
        """
        if not condition.positive and WILDCARD in condition.atom.args:
            # `not blocks(_, t)`: undo each instance that holds now; guards() says which.
            undoing: dict[tuple[str, tuple[str, ...]], GroundAction] = {}
            for atom in instances(condition, state):
                for action in self.achievers(GroundLiteral(atom, False), state, refine, ALL):
                    undoing.setdefault(action.key, action)
            return self._best(list(undoing.values()), state, limit, False)
        return self._best(self._found(condition, state, refine), state, limit,
                          self.options.mutexes)

    def achievers_avoiding(
        self, condition: GroundLiteral, state: frozenset[Atom], refine: Refiner | None,
        pursued: Collection[GroundLiteral],
    ) -> tuple[list[GroundAction], bool]:
        """`achievers(..., ALL)` without those that need a `pursued` condition
        (expand.non_circular), and whether it had some and all were dropped.

        Dropping keeps the order, so the circular ones are dropped before ranking
        instead of after: they are never ranked, but for telling, when no other is
        left, whether ranking would have kept one (the message of a stuck condition
        says so)."""
        if not condition.positive and WILDCARD in condition.atom.args:
            ranked = self.achievers(condition, state, refine, ALL)
            left = non_circular(ranked, pursued)
            return left, bool(ranked) and not left
        kept: list[GroundAction] = []
        dropped: list[GroundAction] = []
        for action in self._found(condition, state, refine):
            (dropped if circular(action, pursued) else kept).append(action)
        drop = self.options.mutexes
        ranked = self._best(kept, state, ALL, drop)
        if ranked or not dropped:
            return ranked, False
        return [], bool(self._best(dropped, state, ALL, drop, first=True))

    def _found(self, condition: GroundLiteral, state: frozenset[Atom], refine: Refiner | None
               ) -> list[GroundAction]:
        """The groundings that make a condition without wildcards true, unranked."""
        reachable = self.relaxed.costs(state) if self.options.prune_bindings else None
        found: dict[int, GroundAction] = {}  # by identity: `ground` makes one per key
        relaxed = self._shared.relaxed  # its groundings, when something built it already
        limit_bindings = self.options.max_bindings
        effects = self._by_effect.get((condition.atom.predicate, condition.positive), [])
        tables = store = None
        if relaxed is not None:
            tables = self._tables(relaxed)
            store = self._grounded().ways  # prepared against those tables: kept with them
        for way in self.static.ways(condition, effects, self._shared.problem.partials, store):
            picked = None
            if relaxed is not None:
                picked = self.static.pick(way, state, reachable, limit_bindings, relaxed.actions,
                                          lambda action: _makes_true(action, condition), tables)
            if picked is None:
                picked = self._enumerate(way, condition, state, refine, reachable)
            for action in picked:
                found.setdefault(id(action), action)
        return list(found.values())

    def _tables(self, relaxed: RelaxedModel) -> Tables:
        """The tables of `relaxed`'s groundings, kept with it for the next calls."""
        grounded = self._grounded()
        assert grounded.relaxed is relaxed
        if grounded.tables is None:
            grounded.tables = Tables(relaxed.actions, self.task.domain.changed_predicates)
        return grounded.tables

    def _enumerate(
        self, way: Way, condition: GroundLiteral, state: frozenset[Atom], refine: Refiner | None,
        reachable: dict[Atom, float] | None,
    ) -> list[GroundAction]:
        """The groundings of `way` that make `condition`, bound one parameter at a time
        (grounding.bindings), for when the static bindings cannot tell (candidates.py)."""
        template = way.template
        made = [self.ground(template, tuple(binding[p.name] for p in template.parameters))
                for binding in bindings(self.task, template, way.partial, state, refine,
                                        self.options.max_bindings, self.objects,
                                        reachable=reachable)]
        return [a for a in made if _makes_true(a, condition)]

    def _profiles(self) -> Profiles:
        """The profiles of the task's groundings (`_Profile`), kept with its mutexes."""
        shared = self._shared
        if shared.profiles is None:
            shared.profiles = self._grounded().profiles(self.task.initial_state)
        return shared.profiles

    def _impossible(self, action: GroundAction) -> bool:
        """Whether two preconditions of `action` exclude each other (h^2): it never runs.

        Barman's fill-shot(shot1, i, left, left, d) needs holding(left, shot1) and
        handempty(left); h_add ranks it like any other grounding. Remembered per action:
        the mutexes hold for the whole task.
        """
        profile = self._profile(action)
        if profile.impossible is None:
            profile.impossible = self.mutexes.any_exclusive(profile.positive)
        return profile.impossible

    def _best(self, candidates: list[GroundAction], state: frozenset[Atom], limit: int | None,
              drop_impossible: bool, first: bool = False) -> list[GroundAction]:
        """The candidates best first, those that cannot run or reach left out, bounded;
        with `first`, only the first one found that is not left out (unranked).

        The rank: cost plus the h_add estimate of the preconditions false now, then how
        many preconditions fail now, then the name (no two actions share it, so the order
        is total). Values a backend refined (poses, trajectories) are unknown to the
        relaxed model: preconditions on them are counted instead of called unreachable.
        """
        heuristic = self.options.heuristic
        cost: dict[Atom, float] | None = None
        inf = math.inf
        profiles = self._profiles()  # `_profile`, written out: it runs per candidate
        known = self.task.object_types
        scored: list[tuple[tuple[float, int, str], GroundAction]] = []
        for action in candidates:
            profile = profiles.get(id(action))
            if profile is None or profile.action is not action:
                profile = profiles[id(action)] = _Profile(action, known)
            if drop_impossible and (profile.impossible if profile.impossible is not None
                                    else self._impossible(action)):
                continue
            missing = [a for a in profile.positive if a not in state]
            failing = len(missing)
            if profile.negative:
                failing += sum(1 for p in profile.negative if not p.holds(state))
            estimate = 0.0
            if heuristic and missing:
                if profile.unknown and not profile.unknown.isdisjoint(missing):
                    estimate = float(len(missing))
                else:
                    if cost is None:
                        cost = self.relaxed.costs(state)
                    get = cost.get
                    for atom in missing:
                        estimate += get(atom, inf)
            total = profile.cost + estimate
            if total < inf:
                if first:
                    return [action]
                scored.append(((total, failing, profile.label), action))
        scored.sort(key=_score)
        return [a for _, a in scored][: limit or self.options.max_alternatives]

    def _profile(self, action: GroundAction) -> _Profile:
        """Kept by identity: `ground` makes one action per key, and the profile keeps
        its action alive, so that the identity is not reused."""
        profiles = self._profiles()
        profile = profiles.get(id(action))
        if profile is None or profile.action is not action:
            profile = profiles[id(action)] = _Profile(action, self.task.object_types)
        return profile


class _Profile:
    """What ranking reads from an achiever, taken apart once: the same achievers are
    ranked again on every look-up, in every state."""

    __slots__ = ("action", "cost", "impossible", "label", "negative", "positive", "unknown")

    def __init__(self, action: GroundAction, known: Mapping[str, str]) -> None:
        self.action = action
        self.impossible: bool | None = None
        """Whether two preconditions exclude each other (`_impossible`), once asked."""
        self.cost = action.cost
        self.label = str(action)
        self.positive = action.needs
        """In order, a precondition written twice counted twice (as the sum always did)."""
        self.negative = tuple(p for p in action.preconditions if not p.positive)
        has = known.__contains__
        self.unknown = frozenset([atom for atom in self.positive
                                  if not all(map(has, atom.args))])


Profiles = dict[int, _Profile]
"""Profiles by the identity of their action (`AchieverIndex._profile`)."""


def _score(scored: tuple[tuple[float, int, str], GroundAction]) -> tuple[float, int, str]:
    return scored[0]


def instances(condition: GroundLiteral, state: frozenset[Atom]) -> list[Atom]:
    """The atoms of `state` that a wildcard condition's pattern matches, sorted."""
    return sorted(a for a in state if matches(condition.atom, a))


def guards(action: GroundAction, condition: GroundLiteral, state: frozenset[Atom]
           ) -> tuple[GroundLiteral, ...]:
    """What an achiever of a wildcard condition is for: the instances it undoes.

    `not blocks(_, t)` is achieved by undoing each `blocks(c, t)` that holds; the
    alternative for c is guarded by `blocks(c, t)`, so that once c is out of the way it
    is not run again (picking c back up) when another object blocks t later.
    """
    if condition.positive or WILDCARD not in condition.atom.args:
        return ()
    return tuple(GroundLiteral(a, True) for a in instances(condition, state)
                 if action.deletes(a))


def _makes_true(action: GroundAction, condition: GroundLiteral) -> bool:
    if condition in action.preconditions:
        return False  # needs what it would achieve: never useful in a fallback
    if condition.positive:
        return condition.atom in action.add
    return action.deletes(condition.atom)
