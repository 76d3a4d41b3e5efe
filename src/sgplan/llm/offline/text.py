"""Tokens of a mission text, with their character spans, split into sentences and list items.

Text is lower-cased; contractions are expanded (``don't`` -> ``do not``, ``we're`` -> ``we are``; ``'d``
after a word that is no subject writes a past participle in a note: ``chk'd`` -> ``checked``), a
possessive ``'s`` becomes its own token (``'s`` after *that*, *there*, *here* ... is *is*), parentheses and
dashes between words (an em or en dash, ``--``, a spaced ``-``, a ``-`` right after a word that breaks it
off: *the- the office*) become commas (an aside). Entity IDs (``room_2``, ``object_27``) stay single tokens,
so already-grounded text is understood too.

Notations are read as the words they stand for (:data:`.lexicon.SYMBOLS`): an arrow (``->``, ``>``, ``→``)
is *then*, ``+`` and ``&`` are *and*, ``w/`` is *with*, ``b/c`` *because*, ``b4`` *before*; a clock time
(``6 pm``, ``18:30``) is one token. Any other symbol is kept as a token of its own, so that the grammar
refuses it by name: nothing typed is ever dropped unread, except quotation marks, the hyphen inside a word
(*ground-floor*) and Markdown's bold marks (``**never**``), which change nothing. An ellipsis (``...``,
``…``) ends a sentence, except before a word in lower case, where it is a pause, read as a dash (*the clock
in the living room... no wait, the one ...*).

A sentence ends at ``.``, ``;``, ``!``, ``?``, ``:`` and at a line break; a list item (a line or a
sentence starting with ``1.``, ``2)``, ``(3)``, or a bullet ``-``, ``*``, ``•`` or an empty box ``[ ]``, ``☐``
at the start of a line)
starts one, and says which kind of list it belongs to (:class:`Part`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Literal

from sgplan.llm.offline.lexicon import (
    BARE_CONTRACTIONS,
    BARE_NEGATED,
    CONTRACTIONS,
    IS_CONTRACTED,
    LINE_CONTINUES,
    NEGATED_STEMS,
    NUMBERED,
    PHRASE_ALIASES,
    POSITIVE_VERBS,
    PRONOUNS,
    SENTENCE_END,
    SYMBOLS,
    WOULD_SUBJECTS,
)

_WORD = re.compile(
    r"(?P<id>(?:room|object)_\d+)"
    r"|(?P<clock>(?:[01]?\d|2[0-3])(?::[0-5]\d(?:\s?[ap]\.?m\b\.?)?|\s?[ap]\.?m\b\.?))"  # 6 pm, 18:30
    r"|(?P<times>\d+x\b|\bx\d+\b)"  # 2x / x2: that many times
    r"|(?P<number>\d+(?:st|nd|rd|th)?)"
    r"|(?P<with>w/o\b|w/|b/c\b|\bb4\b)"
    r"|(?P<word>[a-z]+(?:'[a-z]+)?|'s\b)"
    r"|(?P<bullet>^[ \t]*(?:[-*\u2022\u00b7\u2023\u25e6\u25aa]|\[ ?\]|\u2610)(?=[ \t]))"  # at a line start
    r"|(?P<ticked>\[[x\u2713\u2714]\])"  # a ticked box: one token, refused (done already, or a task?)
    r"|(?P<arrow>-+>|=+>|>+|[\u2192\u21d2\u27f6\u2794\u279c\u27a1])"
    r"|(?P<ellipsis>\u2026|\.{2,})"
    r"|(?P<punct>[,.;:!?()\[\]{}])|(?P<dash>[\u2014\u2013]|--|(?<=\s)-(?=\s)|(?<=\w)-(?=\s))"
    r"|(?P<newline>\n)"
    r"|(?P<silent>(?<=\w)-(?=\w)|[\"'`\u201c\u201d\u2018]"  # a hyphen inside a word, quotation marks,
    r"|\*\*|__)"  # Markdown's bold marks
    r"|(?P<symbol>[^\s\w])",  # any other symbol: a token of its own, refused by the grammar
    re.M,
)
_DASH = "\u2014"
"""An aside's dash, whatever dash was typed."""
BULLET = "\u2022"
"""The token of a bullet starting a list item, whatever bullet was typed."""
LINE_BREAK = "\n"
_BRACKETS = {"[": "(", "{": "(", "]": ")", "}": ")"}


@dataclass(frozen=True)
class Tok:
    """One word (lower case) and the character span ``[start, end)`` it came from."""

    text: str
    start: int
    end: int


