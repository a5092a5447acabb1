"""The contract between btplan's acting loop and a robot: what a world answers, and nothing else.

A world is anything the tree's leaves can reach: a simulator, a fake robot in a test, a
real robot behind its drivers. The loop asks it five things, all keyed by
`(name, args)` with the grounded arguments as strings, e.g. `("Pick", ("cube",))`:

- `check(key) -> bool`: whether a grounded condition holds now. Never blocks.
- `start(key) -> Status`: begin a grounded action; RUNNING while it takes more ticks,
  SUCCESS or FAILURE when it ends at once.
- `step(key) -> Status`: advance an action that answered RUNNING; it must not block.
- `halt(key) -> None`: stop a RUNNING action the tree no longer reaches.
- `facts() -> Iterable[atom]`: the current state, as btplan `Atom`s or plain tuples
  `("holding", "cube")`; the planner plans from it.

A world keeps no logs: the loop records what started, finished, was halted or failed,
and calls `start`/`step`/`halt` at most once at a time per grounded action, however
many leaves name it (btplan.acting.skills). An exception from `check`, `start`,
`step` or `halt` is that action's FAILURE (or that condition's false), with its message
in the trace; one from `facts()` ends the run (WorldError): nothing can be planned
without the state.

Everything else is optional and declared, never probed: a world lists what more it
offers in `capabilities` (a `Capabilities` record), and the loop uses exactly that.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from btplan.bt.status import Status
from btplan.bt.world import LeafKey
from btplan.errors import WorldError
from btplan.model import ActionTemplate, Atom, Parameter
from btplan.records import record

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Protocol
else:
    Protocol = object  # a protocol only types: a plain base at run time

__all__ = ["Capabilities", "Fact", "LeafKey", "Refining", "World", "capabilities_of"]

Fact = Atom | tuple[str, ...]
"""What `facts()` may hold: a btplan Atom, or a tuple `(predicate, arg, ...)`."""


class World(Protocol):
    """What a world must answer for the blended loop to act in it (see the module docstring)."""

    def check(self, key: LeafKey) -> bool:
        """Whether the grounded condition `key` holds now; never blocks."""
        ...

    def start(self, key: LeafKey) -> Status:
        """Begin the grounded action `key`: RUNNING, or SUCCESS/FAILURE if it ended at once."""
        ...

    def step(self, key: LeafKey) -> Status:
        """Advance the running action `key` by one tick; must not block."""
        ...

    def halt(self, key: LeafKey) -> None:
        """Ask the running action `key` to stop (see `Capabilities.reports_stopped`)."""
        ...

    def facts(self) -> Iterable[Fact]:
        """The current state as atoms or `(predicate, *args)` tuples."""
        ...


class Refining(Protocol):
    """A world that supplies the values of `refined` parameters (poses, trajectories)."""

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """Values for `parameter` under `binding` (objects and the values the template's
        `where` constraints bind so far), best first, the same each time it is asked."""
        ...


@record(frozen=True, slots=True)
class Capabilities:
    """What a world offers beyond the five calls of `World`. Each flag names a member the
    world then provides; a world without a `capabilities` attribute offers none of them,
    except `refine`, which a method of that name declares by itself.

    - `refines`: `refine(template, binding, parameter) -> list[str]` (`Refining`).
    - `own_values`: `refine` gives values of the world's own (a trajectory, a grasp
      pose) that the domain's `where` constraints do not; planning in the model before
      acting cannot know them, so the run leaves that to the loop.
    - `continuous`: facts change while an action runs (a base driving past a cube), so
      a state seen twice within one action is not a loop.
    - `outside_changes`: an `outside_changes` int property counting changes others made
      while the robot acted (agents pushing cubes mid-tick).
    - `lessons`: a `lessons` int property counting what the world learned from a failure
      (a grasp side that failed): a state seen before a new lesson is not a loop yet.
    - `dead_ends`: `dead_ends() -> list[str]`, why the robot may be stuck, for messages.
    - `reports_stopped`: `stopped(key) -> bool`, whether a halted action has come to
      rest; the loop waits for it, a bounded time, on every way out of a run.
    - `camera`: `camera_png(width, height) -> bytes`, a PNG picture of the world now;
      `btplan run --view` shows it beside each tick.
    - `closes`: `close()`, called once when `btplan run` ends, however it ends (the CLI
      made the world, so it closes it; `btplan.run` leaves a world it was given open).
    """

    refines: bool = False
    own_values: bool = False
    continuous: bool = False
    outside_changes: bool = False
    lessons: bool = False
    dead_ends: bool = False
    reports_stopped: bool = False
    camera: bool = False
    closes: bool = False


def capabilities_of(world: object) -> Capabilities:
    """The capabilities a world declares (its `capabilities` attribute); a `refine`
    method declares `refines` by itself."""
    declared = getattr(world, "capabilities", None)
    if declared is None:
        declared = Capabilities()
    elif not isinstance(declared, Capabilities):
        raise WorldError(f"{type(world).__name__}.capabilities must be a "
                         f"btplan.robot.Capabilities, not {type(declared).__name__}")
    if not declared.refines and callable(getattr(world, "refine", None)):
        from btplan.records import replace

        declared = replace(declared, refines=True)
    return declared
