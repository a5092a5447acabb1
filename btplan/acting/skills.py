"""The robot as the tree sees it: the loop owns every running skill and every log.

The tree's leaves call `check`, `start`, `step` and `halt` with a key; a tree may name
the same grounded action in several leaves, and a robot with one handle per skill (one
navigation goal, one gripper) cannot be started twice. `Skills` stands between the
tree and the world and keeps the rules of btplan.robot.contract:

- a grounded action runs at most once at a time: a second leaf's `start` while it runs
  goes on with it, a `step` after it was halted starts it again, and a `halt` from one
  leaf in the tick another leaf ran it is not sent;
- every call is guarded: an exception is that action's FAILURE (that condition's
  false), with its message in the tick's events, unless the run stops on it;
- an action whose effects all hold when the tree turns away from it is logged as
  finished with its effects observed, not as cut short (asynchronous skills report
  SUCCESS after the world already shows their work);
- `facts()` accepts any iterable of atoms or `(predicate, *args)` tuples and hands the
  planner one frozenset of atoms, the same object while the state is the same; a world
  whose `facts()` raises cannot be acted in, and the run ends with a WorldError;
- `halt_all` stops every running skill on every way out of a run, waits a bounded time
  for those that say when they stop, and names those that did not.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping

from btplan.acting.clock import Clock, SystemClock
from btplan.bt import FAILURE, RUNNING, SUCCESS, LeafKey, Status
from btplan.errors import BtplanError, SkillError, WorldError
from btplan.model import ActionTemplate, Atom, GroundAction, Parameter
from btplan.records import field, record
from btplan.robot.contract import Capabilities, World, capabilities_of

__all__ = ["SkillEvents", "Skills"]

HALT_WAIT = 2.0
"""Seconds the loop waits, on a way out, for halted skills that report when they stop."""


@record(slots=True)
class SkillEvents:
    """What the robot's skills did since the events were last taken (one tick)."""

    started: list[GroundAction] = field(default_factory=list)
    finished: list[GroundAction] = field(default_factory=list)
    observed: list[GroundAction] = field(default_factory=list)
    """Of `finished`, those whose effects showed before the skill reported SUCCESS."""
    halted: list[GroundAction] = field(default_factory=list)
    failed: list[GroundAction] = field(default_factory=list)
    errors: list[tuple[str, str]] = field(default_factory=list)
    """(action or condition, message) for every exception a world call raised."""


