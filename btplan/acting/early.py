"""Expansions made before a tick reaches the condition, in the tick the loop is in.

Two kinds, both off in the published algorithm (`look_ahead`): the later false
preconditions of an action whose first false one was just expanded, and of their
achievers those that would make the robot give up what it holds (btplan.acting.ahead);
and the conditions ahead of the running actions that an outside change broke
(btplan.acting.watch). Each is expanded as the tick that reached it would
expand it, conflict resolution included; one without achievers or without a
conflict-free place now is left for that tick to find.
"""

from __future__ import annotations

import time

from btplan.acting.ahead import attached, deeper_false, forced_out, later_false
from btplan.acting.choice import achievers_for
from btplan.acting.prepare import on_the_way, relaxed_plans
from btplan.acting.state import LoopState, TickReport
from btplan.acting.watch import broken_ahead
from btplan.bt import Node
from btplan.errors import UnresolvableConflictError
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner import literal_of


def expand_ahead(loop: LoopState, report: TickReport) -> None:
    """Expand the false preconditions after the one just expanded (`loop.ahead`), as the
    tick would once the robot had achieved that one; and those an expansion here adds
    (a credited achiever's, btplan.acting.credit). After each, the false preconditions
    of the achiever it got that conflict where they stand (`expand_forced`)."""
    state = loop.world.facts()
    while loop.ahead:
        node = loop.ahead.pop(0)
        if not _room(loop, report):
            loop.ahead = []
            return
        literal = literal_of(node)
        if literal is None or literal.holds(state):
            continue
        if _expand_early(loop, report, node, state):
            expand_forced(loop, report, node)


def expand_forced(loop: LoopState, report: TickReport, node: Node) -> None:
    """Expand the false preconditions of `node`'s new achiever that every achiever of
    theirs would make the robot give up what an earlier condition holds
    (btplan.acting.ahead): conflict resolution puts them in front now, rather than the
    tick finding them only with the cube in hand. The others wait for the tick.

    The facts are read again: the expansion may have refined a value (a trajectory)
    that the world measures only from now on."""
    state = loop.world.facts()
    for deeper in deeper_false(node, state, loop.expanded):
        if not _room(loop, report):
            return
        literal = literal_of(deeper)
        assert literal is not None

        def reached_first(held: list[GroundLiteral], atom: Atom = literal.atom) -> bool:
            goals = [h.atom for h in held if h.positive]
            return on_the_way(relaxed_plans(loop), state, goals, atom)

        achievers, spare = achievers_for(loop, deeper, literal, state)
        if forced_out(node, achievers, loop.judge(),
                      reached_first if literal.positive else None):
            _expand_early(loop, report, deeper, state, (achievers, spare))


def expand_if_forced(loop: LoopState, report: TickReport) -> None:
    """Of the later false preconditions in `loop.forcing`, expand those whose first
    achiever has a false precondition that every achiever of it would make the robot
    give up what is held before them (`look_deeper` without `look_ahead`): only then
    is the later condition's subtree needed before the tick reaches it. Each is looked
    at as the deeper look of `expand_forced` would, its precondition's achievers ranked
    where the later condition stands."""
    while loop.forcing:
        node = loop.forcing.pop(0)
        if not _room(loop, report):
            loop.forcing = []
            return
        literal = literal_of(node)
        state = loop.world.facts()
        if literal is None or literal.holds(state) or node in loop.expanded:
            continue
        found = achievers_for(loop, node, literal, state)
        if not found[0]:
            continue
        refined = loop.world.facts()  # the achiever may have refined a trajectory
        needs = [p for p in found[0][0].preconditions if not p.holds(refined)]
        if any(_forces(loop, node, need, refined) for need in needs):
            if _expand_early(loop, report, node, state, found):
                expand_forced(loop, report, node)


def _forces(loop: LoopState, node: Node, need: GroundLiteral,
            state: frozenset[Atom]) -> bool:
    """Whether every achiever of `need`, a precondition of `node`'s achiever, would
    make the robot give up what is held before `node` (`forced_out`)."""

    def reached_first(held: list[GroundLiteral]) -> bool:
        goals = [h.atom for h in held if h.positive]
        return on_the_way(relaxed_plans(loop), state, goals, need.atom)

    achievers, _ = achievers_for(loop, node, need, state)
    return forced_out(node, achievers, loop.judge(),
                      reached_first if need.positive else None)


def expand_broken(loop: LoopState, report: TickReport, last: frozenset[Atom]) -> None:
    """Expand the conditions ahead of the running actions that held in `last`, the state
    after the previous tick, and an outside change made false; each with its later
    false preconditions. Looking is monitoring (`report.checks_ahead`); the expansions
    are planning, timed as such."""
    state = loop.world.facts()
    broken, report.checks_ahead = broken_ahead(loop.tree.root, state, last, loop.expanded)
    if not broken:
        return
    started = time.process_time()
    try:
        for node in broken:
            if not _room(loop, report):
                return
            ahead = later_false(node, state, loop.expanded)
            if _expand_early(loop, report, node, state):
                loop.ahead = ahead + loop.ahead
                expand_ahead(loop, report)
    finally:
        report.planning_seconds += time.process_time() - started


def _room(loop: LoopState, report: TickReport) -> bool:
    """Whether this tick and the run may still expand."""
    return (len(report.expansions) < loop.options.expansions_per_tick
            and len(loop.expansions) < loop.options.max_expansions)


def _expand_early(loop: LoopState, report: TickReport, node: Node, state: frozenset[Atom],
                  found: tuple[list[GroundAction], list[GroundAction]] | None = None) -> bool:
    """ExpandTree and conflict resolution on `node` (`found`: its achievers and spare
    ones, when looked up already); False when it is left for later."""
    literal = literal_of(node)
    if literal is None or node in loop.expanded or not attached(node, loop.tree.root):
        return False
    achievers, spare = found if found is not None else achievers_for(loop, node, literal,
                                                                     state)
    if not achievers:
        return False
    try:
        expansion = loop.apply(node, literal, achievers, spare)
    except UnresolvableConflictError:
        return False
    loop.expanded.add(node)
    report.expansions.append(expansion)
    return True
