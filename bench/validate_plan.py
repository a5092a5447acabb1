"""A plan validator for the benchmarks, independent of btplan's own readers.

A planner's plan counts as solved only when this module, which shares no code with
btplan, simulates it on the grounded problem: every action's preconditions hold when
it runs (types of its arguments included), effects apply deletes first and adds
second (as PDDL defines), and the goal holds at the end. It reads the STRIPS fragment
IPC domains use: typing with `either`, negative preconditions, equality, and
`:action-costs` (`(increase (total-cost) N)` or by a static function), which gives
the plan's cost.

    python bench/validate_plan.py domain.pddl problem.pddl plan.txt
"""

from __future__ import annotations

import re
import sys
from dataclasses import dataclass, field

Sexp = str | list["Sexp"]


def parse(text: str) -> list[Sexp]:
    """All top-level lists of a PDDL text, comments dropped, names lower-cased."""
    tokens = re.findall(r"[()]|[^\s()]+", re.sub(r";[^\n]*", "", text).lower())
    stack: list[list[Sexp]] = [[]]
    for token in tokens:
        if token == "(":
            stack.append([])
        elif token == ")":
            if len(stack) == 1:
                raise ValueError("unbalanced ')'")
            done = stack.pop()
            stack[-1].append(done)
        else:
            stack[-1].append(token)
    if len(stack) != 1:
        raise ValueError("unbalanced '('")
    return stack[0]


def typed(items: list[Sexp]) -> list[tuple[str, list[str]]]:
    """`a b - t c - (either u v) d` -> [(a, [t]), (b, [t]), (c, [u, v]), (d, [object])]."""
    out: list[tuple[str, list[str]]] = []
    pending: list[str] = []
    index = 0
    while index < len(items):
        item = items[index]
        if item == "-":
            kind = items[index + 1]
            kinds = [str(k) for k in kind[1:]] if isinstance(kind, list) else [kind]
            out += [(name, kinds) for name in pending]
            pending = []
            index += 2
            continue
        pending.append(str(item))
        index += 1
    return out + [(name, ["object"]) for name in pending]


@dataclass
class Action:
    parameters: list[tuple[str, list[str]]]
    precondition: Sexp
    effect: Sexp


@dataclass
class Problem:
    parents: dict[str, list[str]] = field(default_factory=dict)
    types: dict[str, str] = field(default_factory=dict)
    actions: dict[str, Action] = field(default_factory=dict)
    state: set[tuple[str, ...]] = field(default_factory=set)
    numbers: dict[tuple[str, ...], float] = field(default_factory=dict)
    goal: Sexp = field(default_factory=list)

    def is_a(self, kind: str, wanted: str) -> bool:
        seen = {kind}
        frontier = [kind]
        while frontier:
            current = frontier.pop()
            if current == wanted or wanted == "object":
                return True
            for parent in self.parents.get(current, []):
                if parent not in seen:
                    seen.add(parent)
                    frontier.append(parent)
        return False


def read(domain_text: str, problem_text: str) -> Problem:
    problem = Problem()
    for define in parse(domain_text) + parse(problem_text):
        assert isinstance(define, list)
        for section in define[2:]:
            assert isinstance(section, list)
            key, body = section[0], section[1:]
            if key == ":types":
                for name, parents in typed(body):
                    problem.parents.setdefault(name, []).extend(parents)
            elif key in (":constants", ":objects"):
                for name, kinds in typed(body):
                    problem.types[name] = kinds[0]
            elif key == ":action":
                fields = dict(zip(body[1::2], body[2::2]))
                params = fields.get(":parameters", [])
                assert isinstance(params, list)
                problem.actions[str(body[0])] = Action(
                    typed(params), fields.get(":precondition", []), fields.get(":effect", []))
            elif key == ":init":
                for fact in body:
                    assert isinstance(fact, list)
                    if fact[0] == "=":
                        term = fact[1]
                        assert isinstance(term, list)
                        problem.numbers[tuple(map(str, term))] = float(str(fact[2]))
                    else:
                        problem.state.add(tuple(map(str, fact)))
            elif key == ":goal":
                problem.goal = body[0]
    return problem