@dataclass(frozen=True)
class Part:
    """The tokens of one sentence; ``marker``: the list marker it started with (``"number"``: *1.*, *2)*;
    ``"bullet"``: *-*, *•*), if any; ``new_line``: it starts a line of the text (a heading or an item may
    be a line without punctuation)."""

    toks: tuple[Tok, ...]
    marker: Literal["number", "bullet"] | None = None
    new_line: bool = False


def is_clock_time(word: str) -> bool:
    """Whether a token is a clock time (*6pm*, *18:30*)."""
    return any(c.isdigit() for c in word) and (":" in word or word.rstrip(".").endswith(("am", "pm", "a.m",
                                                                                          "p.m")))


def past_participle(stem: str) -> str:
    """The past participle a note writes as ``stem'd`` (*chk'd* is *checked*, *clean'd* *cleaned*): the word
    the stem stands for (:data:`.lexicon.PHRASE_ALIASES`), or the stem, with *-ed*."""
    said = PHRASE_ALIASES.get((stem,), (stem,))
    verb = said[0] if len(said) == 1 else stem
    return verb + ("d" if verb.endswith("e") else "ed")


def tokenize(text: str) -> list[Tok]:
    """Words and punctuation of ``text`` with contractions expanded and notations read (see the module
    docstring)."""
    out: list[Tok] = []
    lowered = text.lower().replace("\u2019", "'")
    for m in _WORD.finditer(lowered):
        word, start, end, kind = m.group(0), m.start(), m.end(), m.lastgroup
        if kind == "silent":
            continue  # quotation marks, a hyphen inside a word: they change nothing
        if kind == "bullet":
            out.append(Tok(BULLET, end - 1, end))
        elif kind == "dash":
            out.append(Tok(_DASH, start, end))
        elif kind == "ellipsis":  # a pause before words that go on in lower case ("the kitchen... no wait,")
            out.append(Tok(_DASH if re.match(r"\s*[a-z]", text[end:]) else ".", start, end))
        elif kind == "punct" and word == "!" and _prefixes_a_word(lowered, start, end):
            out.append(Tok("avoid", start, end))  # an operator's "!kit": not the kitchen
        elif kind == "symbol" and word == "\u00ac":
            out.append(Tok("avoid", start, end))  # the logician's "¬LR", "¬ gnd flr bath": not there
        elif kind == "punct":
            out.append(Tok(_BRACKETS.get(word, word), start, end))
        elif kind == "clock":
            out.append(Tok(re.sub(r"\s", "", word), start, end))
        elif kind == "times":
            n = int(word.strip("x"))
            out += [Tok(w, start, end) for w in (("twice",) if n == 2 else (str(n), "times"))]
        elif kind in ("with", "arrow", "symbol") and (word in SYMBOLS or kind == "arrow"):
            out += [Tok(w, start, end) for w in SYMBOLS.get(word, ("then",))]
        elif word in BARE_NEGATED:  # "dont", "cant": typed without the apostrophe
            out += [Tok(BARE_NEGATED[word], start, end), Tok("not", start, end)]
        elif word in BARE_CONTRACTIONS:  # "youre", "thats"
            out += [Tok(w, start, end) for w in BARE_CONTRACTIONS[word]]
        elif word.endswith("n't"):
            stem = word[:-3]
            out += [Tok(NEGATED_STEMS.get(stem + "n", stem), start, end), Tok("not", start, end)]
        elif word.endswith("'s") and len(word) > 2:
            said = "is" if word[:-2] in IS_CONTRACTED else "'s"  # "that's", "there's": never a possessive
            out += [Tok(word[:-2], start, end - 2), Tok(said, end - 2, end)]
        elif word.endswith("'d") and word[:-2] not in WOULD_SUBJECTS:
            out.append(Tok(past_participle(word[:-2]), start, end))  # a note's "microwave chk'd": checked
        elif "'" in word and kind == "word":
            stem, suffix = word.split("'", 1)  # you're, we'll, I'd: the verb they stand for
            verb = [Tok(CONTRACTIONS[suffix], start, end)] if suffix in CONTRACTIONS else []
            out += [Tok(stem, start, end), *verb]
        else:
            out.append(Tok(word, start, end))
    return out


def _prefixes_a_word(text: str, start: int, end: int) -> bool:
    """Whether the ``!`` at ``start`` is written onto the word after it, with nothing before it but a space
    or a separator (``!kit``, ``lobby. !kit``): a negation, as in logic, not the end of a sentence."""
    before = text[start - 1] if start else " "
    return end < len(text) and text[end].isalpha() and (before.isspace() or before in ".,;:(")