class Skills:
    """The world behind the tree's leaves, with the loop's logs (see the module docstring)."""

    def __init__(self, world: World, grounding: Mapping[LeafKey, GroundAction],
                 stop_on_error: bool = False,
                 fallback_refine: Callable[[ActionTemplate, Mapping[str, str], Parameter],
                                           list[str]] | None = None,
                 wait_for_alternatives: bool = False) -> None:
        self.world = world
        self.capabilities: Capabilities = capabilities_of(world)
        self.grounding = grounding
        self.stop_on_error = stop_on_error
        self.running: dict[LeafKey, GroundAction] = {}
        """Skills started and not yet ended or halted, in the order they started."""
        self.executed: list[GroundAction] = []
        """Every action finished, in order: the plan the robot carried out."""
        self.ended = 0
        """Actions that ended (finished, failed or halted): the loop's check for circles."""
        self.events = SkillEvents()
        self._made_by_others: set[LeafKey] = set()
        """Running skills some of whose effects another action made while they ran: their
        effects holding says nothing about them."""
        self._ticked: dict[LeafKey, Status] = {}
        self.wait_for_alternatives = wait_for_alternatives
        self._starts = 0
        self._start_number: dict[LeafKey, int] = {}
        """The running skills' places in the order of starts."""
        self._failed_after: dict[LeafKey, int] = {}
        """Actions whose last run failed, and how many starts there had been then."""
        self._raw: object = None
        self._facts: frozenset[Atom] = frozenset()
        refine = getattr(world, "refine", None) if self.capabilities.refines else None
        self._refine = refine if refine is not None else fallback_refine

    @property
    def starts(self) -> int:
        """Skills started so far in this world."""
        return self._starts

    # --- the tree's side ----------------------------------------------------------------

    def begin_tick(self) -> None:
        """A new tick of the tree: each grounded action may be run once in it."""
        self._ticked.clear()

    def check(self, key: LeafKey) -> bool:
        """The world's check of a condition; an exception is logged and counts as false (or
        stops the run with `stop_on_error`)."""
        try:
            return bool(self.world.check(key))
        except Exception as error:  # noqa: BLE001 (a robot's error is a false condition)
            self._error(f"{key[0]}({', '.join(key[1])})", error)
            return False

    def start(self, key: LeafKey) -> Status:
        """Start the skill of `key`; if another leaf already ran it in this tick, answer as it
        did, and if it is still running, step it instead of starting it twice."""
        given = self._ticked.get(key)
        if given is not None:
            return given  # another leaf runs it in this tick
        if key in self.running:
            return self._advance(key)  # still running: go on with it, never start it twice
        return self._begin(key)

    def step(self, key: LeafKey) -> Status:
        """Step the running skill of `key`; one halted for another leaf, or never started, is
        started again, and one another leaf ran in this tick answers as it did."""
        given = self._ticked.get(key)
        if given is not None:
            return given
        if key not in self.running:
            return self._begin(key)  # halted for another leaf, or never started: start it
        return self._advance(key)

    def halt(self, key: LeafKey) -> None:
        """Halt the skill of `key`; ignored if it is not running, or if another leaf ran it in
        this tick (that leaf still wants it)."""
        if key not in self.running or key in self._ticked:
            return  # not running, or another leaf runs it in this tick
        self._halt(key)

    def facts(self) -> frozenset[Atom]:
        """The state as one frozenset of atoms; the same object while it is unchanged."""
        try:
            raw = self.world.facts()
            if raw is self._raw and isinstance(raw, frozenset):
                return self._facts  # an immutable state, unchanged
            facts = _atoms(raw)
        except BtplanError:
            raise
        except Exception as error:  # a robot that cannot say its state: nothing to act on
            raise WorldError(f"{type(self.world).__name__}.facts() raised "
                             f"{type(error).__name__}: {error}") from error
        self._raw = raw
        if facts != self._facts:
            self._facts = facts
        return self._facts

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """The world's refinement, or refinement by constraints for a world without one."""
        if self._refine is None:
            raise WorldError(f"{type(self.world).__name__} cannot refine {parameter.name} "
                             f"of {template.name}: it declares no refine")
        return list(self._refine(template, binding, parameter))

    # --- the loop's side ----------------------------------------------------------------

    def take_events(self) -> SkillEvents:
        """The events since the last call (one tick's), and a fresh list for the next."""
        events, self.events = self.events, SkillEvents()
        return events

    def halt_all(self, wait: float = HALT_WAIT, clock: Clock | None = None) -> list[str]:
        """Halt every running skill; wait up to `wait` seconds for those a world says when
        they stop. Returns the actions that did not stop in time."""
        keys = list(self.running)
        for key in keys:
            self._halt(key)
        if not keys or not self.capabilities.reports_stopped:
            return []
        clock = clock or SystemClock()
        deadline = clock.now() + wait
        moving = list(keys)
        while moving:
            moving = [k for k in moving if not self._stopped(k)]
            if not moving or clock.now() >= deadline:
                break
            clock.sleep(0.01)
        return [str(self._action(k)) for k in moving]

    # ---------------------------------------------------------------------------------

    def _begin(self, key: LeafKey) -> Status:
        if self._alternative_running(key):
            self._ticked[key] = FAILURE  # as it failed: the tree goes on to the alternative
            return FAILURE
        self._starts += 1
        self._start_number[key] = self._starts
        action = self.running[key] = self._action(key)
        self.events.started.append(action)
        if self._effects_hold(action):  # nothing left for it to show
            self._made_by_others.add(key)
        return self._settle(key, self._call(key, self.world.start))

    def _advance(self, key: LeafKey) -> Status:
        return self._settle(key, self._call(key, self.world.step))

    def _settle(self, key: LeafKey, status: Status) -> Status:
        """Log how a start or step ended; a skill still running is the same skill for the
        other leaves that name it in this tick (one that ended may be run again)."""
        if status is RUNNING:
            self._ticked[key] = status
            return status
        action = self.running.pop(key, None) or self._action(key)
        self._made_by_others.discard(key)
        self._start_number.pop(key, None)
        self.ended += 1
        if status is FAILURE:
            self._failed_after[key] = self._starts
        else:
            self._failed_after.pop(key, None)
        if status is SUCCESS:
            self.events.finished.append(action)
            self.executed.append(action)
            self._note_effects_of(action)
        else:
            self.events.failed.append(action)
        return status

    def _alternative_running(self, key: LeafKey) -> bool:
        """Whether `key` failed and an action started since, the alternative the tree
        turned to, still runs (`wait_for_alternatives`). On a robot a failure takes
        ticks to come; a reactive Fallback would start the failed action again at the
        next tick and halt its alternative every time: it is not started again, its
        leaf fails at once, until that alternative has ended."""
        failed = self._failed_after.get(key)
        if not self.wait_for_alternatives or failed is None:
            return False
        return any(number > failed for other, number in self._start_number.items()
                   if other != key)

    def _halt(self, key: LeafKey) -> None:
        self._start_number.pop(key, None)
        action = self.running.pop(key)
        try:
            observed = key not in self._made_by_others and self._effects_hold(action)
        except Exception:  # noqa: BLE001 (the state cannot be read: halt all the same)
            observed = False
        self._made_by_others.discard(key)
        try:
            self.world.halt(key)
        except Exception as error:  # noqa: BLE001 (logged; the others must still be halted)
            self._error(str(action), error, raise_it=False)
        self.ended += 1
        if observed:
            self.events.finished.append(action)
            self.events.observed.append(action)
            self.executed.append(action)
        else:
            self.events.halted.append(action)

    def _call(self, key: LeafKey, call: Callable[[LeafKey], Status]) -> Status:
        try:
            status: object = call(key)
        except Exception as error:  # noqa: BLE001 (a robot's error is the action's failure)
            self._error(str(self._action(key)), error)
            self._quietly_halt(key)
            return FAILURE
        if status is True:
            return SUCCESS
        if status is False:
            return FAILURE
        if status not in (RUNNING, SUCCESS, FAILURE):
            self._error(str(self._action(key)), TypeError(
                f"a skill must answer RUNNING, SUCCESS or FAILURE, not {status!r}"))
            self._quietly_halt(key)
            return FAILURE
        return status

    def _quietly_halt(self, key: LeafKey) -> None:
        """After an exception the skill's state is unknown: tell it to stop, ignore errors."""
        try:
            self.world.halt(key)
        except Exception:  # noqa: BLE001, S110 (already failed; its first error is logged)
            pass

    def _error(self, what: str, error: Exception, raise_it: bool = True) -> None:
        message = str(error) or type(error).__name__
        self.events.errors.append((what, message))
        if raise_it and self.stop_on_error:
            raise SkillError(what, message) from error

    def _stopped(self, key: LeafKey) -> bool:
        try:
            return bool(self.world.stopped(key))  # type: ignore[attr-defined]
        except Exception:  # noqa: BLE001 (cannot tell: counts as not stopped)
            return False

    def _note_effects_of(self, done: GroundAction) -> None:
        """`done` finished: the running skills whose effects it made too are not credited
        with them (a door the key opened while the button's press was still running)."""
        made = set(done.add)
        for key, action in self.running.items():
            if made.intersection(action.add):
                self._made_by_others.add(key)

    def _effects_hold(self, action: GroundAction) -> bool:
        return bool(action.add or action.delete) and action.achieved(self.facts())

    def _action(self, key: LeafKey) -> GroundAction:
        action = self.grounding.get(key)
        return action if action is not None else GroundAction(name=key[0], args=tuple(key[1]))


def _atoms(raw: Iterable[object]) -> frozenset[Atom]:
    """btplan atoms from what a world's `facts()` gave: atoms, `(predicate, args)` pairs
    or flat `(predicate, *args)` tuples."""
    if isinstance(raw, frozenset) and all(type(a) is Atom for a in raw):
        return raw
    out: list[Atom] = []
    for item in raw:
        if type(item) is Atom:
            out.append(item)
            continue
        if isinstance(item, str):
            out.append(Atom(item, ()))
            continue
        parts: tuple[object, ...] = tuple(item)  # type: ignore[arg-type]
        if not parts or not isinstance(parts[0], str):
            raise TypeError(f"a fact must be an Atom or a (predicate, *args) tuple, not {item!r}")
        if len(parts) == 2 and isinstance(parts[1], tuple):
            out.append(Atom(parts[0], tuple(str(a) for a in parts[1])))
        else:
            out.append(Atom(parts[0], tuple(str(a) for a in parts[1:])))
    return frozenset(out)
