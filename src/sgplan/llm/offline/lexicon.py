"""The fixed vocabulary of the controlled English understood by the offline pattern translator.

Only words listed here (plus the room and object names of the scene, see :mod:`.names`) carry meaning.
Words in a verb slot that are not listed are accepted as verbs ("vacuum", "flush"), because whatever the
verb, the goal is the same: be in the room, or within reach of the object. Words that would change the
meaning of a mission in ways the translator does not model (``leave``, ``skip``, ...) are refused with an
error instead of being read as ordinary verbs.
"""

from __future__ import annotations

import re


def word_set(text: str) -> frozenset[str]:
    """The words of ``text`` (split at white space): the word lists below are written as running text."""
    return frozenset(text.split())


# Category synonyms: a word or phrase users say -> the scene categories it may denote (underscores of the
# Gibson categories are spaces here). A synonym only applies to categories the scene actually has.
SYNONYMS: dict[str, tuple[str, ...]] = {
    "fridge": ("refrigerator",),
    "icebox": ("refrigerator",),
    "television": ("tv",),
    "tv set": ("tv",),
    "telly": ("tv",),
    "sofa": ("couch",),
    "settee": ("couch",),
    "plant": ("potted plant",),
    "houseplant": ("potted plant",),
    "flower pot": ("potted plant",),
    "table": ("dining table", "coffee table", "table"),
    "basin": ("sink",),
    "washbasin": ("sink",),
    "stove": ("oven",),
    "cooker": ("oven",),
    "teddy": ("teddy bear",),
    "seat": ("chair",),
    "mug": ("cup",),
    "computer": ("laptop", "keyboard"),
    "hall": ("corridor",),
    "hallway": ("corridor",),
    "passage": ("corridor",),
    "lounge": ("living room",),
    "sitting room": ("living room",),
    "family room": ("living room",),
    "restroom": ("bathroom",),
    "washroom": ("bathroom",),
    "stairs": ("staircase",),
    "stairway": ("staircase",),
    "stairwell": ("staircase",),
    "office": ("home office",),
    "study": ("home office",),
    "entrance": ("lobby",),
    "foyer": ("lobby",),
    "entrance hall": ("lobby",),
    "laundry room": ("utility room",),
}

IRREGULAR_PLURALS: dict[str, str] = {"shelf": "shelves", "knife": "knives", "person": "people",
                                     "stairs": "stairs"}

ROOM_MODIFIERS = frozenset({"dining", "utility"})
"""First words of room categories used alone before an object: *the dining chairs* = the chairs in the
dining room (not *living*, *empty*, *home*: those are ordinary adjectives too)."""

GENERIC_ROOM_WORDS = ("room", "rooms", "place", "places", "area", "areas")
"""Heads meaning 'any room' ("every room on floor 0", "the room with two TVs")."""

ANAPHORIC_ONE = ("one", "ones")
"""``the one on floor 0`` / ``the ones with a bed``: the category of the noun phrase being restricted."""

PRONOUNS = ("it", "them", "they", "its")

WHOLE_BUILDING = ("house", "building", "home", "apartment", "flat")
"""``any TV in the house``: the whole building, which restricts nothing."""

INDEFINITE = ("a", "an", "any", "some", "either")
UNIVERSAL = ("all", "every", "each", "both")

NUMBER_WORDS = {
    "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9,
    "ten": 10,
}
FLOOR_ORDINALS = {
    "first": 0, "1st": 0, "second": 1, "2nd": 1, "third": 2, "3rd": 2, "fourth": 3, "4th": 3,
    "fifth": 4, "5th": 4,
}
"""``the first floor`` is the lowest floor (index 0): ordinals count floors from the lowest, US style."""
FLOOR_NAMED = {"ground": 0, "bottom": 0, "lowest": 0, "basement": 0}
FLOOR_TOP = ("top", "highest", "upper", "uppermost")
FLOOR_MIDDLE = ("middle",)
"""``the middle floor``: understood in a building with an odd number of floors (3: floor 1)."""

FLOOR_WORDS = ("floor", "level", "storey", "story")

