"""A symbolic world: a set of ground atoms that grounded actions change.

It is the world offline planning runs in (`btplan plan`) and the one the acting loop is
tested against. Actions take `duration` ticks: RUNNING until the last one, then their
effects are applied and they return SUCCESS. An action whose preconditions stop
holding while it runs returns FAILURE, as a real controller would abort. Failures can
also be injected, one by one (`fail_next`) or with a seeded probability per template,
to exercise the reactivity the paper's Problem 1 asks for.
"""

from __future__ import annotations

from collections.abc import Mapping

from btplan.bt import FAILURE, RUNNING, SUCCESS, LeafKey, Status
from btplan.errors import WorldError
from btplan.model import (
    EQUALITY,
    WILDCARD,
    ActionTemplate,
    Atom,
    GroundAction,
    Literal,
    Parameter,
    Task,
    matches,
)
from btplan.robot.contract import Capabilities
from btplan.robot.refine import ConstraintRefiner, holds
from btplan.worlds.logs import RecentLog

TYPE_CHECKING = False
if TYPE_CHECKING:
    from random import Random


class SymbolicWorld:
    """The current state as a set of atoms, plus the bookkeeping of the robot's actions.

    `executed` lists the actions the robot completed, in order; `started`, `halted`
    and `failed` record the recent rest of each action's life (btplan.worlds.logs), for
    its agents and for tests; the acting loop keeps its own logs.
    """

    capabilities = Capabilities(refines=True)

    def __init__(
        self,
        task: Task,
        *,
        seed: int = 0,
        failure_probability: Mapping[str, float] | None = None,
        groundings: dict[LeafKey, GroundAction] | None = None,
    ) -> None:
        self.task = task
        self._state: set[Atom] = set(task.initial_state)
        self._frozen: frozenset[Atom] | None = None
        """`facts()` while the state is unchanged; every change below clears it."""
        self._seed = seed
        self._rng: Random | None = None  # made at the first draw (see _draw)
        self._failure_probability = dict(failure_probability or {})
        self._templates = task.domain.action_map
        # Worlds of one task may share their groundings (offline planning starts many).
        self._grounded: dict[LeafKey, GroundAction] = groundings if groundings is not None else {}
        self._remaining: dict[LeafKey, int] = {}
        self._refiner = ConstraintRefiner(task, lambda: self._state)
        self._fail_next: list[tuple[str, tuple[str, ...] | None]] = []
        self.executed: list[GroundAction] = []
        self.started: RecentLog[GroundAction] = RecentLog()
        self.halted: RecentLog[GroundAction] = RecentLog()
        self.failed: RecentLog[GroundAction] = RecentLog()

    # --- the state ---------------------------------------------------------------------

    def facts(self) -> frozenset[Atom]:
        """The state now. The same object until the state changes: planning asks for it
        many times per tick, and what it remembers per state (h_add costs, the atoms by
        predicate) is found by identity or by a hash a new copy would compute again."""
        frozen = self._frozen
        if frozen is None:
            frozen = self._frozen = frozenset(self._state)
        return frozen

    def set_fact(self, atom: Atom) -> None:
        """An external change: `atom` becomes true."""
        self._state.add(Atom(atom[0], tuple(atom[1])))
        self._frozen = None

    def clear_fact(self, atom: Atom) -> None:
        """An external change: `atom` becomes false."""
        self._state.discard(Atom(atom[0], tuple(atom[1])))
        self._frozen = None

    def apply_action(self, action: GroundAction) -> None:
        """An external agent performs `action`: its effects, whatever the preconditions."""
        self._state = set(action.apply(self.facts()))
        self._frozen = None

    def fail_next(self, action_name: str, args: tuple[str, ...] | None = None) -> None:
        """Make the next tick of a matching action (any arguments when None) return FAILURE."""
        self._fail_next.append((action_name, None if args is None else tuple(args)))

    def running_actions(self) -> list[GroundAction]:
        """The actions started and not yet finished, halted or failed, oldest first."""
        return [self.ground(key) for key in self._remaining]

    def ground(self, key: LeafKey) -> GroundAction:
        """The grounded action an Action leaf with this key stands for."""
        action = self._grounded.get(key)
        if action is None:
            name, args = key
            template = self._templates.get(name)
            if template is None:
                raise WorldError(f"the domain has no action named {name!r}")
            try:
                action = self.task.instantiate(template, tuple(args))
            except ValueError as error:
                raise WorldError(str(error)) from None
            self._grounded[key] = action
        return action

    # --- btplan.bt.World ---------------------------------------------------------------

    def check(self, key: LeafKey) -> bool:
        """A condition holds when its atom is in the state.

        `=` compares its two arguments instead, and a `_` argument matches any atom of the
        predicate (`blocks(_, t)`: something blocks t).
        """
        predicate, args = key
        if predicate == EQUALITY:
            return len(args) == 2 and args[0] == args[1]
        if WILDCARD in args:  # blocks(_, t): some atom matches
            pattern = Atom(predicate, tuple(args))
            return any(matches(pattern, atom) for atom in self._state)
        return key in self._state

    def start(self, key: LeafKey) -> Status:
        """Begin the action and count down its `duration` ticks.

        A one-tick action finishes, or fails, on this very tick.
        """
        action = self.ground(key)
        self.started.append(action)
        self._remaining[key] = action.duration
        return self._advance(key, action)

    def step(self, key: LeafKey) -> Status:
        """One more tick of a running action; its effects apply on its last tick.

        An action stepped without a start (a tree rebuilt mid-action) is started here.
        """
        action = self.ground(key)
        if key not in self._remaining:
            # Stepped without a start (a tree built mid-action): treat it as a start.
            self.started.append(action)
            self._remaining[key] = action.duration
        return self._advance(key, action)

    def halt(self, key: LeafKey) -> None:
        """Drop a running action with none of its effects; halting one not running does nothing."""
        if self._remaining.pop(key, None) is not None:
            self.halted.append(self.ground(key))

    @property
    def drew(self) -> bool:
        """Whether an outcome was left to chance yet: until then, the same tree run from
        the same state does the same again."""
        return self._rng is not None

    def _draw(self) -> float:
        """The next number of the seeded generator, made on first use: worlds without
        failure probabilities (all of offline planning) never import `random`."""
        if self._rng is None:
            from random import Random

            self._rng = Random(self._seed)
        return self._rng.random()

    def _advance(self, key: LeafKey, action: GroundAction) -> Status:
        """One tick of a running action: fail, keep running, or finish and apply effects."""
        if (self._take_injected_failure(action) or not action.applicable(self._state)
                or self._stale(action)):
            return self._fail(key, action)
        probability = self._failure_probability.get(action.name, 0.0)
        if probability > 0.0 and self._draw() < probability:
            return self._fail(key, action)
        left = self._remaining[key] - 1
        if left > 0:
            self._remaining[key] = left
            return RUNNING
        del self._remaining[key]
        self._state = set(action.apply(self.facts()))
        self._frozen = None
        self.executed.append(action)
        return SUCCESS

    def _fail(self, key: LeafKey, action: GroundAction) -> Status:
        self._remaining.pop(key, None)
        self.failed.append(action)
        return FAILURE

    def _take_injected_failure(self, action: GroundAction) -> bool:
        for i, (name, args) in enumerate(self._fail_next):
            if name == action.name and (args is None or args == action.args):
                del self._fail_next[i]
                return True
        return False

    # --- refinement (the planner's RefineActions) -----------------------------------------

    def refine(
        self, template: ActionTemplate, binding: Mapping[str, str], parameter: Parameter
    ) -> list[str]:
        """Objects of the parameter's type that satisfy the template's `where` constraints
        now (btplan.robot.refine)."""
        return self._refiner(template, binding, parameter)

    def _stale(self, action: GroundAction) -> bool:
        """A refined value whose `where` constraints no longer hold: a route that is gone.

        The value was chosen in an earlier state; running it in this one would act on a
        world that no longer exists, so the action fails and the loop refines again.
        """
        template = self._templates.get(action.name)
        if template is None or not any(p.refined for p in template.parameters):
            return False
        refined = {p.name for p in template.parameters if p.refined}
        binding = {p.name: a for p, a in zip(template.parameters, action.args)}
        return not all(self._holds(c, binding) for c in template.constraints
                       if refined & set(c.args))

    def _holds(self, literal: Literal, binding: Mapping[str, str]) -> bool:
        return holds(literal, binding, self._state)
