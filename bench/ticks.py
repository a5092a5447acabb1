"""Tick speed of btplan's engine beside BehaviorTree.CPP 4 and py_trees 2.x, on the same trees.

Every engine gets the same tree: a Parallel over goal subtrees, each grown by
backchaining as PA-BT does (`Fallback(condition, Sequence(pre-condition subtrees...,
action))`), reactive composites (BT.CPP: ReactiveFallback, ReactiveSequence and
Parallel, its C++ built-ins, loaded from XML). Conditions read one shared set of true
facts; one action in twenty stays RUNNING, the others succeed at once. One expanded
condition in ten, and one in two of those heading a RUNNING Fallback, flip between
ticks (the facts alternate between two sets), so on every tick reactive composites
preempt subtrees the tick before ran and halt them: the running actions halted per
tick must be above zero and agree between btplan, BT.CPP and py_trees. The nodes each
tick reaches are counted in every engine, tick by tick, and must agree too (BT.CPP's
are counted in a copy whose every node sits under a counting decorator). Node-ticks per
second = ticks x nodes reached per tick / seconds.

BT.CPP runs each tree twice:

- "Python leaves": each condition and action is a Python callback registered in BT.CPP
  (one registered ID per leaf, so a callback is a closure doing one set lookup and
  never asks the node for its name). This is the same leaves' logic as btplan's, but
  every leaf tick crosses from C++ into Python and back, which costs more than the C++
  controls around it: the output says how much of BT.CPP's tick time that crossing
  takes.
- "C++ leaves": the same logic out of BT.CPP's own leaves, so that no Python runs while
  it ticks. A condition that always holds is AlwaysSuccess, one that never holds
  AlwaysFailure, and one that flips is a ScriptCondition on a blackboard flag (set
  once per tick from Python); an action that succeeds at once is AlwaysSuccess, and one
  that stays RUNNING is a WaitValueUpdate on an entry nothing writes (RUNNING without
  ticking its child, so it reaches one node as an action does). These are the
  cheapest leaves BT.CPP has for this logic, so this run is BT.CPP's best case.

The target line takes the lower of btplan's two ratios to BT.CPP over every tree size
(in practice the C++ leaves run): met when it is at least 1.0.

    python bench/ticks.py                  # ~1k and ~10k nodes, 3 s per engine and size,
                                           # in 10 alternating rounds (best round kept)
    python bench/ticks.py --seconds 1 --sizes 1000
"""

from __future__ import annotations

import argparse
import contextlib
import os
import random
import sys
import time
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

from btplan.bt import (
    FAILURE,
    RUNNING,
    SUCCESS,
    Action,
    BehaviorTree,
    Condition,
    Fallback,
    Node,
    Parallel,
    Sequence,
)
from btplan.bt.status import Status
from btplan.bt.trace import TickRecorder
from btplan.bt.world import LeafKey

FLIP_SHARE = 0.1
COUNTED_TICKS = 6  # ticks compared between engines; the last two make the measured period
TARGET = "ticks: at least 1.0x BT.CPP's C++ built-ins"


@dataclass
class Shape:
    """A tree described once and built in every engine: (kind, label, children)."""

    kind: str
    label: str
    children: list[Shape] = field(default_factory=list)


def pa_bt(rng: random.Random, depth: int, branching: int, counter: list[int]) -> Shape:
    """The atomic BT of one condition, expanded `depth` times (the paper's Figure 4 shape)."""
    counter[0] += 1
    number = counter[0]
    if depth == 0:
        return Shape("condition", f"f{number}")
    cond = Shape("condition", f"c{number}")
    pres = [pa_bt(rng, depth - 1, branching, counter) for _ in range(branching)]
    action = Shape("action", f"a{number}")
    return Shape("fallback", "", [cond, Shape("sequence", "", [*pres, action])])


