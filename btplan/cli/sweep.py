"""The `btplan sweep` command: many seeded runs of several methods, rows out, summary shown."""

from __future__ import annotations

import contextlib
import os
import signal
from collections.abc import Callable, Iterator
from types import FrameType
from typing import TYPE_CHECKING, Annotated, Any

import typer
from typer.core import TyperCommand

from btplan.cli.console import escape
from btplan.cli.outputs import Output, check_outputs
from btplan.cli.run import Sim
from btplan.cli.typer_app import app, guarded, stderr
from btplan.errors import BtplanError, InputError, Span

if TYPE_CHECKING:
    from rich.progress import Progress, TaskID

    from btplan.sweep import pool
    from btplan.sweep.journal import RowJournal
    from btplan.sweep.runs import Job, Row


@contextlib.contextmanager
def _terminate_like_ctrl_c() -> Iterator[list[int]]:
    """SIGTERM ends the sweep as Ctrl-C does: the rows done so far are written.

    Yields the list that receives the signal's number, for the exit code (128 + it).
    """
    received: list[int] = []

    def stop(signum: int, frame: FrameType | None) -> None:
        received.append(signum)
        raise KeyboardInterrupt

    try:
        previous = signal.signal(signal.SIGTERM, stop)
    except ValueError:  # not the main thread: leave signals alone
        yield received
        return
    try:
        yield received
    finally:
        signal.signal(signal.SIGTERM, previous)


def _explain(job: Job, rows: list[Row], execute: Callable[[list[pool.Run], list[Row]], None],
              progress: Progress, task: TaskID) -> None:
    """Name the cause of every failed run (btplan.sweep.explain), rerunning the seeds
    that need it with replan-unlimited; those reruns are not rows of the output."""
    from btplan.sweep import explain

    reference = explain.references(rows)
    todo = explain.needed(rows)
    if todo and _baselines_apply(job):
        progress.update(task, total=(progress.tasks[0].total or 0) + len(todo))
        extra: list[Row] = []
        execute(todo, extra)
        reference.update(explain.references(extra))
    explain.label(rows, reference)


def _baselines_apply(job: Job) -> bool:
    from btplan.acting.strips import check_strips, require_pyperplan
    from btplan.sweep.runs import prepared

    try:
        require_pyperplan()
        check_strips(prepared(job)[0])
    except BtplanError:
        return False
    return True


def parse_seeds(text: str) -> range:
    """`A:B` is seeds A to B-1, as a Python range; `N` alone is seeds 0 to N-1."""
    first, sep, last = text.partition(":")
    try:
        seeds = range(int(first), int(last)) if sep else range(int(first))
    except ValueError:
        raise InputError(f"expected A:B (seeds A to B-1), not '{text}'",
                         Span("--seeds", 1, 1)) from None
    if not seeds:
        raise InputError(f"the seed range '{text}' is empty", Span("--seeds", 1, 1))
    return seeds


def parse_rates(text: str) -> list[float]:
    """`--rates` as a list of probabilities: comma-separated, each in [0, 1], sorted and
    without repeats so each rate is swept once; anything else is an InputError."""
    rates = []
    for item in text.split(","):
        try:
            rate = float(item)
        except ValueError:
            rate = -1.0
        if not 0.0 <= rate <= 1.0:
            raise InputError(f"a rate is a probability between 0 and 1, not '{item}'",
                             Span("--rates", 1, 1))
        rates.append(rate)
    return sorted(set(rates))


class _OptionalRayAddress(TyperCommand):
    """Lets `--ray` stand alone (a local Ray) or take an address, as `--ray [ADDRESS]`."""

    def parse_args(self, ctx: Any, args: list[str]) -> list[str]:
        fixed = list(args)
        for i, arg in enumerate(fixed):
            if arg == "--":
                break
            if arg == "--ray" and (i + 1 == len(fixed) or fixed[i + 1].startswith("-")):
                fixed.insert(i + 1, LOCAL)
                break
        return super().parse_args(ctx, fixed)


LOCAL = "local"


