"""A sentence with no verb that only sets the scene: *Time for the evening round.*, *Quick errands before I
get home.*, *Just a routine check, nothing urgent.*, *Working late again.*, *Busy day, sorry.*

People open a message with a fragment that names the occasion, not a task. Such a sentence is known by its
shape, not by its words: a noun phrase whose head is a word of talk, of a list or of a time (*thing*,
*errands*, *round*, *check*, *day*, *party*: :data:`.lexicon.FRAGMENT_HEADS`) with any words before it that
the grammar has no role for (*quick*, *routine*, *evening*, *cleaning*), or a verb in *-ing* the grammar does
not know (*working*) or that the speaker goes out or away with (*Heading out soon*, *Working from home*), then
only tails that ask nothing: *for* / *of* and another such phrase or a person (*for you*), a time (*this
weekend*, *late*), an event said with its subject (*before I get home*, *while the kids are around*) and,
after a comma, remarks and statements (*nothing urgent*, *I promise*, *sorry*). Nothing in it may name a room
or object of the scene (or be a misspelling of one), a floor, *upstairs*, a number, a pronoun or a word of the
grammar's order or negation; *again* and *last* (which could repeat or order a goal) only in a sentence before
any goal. Opening the message, a verb in *-ing* the grammar reads may be followed by any words that name and
ask nothing (*Getting ready for dinner.*, *Moving some decorations around.*). A bare noun the grammar does not
know (*Bins.*) is not a fragment: it may be a goal the scene lacks, and is refused by the parser.
"""

from __future__ import annotations

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.syntax.context import closing_only, is_time, statement
from sgplan.llm.offline.syntax.reader import Reader


def context_fragment(r: Reader, opener: bool) -> bool:
    """Whether the sentence ``r`` is a fragment that only sets the scene (see the module docstring);
    ``opener``: no sentence with goals came before it (then *again* and *last* order nothing)."""
    if any(r.head(k) is not None for k in range(len(r))) or r.says(lx.CORRECTIONS, 0, len(r)):
        return False  # "Change of plan:" takes back what was said before it
    if len(r) <= 2 and any(r.nouns.names_word(w) for w in r.words):
        return False  # "dining:" heading a line is the dining room cut short, never a scene-setting gerund
    k = r.skip(0, lx.INTERJECTIONS)
    if opener and busy_gerund(r, k):
        return True
    end = talk_phrase(r, k, opener) or gerund(r, k)
    if end is None:
        return False
    while end < len(r):
        nxt = tail(r, end, opener)
        if nxt is None:
            return False
        end = nxt
    return True


def talk_phrase(r: Reader, k: int, opener: bool) -> int | None:
    """The end of a noun phrase headed by a word of talk, list or time at ``k`` (*a routine check*, *the
    evening round*, *quick errands*, *dinner party*), or ``None``."""
    j = k + (r.word(k) in lx.FRAGMENT_ARTICLES
             or (r.word(k) == "one" and modifier(r, k + 1, opener)))  # "one last favour", not "one job"
    end = None
    while j < len(r) and (modifier(r, j, opener) or r.word(j) in lx.FRAGMENT_HEADS):
        j += 1
        if r.word(j - 1) in lx.FRAGMENT_HEADS and (r.word(j - 1) not in lx.POSITIVE_VERBS or j - 1 > k):
            end = j  # a verb as the head only after a word before it ("a routine check", not "check")
    return end


def modifier(r: Reader, j: int, opener: bool) -> bool:
    """Whether the word at ``j`` may stand before the head of a talk phrase: a word the grammar has no role
    for, a bare noun the lexicon knows (*laundry*), a time or event (*evening*), or *last* in an opener."""
    w = r.word(j)
    return w.isalpha() and not (r.spelling is not None and r.spelling.may_be_a_misspelt_name(w)) and (
        w not in lx.LEXICON_WORDS or w in lx.NOUN_WORDS or w in lx.EVENT_WORDS or w.endswith("ing")
        or w in lx.FRAGMENT_MODIFIERS or (opener and w == "last"))


