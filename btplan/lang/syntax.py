"""Located syntax: what a file said, and where, before it becomes a model.

The pydantic models carry no positions (they are shared by both languages and by code
that builds domains by hand), so both readers first produce these small records, and
validation turns them into models while it can still point at the offending text.
"""

from __future__ import annotations

from btplan.errors import InputError, Span
from btplan.model import EQUALITY, Literal
from btplan.records import record


class _Place:
    """A place in a source text, with the text of its line for the caret display.

    The reader makes one for every token and nearly all of them are never looked at,
    so a place keeps only its source and position, and its span and line text are made
    when asked for (making them at once cost more than reading a small problem). It
    compares, hashes and prints by those two, and cannot be changed, as a frozen
    record. `Where` is this, made as a tuple (below).
    """

    __slots__ = ()
    source: Source
    line: int
    column: int

    @property
    def span(self) -> Span:
        """The place as a Span, made on each call rather than kept (see the class docstring)."""
        return Span(self.source.path, self.line, self.column)

    @property
    def line_text(self) -> str:
        """The text of the place's line, for the caret display; "" for a line outside the text."""
        lines = self.source.lines
        return lines[self.line - 1] if 0 < self.line <= len(lines) else ""

    def error(self, message: str, hint: str | None = None) -> InputError:
        """An InputError at this place, carrying its line for the caret: what readers and checks
        raise (or report) for a mistake here."""
        return InputError(message, self.span, hint, self.line_text)

    def _key(self) -> tuple[Span, str]:
        return self.span, self.line_text

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Where):
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self) -> int:
        return hash(self._key())

    def __repr__(self) -> str:
        return f"Where(span={self.span!r}, line_text={self.line_text!r})"

    def __setattr__(self, name: str, value: object) -> None:
        raise AttributeError(f"cannot assign to field {name!r}")

    def __delattr__(self, name: str) -> None:
        raise AttributeError(f"cannot delete field {name!r}")

    def __reduce__(self) -> tuple[type[Where], tuple[Source, int, int]]:
        return Where, (self.source, self.line, self.column)


TYPE_CHECKING = False
if TYPE_CHECKING:
    class Where(_Place):
        """A place in a source text (`_Place`)."""

        __slots__ = ("column", "line", "source")

        def __init__(self, source: Source, line: int, column: int) -> None:
            """Where `line` and `column` of `source` are."""

else:  # a tuple, made in C (as sexpr.py makes its words): the reader makes one a token,
    # and setting three slots one by one took 0.4 us of each, 0.14 now
    from collections import _tuplegetter

    _new_tuple = tuple.__new__

    class Where(_Place, tuple):
        __doc__ = _Place.__doc__
        __slots__ = ()
        source = _tuplegetter(0, "The text the place is in.")
        line = _tuplegetter(1, "Its line, from 1.")
        column = _tuplegetter(2, "Its column, from 1.")

        def __new__(cls, source, line, column):
            return _new_tuple(cls, (source, line, column))




@record(frozen=True, slots=True)
class Name:
    """An identifier as written, with its place."""

    text: str
    at: Where


@record(frozen=True, slots=True)
class Number:
    """A number as written (a cost, a duration, a function's value), kept as text so that
    validation can refuse a bad one at its place."""
    text: str
    at: Where


@record(frozen=True, slots=True)
class TypedSyntax:
    """One entry of a types, constants or objects list: `name : type`, type optional."""

    name: Name
    type: Name | None


@record(frozen=True, slots=True)
class ParameterSyntax:
    """A parameter as written: its type (None: the root type), and whether it is `refined`,
    bound by the world rather than chosen among the objects."""
    name: Name
    type: Name | None
    refined: bool = False


@record(frozen=True, slots=True)
class PredicateSyntax:
    """A predicate as declared; also a static function's declaration (PDDL's `:functions`)."""
    name: Name
    parameters: tuple[ParameterSyntax, ...]


@record(frozen=True, slots=True)
class LiteralSyntax:
    """A literal; `predicate` is "=" for equalities, whose `at` is the left operand."""

    predicate: Name
    args: tuple[Name, ...]
    positive: bool
    at: Where

    @property
    def is_equality(self) -> bool:
        """Whether this is `x == y` or `x != y`: it names no declared predicate, so the checks
        treat it apart."""
        return self.predicate.text == EQUALITY

    def literal(self) -> Literal:
        """The model's Literal, the places dropped: what validation keeps once the checks pass,
        and what messages quote."""
        return Literal(
            predicate=self.predicate.text,
            args=tuple(a.text for a in self.args),
            positive=self.positive,
        )


@record(frozen=True, slots=True)
class ActionSyntax:
    """An action as written: `where` holds the binding constraints, `pre` and `post` the
    conditions and effects; cost and duration stay text until validated."""
    name: Name
    parameters: tuple[ParameterSyntax, ...]
    where: tuple[LiteralSyntax, ...] = ()
    pre: tuple[LiteralSyntax, ...] = ()
    post: tuple[LiteralSyntax, ...] = ()
    cost: Number | None = None
    duration: Number | None = None
    cost_term: LiteralSyntax | None = None
    """A cost read from a static function, PDDL's `(increase (total-cost) (f ?x))`."""


@record(frozen=True, slots=True)
class DomainSyntax:
    """A domain as either reader saw it, before validation makes it a Domain."""
    name: Name
    requirements: tuple[Name, ...] = ()
    types: tuple[TypedSyntax, ...] = ()
    constants: tuple[TypedSyntax, ...] = ()
    predicates: tuple[PredicateSyntax, ...] = ()
    actions: tuple[ActionSyntax, ...] = ()
    functions: tuple[PredicateSyntax, ...] = ()
    """Static numeric functions that action costs read (PDDL's `:action-costs`)."""


@record(frozen=True, slots=True)
class ProblemSyntax:
    """A problem as either reader saw it, before it is checked against its domain and made a
    Problem."""
    name: Name
    domain: Name
    objects: tuple[TypedSyntax, ...] = ()
    init: tuple[LiteralSyntax, ...] = ()
    goal: tuple[LiteralSyntax, ...] = ()
    values: tuple[tuple[LiteralSyntax, Number], ...] = ()
    """Initial values of static functions: `(= (road-length a b) 12)`."""


class Source:
    """The text of one input, split into lines once, to build `Where`s cheaply."""

    __slots__ = ("lines", "path", "text")

    def __init__(self, text: str, path: str) -> None:
        self.path = path
        self.text = text
        # lark counts only "\n" as a line break, so str.splitlines would misalign lines
        self.lines = text.split("\n")

    def at(self, line: int, column: int) -> Where:
        """A place in this text; line and column count from 1, as lark and editors do."""
        return Where(self, line, column)

    def end(self) -> Where:
        """The last character of the text: where end-of-file errors point."""
        index = len(self.lines)
        while index > 1 and not self.lines[index - 1].strip():
            index -= 1
        return self.at(index, len(self.lines[index - 1].rstrip()) + 1)

    def start(self) -> Where:
        """The first character: where an error about the input as a whole points (a parse
        failure with no position of its own)."""
        return self.at(1, 1)
