"""Conflicts: the test of Algorithm 1, line 11.

A subtree placed in a Sequence runs only once every earlier sibling succeeded, that is
while each earlier sibling's condition holds (the paper: "the new subtree will be
executed if and only if h = c holds"). So, for the new subtree N and each earlier
sibling X along N's chain of Sequence ancestors, there is a conflict when

  (a) N needs a condition that cannot hold while X's condition does (holding(cube)
      excludes hand_empty, which N needs); mutexes tell, and where they do not, the
      paper's test is used: an action achieving X's condition makes it false; or
  (b) an action of N makes X's condition false: N would undo what an earlier part
      achieved and still relies on.

Where N is moved to is btplan.planner.priority's business. Once N has moved, it must
also not break what now follows it:

  (c) an action achieving a later sibling's condition must not make N's condition false,
  (d) a later sibling must not need a condition that N's condition excludes.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping

from btplan.bt import Action, Fallback, LeafKey, Node
from btplan.bt import Sequence as SequenceNode
from btplan.model import Atom, GroundAction, GroundLiteral
from btplan.planner.expand import literal_of
from btplan.classical import RelaxedModel
from btplan.classical import Mutexes
from btplan.records import record

Grounding = Mapping[LeafKey, GroundAction]


@record(frozen=True, slots=True)
class Conflict:
    """Why a place is bad: an effect that breaks a condition, or two exclusive conditions."""

    cause: str
    condition: str
    rule: str

    def __str__(self) -> str:
        return f"{self.cause} {self.condition} ({self.rule})"


@record(frozen=True, slots=True)
class Judge:
    """What conflict checks know: the grounded actions of the tree and, if built, mutexes.

    Without mutexes (or for atoms they do not cover, such as values a backend refined)
    exclusion falls back to the paper's wording: an action achieving the earlier
    condition has an effect that makes the needed condition false.
    """

    grounding: Grounding
    mutexes: Mutexes | None = None
    guards: frozenset[Node] = frozenset()
    """Guard conditions (achievers.guards): they say what an alternative is for, and
    undoing them is its purpose, so they are never an earlier condition to protect."""
    relaxed: RelaxedModel | None = None
    state: frozenset[Atom] | None = None
    """With both, a place is also refused when it is circular (`circular_place`)."""

    def threatens(
        self, doers: list[Action], conditions: list[GroundLiteral], rule: str
    ) -> list[Conflict]:
        """Actions among `doers` whose effects make one of `conditions` false."""
        found: list[Conflict] = []
        for leaf in doers:
            action = self.grounding.get(leaf.key)
            if action is None:
                continue
            for literal in conditions:
                if falsifies(action, literal):
                    found.append(Conflict(str(action), f"makes {literal} false", rule))
        return found

    def blocks(
        self, held: list[GroundLiteral], node: Node, doers: list[Action], rule: str,
        ways: list[list[GroundLiteral]] | None = None,
    ) -> list[Conflict]:
        """Conflicts when every way `node` can succeed needs something `held` excludes.

        `ways`: `needs_by_alternative(node, self.guards)`, when the caller has it already.
        """
        if ways is None:
            ways = needs_by_alternative(node, self.guards)
        found: list[Conflict] = []
        for needs in ways:
            conflicts = self.excludes(held, needs, doers, rule)
            if not conflicts:
                return []
            found += conflicts
        return found

    def excludes(
        self, held: list[GroundLiteral], needed: list[GroundLiteral], doers: list[Action], rule: str
    ) -> list[Conflict]:
        """Needed conditions that cannot hold while the `held` ones do."""
        found: list[Conflict] = []
        proxy: list[GroundLiteral] = []
        for need in needed:
            if self.mutexes is None or not self.mutexes.knows(need.atom):
                proxy.append(need)
                continue
            for hold in held:
                if self.mutexes.exclusive(hold, need):
                    found.append(Conflict(str(hold), f"excludes {need}", rule))
        return found + (self.threatens(doers, proxy, rule) if proxy else [])

    def clash(self, held: list[GroundLiteral], needed: list[GroundLiteral],
              doers: list[Action], own: list[Action]) -> bool:
        """Whether `excludes(held, needed, doers)` or `threatens(own, held)` would find a
        conflict, without spelling any out (alternative_conflicts asks only whether)."""
        mutexes = self.mutexes
        proxy: list[GroundLiteral] = []
        for need in needed:
            if mutexes is None or not mutexes.knows(need.atom):
                proxy.append(need)
            elif any(mutexes.exclusive(hold, need) for hold in held):
                return True
        return self._falsified(doers, proxy) or self._falsified(own, held)

    def blocked(self, held: list[GroundLiteral], ways: list[list[GroundLiteral]],
                earlier: Node) -> bool:
        """Whether `blocks(held, node, achiever_leaves(earlier), rule, ways)` would find a
        conflict, without spelling any out; the earlier sibling's actions are read only
        for a need the mutexes do not cover (most look-ups find no conflict)."""
        if not ways:
            return False
        mutexes = self.mutexes
        doers: list[Action] | None = None
        for needs in ways:
            hit, proxy = mutexes.screen(needs, held) if mutexes is not None else (False, needs)
            if not hit and proxy:
                if doers is None:
                    doers = achiever_leaves(earlier)
                hit = self._falsified(doers, proxy)
            if not hit:
                return False  # this way can succeed
        return True

    def _falsified(self, doers: list[Action], conditions: list[GroundLiteral]) -> bool:
        """Whether `threatens(doers, conditions)` would find a conflict."""
        if not conditions:
            return False
        grounding = self.grounding
        for leaf in doers:
            action = grounding.get(leaf.key)
            if action is None:
                continue
            add, delete = action.add, action.delete
            for atom, positive in conditions:  # falsifies(action, literal), written out
                if positive:  # action.deletes(atom), the patterns asked only when it has some
                    if ((atom in delete and atom not in add)
                            or (action.delete_patterns and action.deletes(atom))):
                        return True
                elif atom in add:
                    return True
        return False


# --- what a subtree guarantees, needs and does ---------------------------------------------


def guarantees(node: Node) -> list[GroundLiteral]:
    """Literals that hold once `node` succeeded: its condition, or its children's."""
    literal = literal_of(node)
    if literal is not None:
        return [literal]
    if isinstance(node, Fallback) and node.children:
        first = literal_of(node.children[0])
        return [first] if first is not None else []
    if isinstance(node, SequenceNode):
        return [g for child in node.children for g in guarantees(child)]
    return []


