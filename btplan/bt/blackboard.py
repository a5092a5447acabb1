"""The blackboard of BehaviorTree.CPP: typed-by-value entries shared by the nodes of a tree.

Each tree instance has its own blackboard. A SubTree's blackboard maps some of its keys
to keys of the parent's (`goal="{target}"`), may hold literal values given at the call
(`goal="kitchen"`), and with `_autoremap` sees every parent key it does not define
itself. `@key` always names the root blackboard, as in BT.CPP 4.6+. Every write bumps a
per-entry counter so that SkipUnlessUpdated and friends can tell a fresh value.
"""

from __future__ import annotations

from btplan.errors import BtplanError

Value = str | int | float | bool
"""What an entry holds: script numbers, strings, and booleans."""


class NodeError(BtplanError):
    """A BT.CPP node could not tick: a missing entry, a bad port value, a failing script.

    BehaviorTree.CPP throws at that point and stops the tree; btplan does the same,
    naming the node, so an imported tree never silently behaves differently.
    """


class Blackboard:
    """Entries of one tree instance, with the remapping to its parent's."""

    __slots__ = ("autoremap", "enums", "parent", "remap", "seq", "values")

    def __init__(self, parent: Blackboard | None = None, remap: dict[str, str] | None = None,
                 autoremap: bool = False, enums: dict[str, int] | None = None) -> None:
        self.parent = parent
        self.remap = remap or {}
        self.autoremap = autoremap
        self.values: dict[str, Value] = {}
        self.seq: dict[str, int] = {}
        # BT.CPP registers scripting enums in C++; the caller gives them when loading.
        self.enums: dict[str, int] = (enums if enums is not None else
                                      parent.enums if parent is not None else {})

    def root(self) -> Blackboard:
        board = self
        while board.parent is not None:
            board = board.parent
        return board

    def owner(self, key: str) -> tuple[Blackboard, str]:
        """The blackboard and key an entry lives under, following remaps up the tree."""
        board = self
        while True:
            if key.startswith("@"):
                return board.root(), key[1:]
            if key in board.values or board.parent is None:
                return board, key
            if key in board.remap:
                key = board.remap[key]
            elif not board.autoremap:
                return board, key
            board = board.parent

    def has(self, key: str) -> bool:
        board, name = self.owner(key)
        return name in board.values

    def get(self, key: str) -> Value:
        board, name = self.owner(key)
        try:
            return board.values[name]
        except KeyError:
            raise NodeError(f"the blackboard has no entry {key!r}") from None

    def set(self, key: str, value: Value) -> None:
        board, name = self.owner(key)
        board.values[name] = value
        board.seq[name] = board.seq.get(name, 0) + 1

    def unset(self, key: str) -> None:
        board, name = self.owner(key)
        board.values.pop(name, None)

    def sequence(self, key: str) -> int:
        """How many times the entry was written (0: never), for the *Updated nodes."""
        board, name = self.owner(key)
        return board.seq.get(name, 0) if name in board.values else 0

    def snapshot(self) -> dict[str, Value]:
        """This blackboard's own entries, sorted, to compare runs."""
        return dict(sorted(self.values.items()))


def pointer(raw: str, port: str) -> str | None:
    """The blackboard key a port value points at (`{key}`, or `{=}` for the port's own
    name), or None for a literal."""
    if len(raw) >= 3 and raw[0] == "{" and raw[-1] == "}":
        inner = raw[1:-1].strip()
        return port if inner == "=" else inner
    return None


def as_text(value: Value) -> str:
    """An entry as BT.CPP prints it: whole numbers without a decimal point."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    return str(value)


def to_number(value: Value, what: str) -> float:
    if isinstance(value, (int, float)):
        return float(value)
    text = value.strip()
    try:
        return float(int(text, 0)) if text.lower().startswith(("0x", "-0x")) else float(text)
    except ValueError:
        raise NodeError(f"{what}: {value!r} is not a number") from None


def to_int(value: Value, what: str) -> int:
    number = to_number(value, what)
    if not number.is_integer():
        raise NodeError(f"{what}: {as_text(value)!r} is not a whole number")
    return int(number)


def to_bool(value: Value, what: str) -> bool:
    if isinstance(value, (bool, int, float)):
        return bool(value)
    text = value.strip().lower()
    if text in ("true", "1"):
        return True
    if text in ("false", "0"):
        return False
    raise NodeError(f"{what}: {value!r} is not true or false")


class Ports:
    """The port values a BT.CPP node was given in XML, read through its blackboard.

    `values` keeps the raw attribute text; reading a `{key}` port looks the entry up at
    tick time, as BT.CPP's getInput does, and a missing port falls back to `defaults`.
    """

    __slots__ = ("board", "defaults", "owner", "values")

    def __init__(self, owner: str, values: dict[str, str], board: Blackboard,
                 defaults: dict[str, str] | None = None) -> None:
        self.owner = owner
        self.values = values
        self.board = board
        self.defaults = defaults or {}

    def raw(self, port: str) -> Value:
        text = self.values.get(port, self.defaults.get(port))
        if text is None:
            raise NodeError(f"{self.owner}: input port {port!r} is not set")
        key = pointer(text, port)
        if key is None:
            return text
        if not self.board.has(key):
            raise NodeError(f"{self.owner}: port {port!r} reads {{{key}}}, which is not set")
        return self.board.get(key)

    def text(self, port: str) -> str:
        return as_text(self.raw(port))

    def int(self, port: str) -> int:
        return to_int(self.raw(port), f"{self.owner}.{port}")

    def number(self, port: str) -> float:
        return to_number(self.raw(port), f"{self.owner}.{port}")

    def bool(self, port: str) -> bool:
        return to_bool(self.raw(port), f"{self.owner}.{port}")

    def key(self, port: str) -> str:
        """The entry an output port writes to: `{key}` or, as BT.CPP allows, a bare name."""
        text = self.values.get(port, self.defaults.get(port))
        if text is None:
            raise NodeError(f"{self.owner}: output port {port!r} is not set")
        return pointer(text, port) or text

    def write(self, port: str, value: Value) -> None:
        self.board.set(self.key(port), value)


__all__ = ["Blackboard", "NodeError", "Ports", "Value", "as_text", "pointer", "to_bool",
           "to_int", "to_number"]
