"""Every kind of mistake gives our own error, at the right place, in words a user understands.

Each case edits the paper's Example 1 in one place and asserts the whole message.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from btplan.errors import InputError
from btplan.lang import InputErrors, collect, parse_bt

BASE = (Path(__file__).resolve().parents[2] / "domains" / "pick_place.bt").read_text()

# name: (text to replace, replacement, (line, column), message, hint)
CASES = {
    "unknown predicate": (
        "pre:   free(t)",
        "pre:   fre(t)",
        (29, 16),
        "unknown predicate 'fre'",
        "did you mean 'free'?",
    ),
    "wrong arity": (
        "pre:   free(t)",
        "pre:   free(t, l)",
        (29, 16),
        "free takes 1 argument, got 2",
        "declared as free(t: trajectory)",
    ),
    "wrong type in an action": (
        "pre:   free(t)",
        "pre:   free(l)",
        (29, 21),
        "'l' is a location, but free expects a trajectory here",
        None,
    ),
    "wrong type in a fact": (
        "free(tau_cube), free(tau_goal)",
        "free(tau_cube), free(cube)",
        (55, 30),
        "'cube' is an object, but free expects a trajectory here",
        None,
    ),
    "unbound variable in a postcondition": (
        "post: holding(o), not hand_empty",
        "post: holding(x), not hand_empty",
        (36, 23),
        "unbound variable 'x' in a postcondition of Pick",
        "the parameters of Pick are o",
    ),
    "unknown name in a precondition": (
        "pre:  near(o), hand_empty",
        "pre:  near(p), hand_empty",
        (35, 20),
        "'p' is neither a parameter of Pick nor a constant",
        "the parameters of Pick are o",
    ),
    "duplicate predicate": (
        "        hand_empty                          # h = (nothing)",
        "        hand_empty\n        holding(x: object)",
        (22, 9),
        "predicate 'holding' is declared twice",
        "first declared at pp.bt:20:9",
    ),
    "duplicate action": (
        "action Place(",
        "action Pick(",
        (40, 12),
        "action 'Pick' is declared twice",
        "first declared at pp.bt:34:12",
    ),
    "duplicate object": (
        "cube : object",
        "cube : object\n        cube : location",
        (50, 9),
        "object 'cube' is declared twice",
        "first declared at pp.bt:49:9",
    ),
    "duplicate parameter": (
        "action Place(o: object, l: location)",
        "action Place(o: object, o: location)",
        (40, 29),
        "parameter 'o' is declared twice",
        "first declared at pp.bt:40:18",
    ),
    "object that is also a constant": (
        "cube : object",
        "cube, goal : object",
        (49, 15),
        "'goal' is already a constant of domain 'pick_place'",
        None,
    ),
    "goal over an unknown object": (
        "on(cube, goal)\n",
        "on(cub, goal)\n",
        (60, 12),
        "unknown object 'cub' in a goal",
        "did you mean 'cube'?",
    ),
    "contradictory postconditions": (
        "post: holding(o), not hand_empty",
        "post: holding(o), not holding(o)",
        (36, 31),
        "contradictory postconditions: 'holding(o)' and 'not holding(o)'",
        "this action would make it both true and false",
    ),
    "contradictory goal": (
        "on(cube, goal)\n",
        "on(cube, goal), not on(cube, goal)\n",
        (60, 29),
        "contradictory goal conditions: 'on(cube, goal)' and 'not on(cube, goal)'",
        "no state satisfies both",
    ),
    "unknown type": (
        "holding(o: object)",
        "holding(o: objet)",
        (20, 20),
        "unknown type 'objet'",
        "did you mean 'object'?",
    ),
    "type cycle": (
        "        location                    #",
        "        location : object  #",
        (9, 9),
        "the type hierarchy has a cycle: location -> object -> location",
        None,
    ),
    "wildcard in a positive literal": (
        "post:  not near(_), near(l)",
        "post:  near(_), near(l)",
        (30, 21),
        "the wildcard '_' is only allowed in a negative postcondition or precondition",
        "write e.g. 'post: not near(_), near(l)' or 'pre: not blocks(_, t)'",
    ),
    "negative initial fact": (
        "        hand_empty\n        free",
        "        not hand_empty\n        free",
        (54, 13),
        "initial facts are positive",
        "leave out what is false: it is false by default",
    ),
    "problem for another domain": (
        "problem cube_on_goal for pick_place",
        "problem cube_on_goal for pick_plac",
        (47, 26),
        "problem 'cube_on_goal' is for domain 'pick_plac', but the domain given is 'pick_place'",
        None,
    ),
    "fractional duration": (
        "duration: 3",
        "duration: 1.5",
        (31, 19),
        "a duration is a whole number of ticks, at least 1",
        None,
    ),
    "equality as a postcondition": (
        "post:  not near(_), near(l)",
        "post:  not near(_), near(l), l == t",
        (30, 38),
        "an equality cannot be a postcondition",
        "equalities belong under 'where:' or 'pre:'",
    ),
    "equality of unrelated types": (
        "where: route(l, t)",
        "where: route(l, t), l != t",
        (28, 29),
        "'l != t' is always true: l is a location and t is a trajectory",
        None,
    ),
    "parameter named like a constant": (
        "action Pick(o: object)",
        "action Pick(goal: object)",
        (34, 17),
        "parameter 'goal' has the name of a constant",
        "rename the parameter",
    ),
    "refined predicate parameter": (
        "free(t: trajectory)",
        "free(t: trajectory refined)",
        (23, 14),
        "only action parameters can be 'refined'",
        None,
    ),
    "field given twice": (
        "pre:  near(o), hand_empty",
        "pre:  near(o)\n        pre: hand_empty",
        (36, 14),
        "'pre:' appears twice in this action",
        None,
    ),
}

SYNTAX = {
    "missing comma": (
        "pre:  near(o), hand_empty",
        "pre:  near(o) hand_empty",
        (35, 23),
        "unexpected 'hand_empty'; expected ',', '}', 'cost', 'duration', 'post', 'pre' or 'where'",
        "is a ',' missing before it?",
    ),
    "misspelt keyword": (
        "    predicates {",
        "    predicate {",
        (18, 5),
        "unexpected 'predicate'; expected '}', 'action', 'constants', 'predicates' or 'types'",
        "did you mean 'predicates'?",
    ),
    "stray character": (
        "duration: 2\n    }\n\n    action Place",
        "duration: 2 $\n    }\n\n    action Place",
        (37, 21),
        "unexpected character '$'; expected '}', 'cost', 'duration', 'post', 'pre' or 'where'",
        None,
    ),
    "missing closing brace": (
        "    goal {\n        on(cube, goal)\n    }\n}",
        "    goal {\n        on(cube, goal)\n    }",
        (61, 6),
        "the file ends too early; expected '}', 'goal', 'init' or 'objects'",
        None,
    ),
    "missing parenthesis": (
        "holding(o: object)",
        "holding(o: object",
        (21, 9),
        "unexpected 'hand_empty'; expected ')', ',' or 'refined'",
        "is a ',' or ')' missing before it?",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES) + sorted(SYNTAX))
def test_mistake_is_reported_where_it_is(case: str) -> None:
    old, new, (line, column), message, hint = {**CASES, **SYNTAX}[case]
    assert old in BASE
    with pytest.raises(InputError) as caught:
        parse_bt(BASE.replace(old, new, 1), "pp.bt")
    error = caught.value
    assert error.message == message
    assert error.hint == hint
    assert error.span is not None and (error.span.line, error.span.column) == (line, column)
    assert error.source_line == BASE.replace(old, new, 1).split("\n")[line - 1]


def test_the_unchanged_example_is_accepted() -> None:
    assert parse_bt(BASE, "pp.bt").domain is not None


def test_two_domains_in_one_file_are_refused() -> None:
    with pytest.raises(InputError) as caught:
        parse_bt("domain a { }\ndomain b { }\n", "two.bt")
    assert caught.value.message == "a file holds at most one domain"
    assert caught.value.span is not None and caught.value.span.line == 2


def test_every_mistake_is_reported_in_one_pass() -> None:
    text = (
        BASE.replace("pre:   free(t)", "pre:   fre(t)")
        .replace("post: holding(o), not hand_empty", "post: holding(x), not hand_empty")
        .replace("holding(o: object)", "holding(o: objet)")
        .replace("on(cube, goal)\n", "on(cub, goal)\n")
    )
    with pytest.raises(InputErrors) as caught:
        parse_bt(text, "pp.bt")
    found = [(e.span.line, e.message) for e in caught.value.errors if e.span]
    assert found == [
        (20, "unknown type 'objet'"),
        (29, "unknown predicate 'fre'"),
        (36, "unbound variable 'x' in a postcondition of Pick"),
        (60, "unknown object 'cub' in a goal"),
    ]
    assert caught.value.message == "unknown type 'objet'"  # shown alone, it is the first


def test_mistakes_in_several_files_are_all_reported(tmp_path: Path) -> None:
    one, two = tmp_path / "one.bt", tmp_path / "two.bt"
    one.write_text(BASE.replace("pre:   free(t)", "pre:   fre(t)"))
    two.write_text(BASE.replace("duration: 3", "duration: 3 ]"))
    with pytest.raises(InputErrors) as caught:
        collect([str(one), str(two)])
    assert [str(e.span) for e in caught.value.errors] == [f"{one}:29:16", f"{two}:31:21"]


def test_an_unknown_type_is_reported_once() -> None:
    text = BASE.replace("cube : object", "cube : objct")
    with pytest.raises(InputError) as caught:
        parse_bt(text, "pp.bt")
    assert not isinstance(caught.value, InputErrors)
    assert caught.value.message == "unknown type 'objct'"
    assert caught.value.hint == "did you mean 'object'?"


UNREACHABLE = """
domain d {
    predicates { p  q(x: object) }
    action A(x: object) { pre: q(x) post: not q(x) }
}
problem pr for d {
    objects { a }
    init { q(a) }
    goal { p, not q(a) }
}
"""


def test_goals_no_action_can_reach_are_warned_about(tmp_path: Path) -> None:
    path = tmp_path / "unreachable.bt"
    path.write_text(UNREACHABLE)
    collection = collect([str(path)])
    assert collection.problems[0].name == "pr"  # legal input: a warning, not an error
    (remark,) = collection.warnings
    assert remark.message == "the goal 'p' can never hold"
    assert remark.hint == "no action changes 'p', and it is false initially"
    assert remark.span is not None and (remark.span.line, remark.span.column) == (9, 12)
