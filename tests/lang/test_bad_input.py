"""Files that are not domains at all: each ends in our own error with a place, quickly."""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.errors import InputError
from btplan.lang import load
from btplan.lang.pddl_reader import read_pddl
from btplan.limits import MAX_NESTING

PICK_PLACE = Path(__file__).resolve().parents[2] / "domains" / "pick_place.bt"


def load_error(*paths: Path | str) -> InputError:
    with pytest.raises(InputError) as caught:
        load([str(p) for p in paths])
    assert caught.value.span is not None
    return caught.value


def test_empty_file(tmp_path: Path) -> None:
    empty = tmp_path / "empty.bt"
    empty.write_text("")
    error = load_error(empty)
    assert error.message == "this input holds no domain and no problem"
    assert str(error.span) == f"{empty}:1:1"


def test_comments_only_is_empty_too(tmp_path: Path) -> None:
    quiet = tmp_path / "quiet.bt"
    quiet.write_text("# nothing here\n\n")
    assert load_error(quiet).message == "this input holds no domain and no problem"


def test_binary_file(tmp_path: Path) -> None:
    binary = tmp_path / "image.bt"
    binary.write_bytes(bytes(range(256)) * 4)
    assert load_error(binary).message == "this is a binary file, not text"


def test_directory(tmp_path: Path) -> None:
    assert load_error(tmp_path).message == "is a directory, not a file"


def test_missing_file(tmp_path: Path) -> None:
    error = load_error(tmp_path / "absent.bt")
    assert error.message == "no such file"
    assert error.span is not None and error.span.path.endswith("absent.bt")


def test_non_utf8_bytes_are_located(tmp_path: Path) -> None:
    latin = tmp_path / "latin.bt"
    latin.write_bytes(PICK_PLACE.read_bytes().replace(b"cube : object", b"cub\xe9 : object"))
    error = load_error(latin)
    assert error.message == "the file is not valid UTF-8 text"
    assert error.span is not None and (error.span.line, error.span.column) == (49, 12)
    assert error.hint == "byte 0xe9 cannot be decoded"


def test_five_megabytes_of_comments_and_a_domain(tmp_path: Path) -> None:
    big = tmp_path / "big.bt"
    padding = ("# " + "x" * 78 + "\n") * (5 * 1024 * 1024 // 81)
    big.write_text(padding + PICK_PLACE.read_text())
    assert big.stat().st_size > 5 * 1024 * 1024
    task = load([str(big)])
    assert task.problem.name == "cube_on_goal"


def test_five_megabytes_of_garbage(tmp_path: Path) -> None:
    junk = tmp_path / "junk.bt"
    junk.write_text("}{" * (5 * 1024 * 1024 // 2))
    error = load_error(junk)
    assert error.message.startswith("unexpected '}'")
    assert error.span is not None and (error.span.line, error.span.column) == (1, 1)


def test_deeply_nested_parentheses_in_bt(tmp_path: Path) -> None:
    """Refused at the first bracket past the limit, before the parser sees it."""
    deep = tmp_path / "deep.bt"
    deep.write_text("domain d { predicates { p(" + "(" * 20000 + ")" * 20000 + ") } }")
    error = load_error(deep)
    assert error.message == f"brackets nested more than {MAX_NESTING} levels deep"
    assert error.span is not None and error.span.column == 27 + MAX_NESTING - 3


def test_deeply_nested_conjunctions_in_pddl() -> None:
    """Legal PDDL of absurd depth: refused at the first parenthesis too deep, not read."""
    depth = 20000
    prefix = "(define (domain d) (:predicates (p)) (:action a :parameters () :precondition "
    text = prefix + "(and " * depth + "(p)" + ")" * depth + " :effect (not (p))))"
    with pytest.raises(InputError) as caught:
        read_pddl(text, "deep.pddl")
    assert caught.value.message == f"parentheses nested more than {MAX_NESTING} levels deep"
    assert caught.value.span is not None
    assert caught.value.span.column == len(prefix) + 1 + 5 * (MAX_NESTING - 2)


def test_a_hundred_nested_conjunctions_are_still_read() -> None:
    """Just within the limit, the reader flattens the conjunctions without recursion."""
    depth = MAX_NESTING - 3  # define, action and precondition hold three levels
    text = (
        "(define (domain d) (:predicates (p)) (:action a :parameters () :precondition "
        + "(and " * (depth - 1) + "(p)" + ")" * (depth - 1) + " :effect (not (p))))"
    )
    (domain,) = read_pddl(text, "deep.pddl")
    assert len(domain.actions[0].pre) == 1  # type: ignore[union-attr]


def test_deeply_nested_bare_parentheses_in_pddl(tmp_path: Path) -> None:
    deep = tmp_path / "deep.pddl"
    deep.write_text("(" * 20000 + ")" * 20000)
    error = load_error(deep)
    assert error.message == f"parentheses nested more than {MAX_NESTING} levels deep"
    assert error.span is not None and error.span.column == MAX_NESTING + 1


def test_a_byte_order_mark_at_the_start_is_not_part_of_the_text(tmp_path: Path) -> None:
    """Some Windows editors start UTF-8 files with one; PDDL and .bt files read as without."""
    source = Path(__file__).resolve().parents[2] / "domains" / "pick_place.bt"
    marked = tmp_path / "pp.bt"
    marked.write_bytes(b"\xef\xbb\xbf" + source.read_bytes())
    assert load([str(marked)]).domain == load([str(source)]).domain