POSITIVE_VERBS = word_set(
    """visit visits visiting visited enter enters entering entered go goes going went walk walks walking
    head heads heading move moves moving get gets getting come coming reach reaches reaching reached take
    takes taking took grab grabbing pick picking water watering watered clean cleaning cleaned vacuum
    vacuuming sit sitting touch touching touched open opening opened wash washing washed check checking
    find finding inspect inspecting look looking make making use using flush flushing turn turning switch
    switching fetch fetching collect collecting drive navigate navigating run running travel traveling
    travelling proceed pass passing through arrive arriving stop by at to into in on onto inside
    dust dusting wipe wiping tidy tidying feed put putting place placing drop dropping bring bringing carry
    carrying deliver delivering return returning explore exploring see seeing pet mop mopping scrub
    scrubbing fill filling close closing empty emptying sweep sweeping play playing cook cooking
    lie lying rest resting sleep sleeping shower showering bathe use off up down out over from for
    """
)
"""Verb-slot words known to mean "go to / interact with" the noun phrase that follows."""

CARRY_VERBS = word_set("put putting place placing drop dropping bring bringing carry carrying deliver "
                       "delivering take taking took move moving")
"""``put X in Y`` / ``bring X to Y``: the goal is Y (after X when X is a new noun phrase)."""

REFUSED_VERBS: dict[str, str] = {
    "leave": "'leave' (the translator cannot express leaving a place; say where to go instead)",
    "exit": "'exit' (say which room to go to instead)",
    "skip": "'skip' (use 'avoid' or 'never enter' to forbid a place)",
    "ignore": "'ignore' (use 'avoid' or 'never enter' to forbid a place)",
    "bypass": "'bypass' (use 'avoid' to forbid a place)",
    "dodge": "'dodge' (use 'avoid' to forbid a place)",
    "evade": "'evade' (use 'avoid' to forbid a place)",
    "escape": "'escape' (say which room to go to instead)",
    "forget": "'forget'",
    "miss": "'miss'",
    "remain": "'remain' (the translator cannot express staying in a place)",
    "wait": "'wait' (the translator cannot express waiting)",
    "repeat": "'repeat' (the translator cannot express repeated visits)",
    "twice": "'twice' here (say 'visit the kitchen twice')",
    "thrice": "'thrice' (say 'visit the kitchen twice', then again)",
    "unless": "'unless' (rephrase with 'if')",
    "except": "'except' here (put 'except ...' right after the noun phrase it restricts)",
    "previous": "'previous' (name the rooms or objects again instead of referring back to them)",
    "same": "'the same ...' (name the room or object again instead of referring back to it)",
    "former": "'the former' (name the room or object again instead of referring back to it)",
    "latter": "'the latter' (name the room or object again instead of referring back to it)",
    "other": "'other' (name the room or object explicitly)",
    "last": "'last' (name the room or object explicitly)",
    "most": "'most'",
    "least": "'least'",
    "nearest": "'nearest' (distances are not known to the translator; name the room or object)",
    "closest": "'closest' (distances are not known to the translator; name the room or object)",
    "farthest": "'farthest'",
    "only": "'only' here ('only if' and 'only after' are understood)",
    "maybe": "'maybe' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "perhaps": "'perhaps' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "possibly": "'possibly' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "optionally": "'optionally' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "hopefully": "'hopefully' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "ideally": "'ideally' (preferences cannot be expressed; say what must happen)",
    "preferably": "'preferably' (preferences cannot be expressed; say what must happen)",
    "try": "'try' (optional goals cannot be expressed; say what must happen)",
    "none": "'none' (say 'never enter X' to forbid a place)",
    "nothing": "'nothing' (say 'never enter X' or 'do not touch X')",
    "nowhere": "'nowhere' (say 'never enter X' to forbid a place)",
    "instead": "'instead' (say what to visit, and 'never enter X' for what not to)",
    "rather": "'rather' (say what to visit, and 'never enter X' for what not to)",
    "refrain": "'refrain' (say 'never enter X' / 'do not touch X')",
    "forbid": "'forbid' (say 'never enter X')",
    "forbidden": "'forbidden' here (say 'X is forbidden' or 'never enter X')",
    "prohibited": "'prohibited' here (say 'never enter X')",
    "banned": "'banned' here (say 'never enter X')",
    "hardly": "'hardly' (say 'never enter X' or make it a goal)",
    "rarely": "'rarely' (say 'never enter X' or make it a goal)",
    "seldom": "'seldom' (say 'never enter X' or make it a goal)",
    "barely": "'barely'",
    "fail": "'fail'",
    "lest": "'lest' (rephrase with 'never')",
    "cease": "'cease'",
    "quit": "'quit'",
    "prevent": "'prevent' (say 'never enter X')",
    "left": "'left' (say where to go and what to reach)",
    "otherwise": "'otherwise' (alternatives between actions are not understood; say 'visit A or B')",
    "else": "'else' (alternatives between actions are not understood; say 'visit A or B')",
    "alternatively": "'alternatively' (say 'visit A or B')",
    "sometimes": "'sometimes' (say what must happen)",
    "occasionally": "'occasionally' (say what must happen)",
    "often": "'often' (say what must happen)",
    "usually": "'usually' (say what must happen)",
    "normally": "'normally' (say what must happen)",
    "mostly": "'mostly' (say what must happen)",
    "almost": "'almost'",
    "nearly": "'nearly'",
    "repeatedly": "'repeatedly' (say 'twice' or 'three times')",
    "continuously": "'continuously'",
    "constantly": "'constantly'",
    "regularly": "'regularly'",
    "again and again": "'again and again'",
    "unnecessarily": "'unnecessarily'",
    "briefly": "'briefly'",
}
"""Words that would silently change the meaning if read as ordinary words: refused with a reason."""

