"""The controlled-English grammar: mission sentences -> grounded noun phrases -> an LTL formula.

The grammar is documented for users in docs/offline.md. In short, a mission is a list of sentences; each
sentence is a sequence of steps joined by ``then`` / ``after that`` / ``finally`` / ``X after Y`` /
``X before Y`` / ``..., but first X`` / ``Before that, ...``; a step is one or more actions (``visit the
kitchen and water the plant``); an action is verb words followed by a list of noun phrases (``again``,
``twice`` make new visits); negations (``always avoid``, ``never``, ``don't``, ``avoid``, ``without``,
``stay away from``; a trailing one on a room holds for the whole mission), ``until``, conditions
(``if ... , ...``, ``... if ...``, ``... only if ...``, ``whenever ...``) and sentence prefixes (``After
visiting X, ...``, ``Once ...``, ``Only after ...``, ``On your way to X, ...``, ``In the kitchen, ...``)
wrap them; ``if you ever ...`` and ``..., Y afterwards`` make a condition a response like *whenever*, a
bare ``when ...`` is refused. Noun phrases are grounded as they are read (:class:`NounPhrase`), so
pronouns (``it``, ``them``) and room context ("go to the dining room and sit on one of the chairs": the
chairs of that dining room) use what came before.

Anything the grammar does not understand raises :class:`~sgplan.errors.MissionError` naming the phrase;
it never guesses.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Literal

from sgplan.errors import MissionError
from sgplan.llm.offline import backref, preamble
from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.compose import Step, Task, conj, disj, sequence_formula, strict_formulas
from sgplan.llm.offline.everyday import everyday_names
from sgplan.llm.offline.names import Entity, Head, SceneVocabulary
from sgplan.llm.offline.text import Tok, rewrite, sentences, tokenize
from sgplan.logic.formula import Always, And, Atom, Eventually, Formula, Implies, Not, Until, atoms
from sgplan.logic.tokens import action_entity

Mode = Literal["the", "any", "all"]
Role = Literal["goal", "avoid", "condition", "qualifier"]

_POSSESSIVES = lx.word_set("my your our his her their")
_DETERMINERS = lx.word_set("the a an any all every each both either this that these those "
                           "some") | _POSSESSIVES
_SEQ_WORDS = (("and", "then"), ("then",), ("after", "that"), ("afterwards",), ("afterward",), ("next",),
              ("finally",), ("subsequently",), ("after", "which"), ("followed", "by"), ("later",),
              ("and", "finally"), ("lastly",), ("secondly",), ("thirdly",), ("fourthly",), ("second", ","),
              ("third", ","), ("fourth", ","))
_LIST_PREPOSITIONS = frozenset({"to", "into", "by", "past", "through"})
"""Repeated in a list after *either* / *both*: *either to A or to B*."""
_PLURAL_LOOKING = frozenset({"stairs"})
"""Head nouns that look plural but are read as one entity (``the stairs`` is one staircase as a goal);
to avoid, on a mission confined to some floors, they mean each of them (see :meth:`MissionParser.check`)."""
_NEG_STARTS = (("always", "avoid"), ("always", "stay", "away", "from"), ("always", "keep", "away", "from"),
               ("always", "stay", "out", "of"), ("always", "keep", "out", "of"), ("never",),
               ("do", "not"), ("does", "not"), ("must", "not"), ("should", "not"), ("can", "not"),
               ("cannot",), ("may", "not"), ("will", "not"), ("not",), ("avoid",), ("avoiding",),
               ("stay", "away", "from"), ("keep", "away", "from"), ("stay", "out", "of"),
               ("keep", "out", "of"), ("without",), ("while", "avoiding"), ("always", "do", "not"),
               ("and", "avoid"), ("but", "avoid"), ("but", "never"), ("and", "never"), ("but", "do", "not"),
               ("and", "do", "not"), ("but", "not"), ("no",), ("neither",), ("nor",), ("and", "nor"),
               ("keep", "clear", "of"), ("steer", "clear", "of"), ("stay", "clear", "of"),
               ("under", "no", "circumstances"), ("at", "no", "point"), ("at", "no", "time"),
               ("keep", "off"), ("stay", "off"), ("always", "keep", "off"), ("always", "stay", "off"))
_GLOBAL_NEG = frozenset({"always", "never", "do", "does", "must", "should", "can", "cannot", "may", "will",
                         "no", "stay", "keep", "neither", "nor", "steer", "circumstances", "point", "time"})
_OFF_LIMITS = tuple((*be, *said) for be in (("is",), ("are",), ("is", "strictly"), ("are", "strictly"))
                    for said in (("off", "limits"), ("out", "of", "bounds"), ("forbidden",), ("prohibited",),
                                 ("banned",), ("not", "allowed"), ("a", "no", "go"), ("no", "go"),
                                 ("not", "to", "be", "entered"), ("to", "be", "avoided"),
                                 ("not", "to", "be", "touched"), ("out", "of", "limits")))
_COPULAS = frozenset({"is", "are", "was", "were", "should", "must", "will", "has", "have", "seems", "looks",
                      "might", "may", "can", "could", "needs", "need"})
"""After a sentence's first noun phrase: a statement ("the bowl is in the kitchen"), never a goal."""
_OFF_LIMITS += tuple((modal, "be", "avoided") for modal in ("should", "must", "has", "have", "will"))
"""``The kitchen is off limits``: never enter / reach what the sentence names (``G !x``)."""
"""A negation with one of these words holds for the whole mission (G !x); 'avoid' and 'without' after an
action only constrain the moment that action is done (F(x & !y)), as in the authors' missions."""
_QUAL_IN = ("in", "inside", "within", "of", "from")
_QUAL_CONTAINS = (("with",), ("having",), ("containing",), ("that", "has"), ("that", "have"),
                  ("which", "has"), ("which", "have"), ("that", "contains"), ("which", "contains"),
                  ("where", "there", "is"), ("where", "there", "are"), ("that", "holds"),
                  ("that", "only", "has"),
                  ("which", "only", "has"), ("that", "only", "have"), ("with", "only"),
                  ("that", "has", "only"),
                  ("containing", "only"))
_QUAL_LACKS = (("that", "does", "not", "have"), ("which", "does", "not", "have"), ("with", "no"),
               ("that", "has", "no"), ("that", "does", "not", "contain"), ("where", "there", "is", "no"))
_QUAL_NEXT = (("next", "to"), ("adjacent", "to"), ("beside",), ("near",), ("connected", "to"), ("by",),
              ("off",), ("close", "to"), ("joined", "to"), ("linked", "to"), ("attached", "to"),
              ("that", "connects", "to"), ("leading", "to"), ("that", "leads", "to"))
_QUAL_EXCEPT = (("except", "for"), ("except",), ("but", "not"), ("other", "than"), ("apart", "from"),
                ("excluding",), ("besides",))
_PARTICLES = lx.word_set("on off up down out over")
_SUBJECT_FILLERS = lx.word_set("you we i the robot it ever have has had do does did are is were was already "
                                "been also first")
_CONDITION_WORDS = ("if", "when", "in case")
"""Conditions; *once* is temporal ('once you have been to X' = after X), not a condition."""
_WHENEVER = (("whenever",), ("every", "time"), ("each", "time"), ("any", "time"), ("anytime",))
_DONE = frozenset({"done", "finished", "through"})
_WAYPOINT = (("via",), ("through",), ("by", "way", "of"), ("passing", "through"),
             ("going", "through"), ("passing", "by"), ("going", "past"), ("passing",),
             ("by", "going", "through"))
"""Right after a goal: what follows is on the way there (before it)."""
_ON_THE_WAY = (("on", "your", "way"), ("on", "the", "way"), ("on", "my", "way"))
_WAY_BACK = frozenset({"back", "up", "down", "out", "home"})
"""``on your way back (up)``: after what came before, like *then*."""
_ONLY_AFTER = (("only", "after"), ("only", "once"), ("not", "before"), ("not", "until"))
_EVER = (("ever",), ("at", "any", "point"), ("at", "any", "time"), ("at", "some", "point"), ("every", "time"),
         ("each", "time"), ("anytime",))
"""In a condition ("if you ever go into X"): it is about each visit of X, a response, not one event."""
_AFTERWARDS = (("afterwards",), ("afterward",), ("after", "that"), ("after",), ("later",),
               ("straight", "after"), ("right", "after"))
"""In the consequent of a condition ("..., visit Y afterwards"): Y follows X, a response."""
_CONDITION_END = frozenset({"after", "before", "and", "or", "until", "but", "while", "without", "when", "if",
                            "once", "whenever", "unless"})
"""Words that would continue a condition past its one action (a comma or *then* ends it)."""
_FIRST = frozenset({"first", "firstly"})
_ASIDE = tuple((",", rel, be, *also) for rel in ("which", "that") for be in ("is", "are")
               for also in ((), ("also",), ("located",), ("also", "located")))
_ASIDE_QUALIFIERS = frozenset({"in", "inside", "on", "next", "beside", "upstairs", "downstairs", "near",
                               "adjacent", "connected", "attached"})
"""``the couch, which is in the living room``: an aside read as the qualifier it states."""
_THEN_NEXT = (("then",), ("and", "then"), ("finally",), ("and", "finally"), ("after", "that"),
              ("afterwards",), ("lastly",))
"""After a list joined by commas only: the list is a sequence too ("A, B, then C")."""
_VERB_IDIOMS = (("all", "the", "way"), ("a", "look"), ("a", "quick", "look"), ("a", "peek"), ("a", "glance"),
                ("a", "quick", "peek"), ("your", "way"), ("my", "way"), ("its", "way"), ("a", "visit"),
                ("a", "quick", "visit"), ("a", "trip"), ("a", "quick", "trip"), ("a", "detour"),
                ("a", "stop"),
                ("a", "quick", "stop"), ("a", "seat"), ("a", "nap"), ("a", "rest"))
"""Words of a verb that look like a noun phrase: *take a look at*, *make your way to*, *pay a visit to*."""
_FLOOR_DIRECTIONS = {"above": 1, "up": 1, "higher": 1, "upstairs": 1, "below": -1, "down": -1, "lower": -1,
                     "downstairs": -1, "beneath": -1, "under": -1}
"""``the floor above``, ``two floors down``: floors counted from the start floor."""
_FLOOR_PLURALS = (*lx.FLOOR_WORDS, "floors", "levels", "storeys", "stories")
_STRICT_SEQ = tuple((*lead, *only) for lead in ((), (",",), ("and",), ("but",), (",", "and"), (",", "but"))
                    for only in (("only", "after", "that"), ("only", "after", "this"), ("only", "then"),
                                 ("only", "afterwards"), ("not", "before", "that"),
                                 ("only", "once", "that", "is", "done"),
                                 ("only", "when", "that", "is", "done"),
                                 ("only", "after", "you", "have", "done", "that"),
                                 ("only", "once", "you", "have", "done", "that")))
"""``A, and only after that B``: B after A, and not before it (strict)."""
_STAY = frozenset({"stay", "remain", "keep", "staying", "remaining", "keeping"})
_LEAVE = frozenset({"leave", "leaving"})
_OTHER_FLOOR = (("any", "other", "floor"), ("another", "floor"), ("a", "different", "floor"),
                ("other", "floors"),
                ("any", "other", "floors"), ("change", "floors"), ("change", "floor"), ("switch", "floors"),
                ("any", "other", "level"), ("another", "level"), ("change", "levels"))
"""``don't go to any other floor`` / ``don't change floors``: stay on the start floor."""
_TIME_SCOPED = frozenset({"until", "till", "before", "after", "once", "when", "whenever", "if", "unless",
                          "during"})
"""Words that may limit a *stay on this floor* to part of the mission: such a sentence confines nothing."""
"""``stay on this floor`` / ``don't leave the ground floor``: the mission is confined to floors."""
_TRIP_NOUNS = frozenset({"trip", "visit", "stop", "detour", "run", "quick", "short", "pass"})
"""``twice, with a trip / visit / stop to Y in between``: words naming the visit to Y."""
_BETWEEN_TAIL = (("them",), ("the", "two"), ("the", "two", "visits"), ("each", "visit"), ("visits",))
_MODALS = frozenset({"do", "does", "may", "can", "must", "should", "will"})
_STATED_SUBJECTS = (("i", "am"), ("we", "are"), ("you", "are"), ("the", "robot", "is"), ("i",), ("we",),
                    ("you",))
"""*I'm* (the tokenizer drops the part after the apostrophe) / *we are* ... before where the robot is."""
_AFTER_ALL = tuple((w, *rest) for w in ("after", "once", "when")
                   for rest in (("all",), ("both",), ("all", "that"), ("you", "done", "those"),
                                ("you", "have", "done", "those"), ("you", "done", "all", "that"),
                                ("you", "have", "done", "all", "that"), ("you", "done", "all"),
                                ("you", "have", "done", "all"), ("you", "done", "both"),
                                ("you", "have", "done", "both"), ("those", "are", "done"),
                                ("all", "are", "done"), ("all", "that", "is", "done")))
"""*after all three (of them)*, *once you've done those*: after every goal said before (:meth:`after_all`)."""
_NOW = (("right", "now"), ("now",), ("currently",), ("at", "once"), ("at", "present"))
"""*right now* ...; *at the moment* reads *at once* here (``lx.PHRASE_ALIASES``: *the moment* = *once*)."""
_STRUCTURAL = (
    frozenset(w for table in (_SEQ_WORDS, _NEG_STARTS, _QUAL_CONTAINS, _QUAL_LACKS, _QUAL_NEXT, _QUAL_EXCEPT,
                              lx.ORDER_MODIFIERS) for seq in table for w in seq)
    | frozenset(_QUAL_IN) | frozenset(w for c in _CONDITION_WORDS for w in c.split()) | _DETERMINERS
    | frozenset(lx.FLOOR_WORDS) | frozenset(lx.FLOOR_ORDINALS) | frozenset(lx.FLOOR_NAMED)
    | frozenset(lx.FLOOR_TOP) | frozenset(lx.FLOOR_MIDDLE) | frozenset(lx.NUMBER_WORDS)
    | frozenset(lx.PRONOUNS)
    | frozenset(lx.GENERIC_ROOM_WORDS)
    | frozenset({"whenever", "only", "than", "zero", "ever", "again", "twice", "once", "times", "anytime"})
) - lx.POSITIVE_VERBS - {"first", "also", "please", "eventually", "finally"}
"""Words with a role in the grammar: in the verb slot they signal a sentence that was not understood."""


@dataclass
class NounPhrase:
    """A grounded noun phrase: the text and span it came from and the entities it denotes.

    ``mode``: ``the`` (exactly one entity), ``any`` (one of them will do), ``all`` (each of them).
    ``room_scoped``: the objects were located through a room (``the sink in the kitchen``, ``the
    kitchen's sink``, or the room of the same step), so reaching them also requires being in that room.
    """

    phrase: str
    start: int
    end: int
    entities: list[Entity]
    mode: Mode
    room_scoped: bool
    role: Role
    count: int | None = None
    """How many entities the phrase said ("the two beds"), if it said so."""
    generic: bool = False
    """The head noun was *room* / *place* (any room): *the one with ...* after it means any room too."""
    alternative: bool = False
    """One alternative of an *or* list (*the kitchen or the bathroom*): a back-reference to it is not
    determined (see :func:`.backref.choice_refusal`)."""
    choice_of: str | None = None
    """A pronoun whose antecedent is a choice: why it is refused if it is made a goal (:meth:`tasks_of`;
    *put it in Y* only carries it)."""
    floor: bool = False
    """A floor named as a place (*the top floor*: its rooms); *there* / *up there* / *on that floor* after it
    mean that floor."""


@dataclass
class Clause:
    """What one sentence body says: a sequence of steps and global constraints."""

    steps: list[Step] = field(default_factory=lambda: [[]])
    constraints: list[Formula] = field(default_factory=list)

    def formula(self) -> Formula | None:
        goal = sequence_formula(self.steps)
        parts = ([goal] if goal is not None else []) + strict_formulas(self.steps) + self.constraints
        return conj(parts) if parts else None


def member_formula(entity: Entity, room_scoped: bool) -> Formula:
    """The state formula of being at ``entity`` (in its room too, for a room-scoped object)."""
    atom = Atom(entity.action)
    if entity.kind == "object" and room_scoped:
        return conj([atom, Atom(f"enter({entity.room_key})")])
    return atom


