"""What `btplan plan` does once its arguments are read: plan, then write the outputs.

Free of typer, so that the lean start of the command line (`cli/lean.py`) and the
typer command (`cli/plan.py`) run the very same code.
"""

from __future__ import annotations

import gc
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from btplan.cli import edge
from btplan.cli.console import escape
from btplan.cli.edge import EXIT_FAILED, CommandExit, stderr
from btplan.cli.interrupts import HardDeadline, Interrupts, ReadInterrupted, TimeLimitReached
from btplan.cli.outputs import STDIO, Output, check_outputs, write_atomic
from btplan.errors import InputError, Interrupted, PlanningError
from btplan.records import replace

TYPE_CHECKING = False
if TYPE_CHECKING:
    from btplan.acting.loop import Expansion
    from btplan.acting.offline.attempt import PlanResult, PlanStats
    from btplan.bt import BehaviorTree

DEFAULT_TIMEOUT = 300.0
"""Seconds `btplan plan` plans before it gives up, unless told otherwise."""

FORMATS = ("xml", "dot", "json", "ascii")


def plan_and_write(domain: str, problem: str | None = None, fmt: str | None = None,
                   out: str = STDIO, plan_out: str | None = None,
                   trace_expansions: str | None = None, seed: int = 0,
                   max_expansions: int = 1000, max_ticks: int = 100_000,
                   max_alternatives: int | None = None, paper: bool = False,
                   no_search: bool = False, timeout: float = DEFAULT_TIMEOUT,
                   quiet: bool = False, no_improve: bool = False, max_memory: str = "auto",
                   started: float | None = None, goal: str | None = None) -> None:
    """The command `btplan plan`, its arguments read and typed (see its --help);
    `started`: the time.monotonic() the time limit counts from (default: now); `goal`:
    a goal to plan instead of the problem's (`btplan.lang.with_goal`)."""
    from btplan.cli.resources import MemoryLimit, describe, parse_memory

    limit = parse_memory(max_memory)
    try:
        with MemoryLimit(limit):
            _plan_and_write(domain, problem, fmt, out, plan_out, trace_expansions, seed,
                            max_expansions, max_ticks, max_alternatives, paper, no_search,
                            timeout, quiet, no_improve,
                            time.monotonic() if started is None else started, goal)
    except MemoryError:
        what = f"the memory limit ({describe(limit)}, --max-memory)" if limit else "memory"
        raise PlanningError(f"{what} ran out while planning; nothing written") from None


