"""`Robot`: a world for the blended loop written as conditions and skills in plain Python.

    robot = Robot()

    @robot.condition("holding")
    def holding(obj: str) -> bool:          # over the robot's current state
        return gripper.object == obj

    @robot.action("Pick")
    def pick(obj: str) -> Future:           # start a skill; the loop polls it
        return driver.pick_async(obj)

    btplan.run(task, world=robot, rate=10)

Conditions get the grounded objects of the predicate; actions get the grounded objects
and refined values of the template's parameters, in order, and start a skill
(btplan.robot.skills says what they may return). A subclass may declare them as
methods instead, with the `condition` and `action` decorators of this module.

Before the run, `bind(task)` checks the robot against the domain: every action
template and every predicate that actions change must be bound, to a function that
takes their arguments (one error names every misfit, with close matches, at the
subclass's `class` line); predicates no action changes are answered from the problem.
A refined parameter is refined by a `refiner` when one is given, else by the objects of
its type that its `where` constraints hold for.
"""

from __future__ import annotations

import inspect
import os
import threading
from collections.abc import Callable, Iterable, Iterator, Mapping
from difflib import get_close_matches
from itertools import product
from typing import Any, TypeVar

from btplan.bt.status import FAILURE, RUNNING, Status
from btplan.bt.world import LeafKey
from btplan.errors import InputError, Span, WorldError
from btplan.model import (
    EQUALITY,
    WILDCARD,
    ActionTemplate,
    Atom,
    Literal,
    Parameter,
    Task,
    matches,
)
from btplan.records import record, replace
from btplan.robot.contract import Capabilities
from btplan.robot.refine import ConstraintRefiner
from btplan.robot.skills import Running, Threads, as_status

__all__ = ["Ask", "Robot", "action", "condition", "refiner"]

F = TypeVar("F", bound=Callable[..., Any])


@record(frozen=True, slots=True)
class Ask:
    """A refiner's question: values for `parameter` of `action`, given what is bound.

    `binding` maps the parameters bound so far to their values; `where` holds the
    template's `where` constraints with those values put in (`("door_of", ("kitchen",
    "?p"))`: unbound parameters as `?name`), so that a refiner sees a target the
    constraints name even when no ordinary parameter carries it. A negated constraint
    is named `not door_of`; equalities are `==` and `!=` (`("!=", ("?r", "kitchen"))`)."""

    action: str
    parameter: str
    type: str
    binding: Mapping[str, str]
    where: tuple[tuple[str, tuple[str, ...]], ...]


def condition(name: str) -> Callable[[F], F]:
    """Mark a method of a Robot subclass as the condition `name` (a predicate)."""
    return _mark("condition", name)


def action(name: str, *, threaded: bool = False) -> Callable[[F], F]:
    """Mark a method of a Robot subclass as the action `name` (an action template);
    `threaded`: run it in a thread of its own, with a `stop` event a halt sets."""
    return _mark("threaded" if threaded else "action", name)


def refiner(action_name: str, parameter: str) -> Callable[[F], F]:
    """Mark a method of a Robot subclass as the refiner of `parameter` of `action_name`."""
    return _mark("refiner", f"{action_name}.{parameter}")


def _mark(kind: str, name: str) -> Callable[[F], F]:
    def mark(function: F) -> F:
        function.__btplan_binding__ = (kind, name)  # type: ignore[attr-defined]
        return function

    return mark


