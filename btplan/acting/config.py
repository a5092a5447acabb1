"""How the blended loop acts: one configuration, with named presets.

Every switch of the acting loop lives here, by a name that says what it does, beside
the planner's own options (btplan.planner.PlannerOptions). `btplan run`, `btplan
sweep`, `btplan plan` and `btplan.run` all take an `ActingConfig`; three presets cover
what users ask for:

- `ActingConfig.paper()`: Algorithms 1-3 as published. One expansion per tick,
  breadth-first choice of the condition to expand, first-match achievers, no departure.
  The paper's walk-throughs in the docs hold under it (`--paper`).
- `ActingConfig.default()`: what `btplan run` does, measured in docs/results/reactivity.md. It
  first plans offline as `btplan plan` does and acts on that tree, so an undisturbed run
  executes that plan (bench/acting_halts.py); then it grows the tree within the tick
  until it runs (a sequential planner also plans before
  it acts), so an undisturbed run starts no action it will cancel; it retries a
  failing skill instead of giving up after a few ticks; and it adds the departures
  below, each an object of btplan.acting behind a hook of the loop.
- `ActingConfig.algorithm1()`: Algorithm 1's loop (one expansion per tick, no
  departure) with btplan's ranking of achievers: what `btplan run` did before the
  default above, and what the walk-throughs of docs/pybullet.md and docs/yumi.md show.
- `ActingConfig.simulator()`: the default for worlds whose actions refine values as
  they run (trajectories from where the robot stands): no look-ahead along the later
  preconditions (their trajectories would go stale before they are driven) and no
  credit for other goals (measured on the symbolic scenarios only).
"""

from __future__ import annotations

from btplan.planner import PlannerOptions
from btplan.records import record, replace

TYPE_CHECKING = False
if TYPE_CHECKING:
    from typing import Any

__all__ = ["ACTING_PLANNER", "EXPANSIONS_PER_TICK", "PRESETS", "ActingConfig"]

EXPANSIONS_PER_TICK = 64
"""Expansions the loop may make within one tick before the world moves on; Algorithm 1
as published makes one, and then starts an action it may cancel at the next expansion."""

ACTING_PLANNER = PlannerOptions(closest_first=False)
"""The planner's defaults while acting, less nearest-first expansion.

Breadth-first choice of the condition to expand (the paper's Algorithm 3) grows the
shallow alternatives of a Fallback before the deep ones, so an agent that undoes an
action often finds the other way to redo it already in the tree: no new expansion, as
Problem 1 asks. Nearest-first reaches a long plan in far fewer expansions, which is what
offline planning (`plan`) needs, but it leaves those alternatives unexpanded."""


