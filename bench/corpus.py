"""btplan beside peer planners on a folder of competition-layout domains, as whole processes.

Each subfolder of the corpus is a domain: `domain.pddl` beside its instance files, or
one domain file per instance (`p01-domain.pddl`, `domain_p01.pddl`, `p01.domain.pddl`).
Every planner runs as its own process on the untouched files, with a per-problem time
limit, and is measured from process start to exit: start-up and imports count, as
they do for a user. Peak RSS comes from the kernel: GNU time's report of the
planner's processes (`measure` says why not this process's wait4). A plan counts only when
bench/validate_plan.py, which shares no code with btplan, accepts it.

    python bench/planning.py --corpus DIR [--per-domain 3] [--timeout 30]
                             [--planners btplan,pyperplan,fd] [--only barman,tpp]
                             [--fd-python PYTHON]
(`btplan-nosearch` is btplan without its last-resort search, `btplan plan --no-search`.)

Peers: pyperplan (GBFS with h_FF, the `bench` extra) and Fast Downward's lama-first
(the `fd` extra, `up-fast-downward`), skipped when not installed. `--fd-python` runs
Fast Downward from another interpreter that has it (its own virtual environment).
After the table, each domain's largest peak RSS of btplan beside the peers', and whether
btplan's is at most Fast Downward's on every domain.
"""

from __future__ import annotations

import functools
import importlib.util
import os
import signal
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from validate_plan import validate  # noqa: E402

BTPLAN = "import sys; from btplan.cli import main; sys.argv[0] = 'btplan'; main()"
"""What the `btplan` console script runs; PYTHONPATH may point it at another checkout."""

PYPERPLAN = """
import logging, sys
from pyperplan.planner import HEURISTICS, SEARCHES, search_plan
logging.disable(logging.CRITICAL)
plan = search_plan(sys.argv[1], sys.argv[2], SEARCHES["gbf"], HEURISTICS["hff"])
if plan is None:
    sys.exit(1)
with open(sys.argv[3], "w") as out:
    out.writelines(op.name + "\\n" for op in plan)
"""


@dataclass
class Run:
    solved: bool
    seconds: float
    rss_mb: float
    length: int | None = None
    cost: float | None = None
    note: str = ""


@dataclass
class Case:
    domain: str
    problem: str
    runs: dict[str, Run]


def instances(folder: Path) -> list[tuple[Path, Path]]:
    """(domain file, problem file) pairs of one domain folder, smallest problem first."""
    pairs: list[tuple[Path, Path]] = []
    shared = folder / "domain.pddl"
    for path in sorted(folder.glob("*.pddl")):
        if "domain" in path.name:
            continue
        stem = path.stem
        own = [folder / f"{stem}-domain.pddl", folder / f"domain_{stem}.pddl",
               folder / f"{stem}.domain.pddl", folder / f"domain-{stem}.pddl"]
        domain = next((d for d in own if d.exists()), shared)
        if domain.exists():
            pairs.append((domain, path))
    return sorted(pairs, key=lambda p: (p[1].stat().st_size, p[1].name))


FD_PYTHON: str | None = None
"""The interpreter that runs Fast Downward (--fd-python); None: this one."""

FIND_FD = """
import importlib.util
spec = importlib.util.find_spec("up_fast_downward")
if spec is not None and spec.submodule_search_locations:
    print(list(spec.submodule_search_locations)[0])
"""


def fd_python() -> str:
    return FD_PYTHON or sys.executable


def fd_driver() -> str | None:
    return _driver_of(FD_PYTHON)


@functools.cache
def _driver_of(python: str | None) -> str | None:
    """Fast Downward's driver script, as `python` (None: this interpreter) finds it."""
    if python is None:
        spec = importlib.util.find_spec("up_fast_downward")
        found = list(spec.submodule_search_locations or []) if spec is not None else []
        folder = found[0] if found else ""
    else:
        import subprocess

        done = subprocess.run([python, "-c", FIND_FD], capture_output=True, text=True)
        folder = done.stdout.strip()
    if not folder:
        return None
    driver = Path(folder) / "downward" / "fast-downward.py"
    return str(driver) if driver.exists() else None