class Robot:
    """A world made of conditions, skills and refiners (see the module docstring)."""

    def __init__(self) -> None:
        self._conditions: dict[str, Callable[..., object]] = {}
        self._actions: dict[str, tuple[Callable[..., object], bool]] = {}
        self._refiners: dict[tuple[str, str], Callable[[Ask], Iterable[str]]] = {}
        self._running: dict[LeafKey, Running] = {}
        self._stopping: dict[LeafKey, list[Running]] = {}
        self._threads = Threads()
        self._lock = threading.Lock()
        self._task: Task | None = None
        self._static: frozenset[Atom] = frozenset()
        self._groundings: dict[str, list[tuple[str, ...]]] = {}
        self._fallback: ConstraintRefiner | None = None
        self.capabilities = Capabilities(refines=True, reports_stopped=True, closes=True)
        # Marks are looked up on the class, so that no property of a subclass runs
        # before its __init__ has set what the property reads.
        for attribute in dir(type(self)):
            binding = getattr(getattr(type(self), attribute, None), "__btplan_binding__", None)
            if binding is not None:
                self._register(binding[0], binding[1], getattr(self, attribute))

    # --- registering -------------------------------------------------------------------

    def condition(self, name: str) -> Callable[[F], F]:
        """Register the decorated function as the condition `name` (a predicate)."""
        return self._registrar("condition", name)

    def action(self, name: str, *, threaded: bool = False) -> Callable[[F], F]:
        """Register the decorated function as the action `name` (see `action` above)."""
        return self._registrar("threaded" if threaded else "action", name)

    def refiner(self, action_name: str, parameter: str) -> Callable[[F], F]:
        """Register the decorated function, `fn(ask: Ask) -> values`, as a refiner."""
        return self._registrar("refiner", f"{action_name}.{parameter}")

    def _registrar(self, kind: str, name: str) -> Callable[[F], F]:
        def register(function: F) -> F:
            self._register(kind, name, function)
            return function

        return register

    def _register(self, kind: str, name: str, function: Callable[..., Any]) -> None:
        if kind == "condition":
            self._conditions[name] = function
        elif kind == "refiner":
            action_name, _, parameter = name.partition(".")
            self._refiners[(action_name, parameter)] = function
            self.capabilities = replace(self.capabilities, own_values=True)
        else:
            self._actions[name] = (function, kind == "threaded")

    # --- checked against the task --------------------------------------------------------

    def bind(self, task: Task) -> None:
        """Check the robot against `task` and get ready to act in it (see the module
        docstring); raises InputError naming every missing or unknown binding."""
        domain = task.domain
        actions = sorted(a.name for a in domain.actions)
        changing = sorted(domain.changed_predicates)
        predicates = sorted(p.name for p in domain.predicates)
        problems = [
            *_fit("action", actions, actions, self._actions),
            *_fit("predicate", changing, predicates, self._conditions, "condition"),
            *(f"a refiner: {why}" for why in
              _fit("action", [], actions, {a for a, _ in self._refiners})),
            *self._misfits(task),
        ]
        if problems:
            span, line = _where_defined(type(self))
            raise InputError(f"{type(self).__name__} does not fit domain "
                             f"'{domain.name}': " + "; ".join(problems), span,
                             "see docs/robot.md", line)
        self._task = task
        self._static = frozenset(a for a in task.initial_state
                                 if a.predicate not in self._conditions)
        self._groundings = {p.name: _groundings(task, [a.type for a in p.parameters])
                            for p in domain.predicates if p.name in self._conditions}
        self._fallback = ConstraintRefiner(task, self.facts)

    def _misfits(self, task: Task) -> Iterator[str]:
        """Functions that cannot take what the loop will pass them, and refiners of
        parameters the planner never asks the world for."""
        templates = {a.name: a for a in task.domain.actions}
        for name, (function, threaded) in sorted(self._actions.items()):
            template = templates.get(name)
            if template is not None:
                params = [p.name for p in template.parameters]
                yield from _arity(name, function, params, threaded)
        for predicate in task.domain.predicates:
            answer = self._conditions.get(predicate.name)
            if answer is not None:
                params = [p.name for p in predicate.parameters]
                yield from _arity(predicate.name, answer, params)
        for action_name, parameter in sorted(self._refiners):
            template = templates.get(action_name)
            if template is None:
                continue
            refined = sorted(p.name for p in template.parameters if p.refined)
            if parameter not in refined:
                yield (f"a refiner is bound for {action_name}.{parameter}, but "
                       f"{action_name} refines " + (", ".join(refined) or "nothing"))

    # --- the world contract ------------------------------------------------------------

    def check(self, key: LeafKey) -> bool:
        """Whether a grounded condition holds: its bound function, the problem for a
        predicate no action changes, any grounding for a wildcard (`_`)."""
        name, args = key
        function = self._conditions.get(name)
        if function is None:
            if name == EQUALITY:  # as the symbolic world answers it
                return len(args) == 2 and args[0] == args[1]
            if WILDCARD in args:
                pattern = Atom(name, tuple(args))
                return any(matches(pattern, a) for a in self._static)
            return Atom(name, tuple(args)) in self._static
        if WILDCARD in args:
            return any(_truth(function(*g), name) for g in self._groundings.get(name, ())
                       if all(a in (WILDCARD, b) for a, b in zip(args, g)))
        return _truth(function(*args), name)

    def facts(self) -> frozenset[Atom]:
        """Every condition evaluated over every grounding, with the static facts."""
        found = set(self._static)
        for name, function in self._conditions.items():
            for args in self._groundings.get(name, ()):
                try:
                    holds = _truth(function(*args), name)
                except Exception as error:  # noqa: BLE001 (named below)
                    # The planner needs every fact: a condition that cannot say is the
                    # robot's fault, named as such, not a false fact nor a btplan bug.
                    raise WorldError(f"the condition {name}({', '.join(args)}) raised "
                                     f"{type(error).__name__}: {error}") from error
                if holds:
                    found.add(Atom(name, args))
        return frozenset(found)

    def start(self, key: LeafKey) -> Status:
        """Start the bound skill of a grounded action and poll it once."""
        name, args = key
        bound = self._actions.get(name)
        if bound is None:
            raise WorldError(f"{type(self).__name__} has no action {name!r}")
        function, threaded = bound
        what = f"{name}({', '.join(args)})"
        stop = threading.Event() if threaded else None
        if stop is not None:
            answer: object = self._threads.submit(function, *args, stop=stop)
        else:
            answer = function(*args)
        if answer is None or isinstance(answer, (bool, Status)):
            return as_status(True if answer is None else answer, what)  # ended at once
        running = Running(what, answer, stop)
        with self._lock:
            self._running[key] = running
        return self._poll(key, running)

    def step(self, key: LeafKey) -> Status:
        """Poll the running skill of a grounded action (never blocks)."""
        running = self._running.get(key)
        if running is None:
            raise WorldError(f"{key[0]} was stepped without being started")
        return self._poll(key, running)

    def halt(self, key: LeafKey) -> None:
        """Cancel the running skill; `stopped` answers once it has come to rest."""
        with self._lock:
            running = self._running.pop(key, None)
        if running is None:
            return
        # Only the loop's way out asks `stopped`: forget the halted skills that have come
        # to rest since, so that a long run does not keep every one it ever halted.
        earlier = [r for r in self._stopping.get(key, ()) if not r.stopped()]
        self._stopping[key] = [*earlier, running]
        running.cancel()

    def stopped(self, key: LeafKey) -> bool:
        """Whether a halted skill has come to rest (the loop waits for it on the way out)."""
        moving = [r for r in self._stopping.pop(key, ()) if not r.stopped()]
        if moving:
            self._stopping[key] = moving
        return not moving

    def refine(self, template: ActionTemplate, binding: Mapping[str, str],
               parameter: Parameter) -> list[str]:
        """The values of a refined parameter: the robot's refiner when one is bound,
        else the objects its `where` constraints hold for."""
        function = self._refiners.get((template.name, parameter.name))
        if function is None:
            if self._fallback is None:
                raise WorldError("the robot is not bound to a task: call bind(task) first")
            return self._fallback(template, binding, parameter)
        names = _names(template)
        where = tuple((_constraint_name(c), tuple(binding.get(a, f"?{a}") if a in names
                                                  else a for a in c.args))
                      for c in template.constraints)
        ask = Ask(template.name, parameter.name, parameter.type, dict(binding), where)
        return [str(v) for v in function(ask)]

    def close(self) -> None:
        """Cancel whatever still runs and let the skill threads go."""
        for key in list(self._running):
            self.halt(key)
        self._threads.shutdown()

    # ---------------------------------------------------------------------------------

    def _poll(self, key: LeafKey, running: Running) -> Status:
        status = running.poll() if not running.cancelled else FAILURE
        if status is not RUNNING:
            with self._lock:
                self._running.pop(key, None)
        return status