def goal_forest(nodes: int, seed: int) -> Shape:
    """Enough depth-5 goal subtrees under a Parallel to reach about `nodes` nodes (depth 4
    below 3,000 nodes)."""
    rng, counter = random.Random(seed), [0]
    goals: list[Shape] = []
    while 1 + sum(size(g) for g in goals) < nodes:
        goals.append(pa_bt(rng, 4 if nodes < 3000 else 5, 3, counter))
    return Shape("parallel", "", goals)


def size(shape: Shape) -> int:
    return 1 + sum(size(c) for c in shape.children)


def labels(shape: Shape, kind: str) -> list[str]:
    out = [shape.label] if shape.kind == kind else []
    for child in shape.children:
        out.extend(labels(child, kind))
    return out


@dataclass
class Scenario:
    """What the leaves answer: facts on odd ticks, facts on even ticks, running actions."""

    odd: frozenset[str]
    even: frozenset[str]
    running: frozenset[str]

    def flips(self) -> frozenset[str]:
        return self.odd ^ self.even


def scenario(shape: Shape, rng: random.Random) -> Scenario:
    """Which conditions hold on each tick and which actions stay RUNNING.

    Goal conditions are false and each goal's own action keeps running, so every goal
    subtree stays RUNNING. Fringe conditions (never expanded, `f...`) hold, as PA-BT
    stops expanding at facts true in the state; half of the expanded ones (`c...`) hold;
    one other action in twenty keeps running. Then, on odd ticks, one expanded condition
    in ten flips, and so does one in two of those whose Fallback is RUNNING on even
    ticks (its Sequence has a running action): when that condition holds, the Fallback
    succeeds at once and halts the running Sequence, and the Sequence above goes on to
    the children after it; on the next tick the Fallback runs its Sequence again, and
    the Sequence above halts what ran after it. Only conditions that head a Fallback
    flip, and no subtree of this tree can fail (fringe conditions hold and actions never
    fail), so a flip never fails a goal.
    """
    goals = {goal.children[0].label for goal in shape.children}
    running = {goal.children[1].children[-1].label for goal in shape.children}
    true: set[str] = set()
    for label in labels(shape, "condition"):
        if label.startswith("f") or (label not in goals and rng.random() < 0.5):
            true.add(label)
    running |= {a for a in labels(shape, "action") if rng.random() < 0.05}
    flips = {c for c in labels(shape, "condition")
             if c.startswith("c") and c not in goals and rng.random() < FLIP_SHARE}
    flips |= {c for c in running_heads(shape, true, running)
              if c not in goals and rng.random() < 0.5}
    return Scenario(frozenset(true ^ flips), frozenset(true), frozenset(running))


def running_heads(shape: Shape, true: set[str], running: set[str]) -> list[str]:
    """The conditions heading the Fallbacks that one tick reaches and leaves RUNNING."""
    out: list[str] = []

    def status(s: Shape) -> str:
        if s.kind == "condition":
            return "S" if s.label in true else "F"
        if s.kind == "action":
            return "R" if s.label in running else "S"
        if s.kind == "parallel":
            found = [status(c) for c in s.children]
            return "F" if "F" in found else "R" if "R" in found else "S"
        go_on = "F" if s.kind == "fallback" else "S"
        for child in s.children:
            if (answer := status(child)) != go_on:
                break
        if answer == "R" and s.kind == "fallback":
            out.append(s.children[0].label)
        return answer

    status(shape)
    return out


@dataclass
class Engine:
    """One engine ready to tick one tree.

    `period` ticks the measured tree twice (odd facts, then even facts); `trace` holds,
    for each of the first ticks of a separate counted copy, the nodes reached, the
    actions halted (None where the engine cannot tell) and the root's status.
    """

    name: str
    period: Callable[[], object]
    trace: list[tuple[int, int | None, str]]

    def per_period(self) -> int:
        """Nodes reached by the two ticks of one period, once the tree ticks in its cycle."""
        return sum(n for n, _, _ in self.trace[-2:])