def command(planner: str, domain: Path, problem: Path, plan: str, limit: float) -> list[str]:
    if planner in ("btplan", "btplan-nosearch"):  # the latter without the last resort
        return [sys.executable, "-c", BTPLAN, "plan", str(domain), str(problem),
                "-o", os.devnull, "--plan-out", plan, "--timeout", f"{limit:g}",
                *(["--no-search"] if planner == "btplan-nosearch" else [])]
    if planner == "pyperplan":
        return [sys.executable, "-c", PYPERPLAN, str(domain), str(problem), plan]
    driver = fd_driver()
    assert driver is not None
    return [fd_python(), driver, "--alias", "lama-first", "--plan-file", plan,
            str(domain), str(problem)]


def measure(argv: list[str], limit: float, cwd: str) -> tuple[int | None, float, float, str]:
    """(exit code or None on timeout, wall seconds, peak RSS in MB, last stderr line).

    The peak is the largest of the planner's processes (wait4's ru_maxrss covers the
    children a process waited for). It is not read from this process's wait4: a process
    spawned from here starts with this one's high-water mark (Linux counts the memory
    it had before exec), so every planner would read at least the bench's own 20 MB.
    GNU time, which is small, spawns the planner instead and reports its peak; a run
    killed at the limit is read from /proc (VmHWM of its processes) just before the kill.
    """
    err_path = os.path.join(cwd, "stderr.txt")
    rss_path = os.path.join(cwd, "rss.txt")
    timer = gnu_time()
    if timer is not None:
        argv = [timer, "-f", "%M", "-o", rss_path, *argv]
    start = time.perf_counter()
    with open(err_path, "wb") as err:
        pid = os.posix_spawn(argv[0], argv, dict(os.environ), file_actions=[
            (os.POSIX_SPAWN_OPEN, 0, os.devnull, os.O_RDONLY, 0),
            (os.POSIX_SPAWN_OPEN, 1, os.devnull, os.O_WRONLY, 0),
            (os.POSIX_SPAWN_DUP2, err.fileno(), 2)], setsid=True)
    code: int | None = None
    peak = 0.0
    while True:
        done, status, usage = os.wait4(pid, os.WNOHANG)
        if done:
            seconds = time.perf_counter() - start
            code = os.waitstatus_to_exitcode(status)
            break
        if time.perf_counter() - start > limit:
            peak = group_peak_mb(pid)
            os.killpg(pid, signal.SIGKILL)
            _, status, usage = os.wait4(pid, 0)
            seconds = time.perf_counter() - start
            break
        time.sleep(0.002)
    lines = Path(err_path).read_text(errors="replace").strip().splitlines()
    said = [x for x in lines if x.startswith(("error:", "failed:", "Error", "ValueError"))]
    if timer is None:
        peak = usage.ru_maxrss / 1024  # at least this process's own peak (see above)
    elif code is not None:
        told = Path(rss_path).read_text().split() if os.path.exists(rss_path) else []
        peak = int(told[-1]) / 1024 if told and told[-1].isdigit() else peak
    return code, seconds, peak, (said or lines or [""])[-1]


@functools.cache
def gnu_time() -> str | None:
    """GNU time's path, when installed (`-f %M -o FILE`: the peak RSS of a command)."""
    import shutil
    import subprocess

    path = shutil.which("time") or ("/usr/bin/time" if os.path.exists("/usr/bin/time") else None)
    if path is None:
        return None
    try:
        said = subprocess.run([path, "--version"], capture_output=True, text=True, timeout=5)
    except (OSError, subprocess.TimeoutExpired):
        return None
    return path if "GNU" in said.stdout + said.stderr else None


def group_peak_mb(group: int) -> float:
    """The largest VmHWM (peak RSS) of the processes of a process group, in MB."""
    peak = 0
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            stat = Path(f"/proc/{entry}/stat").read_text()
            if int(stat.rsplit(")", 1)[1].split()[2]) != group:
                continue
            for line in Path(f"/proc/{entry}/status").read_text().splitlines():
                if line.startswith("VmHWM:"):
                    peak = max(peak, int(line.split()[1]))
        except (OSError, ValueError, IndexError):
            continue
    return peak / 1024


