"""Load domains and problems from files in either language into checked models.

Any file may hold a domain, problems, or both; problems find their domain by the name
they are written for, so `btplan check domains/*.bt` works on a folder where some
problems live in files of their own.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from btplan.collector import building
from btplan.errors import InputError, Span
from btplan.io import STDIO, read_text
from btplan.lang.names import check_unique, suggest
from btplan.lang.problem_check import build_problem, check_goal
from btplan.lang.report import Report
from btplan.lang.syntax import DomainSyntax, ProblemSyntax
from btplan.lang.validate import build_domain
from btplan.model import ROOT_TYPE, Domain, Problem, Task, TypedName
from btplan.records import record, replace

PDDL_SUFFIXES = (".pddl",)


@record(frozen=True, slots=True)
class BtFile:
    """What one .bt text holds: at most one domain, and any number of problems.

    Problems are checked against the domain when the file holds it; a file of problems
    alone is checked once its domain is known (`bind`).
    """

    path: str
    domain: Domain | None
    problems: tuple[Problem, ...]
    problem_syntax: tuple[ProblemSyntax, ...]

    def bind(self, domain: Domain) -> tuple[Problem, ...]:
        """The problems of this file, checked against `domain`."""
        return tuple(build_problem(p, domain) for p in self.problem_syntax)


@record(frozen=True, slots=True)
class Collection:
    """Every domain and every problem of a set of inputs, each problem checked."""

    domains: tuple[Domain, ...]
    problems: tuple[Problem, ...]
    owners: tuple[int, ...]
    """For each problem, the index in `domains` of the domain it was checked against."""
    paths: tuple[str, ...]
    warnings: tuple[InputError, ...] = ()
    """Located remarks on legal input that is very likely a mistake."""

    def task(self, problem: str | None = None) -> Task:
        """The first problem with its domain, or the one called `problem`."""
        where = Span(self.paths[0] if self.paths else STDIO, 1, 1)
        if not self.problems:
            in_pddl = bool(self.paths) and all(p.lower().endswith(".pddl") for p in self.paths)
            raise InputError(
                "no problem found",
                where,
                "give a problem file: (define (problem NAME) (:domain DOMAIN) (:objects ...) "
                "(:init ...) (:goal ...))" if in_pddl else
                "add 'problem NAME for DOMAIN { objects {...} init {...} goal {...} }' "
                "or give a problem file",
            )
        index = 0
        if problem is not None:
            named = [i for i, p in enumerate(self.problems) if p.name == problem]
            if not named:
                names = [p.name for p in self.problems]
                raise InputError(
                    f"no problem called '{problem}'",
                    where,
                    suggest(problem, names) or f"the problems are {', '.join(sorted(names))}",
                )
            index = named[0]
        return Task(domain=self.domains[self.owners[index]], problem=self.problems[index])


def parse_bt(text: str, path: str) -> BtFile:
    """Parse and check one .bt text (domain and/or problems)."""
    from btplan.lang.bt_reader import read_bt  # builds its lark parser: only for .bt text

    domains, problems = _split(read_bt(text, path))
    if len(domains) > 1:
        raise domains[1].name.at.error(
            "a file holds at most one domain", "put each domain in a file of its own"
        )
    report = Report()
    domain = build_domain(domains[0], report) if domains else None
    if domain is not None:
        found = (report.attempt(build_problem, p, domain, report) for p in problems)
        checked = tuple(p for p in found if p is not None)
    else:
        checked = tuple(_unchecked_problem(p) for p in problems)
    report.raise_errors()
    return BtFile(path=path, domain=domain, problems=checked, problem_syntax=tuple(problems))


def read_units(path: str) -> tuple[list[DomainSyntax], list[ProblemSyntax]]:
    """Read one input (a path, or `-` for standard input) in the language it is written in."""
    text = read_text(path)
    if is_pddl(path, text):
        from btplan.lang.pddl_reader import read_pddl

        return _split(read_pddl(text, path))
    from btplan.lang.bt_reader import read_bt  # builds its lark parser: only for .bt text

    return _split(read_bt(text, path))


def _defined_twice(again: DomainSyntax, first: DomainSyntax) -> None:
    at = first.name.at
    raise again.name.at.error(f"domain '{again.name.text}' is defined twice in this file",
                              f"the first definition is at line {at.line}; keep one")


def collect(paths: Sequence[str]) -> Collection:
    """Read every input, check every domain, and check each problem against its domain.

    The garbage collector is paused meanwhile: syntax trees and models are many small
    objects without cycles, and its passes over them freed nothing (9 of 58 ms of a
    67 KB PDDL domain).

    A problem binds to the domain of its own file when that has the name it is written
    for, else to the first input domain of that name: two files may each define their
    own `blocksworld`, and a file of problems alone finds its domain in another file.
    Mistakes in one file do not stop the others from being checked; all are raised
    together at the end (`InputErrors`).
    """
    if not paths:
        raise InputError("no input files given")
    if sum(1 for p in paths if p == STDIO) > 1:
        raise InputError("standard input ('-') can be read only once")
    with building():
        return _collected(paths)


def _collected(paths: Sequence[str]) -> Collection:
    report = Report()
    nothing: tuple[list[DomainSyntax], list[ProblemSyntax]] = ([], [])
    files = [report.attempt(_read_nonempty, path) or nothing for path in paths]
    built: list[list[Domain]] = []
    broken: set[str] = set()
    for domains, _ in files:
        built.append([])
        first: dict[str, DomainSyntax] = {}
        for d_syntax in domains:
            earlier = first.setdefault(d_syntax.name.text, d_syntax)
            if earlier is not d_syntax:
                report.attempt(_defined_twice, d_syntax, earlier)
                continue
            built_domain = report.attempt(build_domain, d_syntax, report)
            if built_domain is None:
                broken.add(d_syntax.name.text)
            else:
                built[-1].append(built_domain)
    everywhere = [d for per_file in built for d in per_file]
    problems: list[Problem] = []
    owners: list[int] = []
    for (_, file_problems), own in zip(files, built, strict=True):
        check_unique((p.name for p in file_problems), "problem", report)
        for syntax in file_problems:
            domain = report.attempt(_domain_for, syntax, own + everywhere, broken)
            problem = report.attempt(build_problem, syntax, domain, report) if domain else None
            if domain is not None and problem is not None:
                problems.append(problem)
                owners.append(next(i for i, d in enumerate(everywhere) if d is domain))
    report.raise_errors(paths)
    return Collection(
        tuple(everywhere), tuple(problems), tuple(owners), tuple(paths), tuple(report.warnings)
    )


def _domain_for(syntax: ProblemSyntax, domains: list[Domain], broken: set[str]) -> Domain | None:
    """The domain a problem is written for; None when that domain had mistakes."""
    wanted = syntax.domain.text
    domain = next((d for d in domains if d.name == wanted), None)
    if domain is None and wanted not in broken:
        raise syntax.domain.at.error(
            f"problem '{syntax.name.text}' is for domain '{wanted}', "
            "which none of the inputs defines",
            suggest(wanted, {d.name for d in domains}) or "give the domain file too",
        )
    return domain


def _read_nonempty(path: str) -> tuple[list[DomainSyntax], list[ProblemSyntax]]:
    domains, problems = read_units(path)
    if not domains and not problems:
        raise InputError(
            "this input holds no domain and no problem",
            Span(path, 1, 1),
            "a domain starts with '(define (domain NAME)', a problem with "
            "'(define (problem NAME)'" if Path(path).suffix.lower() in PDDL_SUFFIXES else
            "a domain starts with 'domain NAME {', a problem with 'problem NAME for DOMAIN {'",
        )
    return domains, problems


def load(paths: Sequence[str], problem: str | None = None) -> Task:
    """Load a planning task: one .bt file with domain and problem, or a domain file and a
    problem file (.bt or .pddl; `-` reads standard input). With several problems, the
    first is taken unless `problem` names one."""
    if isinstance(paths, str):
        paths = [paths]
    collection = collect(paths)
    if not collection.domains:
        raise InputError(
            "no domain found",
            Span(paths[0], 1, 1),
            "add 'domain NAME { ... }' or give the domain file too",
        )
    return collection.task(problem)


def load_domain(path: str) -> Domain:
    """Load the one domain of a file (any problems in it are checked too)."""
    collection = collect([path])
    if not collection.domains:
        raise InputError(
            "no domain found in this file", Span(path, 1, 1), "a domain starts with 'domain NAME {'"
        )
    return collection.domains[0]


def load_problem(domain: Domain, path: str, problem: str | None = None) -> Task:
    """A problem of `path` as a task of an already loaded `domain` (the first problem, or
    the one called `problem`).

    Many problems of one domain (goal sets, a robot given one goal after another) read
    the domain once, and their tasks share the one `Domain` object, which keeps the
    models planning builds for it (btplan/planner/reuse.py) for the next task. A domain
    in the file is not read again: the problems are checked against `domain`.
    """
    with building():
        return _problem_of(domain, path, problem)


def with_goal(task: Task, goal: str, source: str = "goal") -> Task:
    """`task` with `goal`, one PDDL condition such as `(and (on a b) (not (clear c)))`,
    as its goal: the same domain, objects and initial state.

    A robot in one scene is given one goal after another; reading the scene once and
    each goal alone spares reading and checking the objects and the initial facts again
    (on BTPG's RoboWaiter goals, most of the problem's reading), and the goals' tasks
    share the domain and the models planning keeps with it. The goal is checked as a
    problem's goal is; `source` names it in error messages.

        >>> from btplan import load
        >>> task = with_goal(load("pick_place"), "(holding cube)")
        >>> [str(goal) for goal in task.goal_literals]
        ['holding(cube)']
    """
    from btplan.lang.pddl_reader import read_goal

    with building():
        report = Report()
        literals = check_goal(read_goal(goal, source), task, report)
        report.raise_errors([source])
    return Task(domain=task.domain, problem=replace(task.problem, goal=literals))


def _problem_of(domain: Domain, path: str, problem: str | None) -> Task:
    report = Report()
    _, syntaxes = _read_nonempty(path)
    check_unique((p.name for p in syntaxes), "problem", report)
    problems = []
    for syntax in syntaxes:
        if report.attempt(_domain_for, syntax, [domain], set()) is not None:
            built = report.attempt(build_problem, syntax, domain, report)
            if built is not None:
                problems.append(built)
    report.raise_errors([path])
    collection = Collection((domain,), tuple(problems), (0,) * len(problems), (path,))
    return collection.task(problem)


def is_pddl(path: str, text: str) -> bool:
    """PDDL by suffix; for standard input or other suffixes, by the first character."""
    suffix = Path(path).suffix.lower() if path != STDIO else ""
    if suffix in PDDL_SUFFIXES:
        return True
    if suffix == ".bt":
        return False
    for line in text.splitlines():
        stripped = line.strip()
        if stripped and not stripped.startswith((";", "#")):
            return stripped.startswith("(")
    return False


def _split(
    units: Sequence[DomainSyntax | ProblemSyntax],
) -> tuple[list[DomainSyntax], list[ProblemSyntax]]:
    domains = [u for u in units if isinstance(u, DomainSyntax)]
    problems = [u for u in units if isinstance(u, ProblemSyntax)]
    return domains, problems


def _unchecked_problem(syntax: ProblemSyntax) -> Problem:
    return Problem(
        name=syntax.name.text,
        domain=syntax.domain.text,
        objects=tuple(
            TypedName(name=o.name.text, type=o.type.text if o.type else ROOT_TYPE)
            for o in syntax.objects
        ),
        init=tuple(lit.literal() for lit in syntax.init),
        goal=tuple(lit.literal() for lit in syntax.goal),
    )
