"""The head nouns of one scene: which words name rooms and objects (not which rooms and objects they are).

A scene's room categories and object classes are the head nouns of its missions, read with ``_`` as a
space (``dining_room`` -> "dining room"), in the singular and the plural, and through the synonyms of
:data:`.lexicon.SYNONYMS` and the everyday names of :data:`.lexicon.EVERYDAY_NAMES` that fit a category the
scene has (``sofa`` -> couch, ``loo`` -> bathroom). This table is all the syntax knows of the scene: it
tells a noun from a verb; which entities a noun denotes is decided when a phrase is grounded
(:mod:`.grounding`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Literal

from sgplan.llm.offline import lexicon as lx

Kind = Literal["room", "object"]


@dataclass(frozen=True)
class Head:
    """What a head noun denotes: a kind and the categories it covers (empty = every room)."""

    kind: Kind
    categories: frozenset[str]
    plural: bool
    words: int
    """How many words of the text the head noun spans."""
    everyday: str | None = None
    """A name of a room that the scene decides (*the kids' room*: the room with the toys), as said."""


class NounLexicon:
    """The head nouns of a scene, from its categories.

    Parameters
    ----------
    kinds:
        each category of the scene (Gibson names with ``_`` read as a space) and its kind.
    """

    def __init__(self, kinds: Mapping[str, Kind]) -> None:
        self.kinds = dict(kinds)
        self._heads = self._head_table()
        self._longest = max((len(words) for words in self._heads), default=1)

    def _head_table(self) -> dict[tuple[str, ...], Head]:
        names: dict[str, set[str]] = {c: {c} for c in self.kinds}
        for word, targets in lx.SYNONYMS.items():
            present = {t for t in targets if t in self.kinds}
            # A synonym that is itself a category name keeps its literal meaning; one spanning rooms and
            # objects would be ambiguous in kind, so it is not used.
            if present and word not in self.kinds and len({self.kinds[t] for t in present}) == 1:
                names.setdefault(word, set()).update(present)
        for word, cats in abbreviations(self.kinds).items():
            names.setdefault(word, set()).update(cats)
        for word, preferred in lx.EVERYDAY_NAMES.items():
            chosen = next((t for t in preferred if t in self.kinds), None)
            if chosen is not None and word not in self.kinds:
                names.setdefault(word, {chosen})
        table: dict[tuple[str, ...], Head] = {}
        for word, cats in names.items():
            kind = self.kinds[next(iter(cats))]
            for form, is_plural in ((word, False), (lx.plural(word), True)):
                key = tuple(form.split())
                # A word whose plural is itself ("stairs") stays singular: "the stairs" is then one
                # staircase, ambiguous where there are several, rather than silently all of them.
                table.setdefault(key, Head(kind, frozenset(cats), is_plural, len(key)))
        for word in lx.GENERIC_ROOM_WORDS:
            table.setdefault((word,), Head("room", frozenset(), word.endswith("s"), 1))
        for name in lx.KIDS_ROOM_NAMES:
            said = " ".join(name).replace(" 's", "'s")
            table[name] = Head("room", frozenset(), False, len(name), everyday=said)
        return table

    def words(self) -> frozenset[str]:
        """Every word of every head noun of the scene (its names, synonyms and abbreviations)."""
        return frozenset(w for key in self._heads for w in key)

    def match(self, words: Sequence[str], start: int) -> Head | None:
        """The longest head noun beginning at ``words[start]``, or ``None``."""
        for n in range(min(self._longest, len(words) - start), 0, -1):
            head = self._heads.get(tuple(words[start : start + n]))
            if head is not None:
                return head
        return None

    def room_modifier(self, words: Sequence[str], start: int) -> str | None:
        """``dining`` in "the dining chairs": the first word of a room category (one of
        :data:`.lexicon.ROOM_MODIFIERS`, not an adjective such as *living*) right before an object noun;
        ``None`` otherwise."""
        if start + 1 >= len(words) or words[start] not in lx.ROOM_MODIFIERS or self.match(words, start):
            return None
        after = self.match(words, start + 1)
        named = any(k == "room" and c.split()[0] == words[start] and " " in c for c, k in self.kinds.items())
        return words[start] if named and after is not None and after.kind == "object" else None

    def names_word(self, word: str) -> bool:
        """Whether ``word`` is a word of a category of the scene (*living* in *living room*)."""
        return any(word in category.split() for category in self.kinds)

    def category_names(self, kind: Kind) -> list[str]:
        """The categories of one kind present in the scene, sorted."""
        return sorted(c for c, k in self.kinds.items() if k == kind)


def abbreviations(kinds: Mapping[str, Kind]) -> dict[str, set[str]]:
    """The abbreviations of the scene's categories: those of :data:`.lexicon.ABBREVIATIONS` for the
    categories the scene has (of one kind), the letters of a one-word name without its vowels after the
    first (*bthrm*, *ktchn*, *bdrm*), the initials of a name of several words (*ho*, *dt*, *lr*), and *rm*
    for the *room* of a name (*bathrm*, *living rm*). An abbreviation that is a word of the grammar, or a
    name of the scene, is none; two letters are one only as the initials of a name no word of the lexicon
    has (nor *am* / *pm*)."""
    taken = lx.STRUCTURAL | lx.POSITIVE_VERBS | lx.FILLERS | frozenset(lx.REFUSED_WORDS) | lx.HESITATIONS | {
        w for c in kinds for w in c.split()}
    out: dict[str, set[str]] = {}
    for word, targets in lx.ABBREVIATIONS.items():
        present = {t for t in targets if t in kinds}
        if present and len({kinds[t] for t in present}) == 1:
            out.setdefault(word, set()).update(present)
    for category in kinds:
        forms = {_skeleton(category)} if " " not in category else {_initials(category)}
        if category.endswith("room"):
            stem = category[: -len("room")].strip()
            forms |= {f"{stem}rm", f"{stem} rm"} if " " in category else {f"{stem}rm"}
        for form in forms - {category}:
            short = form == _initials(category) and form not in lx.LEXICON_WORDS | {"am", "pm"}  # not "6 pm"
            if (len(form) >= 3 or short) and form not in taken:
                out.setdefault(form, set()).add(category)
    return {w: c for w, c in out.items() if len({kinds[x] for x in c}) == 1}


def _skeleton(word: str) -> str:
    """``bathroom`` -> ``bthrm``: the word without its vowels after the first letter (and without doubled
    letters)."""
    kept = word[0] + "".join(c for c in word[1:] if c not in "aeiou")
    return "".join(c for k, c in enumerate(kept) if k == 0 or c != kept[k - 1])


def _initials(name: str) -> str:
    """``home office`` -> ``ho``: the first letter of each word of a name."""
    return "".join(w[0] for w in name.split())