@record(frozen=True, slots=True)
class ActingConfig:
    """The acting loop's settings (see the module docstring for the presets).

    - `planner`: how conditions are expanded (achiever ranking, conflicts, budgets).
    - `expansions_per_tick`: expansions within one tick before the world moves on.
    - `expand_later_preconditions`: when an action's first false precondition is
      expanded, expand its later false ones in the same tick, and expand a condition
      ahead of the running action as soon as an outside change breaks it
      (btplan.acting.departures.ahead, btplan.acting.departures.watch).
    - `expand_when_forced`: expand a later false precondition early only when its
      achiever would make the robot give up what it is about to hold (a doorway to clear
      before the cube is picked; implied by `expand_later_preconditions`).
    - `skip_moved_while_held`: skip a subtree that conflict resolution moved in front
      of an achiever while that achiever's condition holds (btplan.acting.departures.scope).
    - `credit_other_goals`: rank first the achievers that make other goals true, and
      set up the step of another goal an achiever enables (btplan.acting.departures.credit,
      btplan.acting.departures.prepare).
    - `finish_halted_action`: finish an action the tree turned away from when it does
      not interfere with the one started instead (btplan.acting.departures.finish).
    - `retry_failed_actions`: a skill that fails with nothing left to expand is tried
      again on the next tick until the tick limit; off, the run ends after
      `planner.stall_limit` such ticks in a row.
    - `plan_offline_when_stuck`: when the loop cannot grow the tree any further, plan
      the task offline from the facts of now, once, and act on that tree
      (btplan.acting.offline_turns); not in worlds that refine values as they run.
    - `plan_before_acting`: before the first action, plan the task offline as `btplan
      plan` does (its shorter plan first) and act on that tree, growing it online where
      the world departs from it: an undisturbed run executes that plan and no more
      (btplan.acting.offline_turns); not in worlds that refine values as they run.
    - `leave_plan_once_departed`: the first tick in which the world departs from that
      plan (no step of it fits), drop the plan's steps and act on the backchained tree
      alone, so that the two do not take turns under frequent outside changes
      (btplan.acting.departures.leave_plan).
    - `wait_for_alternatives`: an action that failed is not started again while the
      alternative the tree turned to (an action started after the failure) still runs;
      its leaf fails at once instead (btplan.acting.skills). On a robot a failure takes
      ticks, and a reactive Fallback would restart the failed action and halt the
      alternative at every tick.
    - `stop_on_skill_error`: an exception inside a skill ends the run (SkillError)
      instead of counting as that action's FAILURE.
    - `stuck_wait`: seconds a run paced on a wall clock (a rate) goes on ticking when
      the loop cannot grow the tree any further, before it counts as stuck: sensors
      read at different moments can show an action's effects in halves, and the dead
      end is gone at the next reading (btplan.acting.stuck_wait). 0: stuck at once.
    - `halt_wait`: seconds to wait, on every way out of a run, for halted skills that
      report when they have stopped.
    """

    name: str = "default"
    planner: PlannerOptions = ACTING_PLANNER
    expansions_per_tick: int = EXPANSIONS_PER_TICK
    expand_later_preconditions: bool = True
    expand_when_forced: bool = True
    skip_moved_while_held: bool = True
    credit_other_goals: bool = True
    finish_halted_action: bool = True
    retry_failed_actions: bool = True
    plan_offline_when_stuck: bool = True
    plan_before_acting: bool = True
    leave_plan_once_departed: bool = True
    wait_for_alternatives: bool = True
    stop_on_skill_error: bool = False
    stuck_wait: float = 1.0
    halt_wait: float = 2.0

    @classmethod
    def paper(cls, **changes: Any) -> ActingConfig:
        """Algorithms 1-3 as published, one expansion per tick, no departure."""
        return replace(cls(name="paper", planner=PlannerOptions.paper(),
                           expansions_per_tick=1, expand_later_preconditions=False,
                           expand_when_forced=False, skip_moved_while_held=False,
                           credit_other_goals=False, finish_halted_action=False,
                           retry_failed_actions=False, plan_offline_when_stuck=False,
                           plan_before_acting=False, leave_plan_once_departed=False,
                           wait_for_alternatives=False, stuck_wait=0.0),
                       **changes)

    @classmethod
    def algorithm1(cls, **changes: Any) -> ActingConfig:
        """Algorithm 1's loop, one expansion per tick and no departure, with btplan's
        planner options for each expansion."""
        return replace(cls.paper(name="algorithm1", planner=ACTING_PLANNER), **changes)

    @classmethod
    def default(cls, **changes: Any) -> ActingConfig:
        """`btplan run`'s behaviour in a symbolic world (or any world that refines nothing)."""
        return replace(cls(), **changes)

    @classmethod
    def simulator(cls, **changes: Any) -> ActingConfig:
        """The default for worlds that refine values as they run (PyBullet)."""
        return replace(cls(name="simulator", expand_later_preconditions=False,
                           credit_other_goals=False, wait_for_alternatives=False), **changes)

    @classmethod
    def preset(cls, name: str) -> ActingConfig:
        """A preset by name: `paper`, `algorithm1`, `default` or `simulator`."""
        try:
            return PRESETS[name]()
        except KeyError:
            raise ValueError(f"no acting preset named {name!r} "
                             f"(presets: {', '.join(sorted(PRESETS))})") from None

    def stall_limit(self, max_ticks: int | None) -> int:
        """Failing ticks in a row, with nothing to expand, after which the run ends
        (`max_ticks` None: a run without a tick limit)."""
        if not self.retry_failed_actions:
            return self.planner.stall_limit
        return max_ticks if max_ticks is not None else 2**62

    @property
    def loop_planner(self) -> PlannerOptions:
        """The planner options the loop runs with: `planner` and the tick's expansion budget."""
        return replace(self.planner, expansions_per_tick=self.expansions_per_tick)


PRESETS = {"paper": ActingConfig.paper, "algorithm1": ActingConfig.algorithm1,
           "default": ActingConfig.default, "simulator": ActingConfig.simulator}
