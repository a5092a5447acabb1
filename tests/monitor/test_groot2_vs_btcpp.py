"""btplan's Groot2 server answers as BehaviorTree.CPP's own Groot2Publisher does.

The same planned tree runs in btplan's engine (served by btplan.monitor.groot2) and in
BT.CPP through behaviortreepy (served by its Groot2Publisher); the same requests go to
both, and the replies are compared: framing, header fields, the tree's structure and
uids, the status buffer after every tick, the error replies."""

from __future__ import annotations

import msgpack
import pytest
import zmq

from btplan.bt.formats.btcpp_catalog import BUILTINS
from btplan.monitor.groot2 import Groot2Server
from btcpp_oracle import quiet_stdout
from peers import SideBySide, ask, free_port, models, shape, update_of

NEWER = {"TryCatch"}
"""Built-in from BT.CPP 4.10; behaviortreepy ships 4.8."""

TREES = ["pick_place.bt", "gripper.bt", "blocksworld.bt", "fetch_cup.bt"]


@pytest.fixture
def context() -> zmq.Context:
    made = zmq.Context()
    yield made
    made.destroy(linger=0)


def serve(domain: str) -> tuple[SideBySide, Groot2Server, int, int, object]:
    import behaviortreepy as bt

    pair = SideBySide(domain)
    theirs = free_port()
    with quiet_stdout():
        publisher = bt.Groot2Publisher(pair.reference.tree, theirs)
    ours = free_port()
    server = Groot2Server(ours)
    server.publish(pair.state, update_of([]))
    return pair, server, ours, theirs, publisher


@pytest.mark.parametrize("domain", TREES)
def test_the_tree_and_every_status_buffer_match_btcpp(domain: str, context: zmq.Context) -> None:
    pair, server, ours, theirs, publisher = serve(domain)
    try:
        mine, reference = ask(context, ours, "T"), ask(context, theirs, "T")
        assert len(mine) == len(reference) == 2
        assert len(mine[0]) == len(reference[0]) == 22
        assert mine[0][:6] == reference[0][:6]  # protocol, type, request id echoed
        assert shape(mine[1]) == shape(reference[1])
        ours_models, their_models = models(mine[1]), models(reference[1])
        # Built-in nodes as BT.CPP declares them (the leaves it got have no ports: the
        # oracle registers them without), and every node of the tree declared.
        builtin = {i for i in ours_models if i in BUILTINS} - NEWER
        assert builtin and builtin <= set(their_models)
        assert all(their_models[i] == ours_models[i] for i in builtin)
        used = {tag.split(":")[1] for tag, _ in shape(mine[1])}
        assert used <= set(ours_models) and used <= set(their_models)
        statuses = 0
        for _ in range(60):
            mine, reference = ask(context, ours, "S"), ask(context, theirs, "S")
            assert mine[0][:6] == reference[0][:6]
            assert mine[1] == reference[1]
            statuses += 1
            their_status, our_status, transitions = pair.tick()
            assert their_status == our_status
            server.publish(pair.state, update_of(transitions))
            if our_status.value != "RUNNING":
                break
        mine, reference = ask(context, ours, "S"), ask(context, theirs, "S")
        assert mine[1] == reference[1] and statuses >= 1
    finally:
        server.close()
        del publisher


def test_requests_other_than_monitoring_get_btcpp_s_replies(context: zmq.Context) -> None:
    pair, server, ours, theirs, publisher = serve("pick_place.bt")
    try:
        for kind in "DAX":  # hooks: a dump of none, remove and disable all
            mine, reference = ask(context, ours, kind), ask(context, theirs, kind)
            assert [len(p) for p in mine] == [len(p) for p in reference]
            assert mine[0][:6] == reference[0][:6] and mine[1:] == reference[1:]
        for request in ([b"\x02Z\x00\x00\x00\x00"], [b"short"]):  # unknown type, bad header
            sock = context.socket(zmq.REQ)
            sock.setsockopt(zmq.RCVTIMEO, 5000)
            replies = []
            for port in (ours, theirs):
                sock = context.socket(zmq.REQ)
                sock.setsockopt(zmq.RCVTIMEO, 5000)
                sock.connect(f"tcp://127.0.0.1:{port}")
                sock.send_multipart(request)
                replies.append(sock.recv_multipart())
                sock.close(linger=0)
            assert replies[0] == replies[1]
            assert replies[0][0] == b"error"
        mine, reference = ask(context, ours, "B"), ask(context, theirs, "B")  # one part only
        assert mine == reference == [b"error", b"must be 2 parts message"]
    finally:
        server.close()
        del publisher


def test_the_blackboard_is_msgpack_json_under_the_tree_s_name(context: zmq.Context) -> None:
    pair, server, ours, theirs, publisher = serve("pick_place.bt")
    try:
        pair.state.facts.update({"near(start)", "hand_empty()"})
        server.publish(pair.state, update_of([]))
        mine = ask(context, ours, "B", pair.tree.name.encode())
        reference = ask(context, theirs, "B", pair.tree.name.encode())
        assert mine[0][:6] == reference[0][:6] and len(mine) == len(reference) == 2
        assert isinstance(msgpack.unpackb(reference[1]), dict)
        board = msgpack.unpackb(mine[1])
        assert board[pair.tree.name]["facts"] == ["hand_empty()", "near(start)"]
        # a name no tree has: both answer JSON null
        assert ask(context, ours, "B", b"Nowhere")[1] == ask(context, theirs, "B", b"Nowhere")[1]
    finally:
        server.close()
        del publisher