def gerund(r: Reader, k: int) -> int | None:
    """The end of a verb in *-ing* at ``k`` that the grammar neither reads nor refuses (*Working late*), or of
    one it reads as an order but that the speaker goes out or away with (*Heading out*, *Working from home*:
    :data:`.lexicon.FRAGMENT_AWAY`); else ``None``."""
    w = r.word(k)
    if not (w.endswith("ing") and len(w) > 5):
        return None
    stems = (w, w[:-3], w[:-3] + "e", w[:-4])
    if any(said in lx.REFUSED_WORDS or said in lx.STRUCTURAL for said in stems):
        return None
    away = r.phrase(k + 1, lx.FRAGMENT_AWAY)
    if away is not None:
        return k + 1 + len(away)
    return None if any(said in lx.POSITIVE_VERBS for said in stems) else k + 1


def busy_gerund(r: Reader, k: int) -> bool:
    """Whether the sentence from ``k`` is a verb in *-ing* of any kind and words that name and ask nothing,
    opening the message (*Getting ready for dinner.*, *Setting up for Sunday lunch.*, *Moving some decorations
    around.*): what the speaker is busy with. No room, object, floor, number, pronoun, misspelt name, or word
    of negation, order or condition may follow it (*Checking the kitchen.* names a place: left to the
    parser)."""
    w = r.word(k)
    if not (w.endswith("ing") and len(w) > 5) or k + 1 >= len(r):
        return False
    if any(said in lx.REFUSED_WORDS for said in (w, w[:-3], w[:-3] + "e", w[:-4])):
        return False  # "Leaving soon.": the robot leaving? (refused by the parser)
    return all(idle(r, j) for j in range(k + 1, len(r)))


def idle(r: Reader, j: int) -> bool:
    """Whether the word at ``j`` names nothing and asks nothing (see :func:`busy_gerund`)."""
    w = r.word(j)
    if w in (".", "!"):
        return True
    return (w.isalpha() and r.head(j) is None and w not in lx.PRONOUNS and w not in lx.RELATIVE_FLOORS
            and w not in lx.FLOOR_WORDS and w not in lx.NUMBER_WORDS and w not in lx.ORDER_HEADS
            and w not in lx.NEGATING and w not in ("never", "no", "not", "if", "when", "until", "there")
            and not (r.spelling is not None and r.spelling.may_be_a_misspelt_name(w)))


def tail(r: Reader, k: int, opener: bool) -> int | None:
    """The end of what follows a fragment's phrase at ``k`` and asks nothing, or ``None``."""
    w = r.word(k)
    if w == "for" and (r.word(k + 1) in lx.FRAGMENT_PEOPLE or r.word(k + 1) in lx.PEOPLE_NOUNS):
        return k + 2  # "a little job for you", "a quick one for Mum"
    if w in ("for", "of"):
        return talk_phrase(r, k + 1, opener)
    if w in lx.FRAGMENT_TIMES or (opener and w == "again"):
        return k + 1
    if w == "on" and r.word(k + 1) in lx.EVENT_WORDS:
        return k + 2  # "on Sunday"
    if w in lx.EVENT_OPENERS and r.word(k + 1) in lx.PEOPLE | lx.PEOPLE_NOUNS | lx.ARTICLES | {"you"}:
        j = k + 1 + (r.word(k + 1) in lx.ARTICLES)
        said = range(j, min(j + 5, len(r)))
        stop = next((i for i in said if r.word(i) == ","), said.stop)
        if stop > j + 1 and all(plain(r.word(i)) for i in range(j + 1, stop)):
            return stop  # "before I get home", "before you charge", "while the kids are around"
        return None
    timed = next((j for j in range(len(r), k, -1) if is_time(r, k, j)), None)
    if timed is not None:
        return timed  # "this weekend", "this evening"
    if w == ",":  # "..., nothing urgent", "..., I promise"
        stop = next((i for i in range(k + 1, len(r)) if r.word(i) == ","), len(r))
        remark = (closing_only(r, k + 1, stop) or statement(r, k + 1, stop) == "aside"
                  or (stop == k + 2 and r.word(k + 1) in lx.APOLOGY_WORDS))  # "..., sorry"
        return stop if stop > k + 1 and remark else None
    return None


def plain(w: str) -> bool:
    """A word of an event clause: no role in the grammar beyond what a statement has (*get*, *home*,
    *around*, *are*)."""
    return w.isalpha() and (w not in lx.STRUCTURAL or w in lx.AUXILIARIES) and w not in lx.RELATIVE_FLOORS
