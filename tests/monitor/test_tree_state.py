"""A growing tree as Groot2 sees it: uids never change, new nodes get new ones, and
the tree's UUID changes exactly when the tree does."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import btplan
from btplan.acting.config import ActingConfig
from btplan.monitor.run_monitor import RunMonitor, TickUpdate
from btplan.monitor.tree_state import IDLE_FROM, TreeState

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


class Snapshots:
    """A monitor that keeps, after every tick, the uid of every node and the UUID."""

    def __init__(self) -> None:
        self.ticks: list[tuple[int, bytes, dict[int, int], str]] = []

    def publish(self, state: TreeState, update: TickUpdate) -> None:
        uids = {id(node): uid for uid, node in state.nodes()}
        self.ticks.append((state.tick, state.uuid, uids, state.xml))

    def close(self) -> None:
        pass


def watched_run(*disturb: str) -> tuple[btplan.RunOutcome, Snapshots, RunMonitor]:
    task = btplan.load(str(DOMAINS / "pick_place_obstacle.bt"))
    snapshots = Snapshots()
    monitor = RunMonitor([snapshots], "MainTree")
    outcome = btplan.run(task, disturb=list(disturb), view=monitor,
                         config=ActingConfig.algorithm1())
    return outcome, snapshots, monitor


def test_uids_stay_and_the_uuid_changes_only_when_the_tree_grows() -> None:
    outcome, snapshots, _ = watched_run("set:blocks(sphere, tau_goal)@5")
    assert outcome.reached
    grew = {r.tick for r in outcome.records if r.expansions}
    assert len(grew) > 2
    seen: dict[int, int] = {}
    for (tick, uuid, uids, _), (_, before, _, _) in zip(snapshots.ticks[1:], snapshots.ticks):
        for node, uid in uids.items():
            assert seen.setdefault(node, uid) == uid  # a node keeps its uid
        assert (uuid != before) == (tick in grew)
    last = snapshots.ticks[-1][2]
    assert sorted(last.values()) == list(range(1, len(last) + 1))


def test_new_nodes_get_uids_after_the_old_ones_and_the_xml_carries_them() -> None:
    _, snapshots, _ = watched_run("set:blocks(sphere, tau_goal)@5")
    first, last = snapshots.ticks[0], snapshots.ticks[-1]
    old = set(first[2].values())
    new = set(last[2].values()) - old
    assert new and min(new) > max(old)
    written = [int(e.attrib["_uid"]) for e in ET.fromstring(last[3]).iter()
               if "_uid" in e.attrib]
    assert sorted(written) == sorted(last[2].values())


def test_statuses_after_a_tick_leave_only_the_running_branch_active() -> None:
    _, _, monitor = watched_run()
    state = monitor.state
    codes = [state.code(uid) for uid, _ in state.nodes()]
    assert all(code == 0 or code > IDLE_FROM for code in codes)  # the run ended: all idle
    assert any(code == IDLE_FROM + 2 for code in codes)  # some from SUCCESS


def test_facts_follow_the_run() -> None:
    outcome, _, monitor = watched_run()
    assert "on(cube, goal)" in monitor.state.facts
    assert monitor.state.tick == outcome.ticks
