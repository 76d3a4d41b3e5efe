"""Hypothesis strategies that damage sgplan's input formats.

Each strategy draws a damaged version of a valid text (or bytes, or JSON value): truncation, a value
replaced by one of the wrong type or range (huge and negative numbers, NaN and infinities, strings,
lists, deep nesting), YAML anchors and alias bombs, duplicate keys, wrong encodings.
"""

from __future__ import annotations

import json
import re
from typing import Any

from hypothesis import strategies as st

DEEP = 100_000
"""Nesting depth of the "deep" values: far beyond any parser's recursion limit."""

BAD_SCALARS = st.sampled_from([
    "-1", "0", "1e308", "-1e308", "1e999", ".nan", ".inf", "-.inf", "NaN", "99999999999999999999999999",
    "-99999999999", "1000", "100000", "''", "'x'", "null", "true", "[]", "{}", "[1, 2]", "[[[[1]]]]",
    "'" + "x" * 5000 + "'", "!!binary aGVsbG8=", "!!python/object:os.system x", "2001-12-14",
    "0x7fffffff", "1_000_000_000_000", "~",
])
"""YAML scalars (as written in a file) of the wrong type or range for some field."""

ANCHOR_BOMB = (
    "&a [x, x, x, x, x, x, x, x, x]\nb0: &b [*a, *a, *a, *a, *a, *a, *a, *a, *a]\n"
    "b1: &c [*b, *b, *b, *b, *b, *b, *b, *b, *b]\nb2: &d [*c, *c, *c, *c, *c, *c, *c, *c, *c]\n"
    "b3: &e [*d, *d, *d, *d, *d, *d, *d, *d, *d]\nb4: &f [*e, *e, *e, *e, *e, *e, *e, *e, *e]\n"
    "b5: &g [*f, *f, *f, *f, *f, *f, *f, *f, *f]\nb6: &h [*g, *g, *g, *g, *g, *g, *g, *g, *g]\n"
    "b7: &i [*h, *h, *h, *h, *h, *h, *h, *h, *h]\n"
)
"""Nine levels of nine aliases: 9^9 (387 M) list items once expanded."""


def _value_lines(text: str) -> list[int]:
    return [i for i, line in enumerate(text.splitlines()) if re.match(r"^\s*(- )?[\w\"']+\s*:\s*\S", line)]


