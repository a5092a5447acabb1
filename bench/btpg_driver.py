"""BTPG's planners on one goal set, one JSON line per goal and planner.

bench/btpg.py starts this script with BTPG's own Python (its virtual environment) and
reads what it prints; it imports nothing of btplan. BTPG is imported from its source
folder as BTPG's examples use it: a `BTPlannerInterface` per goal over RoboWaiter's
behaviour library, and the time is that of its `process()` (the synthesis alone; the
library and the grounded actions are built before the clock starts, as BTPG's own
benchmark scripts do). Each planner is warmed up once on the first goal and the best
of `--repeat` calls is kept (no garbage collection is forced before a call: it leaves
the caches cold and triples a sub-millisecond time).

BTPG's planning code imports its simulators and LLM clients at module level. Modules
BTPG's files import that its environment does not have are given inert stand-ins
(planning never calls them). At BTPG's HEAD, `obtea.py` and `hbtp.py` use names they
no longer import (`CondActPair`, `Action`) and OBTEA reads a `max_expanded_num` it never
sets; the names are taken from BTPG's own `bt_planning_exp` twins and the limit is
left unbounded, at run time: no file of BTPG is changed. Its planners print every
iteration; those prints are silenced, as they would otherwise be timed.

The tree BTPG returns is run from the initial state on BTPG's own action model (a
tick gives the action to run; its effects are applied; again until the tree succeeds
or fails) and the executed actions are printed, so that bench/btpg.py can replay
them on the PDDL model as it does btplan's.

    PYTHONHASHSEED=0 BTPG_PYTHON bench/btpg_driver.py BTPG_SRC goals.json --timeout 10
"""

from __future__ import annotations

import argparse
import ast
import importlib
import importlib.abc
import importlib.machinery
import json
import os
import sys
import time
import types
from pathlib import Path
from typing import Any
from unittest import mock

PLANNERS = {"obtea": "OBTEA", "opt": "HBTP", "bfs": "BTExpansion"}
"""BTPG's names for its planners (`selected_algorithm`) and the names the papers use."""

MAX_STEPS = 300
"""Actions a tree may run from the initial state before its run counts as failed."""


# --- importing BTPG -----------------------------------------------------------------------


def imported_names(source: Path) -> set[str]:
    """Every module BTPG's files import by absolute name, with its parent packages (and,
    for `from package import name`, package.name)."""
    names: set[str] = set()
    for path in source.rglob("*.py"):
        try:
            tree = ast.parse(path.read_text(encoding="utf-8", errors="replace"))
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                modules = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                # `from package import name`: the name may be a module of its own
                modules = [node.module, *(f"{node.module}.{a.name}" for a in node.names)]
            else:
                continue
            for module in modules:
                parts = module.split(".")
                names.update(".".join(parts[:n]) for n in range(1, len(parts) + 1))
    return names


class StandIn(types.ModuleType):
    """A module BTPG imports but never calls while planning: every attribute is a mock."""

    __path__: list[str] = []

    def __getattr__(self, name: str) -> Any:
        if name.startswith("__"):
            raise AttributeError(name)
        value = mock.MagicMock(name=f"{self.__name__}.{name}")
        setattr(self, name, value)
        return value


class StandInFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Last on the import path: a module BTPG names that nothing else found is a stand-in."""

    def __init__(self, names: set[str]) -> None:
        self.names = names
        self.given: list[str] = []

    def find_spec(self, name: str, path: Any = None,
                  target: Any = None) -> importlib.machinery.ModuleSpec | None:
        if name not in self.names:
            return None
        self.given.append(name)
        return importlib.machinery.ModuleSpec(name, self, is_package=True)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        return StandIn(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        pass


def import_btpg(source: Path) -> tuple[Any, Any]:
    """BTPG's planner interface class and its state-update function, ready to plan."""
    sys.path.insert(0, str(source))
    finder = StandInFinder(imported_names(source / "btpg") | imported_names(source / "metric"))
    sys.meta_path.append(finder)
    here = os.getcwd()
    try:
        interface = importlib.import_module("btpg.algos.bt_planning.bt_planner_interface")
    finally:
        os.chdir(here)  # the interface module changes into BTPG's examples folder
    _mend(interface)
    _silence()
    stood_in = sorted({name if name.startswith("btpg.") else name.partition(".")[0]
                       for name in finder.given})
    print(f"stand-ins for modules BTPG imports but its environment lacks: "
          f"{', '.join(stood_in) or 'none'}", file=sys.stderr)
    return interface.BTPlannerInterface, importlib.import_module(
        "btpg.algos.base.planning_action").state_transition


def _mend(interface: Any) -> None:
    """The names OBTEA's and HBTP's modules lost at BTPG's HEAD, from their own twins."""
    action = importlib.import_module("btpg.algos.base.planning_action").PlanningAction
    for planner, twin in (("obtea", "obtea_test"), ("hbtp", "hbtp_test")):
        module = importlib.import_module(f"btpg.algos.bt_planning.{planner}")
        origin = importlib.import_module(f"btpg.algos.bt_planning_exp.{twin}")
        module.__dict__.setdefault("CondActPair", origin.CondActPair)
        module.__dict__.setdefault("Action", action)
    # A class attribute, read when an instance has none: OBTEA's __init__ never sets it.
    interface.OBTEA.max_expanded_num = float("inf")


