"""The typed syntax tree of a mission sentence: what the words say, before any room or object is looked up.

Nodes are frozen dataclasses. Noun phrases keep their words (head nouns, qualifiers, determiners) and the
character span they came from; which rooms and objects they denote is decided later, by
:mod:`sgplan.llm.offline.grounding`. Where the words alone do not decide how a phrase attaches (*the
bedroom without a plant*: a description of the bedroom, or what to avoid there?), the tree says so with an
:class:`Attachment` and its reading is decided against the scene (:func:`.syntax.parse_sentence`).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, fields, is_dataclass
from typing import Literal, TypeVar

from sgplan.llm.offline.nouns import Head
from sgplan.llm.offline.text import Tok

Mode = Literal["the", "any", "all"]
Role = Literal["goal", "avoid", "condition", "qualifier"]


@dataclass(frozen=True)
class Span:
    """Character offsets ``[start, end)`` into the mission text."""

    start: int
    end: int


# ---------------------------------------------------------------------------------------------- floors
@dataclass(frozen=True)
class FloorNumber:
    """*floor 1*, *the second floor*, *the ground floor*: floor ``number`` (0 = the lowest)."""

    number: int
    said: str


@dataclass(frozen=True)
class TopFloor:
    """*the top floor*."""

    said: str


@dataclass(frozen=True)
class MiddleFloor:
    """*the middle floor* (a building with an odd number of floors)."""

    said: str


@dataclass(frozen=True)
class StartFloor:
    """*this floor*, *the same floor* (as the start), *any other floor*: the robot's start floor
    (``to_stay``: said of where to stay)."""

    said: str
    to_stay: bool = False


@dataclass(frozen=True)
class FloorOffset:
    """*the floor above*, *two floors down*: ``delta`` floors from the start floor."""

    delta: int
    said: str


@dataclass(frozen=True)
class RelativeFloor:
    """*upstairs* / *downstairs*: the floors above / below the start (see the grounding); ``robot_there``:
    said as where the robot is (*while you're upstairs*), which is the start floor when none lies that way;
    ``back``: said as a return (*come back up and X*)."""

    word: str
    robot_there: bool = False
    back: bool = False


@dataclass(frozen=True)
class StayExtreme:
    """*stay upstairs* / *stay downstairs*: the upper / lower floor (see the grounding)."""

    word: str


@dataclass(frozen=True)
class UpThere:
    """*up there* / *down there*: the floor of the goal named last."""

    word: str


@dataclass(frozen=True)
class SameFloor:
    """*on the same floor (as X)*, *on that floor*: the floor of X, else of the goal named last."""

    as_phrase: NounPhrase | None


FloorSpec = (FloorNumber | TopFloor | MiddleFloor | StartFloor | FloorOffset | RelativeFloor | StayExtreme
             | UpThere | SameFloor)


# ----------------------------------------------------------------------------------------- noun phrases
@dataclass(frozen=True)
class Pronoun:
    """*it*, *them*, *they*, *its* (alone): the phrase named last that agrees in number."""

    span: Span
    word: str


@dataclass(frozen=True)
class ThereNP:
    """*there* as a place to go: the last place named as a goal."""

    span: Span


@dataclass(frozen=True)
class GroupRepeat:
    """*all of them*, *both of them*, *all three of them*: the group named before (``count`` if said);
    ``choice``: *one / any / either of them*, one of that group."""

    span: Span
    count: int | None
    choice: bool = False


@dataclass(frozen=True)
class SameRoom:
    """*the same room* inside a qualifier (*the sink in the same room*): the room of the place named last."""

    span: Span
    word: str


@dataclass(frozen=True)
class Its:
    """*its X*: the X in (or, for a room, attached to) the room of the thing named just before; ``mode``:
    what a quantifier before it asks (*one of its chairs*: any), ``None`` when the head's number decides."""

    span: Span
    head: Head
    mode: Mode | None = None


@dataclass(frozen=True)
class FloorPlace:
    """A floor named as a place (*the top floor*, *floor 2*, *upstairs* after *never go*): its rooms."""

    span: Span
    floor: FloorSpec
    mode: Mode | None


@dataclass(frozen=True)
class KeyHead:
    """An entity ID said as such (``room_4``)."""

    key: str


@dataclass(frozen=True)
class OneHead:
    """*one* / *ones* as a head: the kind of ``given`` (an apposition's or an exception's phrase), or, when
    ``from_context``, of the room or object named last."""

    plural: bool
    given: Head | None
    from_context: bool


HeadRef = Head | KeyHead | OneHead


@dataclass(frozen=True)
class Determiner:
    """What comes before the head noun: the mode it asks for and the words that say it.

    ``mode`` is ``None`` when the head's number decides it (*the chairs* = each of them). ``pointer`` is the
    demonstrative (*that*, *those*, *the same* ...) of a phrase that names again something said before;
    ``quantified`` the quantifier before it (*one of those*). ``chosen_from``: *one of the two X* (the
    number is checked, the choice stays).
    """

    mode: Mode | None
    count: int | None
    pointer: str | None = None
    quantified: Mode | None = None
    other: bool = False
    descriptive: tuple[str, ...] = ()
    """Descriptive words read with the determiner (:attr:`Described.descriptive`)."""
    ordinal: int | None = None
    """*the first / second X*, *back to the first one* (1, 2 ...): the X named that many-th before."""
    owner: str | None = None
    """*the baby's teddy bear*, *Lily's book*: the person's possessive before an object, as typed; whose it is
    the scene does not say, so it is set aside and said back (the object must be the one of its kind)."""


@dataclass(frozen=True)
class Described:
    """A noun phrase with a head noun: determiner, floor words before the noun, the head, qualifiers."""

    span: Span
    first_word: str
    determiner: Determiner
    relative: str | None
    """*upstairs* / *downstairs* before the noun (*the upstairs bathroom*)."""
    floor_before: FloorSpec | None
    """Floor words before the noun (*the ground floor bathroom*)."""
    modifier: str | None
    """*dining* in *the dining chairs*: the object is in a room of that category."""
    head: HeadRef
    compound: Head | None
    """The object head after a room head: *the kitchen sink*."""
    qualifiers: tuple[Qualifier, ...]
    apposition: Described | None
    """*the bathroom, the one upstairs*: says which."""
    remark_follows: bool
    """A choice remark follows the phrase (*, any one will do*): a definite phrase may then be a choice."""
    descriptive: tuple[str, ...] = ()
    """Words describing the thing that the scene does not know (*big* in *the big couch*)."""
    apposition_excludes: bool = False
    """The apposition says which it is not (*the bathroom, not the one with the vase*)."""
    either_remark: bool = False
    """The choice remark after the phrase says one of two (*, either one*, *(either)*)."""


@dataclass(frozen=True)
class HandledAt:
    """*rinse the watering can at the kitchen sink*, *heat my leftovers in the microwave*: a thing the scene
    does not hold (``thing``: its words), handled at one of the scene's objects (``at``), which is the goal;
    the thing is said back as not part of the mission."""

    span: Span
    thing: Span
    at: NounPhrase


NounPhrase = Pronoun | ThereNP | GroupRepeat | SameRoom | Its | FloorPlace | Described | HandledAt


@dataclass(frozen=True)
class PhraseList:
    """Noun phrases joined by commas, *and*, *or*, *nor*: each of them, or one of them (*or*, *either*)."""

    span: Span
    items: tuple[NounPhrase, ...]
    joiners: frozenset[str]
    either: bool
    comma_list: bool
    """Joined by commas only (*the fridge, the oven*)."""


# ------------------------------------------------------------------------------------------- qualifiers
@dataclass(frozen=True)
class Possessive:
    """``'s`` + a head: *the teddy bear's room* (the room holding it), *the kitchen's sink*."""

    head: Head
    span: Span


@dataclass(frozen=True)
class OnFloor:
    """*on floor 1*, *upstairs*, *up there*, *on the same floor*: the entities on that floor."""

    floor: FloorSpec


@dataclass(frozen=True)
class InRoom:
    """*in / of / inside the kitchen* after an object: the objects in that room; after a phrase about each of
    several objects, *in the office and the kitchen*: those of both rooms; ``choice``: *in A or B*, one
    object of either room."""

    rooms: tuple[NounPhrase, ...]
    span: Span
    choice: bool = False


@dataclass(frozen=True)
class There:
    """*there* after a noun: the floor of a floor named last (rooms), the room of the place named last
    (objects)."""


@dataclass(frozen=True)
class Holds:
    """*the room where the book is*: the rooms holding that object; ``also``: the others said with it (*the
    bedroom where the book and the vase are*: holding each)."""

    thing: NounPhrase
    also: tuple[NounPhrase, ...] = ()


@dataclass(frozen=True)
class Lacks:
    """*the bedroom that does not have a book*: the rooms holding none of it."""

    thing: NounPhrase
    span: Span


@dataclass(frozen=True)
class Contains:
    """*the bedroom with (only) (two) beds*: the rooms holding it (that many; nothing else)."""

    thing: NounPhrase
    span: Span
    count: int | None
    only: bool


@dataclass(frozen=True)
class NextTo:
    """*next to the kitchen* / *next to it*: connected to that room (rooms), in a room connected to it
    (objects). ``thing`` is ``None`` for *it* (the whole phrase named last); ``relation`` is the words that
    said it (*next to*, *just off*, *outside*), for refusals."""

    thing: NounPhrase | None
    span: Span
    it_span: Span | None
    relation: str


@dataclass(frozen=True)
class Between:
    """*the bathroom between the bedrooms* / *between the kitchen and the hall*: a room connected to each of
    the rooms ``things`` name (two or more)."""

    things: tuple[NounPhrase, ...]
    span: Span


@dataclass(frozen=True)
class ByUnlisted:
    """*the bowl on the counter*, *the book on the shelf in the office*: placed by a thing the scene does not
    hold (``words``, as typed, ``span``): a description of the object (read only where the scene leaves one
    such object), the words said back as set aside."""

    words: str
    span: Span


@dataclass(frozen=True)
class ShortStay:
    """*(sit on the couch) for a bit / a while / a few minutes*: how long to stay at the goal, said casually
    (``span``); said back as set aside, the goal is reached."""

    span: Span


@dataclass(frozen=True)
class Except:
    """*except (for) the one on floor 0*: all but those."""

    things: tuple[NounPhrase, ...]
    said: str
    restricted: str
    """The phrase it restricts, as said (for messages)."""


@dataclass(frozen=True)
class Attachment:
    """Words whose attachment the scene decides, at token ``at``: ``kind`` ``"without"`` (*the bedroom
    without a plant*: which bedroom, or what to avoid there?) or ``"and-contents"`` (*the bedroom with the
    book and the vase*: a room with both, or the vase as another goal?) or ``"apposition"`` (*the plant in
    the bedroom, the one in the office, and ...*: which plant, or the next item of the list?). ``prefix`` is
    the phrase up to those words, ``thing`` the object phrase that would describe it (the apposition). Read
    as described (``taken``), the words are a qualifier (the apposition); otherwise the phrase ends before
    them."""

    at: int
    kind: Literal["without", "and-contents", "apposition"]
    prefix: Described
    thing: NounPhrase
    span: Span
    taken: bool


Qualifier = (Possessive | OnFloor | InRoom | There | Holds | Lacks | Contains | NextTo | ByUnlisted | Except
             | Attachment | ShortStay | Between)


# ----------------------------------------------------------------------------------------------- actions
@dataclass(frozen=True)
class VerbWords:
    """The words before an action's noun phrase (the verb, whatever it is) and the floor they name
    (*go upstairs to ...*, *go down two floors to ...*)."""

    words: tuple[str, ...]
    floor: FloorSpec | None
    floor_span: Span | None
    first: bool = False
    """*go first to X*, *go before to X* (as learners write *first*): the action comes first."""
    again: bool = False
    """*go again to X*: a new visit of X (as *X again*)."""
    times: int = 1
    """*go twice / two times to X* (as learners place it): X that many times (as *X twice*)."""


@dataclass(frozen=True)
class Repeat:
    """After an action's phrases: *again*, *twice* / *three times*, *with a visit to Y in between*."""

    again: bool
    times: int
    between: Action | None


@dataclass(frozen=True)
class Action:
    """Verb words and the phrases acted on, with what follows them in the same action.

    ``moved``: the action said after a floor move (*go upstairs and <action>*, *go to the top floor, then
    <action>*): every goal of it is on that floor; then ``phrases`` is the floor (or ``None`` after
    *upstairs*). ``first``: *first* right after the phrases. ``ordered``: an order remark (*in that order*,
    or *then* after a list joined by commas). ``destination``: *to / in / on Y* after the phrases (carried
    things go there next). ``purpose``: *... to turn them off*. ``carried_on``: *bring to Y* with no object
    (what was taken before goes to Y: the phrases come after it).
    """

    span: Span
    verbs: VerbWords
    phrases: PhraseList | None
    moved: Action | None = None
    first: bool = False
    remark: tuple[str, ...] | None = None
    ordered: bool = False
    last: bool = False
    repeat: Repeat | None = None
    destination: PhraseList | None = None
    purpose: PhraseList | None = None
    in_condition: bool = False
    carried_on: bool = False
    destination_remark: tuple[str, ...] | None = None
    """A choice remark after the destination (*put it on the table in the dining room, any one*)."""
    done: bool = False
    """The target of *until* said as done (*until you're done in / have finished with / have done X*, *until X
    is done*): where things are done, more than a place gone to."""
    purpose_remark: tuple[str, ...] | None = None
    """A choice remark after the purpose (*go to the kitchen to grab an apple, either one*)."""
    instead: bool = False
    """*instead* closes the action (*keep out of the kitchen; check the couch instead*): read only after
    prohibitions alone (after a goal it takes that goal back)."""


# -------------------------------------------------------------------------------------------- body items
@dataclass(frozen=True)
class Link:
    """Words between clauses: a sequence word (*then*, *after that*; ``strict``: *only after that*),
    *on the way,* (``waypoint``: the next action comes before the goal named last), or none of these."""

    sequence: bool
    strict: bool = False
    waypoint: bool = False


@dataclass(frozen=True)
class PlainAction:
    """An action of a sentence body, with what the words around it say of its place in the sequence:
    ``moved_first`` (it ends with *first* / *before that* / *on the way*: not in the room of the step before
    it), ``goes_back`` (*back*, *return*), ``on_the_way`` (*X on the way*), ``trailing`` (*first* or
    *before that* after the action's tail; a *first* right after its phrases is :attr:`Action.first`)."""

    action: Action
    moved_first: bool
    goes_back: bool
    on_the_way: bool
    trailing: Literal["first", "before that"] | None
    rest: str
    """The words from the end of the action on, for messages."""
    more: str
    """What follows the action's fillers in the sentence ("" if nothing), for messages."""


@dataclass(frozen=True)
class AfterAll:
    """*and after all three (of them)* / *once you've done those*: what follows comes after every goal said
    before in the sentence (``number`` checked when said)."""

    said: str
    number: int | None


@dataclass(frozen=True)
class DoneWith:
    """*when done with X* inside a body: X goes before the step it is said in."""

    action: Action


@dataclass(frozen=True)
class InlineAfter:
    """*after / once X* inside a body: X goes before the step it is said in."""

    action: Action


@dataclass(frozen=True)
class InlineBefore:
    """*before X* inside a body: X is a step after the step it is said in."""

    action: Action


@dataclass(frozen=True)
class GoalsFirst:
    """*..., but first X* / *..., and before that X*: X comes before the steps said so far. ``obliged``: *...,
    but before that you must X*: an obligation (read as an order and as a restriction alike: refused)."""

    before_that: bool
    action: Action
    rest: str
    obliged: bool = False


@dataclass(frozen=True)
class CommaSequence:
    """A comma between actions followed, later in the sentence, by *then*: the actions are in order."""


@dataclass(frozen=True)
class Waypoint:
    """*via X*, *passing through X* after a goal: X on the way there."""

    words: tuple[str, ...]
    action: Action
    rest: str


@dataclass(frozen=True)
class StayOnFloor:
    """*stay on this floor*, *keep to floor 1*, *don't go to any other floor*: every room of the other floors
    is forbidden for the whole mission. ``other``: the words named the other floors (*any other floor*)."""

    floor: FloorSpec
    span: Span
    other: bool
    and_off: Negation | None
    """*stay on the top floor and off the stairs*: forbidden too, for the whole mission."""


@dataclass(frozen=True)
class OffLimits:
    """*X is off limits* / *X should be avoided*: never at X."""

    phrases: PhraseList


@dataclass(frozen=True)
class UntilDone:
    """*... until you have done that*: the step named before."""


@dataclass(frozen=True)
class Negation:
    """A prohibition: *always avoid X*, *never enter X*, *don't touch X*, *avoid X*, *without X*, *X until Y*.

    ``marker``: the words that start it (they decide whether it holds for the whole mission). ``stay``: a
    negated stay (*don't leave this floor*). ``floor``: *never go upstairs* (every room there).
    ``whole``: *the whole time* after it. ``until``: *until Y* after it."""

    marker: tuple[str, ...]
    stay: StayOnFloor | None
    verbs: VerbWords | None
    phrases: PhraseList | None
    floor: FloorPlace | None
    whole: bool
    until: Action | UntilDone | None


Item = (Link | PlainAction | AfterAll | DoneWith | InlineAfter | InlineBefore | GoalsFirst | CommaSequence
        | Waypoint | StayOnFloor | OffLimits | Negation)


@dataclass(frozen=True)
class Body:
    """The items of a sentence body, in order; ``actions``: how many plain actions it has."""

    items: tuple[Item, ...]

    @property
    def actions(self) -> int:
        return sum(isinstance(item, PlainAction) for item in self.items)


# ------------------------------------------------------------------------------------ sentences and rules
@dataclass(frozen=True)
class WheneverRule:
    """*whenever X, Y* / *Y whenever X*: each time the robot is at X, Y follows."""

    trigger: Action
    consequent: Body


@dataclass(frozen=True)
class IfRule:
    """*if X, Y* / *Y if X* (``word``: *if*, *when*, *in case*), said of one visit of X (each visit is
    *whenever* / *every time*); ``afterwards``: Y is said to follow X (*if you go into X, check Y
    afterwards*: after that visit of X)."""

    word: str
    condition: Action
    consequent: Body
    afterwards: bool = False


Rule = WheneverRule | IfRule


@dataclass(frozen=True)
class RuleSentence:
    """A sentence of condition rules (*whenever ...*, *if ...*), each kept."""

    rules: tuple[Rule, ...]


@dataclass(frozen=True)
class UntilSentence:
    """*Until (you have reached) Y, stay out of X*: the prohibitions hold until Y, which is a step."""

    target: Action
    body: Body


@dataclass(frozen=True)
class OnlyAfterSentence:
    """*Only after X, Y* / *only <do Y> after X* (``said_first``: X said first): Y, and not before X; and
    the condition rules joined to it."""

    before: Action
    body: Body
    rules: tuple[Rule, ...]
    said_first: bool


@dataclass(frozen=True)
class PrefixedSentence:
    """*After X, Y* / *Once X, Y* / *When done with X, Y* (``before`` False), *Before Y, X* / *On your way to
    Y, X* (``before`` True: the prefix comes last); ``strict``: *before Y, you must X*: Y, and not before
    X; ``on_the_way``: Y is where the robot is heading (*on your way to Y*)."""

    prefix: Action
    prefix_last: bool
    body: Body
    postfix: Postfix
    strict: bool = False
    on_the_way: bool = False


@dataclass(frozen=True)
class PlainSentence:
    """A body, with the room it is about (*In the kitchen, ...*) and a trailing condition."""

    scope: NounPhrase | None
    body: Body
    postfix: Postfix
    prohibitions: Body | None = None
    """Whole-mission prohibitions said after the condition (*X, but only after Y, and stay out of Z the whole
    time*): they hold beside it."""


@dataclass(frozen=True)
class OnlyIfPost:
    """*Y only if X*: Y implies X."""

    condition: Action


@dataclass(frozen=True)
class RulesPost:
    """A trailing condition: *Y whenever X* / *Y if X* (the body is the consequent), or *Y, and whenever X,
    Z* (the body stands alone), and further rules."""

    rules: tuple[Rule, ...]
    body_is_consequent: bool


@dataclass(frozen=True)
class OnlyAfterPost:
    """*Y only after X* / *Y, but not before X*."""

    before: Action


Postfix = OnlyIfPost | RulesPost | OnlyAfterPost | None

SentenceBody = RuleSentence | UntilSentence | OnlyAfterSentence | PrefixedSentence | PlainSentence


@dataclass(frozen=True)
class Announced:
    """What announced the list of a sentence, before a colon (*three things:*, *visit two rooms:*): the
    words of the noun group (``said``), the words before it (``prefix``, read with the list), how many items
    it said and the head noun they must fit."""

    said: str
    prefix: tuple[Tok, ...]
    count: int | None
    head: Head | None
    at: int = 0
    """The character offset of the announcement (one announcement may head several list items)."""
    scope: bool = False
    """The words before the colon name the room of what follows (*Kitchen: the fridge, then the sink*)."""
    suffix: tuple[Tok, ...] = ()
    """An order remark said before the colon, read after the list (*Do these in order: A, B*)."""


@dataclass(frozen=True)
class MissionSentence:
    """One sentence of the mission: how it joins the sentences before it, and what it says.

    ``opener``: *The whole time,* (the sentence must then be whole-mission avoidance only). ``precedes``:
    *Before that,* / *First,* (its goals go before the previous sentence's). ``lead``: the sequence words
    it starts with (*Then ...*). ``says_order``: the word *order* occurs (*The order doesn't matter.*).
    ``after_item``: an item of an ordered list after its first one (it continues the sequence, as *Then
    ...* does). ``floor_scope``: *On the top floor, ...* / *While you're upstairs, ...* (or a list's heading,
    *Top floor tasks:*): the goals of the sentence are on that floor. ``after_all``: *After all that, ...*
    / *Once you've done both, ...* (it continues the sequence after every goal of the sentence before).
    ``order_free``: *in either order* closes a clause of it (its actions are independent tasks: an object of
    one is not looked for in the room of another). ``marked``: an item on a line of its own after a list
    marker (*- go to the dining room and sit on a chair*): its actions are one item of the list, so an
    object is looked for in the room its line goes to, whatever announced the list."""

    opener: str | None
    precedes: str | None
    lead: Link
    body: SentenceBody
    says_order: bool
    span: Span
    announced: Announced | None = None
    after_item: bool = False
    floor_scope: FloorSpec | None = None
    after_all: AfterAll | None = None
    order_free: bool = False
    marked: bool = False


@dataclass(frozen=True)
class StatedStart:
    """A sentence that only says where the robot is: *I'm downstairs right now*, *we are on floor 1*."""

    floor: FloorSpec
    said: str


@dataclass(frozen=True)
class SetAside:
    """Words that ask nothing of the robot and are not read (*We're hosting dinner tonight.*, a list's heading
    *Shopping list check*), said back as not part of the mission (``said``: as typed); ``mentions``: the rooms
    and objects they name, which *there* may point back to (*Grandpa's napping in the bedroom, so stay out of
    there*)."""

    said: str
    mentions: tuple[NounPhrase, ...] = ()


Sentence = MissionSentence | StatedStart | SetAside


T = TypeVar("T")


def nodes(tree: object, kind: type[T]) -> Iterator[T]:
    """Every node of type ``kind`` in ``tree``, in text order (a node before the nodes inside it)."""
    if isinstance(tree, kind):
        yield tree
    if is_dataclass(tree) and not isinstance(tree, type):
        for f in fields(tree):
            yield from nodes(getattr(tree, f.name), kind)
    elif isinstance(tree, tuple):
        for child in tree:
            yield from nodes(child, kind)