def _names(template: ActionTemplate) -> set[str]:
    return {p.name for p in template.parameters}


def _constraint_name(literal: Literal) -> str:
    if literal.predicate == EQUALITY:
        return "==" if literal.positive else "!="
    return literal.predicate if literal.positive else f"not {literal.predicate}"


def _truth(answer: object, name: str) -> bool:
    if isinstance(answer, bool):
        return answer
    kind = type(answer)
    if kind.__module__ == "numpy" and kind.__name__.startswith("bool"):
        return bool(answer)  # numpy.bool_ from a comparison of arrays
    raise TypeError(f"the condition {name!r} answered {answer!r}; expected True or False")


def _arity(name: str, function: Callable[..., object], params: list[str],
           threaded: bool = False) -> Iterator[str]:
    """Whether `function` takes the grounded `params` in order (and `stop`, threaded)."""
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return  # a builtin or a C extension: nothing to read, the call will tell
    try:
        signature.bind(*params, **({"stop": None} if threaded else {}))
    except TypeError:
        takes = ", ".join(params + (["stop"] if threaded else []))
        yield f"{_shown(function, signature)} cannot take {name}({takes})"


def _shown(function: Callable[..., object], signature: inspect.Signature) -> str:
    """`Robot.pick(o)`: where a function is written and its parameters, without types."""
    name = str(getattr(function, "__qualname__", None) or getattr(function, "__name__", "it"))
    stars: dict[object, str] = {inspect.Parameter.VAR_POSITIONAL: "*",
                                inspect.Parameter.VAR_KEYWORD: "**"}
    shown = ", ".join(stars.get(p.kind, "") + p.name for p in signature.parameters.values())
    return f"{name.rpartition('<locals>.')[2]}({shown})"