class Facts:
    """The one set of true facts every leaf reads; `now` alternates between two sets."""

    def __init__(self, now: frozenset[str]) -> None:
        self.now = now


# --- btplan --------------------------------------------------------------------------------


class FlipWorld:
    """Conditions are members of `now`; actions in `running` stay RUNNING, others succeed;
    `halts` counts the actions halted while RUNNING. Facts are held as btplan's leaf keys,
    so a check is one set lookup, as in the other engines' leaves."""

    def __init__(self, now: frozenset[LeafKey], running: frozenset[str]) -> None:
        self.now = now
        self.running = keys(running)
        self.halts = 0

    def check(self, key: LeafKey) -> bool:
        return key in self.now

    def start(self, key: LeafKey) -> Status:
        return RUNNING if key in self.running else SUCCESS

    def step(self, key: LeafKey) -> Status:
        return RUNNING if key in self.running else SUCCESS

    def halt(self, key: LeafKey) -> None:
        self.halts += 1


def keys(labels: frozenset[str]) -> frozenset[LeafKey]:
    return frozenset((label, ()) for label in labels)


def build_btplan(shape: Shape) -> Node:
    children = [build_btplan(c) for c in shape.children]
    if shape.kind == "condition":
        return Condition(shape.label)
    if shape.kind == "action":
        return Action(shape.label)
    if shape.kind == "parallel":
        return Parallel(children, success=-1)
    return (Fallback if shape.kind == "fallback" else Sequence)(children)


def btplan_engine(shape: Shape, plan: Scenario) -> Engine:
    odd, even = keys(plan.odd), keys(plan.even)
    tree, world = BehaviorTree(build_btplan(shape)), FlipWorld(even, plan.running)

    def period() -> None:
        world.now = odd
        tree.tick(world)
        world.now = even
        tree.tick(world)

    counted, counting = BehaviorTree(build_btplan(shape)), FlipWorld(even, plan.running)
    recorder = TickRecorder()
    recorder.attach(counted)
    trace: list[tuple[int, int | None, str]] = []
    for tick in range(1, COUNTED_TICKS + 1):
        counting.now = odd if tick % 2 else even
        halts = counting.halts
        status = counted.tick(counting)
        assert recorder.last is not None
        trace.append((len(recorder.last.nodes), counting.halts - halts, status.value))
    return Engine("btplan", period, trace)


# --- BehaviorTree.CPP ----------------------------------------------------------------------


