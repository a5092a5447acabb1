"""Spread the runs of a sweep over local worker processes or Ray tasks.

Each run is computed from its name alone (runs.run_one), so the rows do not depend on
which worker ran them or in which order. A worker that dies loses only the run it was
doing: that run is tried once more on a fresh worker, then recorded as an error row.
Rows come back one at a time through `on_row`, so an interrupted sweep keeps the rows
it already has.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
import time
from collections import deque
from collections.abc import Callable, Sequence
from multiprocessing.connection import Connection, wait
from typing import Any

from btplan.errors import MissingExtraError, WorldError
from btplan.sweep.runs import Job, Row, empty_row, run_one

Run = tuple[str, float, int]
"""(method, rate, seed): the name of one run within a job."""

OnRow = Callable[[Row], None]

ATTEMPTS = 2
"""A run whose worker died is tried this many times in all before it becomes an error row."""


def run_serial(job: Job, runs: Sequence[Run], on_row: OnRow) -> None:
    """In this process, one after the other (--jobs 1)."""
    for method, rate, seed in runs:
        on_row(run_one(job, method, rate, seed))


def _serve(conn: Connection, job: Job) -> None:
    """A worker: run what the parent sends until it sends None."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    while True:
        try:
            item = conn.recv()
        except (EOFError, OSError):
            return  # the parent is gone (killed): nobody wants the rows any more
        if item is None:
            return
        method, rate, seed = item
        row = run_one(job, method, rate, seed)
        try:
            conn.send(row)
        except (BrokenPipeError, OSError):
            return  # the parent died while this run went on: leave quietly


class _Worker:
    def __init__(self, context: Any, job: Job) -> None:
        self.conn, child = context.Pipe()
        self.process = context.Process(target=_serve, args=(child, job), daemon=True)
        self.process.start()
        child.close()
        self.run: Run | None = None
        self.since = 0.0

    def give(self, run: Run) -> None:
        """Send `run` to the worker process, timed from now (the timeout's start)."""
        self.run, self.since = run, time.monotonic()
        self.conn.send(run)

    def take(self) -> Row:
        """The row of the run it was given, which frees it for the next."""
        row: Row = self.conn.recv()
        self.run = None
        return row


def run_local(job: Job, runs: Sequence[Run], on_row: OnRow, jobs: int,
              timeout: float | None = None) -> None:
    """On `jobs` worker processes, one run at a time each; a dead worker is replaced.

    A run that takes longer than `timeout` seconds (wall clock) has its worker killed
    and becomes an error row; it is not retried, since it would only time out again.
    """
    context = multiprocessing.get_context("spawn")
    todo: deque[tuple[Run, int]] = deque((run, 1) for run in runs)
    workers: list[_Worker] = []
    attempts: dict[Run, int] = {}
    try:
        while todo or any(w.run is not None for w in workers):
            while todo and (len(workers) < jobs or any(w.run is None for w in workers)):
                idle = next((w for w in workers if w.run is None), None)
                if idle is None:
                    idle = _Worker(context, job)
                    workers.append(idle)
                run, attempt = todo.popleft()
                attempts[run] = attempt
                idle.give(run)
            busy = [w for w in workers if w.run is not None]
            left = None
            if timeout is not None:
                left = max(0.0, min(w.since + timeout for w in busy) - time.monotonic())
            ready = wait([w.conn for w in busy] + [w.process.sentinel for w in busy], left)
            for worker in busy:
                if worker.conn in ready or worker.process.sentinel in ready:
                    _collect(worker, job, workers, todo, attempts, on_row)
                elif timeout is not None and time.monotonic() - worker.since > timeout:
                    _time_out(worker, job, workers, timeout, on_row)
    finally:
        for worker in workers:
            _stop(worker)


def _collect(worker: _Worker, job: Job, workers: list[_Worker],
             todo: deque[tuple[Run, int]], attempts: dict[Run, int], on_row: OnRow) -> None:
    run = worker.run
    assert run is not None
    try:
        if worker.conn.poll():
            on_row(worker.take())
            return
    except (EOFError, OSError):
        worker.process.join(timeout=5)  # the pipe closed: the worker is going
    if worker.process.is_alive():
        return  # the sentinel was not this worker's
    workers.remove(worker)
    _stop(worker)
    code = worker.process.exitcode
    if attempts[run] < ATTEMPTS:
        todo.appendleft((run, attempts[run] + 1))
    else:
        method, rate, seed = run
        on_row(empty_row(job, method, rate, seed,
                         f"WorkerDied: the worker died twice (exit code {code})"))


def _time_out(worker: _Worker, job: Job, workers: list[_Worker], timeout: float,
              on_row: OnRow) -> None:
    assert worker.run is not None
    method, rate, seed = worker.run
    worker.process.kill()
    worker.process.join()
    workers.remove(worker)
    worker.conn.close()
    on_row(empty_row(job, method, rate, seed, f"Timeout: the run took more than {timeout:g} s"))


def _stop(worker: _Worker) -> None:
    if worker.process.is_alive():
        try:
            worker.conn.send(None)
        except (BrokenPipeError, OSError):
            pass
        worker.process.join(timeout=1)
        if worker.process.is_alive():
            worker.process.kill()
            worker.process.join()
    worker.conn.close()


def run_ray(job: Job, runs: Sequence[Run], on_row: OnRow, address: str | None,
            jobs: int | None) -> None:
    """As Ray tasks, on a local Ray (address None) or an existing cluster.

    Ray retries a task whose worker died (`max_retries`); after that the run becomes
    an error row. The import is here: ray is an optional extra.
    """
    try:
        import ray
    except ImportError:
        raise MissingExtraError("--ray needs ray: pip install 'btplan[cluster]'") from None
    started = not ray.is_initialized()
    if started:
        kwargs: dict[str, Any] = {"include_dashboard": False, "log_to_driver": False,
                                  "configure_logging": False}
        if address:
            kwargs["address"] = address
        elif jobs:
            kwargs["num_cpus"] = jobs
        path = os.pathsep.join(p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p)
        if path:
            kwargs["runtime_env"] = {"env_vars": {"PYTHONPATH": path}}
        try:
            ray.init(**kwargs)
        except (ValueError, ConnectionError, RuntimeError) as error:
            hint = (f"; is the cluster up (`ray status --address {address}`)? one started with "
                    "token authentication needs RAY_AUTH_MODE=token here too" if address else "")
            raise WorldError(f"cannot start or reach Ray ({error}){hint}") from None
    try:
        remote = ray.remote(max_retries=ATTEMPTS - 1)(run_one)
        pending = {remote.remote(job, *run): run for run in runs}
        while pending:
            done, _ = ray.wait(list(pending), num_returns=1)
            for ref in done:
                method, rate, seed = pending.pop(ref)
                try:
                    row = ray.get(ref)
                except Exception as error:  # the worker died on every attempt
                    row = empty_row(job, method, rate, seed,
                                    f"WorkerDied: {type(error).__name__}")
                on_row(row)
    finally:
        if started:
            ray.shutdown()