FILLERS = word_set(
    """please also then eventually first firstly lastly finally afterwards later next
    at some point sometime you should must need needs to have has had be been is are was were can could
    would will shall robot and moreover additionally furthermore too as well go ahead kindly do though hey
    okay ok thanks
    """
)
"""Words that carry no meaning for the formula wherever they appear between clauses. Order words that do
carry meaning (*secondly*, *before that*, *but first*, a trailing *first*, *again*) are grammar, not
fillers (:mod:`.grammar`)."""

POLITE = (("make", "sure"), ("make", "sure", "that"), ("be", "sure", "to"), ("be", "sure", "that"),
          ("i", "need", "you", "to"), ("i", "want", "you", "to"), ("i", "would", "like", "you", "to"),
          ("i", "d", "like", "you", "to"), ("we", "need", "you", "to"), ("can", "you"), ("could", "you"),
          ("would", "you"), ("will", "you"), ("remember", "to"), ("i", "would", "like"), ("i", "need"),
          ("i", "want"), ("let", "us"), ("let", "'s"), ("for", "me"), ("the", "robot"), ("robot", ","),
          *((owner, noun, "is", "to") for owner in ("the", "your", "my", "our")
            for noun in ("task", "job", "goal", "mission", "aim", "objective", "plan", "errand")),
          *((owner, noun, "is") for owner in ("the", "your", "my", "our")
            for noun in ("task", "job", "goal", "mission", "aim", "objective", "plan", "errand")),
          ("all", "you", "need", "to", "do", "is"), ("all", "you", "have", "to", "do", "is"),
          ("what", "i", "need", "is", "for", "you", "to"), ("i", "would", "like", "it", "if", "you"),
          ("i", "would", "appreciate", "it", "if", "you"), ("if", "you", "could"), ("if", "you", "would"),
          ("would", "you", "mind"), ("do", "me", "a", "favor", "and"), ("do", "me", "a", "favour", "and"),
          ("go", "and"), ("please", "make", "sure"),
          *((word,) for word in ("task", "goal", "mission", "objective", "errand", "todo", "instructions")))
"""Polite or emphatic wrappers at a clause start ("could you ...", "make sure you ..."): no meaning."""

START_END_VERBS = word_set("start starting begin beginning end ending finish finishing")
"""``start in X`` / ``end (up) in X``: where the path starts or ends, which a goal cannot say (the start is
the robot's; an end would need an order): refused outside a condition, where *end up in* is just *go to*."""