def achiever_leaves(node: Node) -> list[Action]:
    """The actions that directly achieve `node`'s condition (last child of each alternative)."""
    if isinstance(node, Action):
        return [node]
    if isinstance(node, Fallback):
        out: list[Action] = []
        for child in node.children[1:]:
            if isinstance(child, Action):
                out.append(child)
            elif isinstance(child, SequenceNode) and child.children:
                last = child.children[-1]
                if isinstance(last, Action):
                    out.append(last)
        return out
    if isinstance(node, SequenceNode):
        return [a for child in node.children for a in achiever_leaves(child)]
    return []


def needs_by_alternative(
    node: Node, guards: frozenset[Node] = frozenset()
) -> list[list[GroundLiteral]]:
    """For each way `node` can succeed, the conditions that way needs.

    A condition needs itself; an atomic BT's alternatives need their preconditions (not
    their guards: those say when the alternative applies); a Sequence needs all its
    children's conditions; an action needs nothing here (its preconditions are its
    siblings).
    """
    literal = literal_of(node)
    if literal is not None:
        return [[literal]]
    if isinstance(node, Fallback):
        return [
            [g for c in child.children[:-1] if c not in guards for g in guarantees(c)]
            for child in node.children[1:]
            if isinstance(child, SequenceNode)
        ]
    if isinstance(node, SequenceNode):
        return [[g for child in node.children for g in guarantees(child)]]
    return []


