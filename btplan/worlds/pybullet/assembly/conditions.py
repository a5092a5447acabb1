"""The yumi domain's conditions, measured on the assembly scene every time they are asked.

`lies`, `holds`, `free` and `mounted` are read from poses and grips (state.py), so a
part turned over by someone else is seen on the next tick. Predicates that no action
changes (reaches, grasp_of, turned, needs, mounts) describe the robot and the product,
not the scene: they are taken from the problem as given.
"""

from __future__ import annotations

from btplan.errors import WorldError
from btplan.model import Atom, Task
from btplan.worlds.pybullet.assembly.state import AssemblyState

Key = tuple[str, tuple[str, ...]]
MEASURED = ("lies", "holds", "free", "mounted")


class AssemblyConditions:
    """`check` for one condition, `facts` for the whole state (the planner's view)."""

    def __init__(self, state: AssemblyState, task: Task) -> None:
        self.state = state
        unknown = sorted(task.domain.changed_predicates - set(MEASURED))
        if unknown:
            raise WorldError(f"the assembly scene cannot measure {unknown[0]!r}: its actions "
                             f"may only change {', '.join(MEASURED)}")
        self.static = frozenset(a for a in task.initial_state if a.predicate not in MEASURED)

    def check(self, key: Key) -> bool:
        """Measure `lies`, `holds`, `free` or `mounted` on the scene now.

        Fixtures are always mounted; any other predicate is a static fact of the problem. A
        measured predicate with the wrong number of arguments raises WorldError.
        """
        state = self.state
        name, args = key
        if name == "lies" and len(args) == 3:
            return state.place_of(args[0]) == args[1] and state.face(args[0]) == args[2]
        if name == "holds" and len(args) == 3:
            return state.in_hand(args[0]) == args[1] and state.grasp(args[0], args[1]) == args[2]
        if name == "free" and len(args) == 1:
            return state.in_hand(args[0]) is None
        if name == "mounted" and len(args) == 1:
            return args[0] in state.fixtures or (args[0] in state.size and state.mounted(args[0]))
        if name in MEASURED:
            raise WorldError(f"{name}{args} does not fit the assembly scene")
        return Atom(name, args) in self.static

    def facts(self) -> frozenset[Atom]:
        """The static facts and every measured one that holds now.

        A part in the air or on the fixture lies nowhere; an arm gripping a part that is still
        on the table is `free`, since it does not hold it yet.
        """
        state = self.state
        found = set(self.static)
        found.update(Atom("mounted", (f,)) for f in state.fixtures)
        for part in state.part_names:
            place, face = state.place_of(part), state.face(part)
            if place is not None and face is not None:
                found.add(Atom("lies", (part, place, face)))
            if state.mounted(part):
                found.add(Atom("mounted", (part,)))
        for arm in state.arm_names:
            held = state.in_hand(arm)
            if held is None:
                found.add(Atom("free", (arm,)))
            else:
                found.add(Atom("holds", (arm, held, state.grasp(arm, held))))
        return frozenset(found)