def holds(condition: Sexp, state: set[tuple[str, ...]], binding: dict[str, str]) -> bool:
    if not isinstance(condition, list) or not condition:
        return True
    head = condition[0]
    if head == "and":
        return all(holds(c, state, binding) for c in condition[1:])
    if head == "not":
        return not holds(condition[1], state, binding)
    args = tuple(binding.get(str(a), str(a)) for a in condition[1:])
    if head == "=":
        return args[0] == args[1]
    return (str(head), *args) in state


def effects(
    effect: Sexp, binding: dict[str, str], numbers: dict[tuple[str, ...], float]
) -> tuple[set[tuple[str, ...]], set[tuple[str, ...]], float]:
    """(adds, deletes, cost) of an effect under `binding`."""
    adds: set[tuple[str, ...]] = set()
    deletes: set[tuple[str, ...]] = set()
    cost = 0.0
    stack = [effect]
    while stack:
        current = stack.pop()
        if not isinstance(current, list) or not current:
            continue
        head = current[0]
        if head == "and":
            stack.extend(current[1:])
        elif head == "increase":
            amount = current[2]
            if isinstance(amount, list):
                key = tuple(binding.get(str(a), str(a)) for a in amount)
                cost += numbers[key]
            else:
                cost += float(amount)
        elif head == "not":
            inner = current[1]
            assert isinstance(inner, list)
            deletes.add(tuple(binding.get(str(a), str(a)) for a in inner))
        elif head in ("when", "forall", "decrease", "assign"):
            raise ValueError(f"'{head}' effects are outside this validator's fragment")
        else:
            adds.add(tuple(binding.get(str(a), str(a)) for a in current))
    return adds, deletes, cost


def validate(domain_text: str, problem_text: str, plan_text: str) -> tuple[bool, str, float]:
    """(valid, reason, cost) of a plan in IPC format: one `(name args)` per line."""
    problem = read(domain_text, problem_text)
    state = set(problem.state)
    total = 0.0
    steps = [line.strip().lower() for line in plan_text.splitlines()]
    steps = [s for s in steps if s and not s.startswith(";")]
    for number, step in enumerate(steps, start=1):
        words = step.strip("()").split()
        action = problem.actions.get(words[0]) if words else None
        if action is None or len(words) - 1 != len(action.parameters):
            return False, f"step {number}: unknown action or wrong arity: {step}", total
        binding = {name: value for (name, _), value in zip(action.parameters, words[1:])}
        for (name, kinds), value in zip(action.parameters, words[1:]):
            kind = problem.types.get(value)
            if kind is None or not any(problem.is_a(kind, k) for k in kinds):
                return False, f"step {number}: {value} does not fit {name} in {step}", total
        if not holds(action.precondition, state, binding):
            return False, f"step {number}: a precondition fails: {step}", total
        adds, deletes, cost = effects(action.effect, binding, problem.numbers)
        state = (state - deletes) | adds
        total += cost
    if not holds(problem.goal, state, {}):
        return False, "the goal does not hold at the end", total
    return True, f"valid, {len(steps)} steps", total


def main() -> None:
    if len(sys.argv) != 4 or sys.argv[1] in ("-h", "--help"):
        print("usage: validate_plan.py DOMAIN.pddl PROBLEM.pddl PLAN\n"
              "Exit 0 when the plan is valid, 1 when it is not.", file=sys.stderr)
        sys.exit(0 if sys.argv[1:2] in (["-h"], ["--help"]) else 2)
    domain, problem, plan = (open(p, encoding="utf-8").read() for p in sys.argv[1:4])
    ok, reason, cost = validate(domain, problem, plan)
    print(f"{reason}; cost {cost:g}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