@st.composite
def damaged_yaml(draw: st.DrawFn, text: str) -> bytes:
    """A damaged copy of the YAML document ``text``."""
    lines = text.splitlines()
    kind = draw(st.sampled_from(["truncate", "value", "value", "bomb", "deep", "duplicate", "encoding",
                                 "garbage", "flow-deep"]))
    if kind == "truncate":
        cut = draw(st.integers(0, max(0, len(text) - 1)))
        return text[:cut].encode()
    targets = _value_lines(text) or [0]
    index = draw(st.sampled_from(targets))
    line = lines[index]
    head = line[: line.index(":") + 1] if ":" in line else line
    if kind == "value":
        lines[index] = f"{head} {draw(BAD_SCALARS)}"
    elif kind == "bomb":
        # The bomb's anchor goes on the field; its expansion comes back through the last alias.
        lines[index] = f"{head} *i"
        return (
            "bombs:\n  a: " + ANCHOR_BOMB.replace("\n", "\n  ").rstrip() + "\n" + "\n".join(lines)
        ).encode()
    elif kind == "deep":
        depth = draw(st.sampled_from([70, 300, DEEP]))
        lines[index] = f"{head} " + "[" * depth + "1" + "]" * depth
    elif kind == "flow-deep":
        depth = draw(st.sampled_from([70, 5000]))
        return (
            ("- " * depth + "x\n").encode()
            if draw(st.booleans())
            else ("{a: " * depth + "1" + "}" * depth).encode()
        )
    elif kind == "duplicate":
        lines.insert(index + 1, line)
    elif kind == "encoding":
        encoding = draw(st.sampled_from(["utf-16", "latin-1-bytes", "nul"]))
        if encoding == "utf-16":
            return text.encode("utf-16")
        if encoding == "nul":
            return text.encode()[: len(text) // 2] + b"\x00\xff\xfe" + text.encode()[len(text) // 2:]
        lines[index] = head + " caf\xe9"
        return "\n".join(lines).encode("latin-1", "replace")
    else:
        junk = draw(st.binary(min_size=1, max_size=64))
        return "\n".join(lines).encode() + b"\n" + junk
    return ("\n".join(lines) + "\n").encode()


BAD_JSON_VALUES = st.one_of(
    st.sampled_from([None, True, -1, 0, 10**30, -(10**30), 1e308, "", "x" * 5000, [], {}, [[[1]]], {"a": 1}]),
    st.integers(), st.floats(allow_nan=False), st.text(max_size=20),
    st.lists(st.integers(), max_size=4),
)


def _paths(value: Any, prefix: tuple = ()) -> list[tuple]:
    out = [prefix]
    if isinstance(value, dict):
        for key, item in value.items():
            out += _paths(item, (*prefix, key))
    elif isinstance(value, list):
        for k, item in enumerate(value[:3]):
            out += _paths(item, (*prefix, k))
    return out


@st.composite
def damaged_json(draw: st.DrawFn, document: Any) -> bytes:
    """A damaged copy of the JSON ``document``: a value replaced, a key dropped, NaN, depth, truncation."""
    text = json.dumps(document)
    kind = draw(st.sampled_from(["value", "value", "drop", "special", "deep", "truncate", "encoding"]))
    if kind == "truncate":
        return text[: draw(st.integers(0, max(0, len(text) - 1)))].encode()
    if kind == "encoding":
        return text.encode("utf-16")
    paths = [p for p in _paths(document) if p]
    path = draw(st.sampled_from(paths))
    copy = json.loads(text)
    parent = copy
    for step in path[:-1]:
        parent = parent[step]
    marker = "__SGPLAN_FAULT__"
    if kind == "drop" and isinstance(parent, dict):
        del parent[path[-1]]
        return json.dumps(copy).encode()
    if kind == "value":
        parent[path[-1]] = draw(BAD_JSON_VALUES)
        return json.dumps(copy).encode()
    parent[path[-1]] = marker
    if kind == "special":
        raw = draw(st.sampled_from(["NaN", "Infinity", "-Infinity", "1e999", "-1e999", "1" * 400]))
    else:
        depth = draw(st.sampled_from([70, DEEP]))
        raw = "[" * depth + "]" * depth
    return json.dumps(copy).replace(json.dumps(marker), raw).encode()


@st.composite
def damaged_hoa(draw: st.DrawFn, text: str) -> bytes:
    """A damaged copy of the HOA automaton ``text``."""
    kind = draw(st.sampled_from(["truncate", "number", "aps", "states", "label", "token", "encoding"]))
    if kind == "truncate":
        return text[: draw(st.integers(0, max(0, len(text) - 1)))].encode()
    if kind == "encoding":
        return text.encode("utf-16")
    if kind == "aps":
        count = draw(st.sampled_from([21, 40, 64, 1000]))
        names = " ".join(f'"p{k}"' for k in range(count))
        return re.sub(r"^AP:.*$", f"AP: {count} {names}", text, flags=re.MULTILINE).encode()
    if kind == "states":
        count = draw(st.sampled_from([0, 5_000_000, 10**12]))
        return re.sub(r"^States:.*$", f"States: {count}", text, flags=re.MULTILINE).encode()
    if kind == "label":
        depth = draw(st.sampled_from([50, 5000]))
        label = draw(st.sampled_from(["!" * depth + "0", "(" * depth + "0" + ")" * depth]))
        return re.sub(r"\[[^\]]*\]", f"[{label}]", text, count=1).encode()
    numbers = [m.span() for m in re.finditer(r"\d+", text)]
    if kind == "number" and numbers:
        start, end = draw(st.sampled_from(numbers))
        value = draw(st.sampled_from(["99999999", "18446744073709551616", "-1", "0", "1" * 50]))
        return (text[:start] + value + text[end:]).encode()
    tokens = text.split()
    position = draw(st.integers(0, len(tokens) - 1))
    del tokens[position]
    return " ".join(tokens).encode()


OPERATOR_TOKENS = ["NOT", "AND", "OR", "IMPLY", "EQUAL", "NEXT", "UNTIL", "EVENTUALLY", "ALWAYS"]


@st.composite
def token_lists(draw: st.DrawFn, actions: list[str]) -> str:
    """A token-list formula text: random token soup, long chains, flat junctions, or a damaged repr."""
    kind = draw(st.sampled_from(["soup", "chain", "flat", "repr"]))
    if kind == "soup":
        tokens = draw(
            st.lists(
                st.sampled_from(OPERATOR_TOKENS + actions + ["enter(room_999999999999)", "x", ""]),
                min_size=0, max_size=30,
            )
        )
    elif kind == "chain":
        operator = draw(st.sampled_from(["NOT", "NEXT", "EVENTUALLY", "ALWAYS"]))
        tokens = [operator] * draw(st.sampled_from([99, 1000, 8000])) + [draw(st.sampled_from(actions))]
    elif kind == "flat":
        junction = draw(st.sampled_from(["AND", "OR"]))
        terms = draw(st.integers(2, 600))
        tokens = [junction] * (terms - 1) + [actions[k % len(actions)] for k in range(terms)]
    else:
        text = repr(draw(st.lists(st.sampled_from(OPERATOR_TOKENS + actions), min_size=1, max_size=8)))
        return text[: draw(st.integers(0, len(text)))] + draw(st.sampled_from(["", "]", "[[", "'", "\\x00"]))
    return repr(tokens)