class MissionParser:
    """Parses one mission text against one scene; see :func:`parse_mission`."""

    def __init__(self, text: str, vocabulary: SceneVocabulary, start_floor: int | None = None) -> None:
        self.text = text
        self.vocab = vocabulary
        self.start_floor = start_floor
        self.references: list[NounPhrase] = []
        self.toks: list[Tok] = []
        self.i = 0
        self.sentence_scope: list[Entity] = []
        self.soft_scope: list[Entity] = []
        """The rooms of a condition ("whenever you enter the bathroom, wash at the sink"): an ambiguous
        definite object of the consequent is the one there, when exactly one is."""
        self.prior_steps: list[Step] = []
        """The steps of the previous sentence when this one continues its sequence ("... Then ...")."""
        self.last_step: Step = []
        """The last step with goals of the previous sentence (what *done that* refers to)."""
        self.in_condition = False
        """Reading the condition of *if* / *whenever* (where *end up in X* just means being in X)."""
        self.pending_floor: frozenset[int] | None = None
        """A floor said in the verb slot ("go upstairs to ..."), for the next noun phrase."""
        self.alt_floors: frozenset[int] | None = None
        self.alt_said: tuple[str, str] = ("", "")
        """The floors of the second reading of a start-relative word (:meth:`check_still_on_start_floor`)."""
        self.waypoint_pending = False
        """*On the way (there),* was said: the next action comes before the goal named last."""
        self.said_last = False
        """The sentence ended with *last* ("visit the office last"): its last step follows all else."""
        self.body_actions = 0
        """How many actions the sentence had before a trailing condition ("S if X")."""
        self.actions = 0
        """How many actions the sentence bodies read so far (a condition's consequent must be one)."""
        self.lenient_scope = False
        self.carried_rooms: list[Entity] = []
        """The rooms of the step before a comma that made a sequence ("go to the kitchen, take a bottle,
        then ..."): objects of the next action are looked for there first (leniently: elsewhere if none)."""
        self.comma_list = False
        """The last noun phrase list was joined by commas only ("the fridge, the oven")."""
        self.going_back = False
        """The last action said *back* / *return*: it comes after what was said before it."""
        self.strict_pending = False
        """*only after that* / *only then* was said: the next action is strictly after the step before."""
        self.only_verb = False
        """Reading ``Only <verb> X after Y``: the body stops at *after* (see :meth:`only_verb_after`)."""
        self.confined: frozenset[int] | None = None
        """The floors the mission stays on ("stay on this floor"): goals are grounded there."""
        self.action_floor: tuple[frozenset[int], int] | None = None
        """The floors the action being read is done on, after a floor move ("go upstairs and check the
        bathroom and the office": both upstairs), and the character offset where the action starts (*there*
        after it means those floors)."""

    # -- token helpers --------------------------------------------------------------------------------
    def word(self, k: int = 0) -> str:
        j = self.i + k
        return self.toks[j].text if 0 <= j < len(self.toks) else ""

    def words(self) -> list[str]:
        return [t.text for t in self.toks]

    def at(self, *seq: str, k: int = 0) -> bool:
        return all(self.word(k + n) == w for n, w in enumerate(seq))

    def at_any(self, options: tuple[tuple[str, ...], ...], k: int = 0) -> tuple[str, ...] | None:
        for seq in sorted(options, key=len, reverse=True):
            if self.at(*seq, k=k):
                return seq
        return None

    def done(self) -> bool:
        return self.i >= len(self.toks)

    def span_text(self, start: int, end: int) -> str:
        return self.text[start:end]

    def here(self) -> str:
        """The rest of the sentence, for error messages."""
        if self.done():
            return "the end of the sentence"
        tail = self.toks[self.i : self.i + 6]
        return f"'{self.span_text(tail[0].start, tail[-1].end)}'"

    def fail(self, message: str) -> MissionError:
        return MissionError(f"{message}; rephrase the mission (see docs/offline.md for the understood "
                            f"English)")

    # -- the mission ------------------------------------------------------------------------------------
    def parse(self) -> Formula:
        parts: list[Clause | Formula] = []
        tokens = everyday_names(rewrite(tokenize(self.text), lx.PHRASE_ALIASES), self.vocab)
        all_sentences = self.without_preamble(sentences(tokens))
        self.confined = self.confinement(all_sentences)
        for sentence in all_sentences:
            self.toks, self.i, self.sentence_scope, self.soft_scope = sentence, 0, [], []
            self.waypoint_pending = False
            self.strict_pending = False
            self.body_actions = 0
            previous = parts[-1] if parts and isinstance(parts[-1], Clause) else None
            opener = self.whole_mission_opener()
            precedes = self.sentence_precedes(parts)
            continues = self.skip_fillers(sequence_too=True)
            self.prior_steps = previous.steps if continues and previous is not None else []
            self.said_last = False
            result = self.sentence()
            if opener and not (isinstance(result, Clause) and not any(result.steps) and result.constraints
                               and all(isinstance(c, Always) for c in result.constraints)):
                raise self.fail(f"'{opener}, ...' is understood only before what to avoid for the whole "
                                f"mission ('{opener}, keep out of the kitchen')")
            self.expect_all_read()
            if self.said_last and not continues and not precedes and previous is not None:
                continues = True  # "Go to the office last.": after the goals of the sentences before
                self.prior_steps = previous.steps
            if (isinstance(result, Clause) and not any(result.steps) and not result.constraints and previous
                    and "order" in self.words() and len([s for s in previous.steps if s]) > 1):
                raise self.fail("'the order does not matter' after goals given in order; say which it is")
            if precedes:
                if previous is None or not isinstance(result, Clause):
                    raise self.fail("'before that' / 'first' in a later sentence needs a plain list of goals "
                                    "in this sentence and the one before it")
                previous.steps[0:0] = [s for s in result.steps if s]
                previous.constraints.extend(result.constraints)
            elif continues and previous is not None and isinstance(result, Clause):
                previous.steps.extend(result.steps)
                previous.constraints.extend(result.constraints)
            else:
                parts.append(result)
            if isinstance(result, Clause) and any(result.steps):
                self.last_step = [s for s in result.steps if s][-1]
        formulas = [p.formula() if isinstance(p, Clause) else p for p in parts]
        present = [f for f in formulas if f is not None]
        if not present:
            raise self.fail("the mission names no room or object to visit or avoid")
        return conj(present)

    def without_preamble(self, all_sentences: list[list[Tok]]) -> list[list[Tok]]:
        """The sentences without what asks nothing of the robot: statements of where it starts (*I'm
        downstairs right now.*, :meth:`stated_start`, anywhere), and leading chit-chat sentences and the
        chit-chat clause before the first comma of the first sentence with content (*Hi!*, *I'm hungry, go
        to the fridge*; see :mod:`.preamble`)."""
        kept: list[list[Tok]] = []
        for sentence in all_sentences:
            self.toks, self.i = sentence, 0
            if self.stated_start():
                continue
            if not kept:
                words = [t.text for t in sentence]
                if preamble.is_chitchat(words, self.vocab, _STRUCTURAL):
                    continue
                sentence = sentence[preamble.leading_clause(words, self.vocab, _STRUCTURAL):]
            kept.append(sentence)
        return kept

    def whole_mission_opener(self) -> str:
        """Skips *The whole time,* / *At all times,* ... opening a sentence (the words, or "" if none): they
        say what the trailing form says (*keep out of X the whole time*), so the sentence must be only
        whole-mission avoidance, which :meth:`parse` checks."""
        opener = self.at_any(lx.WHOLE_MISSION)
        if opener is None or self.word(len(opener)) != "," or opener[0] in ("on", "along"):
            return ""  # "On the way, X" is a waypoint (:meth:`body`)
        said = self.span_text(self.toks[0].start, self.toks[len(opener) - 1].end)
        self.i += len(opener) + 1
        return said

    def stated_start(self) -> bool:
        """Reads a sentence that only says where the robot is (*I'm downstairs right now*, *we are on the
        ground floor*, *you're upstairs*): the start floor, used by *upstairs* / *this floor* ...; refused
        when it contradicts the known start floor, or when *upstairs* / *downstairs* do not name one floor.
        False (nothing read) for any other sentence."""
        k = next((len(s) for s in _STATED_SUBJECTS if self.at(*s)), 0)
        if not k:
            return False
        k += 1 if self.word(k) in ("currently", "now", "still") else 0
        w = self.word(k)
        if w in lx.RELATIVE_FLOORS:
            said, n = w, 1
            floors = self.vocab.num_floors
            extreme = 0 if w == "downstairs" else floors - 1
            if floors != 2 and self.start_floor != extreme:
                raise self.fail(f"'{w}': the building {self.vocab.building_name!r} has floors 0 to "
                                f"{floors - 1}; say which floor the robot is on (e.g. 'I am on floor "
                                f"{extreme}')")
            floor = extreme
        else:
            j = k + (1 if w in ("on", "at") else 0)
            j += 1 if self.word(j) == "the" else 0
            if j == k or (found := self.floor_words(j)) is None or len(found[0]) != 1:
                return False
            floor, n, said = next(iter(found[0])), j - k + found[1], " ".join(self.words()[k:j + found[1]])
        end = k + n
        end += len(self.at_any(_NOW, k=end) or ())
        if end != len(self.toks):
            return False
        if self.start_floor is not None and self.start_floor != floor:
            raise self.fail(f"'{said}' says the robot is on floor {floor}, but it starts on floor "
                            f"{self.start_floor}; say where it really is")
        self.start_floor = floor
        return True

    def expect_all_read(self) -> None:
        """The safeguard against silently dropped clauses: a sentence is understood only when every word
        of it was read by some construct (or skipped by an explicit filler rule of :meth:`skip_fillers`);
        otherwise the words left over are named in the refusal."""
        self.skip_fillers()
        if not self.done():
            rest = self.span_text(self.toks[self.i].start, self.toks[-1].end)
            raise self.fail(f"'{rest}' was not understood (the sentence was read only up to there), and "
                            f"no part of a mission is ever dropped")

    def sentence_precedes(self, parts: list[Clause | Formula]) -> bool:
        """Whether this sentence starts with *before that* or *first* after sentences with goals: its steps
        then come before the previous sentence's (consumes the words). Refused when that is ambiguous."""
        has_goals = [p for p in parts if not isinstance(p, Clause) or any(p.steps)]
        if self.at("before", "that"):
            self.i += 2
        elif self.word() in _FIRST and has_goals:
            self.i += 1
        else:
            return False
        if self.word() == ",":
            self.i += 1
        said = self.span_text(self.toks[0].start, self.toks[self.i - 1].end)
        if len(has_goals) != 1 or (said.lower().startswith("before") and
                                   isinstance(has_goals[0], Clause)
                                   and len([s for s in has_goals[0].steps if s]) > 1):
            raise self.fail(f"'{said}': it is not clear which of the earlier goals this comes before; put "
                            f"the goals in the order they must be done (with 'then')")
        return True

    def skip_fillers(self, sequence_too: bool = False) -> bool:
        """Skip words without meaning at a clause start; True if a sequencing word ('then', ...) was seen."""
        seen_sequence = False
        while not self.done():
            strict = self.at_any(_STRICT_SEQ) if sequence_too else None
            if strict is not None:  # "..., and only after that B": B strictly after
                self.i += len(strict)
                self.strict_pending = seen_sequence = True
                continue
            seq = self.at_any(_SEQ_WORDS) if sequence_too else None
            way = self.at_any(_ON_THE_WAY)
            n = len(way or ()) + (1 if self.word(len(way or ())) == "there" else 0)
            if sequence_too and way is not None and (self.word(n) == "," or (self.word(n) in lx.POSITIVE_VERBS
                                                     and self.word(n) not in _WAY_BACK | {"to", "into"})):
                self.i += n  # "On the way (there), stop at X": X before the goal named last
                self.waypoint_pending = seen_sequence = True
            elif way is not None and self.word(len(way)) == "there":
                raise self.fail("'on your way there': say 'before going to X, ...' or put the goals in order")
            elif sequence_too and way is not None and self.word(len(way)) in _WAY_BACK:
                self.i += len(way)
                while self.word() in _WAY_BACK:
                    self.i += 1
                seen_sequence = True
            elif sequence_too and self.done_sequence():
                seen_sequence = True
            elif seq is not None:
                self.i += len(seq)
                seen_sequence = True
            elif self.at_any(lx.TIME_FILLERS) is not None:
                self.i += len(self.at_any(lx.TIME_FILLERS) or ())
            elif self.at_any(lx.POLITE) is not None:
                self.i += len(self.at_any(lx.POLITE) or ())
            elif self.word() == "," or (self.word() in lx.FILLERS
                                        and self.word() not in ("do", "and", "then", "next")):
                self.i += 1
            else:
                break
        return seen_sequence

    def sentence(self) -> Clause | Formula:
        if self.word() in ("and", "but", "so") and (self.at_any(_WHENEVER, k=1) or any(
                self.at(*w.split(), k=1) for w in _CONDITION_WORDS)):
            self.i += 1  # "And whenever you ...", "But if you ...": a new condition, not a continuation
        if self.at_any(_WHENEVER) is not None:
            return self.more_conditions(self.prefix_whenever())
        done = self.done_words()
        if done and self.word(done) == "with" and self.np_starts(done + 1):
            self.i += done + 1  # "when done with the garage, ..."
            before = self.prefix_clause()
            body = self.body()
            body.steps[:0] = before.steps
            return self.postfix_condition(body)
        if self.condition_word() is not None:
            return self.more_conditions(self.prefix_conditional())
        if self.word() in ("until", "till") or self.at("up", "until"):
            return self.until_prefix()
        if self.at_any(_ONLY_AFTER):
            self.i += 2
            before = self.prefix_clause()
            body = self.body()
            return self.more_conditions(self.only_after(before, body))
        if self.word() in ("after", "once") and not self.at("after", "that"):
            self.i += 1
            before = self.prefix_clause()
            body = self.body()
            body.steps[:0] = before.steps
            return self.postfix_condition(body)
        way = self.at_any(_ON_THE_WAY)
        if way is not None and self.word(len(way)) in ("to", "into") and self.np_starts(len(way) + 1):
            self.i += len(way)  # "On your way to the lobby, check the couch": the couch, then the lobby
            after = self.prefix_clause()
            body = self.body()
            body.steps.extend(after.steps)
            return self.postfix_condition(body)
        if self.word() == "before":
            self.i += 1
            after = self.prefix_clause()
            body = self.body()
            body.steps.extend(after.steps)
            return self.postfix_condition(body)
        if self.word() in ("in", "inside", "within") and self.np_starts(1):
            save, known = self.i, len(self.references)
            self.i += 1
            scope = self.noun_phrase("qualifier")
            if self.word() == "," and all(e.kind == "room" for e in scope.entities):
                self.i += 1
                self.sentence_scope = scope.entities
            else:  # not "In <room>, ...": read it again as part of the sentence
                del self.references[known:]
                self.i = save
        if self.word() == "only" and self.word(1) in lx.POSITIVE_VERBS:
            return self.only_verb_after()
        counted = self.actions
        body = self.body()
        self.body_actions = self.actions - counted
        return self.postfix_condition(body)

    def only_verb_after(self) -> Formula:
        """``Only enter the living room after you have been to the kitchen`` (at *only*): the same as
        ``Enter the living room only after ...``; what follows the condition is left to the end check."""
        self.i += 1
        self.only_verb = True
        body = self.body()
        self.only_verb = False
        if self.word() not in ("after", "once"):
            raise self.fail(f"'only' before a verb is understood as 'only <do X> after Y'; found "
                            f"{self.here()}")
        self.i += 1
        self.skip_subject()
        return self.only_after(Clause(steps=self.action()), body)

    def prefix_whenever(self) -> Formula:
        """``Whenever X, Y`` (at *whenever* / *every time* ...): the response ``G(X -> F Y)``."""
        self.i += len(self.at_any(_WHENEVER) or ())
        trigger = self.trigger()
        self.expect_comma_or_then()
        self.soft_scope = self.rooms_of(trigger.members)
        return self.whenever(trigger, self.consequent())

    def condition_word(self, k: int = 0) -> str | None:
        """The condition word (*if*, *when*, *in case*) at ``k`` tokens ahead, if any."""
        return next((w for w in _CONDITION_WORDS if self.at(*w.split(), k=k)), None)

    def prefix_conditional(self) -> Formula:
        """``If X, Y`` / ``When X, Y`` (at the condition word): see :meth:`conditional`."""
        cond_word = self.condition_word() or ""
        self.i += len(cond_word.split())
        start = self.i
        condition, tasks = self.condition()
        said_ever = self.says(_EVER, start, self.i)
        self.expect_comma_or_then()
        self.soft_scope = self.rooms_of([m for t in tasks for m in t.members])
        start = self.i
        body = self.consequent()
        return self.conditional(cond_word, condition, tasks, body,
                                said_ever or self.says(_AFTERWARDS, start, self.i))

    def more_conditions(self, first: Formula) -> Formula:
        """Further condition rules joined to a condition by *and* / *but* / commas (*whenever you enter
        the kitchen, go to the living room, and whenever you are in the living room, go to the lobby*;
        *if X, Y, and if Z, W*): each one is kept, as a conjunct. Anything else after a condition is left
        for :meth:`parse` to refuse (it never drops words)."""
        rules = [first]
        while not self.done():
            k = 0
            while self.word(k) in (",", "and", "but", "also"):
                k += 1
            if not k and self.word(-1) not in (",", "and", "but", "also"):
                break  # "..., open the fridge if ...": not a new rule
            if self.at_any(_WHENEVER, k=k) is not None:
                self.i += k
                rules.append(self.prefix_whenever())
            elif self.condition_word(k) is not None:
                self.i += k
                rules.append(self.prefix_conditional())
            else:
                break
        return conj(rules)

    def until_prefix(self) -> Clause:
        """``Until you have reached X, stay out of Y`` / ``Till X, do not enter Y``: ``!Y U X`` for each
        prohibition of the sentence; X is a step of the sentence, so a later *afterwards* / *then* follows
        it. The rest of the sentence must be prohibitions only."""
        self.i += 2 if self.word() == "up" else 1
        self.skip_subject()
        self.in_condition = True
        steps = self.action()
        self.in_condition = False
        tasks = [t for step in steps for t in step]
        if len(tasks) > 1 and all(t.mode == "all" for t in tasks):  # "until A and B": each of them
            tasks = [Task("all", [m for t in tasks for m in t.members])]
        if len(tasks) != 1:
            raise self.fail("'until X, ...' needs one goal X")
        self.expect_comma_or_then()
        body = self.body()
        if (any(body.steps) or not body.constraints
                or not all(isinstance(c, Always) for c in body.constraints)):
            raise self.fail("'until X, ...' is understood with prohibitions only (e.g. 'until you have been "
                            "to the kitchen, stay out of the office'); put goals in their own sentence")
        target = tasks[0]
        ends = [disj(target.members)] if target.mode == "any" else target.members
        untils: list[Formula] = [Until(c.arg, end) for c in body.constraints if isinstance(c, Always)
                                 for end in ends]
        return Clause(steps=[[target]], constraints=untils)

    def consequent(self) -> Clause:
        """What a condition (*if*, *whenever*) asks for: one action. A second one (*..., grab the fridge
        afterwards, and go to the garage*) may belong to the condition or be a goal of its own, so it is
        refused rather than guessed."""
        before = self.actions
        body = self.body()
        if self.actions - before > 1:
            raise self.fail("a condition followed by several actions: it is not clear which of them belong "
                            "to "
                            "the condition; put the other goals in a sentence of their own")
        return body

    def postfix_condition(self, body: Clause) -> Clause | Formula:
        if self.done():
            return body
        joined = self.word(-1) in ("and", "but")  # "S, and whenever X, T" / "S, but if X, T"
        if self.body_actions > 1 and not joined and (self.at_any(_WHENEVER) or any(
                self.at(*w.split()) for w in (*_CONDITION_WORDS, "only if"))):
            raise self.fail(f"several actions before {self.here()}: it is not clear which of them the "
                            f"condition "
                            f"is about; give the condition its own sentence ('If ..., ...')")
        if self.at_any(_ONLY_AFTER):
            self.i += 2
            self.skip_subject()
            before = Clause(steps=self.action())
            self.expect_end()
            return self.only_after(before, body)
        whenever = self.at_any(_WHENEVER)
        if whenever is not None:
            self.i += len(whenever)
            trigger = self.trigger()
            if joined and self.word() in (",", "then") and self.word(1):
                self.expect_comma_or_then()
                self.soft_scope = self.rooms_of(trigger.members)
                consequent = self.consequent()
                rules = self.more_conditions(self.whenever(trigger, consequent))
                self.expect_end()
                return conj([self.require(body, "before the condition"), rules])
            rules = self.more_conditions(self.whenever(trigger, body))
            self.expect_end()
            return rules
        if self.at("only", "if"):
            self.i += 2
            condition, _ = self.condition()
            self.expect_end()
            return Implies(self.require(body, "before 'only if'"), condition)
        cond_word = next((w for w in _CONDITION_WORDS if self.at(*w.split())), None)
        if cond_word is not None:
            self.i += len(cond_word.split())
            start = self.i
            condition, tasks = self.condition()
            if joined and self.word() in (",", "then") and self.word(1):
                said_ever = self.says(_EVER, start, self.i)
                self.expect_comma_or_then()
                self.soft_scope = self.rooms_of([m for t in tasks for m in t.members])
                start = self.i
                consequent = self.consequent()
                response = said_ever or self.says(_AFTERWARDS, start, self.i)
                rule = self.conditional(cond_word, condition, tasks, consequent, response)
                rules = self.more_conditions(rule)
                self.expect_end()
                return conj([self.require(body, "before the condition"), rules])
            response = self.says(_EVER, start, self.i) or self.says(_AFTERWARDS, 0, start)
            rules = self.more_conditions(self.conditional(cond_word, condition, tasks, body, response))
            self.expect_end()
            return rules
        raise self.fail(f"cannot understand {self.here()}")

    def require(self, clause: Clause, where: str) -> Formula:
        f = clause.formula()
        if f is None:
            raise self.fail(f"nothing to do {where}")
        return f

    def expect_comma_or_then(self) -> None:
        if self.word() == ",":
            self.i += 1
        if self.word() == "then":
            self.i += 1

    def expect_end(self) -> None:
        self.skip_fillers()
        if not self.done():
            raise self.fail(f"cannot understand {self.here()}")

    def only_after(self, before: Clause, body: Clause) -> Formula:
        """``Only after X, visit Y``: Y is visited, and not before X is (``!Y U X`` for each part of X)."""
        prior = [t for step in before.steps for t in step]
        goals = [t for step in body.steps for t in step]
        if not prior or not goals or len([s for s in body.steps if s]) > 1:
            raise self.fail("'only after X, ...' needs one condition and one step after the comma")
        self.check_restriction_target(goals)
        parts: list[Formula] = [f for t in goals for f in _goal_eventually(t)]
        forbidden = conj([Not(m) for t in goals for m in t.members])
        for t in prior:
            if t.mode == "any":
                parts.append(Until(forbidden, disj(t.members)))
            else:
                parts.extend(Until(forbidden, m) for m in t.members)
        return conj(parts + body.constraints)

    def check_restriction_target(self, goals: list[Task]) -> None:
        """*Only after X* restricting an object located by its room (*go to a TV in the living room, but only
        after the kitchen*) can mean "do not enter the living room before X" or "do not reach the TV before
        X"; the two differ, so it is refused with both phrasings, unless the room itself is a goal of the
        same step (then the room is what is restricted anyway). *only enter the living room after X* and
        *reach the TV only after X* single one out."""
        plain = {m for t in goals for m in t.members if isinstance(m, Atom)}
        for member in (m for t in goals for m in t.members if isinstance(m, And)):
            room = next(a for a in member.args if isinstance(a, Atom) and a.name.startswith("enter("))
            if room in plain:
                continue
            obj = next(a.name for a in member.args if isinstance(a, Atom) and a != room)
            named = next((np for np in reversed(self.references)
                          if np.role != "qualifier" and any(e.action == obj for e in np.entities)), None)
            entity = next(e for np in self.references for e in np.entities if e.action == obj)
            room_name = self.vocab_room_name(entity.room_key)
            thing = f"the {entity.category.replace('_', ' ')}"
            said = named.phrase if named else thing
            raise self.fail(f"'only after' about '{said}': it can mean not entering "
                            f"{room_name} before that, or not reaching {thing} before that; say 'only enter "
                            f"{room_name} after ...' or 'reach {thing} only after ...'")

    def vocab_room_name(self, room_key: str) -> str:
        """``the living room`` for the room ``room_key`` (its category), for messages."""
        room = next((e for np in self.references for e in np.entities if e.key == room_key), None)
        return f"the {room.category.replace('_', ' ')}" if room is not None else room_key

    def trigger(self) -> Task:
        """The one place of ``whenever you enter the kitchen``: a task whose members trigger the response."""
        self.skip_subject()
        if self.word() in ("not", "never"):
            raise self.fail("negative triggers ('whenever you do not ...') are not understood")
        self.in_condition = True
        tasks = [t for step in self.action() for t in step]
        self.in_condition = False
        if len(tasks) != 1:
            raise self.fail("'whenever ...' needs one room or object (or a choice of them) as its trigger")
        return tasks[0]

    def whenever(self, trigger: Task, body: Clause) -> Formula:
        """``Whenever X, Y`` / ``Y whenever X``: each time the robot is at X, Y follows (``G(X -> F Y)``, the
        finite-path response; Y may happen at X itself). Y must be goals only: a prohibition scoped to
        "whenever" is not expressible this way, so it is refused."""
        if body.constraints or any(t.avoid for step in body.steps for t in step):
            raise self.fail("'whenever X, ...' is understood with goals only (e.g. 'whenever you enter the "
                            "kitchen, open the fridge'), not with prohibitions")
        return Always(Implies(disj(trigger.members), self.require(body, "for 'whenever'")))

    def prefix_clause(self) -> Clause:
        """The clause of ``After visiting X,`` / ``Before going to Y,`` up to the comma."""
        self.skip_subject()
        steps = self.action()
        self.expect_comma_or_then()
        return Clause(steps=steps)

    def condition(self) -> tuple[Formula, list[Task]]:
        """``if you go to the kitchen``: the formula that the condition happened (F ...), and its tasks.
        One action: more ("... and open the fridge", "... after the office") is refused, not left to the
        consequent."""
        ever = self.at_any(_EVER)
        if ever is not None:  # "if at any point you ...": kept for :meth:`says`
            self.i += len(ever)
        self.skip_subject()
        if self.word() in ("not", "never"):
            raise self.fail("negative conditions ('if you do not ...') are not understood")
        self.in_condition = True
        steps = self.action()
        self.in_condition = False
        if self.word() in _CONDITION_END or self.at_any(_NEG_STARTS):
            raise self.fail(f"the condition goes on with {self.here()}; a condition is one action (e.g. 'if "
                            f"you go to the kitchen, ...')")
        f = sequence_formula(steps)
        if f is None:
            raise self.fail("the condition names no room or object")
        return f, [t for step in steps for t in step]

    def says(self, phrases: tuple[tuple[str, ...], ...], start: int, end: int) -> bool:
        """Whether one of ``phrases`` occurs among the tokens ``[start, end)`` of this sentence."""
        return any(self.at(*p, k=j - self.i) for j in range(start, end) for p in phrases
                   if j + len(p) <= end)

    def conditional(self, word: str, condition: Formula, tasks: list[Task], body: Clause,
                    response: bool) -> Formula:
        """``if X, Y``: ``F X -> Y``. When the antecedent says *ever* / *at any point* or the consequent
        *afterwards* / *after that*, people mean a response to each visit of X, as with *whenever*
        (``G(X -> F Y)``); that needs one place as X (else it is refused rather than guessed). A bare
        ``when X, Y`` may mean either, or a plain sequence, so it is refused."""
        if not response and word == "when":
            raise self.fail("'when X, Y' can mean 'after X, Y' (in order), 'whenever X, Y' (each time) or "
                            "'if X, Y' (X at all); say which")
        if not response:
            return Implies(condition, self.require(body, "for the condition"))
        if len(tasks) != 1:
            raise self.fail("'if you ever go to X, ... afterwards' is understood with one room or object (or "
                            "a choice of them) as X")
        return self.whenever(tasks[0], body)

    def skip_subject(self) -> None:
        while self.word() in _SUBJECT_FILLERS and not self.np_starts():
            self.i += 1

    def done_words(self, k: int = 0) -> int:
        """How many words at offset ``k`` say the previous step is over: ``once you're done``, ``when you
        have finished``, ``after that is done`` (0 if they do not). ``with X`` after them is not counted."""
        if self.word(k) not in ("once", "when", "after"):
            return 0
        n = 1
        while self.word(k + n) in _SUBJECT_FILLERS | {"that", "this", "are", "all", "both", "of", "them"}:
            n += 1
        return n + 1 if self.word(k + n) in _DONE else 0

    def done_sequence(self) -> bool:
        """``once you're done (with that) (,)``: consumed when it refers back to the previous step (a
        sequence word then); not when it names what is done (``when done with the garage``)."""
        n = self.done_words()
        if not n:
            return False
        back = ("that", "this", "it", "them", "everything", "there")
        if self.word(n) == "with" and (self.word(n + 1) not in back or self.np_starts(n + 2)):
            return False
        k = n + 1 if self.word(n) == "with" else n
        self.i += k + (1 if self.word(k) in back else 0)
        return True

    def previous_step(self, clause: Clause) -> Step:
        """The last step with goals, in this clause or the sentence before (what *that* in *before you have
        done that* refers to); refused when there is none."""
        for step in reversed(clause.steps):
            if step:
                return step
        if self.last_step:
            return self.last_step
        raise self.fail("'done that' does not refer to any goal named before it")

    # -- sentence bodies -----------------------------------------------------------------------------
    def body(self) -> Clause:
        clause = Clause()
        while not self.done():
            if self.after_all(clause):  # "..., and after all three, go to X": after every goal so far
                if clause.steps[-1]:
                    clause.steps.append([])
                continue
            if self.at_any(_STRICT_SEQ) is not None and self.skip_fillers(sequence_too=True):
                if clause.steps[-1]:
                    clause.steps.append([])
                continue
            if self.word() in ("but", "and", ",") and self.at_any(_ONLY_AFTER, k=1):
                self.i += 1  # "..., but only after X" / "..., but not before X"
            done = self.done_words()
            if done and self.word(done) == "with" and self.np_starts(done + 1):  # "... when done with X"
                self.i += done + 1
                clause.steps[-1:-1] = [t for t in self.action() if t]
                continue
            way = self.at_any(_ON_THE_WAY, k=1 if self.word() in ("and", ",") else 0)
            if (done or way) and self.skip_fillers(sequence_too=True):
                if clause.steps[-1]:
                    clause.steps.append([])
                continue
            if (self.at("only", "if") or any(self.at(*w.split()) for w in _CONDITION_WORDS)
                    or self.at_any(_ONLY_AFTER) or self.at_any(_WHENEVER)
                    or (self.only_verb and self.word() in ("after", "once"))):
                break
            if self.word() in ("after", "afterwards", "afterward") and self.word(1) in ("", ","):
                self.i += 1  # "..., go to the dining room after."
                continue
            if any(clause.steps) and (self.word() in _FIRST or self.at("before", "that")):
                self.goals_first(clause)
                continue
            if self.word() == "," and any(clause.steps[-1]) and self.comma_sequence():
                self.i += 1  # "go to the kitchen, pop up to the bedroom, then ...": one after the other
                self.carried_rooms = self.step_rooms(clause.steps[-1])
                clause.steps.append([])
                continue
            before = self.i
            if self.skip_fillers(sequence_too=True):
                if clause.steps[-1]:
                    clause.steps.append([])
                continue
            if self.done():
                break
            if self.i > before:
                continue  # look again at what follows the fillers
            if self.stay_on_floor(clause) or self.off_limits(clause):
                continue
            nested = self.verbs_before_neither()
            if nested:  # "go to neither A nor B": the verb says nothing, the negation is all
                self.i += nested
            neg = self.at_any(_NEG_STARTS)
            if neg is not None:
                self.negation(neg, clause)
            elif self.word() in ("after", "once") and not self.at("after", "that"):
                self.i += 1
                self.skip_subject()
                clause.steps[-1:-1] = [t for t in self.action() if t]
            elif self.word() == "before":
                self.i += 1
                self.skip_subject()
                clause.steps.extend(self.action())
                clause.steps.append([])
            elif self.at_any(_WAYPOINT, k=1 if self.word() == "," else 0) and any(clause.steps[-1]):
                self.waypoint(clause)
            elif self.word() in ("and", "but", "or", "while", "as"):
                if self.word() == "or":
                    raise self.fail(f"'or' between actions is not understood at {self.here()} "
                                    "(say 'visit A or B' with one verb)")
                self.i += 1
            else:
                if self.word() in lx.REFUSED_VERBS:
                    raise self.fail(f"cannot understand {lx.REFUSED_VERBS[self.word()]}")
                # "go to the bedroom, but stop by the couch first": a step moved before the others is
                # not in their room
                self.actions += 1
                later = self.moved_first() or self.goes_back()  # nor is "come back to X" (after them)
                context = [] if later else self.step_rooms(clause.steps[-1])
                # "go to the kitchen, take a bottle, then ...": the kitchen's bottle if it has one
                self.lenient_scope = not context and bool(self.carried_rooms) and not later
                steps = self.action(step_rooms=context or (self.carried_rooms if self.lenient_scope else []))
                self.lenient_scope, self.carried_rooms = False, []
                if self.strict_pending:
                    self.check_restriction_target(steps[0])
                    for task in steps[0]:
                        task.strict = True
                    self.strict_pending = False
                if self.waypoint_pending or self.on_the_way_after():
                    self.waypoint_pending = False
                    self.insert_on_the_way(clause, steps)
                    continue
                self.check_revisits(steps[0], self.prior_steps + clause.steps[:-1])
                before_that = self.at("before", "that") and self.word(2) in ("", ",", "and", "then")
                if self.word() in _FIRST or before_that:  # "go to B, but go to A first / before that"
                    if before_that and len([s for s in clause.steps if s]) > 1:
                        raise self.fail(f"'before that' at {self.here()}: it is not clear which of the "
                                        f"earlier goals this comes before; put the goals in the order they "
                                        f"must be done")
                    self.i += 2 if before_that else 1
                    self.skip_of_all()
                    if any(clause.steps):
                        clause.steps[0:0] = [s for s in steps if s]
                        continue
                    if self.done() and self.last_step:  # "Go to B. Go to A first.": before which goal?
                        raise self.fail("a trailing 'first' in a later sentence: start the sentence with "
                                        "'Before that' or put the goals in the order they must be done")
                    clause.steps[-1].extend(steps[0])  # "go to A first and (then) B": A, then the rest
                    clause.steps.extend(steps[1:] + [[]])
                    continue
                if self.said_last:  # "... and the office last": after everything else said
                    self.skip_fillers()
                    if not self.done():
                        raise self.fail(f"'last' followed by {self.here()}: put the goals in the order they "
                                        f"must be done (with 'then'), or say 'finally'")
                    clause.steps[-1].extend(steps[0])
                    clause.steps.extend([*steps[1:], []])
                    continue
                if self.going_back and any(clause.steps[-1]):
                    clause.steps.append([])  # "go to the kitchen and come back to the couch": after it
                clause.steps[-1].extend(steps[0])
                if len(steps) > 1:
                    clause.steps.extend(steps[1:])
        return clause

    def after_all(self, clause: Clause) -> bool:
        """Reads *(and / ,) after all three / after all of them / once you've done those (,)* after goals
        of this sentence: what follows comes after every one of them (as a new step). Refused when the
        number said is not the number of goals, or when an earlier sentence named goals too (all of which
        ones?)."""
        k = 2 if self.at(",", "and") else 1 if self.word() in (",", "and") else 0
        phrase = self.at_any(_AFTER_ALL, k=k)
        if phrase is None:
            return False
        n = len(phrase)
        said = self.word(k + n) if self.word(k + n) in lx.NUMBER_WORDS else None
        n += 1 if said is not None else 0
        n += 2 if self.at("of", "them", k=k + n) or self.at("of", "those", k=k + n) else 0
        if said is None and n == len(phrase) and phrase[-1] in ("all", "both") and self.np_starts(k + n):
            return False  # "after all the bedrooms": an ordinary noun phrase
        text = self.span_text(self.toks[self.i + k].start, self.toks[self.i + k + n - 1].end)
        goals = sum(len(t.members) if t.mode == "all" else 1 for step in clause.steps for t in step)
        if not goals:
            return False
        start = self.toks[0].start
        if any(r.role == "goal" and r.start < start for r in self.references):
            raise self.fail(f"'{text}': after the goals of this sentence only, or of the whole mission? Say "
                            f"'then' and name what comes after what")
        if said is not None and lx.NUMBER_WORDS[said] != goals:
            raise self.fail(f"'{text}': this sentence names {goals} goals before it, not "
                            f"{lx.NUMBER_WORDS[said]}")
        self.i += k + n + (1 if self.word(k + n) == "," else 0)
        return True

    def comma_sequence(self) -> bool:
        """At a comma between two actions (``go to the kitchen, pop up to the bedroom, then ...``): whether
        a *then* / *finally* / *after that* follows later in the sentence, which makes the comma-joined
        actions a sequence too, as people write them."""
        nxt = self.word(1)
        if not nxt.isalpha() or self.np_starts(1) or nxt in _STRUCTURAL \
                or (nxt in lx.FILLERS and nxt not in lx.POSITIVE_VERBS) \
                or nxt in lx.REFUSED_VERBS or self.at_any(_NEG_STARTS, k=1) or self.at_any(_WAYPOINT, k=1):
            return False
        for j in range(self.i + 1, len(self.toks)):
            if self.toks[j].text in ("if", "whenever", "until", "unless", "when", "while", "order",
                                     "whichever"):
                return False  # a condition, or "(in any order)" / "whichever first": not a sequence
            if self.at_any(_THEN_NEXT, k=j - self.i) and (j == 0 or self.toks[j - 1].text in (",", "and")):
                return True
        return False

    def goes_back(self) -> bool:
        """Whether the verb words starting here say *back* / *return* ("come back to the couch")."""
        n = 0
        while self.word(n) in lx.POSITIVE_VERBS | lx.REVISIT_VERBS:
            if self.word(n) in lx.REVISIT_VERBS:
                return True
            n += 1
        return False

    def moved_first(self) -> bool:
        """Whether the action starting here ends with *first* / *before that* / *on the way* (looked ahead,
        up to the next comma, *then* or *but*): it is then done before the step it is written after."""
        for j in range(self.i, len(self.toks)):
            w = self.toks[j].text
            if w in _FIRST or (w == "before" and self.word(j - self.i + 1) == "that"):
                return True
            way = self.at_any(_ON_THE_WAY, k=j - self.i)
            if way is not None and self.word(j - self.i + len(way)) in ("", ",", "there", "and", "then"):
                return True  # "check the couch on the way": before the step
            if w in (",", "then", "but", "after", "before", "if", "until", "when", "whenever"):
                return False
        return False

    def on_the_way_after(self) -> bool:
        """``stop at X on the way (there)`` / ``on your way``, ending the action: consumed, True."""
        way = self.at_any(_ON_THE_WAY)
        if way is None:
            return False
        n = len(way) + (1 if self.word(len(way)) == "there" else 0)
        if self.word(n) not in ("", ",", "and", "then"):
            return False
        self.i += n
        return True

    def insert_on_the_way(self, clause: Clause, steps: list[Step]) -> None:
        """Put ``steps`` (said *on the way*) right before the goal named last, in this sentence or the one
        it continues; refused when that goal is not one place (on the way to which?)."""
        new = [s for s in steps if s]
        for holder in (clause.steps, self.prior_steps):
            filled = [k for k, s in enumerate(holder) if s]
            if filled:
                k = filled[-1]
                if len(holder[k]) != 1 or (self.prior_steps is holder and clause.steps != [[]] and any(
                        clause.steps)):
                    raise self.fail("'on the way' after several goals: it is not clear on the way to which; "
                                    "put the goals in the order they must be done (with 'then')")
                holder[k:k] = new
                return
        raise self.fail("'on the way' needs the goal it is on the way to, named before it")

    def waypoint(self, clause: Clause) -> None:
        """``go to Y via X`` / ``..., passing through X``: X on the way, before the one goal Y just named."""
        if self.word() == ",":
            self.i += 1
        self.i += len(self.at_any(_WAYPOINT) or ())
        if len(clause.steps[-1]) != 1:
            raise self.fail(f"it is not clear which of the goals {self.here()} is on the way to; say 'go to "
                            f"X, then Y'")
        target = clause.steps.pop()
        clause.steps.extend([t for t in self.action() if t])
        clause.steps.extend([target, []])

    def skip_of_all(self) -> None:
        if self.at("of", "all"):
            self.i += 2

    def goals_first(self, clause: Clause) -> None:
        """``..., but first (go to) X`` / ``..., and before that X``: X's steps come before the clause's.
        *before that* after several steps is ambiguous (before which?) and refused."""
        before_that = self.at("before", "that")
        if before_that and len([s for s in clause.steps if s]) > 1:
            raise self.fail(f"'before that' at {self.here()}: it is not clear which of the earlier goals "
                            f"this comes before; put the goals in the order they must be done (with 'then')")
        self.i += 2 if before_that else 1
        self.skip_of_all()
        if self.word() == ",":
            self.i += 1
        self.skip_subject()
        steps = self.action()
        clause.steps[0:0] = [s for s in steps if s]

    def check_revisits(self, step: Step, earlier: list[Step]) -> None:
        """A new visit ("again", "go back to", "return to") must follow an earlier step of the same sequence
        that went there; otherwise nothing orders the two visits and the mission would be misread."""
        done = [m for s in earlier for t in s for m in t.members]
        tasks = [t for s in earlier for t in s]
        for task in step:
            if task.revisit and not all(m in done or any(self.task_is_in(t, m) for t in tasks)
                                        for m in task.members):
                raise self.fail("'again' / 'back to' needs the first visit earlier in the same sequence "
                                "(e.g. 'go to the kitchen, then the bedroom, then back to the kitchen')")

    def task_is_in(self, task: Task, room: Formula) -> bool:
        """Whether doing ``task`` means being in ``room`` (an ``enter(...)`` atom): each of its members is
        that room or an object in it (an object is reached only from its room)."""
        if not isinstance(room, Atom) or not room.name.startswith("enter("):
            return False
        key = room.name[len("enter("):-1]

        def inside(member: Formula) -> bool:
            names = [a.name for a in (member.args if isinstance(member, And) else (member,))
                     if isinstance(a, Atom)]
            return any(n == room.name
                       or (n.startswith("reach(") and self.vocab.by_key[n[len("reach("):-1]].room_key == key)
                       for n in names)
        return all(inside(m) for m in task.members)

    def step_rooms(self, step: Step) -> list[Entity]:
        """Rooms the current step sends the robot to: context for the objects named next."""
        keys = [a.name[len("enter("):-1] for t in step for m in t.members
                for a in (m.args if isinstance(m, And) else (m,))
                if isinstance(a, Atom) and a.name.startswith("enter(")]
        return [self.vocab.by_key[k] for k in dict.fromkeys(keys)] + self.sentence_scope

    def negation(self, marker: tuple[str, ...], clause: Clause, said_whole: bool = False) -> None:
        """``always avoid X`` / ``never enter X`` (global: G !X), ``avoid X`` after an action (local),
        ``don't enter X until Y`` (``!X U Y``). ``said_whole``: for the whole mission whatever came
        before (``stay on the top floor and off the stairs``)."""
        self.i += len(marker)
        if self.at(",", "ever"):  # "never, ever"
            self.i += 1
        if self.word() == "ever":  # "never ever", "don't ever"
            self.i += 1
        if self.stay_on_floor(clause, negated=True):  # "don't leave this floor"
            return
        has_goal = any(clause.steps)
        is_global = said_whole or bool(_GLOBAL_NEG & set(marker)) or not has_goal
        if set(self.verb_words()) & lx.REVISIT_VERBS:  # "never go back to X": only after a first visit
            raise self.fail("'never go back / return to X' (after a first visit) is not understood; say "
                            "'never enter X' for the whole mission")
        rooms = self.step_rooms(clause.steps[-1]) if not is_global else self.sentence_scope
        if self.pending_floor is not None and not self.np_starts():  # "never go upstairs": any room there
            first = self.toks[self.i - 1]
            nps = [self.floor_place(first, self.pending_floor, "all", "avoid")]
            self.pending_floor = None
        else:
            nps = self.noun_phrase_list("avoid", rooms)
        entities = [e for np in nps for e in np.entities]
        forbidden = conj([Not(Atom(e.action)) for e in entities])
        self.skip_particles()
        whole = self.at_any(lx.WHOLE_MISSION)
        if whole is not None:  # "avoid the office the whole time"
            self.i += len(whole)
            is_global = True
        if (self.word() in ("after", "once", "when", "during", "afterwards", "afterward", "later", "again")
                or self.at("from", "then") or self.at("from", "now")):
            raise self.fail(f"a prohibition for part of the mission ({self.here()}) is not understood; say "
                            f"'never enter X' (the whole mission) or 'do not enter X until ...'")
        if self.word() in ("until", "before"):
            self.i += 1
            self.skip_subject()
            back = ("that", "this", "it", "so")
            if self.word() in _DONE and ((self.word(1) in back and not self.np_starts(2))
                                         or not self.np_starts(1)):
                self.i += 1  # "... before you've done that"
                if self.word() in back:
                    self.i += 1
                steps = [self.previous_step(clause)]
            else:
                steps = self.action()
                said_done = self.word(1) in _DONE | {"been", "visited"}
                if self.word() in ("is", "are", "has", "have") and said_done:
                    self.i += 2  # "until both bathrooms are done"
                    if self.word() in ("visited", "checked", "cleaned"):
                        self.i += 1
            tasks = [t for s in steps for t in s]
            if len(tasks) > 1 and all(t.mode == "all" for t in tasks):  # "until A and B": each of them
                tasks = [Task("all", [m for t in tasks for m in t.members])]
            if len(tasks) != 1:
                raise self.fail("'... until X' needs one goal X")
            t = tasks[0]
            targets = [disj(t.members)] if t.mode == "any" else t.members
            clause.constraints.extend(Until(forbidden, m) for m in targets)
            if not any(clause.steps) and not self.prior_steps:
                # "Keep out of X until you have seen Y, then Z": Y (which the until requires) is the step
                # that *then* follows
                clause.steps[-1].append(Task(t.mode, list(t.members)))
        elif is_global:
            clause.constraints.append(Always(forbidden))
        else:
            target = [t for s in clause.steps for t in s][-1]
            local, everywhere = self.avoidance_scope(target, entities)
            target.avoid.extend(Not(Atom(e.action)) for e in local)
            if everywhere:
                clause.constraints.append(Always(conj([Not(Atom(e.action)) for e in everywhere])))

    def verbs_before_neither(self) -> int:
        """How many verb words come before a *neither* here ("go to neither A nor B"), 0 if none do."""
        n = 0
        while self.word(n) in lx.POSITIVE_VERBS:
            n += 1
        return n if n and self.word(n) == "neither" else 0

    def off_limits(self, clause: Clause) -> bool:
        """``The kitchen is off limits`` / ``the office and the garage are out of bounds``: ``G !x`` for each
        (consumed, True); False (nothing consumed) when the sentence does not say that."""
        if not self.np_starts():
            return False
        save, known = self.i, len(self.references)
        try:
            nps = self.noun_phrase_list("avoid", [])
        except MissionError:
            nps = []
        said = self.at_any(_OFF_LIMITS) if nps else None
        if said is None and nps and self.word() in _COPULAS:
            raise self.fail(f"'{self.span_text(nps[0].start, self.toks[self.i].end)} ...' states something; "
                            f"it is not understood as a goal or a prohibition (say what to do, e.g. 'go to "
                            f"...', 'never enter ...', '... is off limits')")
        if said is None:
            del self.references[known:]
            self.i = save
            return False
        self.i += len(said)
        whole = self.at_any(lx.WHOLE_MISSION)
        if whole is not None:
            self.i += len(whole)
        clause.constraints.append(Always(conj([Not(Atom(e.action)) for np in nps for e in np.entities])))
        return True

    def stay_on_floor(self, clause: Clause, negated: bool = False) -> bool:
        """``stay on this floor`` / ``stay on the ground floor`` / ``stay downstairs`` / ``keep to floor 1``
        (or, after a negation, ``leave this floor``): every room of the other floors is forbidden for the
        whole mission (consumed, True); False (nothing consumed) when the words are not there."""
        said = self.staying(negated)
        if said is not None and self.i and self.word(-1) in ("then", "afterwards", "later", "next",
                                                             "finally"):
            raise self.fail(f"'{self.word(-1)} {self.word()} ...': staying on a floor for the rest of the "
                            f"mission only is not understood; say 'stay on ... the whole time'")
        if said is None:
            if negated and self.word() in _LEAVE:
                raise self.fail(f"cannot understand {lx.REFUSED_VERBS['leave']}")
            return False
        floors, k, where = said
        other = self.at_any(_OTHER_FLOOR, k=where) is not None
        self.alt_floors = None  # "stay on ...": the floors said, whatever the goals before
        first, last = self.toks[self.i + where], self.toks[self.i + k - 1]
        self.i += k
        rooms = [e for e in self.vocab.entities if e.kind == "room" and e.floor not in floors]
        if not rooms:
            raise self.fail(f"'{self.span_text(first.start, last.end)}': the building has no other floor")
        # the grounded text names what the words name: the floors kept ("stay on room_9, ... room_14"), or
        # the others ("don't go to room_2, ... room_8" for "any other floor")
        named = rooms if other else [e for e in self.vocab.entities if e.kind == "room" and e.floor in floors]
        self.record(NounPhrase(self.span_text(first.start, last.end), first.start, last.end, named, "all",
                               False, "avoid" if other else "qualifier"))
        whole = self.at_any(lx.WHOLE_MISSION)
        if whole is not None:
            self.i += len(whole)
        clause.constraints.append(Always(conj([Not(Atom(e.action)) for e in rooms])))
        if self.at("and", "off") and self.np_starts(2):  # "stay on the top floor and off the stairs"
            self.i += 1
            self.negation(("off",), clause, said_whole=True)
        return True

    def staying(self, negated: bool) -> tuple[frozenset[int], int, int] | None:
        """The floors of ``stay on <floor>`` / ``stay downstairs`` (or ``leave <floor>`` after a negation)
        here, how many words say it and at which of them the floor words begin; ``None`` if the words are
        not there. Nothing is consumed."""
        if negated:  # "don't go to any other floor", "don't change floors"
            n = 0
            while self.word(n) in lx.POSITIVE_VERBS and not self.at_any(_OTHER_FLOOR, k=n):
                n += 1
            other = self.at_any(_OTHER_FLOOR, k=n)
            if other is not None:
                changed = other[0] in ("change", "switch")  # "change floors": the floors are the ones kept
                return self.start_floor_only(" ".join(other)), n + len(other), n + (1 if changed else 0)
        if self.word() not in (_LEAVE if negated else _STAY):
            return None
        k = 1
        if self.word(k) in lx.RELATIVE_FLOORS and not negated:
            return self.staying_floors(self.word(k)), k + 1, k
        if self.word(k) in ("on", "to", "at", "in", "within") and not negated:
            k += 1
        where = k
        k += 1 if self.word(k) == "the" else 0
        if self.word(k) == "same" and self.word(k + 1) in lx.FLOOR_WORDS:  # "stay on the same floor"
            return self.start_floor_only(f"the same {self.word(k + 1)}"), k + 2, where
        said = self.floor_words(k)
        if said is None or self.vocab.match_head(self.words(), self.i + k + said[1]) is not None:
            return None  # not a floor, or "stay on the ground floor bathroom"
        return said[0], k + said[1], where

    def start_floor_only(self, said: str) -> frozenset[int]:
        """The start floor, for *stay on the same floor* / *don't go to any other floor*; refused when it is
        not known."""
        if self.start_floor is None:
            raise self.fail(f"'{said}' depends on where the robot starts, which is not known here; say which "
                            f"floor to stay on (the building {self.vocab.building_name!r} has floors 0 to "
                            f"{self.vocab.num_floors - 1})")
        return frozenset({self.start_floor})

    def confinement(self, sentence_tokens: list[list[Tok]]) -> frozenset[int] | None:
        """The floors the whole mission is confined to by ``stay on <floor>`` / ``don't leave <floor>``
        anywhere in it (read before the rest, so that "go to the toilet, staying on this floor" grounds
        *the toilet* on that floor); ``None`` when the mission says no such thing."""
        confined: frozenset[int] | None = None
        for sentence in sentence_tokens:
            if {t.text for t in sentence} & _TIME_SCOPED:
                continue  # "until you reach X, stay on this floor": not the whole mission
            self.toks = sentence
            for j, tok in enumerate(sentence):
                self.i = j
                negated = j > 0 and sentence[j - 1].text in ("not", "never")
                said = self.staying(negated) if tok.text in _STAY or negated else None
                if said is not None:
                    confined = said[0] if confined is None else confined & said[0]
        self.toks, self.i = [], 0
        return confined

    def staying_floors(self, word: str) -> frozenset[int]:
        """``stay downstairs`` / ``stay upstairs``: the lower / upper floor of a two-floor building, or the
        start floor when it is the lowest / highest; otherwise it is not clear which floors are meant
        (refused, naming them)."""
        floors, step = self.vocab.num_floors, lx.RELATIVE_FLOORS[word]
        extreme = 0 if step < 0 else floors - 1
        if floors == 2 or self.start_floor == extreme:
            return frozenset({extreme})
        where = "is not known here" if self.start_floor is None else f"is floor {self.start_floor}"
        raise self.fail(f"'stay {word}': the start floor {where} and the building "
                        f"{self.vocab.building_name!r} has floors 0 to {floors - 1}; say 'stay on floor k' "
                        f"or 'never go to floor k'")

    def avoidance_scope(self, target: Task, forbidden: list[Entity]) -> tuple[list[Entity], list[Entity]]:
        """Split what a trailing *avoid* / *without* forbids into what holds when ``target`` is done (an
        object
        of a room the target is in: "visit the bathroom and avoid the sink") and what holds for the whole
        mission: a room (one room at a time makes "in the bedroom and not in the kitchen" say nothing, so
        "go to the bedroom while avoiding the kitchen" means never entering it), or an object elsewhere."""
        keys = [action_entity(a) for m in target.members for a in atoms(m)]
        rooms = {self.vocab.by_key[k].room_key for k in keys if k in self.vocab.by_key}
        local = [e for e in forbidden if e.kind == "object" and e.room_key in rooms]
        return local, [e for e in forbidden if e not in local]

    # -- actions -------------------------------------------------------------------------------------
    def verb_words(self) -> list[str]:
        """Words before the noun phrase: the verb, whatever it is, unless it is refused or a word of the
        grammar itself (``always``, ``floor``, ``next`` ... out of place are errors, not verbs)."""
        seen: list[str] = []
        while not self.done() and (not self.np_starts() or self.verb_idiom()) \
                and self.word() not in (",", "and", "or", "then",
                                                                              "if", "until", "before",
                                                                              "after", "when", "without"):
            w = self.word()
            if self.pending_floor is not None and (self.at_any(lx.WHOLE_MISSION)
                                                   or self.at_any(lx.TIME_FILLERS)):
                break  # "don't go downstairs at any point"
            idiom = self.verb_idiom()
            if idiom:  # "go all the way up to", "take a look at", "wash your hands at": part of the verb
                seen += [t.text for t in self.toks[self.i : self.i + idiom]]
                self.i += idiom
                continue
            if w in lx.REFUSED_VERBS:
                raise self.fail(f"cannot understand {lx.REFUSED_VERBS[w]}")
            ends = self.word(1) in ("in", "at", "up", "with")
            if w in lx.START_END_VERBS and ends and not self.in_condition:
                raise self.fail(f"'{w} {self.word(1)} ...': where the path starts or ends cannot be "
                                f"required; put the goals in order with 'then'")
            if w in ("do", "does", "did", "doing") and self.word(1) in ("it", "that", "this", "so"):
                raise self.fail(f"'{w} {self.word(1)}' refers to what was done, not to a place; name the "
                                f"rooms or objects again")
            if w in _MODALS and self.word(1) not in ("not", "never"):
                seen.append(w)  # "may you go into ...", "I do want you to visit ...": no negation
                self.i += 1
                continue
            if self.at_any(_NEG_STARTS) is not None:
                break
            offset = self.floor_offset()
            if offset is None and w in ("up", "down"):  # "go down two floors", "go up a floor"
                turned = self.floor_count(1)
                if turned is not None and self.word(2) in _FLOOR_PLURALS:
                    offset = self.shifted_floor(turned * _FLOOR_DIRECTIONS[w], f"{w} {self.word(1)} "
                                                f"{self.word(2)}"), 3
            if offset is not None:  # "go two floors down to the garage": the garage on that floor
                self.pending_floor = offset[0]
                self.i += offset[1]
                continue
            if w in lx.RELATIVE_FLOORS:  # "go upstairs to the bathroom": the bathroom on that floor
                self.pending_floor = self.relative_floor(w)
            elif w not in lx.POSITIVE_VERBS and (w in _STRUCTURAL or not w.isalpha()):
                raise self.fail(f"cannot understand '{w}' in {self.here()}")
            seen.append(w)
            self.i += 1
        return seen

    def floor_move(self, nps: list[NounPhrase]) -> bool:
        """``go (up) to the top floor and <action>`` / ``..., then <action>``: the floor is where the next
        action is done, not a goal of its own (read as one, "and check a bathroom" would be any bathroom of
        the building). When ``nps`` is one floor followed by a connective and a positive action, the
        connective is consumed, the next noun phrase is put on that floor and True is returned; the floor
        stays recorded, so *there* / *up there* / *on that floor* in that action mean it."""
        if len(nps) != 1 or not nps[0].floor or nps[0].role != "goal":
            return False
        k = 0
        while self.word(k) in (",", "and", "then"):
            k += 1
        if k == 0 or not (self.word(k) in lx.POSITIVE_VERBS or self.np_starts(k)):
            return False
        self.i += k
        return True

    def moved(self, floors: frozenset[int], step_rooms: list[Entity] | None) -> list[Step]:
        """The action after a floor move (*go upstairs and ...*, *go to floor 1, then ...*): every goal of
        it on ``floors`` (:attr:`action_floor`)."""
        if self.done():
            raise self.fail("expected an action after the floor to go to")
        self.action_floor = (floors, self.toks[self.i].start)
        return self.action(step_rooms)

    def rooms_of(self, members: list[Formula]) -> list[Entity]:
        """The rooms that the state formulas ``members`` put the robot in (their own or their objects')."""
        keys = [action_entity(a) for m in members for a in atoms(m)]
        rooms = dict.fromkeys(self.vocab.by_key[k].room_key for k in keys if k in self.vocab.by_key)
        return [self.vocab.by_key[k] for k in rooms]

    def verb_idiom(self) -> int:
        """How many words here belong to the verb although they look like a noun phrase: ``all the way``,
        ``a look`` / ``your way`` (*take a look at*, *make your way to*), or a body part before a place
        (*wash your hands at the sink*); 0 if none."""
        idiom = self.at_any(_VERB_IDIOMS)
        if idiom is not None:
            return len(idiom)
        if (self.word() in ("your", "my", "his", "her", "their") and self.word(1).isalpha()
                and self.vocab.match_head(self.words(), self.i + 1) is None
                and self.word(2) in ("at", "using", "with", "on") and self.np_starts(3)):
            return 2
        return 0

    def relative_floor(self, word: str, candidates: list[Entity] | None = None) -> frozenset[int]:
        """The floors *upstairs* / *downstairs* mean: those above / below the start floor when it is known;
        in a two-floor building, the upper / lower floor; for a noun ("the downstairs bathroom",
        ``candidates`` = the bathrooms) whose candidates lie on exactly two floors, the lower / upper of
        those, as people name such rooms whatever floor they stand on; otherwise it is refused, naming the
        floors."""
        step = lx.RELATIVE_FLOORS[word]
        floors = self.vocab.num_floors
        on = sorted({e.floor for e in candidates or []})
        if self.start_floor is None and floors > 2 and len(on) == 2:
            return frozenset({on[1] if step > 0 else on[0]})
        if self.start_floor is not None:
            self.check_still_on_start_floor(
                word, lambda base: frozenset(f for f in range(floors) if (f - base) * step > 0))
            wanted = frozenset(f for f in range(floors) if (f - self.start_floor) * step > 0)
            if not wanted:
                raise self.fail(f"'{word}': the robot starts on floor {self.start_floor} and the building "
                                f"{self.vocab.building_name!r} has floors 0 to {floors - 1}")
            return wanted
        if floors == 2:
            return frozenset({1 if step > 0 else 0})
        listing = "floor 0" if floors == 1 else f"floors 0 to {floors - 1}"
        raise self.fail(f"'{word}' depends on where the robot starts, which is not known here; say which "
                        f"floor (the building {self.vocab.building_name!r} has {listing})")

    def action(self, step_rooms: list[Entity] | None = None) -> list[Step]:
        """Verb words and noun phrases -> one or more steps (``put X in Y``, ordered lists give more)."""
        verbs = self.verb_words()
        self.going_back = bool(set(verbs) & lx.REVISIT_VERBS)
        if not self.np_starts() and self.pending_floor is not None and self.word() in ("and", ",", "then"):
            self.i += 1  # "go upstairs and check the laptop": the laptop upstairs
            return self.moved(self.pending_floor, step_rooms)
        if not self.np_starts():
            what = f"after '{' '.join(verbs)}'" if verbs else "here"
            raise self.fail(f"expected a room or object {what}, found {self.here()}")
        scope = list(step_rooms or []) or self.sentence_scope
        carry = bool(set(verbs) & lx.CARRY_VERBS)
        nps = self.noun_phrase_list("goal", scope, "object" if carry else None)
        self.action_floor = None
        if self.floor_move(nps):  # "go up to the top floor and check a bathroom (there)": one goal there
            return self.moved(frozenset(e.floor for e in nps[0].entities), step_rooms)
        first = self.word() in _FIRST
        nps = self.first_of_list(nps)
        lead = first and self.word() not in _FIRST  # "A and B, B first": B, then A
        self.choice_affirmed(nps)
        comma = 1 if self.word() == "," else 0
        ordered = self.at_any(lx.ORDER_MODIFIERS, k=comma)
        if ordered:
            self.i += comma + len(ordered)
        elif self.comma_list and len(nps) > 1 and self.at_any(_THEN_NEXT, k=comma):
            ordered = ("then",)  # "the fridge, the oven, then the couch": one after the other, as written
        pronoun_only = all(np.phrase.lower() in lx.PRONOUNS for np in nps)
        # "put it in Y": the object is already in hand, the goal is Y, after what came before.
        steps: list[Step] = [[]] if carry and pronoun_only else self.tasks_of(nps, ordered is not None)
        if lead:
            steps = [steps[0][:1], steps[0][1:]]
        if self.word() in ("last", "lastly") and self.word(1) in ("", ",") and len(steps) == 1:
            self.i += 1  # "the kitchen and the office last": the office after the rest
            self.said_last = True
            steps = [steps[0][:-1], steps[0][-1:]]
        self.revisits(nps, steps, verbs)
        self.skip_particles()
        # "put X in Y", "take X to Y", "go from X to Y", and any object followed by "to Y": X, then Y.
        carried = carry or (self.word() in ("to", "into", "onto") and (
            set(verbs) & {"from", "through", "via", "past"}
            or all(e.kind == "object" for np in nps for e in np.entities)))
        if carried and self.word() in ("in", "into", "on", "onto", "to", "inside") and self.np_starts(1):
            self.i += 1
            dest = self.noun_phrase_list("goal", [])
            steps.extend(self.tasks_of(dest, False))
        self.skip_particles()
        if self.word() == "to" and not self.np_starts(1):
            self.i += 1  # purpose clause: "... to turn them off"
            purpose_verbs = self.verb_words()
            if self.np_starts():
                purpose = self.noun_phrase_list("goal", list(scope))
                if not all(np.phrase.lower() in lx.PRONOUNS for np in purpose):
                    steps[-1].extend(self.tasks_of(purpose, False)[0])
                self.skip_particles()
            elif not purpose_verbs:
                raise self.fail(f"cannot understand {self.here()}")
        if self.word() == "there":  # "look at the TV there": where the step is
            self.i += 1
        if self.at_any(lx.TIME_FILLERS):
            self.i += len(self.at_any(lx.TIME_FILLERS) or ())
        return steps or [[]]

    def affirmation_ahead(self) -> tuple[str, ...] | None:
        """The words of ``(,) either one is fine`` / ``, any one will do`` / ``, whichever`` right here (a
        remark that the choice is the robot's), or ``None``; nothing is consumed."""
        comma = 1 if self.word() == "," else 0
        said = self.at_any(lx.CHOICE_AFFIRMATIONS, k=comma)
        time = self.at_any(lx.TIME_FILLERS, k=comma)  # "whichever first" is about the order
        if said is None or (said == ("is", "fine") and comma) or (time is not None
                                                                  and len(time) >= len(said)):
            return None
        return (",",) * comma + said

    def choice_affirmed(self, nps: list[NounPhrase]) -> None:
        """Consume ``, either one is fine`` / ``, any of them`` after a choice (a singular definite phrase
        matching several, "the toilet on this floor, any one will do", was made a choice by :meth:`check`);
        refused after a phrase that means each of several (the remark would turn "all" into "one of"), or
        after several phrases."""
        said = self.affirmation_ahead()
        if said is None:
            return
        comma = 1 if said[0] == "," else 0
        said = said[comma:]
        if len(nps) > 1 or (nps[0].mode != "any" and len(nps[0].entities) > 1):
            raise self.fail(f"'{' '.join(said)}' after '{self.span_text(nps[0].start, nps[-1].end)}', which "
                            f"means each of them: say 'any of ...' or 'A or B' for a choice")
        self.i += comma + len(said)

    def first_of_list(self, nps: list[NounPhrase]) -> list[NounPhrase]:
        """``A and B, B first``: the list with B moved to the front and once only (*first* is consumed; the
        caller orders it before the rest). Any other phrase named twice in one list is refused: it is not
        clear what is meant."""
        keys = [frozenset(e.key for e in np.entities) for np in nps]
        # "the chairs, both of them": the second phrase only restates the first; so does "any X" after a
        # choice of the same Xs ("a TV, any TV")
        nps = [np for n, np in enumerate(nps)
               if not (n and keys[n] == keys[n - 1] and (np.phrase.lower().endswith("them")
                                                         or (np.mode == nps[n - 1].mode == "any"
                                                             and np.phrase.lower().startswith("any "))))]
        keys = [frozenset(e.key for e in np.entities) for np in nps]
        repeated = [n for n, k in enumerate(keys) if any(k & j for j in keys[:n])]
        if not repeated:
            return nps
        if repeated == [len(nps) - 1] and self.word() in _FIRST:
            self.i += 1  # "the clocks, the one in the bedroom first": that one, then the (other) clocks
            return [nps[-1]] + [np for n, np in enumerate(nps[:-1]) if keys[n] != keys[-1]]
        raise self.fail(f"'{nps[repeated[0]].phrase}' is named twice in one list")

    def revisits(self, nps: list[NounPhrase], steps: list[Step], verbs: list[str]) -> None:
        """``X again`` / ``go back to X`` / ``return to X`` (X named as a goal before): a new visit;
        ``X twice`` / ``X three times``: the visit and then new visits (see :class:`~.compose.Task`)."""
        again = self.word() == "again"
        # an object in X named as a goal before was a visit of X too ("a vase in the lobby, ..., the lobby
        # again"), when every object the phrase allowed is in X
        named_before = all(
            any(r.role == "goal" and r.start < nps[0].start
                and (e in r.entities or (e.kind == "room" and all(o.kind == "object" and o.room_key == e.key
                                                                  for o in r.entities)))
                for r in self.references)
            for np in nps for e in np.entities)
        if again:
            self.i += 1
            if not named_before:
                raise self.fail(f"'{self.span_text(nps[0].start, nps[-1].end)} again': it was not a goal "
                                f"before")
        if again or (set(verbs) & lx.REVISIT_VERBS and named_before):
            for task in steps[0]:
                task.revisit = True
        times = self.repetitions()
        between = self.in_between() if times == 2 and any(steps) else None
        if between is not None:  # "X twice, with a visit to Y in between": X, then Y, then X
            last = [t for t in steps[-1]]
            steps.extend([*between, [Task(t.mode, t.members) for t in last]])
        elif times > 1 and any(steps):
            last = [t for t in steps[-1]]
            steps.extend([Task(t.mode, t.members, [], True) for t in last] for _ in range(times - 1))

    def in_between(self) -> list[Step] | None:
        """After *twice*: ``(,) with (a trip / visit / stop) (to) Y in between`` or ``(,) visiting Y in
        between``: the steps of Y (consumed); ``None`` when the words are not there (nothing consumed)."""
        save, known = self.i, len(self.references)
        k = 1 if self.word() == "," else 0
        if self.word(k) == "with":
            k += 1
            if self.word(k) in ("a", "an") and self.word(k + 1) in _TRIP_NOUNS:
                k += 2
            elif self.word(k) in _TRIP_NOUNS:
                k += 1
        elif not self.word(k).endswith("ing") or self.word(k) in _STRUCTURAL:
            return None
        self.i += k
        try:
            steps = self.action()
        except MissionError:
            steps = []
        if any(steps) and (self.at("in", "between") or self.word() == "between"):
            self.i += 2 if self.word() == "in" else 1
            if self.at_any(_BETWEEN_TAIL):
                self.i += len(self.at_any(_BETWEEN_TAIL) or ())
            return [s for s in steps if s]
        del self.references[known:]
        self.i = save
        return None

    def repetitions(self) -> int:
        """``twice`` / ``two times`` / ``3 times`` after the noun phrases -> 2, 2, 3 (consumed); else 1."""
        if self.word() == "twice":
            self.i += 1
            return 2
        n = lx.NUMBER_WORDS.get(self.word()) or (int(self.word()) if self.word().isdigit() else None)
        if n is None or self.word(1) != "times":
            return 1
        if not 1 <= n <= 5:
            raise self.fail(f"'{self.word()} times': at most 5 repeated visits are understood")
        self.i += 2
        return n

    def skip_particles(self) -> None:
        if self.word() in _PARTICLES and (self.word(1) in ("", ",", "and", "then", "to")
                                          or self.at_any(_NEG_STARTS, k=1)):
            self.i += 1

    def tasks_of(self, nps: list[NounPhrase], ordered: bool) -> list[Step]:
        tasks = []
        for np in nps:
            if np.choice_of is not None:  # "look at a vase, then look at it again": the same vase
                raise self.fail(np.choice_of)
            members = [member_formula(e, np.room_scoped) for e in np.entities]
            tasks.append(Task("any" if np.mode == "any" else "all", members))
        if ordered and len(tasks) > 1:
            return [[t] for t in tasks]
        return [tasks]

    # -- noun phrases ---------------------------------------------------------------------------------
    def np_starts(self, k: int = 0) -> bool:
        w = self.word(k)
        if not w:
            return False
        if w.startswith(("room_", "object_")) or w in lx.PRONOUNS:
            return w != "it" or self.word(k + 1) not in ("is", "was")
        if w == "there":  # "get there": the last place named as a goal
            return self.word(k + 1) not in ("is", "are", "was", "were")
        if w in _DETERMINERS:
            nxt = self.word(k + 1)
            return (not (w == "some" and nxt == "point") and not (w == "that" and nxt == "order")
                    and self.at_any(_WHENEVER, k=k) is None)  # "every time you ...": a condition
        if w in lx.FLOOR_WORDS and (self.word(k + 1).isdigit() or self.word(k + 1) in lx.NUMBER_WORDS
                                    or self.word(k + 1) == "zero"):
            return True  # "floor 2" as a place
        if w in lx.NUMBER_WORDS or w.isdigit():
            if self.word(k + 1) in _FLOOR_PLURALS and self.word(k + 2) in _FLOOR_DIRECTIONS:
                return False  # "two floors up": where, not what
            return (w != "one" or self.word(k + 1) == "of"
                    or self.vocab.match_head(self.words(), self.i + k + 1) is not None)
        return self.vocab.match_head(self.words(), self.i + k) is not None

    def noun_phrase_list(self, role: Role, scope: list[Entity],
                         pronoun_kind: str | None = None) -> list[NounPhrase]:
        """``A, B and C`` (each) or ``A or B`` / ``either A or B`` (one of them, as one phrase)."""
        either = self.word() == "either" and self.word(1) in _DETERMINERS | {"of"} and self.word(1) != "of"
        # "go either to the couch or to the bed": the preposition is repeated after each conjunction
        repeated = (self.word() in ("either", "both") and self.word(1) in _LIST_PREPOSITIONS
                    and self.np_starts(2))
        preposition = self.word(1) if repeated else None
        either = either or (preposition is not None and self.word() == "either")
        if either or (self.word() == "both" and self.word(1) in _DETERMINERS):
            self.i += 1
        if preposition is not None:
            self.i += 1
        nps = [self.noun_phrase(role, scope, None, pronoun_kind)]
        joiners: set[str] = set()
        while True:
            if (preposition is not None and self.word() in ("and", "or") and self.word(1) == preposition
                    and self.np_starts(2)):
                joiners.add(self.word())
                self.i += 2
            elif self.word() == "," and self.word(1) in ("and", "or") and self.np_starts(2):
                joiners.add(self.word(1))
                self.i += 2
            elif (self.word() == "," and self.np_starts(1) and not self.at_any(_NEG_STARTS, k=1)
                  and not self.at_any(lx.TIME_FILLERS, k=1) and not self.at_any(lx.CHOICE_AFFIRMATIONS, k=1)):
                self.i += 1
            elif self.word() in ("and", "or", "nor") and self.np_starts(1):
                joiners.add(self.word())
                self.i += 1
            elif self.at(",", "nor") and self.np_starts(2):
                joiners.add("nor")
                self.i += 2
            elif self.at("as", "well", "as") and self.np_starts(3):
                joiners.add("and")
                self.i += 3
            else:
                break
            nps.append(self.noun_phrase(role, scope))
        self.comma_list = len(nps) > 1 and not joiners and not either
        if "nor" in joiners:
            if role != "avoid" or len(joiners) > 1:
                raise self.fail(f"'nor' in '{self.span_text(nps[0].start, nps[-1].end)}' is understood only "
                                f"in "
                                f"'never enter / neither A nor B' (each of them forbidden)")
            return nps  # "neither A nor B": each of them is forbidden
        if joiners == {"and", "or"}:
            raise self.fail(f"'{self.span_text(nps[0].start, nps[-1].end)}' mixes 'and' and 'or'; split it "
                            f"into two sentences")
        if "or" in joiners or either:
            if any(np.mode == "all" and len(np.entities) > 1 for np in nps):
                raise self.fail(f"'{self.span_text(nps[0].start, nps[-1].end)}' joins a group with 'or'; say "
                                f"'any of ...'")
            # Being at an object implies being in its room, so locating some alternatives by their room and
            # others not changes nothing: the merged phrase locates all of them.
            for np in nps:
                np.alternative = True
            merged = NounPhrase(self.span_text(nps[0].start, nps[-1].end), nps[0].start, nps[-1].end,
                                [e for np in nps for e in np.entities], "any",
                                any(np.room_scoped for np in nps), role)
            return [merged]
        return nps

    def noun_phrase(self, role: Role, scope: list[Entity] | None = None, one_head: Head | None = None,
                    pronoun_kind: str | None = None) -> NounPhrase:
        """One noun phrase, grounded; ``one_head`` is what ``the one`` means, ``pronoun_kind`` what an ``it``
        here must denote (objects, after ``put`` / ``bring``)."""
        first = self.toks[self.i] if not self.done() else None
        if first is None:
            raise self.fail("expected a room or object at the end of the sentence")
        w = self.word()
        if w == "there":
            self.i += 1
            goals = [r for r in self.references if r.role == "goal" and r.phrase.lower() not in lx.PRONOUNS]
            if not goals:
                raise self.fail("'there' does not refer to any place named before it")
            ref = max(goals, key=lambda r: r.start)
            self.determined("there", ref, len({e.room_key for e in ref.entities}))
            if role == "goal" and self.going_back:  # "A, then B, then go back there": B is where it is
                raise self.fail(f"'back there': 'there' is the place named last ('{ref.phrase}'), where the "
                                f"robot just was; name the place to go back to")
            if role != "qualifier" and ref.mode == "all" and len(ref.entities) > 1:
                raise self.fail(f"'there' refers back to '{ref.phrase}', which is several places; name the "
                                f"one meant")  # "both bedrooms, then back there": which one?
            entities = list(ref.entities)
            if role == "qualifier":  # "the clock in there": the room of the last goal
                entities = list({e.room_key: self.vocab.by_key[e.room_key] for e in entities}.values())
            return self.record(NounPhrase(w, first.start, first.end, entities, ref.mode, ref.room_scoped,
                                          role))
        group = self.all_of_them() if role == "goal" else None
        if group is not None:
            return group
        if self.at("the", "same") and self.word(2) in ("room", "place") and role == "qualifier":
            self.i += 3  # "the sink in the same room": the room of the place named last
            rooms = self.there_rooms(first.start, f"the same {self.word(-1)}")
            if len(rooms) != 1:
                raise self.fail(f"'the same {self.word(-1)}': the place named before it is "
                                f"{' or '.join(r.key for r in rooms)}; name the room")
            return self.record(NounPhrase(self.span_text(first.start, self.toks[self.i - 1].end), first.start,
                                          self.toks[self.i - 1].end, rooms, "the", False, role))
        if w == "its" and self.vocab.match_head(self.words(), self.i + 1) is not None:
            self.i += 1  # "its sink": the sink in the room just named (or in the room of the object named)
            ref = self.antecedent("it")
            container = [self.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in ref.entities)]
            self.determined("its", ref, len(container))
            head = self.head(None)
            if head.kind == "room":  # "the other bedroom and its bathroom": the bathroom attached to it
                owned = self.vocab.next_to(self.vocab.of_head(head), container)
            else:
                owned = self.vocab.inside(self.vocab.of_head(head), container)
            np = NounPhrase(self.span_text(first.start, self.toks[self.i - 1].end), first.start,
                            self.toks[self.i - 1].end, owned, "all" if head.plural else "the",
                            head.kind == "object", role)
            self.check(np, head, None)
            return self.record(np)
        if w in lx.PRONOUNS:
            self.i += 1
            ref = self.antecedent(w, pronoun_kind)
            pronoun_mode: Mode = "all" if w in ("them", "they") else ref.mode
            np = NounPhrase(self.span_text(first.start, first.end), first.start, first.end,
                            list(ref.entities),
                            pronoun_mode, ref.room_scoped, role)
            np.choice_of = backref.choice_refusal(w, ref, len(ref.entities))
            if np.choice_of is not None and role != "goal":  # only a carried goal may leave it open
                raise self.fail(np.choice_of)
            return self.record(np)
        if self.word() in ("the", "a") and self.word(1) in lx.ANAPHORIC_ONE and one_head is None:
            one_head = self.last_head()  # "the teddy bear in the bedroom, then the one in the living room"
        other = self.at("the", "other") and self.vocab.match_head(self.words(), self.i + 2) is not None
        if self.at("the", "other", "one") and one_head is None:
            one_head = self.last_head()  # "the bedroom with the book, then the other one"
            other = True
        if other:
            self.i += 1
        demo = self.demonstrative()
        mode: Mode | None
        count: int | None
        quantified: Mode | None = None
        """The quantifier before a demonstrative (*one of* / *all of those bedrooms*)."""
        pointer = self.word() if demo else ""
        if demo:  # "that bathroom", "those two bedrooms", "the same sink": resolved below, never fresh
            self.i += demo
            mode, count = "the", None
            n = self.count_word()
            if n is not None:
                mode, count = "all", n
        else:
            mode, count = self.quantifier()
            if mode is not None and self.demonstrative():  # "one of those bedrooms": chosen among them
                quantified = mode
                demo = self.demonstrative()
                pointer = self.word()
                self.i += demo
                if count is None and (n := self.count_word()) is not None:
                    count = n
        floors_first: frozenset[int] | None = None
        relative = ""
        if self.word() in lx.RELATIVE_FLOORS:  # "the upstairs bathroom": applied once the noun is read
            relative = self.word()
            self.i += 1
        elif (said := self.floor_words()) is not None:  # "the ground floor bathroom", "the top floor"
            floors_first = said[0]
            self.i += said[1]
            if self.vocab.match_head(self.words(), self.i) is None:
                return self.floor_place(first, floors_first, mode, role)
        modifier: list[Entity] = []
        if self.word().startswith(("room_", "object_")):
            key = self.word()
            if key not in self.vocab.by_key:
                raise self.fail(f"'{key}' is not a room or object of this scene")
            entities = [self.vocab.by_key[key]]
            head = Head(entities[0].kind, frozenset({entities[0].category}), False, 1)
            self.i += 1
            mode = "the"
        else:
            if other:
                self.i += 1  # "other"
            modifier = self.vocab.room_modifier(self.words(), self.i)
            if modifier:  # "the dining chairs": the chairs in the dining room
                self.i += 1
            head = self.head(one_head)
            entities = self.vocab.of_head(head)
            if modifier:
                entities = self.vocab.inside(entities, modifier)
            if mode is None:
                mode = "all" if head.plural else "the"
            elif mode == "the" and head.plural:
                mode = "all"
        if relative:
            floors_first = self.relative_floor(relative, entities)
        if other:
            entities = self.others(entities, first.start)
        if floors_first is not None:
            entities = self.on_floors(entities, floors_first)
        if self.pending_floor is not None:
            entities = self.on_floors(entities, self.pending_floor)
            self.pending_floor = None
        if self.action_floor is not None and role == "goal":  # "go upstairs and check A and B": both there
            entities = self.vocab.on_floor(entities, self.action_floor[0])
        if self.confined is not None and role in ("goal", "condition"):
            entities = self.vocab.on_floor(entities, self.confined)  # "stay on this floor": goals there
        room_scoped = bool(modifier)
        compound = head.kind == "room" and self.vocab.match_head(self.words(), self.i)
        if compound and compound.kind == "object":  # "the kitchen sink": the sink in the kitchen
            container = entities
            head = self.head(None)
            entities = self.vocab.inside(self.vocab.of_head(head), container)
            if head.plural and mode in (None, "the"):
                mode = "all"
            room_scoped = True
        while True:
            aside = self.at_any(_ASIDE)
            if aside is not None and self.word(len(aside)) in _ASIDE_QUALIFIERS:
                self.i += len(aside)  # "the couch, which is in the living room": a qualifier all the same
                continue
            if self.word() == "'s" and head.kind == "object":  # "the teddy bear's room": the room holding it
                self.i += 1
                owners = entities
                head = self.head(None)
                if head.kind != "room":
                    raise self.fail(f"'{self.span_text(first.start, self.toks[self.i - 1].end)}': only "
                                    f"a room can hold an object ('the teddy bear's room')")
                entities = self.vocab.containing(self.vocab.of_head(head), owners, None)
                mode = "all" if head.plural else "the"
                continue
            if self.word() == "'s" and head.kind == "room":
                self.i += 1
                container = entities
                head = self.head(None)
                if head.kind != "object":
                    raise self.fail(f"'{self.span_text(first.start, self.toks[self.i - 1].end)}': only "
                                    f"objects belong to a room")
                entities = self.vocab.inside(self.vocab.of_head(head), container)
                mode = "all" if head.plural else "the"
                room_scoped = True
                continue
            floor = self.floor_qualifier(entities)
            if floor is not None:
                entities = self.on_floors(entities, floor)
                continue
            if self.whole_building():  # "any TV in the house": anywhere, as without it
                continue
            if (self.word() in _QUAL_IN and self.np_starts(1) and not self.at_any(lx.ORDER_MODIFIERS)
                    and not self.at_any(lx.TIME_FILLERS)
                    and not (role == "qualifier" and self.word(1) in ("it", "there"))):
                self.i += 1
                inner = self.noun_phrase("qualifier")
                if head.kind != "object" or any(e.kind != "room" for e in inner.entities):
                    raise self.fail(f"'{self.span_text(first.start, inner.end)}': say 'the <object> in the "
                                    f"<room>' (rooms are not inside rooms, objects not inside objects)")
                entities = self.vocab.inside(entities, inner.entities)
                inner.entities = [r for r in inner.entities if any(e.room_key == r.key for e in entities)]
                room_scoped = True
                continue
            if self.word() == "there" and head.kind == "room" and self.word(1) not in ("is", "are", "was",
                                                                                      "were"):
                self.i += 1  # "go to the top floor and check a bathroom there": on that floor
                entities = self.on_floors(entities, self.there_floors(first.start, head))
                continue
            if (self.word() == "there" and head.kind == "object" and role == "goal" and not room_scoped
                    and self.word(1) not in ("is", "are", "was", "were")):
                self.i += 1  # "grab a bottle there": in the room of the place named last
                entities = self.vocab.inside(entities, self.there_rooms(first.start))
                room_scoped = True
                continue
            held = self.relative_contents(head) if head.kind == "room" else None
            if held is not None:  # "the room where the book is", "the room the book is in"
                entities = self.vocab.containing(entities, held.entities, None)
                held.entities = [o for o in held.entities if any(o.room_key == r.key for r in entities)]
                continue
            if self.without_contents(head, entities):  # "the bedroom without a potted plant"
                inner = self.noun_phrase("qualifier")
                entities = self.vocab.lacking(entities, inner.entities)
                self.skip_in_it()
                continue
            lacks = self.at_any(_QUAL_LACKS)
            if lacks and self.np_starts(len(lacks)):
                self.i += len(lacks)
                inner = self.noun_phrase("qualifier")
                if head.kind != "room" or any(e.kind != "object" for e in inner.entities):
                    raise self.fail(f"'{self.span_text(first.start, inner.end)}': say 'the <room> without "
                                    f"any <object>'")
                entities = self.vocab.lacking(entities, inner.entities)
                self.skip_in_it()
                continue
            contains = self.at_any(_QUAL_CONTAINS)
            if contains and self.np_starts(len(contains)):
                self.i += len(contains)
                n = self.count_word()
                inner = self.noun_phrase("qualifier")
                if head.kind != "room" or any(e.kind != "object" for e in inner.entities):
                    raise self.fail(f"'{self.span_text(first.start, inner.end)}': say 'the <room> with the "
                                    f"<object>'")
                entities = self.vocab.containing(entities, inner.entities,
                                                 n if n is not None else inner.count,
                                                 only="only" in contains)
                inner.entities = [o for o in inner.entities if any(o.room_key == r.key for r in entities)]
                self.skip_in_it()
                entities = self.more_contents(first, entities)
                continue
            nxt = self.at_any(_QUAL_NEXT)
            if nxt and self.np_starts(len(nxt)):
                self.i += len(nxt)
                inner = self.next_to_it() if self.word() == "it" else self.noun_phrase("qualifier")
                if any(e.kind != "room" for e in inner.entities):
                    raise self.fail(f"'{self.span_text(first.start, inner.end)}': 'next to' is understood "
                                    f"for rooms only (distances between objects are not known); name the "
                                    f"room the object is in")
                if head.kind == "object":  # "the toilet next to the bedroom": in a room next to it
                    rooms = self.vocab.next_to(
                        [self.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in entities)],
                        inner.entities)
                    entities = self.vocab.inside(entities, rooms)
                    inner.entities = [r for r in inner.entities
                                      if any(r.key in self.vocab.adjacent.get(x.key, ()) for x in rooms)]
                    continue
                entities = self.vocab.next_to(entities, inner.entities)
                inner.entities = [r for r in inner.entities
                                  if any(r.key in self.vocab.adjacent.get(e.key, ()) for e in entities)]
                continue
            comma = 1 if self.word() == "," else 0
            exc = self.at_any(_QUAL_EXCEPT, k=comma)
            if exc and self.np_starts(comma + len(exc)):
                restricted = self.span_text(first.start, self.toks[self.i - 1].end)
                self.i += comma + len(exc)
                excluded = self.except_list(head)
                keys = {e.key for np in excluded for e in np.entities}
                stray = [np.phrase for np in excluded if not {e.key for e in np.entities}
                         & {e.key for e in entities}]
                if stray:  # "the dining room but not the kitchen": not an exception, and not understood
                    raise self.fail(f"'{' '.join(exc)} {stray[0]}': {stray[0]!r} is not one of "
                                    f"{restricted!r}; to forbid it, say 'never enter {stray[0]}'")
                entities = [e for e in entities if e.key not in keys]
                continue
            break
        if demo:
            spoken = self.span_text(first.start, self.toks[self.i - 1].end)
            plural = head.plural or quantified is not None or pointer in backref.PLURAL_DEMONSTRATIVES
            got = backref.resolve(spoken, head, plural, entities, self.references, first.start,
                                  self.vocab.by_key, role == "goal")
            if isinstance(got, str):
                raise self.fail(got)
            entities, mode, room_scoped = got.entities, quantified or got.mode, room_scoped or got.room_scoped
            if count is not None and len(entities) != count:
                raise self.fail(f"'{spoken}' refers back to '{got.antecedent}', which is {len(entities)}, "
                                f"not {count}")
        there = (self.vocab.inside(entities, self.soft_scope)
                 if role == "goal" and head.kind == "object" and not demo else [])
        if not room_scoped and mode == "the" and not head.plural and len(entities) > 1 and len(there) == 1:
            entities, room_scoped = there, True
        elif not room_scoped and 0 < len(there) < len(entities) and first.text in ("the", "a", "an"):
            where = " or ".join(f"{r.key} ({r.category})" for r in self.soft_scope)
            noun = lx.plural(head_word(entities)) if head.plural else head_word(entities)
            raise self.fail(f"'{self.span_text(first.start, self.toks[self.i - 1].end)}' after a condition "
                            f"on "
                            f"{where}: the ones there, or any in the building? Say 'the {noun} in the "
                            f"{self.soft_scope[0].category}' or 'any {head_word(entities)}'")
        if role != "qualifier" and scope and head.kind == "object" and not room_scoped and not demo:
            scoped = self.vocab.inside(entities, scope)
            if scoped:
                entities, room_scoped = scoped, True
            elif role == "goal" and entities and not self.lenient_scope:
                # "go to the lobby and sit on the couch" where the lobby has no couch: another room's couch
                # is not what was asked for.
                where = " or ".join(f"{r.key} ({r.category})" for r in scope)
                raise self.fail(f"'{self.span_text(first.start, self.toks[self.i - 1].end)}' is not in "
                                f"{where} named in the same step; it is at "
                                f"{', '.join(e.describe() for e in entities[:8])}; say 'then' between the "
                                f"two, or name its room ('the {head_word(entities)} in the ...')")
        if (role != "qualifier" and mode == "the" and not head.plural and head.categories
                and self.at(",", "the", "one") and not self.at_any(lx.CHOICE_AFFIRMATIONS, k=2)):
            # "the bathroom, the one upstairs": the apposition says which
            self.i += 1
            which = self.noun_phrase("qualifier", None, Head(head.kind, head.categories, False, 1))
            entities = [e for e in entities if e in which.entities]
        last = self.toks[self.i - 1]
        np = NounPhrase(self.span_text(first.start, last.end), first.start, last.end, entities, mode,
                        room_scoped, role, count, head.kind == "room" and not head.categories)
        self.check(np, head, count)
        return self.record(np)

    def object_qualifier_or_none(self) -> NounPhrase | None:
        """The qualifier phrase here if it parses and names objects only, else ``None`` (a failed parse
        may leave the position moved: the caller restores it)."""
        try:
            inner = self.noun_phrase("qualifier")
        except MissionError:
            return None
        return None if any(e.kind != "object" for e in inner.entities) else inner

    def more_contents(self, first: Tok, rooms: list[Entity]) -> list[Entity]:
        """After ``the bedroom with the book``: ``and the vase`` may say more of its contents, or name
        another goal. When the rooms are still several and the object narrows them, it is contents
        (consumed); when one room is left and it holds that object too, either reading fits, which is
        refused; otherwise nothing is consumed (another goal)."""
        if self.word() != "and" or not self.np_starts(1) or role_is_pronoun(self.word(1)):
            return rooms
        save, known = self.i, len(self.references)
        self.i += 1
        inner = self.object_qualifier_or_none()
        holders = [] if inner is None else self.vocab.containing(rooms, inner.entities, None)
        if len(rooms) > 1 and 0 < len(holders) < len(rooms):
            self.skip_in_it()
            return holders
        if len(rooms) == 1 and holders and inner is not None:
            raise self.fail(f"'{self.span_text(first.start, inner.end)}': a room with both, or "
                            f"'{inner.phrase}' as another goal? Say 'the ... that has both ...', or 'then' "
                            f"before '{inner.phrase}'")
        del self.references[known:]
        self.i = save
        return rooms

    def relative_contents(self, head: Head) -> NounPhrase | None:
        """``where the book is`` / ``in which the book is`` / ``(that) the book is in`` after a room head:
        the object phrase those rooms must hold (consumed), or ``None`` (nothing consumed)."""
        save, known = self.i, len(self.references)
        if self.word() == "where" and self.np_starts(1) and self.word(1) != "there":
            self.i += 1
            tail: tuple[str, ...] = ()
        elif self.at("in", "which") and self.np_starts(2):
            self.i += 2
            tail = ()
        elif self.word() in ("that", "which") and self.np_starts(1):
            self.i += 1
            tail = ("in",)
        elif self.np_starts() and not self.word().startswith(("room_", "object_")):
            tail = ("in",)
        else:
            return None
        try:
            inner = self.noun_phrase("qualifier")
        except MissionError:
            if not tail:
                raise
            inner = None
        ok = inner is not None and self.word() in ("is", "are", "was", "were", "sits", "lives", "stands")
        if ok:
            self.i += 1
            if self.word() in ("located", "kept", "stored", "placed", "found", "standing", "sitting"):
                self.i += 1
            ok = all(self.word(n) == w for n, w in enumerate(tail))
            self.i += len(tail)
        if not ok or inner is None:
            if not tail:
                raise self.fail(f"'where ...' after a room is understood as 'the room where the <object> "
                                f"is'; found {self.here()}")
            del self.references[known:]
            self.i = save
            return None
        if any(e.kind != "object" for e in inner.entities):
            raise self.fail(f"'{inner.phrase}': a room is described by an object it holds ('the room where "
                            f"the book is')")
        return inner

    def without_contents(self, head: Head, rooms: list[Entity]) -> bool:
        """Whether ``without <object>`` here describes the rooms (``the bedroom without a potted plant``)
        rather than what to avoid: only when several rooms are in question and the object tells them apart
        (some hold it, some do not). Nothing is consumed but ``without``."""
        if head.kind != "room" or self.word() != "without" or len(rooms) < 2 or not self.np_starts(1):
            return False
        save, known = self.i, len(self.references)
        self.i += 1
        inner = self.object_qualifier_or_none()
        del self.references[known:]
        self.i = save
        if inner is None:
            return False
        left = self.vocab.lacking(rooms, inner.entities)
        if not left or len(left) == len(rooms):
            return False
        self.i += 1
        return True

    def there_rooms(self, before: int, said: str = "there") -> list[Entity]:
        """The rooms *there* means at character offset ``before``: those of the last place named as a goal
        or a condition before it ("whenever you enter the kitchen, grab a bottle there")."""
        places = [r for r in self.references if r.role in ("goal", "condition") and r.start < before
                  and r.entities and r.phrase.lower() not in lx.PRONOUNS]
        if not places:
            raise self.fail("'there' does not refer to any place named before it")
        last = max(places, key=lambda r: r.start)
        self.floor_or_place(said, last, rooms=True)
        rooms = [self.vocab.by_key[k] for k in dict.fromkeys(e.room_key for e in last.entities)]
        if not last.floor:  # a floor is one place: "the top floor ... a book there" is any room of it
            self.determined(said, last, len(rooms))
        return rooms

    def floor_or_place(self, said: str, last: NounPhrase, rooms: bool = False) -> None:
        """Refuses ``said`` (*there*, *up there*, *on that floor*) when a floor was named as a place before
        ``last``, the place named last, and the two readings differ: "go to the top floor, then the
        kitchen, then a bathroom up there" could mean either floor; with ``rooms`` (*there* as rooms: "a
        book there") the floor and a room on it already differ."""
        floors = [r for r in self.references if r.floor and r.role in ("goal", "condition")
                  and r.start < last.start]
        if last.floor or not floors:
            return
        floor = max(floors, key=lambda r: r.start)
        if rooms or {e.floor for e in floor.entities} != {e.floor for e in last.entities}:
            raise self.fail(f"'{said}' could refer back to '{floor.phrase}' or to '{last.phrase}', named "
                            f"after it; name the floor or room again")

    def there_floors(self, before: int, head: Head) -> frozenset[int]:
        """The floor(s) *there* after a room (*a bathroom there*) means at character offset ``before``: a
        floor named last as a place. A room or object named last is refused: rooms are not inside rooms,
        and reading *there* as nothing would silently widen the phrase."""
        places = [r for r in self.references if r.role in ("goal", "condition") and r.start < before
                  and r.entities and r.phrase.lower() not in lx.PRONOUNS]
        last = max(places, key=lambda r: r.start) if places else None
        moved = self.action_floor
        if moved is not None and (last is None or last.start < moved[1]):  # "go upstairs, then X there"
            return moved[0]
        if last is None and self.confined is not None:  # "keep to the top floor and visit X there"
            return self.confined
        if last is None or not last.floor:
            what = f"'{last.phrase}'" if last is not None else "nothing"
            raise self.fail(f"'{head_word(self.vocab.of_head(head))} there': 'there' refers back to {what}, "
                            f"not a floor (rooms are not inside rooms); name the floor (e.g. 'on floor 1') "
                            f"or the room")
        return frozenset(e.floor for e in last.entities)

    def whole_building(self) -> bool:
        """Skips ``in the house`` / ``in this building`` / ``anywhere in the home`` after a noun (not ``in the
        home office``, a room): the whole building restricts nothing."""
        k = 2 if self.at("anywhere", "in") else 1 if self.word() in ("in", "inside", "throughout") else 0
        if not k or self.word(k) not in ("the", "this", "our", "my", "your"):
            return False
        if self.word(k + 1) not in lx.WHOLE_BUILDING or self.vocab.match_head(self.words(), self.i + k + 1):
            return False
        self.i += k + 2
        return True

    def determined(self, said: str, ref: NounPhrase, places: int) -> None:
        """Refuses ``said`` (*there*, *up there*, *its*, *next to it*) pointing back to a choice whose
        alternatives differ in what ``said`` denotes (``places`` of them)."""
        reason = backref.choice_refusal(said, ref, places)
        if reason is not None:
            raise self.fail(reason)

    def floor_place(self, first: Tok, floors: frozenset[int], mode: Mode | None, role: Role) -> NounPhrase:
        """``the top floor`` as a place: any of its rooms as a goal or condition, all of them to avoid."""
        rooms = self.on_floors(self.vocab.of_head(Head("room", frozenset(), True, 1)), floors)
        chosen: Mode = "all" if role == "avoid" or mode == "all" else "any"
        last = self.toks[self.i - 1]
        return self.record(NounPhrase(self.span_text(first.start, last.end), first.start, last.end, rooms,
                                      chosen, False, role, floor=True))

    def last_head(self) -> Head | None:
        """The kind and category of the last room or object named (what *the other one* refers to)."""
        for np in sorted(self.references, key=lambda r: r.start, reverse=True):
            categories = {e.category for e in np.entities}
            if np.role != "qualifier" and np.generic:  # "the room where the book is, then the one ..."
                return Head("room", frozenset(), False, 1)
            if np.role != "qualifier" and np.entities and len(categories) == 1:
                return Head(np.entities[0].kind, frozenset(categories), False, 1)
        return None

    def others(self, entities: list[Entity], before: int) -> list[Entity]:
        """``the other X``: the X not named before ``before`` (a character offset); refused when none was."""
        named = {e.key for r in self.references if r.start < before for e in r.entities}
        if not any(e.key in named for e in entities):
            raise self.fail(f"'the other {head_word(entities)}': no {head_word(entities)} was named before "
                            f"it")
        return [e for e in entities if e.key not in named]

    def skip_in_it(self) -> None:
        """``the bedroom that only has a bed in it``: the trailing *in it* repeats the room."""
        if self.word() in ("in", "inside") and self.word(1) in ("it", "there"):
            self.i += 2

    def except_list(self, head: Head) -> list[NounPhrase]:
        out = [self.noun_phrase("qualifier", None, head)]
        while self.word() in ("and", "or", ",") and self.np_starts(1):
            self.i += 1
            out.append(self.noun_phrase("qualifier", None, head))
        return out

    def record(self, np: NounPhrase) -> NounPhrase:
        self.references.append(np)
        return np

    def antecedent(self, pronoun: str, kind: str | None = None) -> NounPhrase:
        """The phrase a pronoun refers to: the last one mentioned (by position) that agrees in number.

        ``it`` takes a phrase denoting one entity, ``them``/``they`` one denoting several, so in "go to the
        bedroom with the TV and turn it on" *it* is the TV, and in "take both bowls in the kitchen and put
        them in the fridge" *them* are the bowls. An object named inside an object phrase to locate it is
        not the antecedent: in "get the book from the bedroom with the vase, then bring it ..." *it* is the
        book.
        """
        plural = pronoun in ("them", "they")
        fits = [np for np in sorted(self.references, key=lambda r: r.start, reverse=True)
                if (np.mode == "all" and len(np.entities) > 1) == plural
                and np.phrase.lower() not in lx.PRONOUNS
                and (kind is None or all(e.kind == kind for e in np.entities))]
        if fits:
            np = fits[0]
            # "the book from the bedroom with the vase ... it": the object the phrase is about (its head),
            # not an object named inside it to locate it
            outer = [o for o in fits[1:] if o.start <= np.start and np.end <= o.end
                     and all(e.kind == "object" for e in o.entities)]
            return min(outer, key=lambda o: o.start) if outer else np
        raise self.fail(f"'{pronoun}' does not refer to any {'group of ' if plural else ''}room or object "
                        f"named before it")

    def next_to_it(self) -> NounPhrase:
        """``next to it``: *it* is the last whole phrase named (not one nested in it: in "the bedroom where
        the teddy bear is" that is the bedroom); it must be a room, since distances between objects are not
        known."""
        refs = [r for r in self.references if r.phrase.lower() not in lx.PRONOUNS and r.entities]
        outer = [r for r in refs if not any(o is not r and o.start <= r.start and r.end <= o.end
                                            and (o.start, o.end) != (r.start, r.end) for o in refs)]
        if not outer:
            raise self.fail("'it' does not refer to any room named before it")
        ref = max(outer, key=lambda r: r.start)
        self.determined("next to it", ref, len(ref.entities))
        if any(e.kind != "room" for e in ref.entities):
            raise self.fail(f"'next to it': 'it' is '{ref.phrase}', an object; 'next to' is understood for "
                            f"rooms "
                            f"only (distances between objects are not known)")
        tok = self.toks[self.i]
        self.i += 1
        return self.record(NounPhrase("it", tok.start, tok.end, list(ref.entities), ref.mode, False,
                                      "qualifier"))

    def all_of_them(self) -> NounPhrase | None:
        """``all of them`` / ``both of them`` / ``each of them`` / ``all three of them``: the group named
        before (its size checked against the number said); None if the words are not there."""
        n = 1 if self.word() in ("all", "both", "each", "every") else 0
        said = lx.NUMBER_WORDS.get(self.word(n)) if n else None
        k = n + (1 if said else 0)
        if not n or (not self.at("of", "them", k=k) and not (said and self.word(k) in ("", ","))):
            return None
        count = 2 if self.word() == "both" else said
        first = self.toks[self.i]
        self.i += k + (2 if self.at("of", "them", k=k) else 0)
        ref = self.antecedent("them")
        if count is not None and len(ref.entities) != count:
            raise self.fail(f"'{self.span_text(first.start, self.toks[self.i - 1].end)}': '{ref.phrase}' is "
                            f"{len(ref.entities)}, not {count}")
        return self.record(NounPhrase(self.span_text(first.start, self.toks[self.i - 1].end), first.start,
                                      self.toks[self.i - 1].end, list(ref.entities), "all", ref.room_scoped,
                                      "goal"))

    def demonstrative(self) -> int:
        """How many words of a back-pointing determiner start the noun phrase here (*that*, *those*, *the
        same* ... before a room or object noun, with or without a number); 0 if none."""
        n = backref.demonstrative_length(self.words(), self.i)
        if not n:
            return 0
        k = n + (1 if self.word(n) in lx.NUMBER_WORDS or self.word(n).isdigit() else 0)
        if self.word(k) in lx.FLOOR_WORDS or self.word(k) in lx.ANAPHORIC_ONE:
            return 0  # "this floor": the start floor (:meth:`floor_words`); "that one" is refused
        return n

    def quantifier(self) -> tuple[Mode | None, int | None]:
        """Determiners -> (mode, required count); ``None`` mode = decided by the head's number."""
        w = self.word()
        mode: Mode | None = None
        count: int | None = None
        chosen_from = False
        if w in ("one", "any", "either") and self.word(1) == "of":
            self.i += 2
            mode = "any"
            chosen_from = self.word() in ("the", "these", "those")  # "one of the two bathrooms"
        elif w in ("a", "an", "any", "some", "either"):
            self.i += 1
            mode = "any"
        elif w in ("all", "every", "each", "both"):
            self.i += 1
            mode, count = "all", (2 if w == "both" else None)
            if self.word() == "of":
                self.i += 1
        elif w in backref.DEMONSTRATIVES and self.word(1) not in lx.FLOOR_WORDS:
            # the guard against reading a back-reference as a fresh description: only the demonstrative
            # path (:meth:`demonstrative`, :func:`.backref.resolve`) may ground "that ..." / "this ..."
            raise self.fail(f"'{w} {self.word(1)}' refers back to something named before, and is understood "
                            f"only directly before a room or object ('{w} bathroom'); name it instead")
        elif w in ("the", "this", "that", "these", "those") or w in _POSSESSIVES:
            self.i += 1
            mode = "the"
        if self.word() == "the" and mode is not None:
            self.i += 1
        counted = self.np_starts(1) or self.vocab.match_head(self.words(), self.i + 1)
        n = self.count_word() if counted else None
        if n is not None and chosen_from:
            return mode, n  # one of them, and there must be n
        if n is not None:
            if mode in (None, "any"):
                raise self.fail(f"'{self.word(-1)} ...': choosing a number of them is not understood; "
                                f"say 'any of the ...' or 'all the ...'")
            mode, count = "all", n
        return mode, count

    def count_word(self) -> int | None:
        w = self.word()
        if w in lx.NUMBER_WORDS and (w != "one" or self.word(1) != "of"):
            self.i += 1
            return lx.NUMBER_WORDS[w]
        if w.isdigit():
            self.i += 1
            return int(w)
        return None

    def head(self, one_head: Head | None) -> Head:
        w = self.word()
        if w in lx.ANAPHORIC_ONE:
            if one_head is None:
                raise self.fail(f"'{w}' does not refer to a kind of room or object named just before")
            self.i += 1
            return Head(one_head.kind, one_head.categories, w == "ones", 1)
        if w in lx.REFUSED_VERBS:
            raise self.fail(f"cannot understand {lx.REFUSED_VERBS[w]}")
        if w in lx.FLOOR_ORDINALS or w in lx.FLOOR_NAMED or w in lx.FLOOR_TOP:
            raise self.fail(f"ordinals like '{w}' are only understood for floors ('the bathroom on the {w} "
                            f"floor')")
        head = self.vocab.match_head(self.words(), self.i)
        if head is None and self.done():
            raise self.fail(f"expected a room or object after '{self.toks[self.i - 1].text}' at the end of "
                            f"the sentence")
        if head is None:
            unknown = self.word()
            raise self.fail(
                f"no room or object of this scene is called '{unknown}' (rooms: "
                f"{', '.join(self.vocab.category_names('room'))}; objects: "
                f"{', '.join(self.vocab.category_names('object'))})"
            )
        self.i += head.words
        return head

    def floor_qualifier(self, candidates: list[Entity]) -> frozenset[int] | None:
        """``on floor 1`` / ``in floor 1`` / ``on the second floor`` / ``on the ground floor`` -> {1}, {1},
        {0}; ``upstairs`` / ``downstairs`` / ``on this floor``: relative to the start floor
        (:meth:`relative_floor`); ``up there`` / ``down there``: the floor(s) of the last goal. Not ``in the
        ground floor bathroom``: that names a room."""
        if self.word() in lx.RELATIVE_FLOORS:  # "the bathroom upstairs"
            relative = self.relative_floor(self.word(), candidates)
            self.i += 1
            return relative
        comma = 1 if self.word() == "," else 0
        if self.floor_count(comma) is not None and self.word(comma + 1) in _FLOOR_PLURALS:
            offset = self.floor_offset(comma)  # "the kitchen (,) one floor down"
            if offset is not None:
                self.i += comma + offset[1]
                return offset[0]
        if self.word() in ("up", "down") and self.word(1) == "there":  # "the bathroom up there"
            goals = [r for r in self.references if r.role == "goal" and r.entities]
            if not goals:
                raise self.fail(f"'{self.word()} there' does not refer to any place named before it")
            where = f"{self.word()} there"
            self.i += 2
            last = max(goals, key=lambda r: r.start)
            self.floor_or_place(where, last)
            floors = frozenset(e.floor for e in last.entities)
            self.determined(where, last, len(floors))
            return floors
        if self.word() not in ("on", "in", "at", "of", "from"):
            return None
        if self.at("the", "same", k=1) and self.word(3) in lx.FLOOR_WORDS:
            self.i += 4
            return self.same_floor()
        if self.word(1) == "that" and self.word(2) in lx.FLOOR_WORDS:  # "on that floor": the last goal's
            self.i += 3
            return self.same_floor()
        k = 2 if self.word(1) == "the" else 1
        said = self.floor_words(k)
        if said is None or self.vocab.match_head(self.words(), self.i + k + said[1]) is not None:
            return None  # none, or "in the ground floor bathroom": a room named with its floor
        self.i += k + said[1]
        return said[0]

    def same_floor(self) -> frozenset[int]:
        """After ``on the same floor`` / ``on that floor``: the floor of ``as <phrase>`` when said, else of
        the last goal named. It must be one floor: after a choice across floors ("either bedroom, then the
        bathroom on the same floor") the floor depends on the choice, which is refused rather than
        guessed."""
        if self.word() == "as" and self.np_starts(1):
            self.i += 1
            ref = self.noun_phrase("qualifier")
        else:
            goals = [r for r in self.references if r.role == "goal" and r.entities]
            if not goals:
                raise self.fail("'the same floor' / 'that floor' does not refer to any place named before it")
            ref = max(goals, key=lambda r: r.start)
            self.floor_or_place("the same floor' / 'that floor", ref)
        floors = frozenset(e.floor for e in ref.entities)
        if len(floors) != 1:
            raise self.fail(f"'the same floor' as '{ref.phrase}', which is on floors "
                            f"{', '.join(str(f) for f in sorted(floors))}: the floor depends on which one is "
                            f"chosen; say which floor, or give each choice its own sentence")
        return floors

    def floor_offset(self, k: int = 0) -> tuple[frozenset[int], int] | None:
        """Floors counted from the start floor, at offset ``k``: ``floor above`` / ``floor below`` (after
        *the*), ``next floor up``, ``one floor up``, ``two floors down``, ``a floor down`` -> the floor and
        how many words say it; ``None`` if the words are not there. Needs the start floor."""
        w, nxt, third = self.word(k), self.word(k + 1), self.word(k + 2)
        count = self.floor_count(k)
        if w in lx.FLOOR_WORDS and nxt in _FLOOR_DIRECTIONS:
            delta, n = _FLOOR_DIRECTIONS[nxt], 2
        elif w == "next" and nxt in lx.FLOOR_WORDS and third in _FLOOR_DIRECTIONS:
            delta, n = _FLOOR_DIRECTIONS[third], 3
        elif count is not None and nxt in _FLOOR_PLURALS and third in _FLOOR_DIRECTIONS:
            delta, n = _FLOOR_DIRECTIONS[third] * count, 3
        else:
            return None
        floors = self.shifted_floor(delta, " ".join(self.word(k + j) for j in range(n)))
        if self.word(k + n) in ("us", "you", "me"):
            n += 1  # "the floor above us"
        elif self.at("this", "one", k=k + n):
            n += 2  # "the floor below this one"
        return floors, n

    def check_still_on_start_floor(self, said: str, relate: Callable[[int], frozenset[int]]) -> None:
        """Words relative to the start floor (*upstairs*, *the floor below*) after a goal on another floor
        could be relative to where that goal took the robot: ``relate`` (a floor -> the floors the words
        mean from there) gives that second reading, kept in :attr:`alt_floors` and compared when the floors
        are applied (:meth:`on_floors`); a last goal on several floors leaves no second reading to compare,
        which is refused."""
        goals = [r for r in self.references if r.role == "goal" and r.entities]
        if not goals:
            return
        last = max(goals, key=lambda r: r.start)
        at = {e.floor for e in last.entities}
        if at == {self.start_floor}:
            return
        if len(at) > 1:
            raise self.fail(f"'{said}' after '{last.phrase}' (floors "
                            f"{', '.join(str(f) for f in sorted(at))}): relative to the start (floor "
                            f"{self.start_floor}) or to there? Say which floor")
        self.alt_floors = relate(at.pop())
        self.alt_said = (said, last.phrase)

    def on_floors(self, entities: list[Entity], floors: frozenset[int]) -> list[Entity]:
        """``entities`` on ``floors``; when words relative to the start could also be read from the floor of
        the goal named before them (:meth:`check_still_on_start_floor`), both readings must pick the same
        entities, else it is refused."""
        out = self.vocab.on_floor(entities, floors)
        alt, self.alt_floors = self.alt_floors, None
        if alt is not None and {e.key for e in self.vocab.on_floor(entities, alt)} != {e.key for e in out}:
            said, after = self.alt_said
            raise self.fail(f"'{said}' after '{after}': relative to the start (floor {self.start_floor}) or "
                            f"to there? The two differ here; say which floor")
        return out

    def floor_count(self, k: int) -> int | None:
        """``a`` / ``one`` / ``two`` / ``2`` at offset ``k`` as a number of floors, else ``None``."""
        w = self.word(k)
        return 1 if w == "a" else int(w) if w.isdigit() else lx.NUMBER_WORDS.get(w)

    def shifted_floor(self, delta: int, said: str) -> frozenset[int]:
        """The floor ``delta`` floors above the start floor (below if negative); refused without a start
        floor or outside the building."""
        floors = self.vocab.num_floors
        if self.start_floor is None:
            raise self.fail(f"'{said}' depends on where the robot starts, which is not known here; say which "
                            f"floor (the building {self.vocab.building_name!r} has floors 0 to {floors - 1})")
        self.check_still_on_start_floor(
            said, lambda base: frozenset({base + delta}) if 0 <= base + delta < floors else frozenset())
        floor = self.start_floor + delta
        if not 0 <= floor < floors:
            raise self.fail(f"'{said}': the robot starts on floor {self.start_floor} and the building "
                            f"{self.vocab.building_name!r} has floors 0 to {floors - 1}")
        return frozenset({floor})

    def floor_words(self, k: int = 0) -> tuple[frozenset[int], int] | None:
        """The floor named by the words at offset ``k`` and how many words name it: ``floor 1``, ``second
        floor``, ``ground floor``, ``top floor``, ``middle floor``, ``this floor`` (the start floor); ``None``
        if they name no floor. Floors the building does not have are refused."""
        w, nxt = self.word(k), self.word(k + 1)
        floors = self.vocab.num_floors
        moved = self.floor_offset(k)
        if moved is not None:
            return moved
        if w in lx.FLOOR_WORDS and (nxt.isdigit() or nxt in lx.NUMBER_WORDS or nxt == "zero"):
            floor = 0 if nxt == "zero" else int(nxt) if nxt.isdigit() else lx.NUMBER_WORDS[nxt]
        elif nxt not in lx.FLOOR_WORDS:
            return None
        elif w in lx.FLOOR_ORDINALS or w in lx.FLOOR_NAMED or w in lx.FLOOR_TOP:
            floor = lx.FLOOR_ORDINALS.get(w, lx.FLOOR_NAMED.get(w, floors - 1))
        elif w in lx.FLOOR_MIDDLE:
            if floors % 2 == 0:
                raise self.fail(f"'{w} {nxt}': the building {self.vocab.building_name!r} has {floors} floors "
                                f"(0 to {floors - 1}), so no middle one; say which floor")
            floor = floors // 2
        elif w in lx.START_FLOOR_WORDS:  # "on this floor": where the robot starts
            if self.start_floor is None:
                raise self.fail(f"'{w} {nxt}' depends on where the robot starts, which is not known here; "
                                f"say which floor (the building {self.vocab.building_name!r} has floors 0 to "
                                f"{floors - 1})")
            floor = self.start_floor
        else:
            return None
        if not 0 <= floor < floors:
            raise self.fail(f"'{w} {nxt}': the building {self.vocab.building_name!r} has floors 0 to "
                            f"{floors - 1} (floor 0 is the lowest; 'the first floor' is floor 0)")
        return frozenset({floor}), 2

    # -- grounding checks -----------------------------------------------------------------------------
    def check(self, np: NounPhrase, head: Head, count: int | None) -> None:
        if np.role == "qualifier":
            if not np.entities:
                raise self.fail(f"'{np.phrase}' matches no {head.kind} of this scene{self.existing(head)}")
            return
        if not np.entities:
            kept = ""
            if self.confined is not None and np.role in ("goal", "condition"):
                kept = (f", on the floor(s) the mission stays on "
                        f"({', '.join(str(f) for f in sorted(self.confined))})")
            raise self.fail(f"'{np.phrase}' matches no {head.kind}{kept}{self.existing(head)}")
        if count is not None and len(np.entities) != count:
            listing = ", ".join(e.describe() for e in np.entities)
            raise self.fail(f"'{np.phrase}' should be {count} {head.kind}s but matches {len(np.entities)}: "
                            f"{listing}")
        if np.mode == "the" and len(np.entities) > 1 and head.kind == np.entities[0].kind \
                and not head.plural and self.affirmation_ahead() is not None:
            np.mode = "any"  # "the toilet on this floor, any one will do": one of them
        if (np.mode == "the" and np.role == "avoid" and np.phrase.lower().split()[-1] in _PLURAL_LOOKING
                and self.confined is not None):
            # "stay on the top floor and keep off the stairs": the staircases of the floors the mission
            # stays on, and those elsewhere are forbidden anyway, so every one of them. Without a
            # confinement, all of them or those of the floors the mission uses differ: asked below.
            np.mode = "all"
        if np.mode == "the" and len(np.entities) > 1:
            listing = ", ".join(
                f"{e.key} (floor {e.floor})" if e.kind == "room"
                else f"{e.key} (in {e.room_key}, floor {e.floor})"
                for e in np.entities
            )
            raise MissionError(
                f"'{np.phrase}' matches {len(np.entities)} {head.kind}s: {listing}; {self.hint(np)}"
            )

    def existing(self, head: Head) -> str:
        found = self.vocab.of_head(head)
        if not found:
            return ""
        listing = ", ".join(e.describe() for e in found[:8]) + (", ..." if len(found) > 8 else "")
        return f" (this scene has: {listing})"

    def hint(self, np: NounPhrase) -> str:
        """How to single one entity out: by floor, by a room, by contents or neighbours, or by quantifier."""
        ents = np.entities
        word = ents[0].category
        if len({e.floor for e in ents}) == len(ents):
            return f"say which floor (e.g. 'the {word} on floor {ents[0].floor}')"
        if ents[0].kind == "object":
            if len({e.room_key for e in ents}) == len(ents):
                room = self.vocab.by_key[ents[0].room_key]
                example = f"the {word} in the {room.category} on floor {room.floor}"
                return f"say which room it is in (e.g. '{example}')"
        else:
            for e in ents:
                own = {o.category for o in self.vocab.entities if o.kind == "object" and o.room_key == e.key}
                others = {o.category for o in self.vocab.entities
                          if o.kind == "object" and o.room_key != e.key
                          and o.room_key in {x.key for x in ents}}
                unique = sorted(own - others)
                if unique:
                    return f"say what it contains (e.g. 'the {word} with the {unique[0]}')"
        return f"say 'any {word}' or 'every {word}', or name it by its ID (e.g. {ents[0].key})"


