"""Tokens of a mission text, with their character spans, split into sentences.

Text is lower-cased; contractions are expanded (``don't`` -> ``do not``), a possessive ``'s`` becomes
its own token, parentheses and dashes between words (an em or en dash, ``--``, a spaced ``-``) become commas
(an aside), and list markers (``1)``, ``(2)``, ``3.`` at the start of an item) end a sentence like ``.``,
``;``, ``!``, ``?`` and ``:`` do. Entity IDs (``room_2``,
``object_27``) stay single tokens, so already-grounded text is understood too.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from sgplan.llm.offline.lexicon import BARE_NEGATED, NEGATED_STEMS, SENTENCE_END

_WORD = re.compile(r"(?:room|object)_\d+|\d+(?:st|nd|rd|th)?|[a-z]+(?:'[a-z]+)?|'s\b|[,.;:!?()]"
                   r"|[\u2014\u2013]|--|(?<=\s)-(?=\s)")
_DASH = "\u2014"
"""An aside's dash, whatever dash was typed."""


@dataclass(frozen=True)
class Tok:
    """One word (lower case) and the character span ``[start, end)`` it came from."""

    text: str
    start: int
    end: int


def tokenize(text: str) -> list[Tok]:
    """Words and punctuation of ``text`` with contractions expanded (see the module docstring)."""
    out: list[Tok] = []
    lowered = text.lower().replace("\u2019", "'")
    for m in _WORD.finditer(lowered):
        word, start, end = m.group(0), m.start(), m.end()
        if word in BARE_NEGATED:  # "dont", "cant": typed without the apostrophe
            out += [Tok(BARE_NEGATED[word], start, end), Tok("not", start, end)]
        elif word.endswith("n't"):
            stem = word[:-3]
            out += [Tok(NEGATED_STEMS.get(stem + "n", stem), start, end), Tok("not", start, end)]
        elif word in ("\u2013", "--", "-"):
            out.append(Tok(_DASH, start, end))
        elif word.endswith("'s") and len(word) > 2:
            out += [Tok(word[:-2], start, end - 2), Tok("'s", end - 2, end)]
        elif "'" in word:
            out.append(Tok(word.split("'")[0], start, end))  # you're, we'll: the suffix adds nothing
        else:
            out.append(Tok(word, start, end))
    return out


def sentences(tokens: list[Tok]) -> list[list[Tok]]:
    """Split at sentence punctuation and list markers (a sentence ending with a colon keeps it, and the
    items of a list marked after a colon, *three stops: 1) A 2) B 3) C*, are one sentence joined by commas);
    empty sentences are dropped."""
    parts: list[list[Tok]] = [[]]
    after_colon = False
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        nxt = tokens[i + 1].text if i + 1 < len(tokens) else ""
        at_item_start = not parts[-1] or parts[-1][-1].text == "("
        if tok.text in SENTENCE_END:
            if tok.text == ":":  # kept: what comes before a colon may announce the list after it
                parts[-1].append(tok)
            after_colon = tok.text == ":"
            parts.append([])
        elif (tok.text.isdigit() and nxt == ")") or (tok.text.isdigit() and nxt == "." and at_item_start):
            if parts[-1] and parts[-1][-1].text == "(":
                parts[-1].pop()
            if after_colon and parts[-1]:
                parts[-1].append(Tok(",", tok.start, tok.end))
            elif not after_colon:
                parts.append([])
            i += 1  # the ')' or '.'
        elif tok.text == _DASH or (tok.text in ("(", ")") and not (i + 1 < len(tokens)
                                                                   and tokens[i + 1].text.isdigit())):
            # an aside in parentheses or dashes reads like one between commas: "the fridge (any order), ..."
            if parts[-1] and parts[-1][-1].text != "," and nxt not in (",", ""):
                parts[-1].append(Tok(",", tok.start, tok.end))
        else:
            parts[-1].append(tok)
        i += 1
    return [p for p in parts if p]


def rewrite(tokens: list[Tok], aliases: dict[tuple[str, ...], tuple[str, ...]]) -> list[Tok]:
    """``tokens`` with every phrase of ``aliases`` (longest first, left to right) replaced by its reading;
    each new token spans the whole phrase it replaces, so messages still quote the user's words."""
    longest = max((len(k) for k in aliases), default=0)
    out: list[Tok] = []
    i = 0
    while i < len(tokens):
        for n in range(min(longest, len(tokens) - i), 0, -1):
            reading = aliases.get(tuple(t.text for t in tokens[i : i + n]))
            if reading is not None:
                start, end = tokens[i].start, tokens[i + n - 1].end
                out += [Tok(w, start, end) for w in reading]
                i += n
                break
        else:
            out.append(tokens[i])
            i += 1
    return out
