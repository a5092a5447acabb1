"""Watching a run from outside: Groot2's live protocol, its replay files, and the tree as
the tools BT users know see it.

- `tree_state`: the growing tree as BehaviorTree.CPP describes a tree it runs: a
  `_uid` per node that never changes while the tree grows, the tree's XML, the status
  of every node after each tick in BT.CPP's encoding, and the transitions between them;
- `groot2`: a server speaking BT.CPP 4's Groot2 protocol over ZeroMQ (`btplan run
  --groot`);
- `btlog`: a run written as BT.CPP's FileLogger2 file, which Groot2 replays
  (`btplan run --btlog`).
"""
