"""What the monitor tests share: a planned tree ticked by btplan and by BT.CPP side by
side, Groot2 requests, and free ports on 127.0.0.1."""

from __future__ import annotations

import socket
import struct
import xml.etree.ElementTree as ET
from pathlib import Path

import zmq

import btplan
from btplan.bt import BehaviorTree, Status
from btplan.bt.formats.btcpp import dump_xml
from btplan.bt.trace import TickRecorder
from btplan.acting.records import TickRecord
from btplan.monitor.run_monitor import TickUpdate
from btplan.monitor.tree_state import TreeState
from btplan.worlds.symbolic import SymbolicWorld
from btcpp_oracle import BtcppRun, quiet_stdout

DOMAINS = Path(__file__).resolve().parents[2] / "domains"


def free_port() -> int:
    """A port with its next one free too (a Groot2 server takes both)."""
    for _ in range(50):
        with socket.socket() as probe:
            probe.bind(("127.0.0.1", 0))
            port = probe.getsockname()[1]
        if port < 65535:
            with socket.socket() as second:
                try:
                    second.bind(("127.0.0.1", port + 1))
                except OSError:
                    continue
            return port
    raise RuntimeError("no two free ports in a row")


class SideBySide:
    """One planned tree, ticked in btplan's engine (its state kept by a TreeState) and
    in BT.CPP (behaviortreepy), each against its own symbolic world."""

    def __init__(self, domain: str) -> None:
        task = btplan.load(str(DOMAINS / domain))
        self.tree: BehaviorTree = btplan.plan(task).tree
        self.reference = BtcppRun(dump_xml(self.tree), SymbolicWorld(task))
        self.world = SymbolicWorld(task)
        self.recorder = TickRecorder(keep=1)
        self.recorder.attach(self.tree)
        self.state = TreeState(self.tree.name)
        self.state.update(self.tree.root, {})

    def tick(self) -> tuple[Status, Status, list[tuple[int, int]]]:
        """One tick on both sides: BT.CPP's status, btplan's, btplan's transitions."""
        with quiet_stdout():
            theirs = self.reference.tick()
        ours = self.tree.tick(self.world)
        nodes = self.tree.nodes()
        trace = self.recorder.last
        assert trace is not None
        reached = {id(nodes[int(n.id[1:])]): n.status for n in trace.nodes}
        return theirs, ours, self.state.update(self.tree.root, reached)


def update_of(transitions: list[tuple[int, int]]) -> TickUpdate:
    """A tick's update carrying only its transitions (what the servers read of it)."""
    return TickUpdate(TickRecord(tick=0, status="RUNNING"), transitions, [], None, None)


def ask(context: zmq.Context, port: int, kind: str, *parts: bytes,
        request_id: int = 0x1234ABCD) -> list[bytes]:
    """One Groot2 request, the reply's parts."""
    sock = context.socket(zmq.REQ)
    sock.setsockopt(zmq.RCVTIMEO, 5000)
    sock.setsockopt(zmq.LINGER, 0)
    sock.connect(f"tcp://127.0.0.1:{port}")
    try:
        sock.send_multipart([struct.pack("<BBI", 2, ord(kind), request_id), *parts])
        return sock.recv_multipart()
    finally:
        sock.close()


def shape(xml: bytes | str) -> list[tuple[str, str]]:
    """The tree part of a FULLTREE or FileLogger2 XML: tag and `_uid` of every node,
    depth first, with the depth."""
    root = ET.fromstring(xml)
    tree = root.find("BehaviorTree")
    assert tree is not None
    out: list[tuple[str, str]] = []

    def walk(element: ET.Element, depth: int) -> None:
        for child in element:
            out.append((f"{depth}:{child.tag}", child.attrib["_uid"]))
            walk(child, depth + 1)

    walk(tree, 0)
    return out


def models(xml: bytes | str) -> dict[str, tuple[str, frozenset[str]]]:
    """The TreeNodesModel: ID -> (kind, port names; BT.CPP lists them in no set order)."""
    found = ET.fromstring(xml).find("TreeNodesModel")
    assert found is not None
    return {e.attrib["ID"]: (e.tag, frozenset(p.attrib["name"] for p in e)) for e in found}