@contextlib.contextmanager
def quiet_stdout() -> Iterator[None]:
    """Keep BT.CPP's own prints on file descriptor 1 out of the table while it loads."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "w") as sink:
            os.dup2(sink.fileno(), 1)
            yield
    finally:
        os.dup2(saved, 1)
        os.close(saved)


def btcpp_xml(shape: Shape, leaf: Callable[[Shape], ET.Element], counted: bool) -> str:
    """The tree as a BT.CPP 4 document of its built-in controls; `counted` puts every node
    that can be reached under a `Count` decorator."""

    def element(s: Shape) -> ET.Element:
        if s.kind in ("condition", "action"):
            node = leaf(s)
        elif s.kind == "parallel":
            node = ET.Element("Parallel", success_count="-1", failure_count="1")
        else:
            node = ET.Element("ReactiveFallback" if s.kind == "fallback" else "ReactiveSequence")
        node.extend(element(c) for c in s.children)
        if not counted:
            return node
        wrapper = ET.Element("Count")
        wrapper.append(node)
        return wrapper

    root = ET.Element("root", BTCPP_format="4", main_tree_to_execute="Main")
    ET.SubElement(root, "BehaviorTree", ID="Main").append(element(shape))
    return ET.tostring(root, encoding="unicode")


def python_leaves_engine(shape: Shape, plan: Scenario) -> Engine:
    """BT.CPP's controls, each leaf a Python callback of its own registered ID."""
    import behaviortreepy as bt  # type: ignore[import-untyped]

    ok, no, run = bt.NodeStatus.SUCCESS, bt.NodeStatus.FAILURE, bt.NodeStatus.RUNNING
    names = {ok: "SUCCESS", no: "FAILURE", run: "RUNNING"}

    def load(counted: bool) -> tuple[object, Facts, list[int], list[int]]:
        facts, running, halts = Facts(plan.even), plan.running, [0]
        factory = bt.BehaviorTreeFactory()
        for label in labels(shape, "condition"):
            factory.register_simple_condition(
                f"L_{label}", lambda node, k=label: ok if k in facts.now else no)
        for label in labels(shape, "action"):
            answer = (lambda node, k=label: run if k in running else ok)
            factory.register_simple_stateful_action(
                f"L_{label}", answer, answer, lambda node: halts.__setitem__(0, halts[0] + 1))
        reached = [0]

        def count(status: object, node: object) -> object:
            reached[0] += 1
            return status

        factory.register_simple_decorator("Count", count)
        text = btcpp_xml(shape, lambda s: ET.Element(f"L_{s.label}"), counted)
        with quiet_stdout():
            tree = factory.create_tree_from_text(text)
        return tree, facts, reached, halts

    tree, facts, _, _ = load(False)
    tick = tree.tick_exactly_once  # type: ignore[attr-defined]
    odd, even = plan.odd, plan.even

    def period() -> None:
        facts.now = odd
        tick()
        facts.now = even
        tick()

    counted, counts, reached, halts = load(True)
    trace: list[tuple[int, int | None, str]] = []
    for number in range(1, COUNTED_TICKS + 1):
        counts.now = odd if number % 2 else even
        before = reached[0], halts[0]
        status = counted.tick_exactly_once()  # type: ignore[attr-defined]
        trace.append((reached[0] - before[0], halts[0] - before[1], names[status]))
    return Engine("BT.CPP Python leaves", period, trace)


def builtin_leaves_engine(shape: Shape, plan: Scenario) -> Engine:
    """BT.CPP's controls and its own leaves: no Python runs while it ticks."""
    import behaviortreepy as bt

    names = {bt.NodeStatus.SUCCESS: "SUCCESS", bt.NodeStatus.FAILURE: "FAILURE",
             bt.NodeStatus.RUNNING: "RUNNING"}
    flips = plan.flips()

    def leaf(s: Shape) -> ET.Element:
        if s.kind == "action":
            if s.label not in plan.running:
                return ET.Element("AlwaysSuccess")
            wait = ET.Element("WaitValueUpdate", entry="{never_written}")
            wait.append(ET.Element("AlwaysSuccess"))
            return wait
        if s.label in flips:
            return ET.Element("ScriptCondition", code="odd" if s.label in plan.odd else "!odd")
        return ET.Element("AlwaysSuccess" if s.label in plan.even else "AlwaysFailure")

    def load(counted: bool) -> tuple[object, object, list[int]]:
        factory = bt.BehaviorTreeFactory()
        reached = [0]

        def count(status: object, node: object) -> object:
            reached[0] += 1
            return status

        factory.register_simple_decorator("Count", count)
        with quiet_stdout():
            tree = factory.create_tree_from_text(btcpp_xml(shape, leaf, counted))
        board = tree.root_blackboard()
        board.set_bool("odd", False)
        return tree, board, reached

    tree, board, _ = load(False)
    tick, flag = tree.tick_exactly_once, board.set_bool  # type: ignore[attr-defined]

    def period() -> None:
        flag("odd", True)
        tick()
        flag("odd", False)
        tick()

    counted, counted_board, reached = load(True)
    trace: list[tuple[int, int | None, str]] = []
    for number in range(1, COUNTED_TICKS + 1):
        counted_board.set_bool("odd", bool(number % 2))  # type: ignore[attr-defined]
        before = reached[0]
        status = counted.tick_exactly_once()  # type: ignore[attr-defined]
        trace.append((reached[0] - before, None, names[status]))
    return Engine("BT.CPP C++ leaves", period, trace)


