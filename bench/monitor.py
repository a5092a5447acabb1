"""What watching a run costs: ticks per second of the same run with and without the
Groot2 server (`--groot`), the replay file (`--btlog`) and the browser view (`--view`,
its server keeping the trace's lines; no page attached), on a tree of about a thousand
nodes.

The run is a generated logistics problem (12 packages) acted on with `keep`, while an
agent undoes the last action now and then, so the tree keeps acting for the whole run;
the same seed makes every variant the same run, tick for tick. Each variant runs
`--repeat` times, in turn, and the best time counts.

    python bench/monitor.py                 # about a minute
    python bench/monitor.py --ticks 5000 --repeat 5
"""

from __future__ import annotations

import argparse
import socket
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import btplan
from btplan.lang.generators import logistics
from btplan.model import Task
from btplan.monitor.browser import LIVE_LINES, BrowserView, TraceLines
from btplan.monitor.btlog import BtlogWriter
from btplan.monitor.groot2 import Groot2Server
from btplan.monitor.run_monitor import Monitor, RunMonitor


def free_port() -> int:
    """A port whose next one is free too (the server takes both)."""
    while True:
        with socket.socket() as probe, socket.socket() as next_one:
            probe.bind(("127.0.0.1", 0))
            port = int(probe.getsockname()[1])
            try:
                next_one.bind(("127.0.0.1", port + 1))
            except OSError:
                continue
            return port


def timed(task: Task, ticks: int, make: Callable[[], list[Monitor]] | None
          ) -> tuple[float, int, int]:
    """Seconds, ticks and final tree size of one run (the monitors made anew)."""
    monitor = RunMonitor(make()) if make is not None else None
    started = time.perf_counter()
    outcome = btplan.run(task, keep=True, max_ticks=ticks, disturb=["undo@p=0.2"],
                         view=monitor, seed=1)
    seconds = time.perf_counter() - started
    if monitor is not None:
        monitor.close()
    return seconds, outcome.ticks, len(outcome.tree.nodes())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ticks", type=int, default=2000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--packages", type=int, default=12)
    args = parser.parse_args()
    domain, problem = logistics(args.packages, seed=1)
    task = Task(domain=domain, problem=problem)
    folder = Path(tempfile.mkdtemp())
    variants: dict[str, Callable[[], list[Monitor]] | None] = {
        "plain": None,
        "--groot": lambda: [Groot2Server(free_port())],
        "--btlog": lambda: [BtlogWriter(str(folder / "run.btlog"))],
        "--groot --btlog": lambda: [Groot2Server(free_port()),
                                    BtlogWriter(str(folder / "run.btlog"))],
        "--view": lambda: [BrowserView(TraceLines(keep=LIVE_LINES), "bench", 0)],
    }
    best: dict[str, float] = {}
    size = ticks = 0
    for _ in range(args.repeat):
        for name, make in variants.items():
            seconds, ticks, size = timed(task, args.ticks, make)
            best[name] = min(best.get(name, seconds), seconds)
    print(f"logistics {args.packages} packages, seed 1: {ticks} ticks, final tree "
          f"{size} nodes; best of {args.repeat}")
    print(f"{'variant':<18}{'ticks/s':>10}{'per tick (us)':>15}{'vs plain':>10}")
    for name, seconds in best.items():
        print(f"{name:<18}{ticks / seconds:>10.0f}{seconds / ticks * 1e6:>15.1f}"
              f"{best['plain'] / seconds:>10.2f}")


if __name__ == "__main__":
    main()