def _plan_and_write(domain: str, problem: str | None, fmt: str | None, out: str,
                    plan_out: str | None, trace_expansions: str | None, seed: int,
                    max_expansions: int, max_ticks: int, max_alternatives: int | None,
                    paper: bool, no_search: bool, timeout: float, quiet: bool,
                    no_improve: bool, started: float, goal: str | None) -> None:
    # Imported here, not at the top: the typer app imports this module to build the
    # command line, and the planner, the trees and their formats serve only this command.
    from btplan.acting.offline import load, plan
    from btplan.bt.formats import dump
    from btplan.planner import PlannerOptions
    from btplan.shipped import resolve

    limits = [("--max-expansions", max_expansions), ("--max-ticks", max_ticks)]
    if max_alternatives is not None:
        limits.append(("--max-alternatives", max_alternatives))
    for name, value in limits:
        if value < 1:
            raise InputError(f"{name} must be at least 1, got {value}")
    if timeout < 0:
        raise InputError(f"--timeout must be 0 (no limit) or positive, got {timeout:g}")
    check_outputs(Output("-o/--output", out), Output("--plan-out", plan_out),
                  Output("--trace-expansions", trace_expansions, folder=True),
                  inputs=[domain, *([problem] if problem else [])])
    chosen = fmt if fmt is not None else default_format(out)
    snapshots: list[tuple[str, str]] = []

    progress = Progress(enabled=not quiet)

    def trace(tree: BehaviorTree, expansion: Expansion) -> None:
        if trace_expansions is not None:
            snapshots.append((dump(tree, "dot"), dump(tree, "json")))
        progress.update(tree)

    options = PlannerOptions.paper() if paper else None
    if max_alternatives is not None:
        options = replace(options or PlannerOptions(), max_alternatives=max_alternatives)
    if no_search and options is not None:
        options = replace(options, search_stuck=False)
    with Interrupts() as interrupted, HardDeadline(timeout or None, started) as limit:
        if edge.console:
            limit.expire = lambda phase: _out_of_time(timeout, phase)
        try:
            with interrupted.reading():
                task = load(resolve(domain), *([problem] if problem is not None else []))
                if goal is not None:
                    from btplan.lang import with_goal

                    task = with_goal(task, goal, source="--goal")
            limit.phase = "planning"
            left = (max(0.001, started + timeout - time.monotonic()) if timeout else None)
            with collecting():
                result = plan(task, seed=seed, max_expansions=max_expansions,
                              max_ticks=max_ticks, timeout=left, options=options,
                              on_expansion=trace, stop=interrupted, last_resort=not no_search,
                              improve=not no_improve, say=progress.say)
            limit.disarm()
        except TimeLimitReached:
            raise PlanningError(f"the time limit ({timeout:g} s) was reached while "
                                f"{limit.phase}; nothing written") from None
        except Interrupted as error:
            stderr.print(f"[bold yellow]interrupted[/]: {escape(error.progress)}; "
                         "nothing written")
            raise CommandExit(interrupted.exit_code) from None
        except ReadInterrupted as stopped:
            stderr.print("[bold yellow]interrupted[/] while reading the input; nothing written")
            raise CommandExit(stopped.exit_code) from None
        finally:
            progress.close()
    if trace_expansions is not None:
        folder = Path(trace_expansions)
        folder.mkdir(parents=True, exist_ok=True)
        # Only the attempt that succeeded: plan() may have started over with wider options.
        kept = snapshots[len(snapshots) - len(result.expansions):] if result.expansions else []
        for number, (dot, saved) in enumerate(kept, start=1):
            stem = folder / f"expansion_{number:03d}"
            write_atomic(f"{stem}.dot", dot)
            write_atomic(f"{stem}.json", saved)
    if chosen == "json":  # the default format, written as it is made (large trees)
        from btplan.bt.formats.saved_out import json_pieces
        from btplan.io import write_pieces_atomic

        write_pieces_atomic(out, json_pieces(result.tree))
    else:
        text = dump(result.tree, chosen)
        write_atomic(out, text if text.endswith("\n") else text + "\n")
    if plan_out is not None:
        write_atomic(plan_out, plan_text(result, task.domain.has_costs))
    if not quiet:
        stderr.print(summary(result))


PLANNING_GC_THRESHOLD = 10_000
"""Allocations between two young-generation collections while planning (Python's
default is 700): the planner builds large tables that live through the whole search,
and every collection walks whatever of them is still young."""


@contextmanager
def collecting() -> Iterator[None]:
    """The garbage collector on while planning, if the console script started without
    it (btplan.cli.main), collecting less often than Python's default; off again after,
    so that the process also ends without a last full collection.

    Left as it is when it is on (a library caller, a test): the process is theirs.
    On the competition problems the collections during planning took 3-7 ms of a small
    problem and 50-110 ms of a longer one with the default; 0-3 ms and 14-76 ms
    with this threshold, the peak memory the same.
    """
    if gc.isenabled():
        yield
        return
    before = gc.get_threshold()
    gc.set_threshold(PLANNING_GC_THRESHOLD, *before[1:])
    gc.enable()
    try:
        yield
    finally:
        gc.disable()
        gc.set_threshold(*before)