def run_one(planner: str, domain: Path, problem: Path, limit: float) -> Run:
    with tempfile.TemporaryDirectory() as work:
        plan = os.path.join(work, "plan.txt")
        argv = command(planner, domain, problem, plan, limit)
        code, seconds, rss, last = measure(argv, limit + 2, work)
        if code is None:
            return Run(False, seconds, rss, note="timeout")
        if not os.path.exists(plan):
            return Run(False, seconds, rss, note=last[:70] or f"exit {code}")
        text = Path(plan).read_text()
    ok, reason, cost = validate(domain.read_text(), problem.read_text(), text)
    if not ok:
        return Run(False, seconds, rss, note="INVALID: " + reason[:60])
    steps = [s for s in text.splitlines() if s.strip() and not s.startswith(";")]
    return Run(True, seconds, rss, len(steps), cost)


def compile_btplan() -> None:
    """Write btplan's bytecode once, as pip does when it installs a wheel.

    An editable install compiles its sources on first import, and not at all when
    PYTHONDONTWRITEBYTECODE is set: then every btplan process would recompile them
    while the peers, installed from wheels, load bytecode.
    """
    import compileall

    import btplan

    package = Path(btplan.__file__).parent
    compileall.compile_dir(str(package), quiet=1)
    print(f"btplan's bytecode compiled first ({package.name}/), as pip compiles an installed "
          "package: no btplan process compiles its sources while timed", flush=True)


def available(planners: list[str]) -> list[str]:
    if "btplan" in planners:
        compile_btplan()
    kept = []
    for planner in planners:
        if planner == "pyperplan" and importlib.util.find_spec("pyperplan") is None:
            print("pyperplan is not installed: skipped", file=sys.stderr)
        elif planner == "fd" and fd_driver() is None:
            print("up-fast-downward is not installed (extra 'fd'): skipped", file=sys.stderr)
        else:
            kept.append(planner)
    return kept


def cell(run: Run) -> str:
    if run.solved:
        return f"{run.length:>4} {run.seconds:6.2f}s {run.rss_mb:5.0f}MB"
    return f"{'-':>4} {run.seconds:6.2f}s {run.note[:40]}"


def bench_corpus(corpus: Path, planners: list[str], per_domain: int, limit: float,
                 only: list[str] | None) -> list[Case]:
    planners = available(planners)
    cases: list[Case] = []
    folders = sorted(p for p in corpus.iterdir() if p.is_dir())
    for folder in folders:
        if only and folder.name not in only:
            continue
        for domain, problem in instances(folder)[:per_domain]:
            runs = {p: run_one(p, domain, problem, limit) for p in planners}
            case = Case(folder.name, problem.name, runs)
            cases.append(case)
            print(f"{folder.name:<12} {problem.name:<12} " + " | ".join(
                f"{p}: {cell(r)}" for p, r in runs.items()), flush=True)
    return cases


def _median(values: list[float]) -> float:
    return statistics.median(values) if values else float("nan")


def report(cases: list[Case], planners: list[str], limit: float) -> list[str]:
    planners = [p for p in planners if cases and p in cases[0].runs]
    lines = [f"coverage within {limit:g} s per problem (valid plans):",
             f"{'domain':<12} " + " ".join(f"{p:>10}" for p in planners)]
    domains = sorted({c.domain for c in cases})
    for name in [*domains, "total"]:
        mine = [c for c in cases if name in ("total", c.domain)]
        lines.append(f"{name:<12} " + " ".join(
            f"{sum(c.runs[p].solved for c in mine):>4}/{len(mine):<5}" for p in planners))
    for peer in planners:
        if peer == "btplan" or "btplan" not in planners:  # ratios are btplan's to a peer
            continue
        both = [c for c in cases if c.runs["btplan"].solved and c.runs[peer].solved]
        time_ratio = _median([c.runs["btplan"].seconds / c.runs[peer].seconds for c in both])
        length_ratio = _median([(c.runs["btplan"].length or 0) / max(c.runs[peer].length or 1, 1)
                                for c in both])
        lines.append(
            f"btplan / {peer} on the {len(both)} problems both solve: median whole-process "
            f"time ratio {time_ratio:.2f}, median plan length ratio {length_ratio:.2f}")
    for planner in planners:
        runs = [c.runs[planner] for c in cases]
        solved = [r.seconds for r in runs if r.solved]
        lines.append(f"{planner}: median time of solved {_median(solved):.2f} s, "
                     f"peak RSS max {max((r.rss_mb for r in runs), default=0):.0f} MB")
    return lines + coverage_target(cases, planners) + time_target(cases, planners) + memory(
        cases, planners)


