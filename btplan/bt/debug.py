"""A debug check on the leaf contract: conditions answer yes or no, actions a real status.

Conditions never return RUNNING (the paper, Section III); a world that answers a
condition with a Status, or an action with anything but SUCCESS/FAILURE/RUNNING,
would otherwise be read silently as a truthy value. `BehaviorTree(root, debug=True)`
ticks through `StrictWorld`, so the mistake is raised at the leaf that exposed it.
"""

from __future__ import annotations

from btplan.bt.status import FAILURE, RUNNING, SUCCESS, Status
from btplan.bt.world import LeafKey, World

_ACTION_RESULTS = (SUCCESS, FAILURE, RUNNING)


class LeafContractError(RuntimeError):
    """A world broke the leaf protocol; a bug in the world backend, not bad user input."""


def _name(key: LeafKey) -> str:
    return f"{key[0]}({', '.join(key[1])})"


class StrictWorld:
    """Wraps a world and checks every answer it gives to a leaf."""

    __slots__ = ("world",)

    def __init__(self, world: World) -> None:
        self.world = world

    def check(self, key: LeafKey) -> bool:
        """Forward the condition; a Status or None answer raises LeafContractError instead of
        being read as true or false. Other answers are turned into a bool."""
        answer = self.world.check(key)
        if isinstance(answer, Status) or answer is None:
            raise LeafContractError(
                f"condition {_name(key)} answered {answer!r}; a condition is true or false, "
                "never RUNNING")
        return bool(answer)

    def start(self, key: LeafKey) -> Status:
        """Start the action in the wrapped world; an answer that is not SUCCESS, FAILURE or
        RUNNING raises LeafContractError."""
        return self._action("start", key, self.world.start(key))

    def step(self, key: LeafKey) -> Status:
        """Step the action in the wrapped world; an answer that is not SUCCESS, FAILURE or
        RUNNING raises LeafContractError."""
        return self._action("step", key, self.world.step(key))

    def halt(self, key: LeafKey) -> None:
        """Forwarded unchecked: a halt answers nothing that could break the contract."""
        self.world.halt(key)

    @staticmethod
    def _action(call: str, key: LeafKey, answer: object) -> Status:
        if answer not in _ACTION_RESULTS:
            raise LeafContractError(
                f"action {_name(key)}: {call} returned {answer!r}; expected SUCCESS, FAILURE "
                "or RUNNING")
        assert isinstance(answer, Status)
        return answer
