"""How syntax rules read a sentence: an immutable view of its words, and what a rule returns.

A rule is a function ``rule(r, i, ...) -> Match | Refusal | None`` reading the sentence ``r`` from token
``i``: a :class:`Match` holds the node it built and the index after its last token, ``None`` says the rule
does not apply here (nothing was consumed, since nothing is ever consumed: positions are values), and a
:class:`Refusal` says the words are the rule's but cannot be read, and why. No rule raises: a caller
that can try something else on ``None`` or a refusal does; one that cannot passes the refusal up.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Generic, Literal, TypeVar

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.nouns import Head, NounLexicon
from sgplan.llm.offline.phrases import Phrases
from sgplan.llm.offline.spelling import Spelling
from sgplan.llm.offline.syntax.tree import Announced, Span
from sgplan.llm.offline.text import Tok, is_clock_time

N = TypeVar("N", covariant=True)


@dataclass(frozen=True)
class Match(Generic[N]):
    """A rule's node and the index of the first token after it."""

    node: N
    end: int


@dataclass(frozen=True)
class Refusal:
    """Words a rule owns but cannot read: the refusal's message (:mod:`.refusals`)."""

    message: str


Parse = Match[N] | Refusal | None


@dataclass(frozen=True)
class Reader:
    """One sentence's tokens, the mission text they come from and the scene's head nouns.

    ``choices`` decides the attachments the words leave open (token index -> read as a description, see
    :class:`.tree.Attachment`); an attachment not in it is read as a description.
    """

    toks: tuple[Tok, ...]
    text: str
    nouns: NounLexicon
    choices: Mapping[int, bool] = field(default_factory=dict)
    announced: Announced | None = None
    """What a colon before this sentence announced of its list (:mod:`.lists`)."""
    marker: Literal["number", "bullet"] | None = None
    """The list marker the sentence started with (:class:`~sgplan.llm.offline.text.Part`)."""
    new_line: bool = False
    """The sentence starts a line of the text."""
    after_item: bool = False
    """An item of an ordered list after its first one (:mod:`.lists`)."""
    aside: bool = False
    """Words set aside unread (a list's heading): said back, not parsed (:mod:`.lists`)."""
    spelling: Spelling | None = None
    """The words the scene's missions use: an unknown word that looks like a noun is no verb."""
    words: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "words", tuple(t.text for t in self.toks))

    def __len__(self) -> int:
        return len(self.toks)

    def word(self, i: int) -> str:
        """The word at ``i``, or ``""`` outside the sentence."""
        return self.words[i] if 0 <= i < len(self.words) else ""

    def at(self, i: int, *seq: str) -> bool:
        """Whether the words from ``i`` are ``seq``."""
        return all(self.word(i + n) == w for n, w in enumerate(seq))

    def phrase(self, i: int, table: Phrases) -> tuple[str, ...] | None:
        """The longest phrase of ``table`` at ``i``."""
        return table.longest_at(self.words, i)

    def says(self, table: Phrases, start: int, end: int) -> bool:
        """Whether a phrase of ``table`` lies within the tokens ``[start, end)``."""
        return any(self.at(j, *p) for j in range(start, end) for p in table if j + len(p) <= end)

    def trailing_after(self, i: int) -> int:
        """The length of *after / afterwards / after that* at ``i`` closing a clause (before a comma or the
        end), with a *too* / *also* / *as well* after it (*Check X afterwards too.*), else 0."""
        said = self.phrase(i, lx.TRAILING_AFTER)
        if not said:
            return 0
        end = i + len(said)
        end += len(self.phrase(end, lx.TOO) or ())
        if self.word(i - 1) == "and" and self.word(end) == "," and end + 1 < len(self.toks):
            return 0  # "A, and afterwards, (while you're upstairs,) B": it opens B's clause
        return end - i if self.word(end) in ("", ",") else 0

    def head(self, i: int) -> Head | None:
        """The head noun starting at ``i``."""
        return self.nouns.match(self.words, i)

    def head_before(self, k: int) -> Head | None:
        """The head noun that ends right before the token ``k`` (of up to three words), if any."""
        return next((h for j in range(max(0, k - 3), k)
                     if (h := self.head(j)) is not None and j + h.words == k), None)

    def span(self, i: int, j: int) -> Span:
        """The characters of the tokens ``[i, j)`` (of all of them, when words were moved: :meth:`quote`)."""
        said = self.toks[i:j]
        return Span(min(t.start for t in said), max(t.end for t in said))

    def quote(self, i: int, j: int) -> str:
        """The mission text of the tokens ``[i, j)`` (from the first character of any of them to the last:
        words moved before others, *Only after that, go ...* for *Go ... only after that*, are quoted
        whole)."""
        if j <= i:
            return ""
        said = self.toks[i:j]
        return self.text[min(t.start for t in said) : max(t.end for t in said)]

    def rest(self, i: int) -> str:
        """The words from ``i`` (at most six), quoted, or "the end of the sentence"."""
        if i >= len(self.toks):
            return "the end of the sentence"
        return f"'{self.quote(i, min(i + 6, len(self.toks)))}'"

    def np_starts(self, i: int) -> bool:
        """Whether a noun phrase may start at ``i`` (a determiner, a head noun, an ID, a pronoun ...)."""
        w, nxt = self.word(i), self.word(i + 1)
        if not w:
            return False
        if w.startswith(("room_", "object_")) or w in lx.PRONOUNS:
            return w != "it" or nxt not in ("is", "was")
        if nxt == "'s" and self.head(i) is None and self.head(i + 2) is not None:
            return True  # "Lily's teddy bear": someone's thing (read or refused in the phrase)
        if w == "there":  # "get there": the last place named as a goal
            return nxt not in lx.STATEMENT_LINKS
        if w in lx.DETERMINERS:
            return (not (w == "some" and nxt == "point") and not (w == "that" and nxt == "order")
                    and self.phrase(i, lx.WHENEVER) is None)  # "every time you ...": a condition
        if w in lx.FLOOR_WORDS and (nxt.isdigit() or nxt in lx.NUMBER_WORDS or nxt == "zero"):
            return True  # "floor 2" as a place
        if w in lx.FLOOR_NAMES and nxt in lx.FLOOR_WORDS and self.head(i + 2) is not None:
            return True  # "top floor bathroom", "ground-floor bathroom" (notes leave the article out)
        if w in lx.RELATIVE_FLOORS and (room := self.head(i + 1)) is not None and room.kind == "room" \
                and not room.plural:  # not "Upstairs bedrooms: - the one with ...": the kind of a list
            return True  # "upstairs bath: sink + bottle" (the article left out, as notes do)
        if w in lx.FLOOR_ENDS_ALONE and (room := self.head(i + 1)) is not None and room.kind == "room" \
                and not room.plural:
            return True  # "avoid top bath": the bathroom on the top floor, the article left out
        if w == "whichever" and self.head(i + 1) is not None:
            return True  # "then whichever bedroom": any of them ("whichever first" is an order remark)
        if w == "other" and self.head(i + 1) is not None:
            return True  # "-> other bdrm": the other bedroom, the article left out as notes do
        if self.nouns.room_modifier(self.words, i) is not None:
            return True  # "dining chair, either": the chair in the dining room, the article left out
        if w in lx.NUMBER_WORDS or w.isdigit():
            if nxt in lx.FLOOR_PLURALS and self.word(i + 2) in lx.FLOOR_DIRECTIONS:
                return False  # "two floors up": where, not what
            return w != "one" or nxt == "of" or self.head(i + 1) is not None
        return self.head(i) is not None or self.descriptive_end(i) > i

    def descriptive_end(self, i: int) -> int:
        """Where the descriptive words at ``i`` end (*the big comfy couch*) when a noun follows them, else
        ``i`` (:data:`.lexicon.DESCRIPTIVE`, not words of the scene's categories)."""
        j = i
        while (self.word(j) in lx.DESCRIPTIVE and not self.nouns.names_word(self.word(j))
               and self.head(j) is None):  # "the front room" is a name, not a description
            j += 1
        noun = (self.head(j) is not None or self.word(j) in lx.ANAPHORIC_ONE
                or self.word(j) in lx.RELATIVE_FLOORS or self.nouns.room_modifier(self.words, j) is not None)
        return j if noun else i

    def skip(self, i: int, words: Sequence[str] | frozenset[str]) -> int:
        """The first index from ``i`` whose word is not one of ``words``."""
        while self.word(i) and self.word(i) in words:
            i += 1
        return i

    def with_commas(self, cuts: Sequence[int]) -> Reader:
        """This sentence with a comma inserted before each token index of ``cuts`` (a pause that typing or
        dictation left out), at no width in the text."""
        toks = list(self.toks)
        for k in sorted(set(cuts), reverse=True):
            toks.insert(k, Tok(",", toks[k - 1].end, toks[k - 1].end))
        return replace(self, toks=tuple(toks)) if cuts else self

    def decided(self, at: int) -> bool | None:
        """How the attachment at token ``at`` is read (:attr:`choices`), ``None`` if not decided yet."""
        return self.choices.get(at)


def unreadable(r: Reader, i: int) -> Refusal:
    """The refusal of the word at ``i`` where it cannot be read: a clock time (*at 6 pm*), a symbol (*A / B*),
    a word of the grammar out of place."""
    w = r.word(i)
    if is_clock_time(w):
        before = i - 1 if r.word(i - 1) in lx.CLOCK_PREPOSITIONS else i
        return Refusal(rf.clock_time(r.quote(before, i + 1)))
    if not w[:1].isalnum():
        return Refusal(rf.symbol(w, r.rest(max(i - 1, 0))))
    return Refusal(rf.cannot_understand_word(w, r.rest(i)))
