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
        """The blackboard of the outermost tree instance, which `@key` names from any SubTree
        depth."""
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
        """Whether the entry exists where the remapping leads (`owner`); a remapped key whose
        parent entry was never written is absent."""
        board, name = self.owner(key)
        return name in board.values

    def get(self, key: str) -> Value:
        """The entry's value, found through the remapping; NodeError when it does not exist,
        since BT.CPP stops the tree there too."""
        board, name = self.owner(key)
        try:
            return board.values[name]
        except KeyError:
            raise NodeError(f"the blackboard has no entry {key!r}") from None

    def set(self, key: str, value: Value) -> None:
        """Write the entry where the remapping leads (so a SubTree writes its caller's entry)
        and count the write for SkipUnlessUpdated, WaitValueUpdate and WasEntryUpdated."""
        board, name = self.owner(key)
        board.values[name] = value
        board.seq[name] = board.seq.get(name, 0) + 1

    def unset(self, key: str) -> None:
        """Remove the entry where the remapping leads; no error when there is none. Its write
        count is kept, so a later write still reads as new."""
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
    """A port or entry value as a float: numbers (and booleans) as they are, text in decimal
    or `0x` hex. Other text is a NodeError whose message starts with `what`."""
    if isinstance(value, (int, float)):
        return float(value)
    text = value.strip()
    try:
        return float(int(text, 0)) if text.lower().startswith(("0x", "-0x")) else float(text)
    except ValueError:
        raise NodeError(f"{what}: {value!r} is not a number") from None


def to_int(value: Value, what: str) -> int:
    """A value as a whole number for counting ports (`num_cycles`, `num_attempts`): `3` and
    `3.0` pass, `2.5` or non-numeric text is a NodeError naming `what`."""
    number = to_number(value, what)
    if not number.is_integer():
        raise NodeError(f"{what}: {as_text(value)!r} is not a whole number")
    return int(number)


def to_bool(value: Value, what: str) -> bool:
    """A value as true or false: numbers by being non-zero, text only as `true`, `false`,
    `1` or `0` (any case); other text is a NodeError naming `what`, not a guess."""
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
        """The port's value this tick: the entry's value for a `{key}` port, else the literal
        text or the declared default. Not given and no default, or an unset entry, is a
        NodeError naming the node and port."""
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
        """The port's value as text, numbers written the BT.CPP way (`3`, not `3.0`)."""
        return as_text(self.raw(port))

    def int(self, port: str) -> int:
        """The port's value as a whole number (`to_int`); errors name `owner.port`."""
        return to_int(self.raw(port), f"{self.owner}.{port}")

    def number(self, port: str) -> float:
        """The port's value as a float (`to_number`); errors name `owner.port`."""
        return to_number(self.raw(port), f"{self.owner}.{port}")

    def bool(self, port: str) -> bool:
        """The port's value as true or false (`to_bool`); errors name `owner.port`."""
        return to_bool(self.raw(port), f"{self.owner}.{port}")

    def key(self, port: str) -> str:
        """The entry an output port writes to: `{key}` or, as BT.CPP allows, a bare name."""
        text = self.values.get(port, self.defaults.get(port))
        if text is None:
            raise NodeError(f"{self.owner}: output port {port!r} is not set")
        return pointer(text, port) or text

    def write(self, port: str, value: Value) -> None:
        """Write `value` to the entry the output port names (`key`), counting the write as any
        `Blackboard.set` does."""
        self.board.set(self.key(port), value)


__all__ = ["Blackboard", "NodeError", "Ports", "Value", "as_text", "pointer", "to_bool",
           "to_int", "to_number"]
