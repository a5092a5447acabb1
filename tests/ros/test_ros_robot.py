"""The blended loop on a ROS 2 robot: real processes on real DDS, confined to loopback.

Each test starts the fake robot of examples/ros (action servers and state topics for
the paper's Example 2) and `btplan run --ros`, in a ROS domain of its own, with Fast DDS
on 127.0.0.1 only (loopback.xml): nothing leaves this machine."""

from __future__ import annotations

import itertools
import json
import os
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FAKE = ROOT / "examples" / "ros" / "fake_robot.py"
BINDINGS = ROOT / "examples" / "ros" / "example2.toml"
DOMAIN = str(ROOT / "domains" / "pick_place_obstacle.bt")
SPEED = "2"
"""The fake robot's time runs this much faster, to keep the tests lean."""

_domains = itertools.count(20 + os.getpid() % 40)


def ros_env() -> dict[str, str]:
    """A ROS domain of this test's own, discovery on this machine, Fast DDS on loopback."""
    return {**os.environ, "ROS_DOMAIN_ID": str(next(_domains)),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
            "FASTDDS_DEFAULT_PROFILES_FILE": str(Path(__file__).with_name("loopback.xml")),
            "PYTHONUNBUFFERED": "1"}


class Robot:
    """The fake robot, running in its own process until the test ends."""

    def __init__(self, env: dict[str, str], *flags: str) -> None:
        self.log = ""
        self.process = subprocess.Popen([sys.executable, str(FAKE), "--speed", SPEED, *flags],
                                        env=env, stdout=subprocess.PIPE,
                                        stderr=subprocess.STDOUT, text=True)
        assert self.process.stdout is not None
        first = self.process.stdout.readline()
        assert "fake robot ready" in first, first

    def stop(self) -> str:
        self.process.terminate()
        try:
            out, _ = self.process.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.process.kill()
            out, _ = self.process.communicate()
        self.log = out
        return out


@pytest.fixture
def env() -> dict[str, str]:
    return ros_env()


@pytest.fixture
def robot_factory(env: dict[str, str]) -> Iterator[object]:
    made: list[Robot] = []

    def make(*flags: str) -> Robot:
        made.append(Robot(env, *flags))
        return made[-1]

    yield make
    for robot in made:
        if robot.process.poll() is None:
            robot.stop()


def btplan_run(env: dict[str, str], tmp_path: Path, *flags: str, bindings: Path = BINDINGS
               ) -> tuple[subprocess.CompletedProcess[str], list[dict[str, object]]]:
    trace = tmp_path / "run.jsonl"
    done = subprocess.run([sys.executable, "-m", "btplan", "run", DOMAIN, "--ros",
                           str(bindings), "--hz", "50", "-q", "--trace", str(trace), *flags],
                          env=env, capture_output=True, text=True, timeout=300)
    lines = [json.loads(line) for line in trace.read_text().splitlines()] \
        if trace.exists() else []
    return done, lines


def grown(lines: list[dict[str, object]]) -> list[tuple[int, list[str]]]:
    return [(int(line["tick"]), [e["condition"] for e in line["expansions"]])  # type: ignore[index,union-attr]
            for line in lines if line["expansions"]]


