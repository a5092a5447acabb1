"""The blended loop on a ROS 2 robot: the tick rate it holds, and how soon the next
goal follows a result.

Runs the fake robot of examples/ros (Example 2: the sphere rolls onto the path, the
cube is taken out of the gripper) and `btplan run --ros` at each rate, on loopback only,
and reports: ticks, late ticks and the worst lateness (from the run's summary), and the
time from each goal's result at the robot to the next goal it receives (from the fake
robot's log, one clock for both).

    python bench/ros_rate.py                  # --hz 10 and 50, about a minute
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def environment(domain_id: int) -> dict[str, str]:
    return {**os.environ, "ROS_DOMAIN_ID": str(domain_id),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
            "FASTDDS_DEFAULT_PROFILES_FILE": str(ROOT / "tests" / "ros" / "loopback.xml"),
            "PYTHONUNBUFFERED": "1"}


def one(rate: float, domain_id: int) -> dict[str, object]:
    env = environment(domain_id)
    robot = subprocess.Popen([sys.executable, str(ROOT / "examples/ros/fake_robot.py"),
                              "--sphere-rolls", "--take-cube"], env=env, text=True,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    assert robot.stdout is not None and "ready" in robot.stdout.readline()
    started = time.perf_counter()
    run = subprocess.run([sys.executable, "-m", "btplan", "run",
                          str(ROOT / "domains/pick_place_obstacle.bt"), "--ros",
                          str(ROOT / "examples/ros/example2.toml"), "--hz", f"{rate:g}", "-q"],
                         env=env, capture_output=True, text=True, timeout=600)
    seconds = time.perf_counter() - started
    robot.terminate()
    log, _ = robot.communicate(timeout=20)
    summary = run.stderr
    ticks = int(re.search(r"ticks\s+(\d+)", summary).group(1))  # type: ignore[union-attr]
    late = re.search(r"late ticks\s+(\d+) \(worst ([\d.]+) ms\)", summary)
    gaps = []
    ended: float | None = None
    for line in log.splitlines():
        stamp, _, text = line.partition(" ")
        if text.startswith("succeeded "):
            ended = float(stamp)
        elif text.startswith("goal ") and ended is not None:
            gaps.append((float(stamp) - ended) * 1000)
            ended = None
    return {"rate": rate, "reached": run.returncode == 0, "ticks": ticks,
            "seconds": seconds, "late": int(late.group(1)) if late else 0,
            "worst_ms": float(late.group(2)) if late else 0.0, "gaps": gaps}


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    parser.add_argument("--rates", type=float, nargs="+", default=[10, 50])
    args = parser.parse_args()
    print(f"{'hz':>4} {'goal':>5} {'ticks':>6} {'late':>5} {'worst ms':>9} "
          f"{'result->next goal ms (median / max, n)':>40}")
    for number, rate in enumerate(args.rates):
        row = one(rate, 70 + number)
        gaps = row["gaps"]
        assert isinstance(gaps, list)
        spread = (f"{statistics.median(gaps):.0f} / {max(gaps):.0f}, {len(gaps)}"
                  if gaps else "-")
        print(f"{rate:>4g} {'yes' if row['reached'] else 'no':>5} {row['ticks']:>6} "
              f"{row['late']:>5} {row['worst_ms']:>9.1f} {spread:>40}")


if __name__ == "__main__":
    main()