RELATIVE_FLOORS = {"upstairs": 1, "downstairs": -1}
"""Floors relative to the robot's start floor (or, in a two-floor building, the upper / lower floor)."""

START_FLOOR_WORDS = ("this", "current", "my", "our")
"""``on this floor`` / ``on the current floor``: the robot's start floor."""

REVISIT_VERBS = word_set("return returning back")
"""``return to X`` / ``go back to X`` after X was visited: a new visit, as with ``again``."""

ORDER_MODIFIERS = (
    ("one", "after", "the", "other"), ("one", "after", "another"), ("in", "that", "order"),
    ("in", "this", "order"), ("in", "order"), ("in", "sequence"), ("sequentially",), ("one", "by", "one"),
    ("in", "turn"), ("consecutively",), ("successively",),
)
"""Said after a list: its items are done one after the other (in the order written, for explicit lists)."""

TIME_FILLERS = (("at", "some", "point"), ("at", "any", "time"), ("sometime",), ("eventually",), ("later",),
                ("in", "any", "order"), ("in", "whatever", "order"), ("in", "either", "order"),
                ("any", "order"),
                ("in", "no", "particular", "order"), ("whichever", "first"), ("whichever", "order"),
                ("order", "does", "not", "matter"), ("the", "order", "does", "not", "matter"),
                ("order", "is", "not", "important"), ("the", "order", "is", "not", "important"),
                ("it", "does", "not", "matter"), ("is", "fine"), ("at", "any", "point"),
                *((*order, *liking) for order in (("in", "any", "order"), ("in", "whatever", "order"),
                                                  ("in", "whichever", "order"), ("in", "either", "order"))
                  for liking in (("you", "like"), ("you", "want"), ("you", "prefer"), ("you", "choose"),
                                 ("you", "please"), ("you", "wish"),
                                 # "in whatever order is quickest": the planner's optimal order is that
                                 *(("is", best) for best in ("quickest", "fastest", "shortest", "best",
                                                             "easiest", "efficient", "cheapest")),
                                 ("is", "most", "efficient"), ("works", "best"), ("makes", "sense"),
                                 ("makes", "the", "most", "sense"), ("is", "the", "quickest"),
                                 ("is", "the", "fastest"), ("is", "the", "shortest"))),
                ("in", "whichever", "order"))
"""Phrases that say nothing beyond the default (every goal is 'eventually', sets are done in any order, a
choice is anyone's)."""

_CHOOSERS = (("either",), ("any",), ("whichever",), ("either", "one"), ("any", "one"), ("whichever", "one"),
             ("any", "of", "them"), ("either", "of", "them"), ("whichever", "of", "them"))
_FINE = ((), ("is", "fine"), ("is", "ok"), ("is", "okay"), ("is", "good"), ("will", "do"), ("works",),
         ("would", "do"), ("would", "be", "fine"), ("will", "be", "fine"), ("you", "like"), ("you", "want"),
         ("you", "prefer"), ("you", "choose"), ("is", "closer"), ("is", "nearer"))
CHOICE_AFFIRMATIONS = tuple(
    chooser + fine for chooser in _CHOOSERS for fine in _FINE
    if chooser + fine not in (("either",), ("any",))  # bare "either" / "any" start a noun phrase
) + (
    ("no", "matter", "which"), ("no", "matter", "which", "one"),
    ("it", "does", "not", "matter", "which"), ("does", "not", "matter", "which"),
    ("does", "not", "matter", "which", "one"), ("it", "does", "not", "matter", "which", "one"),
    ("i", "do", "not", "care", "which"), ("i", "do", "not", "mind", "which"), ("is", "fine"),
    ("your", "choice"), ("your", "pick"), ("take", "your", "pick"), ("you", "pick"), ("you", "choose"),
    ("it", "is", "up", "to", "you"), ("up", "to", "you"), ("i", "do", "not", "care"),
)
"""Said after a choice ("a bedroom, either one is fine"): it only confirms the choice. After a phrase that
means each of several ("the TVs, any of them") it would change the meaning, so it is refused there."""