def _silence() -> None:
    """No output from BTPG's planning modules: their prints would be timed with them."""
    for name, module in list(sys.modules.items()):
        if name.startswith("btpg.algos") and isinstance(module, types.ModuleType):
            module.print = lambda *args, **kwargs: None  # type: ignore[attr-defined]


# --- the RoboWaiter scene -----------------------------------------------------------------


def robowaiter() -> tuple[Any, set[str]]:
    """RoboWaiter's behaviour library and initial state, as BTPG's environment sets them up
    (btpg.utils.tools.setup_environment): at the bar, hands empty, and every object
    present except the ones the robot makes (coffee, water, dessert)."""
    libraries = importlib.import_module("btpg.behavior_tree.behavior_libs")
    actions = importlib.import_module("btpg.envs.robowaiter.exec_lib._base.rw_action")
    root = importlib.import_module("btpg.utils").ROOT_PATH
    library = libraries.ExecBehaviorLibrary(f"{root}/envs/robowaiter/exec_lib")
    made = {"Coffee", "Water", "Dessert"}
    state = {"RobotNear(Bar)", "Holding(Nothing)"}
    state |= {f"Exists({thing})" for thing in actions.RWAction.all_object - made}
    return library, state


SCENES = {"RW": robowaiter}


# --- one planner on one goal --------------------------------------------------------------


def tree_counts(node: Any) -> tuple[int, int, int]:
    """(nodes, condition leaves, literals in them): a BTPG condition leaf is a conjunction."""
    children = getattr(node, "children", None)
    if children is None:
        literals = len(node.content) if node.type == "cond" else 0
        return 1, int(node.type == "cond"), literals
    counts = [1, 0, 0]
    for child in children:
        for number, value in enumerate(tree_counts(child)):
            counts[number] += value
    return counts[0], counts[1], counts[2]


def the_tree(wrapper: Any) -> Any:
    """The tree under the one-child condition wrapper BTPG's planners return."""
    children = getattr(wrapper, "children", None)
    return children[0] if wrapper.type == "cond" and children else wrapper


def run_tree(tree: Any, state: set[str], transition: Any) -> tuple[str, list[Any]]:
    """Tick the tree on BTPG's model until it stops running: its verdict and the actions."""
    done: list[Any] = []
    verdict, what = tree.tick(state)
    while verdict == "running" and len(done) < MAX_STEPS:
        done.append(what)
        state = transition(state, what)
        verdict, what = tree.tick(state)
    return verdict, done


def plan_once(interface: Any, library: Any, state: set[str], goal: set[str], planner: str,
              timeout: float, just_best: bool) -> tuple[Any, float]:
    """One timed `process()`: the interface that ran it and its seconds."""
    planning = interface(library, cur_cond_set=set(state), selected_algorithm=planner,
                         mode="big", time_limit=timeout, heuristic_choice=-1,
                         output_just_best=just_best)
    started = time.perf_counter()
    planning.process([set(goal)])
    return planning, time.perf_counter() - started


def measure(interface: Any, transition: Any, library: Any, state: set[str], goal: set[str],
            planner: str, timeout: float, just_best: bool, repeat: int) -> dict[str, Any]:
    """What one planner does on one goal: time (best of `repeat`), tree, plan."""
    row: dict[str, Any] = {"planner": PLANNERS[planner], "solved": False}
    best = float("inf")
    try:
        for _ in range(repeat):
            planning, seconds = plan_once(interface, library, state, goal, planner, timeout,
                                          just_best)
            best = min(best, seconds)
    except Exception as error:  # BTPG's own failure, reported as that planner's result
        row["note"] = f"crashed: {type(error).__name__}: {error}"[:200]
        return row
    algorithm = planning.algo
    row["seconds"] = best
    row["expansions"] = len(algorithm.expanded)
    if getattr(algorithm, "time_limit_exceeded", False):
        row["note"] = "time limit"
        return row
    tree = the_tree(algorithm.bt)
    row["tree_nodes"], row["condition_nodes"], row["condition_literals"] = tree_counts(tree)
    verdict, done = run_tree(tree, set(state), transition)
    row["plan"] = [action.name for action in done]
    row["plan_cost"] = sum(action.real_cost for action in done)
    if verdict != "success":
        row["note"] = f"the tree's run ended in {verdict} after {len(done)} actions"
    else:
        row["solved"] = True
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("source", type=Path, help="BTPG's exported source folder")
    parser.add_argument("goals", type=Path, help="the goal set's goals.json")
    parser.add_argument("--planners", default=",".join(PLANNERS))
    parser.add_argument("--timeout", type=float, default=10.0)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--first", type=int, help="only the first N goals")
    parser.add_argument("--just-best", action="store_true",
                        help="BTPG's output_just_best: only the cheapest branch in the tree")
    args = parser.parse_args()
    meta = json.loads(args.goals.read_text(encoding="utf-8"))
    records = [r for r in meta["records"] if "problem" in r][:args.first]
    interface, transition = import_btpg(args.source.resolve())
    library, state = SCENES[meta["scene"]]()
    planners = [p for p in args.planners.split(",") if p]
    for planner in planners:  # warm-up: first calls pay for lazy set-ups
        if records:
            measure(interface, transition, library, state, set(records[0]["literals"]),
                    planner, args.timeout, args.just_best, 1)
    for record in records:
        for planner in planners:
            row = measure(interface, transition, library, state, set(record["literals"]),
                          planner, args.timeout, args.just_best, args.repeat)
            row["index"] = record["index"]
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