class Progress:
    """One stderr line a second once planning has run for a second: expansions, tree
    size, conditions open. On a terminal the line is rewritten in place."""

    def __init__(self, enabled: bool = True) -> None:
        self.enabled = enabled
        self.started = time.perf_counter()
        self.shown = self.started
        self.expansions = 0
        self.terminal = sys.stderr.isatty()
        self.dirty = False

    def update(self, tree: BehaviorTree) -> None:
        """Count one expansion of `tree`; from the first second of planning on, at most once a
        second, write the progress line (rewritten in place on a terminal)."""
        self.expansions += 1
        now = time.perf_counter()
        if not self.enabled or now - self.shown < 1.0:
            return
        self.shown = now
        from btplan.bt import FAILURE, Condition

        nodes = tree.nodes()
        open_ = sum(1 for n in nodes if n.status is FAILURE and isinstance(n, Condition))
        line = (f"planning: {self.expansions} expansions, tree of {len(nodes)} nodes, "
                f"{open_} conditions failing, {now - self.started:.0f} s")
        if self.terminal:
            sys.stderr.write("\r\x1b[2K" + line)
            self.dirty = True
        else:
            sys.stderr.write(line + "\n")
        sys.stderr.flush()

    def say(self, text: str) -> None:
        """A line about what planning does next, once it has run for a second."""
        now = time.perf_counter()
        if not self.enabled or now - self.started < 1.0:
            return
        self.shown = now
        self.close()
        self.dirty = False
        sys.stderr.write(f"planning: {text}, {now - self.started:.0f} s\n")
        sys.stderr.flush()

    def close(self) -> None:
        """Clear a progress line left on the terminal, so the next output starts on a clean line."""
        if self.dirty:
            sys.stderr.write("\r\x1b[2K")
            sys.stderr.flush()


def default_format(out: str) -> str:
    """ascii on a terminal, json in a pipe; for a file, what its extension says (json)."""
    if out == STDIO:
        return "ascii" if sys.stdout.isatty() else "json"
    suffix = Path(out).suffix.lower().lstrip(".")
    return {"xml": "xml", "dot": "dot", "gv": "dot", "txt": "ascii"}.get(suffix, "json")


def plan_text(result: PlanResult, general: bool) -> str:
    """The executed actions in IPC plan format, ending with the cost line IPC tools write."""
    kind = "general cost" if general else "unit cost"
    steps = "".join(a.ipc() + "\n" for a in result.executed)
    return steps + f"; cost = {result.stats.cost:g} ({kind})\n"


def summary(result: PlanResult) -> str:
    """The one-line result of `btplan plan` in rich markup: expansions, conflicts, tree size,
    plan cost and time, then what the last resort, retries and plan improvement did."""
    s = result.stats
    return (
        f"[green]planned[/]: {s.expansions} expansions, {s.conflicts_resolved} conflicts "
        f"resolved ({s.moves} moves), tree of {s.tree_size} nodes, {s.actions_executed} actions "
        f"executed (cost {s.cost:g}), {s.seconds:.3f} s"
        + ("; last resort: the whole goal planned by search from the initial state"
           if s.whole_goal else
           f"; last resort: {s.searches} stuck conditions planned by search"
           if s.searches else "")
        + (f"; {s.retries} attempts started over without a choice that failed"
           if s.retries else "")
        + _improvement(s)
    )


def _improvement(s: PlanStats) -> str:
    """What plan improvement did, for the summary ('' when it did not run)."""
    if s.removed is None:
        return ""
    if s.shortest:
        return "; plan improvement not needed: a lower bound shows no plan has fewer steps"
    if not s.removed:
        return f"; plan improvement found no plan with fewer steps ({s.improve_seconds:.2f} s)"
    searched = s.removed - s.eliminated
    return (f"; plan improvement removed {s.removed} of {s.actions_executed + s.removed} steps "
            f"({s.eliminated} by action elimination, {searched} by neighbourhood search, "
            f"{s.improve_seconds:.2f} s)")


def _out_of_time(timeout: float, phase: str) -> None:
    """The time limit went off: nothing is written yet and nothing needs cleaning up, so
    the process ends here (as `leave` does), without first freeing the model."""
    from btplan.cli import lean

    stderr.print(f"[bold red]failed:[/] the time limit ({timeout:g} s) was reached while "
                 f"{escape(phase)}; nothing written")
    lean.leave(EXIT_FAILED)