# --- py_trees ------------------------------------------------------------------------------


def py_trees_engine(shape: Shape, plan: Scenario) -> Engine:
    import py_trees
    from py_trees.common import Status as PS

    def load() -> tuple[py_trees.behaviour.Behaviour, Facts, list[int]]:
        facts, running, halts = Facts(plan.even), plan.running, [0]

        class Check(py_trees.behaviour.Behaviour):
            def update(self) -> PS:
                return PS.SUCCESS if self.name in facts.now else PS.FAILURE

        class Run(py_trees.behaviour.Behaviour):
            def update(self) -> PS:
                return PS.RUNNING if self.name in running else PS.SUCCESS

            def terminate(self, new_status: PS) -> None:
                if new_status is PS.INVALID and self.status is PS.RUNNING:
                    halts[0] += 1

        def build(s: Shape) -> py_trees.behaviour.Behaviour:
            kids = [build(c) for c in s.children]
            if s.kind == "condition":
                return Check(s.label)
            if s.kind == "action":
                return Run(s.label)
            if s.kind == "parallel":
                policy = py_trees.common.ParallelPolicy.SuccessOnAll(synchronise=False)
                return py_trees.composites.Parallel("par", policy, kids)
            if s.kind == "fallback":
                return py_trees.composites.Selector("fb", memory=False, children=kids)
            return py_trees.composites.Sequence("seq", memory=False, children=kids)

        return build(shape), facts, halts

    root, facts, _ = load()
    tick = root.tick_once
    odd, even = plan.odd, plan.even

    def period() -> None:
        facts.now = odd
        tick()
        facts.now = even
        tick()

    counted, counts, halts = load()
    seen = [0]

    class Count(py_trees.visitors.VisitorBase):
        def run(self, behaviour: object) -> None:
            seen[0] += 1

    counting = py_trees.trees.BehaviourTree(counted)
    counting.visitors.append(Count())
    trace: list[tuple[int, int | None, str]] = []
    for number in range(1, COUNTED_TICKS + 1):
        counts.now = odd if number % 2 else even
        before = seen[0], halts[0]
        counting.tick()
        trace.append((seen[0] - before[0], halts[0] - before[1], counted.status.name))
    return Engine("py_trees", period, trace)


# --- measurement ---------------------------------------------------------------------------


def engines(shape: Shape, plan: Scenario, with_py_trees: bool = True) -> list[Engine]:
    """btplan, BT.CPP with Python leaves, BT.CPP with its own leaves (and py_trees), after
    checking that their counted ticks agree."""
    out = [btplan_engine(shape, plan), python_leaves_engine(shape, plan),
           builtin_leaves_engine(shape, plan)]
    if with_py_trees:
        out.append(py_trees_engine(shape, plan))
    check_agreement(out)
    return out


def check_agreement(found: list[Engine]) -> None:
    """Every engine reached the same nodes and gave the same status on every counted tick,
    halted the same actions where it can tell, halted some, and ticks in a cycle of two."""
    ours = found[0].trace
    for engine in found[1:]:
        for tick, (mine, theirs) in enumerate(zip(ours, engine.trace, strict=True), 1):
            same_halts = theirs[1] is None or theirs[1] == mine[1]
            assert mine[0] == theirs[0] and mine[2] == theirs[2] and same_halts, (
                f"tick {tick}: btplan reached {mine[0]} nodes, halted {mine[1]}, "
                f"{mine[2]}; {engine.name} {theirs[0]}, {theirs[1]}, {theirs[2]}")
    assert ours[-4:-2] == ours[-2:], f"not yet ticking in a cycle of two: {ours}"
    assert sum(h or 0 for _, h, _ in ours[-2:]) > 0, "no action was halted"