EXAMPLES = """Examples:

  btplan sweep domains/pick_place_obstacle.bt --scenario obstacle --seeds 0:100 --rates 0,0.1,0.2 -o rows.csv
  btplan sweep domains/pick_place_obstacle.bt --scenario obstacle --seeds 0:1000 --rates 0.1 --method btplan,repair -o rows.parquet --plot rows.png
  btplan sweep domains/pick_place.bt --seeds 0:50 --rates 0.2 --ray -o rows.csv
"""


@app.command(cls=_OptionalRayAddress, epilog=EXAMPLES)
@guarded
def sweep(
    domain: Annotated[str, typer.Argument(
        metavar="DOMAIN", help="Domain (.bt or .pddl), or domain and problem in one .bt file.")],
    seeds: Annotated[str, typer.Option(
        metavar="A:B", help="Seeds A to B-1 (N alone: 0 to N-1).")],
    rates: Annotated[str, typer.Option(metavar="R,...", help="Disturbance rates per tick.")],
    output_path: Annotated[str, typer.Option(
        "-o", "--output", metavar="FILE", help="One row per run: .csv or .parquet.")],
    problem: Annotated[str | None, typer.Argument(
        metavar="PROBLEM", help="Problem file, when it is not in DOMAIN.", show_default=False)
    ] = None,
    scenario: Annotated[str, typer.Option(
        metavar="NAME", help="undo, obstacle, towers, packages, scene, shove; a spec file with {p} for the rate; "
             "or module:attribute.")] = "undo",
    method: Annotated[str, typer.Option(
        metavar="M,...", help="btplan, btplan-paper, replan, repair, replan-unlimited.")
    ] = "btplan,replan,repair",
    sim: Annotated[Sim, typer.Option(help="The world to act in.")] = Sim.symbolic,
    jobs: Annotated[int | None, typer.Option(
        "-j", "--jobs", min=1, metavar="N", help="Local worker processes (default: all cores).")] = None,
    ray: Annotated[str | None, typer.Option(
        "--ray", metavar="[ADDRESS]",
        help="Run as Ray tasks: a local Ray, or the cluster at ADDRESS.")] = None,
    max_ticks: Annotated[int | None, typer.Option(
        min=1, metavar="N", help="Tick budget per run (default: the scenario's).")] = None,
    plot: Annotated[str | None, typer.Option(
        metavar="OUT.png", help="Draw success, planning time and ticks against rate "
                                "(.png, .svg or .pdf).")] = None,
    timeout: Annotated[float | None, typer.Option(
        metavar="SECONDS", help="Stop a run after this long (wall clock): an error row. "
                                "Local workers only.")] = None,
    quiet: Annotated[bool, typer.Option("-q", "--quiet", help="No progress bar.")] = False,
    resume: Annotated[bool, typer.Option(
        "--resume", help="Go on from the rows an unfinished sweep left next to the output "
                         "(FILE.rows.jsonl): only the runs not done yet are run.")] = False,
) -> None:
    """Run every method on every seed at every rate; write the rows and print medians.

    Exit 0 when every run ended (reached or not), 1 when some runs crashed (error
    rows), 2 on bad input, 130 on Ctrl-C and 143 on SIGTERM (the rows done so far are written).
    """
    # Imported here: every command's module is imported when btplan starts.
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from btplan.acting.strips import require_pyperplan
    from btplan.baselines import BASELINES
    from btplan.shipped import resolve
    from btplan.sweep import explain, output, pool
    from btplan.sweep.journal import RowJournal
    from btplan.sweep.runs import Job, check_methods, check_sim, prepared
    from btplan.sweep.stats import summarize

    files = [resolve(domain)] if problem is None else [resolve(domain), problem]
    check_outputs(Output("-o/--output", output_path), Output("--plot", plot), inputs=files)
    seed_range, rate_list = parse_seeds(seeds), parse_rates(rates)
    methods = [m.strip() for m in method.split(",") if m.strip()]
    check_methods(methods, sim.value)
    if any(m in BASELINES for m in methods):
        require_pyperplan()
    if timeout is not None and timeout <= 0:
        raise InputError(f"--timeout must be positive, got {timeout:g}", Span("--timeout", 1, 1))
    if timeout is not None and ray is not None:
        raise InputError("--timeout applies to local workers, not to --ray",
                         Span("--timeout", 1, 1), "leave one of them out")
    output.check_output(output_path)
    if plot is not None:
        output.check_plot(plot)
    job = Job(tuple(files), scenario, sim.value, max_ticks)
    prepared(job)  # bad domain files or scenarios are refused here, not in every worker
    check_sim(job)
    runs = [(m, r, s) for r in rate_list for m in methods for s in seed_range]
    journal = RowJournal(output_path)
    rows = _resumed(journal, resume, set(runs))
    done = {(r["method"], float(r["rate"]), int(r["seed"])) for r in rows}
    total = len(runs)
    runs = [run for run in runs if run not in done]
    journal.open(keep=bool(rows))
    if not quiet:
        stderr.print(f"finished rows go to {escape(journal.path)} as they come"
                     + (f" ({len(rows)} resumed)" if rows else ""))
    interrupted = False
    with Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                  TimeElapsedColumn(), TextColumn("eta"), TimeRemainingColumn(),
                  console=stderr.rich, disable=quiet, transient=True) as progress:
        task = progress.add_task("runs", total=len(runs))

        def execute(todo: list[pool.Run], into: list[Row]) -> None:
            def on_row(row: Row) -> None:
                into.append(row)
                if into is rows:
                    journal.add(row)
                progress.advance(task)

            if ray is not None:
                pool.run_ray(job, todo, on_row, None if ray == LOCAL else ray, jobs or None)
            elif (jobs or os.cpu_count() or 1) == 1 and timeout is None:
                pool.run_serial(job, todo, on_row)
            else:  # a run that must be stopped needs a process of its own
                pool.run_local(job, todo, on_row, jobs or os.cpu_count() or 1, timeout)

        try:
            with _terminate_like_ctrl_c() as terminated:
                execute(runs, rows)
                _explain(job, rows, execute, progress, task)
        except KeyboardInterrupt:
            interrupted = True
    journal.close()
    try:
        output.write_rows(output_path, rows)
    except OSError as error:
        raise InputError(f"-o/--output {output_path}: cannot write: "
                         f"{error.strerror or error}; the {len(rows)} rows are kept in "
                         f"{journal.path}", hint="free the space, then run the same "
                         "command with --resume to write them") from None
    if not interrupted:
        journal.remove()
    points = summarize(rows)
    stderr.print(escape(output.markdown_table(points)), end="")
    causes = explain.markdown(rows)
    if causes:
        stderr.print("failed runs by cause (replan-unlimited rerun on the same seed):")
        stderr.print(escape(causes), end="")
    if plot is not None and points:
        output.plot(points, plot)
    if interrupted:
        stderr.print(f"[bold red]interrupted:[/] {len(rows)} of {total} runs written "
                     f"to {escape(output_path)}; --resume goes on from {escape(journal.path)}")
        raise typer.Exit(128 + (terminated[0] if terminated else signal.SIGINT))
    errors = [r for r in rows if r["error"]]
    if errors:
        stderr.print(f"[bold red]failed:[/] {len(errors)} runs crashed; first: "
                     f"{escape(errors[0]['error'])}")
        raise typer.Exit(1)


def _resumed(journal: RowJournal, resume: bool, planned: set[tuple[str, float, int]]
             ) -> list[Row]:
    """The rows an unfinished sweep left for these runs (with --resume); a side file left
    without --resume is refused rather than overwritten."""
    if not journal.exists():
        return []
    if not resume:
        raise InputError(f"{journal.path} holds the rows of an unfinished sweep",
                         Span("-o/--output", 1, 1),
                         "add --resume to go on from them, or remove the file")
    return [r for r in journal.read()
            if (r.get("method"), float(r.get("rate", -1)), int(r.get("seed", -1))) in planned]
