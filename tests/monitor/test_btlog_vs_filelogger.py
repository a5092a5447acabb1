"""`btplan run --btlog` writes what BehaviorTree.CPP's FileLogger2 writes.

The same planned tree runs in btplan's engine and in BT.CPP (behaviortreepy, whose
FileLogger is FileLogger2); both logs are read back and compared: the header's layout,
the tree's structure and uids, and for every node the sequence of its transitions
(times differ, and BT.CPP logs a tick's transitions in the order it runs its nodes)."""

from __future__ import annotations

import gc
import struct
import time
from collections import defaultdict
from pathlib import Path

import pytest

from btplan.monitor.btlog import MAGIC, BtlogWriter, read_btlog
from btcpp_oracle import quiet_stdout
from peers import SideBySide, shape, update_of

TREES = ["pick_place.bt", "gripper.bt", "blocksworld.bt", "fetch_cup.bt"]


def per_node(transitions: list[tuple[int, int, int]]) -> dict[int, list[int]]:
    out: dict[int, list[int]] = defaultdict(list)
    for _, uid, status in transitions:
        out[uid].append(status)
    return dict(out)


def layout(data: bytes) -> tuple[bytes, int, int]:
    """Magic, protocol byte, and whether the rest is XML length + XML + 8 + 9k bytes."""
    (size,) = struct.unpack_from("<i", data, len(MAGIC) + 1)
    rest = len(data) - (len(MAGIC) + 1 + 4 + size + 8)
    return data[:len(MAGIC)], data[len(MAGIC)], rest % 9


@pytest.mark.parametrize("domain", TREES)
def test_the_log_matches_filelogger2(domain: str, tmp_path: Path) -> None:
    import behaviortreepy as bt

    pair = SideBySide(domain)
    theirs_path, ours_path = tmp_path / "btcpp.btlog", tmp_path / "btplan.btlog"
    with quiet_stdout():
        logger = bt.FileLogger(pair.reference.tree, str(theirs_path))
    writer = BtlogWriter(str(ours_path))
    started = time.time()
    for _ in range(60):
        theirs, ours, transitions = pair.tick()
        writer.publish(pair.state, update_of(transitions))
        assert theirs == ours
        if ours.value != "RUNNING":
            break
    time.sleep(0.1)  # FileLogger2 writes from a thread of its own, every 10 ms
    logger.flush()
    del logger
    gc.collect()  # and closes the file when it is destroyed
    writer.close()
    reference, mine = theirs_path.read_bytes(), ours_path.read_bytes()
    assert layout(mine) == layout(reference) == (MAGIC, 1, 0)
    their_xml, _, their_transitions = read_btlog(reference)
    our_xml, our_start, our_transitions = read_btlog(mine)
    assert shape(our_xml) == shape(their_xml)
    assert per_node(our_transitions) == per_node(their_transitions)
    assert len(our_transitions) == len(their_transitions) > 0
    assert abs(our_start / 1e6 - started) < 60
    stamps = [t for t, _, _ in our_transitions]
    assert stamps == sorted(stamps)