def role_is_pronoun(word: str) -> bool:
    """Whether ``word`` is a pronoun (``and it`` never adds to a room's contents)."""
    return word in lx.PRONOUNS


def head_word(entities: list[Entity]) -> str:
    """The category of a group of entities, for messages (``room`` when they differ)."""
    categories = {e.category for e in entities}
    return categories.pop() if len(categories) == 1 else entities[0].kind if entities else "room"


def _goal_eventually(task: Task) -> list[Formula]:
    if task.mode == "any":
        return [Eventually(disj(task.members))]
    return [Eventually(m) for m in task.members]


def parse_mission(text: str, vocabulary: SceneVocabulary,
                  start_floor: int | None = None) -> tuple[Formula, list[NounPhrase]]:
    """Parse and ground ``text``; the formula and every noun phrase read, in text order. ``start_floor``
    (the robot's, when known) is what *upstairs* / *downstairs* are relative to.

    Raises
    ------
    MissionError
        a phrase that is not understood, a reference that matches nothing, or a definite reference
        ("the bathroom") that matches several entities; the message names the phrase and the candidates.
    """
    parser = MissionParser(text, vocabulary, start_floor)
    formula = parser.parse()
    check_all_used(formula, parser.references, parser)
    return formula, sorted(parser.references, key=lambda np: np.start)


def check_all_used(formula: Formula, nps: list[NounPhrase], parser: MissionParser) -> None:
    """The second safeguard against a silently dropped clause: every place the text names as a goal, a
    place to avoid or a condition must show up in the formula (qualifiers such as *the kitchen* in *the
    sink in the kitchen* only narrow another phrase). A phrase that vanished is refused, named."""
    used = set(atoms(formula))
    for np in nps:
        if np.role != "qualifier" and np.entities and not any(e.action in used for e in np.entities):
            raise parser.fail(f"'{np.phrase}' was read but is not part of the mission that would be planned, "
                              f"and no part of a mission is ever dropped")