def falsifies(action: GroundAction, literal: GroundLiteral) -> bool:
    """Whether running `action` makes `literal` false (it deletes a positive literal's atom,
    or adds a negative literal's): the threat test of the conflict rules (module docstring)."""
    if literal.positive:
        return action.deletes(literal.atom)
    return literal.atom in action.add


# --- finding conflicts ---------------------------------------------------------------------


def sequence_slots(node: Node) -> list[tuple[SequenceNode, int]]:
    """(Sequence ancestor, index of the child that contains `node`), innermost first."""
    slots: list[tuple[SequenceNode, int]] = []
    child = node
    parent = node.parent
    while parent is not None:
        if isinstance(parent, SequenceNode):
            slots.append((parent, parent.index_of(child)))
        child, parent = parent, parent.parent
    return slots


def held_before(node: Node) -> list[GroundLiteral]:
    """What the earlier siblings along `node`'s Sequence ancestors hold when it runs."""
    held: list[GroundLiteral] = []
    for sequence, index in sequence_slots(node):
        for earlier in sequence.children[:index]:
            held += guarantees(earlier)
    return list(dict.fromkeys(held))


def find_conflicts(subtree: Node, judge: Judge) -> list[Conflict]:
    """Rules (a) and (b) for `subtree` where it stands now."""
    return list(_conflicts(subtree, judge))


def has_conflicts(subtree: Node, judge: Judge) -> bool:
    """Whether `find_conflicts` would find any: stops at the first."""
    return next(_conflicts(subtree, judge), None) is not None


def _conflicts(subtree: Node, judge: Judge) -> Iterator[Conflict]:
    """find_conflicts' conflicts, one earlier sibling at a time; each is first asked
    whether it conflicts at all, and only then are its conflicts spelled out."""
    own = achiever_leaves(subtree)
    ways: list[list[GroundLiteral]] | None = None  # the same for every earlier sibling
    for sequence, index in sequence_slots(subtree):
        for earlier in sequence.children[:index]:
            if earlier in judge.guards:
                continue
            held = guarantees(earlier)
            if ways is None:
                ways = needs_by_alternative(subtree, judge.guards)
            if judge.blocked(held, ways, earlier):
                yield from judge.blocks(held, subtree, achiever_leaves(earlier),
                                        "needed after it holds", ways)
            if judge._falsified(own, held):
                yield from judge.threatens(own, held, "undoes earlier work")


def placement_conflicts(moved: Node, judge: Judge) -> list[Conflict]:
    """Rules (c) and (d) for a subtree that was moved before some siblings.

    The action that ends an achiever sequence is exempt from (c): once it has run,
    the enclosing condition holds and the sequence is not ticked any more, so it may
    use up what came before it (stack(b, c) makes clear(c) false).
    """
    parent = moved.parent
    if not isinstance(parent, SequenceNode):
        return []
    index = parent.index_of(moved)
    kept = guarantees(moved)
    own = achiever_leaves(moved)
    later = parent.children[index + 1 :]
    if isinstance(parent.parent, Fallback) and later and isinstance(later[-1], Action):
        later = later[:-1]
    found: list[Conflict] = []
    for sibling in later:
        found += judge.threatens(achiever_leaves(sibling), kept, "later work undoes it")
        found += judge.blocks(kept, sibling, own, "later work needs otherwise")
        found += _blocks_unexpanded(kept, sibling, judge)
    return found


