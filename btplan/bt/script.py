"""BehaviorTree.CPP's Script language: parsed once at load, evaluated against a blackboard.

The subset BT.CPP 4 documents: statements separated by `;`; assignment (`:=` creates
an entry, `=` needs one to exist, `+= -= *= /=`); `a ? b : c`; `||` and `&&`; chained
comparisons (`== != < > <= >=`); `+ - * /`; the bit operators `& | ^ ~`; unary `-` and
`!`; `..` to join strings; numbers (decimal, real, hex), strings in single or double
quotes, `true`/`false`, blackboard names (`@name` is the root blackboard) and enum names
given by the caller. As in BT.CPP, every arithmetic result is a real number, a
comparison or logic result is 1 or 0, a string compared with a number is read as a
number (an error if it is not one), and equality of numbers allows a float epsilon.
Unlike BT.CPP, math and bit operators may be mixed without parentheses (C precedence).
A syntax error is a ScriptSyntaxError with the offset of the offending character, so
the reader can point at it in the file.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from btplan.bt.blackboard import Blackboard, NodeError, Value, as_text, to_number

MAX_CODE = 10_000
"""Longest script read; BT.CPP scripts are one-liners."""
EPSILON = 1.1920929e-07
"""Numbers closer than a float epsilon compare equal, as in BT.CPP."""

_TOKEN = re.compile(r"""
    (?P<space>\s+)
  | (?P<number>0[xX][0-9a-fA-F]+|(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?)
  | (?P<string>'[^']*'|"[^"]*")
  | (?P<name>@?[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>:=|\+=|-=|\*=|/=|==|!=|<=|>=|&&|\|\||\.\.|[-+*/<>=!~&|^?:;()])
""", re.VERBOSE)


class ScriptSyntaxError(Exception):
    """A script that does not parse; `offset` is the 0-based index of the bad character."""

    def __init__(self, message: str, offset: int) -> None:
        super().__init__(message)
        self.message, self.offset = message, offset


@dataclass(frozen=True, slots=True)
class _Tok:
    kind: str
    text: str
    at: int


def _tokens(code: str) -> list[_Tok]:
    out: list[_Tok] = []
    i = 0
    while i < len(code):
        match = _TOKEN.match(code, i)
        if match is None:
            raise ScriptSyntaxError(f"unexpected character {code[i]!r}", i)
        kind = match.lastgroup or ""
        if kind != "space":
            out.append(_Tok(kind, match.group(), i))
        i = match.end()
    out.append(_Tok("end", "", len(code)))
    return out


Env = tuple[Blackboard, Mapping[str, int]]
Expr = Callable[[Env], Value]


def _number(value: Value, op: str) -> float:
    if isinstance(value, str):
        raise NodeError(f"operator {op} is not allowed on the string {value!r}")
    return float(value)


def _truth(value: Value) -> bool:
    """How a condition reads a result: non-zero numbers, 'true'/'false' strings."""
    if isinstance(value, str):
        if value in ("true", "1"):
            return True
        if value in ("false", "0", ""):
            return False
        raise NodeError(f"the string {value!r} is not a condition")
    return value != 0


def _compare(op: str, left: Value, right: Value) -> bool:
    if not isinstance(left, str) and not isinstance(right, str):
        a, b = float(left), float(right)
        if op == "==":
            return abs(a - b) <= EPSILON
        if op == "!=":
            return abs(a - b) > EPSILON
    elif isinstance(left, str) and isinstance(right, str):
        a_s, b_s = left, right
        return {"==": a_s == b_s, "!=": a_s != b_s, "<": a_s < b_s, ">": a_s > b_s,
                "<=": a_s <= b_s, ">=": a_s >= b_s}[op]
    else:  # BT.CPP 4.8 reads the string as a number, and fails if it is not one
        a, b = (to_number(left, "script comparison"), to_number(right, "script comparison"))
        if op in ("==", "!="):
            return (abs(a - b) <= EPSILON) == (op == "==")
    return {"<": a < b, ">": a > b, "<=": a <= b, ">=": a >= b}[op]


def _arith(op: str, a: float, b: float) -> float:
    if op == "+":
        return a + b
    if op == "-":
        return a - b
    if op == "*":
        return a * b
    if b == 0:
        return math.nan if a == 0 else math.copysign(math.inf, a) * math.copysign(1.0, b)
    return a / b


def _bits(op: str, left: Value, right: Value) -> float:
    a, b = _number(left, op), _number(right, op)
    if not (a.is_integer() and b.is_integer()):
        raise NodeError(f"operator {op} needs whole numbers")
    x, y = int(a), int(b)
    return float(x & y if op == "&" else x | y if op == "|" else x ^ y)


class _Parser:
    """Precedence climbing over the token list; each rule returns a closure."""

    def __init__(self, code: str) -> None:
        self.toks = _tokens(code)
        self.i = 0

    def peek(self) -> _Tok:
        return self.toks[self.i]

    def take(self) -> _Tok:
        tok = self.toks[self.i]
        self.i += 1
        return tok

    def expect(self, text: str) -> None:
        tok = self.take()
        if tok.text != text:
            raise ScriptSyntaxError(f"expected {text!r}, found {tok.text or 'the end'!r}", tok.at)

    def statements(self) -> list[Expr]:
        out: list[Expr] = []
        while self.peek().kind != "end":
            out.append(self.assignment())
            if self.peek().text == ";":
                self.take()
            elif self.peek().kind != "end":
                tok = self.peek()
                raise ScriptSyntaxError(f"unexpected {tok.text!r}; separate statements with ';'",
                                        tok.at)
        if not out:
            raise ScriptSyntaxError("the script is empty", 0)
        return out

    def assignment(self) -> Expr:
        start = self.peek()
        left = self.conditional()
        op = self.peek()
        if op.text not in (":=", "=", "+=", "-=", "*=", "/="):
            return left
        if start.kind != "name" or self.toks[self.i - 1] is not start:
            raise ScriptSyntaxError("only a blackboard name can be assigned to", op.at)
        self.take()
        right = self.conditional()
        return _assign(start.text, op.text, right)

    def conditional(self) -> Expr:
        cond = self.logical()
        if self.peek().text != "?":
            return cond
        self.take()
        then = self.assignment()
        self.expect(":")
        other = self.logical()
        return lambda env: then(env) if _truth(cond(env)) else other(env)

    def logical(self) -> Expr:
        left = self.comparison()
        while self.peek().text in ("||", "&&"):
            op = self.take().text
            right = self.comparison()
            left = _logic(op, left, right)
        return left

    def comparison(self) -> Expr:
        first = self.binary(0)
        ops: list[str] = []
        rest: list[Expr] = []
        while self.peek().text in ("==", "!=", "<", ">", "<=", ">="):
            ops.append(self.take().text)
            rest.append(self.binary(0))
        if not ops:
            return first

        def chain(env: Env) -> Value:
            left = first(env)
            for op, operand in zip(ops, rest, strict=True):
                right = operand(env)
                if not _compare(op, left, right):
                    return 0.0
                left = right
            return 1.0
        return chain

    LEVELS = (("|", "^"), ("&",), ("+", "-", ".."), ("*", "/"))

    def binary(self, level: int) -> Expr:
        if level == len(self.LEVELS):
            return self.unary()
        left = self.binary(level + 1)
        while self.peek().kind == "op" and self.peek().text in self.LEVELS[level]:
            op = self.take().text
            right = self.binary(level + 1)
            left = _binop(op, left, right)
        return left

    def unary(self) -> Expr:
        tok = self.peek()
        if tok.text in ("-", "!", "~"):
            self.take()
            operand = self.unary()
            return _unop(tok.text, operand)
        return self.atom()

    def atom(self) -> Expr:
        tok = self.take()
        if tok.text == "(":
            inner = self.assignment()
            self.expect(")")
            return inner
        if tok.kind == "number":
            text = tok.text
            try:
                value: Value = (int(text, 16) if text[:2] in ("0x", "0X") else
                                int(text) if text.isdigit() else float(text))
            except ValueError:  # more digits than Python converts
                raise ScriptSyntaxError("this number is too long", tok.at) from None
            if isinstance(value, int) and not -2**63 <= value < 2**63:
                raise ScriptSyntaxError("this number does not fit in 64 bits", tok.at)
            return lambda env: value
        if tok.kind == "string":
            literal = tok.text[1:-1]
            return lambda env: literal
        if tok.kind == "name":
            if tok.text in ("true", "false"):
                truth = tok.text == "true"
                return lambda env: truth
            return _name(tok.text)
        raise ScriptSyntaxError(f"expected a value, found {tok.text or 'the end'!r}", tok.at)


def _name(name: str) -> Expr:
    def read(env: Env) -> Value:
        board, enums = env
        if name in enums:
            return float(enums[name])
        if not board.has(name):
            raise NodeError(f"script: the blackboard has no entry {name!r}")
        return board.get(name)
    return read


def _assign(name: str, op: str, right: Expr) -> Expr:
    def run(env: Env) -> Value:
        board = env[0]
        exists = board.has(name)
        if not exists and op != ":=":
            raise NodeError(f"script: the blackboard has no entry {name!r} yet "
                            "(use := to create it)")
        value = right(env)
        if op in ("+=", "-=", "*=", "/="):
            current = board.get(name)
            if isinstance(current, str) or isinstance(value, str):
                if op != "+=" or not (isinstance(current, str) and isinstance(value, str)):
                    raise NodeError(f"script: {op} mixes strings and numbers on {name!r}")
                value = current + value
            else:
                value = _arith(op[0], float(current), float(value))
        board.set(name, value)
        return value
    return run


def _logic(op: str, left: Expr, right: Expr) -> Expr:
    def run(env: Env) -> Value:
        a, b = left(env), right(env)
        x, y = _truth(_number(a, op)), _truth(_number(b, op))
        return 1.0 if (x or y if op == "||" else x and y) else 0.0
    return run


def _binop(op: str, left: Expr, right: Expr) -> Expr:
    def run(env: Env) -> Value:
        a, b = left(env), right(env)
        if op == "..":
            return as_text(a) + as_text(b)
        if op in ("&", "|", "^"):
            return _bits(op, a, b)
        if isinstance(a, str) and isinstance(b, str) and op == "+":
            return a + b
        return _arith(op, _number(a, op), _number(b, op))
    return run


def _unop(op: str, operand: Expr) -> Expr:
    def run(env: Env) -> Value:
        value = _number(operand(env), op)
        if op == "-":
            return -value
        if op == "!":
            return 0.0 if value else 1.0
        if not value.is_integer():
            raise NodeError("operator ~ needs a whole number")
        return float(~int(value))
    return run


class Script:
    """A parsed script; `run` executes every statement and returns the last value."""

    __slots__ = ("code", "statements")

    def __init__(self, code: str) -> None:
        self.code = code
        if len(code) > MAX_CODE:
            raise ScriptSyntaxError(f"a script longer than {MAX_CODE:,} characters", MAX_CODE)
        try:
            self.statements = _Parser(code).statements()
        except RecursionError:
            raise ScriptSyntaxError("the script is nested too deeply", 0) from None

    def run(self, board: Blackboard, enums: Mapping[str, int] | None = None) -> Value:
        """Execute the statements in order against `board` and return the last one's value
        (0.0 for an empty script). `enums` replaces the board's enum names; a run-time error
        (an unset entry, strings in arithmetic) is a NodeError."""
        env: Env = (board, board.enums if enums is None else enums)
        value: Value = 0.0
        for statement in self.statements:
            value = statement(env)
        return value

    def holds(self, board: Blackboard, enums: Mapping[str, int] | None = None) -> bool:
        """The script's value read as a condition (`_skipIf`, ScriptCondition, ...)."""
        return _truth(self.run(board, enums))


__all__ = ["EPSILON", "MAX_CODE", "Script", "ScriptSyntaxError"]