def _where_defined(cls: type) -> tuple[Span | None, str | None]:
    """Where a Robot subclass is written (file, line of its `class`), for the bind error."""
    if cls is Robot:
        return None, None
    try:
        lines, number = inspect.getsourcelines(cls)
        path = inspect.getsourcefile(cls)
    except (OSError, TypeError):
        return None, None
    if path is None:
        return None, None
    try:
        shown = os.path.relpath(path)
    except ValueError:  # another drive
        shown = path
    if shown.startswith(".."):
        shown = path
    text = next((line for line in lines if line.lstrip().startswith("class ")), lines[0])
    column = len(text) - len(text.lstrip()) + 1
    return Span(shown, number + lines.index(text), column), text


def _groundings(task: Task, types: list[str]) -> list[tuple[str, ...]]:
    return [tuple(g) for g in product(*(task.objects_of(t) for t in types))]


def _fit(kind: str, needed: list[str], known: list[str], bound: Iterable[str],
         missing_as: str = "") -> Iterator[str]:
    """Bound names that are not `known`, each with its likely meaning (a missing name
    first: a misspelling), then the `needed` names left unbound, in one short item."""
    bound = sorted(bound)
    missing = [n for n in needed if n not in bound]
    meant: set[str] = set()
    for name in bound:
        if name in known:
            continue
        near = get_close_matches(name, missing, n=1) or get_close_matches(name, known, n=1)
        meant.update(near)
        yield f"'{name}' is no {kind} of the domain" + (
            f" (did you mean '{near[0]}'?)" if near else "")
    rest = [n for n in missing if n not in meant]
    if rest:
        yield f"no {missing_as or kind} for {', '.join(rest)}"