_SPAN_NOUNS = ("mission", "task", "trip", "route", "run", "time", "way", "journey", "tour", "job", "thing",
               "path")
WHOLE_MISSION = (("the", "whole", "time"), ("the", "entire", "time"), ("at", "all", "times"),
                 ("at", "any", "time"),
                 ("at", "any", "point"), ("throughout",), ("the", "whole", "way"), ("all", "the", "time"),
                 ("on", "the", "way"), ("on", "your", "way"), ("along", "the", "way"), ("at", "all"),
                 ("all", "along"), ("for", "the", "duration"), ("the", "entire", "way"),
                 *((pre, "the", whole, noun) for pre in ("for", "during", "throughout", "over")
                   for whole in ("whole", "entire", "full") for noun in _SPAN_NOUNS),
                 *(("throughout", "the", noun) for noun in _SPAN_NOUNS),
                 ("while", "you", "do", "it"), ("while", "you", "do", "that"),
                 ("while", "you", "are", "at", "it"),
                 ("while", "doing", "so"), ("while", "doing", "that"), ("while", "doing", "it"),
                 ("in", "the", "process"),
                 *(("during", "the", noun) for noun in _SPAN_NOUNS))
"""Said after what to avoid: the prohibition holds for the whole mission (``G !x``), not only at one step."""


def plural(word: str) -> str:
    """English plural of the last word of a (multi-word) name: ``potted plant`` -> ``potted plants``."""
    head, _, last = word.rpartition(" ")
    if last in IRREGULAR_PLURALS:
        out = IRREGULAR_PLURALS[last]
    elif last in ("tv", "pc"):
        out = last + "s"
    elif re.search(r"(s|x|z|ch|sh)$", last):
        out = last + "es"
    elif re.search(r"[^aeiou]y$", last):
        out = last[:-1] + "ies"
    else:
        out = last + "s"
    return f"{head} {out}" if head else out


PHRASE_ALIASES: dict[tuple[str, ...], tuple[str, ...]] = {
    ("prior", "to"): ("before",),
    ("ahead", "of"): ("before",),
    ("in", "advance", "of"): ("before",),
    ("as", "soon", "as"): ("once",),
    ("the", "moment"): ("once",),
    ("right", "after"): ("after",),
    ("straight", "after"): ("after",),
    ("immediately", "after"): ("after",),
    ("start", "with"): ("first",),
    ("begin", "with"): ("first",),
    ("start", "off", "with"): ("first",),
    ("to", "start", ","): ("first", ","),
    ("to", "begin", ","): ("first", ","),
    ("to", "start", "with", ","): ("first", ","),
    ("to", "begin", "with", ","): ("first", ","),
    ("first", "of", "all"): ("first",),
    ("first", "off"): ("first",),
    ("last", "of", "all"): ("finally",),
    ("to", "finish", ","): ("finally", ","),
    ("to", "finish", "off", ","): ("finally", ","),
    ("to", "wrap", "up", ","): ("finally", ","),
    ("along", "with"): ("and",),
    ("together", "with"): ("and",),
    ("plus",): ("and",),
    ("anywhere", "near"): ("into",),
    ("where", "you", "can", "find"): ("containing",),
    ("where", "you", "will", "find"): ("containing",),
    ("where", "you", "find"): ("containing",),
    ("holding",): ("containing",),
    ("and", "also"): ("and",),
    # "take the stairs down to the ground floor": the stairs are the way there, not a goal; where to is
    # said after them
    **{("take", "the", stairs, way, "to"): ("go", way, "to")
       for stairs in ("stairs", "staircase") for way in ("down", "up")},
    **{(verb, way, "the", "stairs", "to"): ("go", way, "to")
       for verb in ("go", "walk", "head") for way in ("down", "up")},
}
"""Phrases read as another (``prior to`` is ``before``, ``as soon as`` is ``once``), rewritten on the tokens
before parsing (:func:`.text.rewrite`), so that no unknown word of such a phrase is taken for a verb."""