COVERAGE_SHARE = 0.95
"""btplan's coverage on every domain, as a share of Fast Downward's at least."""


def coverage_target(cases: list[Case], planners: list[str]) -> list[str]:
    """The target: at least 95% of Fast Downward's coverage on every domain."""
    if "btplan" not in planners or "fd" not in planners:
        return []
    short = []
    for name in sorted({c.domain for c in cases}):
        mine = [c for c in cases if c.domain == name]
        ours, theirs = (sum(c.runs[p].solved for c in mine) for p in ("btplan", "fd"))
        if ours < COVERAGE_SHARE * theirs:
            short.append(f"{name} {ours}/{theirs}")
    verdict = "met" if not short else "missed (" + ", ".join(short) + ")"
    return [f"target: at least {COVERAGE_SHARE:.0%} of Fast Downward's coverage on every "
            f"domain: {verdict}"]


def time_target(cases: list[Case], planners: list[str]) -> list[str]:
    """The target: median whole-process time at most pyperplan's on small and on large
    problems alike. Small: the first half of each domain's problems, smallest first."""
    if "btplan" not in planners or "pyperplan" not in planners:
        return []
    order = {id(c): [d for d in cases if d.domain == c.domain].index(c) for c in cases}
    size = {name: sum(c.domain == name for c in cases) for name in {c.domain for c in cases}}
    verdicts = []
    for label, small in (("small", True), ("large", False)):
        part = [c for c in cases if (order[id(c)] < size[c.domain] / 2) == small
                and c.runs["btplan"].solved and c.runs["pyperplan"].solved]
        ratio = _median([c.runs["btplan"].seconds / c.runs["pyperplan"].seconds for c in part])
        ok = bool(part) and ratio <= 1.0
        verdicts.append((ok, f"{label} {ratio:.2f} on {len(part)}"))
    verdict = "met" if all(ok for ok, _ in verdicts) else "missed"
    return [f"target: median whole-process time at most pyperplan's on small and large "
            f"problems (btplan / pyperplan: {', '.join(text for _, text in verdicts)}): "
            f"{verdict}"]


def memory(cases: list[Case], planners: list[str]) -> list[str]:
    """Each domain's largest peak RSS per planner, and the target's verdict.

    The target: btplan's peak grows with what the problem needs, so on no domain does
    it exceed Fast Downward's, whose search is in C++ behind a Python translator.
    """
    lines = ["", "peak RSS per domain, MB (largest of its problems, whole processes; "
             "*: on a problem it did not solve):",
             f"{'domain':<12} " + " ".join(f"{p:>10}" for p in planners)]
    domains = sorted({c.domain for c in cases})
    worse: list[str] = []
    for name in domains:
        mine = [c for c in cases if c.domain == name]
        peaks = {p: max(c.runs[p].rss_mb for c in mine) for p in planners}
        failed = {p for p in planners for c in mine
                  if c.runs[p].rss_mb == peaks[p] and not c.runs[p].solved}
        lines.append(f"{name:<12} " + " ".join(
            f"{peaks[p]:>9.0f}{'*' if p in failed else ' '}" for p in planners))
        if "btplan" in peaks and "fd" in peaks and peaks["btplan"] > peaks["fd"]:
            worse.append(f"{name} {peaks['btplan']:.0f} > {peaks['fd']:.0f}")
    if "btplan" in planners and "fd" in planners:
        verdict = "met" if not worse else "missed (" + ", ".join(worse) + ")"
        lines.append(f"target: peak RSS at most Fast Downward's on every domain: {verdict}")
    return lines
