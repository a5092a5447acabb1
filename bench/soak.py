"""Memory and speed of one long acting run: a Place that always fails keeps the loop going.

A robot's loop runs for hours. The default preset retries a failing action until the
tick limit, so `btplan run domains/pick_place.bt --fail-prob Place=1 --max-ticks N`
ticks exactly N times; its peak memory must not grow with N (the outcome keeps the last
RECENT_TICKS records, the summary's lists their first LISTED entries, the trace
streams). Each N runs in a fresh process, without a trace and with one streamed to a
temporary file (one JSON line per tick, one write each, as `--trace` does), and
reports its peak resident memory (VmHWM), its resident memory at a tenth of the run
and at the end, and ticks per second.

    python bench/soak.py                    # 10^3 .. 10^5 ticks, about a minute
    python bench/soak.py --million          # and 10^6 (several minutes per row)
    python bench/soak.py --cli              # also the `btplan run` command itself
    python bench/soak.py --disturb 'help:Pick@p=0.5' --sizes 10000 20000 40000
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

DOMAIN = Path(__file__).resolve().parent.parent / "domains" / "pick_place.bt"
SIZES = (10**3, 10**4, 10**5)
MILLION = 10**6


def status_kb(field: str) -> int:
    """A memory figure of this process from /proc/self/status, in kB (0 if unavailable)."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def child(ticks: int, trace: bool, disturb: list[str]) -> dict[str, Any]:
    """One run in this process; what it measured, as a JSON-ready dict."""
    import btplan
    from btplan.worlds.symbolic import SymbolicWorld

    task = btplan.load(str(DOMAIN))
    world = SymbolicWorld(task, failure_probability={"Place": 1.0})
    sample_at = max(1, ticks // 10)
    samples: dict[str, int] = {"before": status_kb("VmRSS")}
    fd = -1
    path = ""
    if trace:
        handle, path = tempfile.mkstemp(prefix="soak-", suffix=".jsonl")
        fd = handle

    def view(root: object, reached: Mapping[int, object], record: Any) -> None:
        if fd >= 0:
            data = memoryview((record.to_json() + "\n").encode("utf-8"))
            while data:
                data = data[os.write(fd, data):]
        if record.tick == sample_at:
            samples["tenth"] = status_kb("VmRSS")

    started = time.perf_counter()
    try:
        outcome = btplan.run(task, world=world, max_ticks=ticks, view=view, disturb=disturb)
        seconds = time.perf_counter() - started
        samples["end"] = status_kb("VmRSS")
        trace_bytes = os.fstat(fd).st_size if fd >= 0 else 0
    finally:
        if fd >= 0:
            os.close(fd)
            os.unlink(path)
    summary = outcome.summary()
    return {
        "ticks": outcome.ticks, "reached": outcome.reached, "seconds": seconds,
        "failed": summary.count("failed"), "started": summary.count("started"),
        "kept_records": len(outcome.records), "kept_failed": len(summary.failed),
        "rss_before_kb": samples["before"], "rss_tenth_kb": samples.get("tenth", 0),
        "rss_end_kb": samples["end"], "hwm_kb": status_kb("VmHWM"),
        "maxrss_kb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss,
        "trace_bytes": trace_bytes,
    }


def measure(ticks: int, trace: bool, disturb: list[str]) -> dict[str, Any]:
    """`child` in a fresh interpreter."""
    argv = [sys.executable, __file__, "--child", str(ticks), *(["--trace"] if trace else []),
            *(f"--disturb={spec}" for spec in disturb)]
    done = subprocess.run(argv, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"the run of {ticks} ticks failed (exit {done.returncode}):\n"
                         + done.stderr[-2000:])
    result: dict[str, Any] = json.loads(done.stdout.splitlines()[-1])
    return result


def measure_cli(ticks: int, trace: bool, disturb: list[str]) -> dict[str, Any]:
    """The `btplan run` command, measured from outside: wall time and peak RSS (wait4)."""
    exe = shutil.which("btplan") or str(Path(sys.executable).parent / "btplan")
    with tempfile.TemporaryDirectory(prefix="soak-") as folder:
        trace_path = os.path.join(folder, "trace.jsonl")
        argv = [exe, "run", str(DOMAIN), "-q", "--fail-prob", "Place=1",
                "--max-ticks", str(ticks), *(["--trace", trace_path] if trace else []),
                *(f"--disturb={spec}" for spec in disturb)]
        started = time.perf_counter()
        process = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        _, status, usage = os.wait4(process.pid, 0)
        seconds = time.perf_counter() - started
        process.returncode = os.waitstatus_to_exitcode(status)
        size = os.path.getsize(trace_path) if os.path.exists(trace_path) else 0
    return {"seconds": seconds, "maxrss_kb": usage.ru_maxrss,
            "exit": process.returncode, "trace_mb": size / 2**20}


def mb(kb: int) -> str:
    return f"{kb / 1024:7.1f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=list(SIZES), metavar="N",
                        help="tick limits to run (default: 10^3, 10^4, 10^5)")
    parser.add_argument("--million", action="store_true", help="also run 10^6 ticks")
    parser.add_argument("--cli", action="store_true",
                        help="also measure the `btplan run` command (peak RSS from wait4)")
    parser.add_argument("--disturb", action="append", default=[], metavar="SPEC",
                        help="an agent, as `btplan run --disturb` takes it (repeatable)")
    parser.add_argument("--child", type=int, metavar="TICKS", help=argparse.SUPPRESS)
    parser.add_argument("--trace", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child is not None:
        print(json.dumps(child(args.child, args.trace, args.disturb)))
        return

    sizes = (*args.sizes, *((MILLION,) if args.million else ()))
    print("btplan.run(pick_place, SymbolicWorld(failure_probability={'Place': 1.0}), "
          "max_ticks=N), default preset, one fresh process per row"
          + "".join(f", disturb {spec!r}" for spec in args.disturb))
    print("RSS in MB: before the run (task loaded), at N/10 ticks, at the end; peak = VmHWM")
    print()
    print(f"{'ticks':>9} {'trace':>5} | {'before':>7} {'at N/10':>7} {'end':>7} {'peak':>7} | "
          f"{'ticks/s':>8} {'seconds':>8} | {'failed':>7} {'kept':>6} {'trace MB':>8}")
    started = time.perf_counter()
    rows: list[tuple[int, bool, dict[str, Any]]] = []
    for ticks in sizes:
        for trace in (False, True):
            r = measure(ticks, trace, args.disturb)
            rows.append((ticks, trace, r))
            print(f"{r['ticks']:>9} {'yes' if trace else 'no':>5} | {mb(r['rss_before_kb'])} "
                  f"{mb(r['rss_tenth_kb'])} {mb(r['rss_end_kb'])} {mb(r['hwm_kb'])} | "
                  f"{r['ticks'] / r['seconds']:>8.0f} {r['seconds']:>8.1f} | "
                  f"{r['failed']:>7} {r['kept_records']:>6} "
                  f"{r['trace_bytes'] / 2**20:>8.1f}", flush=True)
    print()
    print("kept: tick records the outcome holds (the last RECENT_TICKS)")
    if not args.million and MILLION not in sizes:
        last_run = rows[-1][2]
        minutes = MILLION / last_run["ticks"] * last_run["seconds"] / 60
        print(f"10^6 ticks not run (--million): about {minutes:.0f} min per row at the "
              "last row's speed")
    for trace in (False, True):
        first = next(r for t, tr, r in rows if tr == trace)
        last = [r for t, tr, r in rows if tr == trace][-1]
        grew = last["hwm_kb"] - first["hwm_kb"]
        in_run = last["rss_end_kb"] - last["rss_tenth_kb"]
        print(f"trace {'on ' if trace else 'off'}: peak {mb(first['hwm_kb']).strip()} MB at "
              f"{first['ticks']} ticks, {mb(last['hwm_kb']).strip()} MB at {last['ticks']} "
              f"ticks ({grew / 1024:+.1f} MB); within the longest run, from N/10 to the end: "
              f"{in_run / 1024:+.1f} MB")

    if args.cli:
        print()
        print("btplan run domains/pick_place.bt -q --fail-prob Place=1 --max-ticks N "
              "[--trace FILE]" + "".join(f" --disturb {spec}" for spec in args.disturb)
              + ": peak RSS from wait4; exit 1 is the goal not reached, as meant")
        print(f"{'ticks':>9} {'trace':>5} | {'peak':>7} {'seconds':>8} {'ticks/s':>8} {'exit':>4} "
              f"{'trace MB':>8}")
        for ticks in sizes:
            for trace in (False, True):
                c = measure_cli(ticks, trace, args.disturb)
                print(f"{ticks:>9} {'yes' if trace else 'no':>5} | {mb(c['maxrss_kb'])} "
                      f"{c['seconds']:>8.1f} {ticks / c['seconds']:>8.0f} {c['exit']:>4} "
                      f"{c['trace_mb']:>8.1f}",
                      flush=True)
    print()
    print(f"took {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    main()
