"""Untrusted XML: no entities, no external files, bounded size and depth, never a traceback."""

from __future__ import annotations

import random

import pytest

from btplan.bt.formats import load_tree
from btplan.bt.formats.xmlparse import MAX_DEPTH, parse_xml
from btplan.errors import EXCERPT_WIDTH, InputError

LAUGHS = ('<?xml version="1.0"?>\n<!DOCTYPE lolz [<!ENTITY lol "lol">'
          '<!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">]>\n'
          '<root BTCPP_format="4"><BehaviorTree ID="M"><AlwaysSuccess name="&lol2;"/>'
          '</BehaviorTree></root>')
EXTERNAL = ('<!DOCTYPE root [<!ENTITY secret SYSTEM "file:///etc/hostname">]>\n'
            '<root BTCPP_format="4"><BehaviorTree ID="M"><AlwaysSuccess name="&secret;"/>'
            '</BehaviorTree></root>')


@pytest.mark.parametrize("text", [LAUGHS, EXTERNAL])
def test_entities_are_refused_with_a_location(text: str) -> None:
    with pytest.raises(InputError, match="DOCTYPE is not allowed") as info:
        load_tree(text, "xml", "evil.xml")
    assert info.value.span is not None and info.value.span.path == "evil.xml"


def test_an_undeclared_entity_is_a_syntax_error() -> None:
    with pytest.raises(InputError, match="undefined entity"):
        parse_xml("<root>&x;</root>", "t.xml")


def test_nesting_deeper_than_the_limit_is_refused() -> None:
    text = "<a>" * (MAX_DEPTH + 5) + "</a>" * (MAX_DEPTH + 5)
    with pytest.raises(InputError, match=f"nested more than {MAX_DEPTH} deep") as info:
        parse_xml(text, "deep.xml")
    assert info.value.span is not None and info.value.span.line == 1


def test_a_long_line_is_shown_as_a_short_window_around_the_caret() -> None:
    text = '<root BTCPP_format="4">' + '<a x="1"/>' * 2000 + '<b></c></root>'
    with pytest.raises(InputError) as info:
        parse_xml(text, "long.xml")
    excerpt = info.value.excerpt()
    assert excerpt is not None
    shown, caret = excerpt
    assert len(shown) <= EXCERPT_WIDTH + 6 and shown[caret - 2:caret + 2] == "</c>"


@pytest.mark.parametrize("seed", range(30))
def test_random_bytes_never_escape_as_anything_but_input_errors(seed: int) -> None:
    rng = random.Random(seed)
    pieces = ["<", ">", "/", "<root", '<root BTCPP_format="4">', "<BehaviorTree ID='M'>",
              "</BehaviorTree>", "</root>", "<include path='x.xml'/>", "&", "&amp;", "\"",
              "<SubTree ID='M'/>", "<Sequence>", "</Sequence>", "<Script code='x:=1'/>",
              "\ud800", "\x00", "é", "<!--", "-->", "<![CDATA[", "]]>", " ", "\n"]
    text = "".join(rng.choice(pieces) for _ in range(rng.randint(0, 40)))
    try:
        load_tree(text, "xml", "fuzz.xml")
    except InputError:
        pass


@pytest.mark.parametrize(("code", "message"), [
    ("x := " + "9" * 5000, "too long"), ("x := 0x" + "f" * 40, "64 bits"),
    ("x := " + "(" * 3000, "nested too deeply")])
def test_hostile_scripts_are_refused_when_read(code: str, message: str) -> None:
    text = ('<root BTCPP_format="4"><BehaviorTree ID="T">'
            f'<Script code="{code}"/></BehaviorTree></root>')
    with pytest.raises(InputError, match=message):
        load_tree(text, "xml", "s.xml")