def sentences(tokens: list[Tok]) -> list[Part]:
    """Split at sentence punctuation, line breaks and list markers (a sentence ending with a colon keeps it:
    what comes before a colon may announce the list after it); a line break inside a sentence that goes on
    (after a comma or *and*) joins the lines; empty sentences are dropped."""
    parts: list[Part] = []
    current: list[Tok] = []
    marker: Literal["number", "bullet"] | None = None
    new_line = True
    numbered = 0  # the number of the last numbered item, while the items run on one line

    def close() -> None:
        nonlocal current, marker, new_line
        if current:
            parts.append(Part(tuple(current), marker, new_line))
            current, marker, new_line = [], None, False

    i = 0
    while i < len(tokens):
        tok = tokens[i]
        nxt = tokens[i + 1].text if i + 1 < len(tokens) else ""
        at_item_start = not current or current[-1].text == "("
        if tok.text == LINE_BREAK:
            if not current or current[-1].text not in LINE_CONTINUES:
                close()
                new_line = True
        elif tok.text == "!" and not current and negating_mark(tokens, i):
            current.append(Tok("never", tok.start, tok.end))  # operators' "! lvg rm": "never lvg rm"
        elif tok.text in SENTENCE_END:
            if tok.text == ":":  # kept: what comes before a colon may announce the list after it
                current.append(tok)
            close()
        elif tok.text == "#" and not current and new_line:
            pass  # "## Office errand": a heading's marks (Markdown), not words
        elif tok.text == BULLET and not current:
            marker = "bullet"
        elif tok.text.isdigit() and (
                (nxt == ")" and not (current and current[-1].text in NUMBERED))
                or (nxt == "." and (at_item_start or next_inline_item(tok, current, marker, numbered)))):
            if current and current[-1].text == "(":
                current.pop()
            close()
            marker, numbered = "number", int(tok.text)
            i += 1  # the ')' or '.'
        elif tok.text in (_DASH, ")") or (tok.text == "(" and not nxt.isdigit()):
            # an aside in parentheses or dashes reads like one between commas: "the fridge (any order), ..."
            # ("(2) the oven": an item's number; "chair (any) 3) kit": the aside closed before one)
            if current and current[-1].text != "," and nxt not in (",", "", LINE_BREAK):
                current.append(Tok(",", tok.start, tok.end))
        else:
            current.append(tok)
        i += 1
    close()
    return parts


def negating_mark(tokens: list[Tok], i: int) -> bool:
    """Whether the ``!`` at ``i``, opening a sentence, is operators' *not* before a place (*sink. ! lvg rm*):
    a word follows that is no verb, and no ``!`` or ``?`` is right before it (*!! check the fridge*:
    emphasis)."""
    nxt = tokens[i + 1].text if i + 1 < len(tokens) else ""
    before = tokens[i - 1].text if i > 0 else ""
    return nxt.isalpha() and nxt not in POSITIVE_VERBS and before not in ("!", "?")


def next_inline_item(tok: Tok, current: list[Tok], marker: str | None, numbered: int) -> bool:
    """Whether *N.* inside the item being read is the next item's number on the same line (*1. check the
    oven 2. then the couch*): N follows the item's number, and no word before it takes a number (*floor
    2.*)."""
    return (marker == "number" and int(tok.text) == numbered + 1 and bool(current)
            and current[-1].text not in NUMBERED)


def rewrite(tokens: list[Tok], aliases: dict[tuple[str, ...], tuple[str, ...]]) -> list[Tok]:
    """``tokens`` with every phrase of ``aliases`` (longest first, left to right) replaced by its reading;
    each new token spans the whole phrase it replaces, so messages still quote the user's words, except a
    pronoun kept in its place (*set it down* read *put it down*: *it* is still the word *it*) and a comma,
    colon or question mark ending both the phrase and its reading, which keeps its own span."""
    longest = max((len(k) for k in aliases), default=0)
    out: list[Tok] = []
    i = 0
    while i < len(tokens):
        for n in range(min(longest, len(tokens) - i), 0, -1):
            reading = aliases.get(tuple(t.text for t in tokens[i : i + n]))
            if reading is None:
                continue
            # a mark read as typed keeps its own place ("Before bed, ...": 'Before bed')
            mark = n > 1 and reading[-1] in (",", ":", "?") and reading[-1] == tokens[i + n - 1].text
            start, end = tokens[i].start, tokens[i + n - 1 - mark].end
            kept = [k < n and w == tokens[i + k].text and w in PRONOUNS for k, w in enumerate(reading)]
            out += [tokens[i + k] if kept[k] else Tok(w, start, end)
                    for k, w in enumerate(reading[:len(reading) - mark])]
            out += [tokens[i + n - 1]] if mark else []
            i += n
            break
        else:
            out.append(tokens[i])
            i += 1
    return out