def rate(period: Callable[[], object], per_period: int, seconds: float) -> float:
    """Node-ticks per second over at least `seconds`, in batches to keep clock reads rare."""
    periods, batch = 0, 1
    start = time.perf_counter()
    while (elapsed := time.perf_counter() - start) < seconds:
        for _ in range(batch):
            period()
        periods += batch
        batch = min(batch * 2, 32)
    return periods * per_period / elapsed


@dataclass
class Row:
    nodes: int
    reached: float
    halts: float
    rates: dict[str, float]

    def ratio(self, other: str) -> float:
        return self.rates["btplan"] / self.rates[other]


def measure(wanted: int, seed: int, seconds: float, rounds: int,
            with_py_trees: bool = True) -> Row:
    """One tree size: every engine, alternating, each one's best round kept (the machine is
    shared, and a burst of other work should not decide a ratio)."""
    shape = goal_forest(wanted, seed)
    plan = scenario(shape, random.Random(seed))
    found = engines(shape, plan, with_py_trees)
    best = dict.fromkeys((e.name for e in found), 0.0)
    for _ in range(rounds):
        for engine in found:
            best[engine.name] = max(best[engine.name], rate(
                engine.period, engine.per_period(), seconds / rounds))
    trace = found[0].trace[-2:]
    return Row(size(shape), sum(n for n, _, _ in trace) / 2,
               sum(h or 0 for _, h, _ in trace) / 2, best)


def table(rows: list[Row]) -> list[str]:
    with_py_trees = all("py_trees" in r.rates for r in rows)
    head = (f"{'nodes':>7} {'reached':>8} {'halts':>6} {'btplan':>11} {'BT.CPP py':>11} "
            f"{'BT.CPP C++':>11}" + (f" {'py_trees':>9}" if with_py_trees else "")
            + f" {'/BT.CPP py':>10} {'/BT.CPP C++':>11}" + (" /py_trees" if with_py_trees else ""))
    lines = ["node-ticks/s; reached and halts per tick (mean of the two ticks of a cycle); "
             "ratios are btplan's", head]
    for r in rows:
        line = (f"{r.nodes:>7} {r.reached:>8.1f} {r.halts:>6.1f} {r.rates['btplan']:>11,.0f} "
                f"{r.rates['BT.CPP Python leaves']:>11,.0f} "
                f"{r.rates['BT.CPP C++ leaves']:>11,.0f}")
        if with_py_trees:
            line += f" {r.rates['py_trees']:>9,.0f}"
        line += (f" {r.ratio('BT.CPP Python leaves'):>9.2f}x"
                 f" {r.ratio('BT.CPP C++ leaves'):>10.2f}x")
        if with_py_trees:
            line += f" {r.ratio('py_trees'):>8.1f}x"
        lines.append(line)
    return lines


def verdicts(rows: list[Row]) -> list[str]:
    """How much of BT.CPP's tick the Python leaves take, and the target, judged on the
    slower of btplan's two ratios to BT.CPP over every tree."""
    share = max(1 - r.rates["BT.CPP Python leaves"] / r.rates["BT.CPP C++ leaves"]
                for r in rows)
    lines = [f"BT.CPP with Python leaves spends up to {share:.0%} of its tick time in the "
             "leaf callbacks (C++ to Python and back)"
             + (": they dominate its cost, so the C++ leaves run is the fair one"
                if share > 0.5 else "")]
    worst = min(min(r.ratio("BT.CPP Python leaves"), r.ratio("BT.CPP C++ leaves"))
                for r in rows)
    lines.append(f"{TARGET} (worst ratio {worst:.2f}x): {'met' if worst >= 1.0 else 'missed'}")
    return lines


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[1000, 10000])
    parser.add_argument("--seconds", type=float, default=3.0)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--rounds", type=int, default=10)
    args = parser.parse_args()
    rows = [measure(n, args.seed, args.seconds, args.rounds) for n in args.sizes]
    print("\n".join(table(rows) + verdicts(rows)))


if __name__ == "__main__":
    main()