def _blocks_unexpanded(kept: list[GroundLiteral], sibling: Node, judge: Judge) -> list[Conflict]:
    """Rule (d) for a later condition not expanded yet: every achiever of it needs
    something `kept` excludes (clear(b37) first among the goals, on(b37, b87) later:
    stacking b37 needs holding b37). Only with the relaxed model and mutexes."""
    literal = literal_of(sibling)
    mutexes = judge.mutexes
    if (literal is None or not literal.positive or judge.relaxed is None or judge.state is None
            or mutexes is None or literal.atom in judge.state):
        return []
    producers = judge.relaxed.producers(literal.atom)
    if not producers:
        return []
    found: list[Conflict] = []
    for action in producers:
        clash = [Conflict(str(hold), f"excludes {need}", "later work needs otherwise")
                 for need in action.preconditions if mutexes.knows(need.atom)
                 for hold in kept if mutexes.exclusive(hold, need)]
        if not clash:
            return []
        found += clash[:1]
    return found[:1]


Earlier = list[list[tuple[list[GroundLiteral], list[Action]]]]
"""Per Sequence ancestor of a subtree, innermost first: what each earlier sibling (not a
guard) holds and the actions that achieve it (`earlier_work`)."""


def earlier_work(subtree: Node, judge: Judge) -> Earlier:
    """What the earlier siblings along `subtree`'s Sequence ancestors hold and do, read
    once for all the alternatives of an atomic BT (they share the place)."""
    return [[(guarantees(e), achiever_leaves(e)) for e in sequence.children[:index]
             if e not in judge.guards]
            for sequence, index in sequence_slots(subtree)]


def alternative_conflicts(
    subtree: Fallback, alternative: Node, judge: Judge, depth: int | None = None,
    earlier: Earlier | None = None,
) -> bool:
    """Whether one alternative of an atomic BT conflicts, looking `depth` Sequences up.

    `earlier`: `earlier_work(subtree, judge)`, when the caller has it already.
    """
    needs = [g for c in alternative.children[:-1] for g in guarantees(c)]
    own = [c for c in alternative.children[-1:] if isinstance(c, Action)]
    if earlier is not None:
        return any(judge.clash(held, needs, doers, own)
                   for slot in earlier[:depth] for held, doers in slot)
    for sequence, index in sequence_slots(subtree)[:depth]:
        for sibling in sequence.children[:index]:
            if sibling in judge.guards:
                continue
            if judge.clash(guarantees(sibling), needs, achiever_leaves(sibling), own):
                return True
    return False


def circular_place(moved: Node, judge: Judge) -> bool:
    """Whether `moved`, where it stands, needs what an enclosing Fallback pursues.

    Rule (e), with the relaxed model and state the judge carries (none: never).
    Placed at the front of the sequence that unstacks b18 from b37 to clear b37, the
    subtree for on(b37, b87) runs only while clear(b37) is false, yet stacking b37
    needs holding b37, and every way to hold b37 needs clear(b37): it never succeeds.
    Looked at two achiever steps deep, over all grounded actions, not from the state
    judged: after a move the run starts over, and the branch runs in another state.
    """
    if judge.relaxed is None or judge.state is None:
        return False
    pursued: set[Atom] = set()
    node = moved.parent
    while node is not None:
        if isinstance(node, Fallback) and node.children:
            first = literal_of(node.children[0])
            if first is not None and first.positive:  # false whenever `moved` runs
                pursued.add(first.atom)
        node = node.parent
    if not pursued:
        return False
    return any(g.positive and g.atom not in pursued
               and _needs(g.atom, pursued, judge.relaxed, judge.state, 2)
               for g in guarantees(moved))


def _needs(atom: Atom, pursued: set[Atom], relaxed: RelaxedModel, state: frozenset[Atom],
           depth: int) -> bool:
    """Whether every achiever of `atom` (false in `state`) needs a pursued atom, directly
    or through a precondition all of whose achievers do (up to `depth` steps)."""
    if atom in state:
        return False
    producers = relaxed.producers(atom)
    if not producers:
        return False  # nothing known about it: not judged
    return all(
        any(p.positive and (p.atom in pursued
                            or (depth > 1 and _needs(p.atom, pursued, relaxed, state, depth - 1)))
            for p in action.preconditions)
        for action in producers)