def test_example_2_grows_the_clearing_subtree_when_the_sphere_blocks_the_path(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    robot = robot_factory("--sphere-rolls")  # type: ignore[operator]
    done, lines = btplan_run(env, tmp_path)
    log = robot.stop()
    assert done.returncode == 0, done.stderr
    growth = grown(lines)
    assert growth[0][0] == 1  # the plan, then, at run time, the subtree that clears the path
    tick = next(t for t, conditions in growth[1:] if conditions[0] == "not blocks(_, tau_goal)")
    assert tick > 1
    assert "blocks(sphere, tau_goal)" in lines[tick - 1]["facts"]["added"]  # type: ignore[index]
    # What the robot did, by its own log: the loop credits an action whose effects show
    # before its result as done, so the trace's order depends on timing.
    assert "succeeded place sphere" in log
    assert "the sphere rolled onto the path" in log and "succeeded place cube" in log


def test_the_cube_taken_from_the_gripper_is_picked_again_with_no_growth(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    robot = robot_factory("--take-cube")  # type: ignore[operator]
    done, lines = btplan_run(env, tmp_path)
    log = robot.stop()
    assert done.returncode == 0, done.stderr
    assert [tick for tick, _ in grown(lines)] == [1]  # the paper's first property
    assert log.count("succeeded pick cube") == 2
    assert "someone took the cube" in log
    # MoveTo(goal) was running when the cube went: halting it cancelled the goal
    assert "cancel move_to" in log and "cancelled move_to" in log


def test_an_aborted_goal_is_a_failure_and_the_loop_goes_on(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    robot = robot_factory("--abort", "pick")  # type: ignore[operator]
    done, lines = btplan_run(env, tmp_path)
    log = robot.stop()
    assert done.returncode == 0, done.stderr
    errors = [e for line in lines for e in line.get("errors", [])]  # type: ignore[attr-defined]
    assert errors == [{"action": "Pick(cube)", "message": "/robot/pick aborted the goal"}]
    assert [a for line in lines for a in line["failed"]] == ["Pick(cube)"]  # type: ignore[union-attr]
    assert log.count("succeeded pick cube") == 1


def test_a_server_that_never_ends_a_goal_times_out_and_is_cancelled(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    short = tmp_path / "short.toml"
    short.write_text(BINDINGS.read_text().replace("result_timeout = 30.0",
                                                  "result_timeout = 0.5"))
    robot = robot_factory("--never-finish", "pick")  # type: ignore[operator]
    done, lines = btplan_run(env, tmp_path, "--max-ticks", "300", bindings=short)
    log = robot.stop()
    assert done.returncode == 1
    messages = {e["message"] for line in lines for e in line.get("errors", [])}  # type: ignore[attr-defined]
    assert messages == {"no result from /robot/pick within 0.5 s; the goal was cancelled"}
    assert "cancel pick" in log


def test_a_condition_read_from_a_service_drives_the_loop_too(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    by_service = tmp_path / "service.toml"
    text = BINDINGS.read_text()
    start = text.index("[conditions.hand_empty]")
    end = text.index("[conditions.on]")
    by_service.write_text(text[:start] + """[conditions.hand_empty]
service = "/robot/hand_empty"
type = "std_srvs/srv/Trigger"
when = "msg.success"
timeout = 2.0

""" + text[end:])
    robot = robot_factory()  # type: ignore[operator]
    done, lines = btplan_run(env, tmp_path, bindings=by_service)
    log = robot.stop()
    assert done.returncode == 0, done.stderr
    assert "first call of /robot/hand_empty" in log
    assert log.count("succeeded place cube") == 1


def test_a_missing_action_server_is_bad_input_naming_it(
        env: dict[str, str], tmp_path: Path) -> None:
    quick = tmp_path / "quick.toml"
    quick.write_text(BINDINGS.read_text().replace("server_wait = 10.0", "server_wait = 1.0"))
    done, lines = btplan_run(env, tmp_path, bindings=quick)
    assert done.returncode == 2
    assert "no action server /robot/drop (for Drop)" in done.stderr
    assert "Traceback" not in done.stderr and lines == []


def test_a_topic_that_never_comes_reads_false_and_the_reason_says_why(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    robot = robot_factory("--silent", "/robot/near")  # type: ignore[operator]
    done, _ = btplan_run(env, tmp_path, "--max-ticks", "40")
    robot.stop()
    assert done.returncode == 1
    assert "near: no message on /robot/near yet" in done.stderr


def test_the_tree_and_its_statuses_are_on_topics(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    robot = robot_factory()  # type: ignore[operator]
    listener = subprocess.Popen([sys.executable, "-c", LISTENER], env=env,
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert listener.stdout is not None
        assert listener.stdout.readline().strip() == "listening"  # it hears the robot
        done, lines = btplan_run(env, tmp_path, "--hz", "10")  # time for discovery
        robot.stop()
        assert done.returncode == 0, done.stderr
        out, err = listener.communicate(timeout=150)
    finally:
        if listener.poll() is None:
            listener.kill()
    seen = json.loads(out.strip().splitlines()[-1])
    assert seen["tree"].startswith("<root BTCPP_format=\"4\">") and "_uid=" in seen["tree"]
    assert seen["statuses"] > 0 and seen["last_tick"] == lines[-1]["tick"]


LISTENER = """
import json, time, rclpy
from rclpy.qos import DurabilityPolicy, QoSProfile
from std_msgs.msg import String
rclpy.init()
node = rclpy.create_node("listener")
seen = {"tree": "", "statuses": 0, "last_tick": 0}
def tree(m): seen["tree"] = m.data
def status(m):
    seen["statuses"] += 1
    seen["last_tick"] = json.loads(m.data)["tick"]
node.create_subscription(String, "/btplan/tree", tree,
                         QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
node.create_subscription(String, "/btplan/statuses", status,
                         QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL))
heard = []
node.create_subscription(String, "/robot/holding", heard.append, 10)
while not heard:  # discovery works on this domain: the robot is heard
    rclpy.spin_once(node, timeout_sec=0.1)
print("listening", flush=True)
quiet_since = began = time.monotonic()
while (time.monotonic() - quiet_since < 4.0 or not seen["statuses"] or not seen["tree"]) and (
        time.monotonic() - began < 120):
    before = seen["statuses"]
    rclpy.spin_once(node, timeout_sec=0.1)
    if seen["statuses"] != before:
        quiet_since = time.monotonic()
print(json.dumps(seen), flush=True)
"""


def test_ctrl_c_cancels_the_running_goal_before_btplan_exits(
        env: dict[str, str], robot_factory: object, tmp_path: Path) -> None:
    import signal

    robot = robot_factory("--never-finish", "pick")  # type: ignore[operator]
    trace = tmp_path / "run.jsonl"
    run = subprocess.Popen([sys.executable, "-m", "btplan", "run", DOMAIN, "--ros",
                            str(BINDINGS), "--hz", "50", "-q", "--trace", str(trace)],
                           env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while '"started":["Pick(cube)"]' not in (trace.read_text() if trace.exists() else ""):
            assert run.poll() is None and time.monotonic() < deadline
            time.sleep(0.05)
        run.send_signal(signal.SIGINT)
        _, err = run.communicate(timeout=60)
    finally:
        if run.poll() is None:
            run.kill()
    log = robot.stop()
    assert run.returncode == 130, err
    assert "cancel pick" in log and "cancelled pick" in log
    assert "Pick(cube)" in err  # the summary names the action halted on the way out


def test_an_aborted_goal_hands_over_to_the_next_alternative(
        env: dict[str, str], tmp_path: Path) -> None:
    """domains/run_alternatives.bt: the road is closed, every Drive goal is aborted after a
    while; the tree's other way, Fly, runs and is not halted for Drive again."""
    here = Path(__file__).parent
    robot = subprocess.Popen([sys.executable, str(here / "parcel_robot.py")], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        assert robot.stdout is not None and "ready" in robot.stdout.readline()
        trace = tmp_path / "run.jsonl"
        done = subprocess.run([sys.executable, "-m", "btplan", "run",
                               str(ROOT / "domains" / "run_alternatives.bt"), "--ros",
                               str(here / "parcel.toml"), "--hz", "50", "-q", "--trace",
                               str(trace)], env=env, capture_output=True, text=True,
                              timeout=300)
    finally:
        robot.terminate()
        log, _ = robot.communicate(timeout=20)
    assert done.returncode == 0, done.stderr
    lines = [json.loads(line) for line in trace.read_text().splitlines()]
    errors = [e for line in lines for e in line.get("errors", [])]
    assert {e["message"] for e in errors} == {"/parcel/drive aborted the goal"}
    assert "succeeded load" in log and "succeeded fly" in log and "succeeded drive" not in log
    assert "cancelled fly" not in log and [a for line in lines for a in line["halted"]] == []
