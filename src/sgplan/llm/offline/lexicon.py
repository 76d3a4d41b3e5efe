"""The lexicon of the offline translator: every closed word list and phrase table it reads, in one place.

Only the words listed here (and the room and object names of the scene, :mod:`.nouns`) carry meaning.
Words in a verb slot that are not listed are accepted as verbs ("vacuum", "flush"), because whatever the
verb, the goal is the same: be in the room, or within reach of the object. Words that would change the
meaning of a mission in ways the translator does not model (``leave``, ``skip``, ...) are refused with a
reason instead of being read as ordinary verbs (:data:`REFUSED_WORDS`).

Sections: tokens, nouns, determiners, floors, verbs, fillers and remarks, order, negation, conditions,
qualifiers, chit-chat, phrase aliases. A table's docstring says what the grammar does with it; the rules
that read it are in :mod:`.syntax`.
"""

from __future__ import annotations

import re

from sgplan.llm.offline.phrases import Phrases, word_set

# ---------------------------------------------------------------------------------------------- tokens
NEGATED_STEMS = {"don": "do", "doesn": "does", "didn": "did", "can": "can", "won": "will", "mustn": "must",
                 "shouldn": "should", "isn": "is", "aren": "are", "haven": "have", "hasn": "has",
                 "wouldn": "would", "couldn": "could", "shan": "shall", "mayn": "may"}
"""``don't`` -> ``do not``: the auxiliary of a negated contraction (its stem before ``n't``)."""

BARE_NEGATED = {"dont": "do", "doesnt": "does", "didnt": "did", "cant": "can", "wont": "will",
                "mustnt": "must", "shouldnt": "should", "isnt": "is", "arent": "are", "havent": "have",
                "hasnt": "has", "wouldnt": "would", "couldnt": "could", "neednt": "need"}
"""Negated auxiliaries typed without their apostrophe: read as ``do not`` ... (never as a verb)."""

CONTRACTIONS = {"re": "are", "m": "am", "ve": "have", "ll": "will", "d": "would"}
"""``we're`` -> ``we are``: the verb of a contracted auxiliary (``'s`` is a token of its own: *is* or a
possessive)."""

IS_CONTRACTED = frozenset({"that", "there", "here", "what", "where", "who", "how"})
"""Words whose ``'s`` is *is* (*that's*, *there's a few*), never a possessive."""
BARE_CONTRACTIONS = {"youre": ("you", "are"), "theyre": ("they", "are"), "im": ("i", "am"),
                     "ive": ("i", "have"), "youve": ("you", "have"), "weve": ("we", "have"),
                     "thats": ("that", "is"), "theres": ("there", "is"), "youll": ("you", "will"),
                     "itll": ("it", "will"), "lets": ("let", "'s"), "whats": ("what", "is")}
"""Contractions typed without their apostrophe (*then youre done*): read as the words they stand for."""

WOULD_SUBJECTS = frozenset({"i", "you", "we", "they", "he", "she", "it", "that", "who", "what", "where",
                            "how", "there", "here", "this", "u"})
"""Before *'d* these are *would* / *had* (*I'd*, *you'd*); after any other word *'d* writes a past participle
in a note (*microwave chk'd*: checked)."""
SENTENCE_END = frozenset(".;:!?")
NUMBERED = frozenset({"floor", "level", "flr", "fl", "lvl", "storey", "story", "step", "item", "number",
                      "no"})
"""Before a number and ``)`` (*(floor 1)*): the number is theirs, not a list marker."""

SYMBOLS: dict[str, tuple[str, ...]] = {
    "+": ("and",), "&": ("and",), "w/": ("with",), "w/o": ("without",), "@": ("at",),
    "b/c": ("because",), "b4": ("before",),
}
"""Notations read as words (an arrow, ``->``, ``>``, ``→``, is *then*): ``A + B`` is *A and B*, ``bdrm w/
bed`` *bedroom with bed*. Every other symbol is a token the grammar refuses by name (``A / B``: and, or?)."""

DASHES = frozenset({"-", "--", "\u2013", "\u2014"})
"""The dashes of an aside (*the kitchen -- the one downstairs -- and ...*), read as commas."""
CLOCK_PREPOSITIONS = ("at", "by", "before", "after", "until", "till", "around", "about")
"""Before a clock time (*at 6 pm*): quoted with it in the refusal."""

LINE_CONTINUES = frozenset({",", "and", "or", "then", "but", "with", "to", "of", "in", "the", "a", "an"})
"""A line ending with one of these goes on in the next line (a wrapped sentence, not a new one)."""

# ----------------------------------------------------------------------------------------------- nouns
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
    "flowerpot": ("potted plant",),
    "flowers pot": ("potted plant",),
    "plant pot": ("potted plant",),
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
    "salon": ("living room",),  # learners' word (French, Polish, Russian)
    "dinner room": ("dining room",),
    "office room": ("home office",),
    "bath room": ("bathroom",),
    "bed room": ("bedroom",),
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
    "utility": ("utility room",),
    "hob": ("oven",),
    "fridge freezer": ("refrigerator",),
    "coffee cup": ("cup",),
    "teacup": ("cup",),
    "tea cup": ("cup",),
    "coffee mug": ("cup",),
    "water bottle": ("bottle",),
    "flower vase": ("vase",),
    "dinner table": ("dining table",),
    "pot plant": ("potted plant",),
    "tv screen": ("tv",),
    "armchair": ("chair",),
    "bathtub": ("bathtub", "bath"),
    "wash basin": ("sink",),
    "landing": ("corridor",),
    "front room": ("living room",),
    "shower room": ("bathroom",),
}
"""Category synonyms: a word or phrase users say -> the scene categories it may denote (underscores of the
Gibson categories are spaces here). A synonym only applies to categories the scene actually has."""

ABBREVIATIONS: dict[str, tuple[str, ...]] = {
    "lr": ("living room",), "liv rm": ("living room",), "lvng rm": ("living room",),
    "lvg rm": ("living room",),
    "dr": ("dining room",), "din rm": ("dining room",), "dng rm": ("dining room",),
    "dining": ("dining room",),  # "dining: both chairs", "keep out of dining" (never before "table")
    "br": ("bedroom", "bathroom"), "bdr": ("bedroom",), "bd": ("bedroom",), "mbr": ("bedroom",),
    "bth": ("bathroom",), "bthr": ("bathroom",), "bath": ("bathroom",), "baths": ("bathroom",),
    "teddy": ("teddy bear",), "teddies": ("teddy bear",),
    "kit": ("kitchen",), "kitch": ("kitchen",), "ktch": ("kitchen",),
    "ofc": ("home office",), "offc": ("home office",), "ofis": ("home office",),
    "hwy": ("corridor",), "hllwy": ("corridor",), "corr": ("corridor",),
    "kbd": ("keyboard",), "kybd": ("keyboard",), "tbl": ("dining table", "table"), "frdg": ("refrigerator",),
    "kb": ("keyboard",), "kbrd": ("keyboard",),
    "frig": ("refrigerator",), "micro": ("microwave",), "mw": ("microwave",), "tele": ("tv",),
    "plt": ("potted plant",), "chr": ("chair",),
}
"""Abbreviations people type for rooms and objects (*LR*, *bdrm*, *kbd*, *tbl*): read as the categories they
may denote, like :data:`SYNONYMS` (only those the scene has; one that could be several is refused as
ambiguous, naming them). The scene's own names give more (:mod:`.nouns`): the letters of a name without its
vowels (*bthrm*, *ktchn*) and *rm* for *room* (*bathrm*, *dining rm*)."""

EVERYDAY_NAMES: dict[str, tuple[str, ...]] = {
    "loo": ("bathroom", "toilet"),
    "lavatory": ("bathroom", "toilet"),
    "wc": ("bathroom", "toilet"),
    "cloakroom": ("bathroom", "toilet"),
}
"""Everyday names of a place no category spells: the first of the categories the scene has (*the loo* is
the bathrooms, or the toilets in a scene without bathrooms)."""
FIXTURE_VERBS = word_set("check inspect clean wipe scrub flush unblock")
"""Verbs that act on a thing: after one, *the loo* may be the toilet as well as the room (refused)."""

KIDS_ROOM_NAMES = (("kids", "room"), ("kid", "'s", "room"), ("kids", "'s", "room"),
                   ("children", "'s", "room"), ("childrens", "room"), ("nursery",), ("playroom",),
                   ("play", "room"))
"""Names of the room with the toys: the one room of the scene holding one of :data:`TOYS`."""

TOYS = frozenset({"teddy bear"})
"""Object classes that mark a child's room."""

IRREGULAR_PLURALS: dict[str, str] = {"shelf": "shelves", "knife": "knives", "person": "people",
                                     "stairs": "stairs"}

INTO_A_ROOM = word_set("to into inside enter entering visit visiting")
"""Before *the plant bedroom* (an object then a room: the room holding it): words that lead to a room, so
the phrase is a room (after *grab the bowl kitchen* the bowl may be meant)."""
ROOM_MODIFIERS = frozenset({"dining", "utility"})
"""First words of room categories used alone before an object: *the dining chairs* = the chairs in the
dining room (not *living*, *empty*, *home*: those are ordinary adjectives too)."""

GENERIC_ROOM_WORDS = ("room", "rooms", "place", "places", "area", "areas")
"""Heads meaning 'any room' ("every room on floor 0", "the room with two TVs")."""

ANAPHORIC_ONE = ("one", "ones")
"""``the one on floor 0`` / ``the ones with a bed``: the category of the noun phrase being restricted."""
RESTATED_CHOOSERS = frozenset({"any", "either"})
"""*a TV, any TV*, *a bed in the bedroom, either bed*: the choice said again, free."""
ORDINAL_ALONE_BEFORE = frozenset({"", ",", "again", "and", "then", "too", "once"})
"""After *the first* / *the second* with no noun (*then back to the first (again)*): the one named that
many-th before, as *the first one*."""
ONE_NOT_A_NOUN = frozenset({"of", "after", "another", "by", "at", "more", "floor", "floors", "level", "time"})
"""After *the <room> one*: *one* is a number, not a noun (*the lobby, one of them*, *the bathrooms one after
another*, *the bathroom one floor up*); else *the living room one* is the kind named last, in that room."""

PLURAL_LOOKING = frozenset({"stairs"})
"""Head nouns that look plural but are read as one entity (``the stairs`` is one staircase as a goal);
to avoid, on a mission confined to some floors, they mean each of them."""

DESCRIPTIVE = word_set(
    """big small large little tiny huge giant tall short long wide narrow old new older newer nice lovely
    pretty ugly comfy comfortable cosy cozy fancy favourite favorite usual messy dirty dusty broken shiny
    spare guest master main whole entire white black red blue green yellow grey gray brown pink purple
    orange wooden leather glass plastic metal corner front"""
)
"""Words that describe a thing without the scene saying which things they fit (*the big couch*, *the red
vase*): read only where they cannot change which entity is meant, when the phrase names one entity without
them; otherwise refused, naming the word (never ignored, never guessed). Words of a category of the scene
(*living* in *living room*) and verbs (*clean*, *empty*) are not among them."""

WHOLE_BUILDING = ("house", "building", "home", "apartment", "flat")
"""``any TV in the house``: the whole building, which restricts nothing."""


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


# ----------------------------------------------------------------------------------------- determiners
PRONOUNS = ("it", "them", "they", "its")
PLURAL_PRONOUNS = ("them", "they")
POSSESSIVES = word_set("my your our his her their")
"""*my / your ...* before a noun are read as *the*: *read my book*."""
OWNERS = ("his", "her", "their")
"""*her room*, *his bedroom*: a room said before to be someone's (*My sister is staying in the bedroom with
the two beds. Check her room.*), never a fresh room (whose?)."""
RESIDING = word_set("stay stays staying stayed sleep sleeps sleeping slept live lives living lived")
"""In a statement naming a room: the room is someone's (*my sister is staying in the bedroom*: *her room*)."""
_FEMALE_PEOPLE = word_set("she sister daughter mum mom mother wife grandma granny nan aunt auntie niece "
                          "girlfriend woman girl lady")
_MALE_PEOPLE = word_set("he brother son dad father husband grandpa grandad granddad uncle nephew boyfriend "
                        "man boy")
_GROUPS_OF_PEOPLE = word_set("they kids children parents guests guest friend friends cousin partner baby "
                             "family roommate flatmate")


def owners(pronoun: str) -> frozenset[str]:
    """Who *her / his / their room* may stand for (a statement must name one of them). Kept out of
    :data:`LEXICON_WORDS`: a person's word is no word of the grammar (*Grandma is in the kitchen* is a
    statement set aside)."""
    if pronoun == "her":
        return _FEMALE_PEOPLE
    if pronoun == "his":
        return _MALE_PEOPLE
    return _FEMALE_PEOPLE | _MALE_PEOPLE | _GROUPS_OF_PEOPLE
DEMONSTRATIVES = ("that", "this", "these", "those")
"""Determiners that point back (``the same`` and ``that same`` / ``this same`` too)."""
PLURAL_DEMONSTRATIVES = ("these", "those")
DETERMINERS = word_set("the a an any all every each both either this that these those some") | POSSESSIVES
INDEFINITE = ("a", "an", "any", "some", "either", "whichever")
CONTACT_SUBJECTS = ("you", "i", "we")
"""Right after a noun (*the chair you want*, *the bowl I left*): the subject of a relative clause without
*that* (refused: *in X* after it could be where the thing is or another goal); before order words, the
subject of a clause said to the robot (*..., you begin with X*)."""
UNIVERSAL = ("all", "every", "each", "both")
CHOOSING_OF = ("one", "any", "either")
"""``one of / any of / either of the X``: one of them."""
CHOICE_WORDS = frozenset({"a", "an", "any", "either", "one", "some", "whichever"})
"""Words before a noun that leave the choice of the entity to the robot (*a plant*, *any TV*)."""
ONE_SAID = ("one", "1")
"""*one* as notes also write it (*1 of the chairs*, *grab 1 bottle*): any one of them."""
DEFINITE = ("the", "this", "that", "these", "those")

ANNOUNCED = word_set("things thing tasks task errands errand jobs job chores chore items item stops stop "
                     "places spots bits stuff rounds visits checks destinations following these those this")
"""The last word of what announces a list after a colon (*three things:*, *the following:*, *check these:*);
a plural head noun of the scene does too (*visit two rooms:*)."""
ANNOUNCING = word_set("the a few couple of some several my your our today 's following quick little "
                      "small") | DETERMINERS
"""Words of an announcement's noun group before its last word (*a few quick things*, *today's tasks*)."""
LIST_NOUNS = word_set("list lists checklist todo do round rounds run runs tour route schedule agenda routine "
                      "plan steps step sequence order tasks task jobs job chores chore errands errand checks "
                      "check stops visits things items duties rota program programme rules rule dos donts "
                      "rundown")
"""Words that name a list in its heading (*Morning round*, *Evening checks*, *To do:*, *Top floor tasks*)."""
ORDER_NAMES = frozenset({"order", "sequence"})
"""Words of :data:`LIST_NOUNS` that name an order: a list so named (*Order of jobs:*, *Sequence:*) is done in
the order written, as a numbered one is (:func:`.syntax.lists.named_order`)."""
WORK_NOUNS = word_set("duty care patrol sweep sweeps maintenance cleanup inspection inspections walkthrough "
                      "circuit loop reset")
"""Nouns of a round of work that head a list or the steps after a colon as :data:`LIST_NOUNS` do
(*Bathroom duty:*, *Plant care:*, *Evening patrol:*): they name the work, never a goal."""
LIST_NOUNS = LIST_NOUNS | WORK_NOUNS
LABEL_STOPS = word_set("until till before after only except never not no if unless when whenever then first "
                       "last again twice once but or nor without stay remain keep staying avoid leave there")
"""Words a list's label never holds: a heading with one of them is a sentence of its own."""
ORDER_FILLERS = word_set(", do them these this it all the items steps things list")
LIST_JOINERS = frozenset({",", "and", "or", "then", "after", "before", "first", "last", "finally", "again",
                          "also", "too", "both", "all", "every", "each", "once", "when", "whenever", "if",
                          "until"})
"""Words that make a sentence more than one plain goal (a list, an order, a condition of its own): *In that
order.* after it is not read."""
"""Words of a sentence after a list that only says its order (*Do them in this order.*)."""
HEADS_UP = word_set("remember note important reminder ps also careful warning update oh btw nb urgent fyi "
                    "priority quick favour favor question request")
"""Words that only ask for attention before a colon (*Remember: never enter the kitchen.*)."""
WISH_HEADINGS = Phrases(tuple((*here, "what", *who, *wish) for here in ((), ("here", "is"), ("so",))
                              for who, wish in ((("i",), ("need",)), (("i",), ("want",)),
                                                (("i",), ("would", "like")), (("we",), ("need",)),
                                                ((), ("needs", "doing")), ((), ("needs", "to", "be", "done")),
                                                (("i",), ("need", "you", "to", "do")))))
"""Before a colon, what the speaker wants said as a heading (*What I need: ...*, *Here's what I'd like:*): it
asks nothing itself; the words after the colon say what."""
ANNOUNCE_TAIL = Phrases((("for", "me"), ("for", "today"), ("today",), ("to", "do"), ("please",),
                         ("for", "you"), ("to", "check"), ("to", "visit")))
"""Words after an announcement's noun group (*three things for me:*)."""

NUMBER_WORDS = {
    "one": 1, "two": 2, "three": 3, "four": 4, "five": 5, "six": 6, "seven": 7, "eight": 8, "nine": 9,
    "ten": 10,
}
MAX_REPEATS = 5
"""``X three times``: at most this many visits are understood."""

# ---------------------------------------------------------------------------------------------- floors
FLOOR_ORDINALS = {
    "first": 0, "1st": 0, "second": 1, "2nd": 1, "third": 2, "3rd": 2, "fourth": 3, "4th": 3,
    "fifth": 4, "5th": 4,
}
"""``the first floor`` is the lowest floor (index 0): ordinals count floors from the lowest, US style."""
FLOOR_NAMED = {"ground": 0, "bottom": 0, "lowest": 0, "basement": 0, "gnd": 0, "grnd": 0}
FLOOR_TOP = ("top", "highest", "upper", "uppermost")
FLOOR_ENDS_ALONE = ("top", "highest", "uppermost", "bottom", "lowest")
"""Before a room's noun without *floor* (*the top bathroom*): the top or lowest floor."""
FLOOR_MIDDLE = ("middle", "mid")
"""``the middle floor``: understood in a building with an odd number of floors (3: floor 1)."""
FLOOR_WORDS = ("floor", "level", "storey", "story", "flr", "fl", "lvl")
FLOOR_NAMES = (frozenset(FLOOR_ORDINALS) | frozenset(FLOOR_NAMED) | frozenset(FLOOR_TOP)
               | frozenset(FLOOR_MIDDLE))
"""The words that name a floor before *floor* (*ground*, *top*, *second*)."""
FLOOR_PLURALS = (*FLOOR_WORDS, "floors", "levels", "storeys", "stories", "flrs")
RELATIVE_FLOORS = {"upstairs": 1, "downstairs": -1}
"""Floors relative to the robot's start floor (or, in a two-floor building, the upper / lower floor)."""
START_FLOOR_WORDS = ("this", "current", "my", "our")
"""``on this floor`` / ``on the current floor``: the robot's start floor."""
FLOOR_DIRECTIONS = {"above": 1, "up": 1, "higher": 1, "upstairs": 1, "below": -1, "down": -1, "lower": -1,
                    "downstairs": -1, "beneath": -1, "under": -1}
"""``the floor above``, ``two floors down``: floors counted from the start floor."""
FLOOR_PREPOSITIONS = ("on", "in", "at", "of", "from")
"""Before a floor that qualifies a noun: *the bathroom on floor 1*."""
BACK_THERE = ("up", "down")
"""``up there`` / ``down there``: the floor of the place named last."""
OTHER_FLOOR = Phrases((("any", "other", "floor"), ("another", "floor"), ("a", "different", "floor"),
                       ("other", "floors"), ("any", "other", "floors"), ("change", "floors"),
                       ("change", "floor"), ("switch", "floors"), ("any", "other", "level"),
                       ("another", "level"), ("change", "levels"),
                       ("the", "other", "floors"), ("the", "other", "levels"), ("other", "levels"),
                       ("any", "of", "the", "other", "floors")))
"""``don't go to any other floor`` / ``don't change floors`` / ``keep off the other floors``: stay on the
start floor (a goal on another floor is then refused, as after *stay on this floor*; *the other floor*, one
of them, is a place and not read here)."""
STAY = frozenset({"stay", "remain", "keep", "staying", "remaining", "keeping"})
LEAVE = frozenset({"leave", "leaving"})
STAY_PREPOSITIONS = ("on", "to", "at", "in", "within")
"""``stay on / keep to / remain at <floor>``."""
TIME_SCOPED = frozenset({"until", "till", "before", "after", "once", "when", "whenever", "if", "unless",
                         "during"})
"""Words that may limit a *stay on this floor* to part of the mission: such a sentence confines nothing."""
STAY_AFTER = ("then", "afterwards", "later", "next", "finally")
"""``then stay on this floor``: for the rest of the mission only, which is not understood."""
STATED_SUBJECTS = Phrases((("i", "am"), ("we", "are"), ("you", "are"), ("the", "robot", "is"), ("i",),
                           ("we",), ("you",)))
"""*I'm* (the tokenizer drops the part after the apostrophe) / *we are* ... before where the robot is."""
STATED_NOW = ("currently", "now", "still", "already")
NOW = Phrases((("right", "now"), ("now",), ("currently",), ("at", "once"), ("at", "present"), ("with", "you"),
               ("with", "you", "now"), ("already",), ("now", "already"), ("by", "now")))
"""*right now* ...; *at the moment* reads *at once* here (:data:`PHRASE_ALIASES`: *the moment* = *once*);
*You're upstairs already, so ...*: where the robot is, said as where it has got to."""

# ----------------------------------------------------------------------------------------------- verbs
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
    read reading watch watching examine examining fix fixing straighten straightening hoover hoovering
    polish polishing arrange arranging organize organizing organise organising give giving clear clearing"""
)
"""Verb-slot words known to mean "go to / interact with" the noun phrase that follows."""

APPLIANCE_VERBS = word_set("heat heating warm warming reheat reheating cook cooking defrost defrosting toast "
                           "toasting")
"""*heat the bowl (up) in the microwave*: the bowl, then the microwave, as *put X in Y* (not the bowl that is
in the microwave)."""
CARRY_VERBS = word_set("put putting place placing drop dropping bring bringing carry carrying deliver "
                       "delivering take taking took move moving") | APPLIANCE_VERBS
"""``put X in Y`` / ``bring X to Y``: the goal is Y (after X when X is a new noun phrase)."""
CARRY_ON_VERBS = word_set("bring bringing brought carry carrying carried deliver delivering delivered take "
                          "taking")
"""*take an apple and bring to the kitchen*: said with no object, the thing taken before is carried there, so
the destination comes after it (not *move to*, *put in*, *drop in*: those also mean going)."""
PAST_CARRY_VERBS = word_set("brought carried delivered")
"""Of :data:`CARRY_ON_VERBS`, the past: *after you brought it to Y* says it was carried before."""
TAKING_VERBS = word_set("take grab get fetch pick collect retrieve")
"""Opening the clause before *, after you bring it to Y* (*Take the bowl, after you bring it to the table*):
it must be taken before it is carried, so *after* can only be *then* (as learners of English write it)."""
PUT_DOWN_VERBS = word_set("put place set drop")
"""*take an apple and put on the table*: after a verb of :data:`TAKING_VERBS` in the sentence, said with no
object, the thing taken is put there, after it (as *bring to*); with nothing taken before, unchanged."""
ROUTE_VERBS = word_set("from through via past")
"""``go from X to Y``, ``go through X to Y``: X, then Y."""
DESTINATION_WORDS = ("to", "into", "onto")
"""After an object (or a route): where it goes next (*bring the bowl to the table*)."""
CARRY_DESTINATION_WORDS = ("in", "into", "on", "onto", "to", "inside", "until", "till")
"""After a carry verb's object: *put the bowl in the sink*; *bring the bowl until the table* (as learners
write *to*)."""
PLACING_VERBS = word_set("put putting place placing drop dropping move moving") | APPLIANCE_VERBS
"""Carry verbs that say where the thing is put: after them, *on / in / by Y* (an object) is where it goes;
after *take / bring / carry* it could also say where the thing is, and is read so only before *to Z*."""
CARRY_BESIDE = Phrases((("by",), ("next", "to"), ("beside",), ("near",), ("right", "by"),
                        ("right", "next", "to"), ("just", "by"), ("close", "to")))
"""After a carry verb's object: *put the cup by the keyboard*: the keyboard is where it goes (a goal)."""
HANDLED_AT = ("at", "in", "on", "into", "inside", "under")
"""*rinse the watering can at the sink*, *heat my leftovers in the microwave*: before the scene's object
where a thing it does not hold is handled."""
FETCH_VERBS = (CARRY_VERBS - APPLIANCE_VERBS) | word_set(
    "get getting grab grabbing fetch fetching find finding pick picking collect collecting retrieve "
    "retrieving gather gathering")
"""Before a thing the scene does not hold (*put my keys on the table*): the robot would have to find it."""
TAKING_OUT_VERBS = word_set("get getting got grab grabbing grabbed fetch fetching fetched take taking took "
                            "pull pulling pulled")
"""*grab the bottle out of the bathroom*: before a thing taken, *out of X* says where it is (*from X*); after
other verbs (*keep the vase out of the kitchen*) it may say where it must not be, and is not read."""

CAUTION_PAIRS = frozenset({("take", "care"), ("watch", "out"), ("look", "out"), ("never", "mind")})
"""Two words that say how to behave near a place, or to disregard it (*take care in the kitchen*, *watch
out for the vase*, *never mind the office*): no goal and no prohibition, so refused, not read as a visit."""

CAUTION_VERBS = frozenset({"mind", "beware"})
"""Verbs of caution before a place (*mind the stairs*): refused like :data:`CAUTION_PAIRS`."""
CAUTIONS = frozenset({"careful"})
"""A caution without its verb: alone in the clause before what it warns of (*Careful, the office is off
limits*, *Careful now, don't ...*) a remark, said back; before a place (*careful in the office*, *Careful, the
office.*) refused like :data:`CAUTION_PAIRS` (not *carefully*, which says how to do an order)."""

BE_FINE = frozenset({"sure", "certain"})
"""*be sure to ...*: a wrapper, not a manner of being (:func:`.syntax.actions.refused_verb`)."""


SUPERLATIVES = word_set("best worst most least")
"""Words that compare the things of a kind (with any word of 6 letters or more ending in *-est*, but
:data:`NOT_SUPERLATIVE`): which one is heaviest, ripest, cleanest is not in the scene."""
NOT_SUPERLATIVE = word_set("interest forest honest modest harvest request guest guests chest")

REFUSED_WORDS: dict[str, str] = {
    "leave": "'leave' (the translator cannot express leaving a place; say where to go instead)",
    "postpone": "'hold off on / postpone' (put off until when? Say 'only after X, ...' for later, or 'don't "
                "...' to leave it out)",
    "him": "'him' (a person cannot be planned for; for a thing, say 'it')",
    "depending": "'if so / if yes / depending on' (what the robot finds there is not known when the "
                 "plan is made; say what to do in every case)",
    "exit": "'exit' (say which room to go to instead)",
    "between": "'between' (between which steps? Say the order with 'then': 'A, then B, then A again')",
    "meanwhile": "'meanwhile' (while doing what? Say the order with 'then', or 'on the way')",
    "meantime": "'in the meantime' (while doing what? Say the order with 'then', or 'on the way')",
    "simultaneously": "'simultaneously' (the robot does one thing at a time; say the order with 'then')",
    "earlier": "'earlier' (before which step? Say 'before that' or 'first')",
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
    "probably": "'probably' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "likely": "'likely' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "optionally": "'optionally' (optional goals cannot be expressed; leave the goal out or make it a goal)",
    "optional": "'optional' (optional goals cannot be expressed; leave the goal out or make it a goal)",
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

START_VERBS = word_set("start starting begin beginning")
"""``start in X``: where the path starts, which is the robot's: refused (outside a condition, where it is just
being in X)."""
END_VERBS = word_set("end ending finish finishing")
"""``end (up) in X`` / ``finish at X``: X after the rest (the plan ends once the mission is done: there)."""
START_END_PARTICLES = ("in", "at", "up", "with")
REVISIT_VERBS = word_set("return returning back")
"""``return to X`` / ``go back to X`` after X was visited: a new visit, as with ``again``."""
MODALS = frozenset({"do", "does", "may", "can", "must", "should", "will"})
"""In a verb slot without a negation after it: no meaning (*may you go into ...*, *I do want you to ...*)."""
ORDER_MODALS = frozenset({"must", "should"})
"""After *you*, the modals of an order (*Today you must not enter X*); not *you will / can*, which may say
what is not needed (*you won't need X*)."""
DONE_WHAT = ("it", "that", "this", "so")
"""``do it`` / ``do that``: what was done, not a place (refused as a goal)."""
VERB_IDIOMS = Phrases((("all", "the", "way"), ("a", "look"), ("a", "quick", "look"), ("a", "peek"),
                       ("a", "glance"), ("a", "quick", "peek"), ("your", "way"), ("my", "way"),
                       ("its", "way"), ("a", "visit"), ("a", "quick", "visit"), ("a", "trip"),
                       ("a", "quick", "trip"), ("a", "detour"), ("a", "stop"), ("a", "quick", "stop"),
                       ("a", "seat"), ("a", "nap"), ("a", "rest"), ("a", "good", "look"),
                       ("a", "proper", "look"), ("a", "little", "look"), ("a", "quick", "glance"),
                       ("a", "little", "peek"),
                       *(("a", *quick, walk) for quick in ((), ("quick",))
                         for walk in ("round", "walk"))))
"""Words of a verb that look like a noun phrase: *take a look at*, *make your way to*, *pay a visit to*, *do a
round through* (a chore at the place: a visit; not *a lap*: *lap* would become a known word, and *the lap-
uh, the laptop* a thing named)."""
BACK_TO_START_ENDS = frozenset({"", ",", "and", "then", "here", "again", "please"})
"""After *come back* / *and back* with no place: the robot would return to where it started."""
CHORE_PHRASALS = Phrases((("top", "up"), ("topping", "up"), ("top", "off")))
"""Chore verbs whose first word is also a word of floors (*top up the plant*, not *the top floor*)."""
GIVE_VERBS = frozenset({"give", "giving"})
"""*give X a look*: read only with what is given after X (:data:`GIVEN_LOOKS`), never alone (*give X to
Y*)."""
GIVEN_LOOKS = Phrases(tuple((*quick, what) for quick in ((), ("quick",), ("good",), ("little",), ("proper",))
                            for what in ("look", "check", "glance", "peek", "clean", "wipe", "dust",
                                         "visit", "tidy", "scrub", "wash", "polish", "hoover", "sweep",
                                         "mop", "spray"))
                     + tuple((*quick, "once", "over") for quick in ((), ("quick",), ("good",))))
"""What *give X ...* gives X, after *a* (*give the toilet a quick look*): acting on X there."""
THERE_POINTING = frozenset({"out", "over"})
"""Before *there* after an object (*both plants out there*, *the vase over there*): *there* as it is."""
THERE_SAID = Phrases((("there",), ("while", "you", "are", "there"), ("while", "you", "are", "in", "there"),
                     ("while", "there"), ("while", "you", "are", "at", "it", "there"),
                     ("while", "you", "are", "at", "it"), ("while", "you", "are", "about", "it")))
"""After an action, closing its clause: where the step is (*look at the clock while you're in there*; *sit on
the couch while you're at it*, in the course of what was said before)."""
CLAUSE_ENDS = frozenset({"", ",", "and", "then", "but"})
GIVEN_MANNER = frozenset({"quick", "good", "little", "proper", "gentle", "thorough", "light", "fast"})
"""Between *a* and a chore said as a noun (*give the couch a good fluff*)."""
GIVEN_AGAIN = frozenset({"another"})
"""*give X another splash / look*: the chore given again (a new visit of X, as *X again*)."""
LOOK_LIGHT_VERBS = frozenset({"take", "taking"})
"""Before *a (quick) look* (*have a look* is read *take a look*)."""
LOOK_NOUNS = frozenset({"look", "peek", "glance"})
"""The last word of a look said as a noun (*a quick look*, *a peek*)."""
LOOK_AROUND = frozenset({"around", "round", "about", "inside"})
"""After a look at nothing named (*go to the lobby and have a look around*): the room just named."""
LOOKED_AGAIN = Phrases(tuple(("another", *quick, what) for quick in ((), ("quick",), ("good",), ("little",),
                                                                ("proper",), ("close",), ("closer",))
                             for what in ("look", "peek", "glance", "visit", "trip", "stop", "check")))
"""*have / take another look at X*, *pay another visit to X*, *make another trip to X*: a verb idiom of a new
visit of X (as *X again*)."""
GIVEN_ENDS = frozenset({"", ",", "and", "then", "but", "please", "too", "as", "before", "after", "first"})
"""After *give X a <chore>*: the clause ends (a word after the chore may make it a thing: *a new flower*)."""
BODY_PART_OWNERS = ("your", "my", "his", "her", "their")
BODY_PART_LINKS = ("at", "using", "with", "on", "into")
"""*wash your hands at the sink*, *pop your head into the office*: a body part before a place is part of the
verb (not *in*: *wash your hands in the bathroom* implies a sink that is not said)."""
PARTICLES = word_set("on off up down out over")
AWAY_VERBS = word_set("put puts putting tidy tidies tidying pack packs packing stow stows stowing store "
                      "stores storing")
"""Before *away* (*put away the bowl*, *put the bowl away*): the verb's particle; the object is reached (where
it is put away is not said)."""
CHECK_THAT = ("that", "if", "whether")
CHECK_VERBS = word_set("check checks checking checked see seeing seen ensure ensuring ensured verify "
                       "verifying verified confirm confirming confirmed make made sure look looking looked")
"""*check that / if X is Y*: X is the goal (the state is what the check sees there)."""
STATE_VERBS = ("is", "are", "'s", "looks", "look", "seems")
"""After *check (that) X*: the verb of the state the check sees (*is off*, *looks tidy*)."""
KEPT_AWAY_STATES = word_set("untouched alone skipped avoided limits bounds undisturbed unvisited entered "
                            "touched disturbed empty clear")
"""States that say the robot stays away (*make sure the office is left alone*, *... is untouched*): not a
state the check sees there, so the check is not read as a visit."""
CHECK_WRAPPERS = Phrases((("make", "sure"), ("make", "sure", "that"), ("please", "make", "sure"),
                          ("be", "sure", "that")))
"""Polite wrappers that are the check's own verb before a thing and its state (*make sure the oven is
off*: the oven)."""
UP_DOWN = {"up": "upstairs", "down": "downstairs"}
FLOOR_CHANGES = frozenset({"up", "down", "upstairs", "downstairs"})
"""In the verb words of an action (*then head down to the kitchen*): it leaves the floor a sentence's
opening put its goals on (*While you're on the top floor, ...*)."""
"""*go up and X* / *come down and X*: upstairs / downstairs, and X there."""
NOT_A_SEQUENCE = frozenset({"if", "whenever", "until", "unless", "when", "while", "order", "whichever"})
"""Words that make a sentence's comma-joined actions no sequence as written: a condition, or *(in any
order)* / *whichever first*."""
CARRIED_ALL = frozenset({"everything", "all"})
"""What a carry verb takes when it takes what was fetched before (*bring everything down to the lobby*, *take
it all to X*): its destination comes after every goal of the sentence (as *... last*)."""
SUBJECT_FILLERS = word_set("you we i the robot it ever have has had do does did are is were was already "
                           "been also first")
"""Skipped before the verb of a clause that follows a conjunction (*after you have been to X*)."""
FUTURE_AUXILIARIES = frozenset({"will", "shall", "would"})
"""After *after you* inside a sentence (*X, after you will go to Y*): no tense of a clause of time, so
learners' *afterwards you will* as much as *after*: refused."""
LIST_PREPOSITIONS = frozenset({"to", "into", "by", "past", "through", "on", "onto"})
"""Repeated in a list after *either* / *both*: *either to A or to B*."""
SHORT_STAYS = Phrases(tuple(("for", "a", *little, spell) for little in ((), ("little",), ("quick",))
                            for spell in ("bit", "while", "sec", "second", "moment", "minute")))
"""*sit on the couch for a bit / a (little) while / a sec / a moment / a minute*: how long to stay at a goal,
said casually; the plan reaches it and says the words back as not part of the mission (a time counted, *for
ten minutes*, *for two minutes*, is not among them: refused as a duration)."""
STAY_TIMED_CLAUSES = word_set("once until till before after unless while")
"""Words of a clause that make a short stay in it the time of something else (*until you've sat on the couch
for a bit*): refused."""
OBJECT_PLACING = frozenset({"at", "on", "under", "beside", "behind", "above", "below", "near", "by"})
"""Before an object, after an object: placed by it (*the chair at the desk*), which the scene cannot tell."""
AFTER_UNLISTED_THING = word_set("and then in upstairs downstairs there please first too for")
"""After *on the counter* (a thing the scene does not hold, after an object): where the words naming that
thing end (any other word may go on naming it: *on the counter top*, *on the side of the couch*)."""
REPEATED_PREPOSITIONS = LIST_PREPOSITIONS | {"from", "of", "in", "at"}
"""Said again before a further item of a list they began (*keep away from A and from B*)."""
PLACE_PREPOSITIONS = frozenset({"to", "into", "in", "at", "on", "by", "through", "past", "inside"})
"""Before a place (*go first to the kitchen*)."""
VERB_STOPS = frozenset({",", "and", "or", "then", "if", "until", "before", "after", "when", "without"})
"""Words that end the verb words of an action."""

# -------------------------------------------------------------------------------- fillers and remarks
FILLERS = word_set(
    """please also then eventually first firstly lastly finally afterwards later next
    at some point sometime you should must need needs to have has had be been is are was were can could
    would will shall robot and moreover additionally furthermore too as well go ahead kindly do though hey
    okay ok thanks
    """
)
"""Words that carry no meaning for the formula wherever they appear between clauses. Order words that do
carry meaning (*secondly*, *before that*, *but first*, a trailing *first*, *again*) are grammar, not
fillers."""
NOT_FILLERS_HERE = ("do", "and", "then", "next")
"""Fillers that the filler rule leaves to other rules (*do not*, *and then*, *next to*)."""
SOUNDS = word_set("um umm uh uhh uhm er erm ehm hmm hm ah ahh mm mmm ooh oooh")
"""Hesitation sounds of spoken missions (*go to the uh bedroom*): no word at all, removed before parsing."""
HESITATIONS = SOUNDS | word_set("like yeah yep so well basically actually anyway alright right just "
                                "literally")
"""Hesitations and discourse words of spoken and dictated missions (*um, go to the kitchen and then like go
sit on the couch*): no meaning between clauses, like :data:`FILLERS`."""

_TASK_NOUNS = ("task", "job", "goal", "mission", "aim", "objective", "plan", "errand")
POLITE = Phrases((
    ("make", "sure"), ("make", "sure", "that"), ("be", "sure", "to"), ("be", "sure", "that"),
    ("i", "need", "you", "to"), ("i", "want", "you", "to"), ("i", "would", "like", "you", "to"),
    ("i", "d", "like", "you", "to"), ("we", "need", "you", "to"), ("can", "you"), ("could", "you"),
    ("would", "you"), ("will", "you"), ("remember", "to"), ("i", "would", "like"), ("i", "need"),
    ("i", "want"), ("let", "us"), ("let", "'s"), ("for", "me"), ("the", "robot"), ("robot", ","),
    # not "the first / next task is to": that says an order
    *((owner, *main, noun, *be) for owner in ("the", "your", "my", "our")
      for main in ((), ("main",), ("only",)) for noun in _TASK_NOUNS for be in (("is", "to"), ("is",))),
    ("all", "you", "need", "to", "do", "is"), ("all", "you", "have", "to", "do", "is"),
    # "(the) main thing is to ...": what the mission is, said as a remark
    *((*the, main, "thing", "is", *to) for the in ((), ("the",)) for main in ("main", "only", "big")
      for to in (("to",), ())),
    ("what", "i", "need", "is", "for", "you", "to"), ("i", "would", "like", "it", "if", "you"),
    ("i", "would", "appreciate", "it", "if", "you"), ("if", "you", "could"), ("if", "you", "would"),
    ("would", "you", "mind"),
    *(("do", who, "a", favour, "and") for who in ("me", "us") for favour in ("favour", "favor")),
    *((*ask, *you) for ask in (("would", "it", "be", "possible"), ("is", "it", "possible"),
                               ("would", "it", "be", "okay"), ("would", "it", "be", "ok"))
      for you in (("for", "you", "to"), ("to",))),
    *(("i", *wonder, "if", "you", *modal)
      for wonder in (("was", "wondering"), ("wonder",), ("am", "wondering"))
      for modal in (("could",), ("would",), ("might",), ("can",), ("would", "mind"))),
    *(("i", "would", *really, *feel, "if", "you", *modal)
      for really in ((), ("really",), ("so",))
      for feel in (("be", "grateful"), ("appreciate", "it"), ("love", "it"), ("like", "it"),
                   ("be", "thankful"))
      for modal in ((), ("could",), ("would",))),
    ("do", "you", "think", "you", "could"), ("any", "chance", "you", "could"),
    *(("i", "would", "be", *very, glad, "if", "you", *modal)  # "I'd be ever so grateful if you could"
      for very in (("ever", "so"), ("very",), ("so",), ("really",), ("most",))
      for glad in ("grateful", "thankful") for modal in ((), ("could",), ("would",))),
    ("is", "there", "any", "chance", "you", "could"), ("is", "there", "a", "chance", "you", "could"),
    *(("would", "it", "be", "too", "much", "to", "ask", *you, "to") for you in ((), ("for", "you"))),
    ("could", "i", "ask", "you", "to"),
    ("can", "i", "ask", "you", "to"), ("would", "you", "be", "able", "to"), ("could", "you", "possibly"),
    ("can", "you", "possibly"), ("would", "you", "be", "willing", "to"), ("i", "would", "like", "you", "to"),
    ("if", "you", "could", "please"), ("please", "could", "you"), ("please", "can", "you"),
    ("go", "and"), ("please", "make", "sure"), ("would", "you", "be", "so", "kind", "as", "to"),
    ("come", "and"),  # "come and look at X", as "go and look at X"
    ("would", "you", "kindly"), ("could", "you", "kindly"), ("would", "you", "please"),
    ("could", "you", "please"),
    ("be", "a", "dear", "and"), ("be", "a", "star", "and"),
    *((word,) for word in ("task", "goal", "mission", "objective", "errand", "todo", "instructions", "target",
                           "tgt"))))
"""Polite or emphatic wrappers at a clause start ("could you ...", "make sure you ..."): no meaning."""
POLITE = POLITE + Phrases((("whatever", "you", "do"), ("whatever", "happens"), ("above", "all"),
                           ("most", "importantly"), ("more", "importantly"),
                           # "the main job's just to ...", "main thing's simply to ..."
                           *((*owner, *main, noun, be, just, "to") for owner in ((), ("the",), ("your",))
                             for main in ((), ("main",), ("only",)) for noun in (*_TASK_NOUNS, "thing")
                             for be in ("is", "'s") for just in ("just", "simply", "only")),
                           *((*owner, "main", noun, "'s", "to") for owner in ((), ("the",))
                             for noun in (*_TASK_NOUNS, "thing")),
                           # "I just need you to ...", "all I need is for you to ..."
                           *((who, just, want, "you", "to") for who in ("i", "we")
                             for just in ("just", "only", "really") for want in ("need", "want")),
                           *(("all", who, want, "is", "for", "you", "to") for who in ("i", "we")
                             for want in ("need", "want", "ask")),
                           *(("all", who, want, "you", "to", "do", "is", *to) for who in ("i", "we")
                             for want in ("need", "want") for to in ((), ("to",))),
                           # "be an angel and ...", "would you be a sweetheart and ..."
                           *((*would, "be", a, dear, "and")
                             for would in ((), ("would", "you"), ("could", "you")) for a in ("a", "an")
                             for dear in ("angel", "sweetheart", "darling", "doll", "love", "gem", "treasure",
                                          "dear", "star", "sport")),
                           # spoken to an assistant: "Alexa, tell the robot to ..."
                           *((tell, "the", "robot", "to") for tell in ("tell", "ask", "get"))))
"""Emphatic openers of an order (*whatever you do, don't ...*, *above all, ...*) and wrappers of one (*the
main job's just to ...*, *I just need you to ...*, *tell the robot to ...*): no meaning."""
_HEDGED_ENDS = frozenset({("could",), ("can",), ("would",),
                          ("could", "you"), ("can", "you"), ("would", "you")})
POLITE = POLITE + Phrases((*phrase, hedge) for phrase in POLITE
                           if phrase[-1:] in _HEDGED_ENDS or phrase[-2:] in _HEDGED_ENDS
                           for hedge in ("possibly", "maybe", "perhaps", "just"))
"""*I was wondering if you could possibly ...*, *would you maybe ...*: a hedge right after a polite wrapper's
modal is part of the wrapper (elsewhere *possibly X* / *maybe X* asks for an optional goal: refused)."""

SOFTENERS = frozenset({"maybe", "perhaps"})
"""*Perhaps look in on the office first*, *... and maybe have a peek at the TV*, *... and then maybe the
bed*: before a step's verb at the start of a clause, or after *then*, a softened request, read as the step
(every held-out writer read it so, 11 missions); elsewhere (*A and maybe B* without a verb, *or maybe on the
couch*, *maybe it's his*), or when the mission says a step may be left out, it is not skipped."""

_ORDER_LIKING = (("you", "like"), ("you", "want"), ("you", "prefer"), ("you", "choose"), ("you", "please"),
                 ("you", "wish"), ("suits", "you"), ("is", "fine"), ("works",), ("suits",), ("'s", "fine"),
                 ("is", "ok"), ("is", "okay"), ("'s", "ok"), ("'s", "okay"), ("works", "for", "you"),
                 *(("is", easy) for easy in ("easiest", "easier", "simplest", "quicker", "faster", "shorter",
                                             "convenient")),
                 ("is", "most", "convenient"),
                 # "in whatever order is quickest": the planner's optimal order is that
                 *(("is", best) for best in ("quickest", "fastest", "shortest", "best", "easiest",
                                             "efficient", "cheapest")),
                 ("is", "most", "efficient"), ("works", "best"), ("makes", "sense"),
                 ("is", "fine", "by", "me"), ("is", "fine", "with", "me"), ("is", "ok", "by", "me"),
                 ("is", "okay", "by", "me"),
                 ("makes", "the", "most", "sense"), ("is", "the", "quickest"), ("is", "the", "fastest"),
                 ("is", "the", "shortest"),
                 ("you", "fancy"), ("you", "think", "best"), ("you", "think", "is", "best"),
                 ("you", "see", "fit"),
                 ("you", "feel", "like"), ("you", "reckon", "is", "best"), ("is", "handiest"),
                 ("you", "find", "easiest"))
_ORDER_LIKING += tuple((*liking, "for", "you") for liking in _ORDER_LIKING  # "... is quickest for you"
                       if liking[0] in ("is", "'s") and liking[-1] not in ("me", "you"))
ANY_ORDER = Phrases((
    ("in", "any", "order"), ("in", "whatever", "order"), ("in", "either", "order"), ("any", "order"),
    ("in", "no", "particular", "order"), ("whichever", "first"), ("whichever", "order"),
    ("order", "does", "not", "matter"), ("the", "order", "does", "not", "matter"),
    *((*it, "does", "not", "matter", "which", *one, "first")
      for it in ((), ("it",)) for one in ((), ("one",))),
    ("order", "is", "not", "important"), ("the", "order", "is", "not", "important"),
    *((*order, *liking) for order in (("in", "any", "order"), ("in", "whatever", "order"),
                                      ("in", "whichever", "order"), ("in", "either", "order"),
                                      ("any", "order"),
                                      ("whatever", "order"), ("whichever", "order"), ("either", "order"))
      for liking in _ORDER_LIKING),
    ("in", "whichever", "order"), ("whatever", "order"), ("either", "order"), ("no", "particular", "order"),
    *((*in_, "which", "order", *liking) for in_ in ((), ("in",))
      for liking in _ORDER_LIKING),  # learners: "(in) which order you want"
    ("the", "order", "is", "up", "to", "you"), ("order", "is", "up", "to", "you"),
    # "in any order doesnt matter", "any order, it doesn't matter": the order said free twice
    *((*order, *comma, *it, "does", "not", "matter") for order in (("in", "any", "order"), ("any", "order"),
                                                                   ("in", "whatever", "order"),
                                                                   ("whatever", "order"), ("either", "order"))
      for comma in ((), (",",)) for it in ((), ("it",))),
    *((*who, "do", "not", "care", what, "order") for who in ((), ("i",)) for what in ("what", "which")),
    ("i", "do", "not", "care", "about", "the", "order"), ("i", "do", "not", "mind", "the", "order"),
    ("i", "do", "not", "mind", "about", "the", "order"), ("do", "not", "worry", "about", "the", "order"),
    *((*the, "order", *really) for the in ((), ("the",))
      for really in (("does", "not", "really", "matter"), ("really", "does", "not", "matter"),
                     ("is", "not", "really", "important"), ("does", "not", "matter", "much"),
                     ("does", "not", "matter", "at", "all"))),
    ("i", "do", "not", "really", "mind", "the", "order"), ("i", "do", "not", "really", "care", "about", "the",
                                                           "order"),
    # "whichever's quickest", "however you like", "doesn't matter which order", "the order's up to you"
    *((chooser, be, best) for chooser in ("whichever", "whatever") for be in ("is", "'s")
      for best in ("quickest", "easiest", "fastest", "shortest", "simplest", "best")),
    *(("however", "you", like) for like in ("like", "want", "prefer", "wish", "please")),
    *((*it, *does, "matter", "which", "order") for it in ((), ("it",))
      for does in (("does", "not"), ("doesnt",))),
    ("no", "matter", "which", "order"), ("do", "not", "mind", "which", "order"),
    ("i", "do", "not", "mind", "which", "order"), ("the", "order", "'s", "up", "to", "you"),
    ("order", "'s", "up", "to", "you"),
    ("before", "or", "after"),  # "and also the bathroom, before or after": either order
    # learners put the order last: "doesn't matter the order", "is not important which one first"
    *((*it, *does_not, "the", "order") for it in ((), ("it",))
      for does_not in (("does", "not", "matter"), ("do", "not", "matter"), ("is", "not", "important"))),
    *((*it, "is", "not", "important", "which", *one, "first") for it in ((), ("it",))
      for one in ((), ("one",)))))
"""Remarks that leave the order to the robot (the default of a set of goals; a numbered list is in order
unless one of these is said with it)."""
TIME_FILLERS = Phrases((
    ("at", "some", "point"), ("at", "any", "time"), ("sometime",), ("eventually",), ("later",),
    ("real", "quick"), ("real", "fast"), ("quickly",), ("asap",), ("right", "away"), ("straight", "away"),
    ("now",), ("immediately",), ("straightaway",),
    ("it", "does", "not", "matter"), ("is", "fine"), ("at", "any", "point"))) + ANY_ORDER
"""Phrases that say nothing beyond the default (every goal is 'eventually', sets are done in any order, a
choice is anyone's)."""
ANY_TIME = frozenset({("at", "some", "point"), ("at", "any", "time"), ("sometime",), ("at", "any", "point")})
"""Time fillers that free a goal from the order around it: after steps said in order (*A, then B, and at some
point C*), is C anywhere in that order, or after B? Refused there."""

CLOSING = Phrases((
    # sign-offs
    ("thanks",), ("thank", "you"), ("thanks", "a", "lot"), ("thanks", "so", "much"),
    ("thank", "you", "so", "much"),
    ("thank", "you", "very", "much"), ("thanks", "very", "much"), ("many", "thanks"),
    ("thanks", "a", "bunch"),
    ("thanks", "a", "million"), ("thanks", "in", "advance"), ("thank", "you", "in", "advance"),
    ("thanks", "for", "your", "help"), ("thank", "you", "for", "your", "help"), ("thanks", "for", "that"),
    ("before", "you", "move", "on"), ("before", "moving", "on"),  # "..., check the fridge before you move on"
    ("cheers",), ("ta",), ("bye",), ("goodbye",), ("bye", "for", "now"), ("see", "you", "later"),
    ("much", "appreciated"), ("appreciate", "it"), ("i", "appreciate", "it"),
    ("i", "would", "appreciate", "it"),
    ("that", "'s", "all"), ("that", "'s", "all", "for", "now"), ("that", "'s", "it"),
    ("that", "'s", "it", "for", "now"),
    ("that", "'s", "everything"), ("that", "is", "all"), ("that", "is", "it"), ("that", "is", "everything"),
    ("that", "is", "all", "for", "now"), ("that", "is", "it", "for", "now"),
    ("that", "will", "be", "all"), ("that", "would", "be", "all"), ("that", "should", "be", "all"),
    ("have", "a", "nice", "day"), ("have", "a", "good", "day"), ("have", "a", "great", "day"),
    ("have", "a", "good", "one"), ("good", "luck"), ("have", "fun"), ("you", "the", "best"),
    ("you", "are", "the", "best"), ("you", "a", "star"), ("you", "are", "a", "star"), ("great", "job"),
    ("good", "job"), ("well", "done"), ("over", "and", "out"), ("thanks", "mate"), ("cheers", "mate"),
    ("thanks", "robot"), ("thank", "you", "robot"), ("thanks", "buddy"), ("thanks", "a", "ton"),
    ("thanks", "loads"), ("ta", "very", "much"), ("ta", "muchly"), ("cheers", "for", "that"), ("lol",),
    ("just", "to", "be", "sure"), ("just", "want", "to", "be", "sure"),
    ("i", "just", "want", "to", "be", "sure"),
    # asides that ask nothing
    ("no", "rush"), ("no", "hurry"), ("no", "pressure"), ("if", "possible"), ("if", "you", "can"),
    ("if", "you", "can", "help", "it"),  # "If you can help it, please don't ...": not a visit of "it"
    ("if", "you", "could"), ("when", "you", "can"), ("when", "you", "get", "a", "chance"),
    ("when", "you", "have", "a", "moment"), ("when", "you", "have", "time"), ("whenever", "you", "can"),
    ("at", "your", "convenience"), ("take", "your", "time"), ("in", "your", "own", "time"),
    ("if", "that", "is", "okay"), ("if", "that", "is", "ok"), ("if", "that", "is", "alright"),
    ("if", "you", "do", "not", "mind"), ("as", "usual"), ("as", "always"), ("no", "need", "to", "rush"),
    ("that", "would", "be", "great"), ("that", "would", "be", "lovely"), ("that", "would", "be", "perfect"),
    ("that", "would", "help"), ("if", "that", "makes", "sense"), ("thanks", "heaps"), ("really",), ("oh",),
    ("you", "know"), ("quick", "one"), ("quick", "question"), ("quick", "request"), ("off", "you", "go"),
    ("quick", "favour"), ("quick", "favor"), ("a", "quick", "favour"), ("a", "quick", "favor"),
    ("merci",),
    *(("if", "it", be, *no, "too", "much", *trouble) for be in ("is", "'s", "would", "will")
      for no in (("not",), ("no",), ("not", "be")) for trouble in (("trouble",), ("to", "ask"))),
    ("if", "it", "is", "no", "trouble"), ("if", "it", "'s", "no", "trouble"),
    ("when", "you", "get", "a", "moment"), ("when", "you", "get", "a", "minute"),
    *((when, "you", have, "a", moment) for when in ("when", "whenever") for have in ("have", "get")
      for moment in ("minute", "second", "moment", "chance")),
    ("whenever", "you", "get", "a", "chance"), ("whenever", "you", "get", "a", "moment"),
    ("when", "you", "are", "free"), ("when", "you", "are", "ready"), ("if", "you", "get", "a", "chance"),
    ("if", "you", "have", "a", "moment"), ("at", "your", "earliest", "convenience"),
    ("sorry", "to", "bother", "you"), ("sorry", "to", "be", "a", "pain"), ("i", "hate", "to", "ask"),
    ("i", "hate", "to", "bother", "you"), ("hope", "you", "are", "well"),
    ("hope", "you", "are", "doing", "well"),
    ("if", "you", "would", "be", "so", "kind"), ("real", "quick"), ("quickly",), ("please",),
    ("thank", "you", "so", "much", "in", "advance"), ("thanks", "so", "much", "in", "advance"),
    ("thanks", "a", "lot", "in", "advance"), ("if", "that", "is", "alright"), ("no", "worries"),
    ("when", "convenient"), ("when", "you", "can", "manage", "it"), ("no", "idea", "where"), ("no", "idea"),
    ("and", "then", "you", "are", "done"), ("then", "you", "are", "done"), ("you", "are", "done"),
    ("and", "you", "are", "done"), ("and", "that", "is", "it"), ("and", "that", "'s", "it"),
    ("and", "that", "'s", "all"), ("and", "that", "is", "all"), ("done",), ("the", "end"), ("finished",),
    # sign-offs of everyday speech: thanks to a person, thanks made stronger, praise, a warning word
    *((thanks, who) for thanks in ("thanks", "cheers", "ta") for who in ("man", "dude", "pal", "love", "mate",
                                                                       "buddy", "bud", "hun", "dear")),
    *((*thanks, "ever", "so", "much") for thanks in (("thanks",), ("thank", "you"))),
    *((*thanks, "a", "lot") for thanks in (("cheers",), ("ta",))),
    ("thx",), ("ty",), ("tyvm",), ("cheers", "then"), ("mind",), ("mind", "you"), ("much", "obliged"),
    ("nice", "one"), ("legend",), ("you", "are", "a", "legend"), ("love", "you"), ("love", "ya"),
    ("urgent",), ("please", "and", "thanks"), ("cheers", "in", "advance"),
    ("let", "me", "know"), ("thank", "you", "kindly"), ("thanks", "kindly"), ("thanks", "again"),
    ("thank", "you", "again"), ("see", "ya"), ("see", "you"), ("see", "you", "soon"),
    ("catch", "you", "later"),
    ("take", "care"), ("appreciate", "you"), ("appreciate", "ya"), ("good", "robot"),
    *((stop, "what", "you", "are", "doing") for stop in ("stop", "drop", "pause", "leave")),
    ("you", "rock"),
    ("ta", "in", "advance"),
    *((*and_, "that", be, "about", "it") for and_ in ((), ("and",)) for be in ("is", "'s")),
    *((*ask, "me", "a", favour)
      for ask in (("could", "you", "do"), ("can", "you", "do"), ("would", "you", "do"), ("do",))
      for favour in ("favour", "favor")),
    *((when, "you", *have, "a", sec) for when in ("when", "whenever")
      for have in (("have", "got"), ("have", "get"), ("have",), ("get",), ("got",))
      for sec in ("sec", "mo", "min")),
    ("whenever", "you", "are", "ready"), ("whenever", "you", "are", "free"),
    ("if", "that", "is", "fine"),
    *(("if", "you", would, "not", "mind") for would in ("would", "could")),
    *((when, "suits", *you) for when in ("whenever", "when", "whatever") for you in ((), ("you",))),
    *((when, "it", "suits", *you) for when in ("when", "whenever") for you in ((), ("you",))),
    ("whenever", "is", "convenient"),
    # praise only with thanks after it: "Is the kitchen lovely?" asks something
    *((praise, *comma, thanks) for praise in ("lovely", "brilliant", "perfect", "great", "awesome", "super")
      for comma in ((), (",",)) for thanks in ("thanks", "cheers", "ta")),
    *(("if", "that", "'s", fine) for fine in ("alright", "ok", "okay", "fine")),
    # thanks made stronger, in any spelling: "thx so much", "ty very much", "cheers a bunch"
    *((thanks, *much) for thanks in ("thanks", "thx", "ty", "cheers", "ta")
      for much in (("so", "much"), ("very", "much"), ("a", "lot"), ("a", "bunch"), ("a", "ton"), ("heaps",),
                   ("loads",), ("a", "million"), ("so", "so", "much")))))
"""Sign-offs (*thanks a lot*, *cheers*, *that's all for now*) and asides that ask nothing (*no rush*, *if
possible*, *when you get a chance*): skipped where they close a clause, that is before a comma or at the end
of the sentence (*if you can't find it, ...* is a condition, not *if you can*)."""

EXCLAMATIONS = word_set("gosh golly jeez geez gee blimey crikey wow whoa yikes phew ugh argh oof ooh aw")
"""Exclamations of everyday speech (*Oh gosh, ...*, *Phew!*): they ask nothing, like the sounds of
:data:`HESITATIONS`, but are said back (set aside) rather than dropped."""
_NUISANCES = ("bug", "bother", "trouble", "pester", "disturb", "interrupt", "nag", "hassle", "ask")
CLOSING = CLOSING + Phrases((
    # apologies for asking: "sorry to bug you", "sorry for the hassle", "apologies for the bother"
    *((sorry, "to", nuisance, *you) for sorry in ("sorry", "apologies") for nuisance in _NUISANCES
      for you in ((), ("you",), ("you", "again"), ("again",))),
    *((sorry, "for", *the, *trouble) for sorry in ("sorry", "apologies")
      for the in ((), ("the",), ("all", "the"))
      for trouble in (("bother",), ("trouble",), ("hassle",), ("interruption",), ("fuss",), ("mess",),
                      ("back", "and", "forth"))),
    *((sorry, "to", "be", "a", pain) for sorry in ("sorry", "apologies")
      for pain in ("bother", "pain", "nuisance", "pest")),
    ("sorry", "about", "this"), ("sorry", "about", "that"), ("sorry", "in", "advance"),
    # exclamations, alone or after "oh": "oh gosh", "oh my goodness", "oh dear", "oh boy"
    *((*oh, word) for oh in ((), ("oh",)) for word in EXCLAMATIONS),
    *((*oh, "my", word) for oh in ((), ("oh",))
      for word in ("god", "gosh", "goodness", "word", "lord", "days")),
    ("oh", "dear"), ("oh", "boy"), ("oh", "man"), ("dear", "me"), ("good", "grief"), ("goodness", "me"),
    # getting started: "so let's get a head start", "let's get going", "let's do this"
    *(("let", "'s", "get", *going) for going in (("a", "head", "start"), ("started",), ("going",),
                                                 ("cracking",), ("moving",), ("on", "with", "it"))),
    ("let", "'s", "do", "this"), ("here", "goes"), ("here", "we", "go"),
    # leaving and signing off: "wish me luck", "talk later", "off to work now", "much love"
    ("wish", "me", "luck"), ("talk", "later"), ("talk", "soon"), ("speak", "soon"), ("speak", "later"),
    ("much", "love"), ("lots", "of", "love"), ("long", "story"), ("long", "story", "short"),
    *((*i_am, "off", "to", *place, *now) for i_am in ((), ("i", "am"), ("we", "are"))
      for place in (("work",), ("school",), ("the", "shops"), ("the", "gym")) for now in ((), ("now",))),
    *((*i_will, "be", "back", when) for i_will in ((), ("i", "will"), ("we", "will"))
      for when in ("soon", "later", "tonight")), ("back", "soon"), ("back", "later"),
    *(("you", "are", *a, praise) for a in ((), ("a",), ("an",))
      for praise in ("lifesaver", "gem", "angel", "diamond", "hero", "saint", "champ", "legend", "star",
                     "treasure", "amazing", "brilliant", "awesome", "wonderful", "great")),
    ("tia",), ("owe", "you", "one"), ("i", "owe", "you", "one"), ("i", "owe", "you"),
    # openers of talk and asides of time: "listen up,", "tell you what,", "at your leisure"
    *((*i, "would", *really, "appreciate", "it") for i in ((), ("i",), ("we",))
      for really in ((), ("really",))),
    *(("would", "be", great) for great in ("great", "lovely", "amazing", "perfect", "brilliant", "helpful")),
    *(("hope", "that", be, fine) for be in ("is", "'s")
      for fine in ("ok", "okay", "alright", "fine", "clear")),
    ("hope", "that", "makes", "sense"), ("hope", "this", "makes", "sense"),
    *(("not", "even", "a", peek) for peek in ("peek", "look", "glance", "second", "minute", "moment")),
    *((*would, "that", *be, *ok) for would, be in ((("would",), ("be",)), (("is",), ()), (("if",), ("is",)))
      for ok in (("okay",), ("ok",), ("alright",), ("all", "right"), ("fine",))),
    *(("any", "questions", *comma, "just", "ask") for comma in ((), (",",))),
    *(("let", "me", "know", "if", "you", have, *any, "questions") for have in ("have", "get")
      for any in ((), ("any",))),
    # letters and notes: "Dear robot,", "Kind regards", "Many thanks in advance", "Excuse me,", "it's me"
    *(("dear", who) for who in ("robot", "helper", "assistant", "bot")),
    *((*kind, "regards") for kind in ((), ("kind",), ("best",), ("warm",), ("warmest",))),
    ("best", "wishes"), ("greetings",), ("all", "the", "best"), ("many", "thanks", "in", "advance"),
    ("love",), ("with", "love"), ("cheers", "again"),
    ("thank", "you", "very", "very", "much"), ("thanks", "very", "very", "much"), ("excuse", "me"),
    ("pardon",), ("pardon", "me"), ("attention", "please"), ("attention",),
    *(("have", "a", good, when) for good in ("good", "nice", "great", "lovely")
      for when in ("evening", "night", "weekend", "afternoon", "morning", "one")),
    *((*it_is, *my, who, *again) for it_is in (("it", "is"), ("this", "is"), ("its",))
      for my in ((), ("your",))
      for who in ("me", "us", "mum", "mom", "dad", "mummy", "daddy", "grandma", "grandpa", "nan", "granny")
      for again in ((), ("again",), ("here",), ("speaking",))),
    *((*it, *very, "important") for it in ((), ("it", "is"), ("is",))
      for very in ((), ("very",), ("really",))),
    ("let", "me", "think"), ("listen",), ("listen", "up"), ("you", "know", "what"),
    ("tell", "you", "what"), ("at", "your", "leisure"),
    *((when, "you", "get", way, "to", "it") for when in ("when", "whenever") for way in ("round", "around")),
    *(("if", "you", "get", "a", moment) for moment in ("minute", "sec", "second", "moment", "mo")),
    *(("if", "it", be, "not", "too", "much", bother) for be in ("is", "'s")
      for bother in ("bother", "trouble", "hassle")),
    ("just", "in", "case"), ("to", "be", "safe"), ("to", "be", "on", "the", "safe", "side"),
    ("better", "safe", "than", "sorry"), ("just", "to", "be", "safe"), ("just", "to", "check"),
    *(("bless", who) for who in ("her", "him", "them", "you", "it")),
    # tag questions closing an order: "never go in there, okay?", "..., alright?", "..., yeah?"
    ("okay",), ("ok",), ("alright",), ("all", "right"), ("got", "it"), ("you", "got", "it"),
    ("sound", "good"), ("sounds", "good"), ("yeah",)))
"""More of :data:`CLOSING`: apologies for asking, exclamations, words of getting started and tag
questions, which ask nothing wherever they close a clause."""

THING_SUBJECTS = frozenset({"it", "they", "there", "this", "that", "these", "those"})
"""The subject of a condition about the state of something (*if it is open*, *if there is time*): refused,
never skipped to read the verb after it as the robot's."""
WISH_VERBS = frozenset({"want", "wish", "like", "prefer", "feel", "fancy"})
"""The verb of a condition on what the robot would like (*if you want, the office*): an optional goal."""
CONDITION_OPENERS_OF_ASIDES = ("if", "when", "whenever")
"""Asides of :data:`CLOSING` that start like a condition (*if you can*, *when you get a chance*): before a
noun phrase they are still asides (a condition needs a verb)."""
CORRECTIONS = Phrases((("i", "mean"), ("i", "meant"), ("no", "wait"), ("wait", "no"), ("scratch", "that"),
                       ("wait", ",", "no"), ("no", ",", "wait"), ("make", "that"), ("correction",),
                       ("or", "rather"),
                       ("actually", "no"),
                       ("no", "sorry"), ("sorry", "no"), ("i", "said", "wrong"), ("my", "mistake"),
                       ("my", "bad"), ("let", "me", "rephrase"),
                       # a bare "sorry" or "no" between commas: "the garage, sorry, the office"
                       ("sorry", ","), ("no", ","), ("oops", ","), ("whoops", ","), ("er", "no"),
                       ("no", "no"), ("hang", "on"), ("wait", "a", "sec"), ("wait", "a", "second"),
                       ("wait", ",", "actually"), ("wait", "actually"), ("oh", "wait"),
                       ("sorry", "i", "mean"),
                       # "no" before an article or "actually" names the thing meant, not one to avoid
                       ("no", "actually"), ("no", "a"), ("no", "an"), ("no", "the"),
                       # a change of mind said in a sentence of its own (*Go to the kitchen. Actually, the
                       # office.*)
                       ("actually", ","), ("actually", "the"), ("actually", "a"), ("actually", "an"),
                       ("actually", "make"), ("actually", "go"), ("actually", "just"), ("make", "it"),
                       ("change", "of", "plan"), ("change", "of", "plans"),
                       ("on", "second", "thought"), ("on", "second", "thoughts"), ("scratch", "the")))
"""Words with which a speaker takes back what they said (*go to the kitchen, sorry, I mean the office*):
which part stands is not read; refused."""
UNFINISHED = DETERMINERS | frozenset({"to", "into", "in", "on", "at", "of", "through", "from", "by"})
"""Words no clause ends with: one broken off after them at a dash is started again (*don't take the- don't go
...*)."""
_CHOOSERS = (("either",), ("any",), ("whichever",), ("either", "one"), ("any", "one"), ("whichever", "one"),
             ("any", "of", "them"), ("either", "of", "them"), ("whichever", "of", "them"), ("whatever",),
             ("whatever", "one"))
_FINE: tuple[tuple[str, ...], ...] = (
         (), ("is", "fine"), ("is", "ok"), ("is", "okay"), ("is", "good"), ("will", "do"), ("works",),
         ("would", "do"), ("would", "be", "fine"), ("will", "be", "fine"), ("you", "like"), ("you", "want"),
         ("you", "prefer"), ("you", "choose"), ("is", "closer"), ("is", "nearer"), ("is", "free"),
         ("is", "easier"), ("is", "easiest"), ("is", "handiest"), ("is", "closest"), ("is", "nearest"))
_FINE += (("does", "not", "matter"),)  # "any of them doesn't matter"
_FINE += tuple((*fine, "for", "you") for fine in _FINE if fine[:1] == ("is",))  # "is easier for you"
_FINE += tuple(("'s", *fine[1:]) for fine in _FINE if fine[:1] == ("is",))  # "either one's fine"
CHOOSERS_OF_KIND = ("either", "any", "whichever")
REMARK_FINE = Phrases(tuple(fine for fine in _FINE if fine))
"""*the bathroom upstairs, either sink is fine*: a remark choosing an object of the room just named (a sink of
that bathroom)."""
CHOICE_AFFIRMATIONS = Phrases(tuple(
    chooser + fine for chooser in _CHOOSERS for fine in _FINE
    if chooser + fine not in (("either",), ("any",))  # bare "either" / "any" start a noun phrase
) + (
    ("no", "matter", "which"), ("no", "matter", "which", "one"),
    ("it", "does", "not", "matter", "which"), ("does", "not", "matter", "which"),
    ("is", "not", "important", "which"), ("it", "is", "not", "important", "which"),
    ("not", "important", "which"), ("no", "matter", "which", "one"),
    ("does", "not", "matter", "which", "one"), ("it", "does", "not", "matter", "which", "one"),
    ("i", "do", "not", "care", "which"), ("i", "do", "not", "mind", "which"),
    ("do", "not", "mind", "which"), ("do", "not", "mind", "which", "one"), ("do", "not", "care", "which"),
    ("i", "do", "not", "mind", "which", "one"), ("i", "do", "not", "really", "mind", "which"),
    ("your", "choice"), ("your", "pick"), ("take", "your", "pick"), ("you", "pick"), ("you", "choose"),
    *(("the", one, "you", like) for one in ("one", "ones")  # "the TV in the living room, the one you want"
      for like in ("want", "like", "prefer", "choose", "pick")),
    ("it", "is", "up", "to", "you"), ("up", "to", "you"), ("i", "do", "not", "care"),
    *((*just, pick, one) for just in ((), ("just",)) for pick in ("pick", "choose")
      for one in ("one", "any", "whichever")),
) + tuple(("which", *one, "you", want) for one in ((), ("one",))  # "which one you want", as learners say it
        for want in ("want", "like", "prefer", "choose"))
    + tuple(("what", *one, "you", want) for one in ((), ("one",))  # "what you prefer": learners' "whichever"
            for want in ("want", "like", "prefer", "choose", "wish"))
    # "which one doesn't matter", "which one is egal"
    + tuple(("which", *one, *said) for one in ((), ("one",))
            for said in (("does", "not", "matter"), ("is", "not", "important"), ("no", "problem"),
                         ("is", "no", "problem"), ("is", "egal"), ("is", "not", "matter"),
                         ("not", "matter"))))
"""Said after a choice ("a bedroom, either one is fine"): it only confirms the choice. After several phrases
("the TVs and the couch, either one is fine") it would turn each of them into one of them, so it is refused
there (see :func:`.meaning.actions.choice_remark`)."""
BEFORE_REMARK = Phrases((("for", "me"), ("for", "us"), ("please",), ("for", "me", "please")))
"""Said between a choice and its remark (*grab an apple for me, either one is fine*): the remark is still
about that choice."""
ONE_SUFFICES = Phrases(tuple(
    (*lead, *one, *enough) for lead in ((), ("just",), ("only",), ("getting", "to"), ("reaching",),
                                        ("pick",), ("just", "pick"), ("choose",), ("just", "choose"))
    for one in (("one", "of", "them"), ("one",), ("any", "one", "of", "them"))
    for enough in ((), ("is", "enough"), ("will", "do"), ("is", "fine"), ("is", "ok"), ("is", "okay"),
                   ("would", "do"), ("suffices",))
    if lead or enough or len(one) > 1) + tuple(  # "the TVs in the office, any of them (will do)"
    ("any", "of", "them", *enough) for enough in ((), ("will", "do"), ("is", "enough"), ("is", "fine"),
                                                  ("would", "do"), ("suffices",))))
"""After a phrase that means each of several (*the vases in the lobby, just one of them*, *check the apples,
getting to one of them is enough*): one of them will do, which makes it a choice (said outright, unlike
*either one*, which is refused there)."""
PICK_VERBS = frozenset({"pick", "choose"})
"""In a remark that one will do (*just pick one*): said after one place, it picks something else (refused)."""
BARE_CHOOSERS = ("either", "any", "whichever")
CLAUSE_ENDS = frozenset({"", ",", "then", "and", "but"})
"""After ``, either`` / ``, any``: no noun follows, so the word is a choice remark (*DR vase, any*)."""

_SPAN_NOUNS = ("mission", "task", "trip", "route", "run", "time", "way", "journey", "tour", "job", "thing",
               "path")
WHOLE_MISSION = Phrases((
    ("the", "whole", "time"), ("the", "entire", "time"), ("at", "all", "times"), ("at", "any", "time"),
    ("whole", "time"), ("entire", "time"),  # operators' "!kit whole time"
    ("for", "all", "of", "it"), ("for", "all", "of", "this"), ("for", "all", "of", "that"),
    ("at", "any", "point"), ("throughout",), ("the", "whole", "way"), ("all", "the", "time"),
    ("on", "the", "way"), ("on", "your", "way"), ("along", "the", "way"), ("at", "all"),
    ("all", "along"), ("for", "the", "duration"), ("the", "entire", "way"),
    *((pre, "the", whole, noun) for pre in ("for", "during", "throughout", "over")
      for whole in ("whole", "entire", "full") for noun in _SPAN_NOUNS),
    *(("throughout", "the", noun) for noun in _SPAN_NOUNS),
    ("while", "you", "do", "it"), ("while", "you", "do", "that"), ("while", "you", "are", "at", "it"),
    ("while", "doing", "so"), ("while", "doing", "that"), ("while", "doing", "it"), ("in", "the", "process"),
    ("while", "you", "are", "doing", "it"), ("while", "you", "are", "doing", "that"),
    ("while", "you", "are", "doing", "this"), ("while", "you", "are", "about", "it"),
    ("while", "you", "are", "out"), ("while", "you", "are", "out", "and", "about"),
    ("while", "you", "are", "out", "there"), ("while", "you", "are", "going", "round"),
    ("entirely",), ("completely",), ("altogether",), ("at", "all", "costs"),
    ("not", "even", "once"), ("even", "once"),  # "don't go in X not even once": never
    *(("during", "the", noun) for noun in _SPAN_NOUNS)))
"""Said after what to avoid: the prohibition holds for the whole mission (``G !x``), not only at one step."""
WAYPOINT_OPENERS = ("on", "along")
"""*On the way, X* opening a sentence is a waypoint, not a whole-mission opener."""

# ----------------------------------------------------------------------------------------------- order
SEQ_WORDS = Phrases((("and", "then"), ("then",), ("after", "that"), ("afterwards",), ("afterward",),
                     ("last", ","), ("and", "last"), ("last",),
                     ("next",), ("finally",), ("subsequently",), ("after", "which"), ("followed", "by"),
                     ("later",), ("and", "finally"), ("lastly",), ("secondly",), ("thirdly",),
                     ("fourthly",), ("second", ","), ("third", ","), ("fourth", ",")))
"""Between clauses: what follows comes after what came before."""
THEN_NEXT = Phrases((("then",), ("and", "then"), ("finally",), ("and", "finally"), ("after", "that"),
                     ("afterwards",), ("lastly",)))
"""After a list joined by commas only: the list is a sequence too ("A, B, then C")."""
STRICT_SEQ = Phrases(tuple(
    (*lead, *only) for lead in ((), (",",), ("and",), ("but",), (",", "and"), (",", "but"))
    for only in (("only", "after", "that"), ("only", "after", "this"), ("only", "then"),
                 ("only", "afterwards"), ("not", "before", "that"), ("only", "once", "that", "is", "done"),
                 ("only", "when", "that", "is", "done"), ("only", "after", "you", "have", "done", "that"),
                 ("only", "once", "you", "have", "done", "that"))))
"""``A, and only after that B``: B after A, and not before it (strict)."""
STRICT_WORDS = frozenset({"only", "once", "when", "until", "unless", "if", "not", "never", "do"})
"""Words that, in a clause closing with *only after that*, make which goal waits unclear."""
ORDER_MODIFIERS = Phrases((("one", "after", "the", "other"), ("one", "after", "another"),
                           ("in", "that", "order"), ("in", "this", "order"), ("in", "order"),
                           ("in", "sequence"), ("sequentially",), ("one", "by", "one"), ("in", "turn"),
                           ("consecutively",), ("successively",)))
"""Said after a list: its items are done one after the other (in the order written, for explicit lists)."""
FIRST = frozenset({"first", "firstly"})
LAST = ("last", "lastly")
ORDER_HEADS = frozenset({"first", "firstly", "then", "next", "finally", "last", "lastly", "afterwards",
                         "after", "before", "second", "secondly", "third", "thirdly"})
"""Before a colon (*Then: the kitchen*, *Before that: the office*): words of the order, read as if a comma
stood there, never dropped as a heading."""
BEFORE_THAT = ("before", "that")
BEFORE_ENTERING = Phrases(tuple((*who, *verb) for who in (("you",), ("u",), ()) for verb in (
    ("enter",), ("go", "into"), ("go", "in"), ("step", "into"), ("walk", "into"), ("head", "into"),
    ("set", "foot", "in"), ("set", "foot", "into"))))
"""After *before*: entering a room, which blind writers read as keeping out of it until then (*before you go
into the kitchen, X*: not the kitchen until X), unlike *before you go to Y* (X, then Y)."""
BEFORE_PRONOUNS = frozenset({"it", "this"})
"""After *before*, words learners write for *that* (*visit the lobby, but before it pass the table*)."""
ON_THE_WAY = Phrases((("on", "your", "way"), ("on", "the", "way"), ("on", "my", "way")))
WAY_TOWARDS = frozenset({"up", "down", "over", "out"})
"""*on your way up to X*: the way to X all the same."""
WAY_BACK = frozenset({"back", "up", "down", "out", "home"})
"""``on your way back (up)``: after what came before, like *then*."""
ON_THE_WAY_ENDS = ("", ",", "there", "and", "then", "but")
"""After *on the way* ending an action (looked ahead)."""
WAYPOINT = Phrases((("via",), ("through",), ("by", "way", "of"), ("passing", "through"),
                    ("going", "through"), ("passing", "by"), ("going", "past"), ("passing",),
                    ("by", "going", "through")))
"""Right after a goal: what follows is on the way there (before it)."""
AFTER_ALL = Phrases(tuple(
    (w, *rest) for w in ("after", "once", "when")
    for rest in (("all",), ("both",), ("all", "that"), ("you", "done", "those"),
                 ("you", "have", "done", "those"), ("you", "done", "all", "that"),
                 ("you", "have", "done", "all", "that"), ("you", "done", "all"),
                 ("you", "have", "done", "all"),
                 ("you", "done", "both"), ("you", "have", "done", "both"), ("those", "are", "done"),
                 ("all", "are", "done"), ("all", "that", "is", "done"))))
"""*after all three (of them)*, *once you've done those*: after every goal said before."""
LEFT_THERE = frozenset({"left", "forgot", "dropped", "lost", "put"})
"""Verbs of a person leaving a thing somewhere (*I left my book in the bedroom*, *I put my keys by the
TV*)."""
DONE = frozenset({"done", "finished", "through", "finishing"})
DONE_OPENERS = ("once", "when", "after")
DONE_WITH = ("with", "in", "at")
"""*once you're done with / in / at X*: X is what is done (before what follows)."""
DONE_FILLERS = frozenset({"that", "this", "are", "all", "both", "of", "them"})
DONE_BACK = ("that", "this", "it", "them", "everything", "there")
"""``once you're done with that``: the step before, not a new place."""
DONE_BACK_ENDS = frozenset({",", "", "then", "go", "and"})
"""After *once you've done that*: the words that show *that* is the step before (*..., go to X*), not the
start of a noun phrase (*once you've done that room*)."""
TRIP_NOUNS = frozenset({"trip", "visit", "stop", "detour", "run", "quick", "short", "pass"})
"""``twice, with a trip / visit / stop to Y in between``: words naming the visit to Y."""
BETWEEN_TAIL = Phrases((("them",), ("the", "two"), ("the", "two", "visits"), ("each", "visit"), ("visits",)))
AFTERWARDS = Phrases((("afterwards",), ("afterward",), ("after", "that"), ("after", "it"), ("after",),
                      ("later",), ("straight", "after"), ("right", "after")))
"""In the consequent of a condition ("..., visit Y afterwards"): Y follows that visit of X."""
TRAILING_AFTER = Phrases((("after",), ("afterwards",), ("afterward",), ("later",), ("after", "that"),
                          ("after", "it"), ("after", "this"), ("next",)))
"""``..., go to the dining room after / after that.``: at the end of a clause, after what was said before it
(*after it* there is the step before, not the place just named)."""
AFTER_THAT = Phrases((("after", "that"), ("after", "it"), ("after", "this")))
"""*after that / it / this*: after the step before, never a place named *it*."""
AFTER_AS_THEN = frozenset({"to", "into", "in", "at", "on", "up", "down", "over", "again", ","})
"""After *, after* / *and after*: no place follows, so *after* is *then* (*go first to A, after to B*)."""
FLOOR_MOVE_VERBS = word_set("go come head pop nip run walk move get travel proceed")
"""Verbs of a sentence that only moves between floors (*Go upstairs.*: the floor of the goals after it)."""
LIGHT_PREFIX = frozenset({"please", "do", "kindly", "also"})
"""An announcement's words before its list (*Please do these:*) that say nothing before a prohibition item."""
MAX_LABEL_WORDS = 4
"""A list's heading of words the grammar has no role for (*Kids' stuff:*, *Shopping prep:*) is its name
(set aside and said back) up to this many words; a longer one is read as a sentence."""
VISIT_PARTICIPLES = frozenset({"visited", "entered"})
"""A passive closing a condition on a place (*if the living room is visited / entered*): the robot was
there."""
LEAVE_AS_IS = frozenset({"but", "not", "never", "just", "simply"})
"""Before *leave it on X*: it may say not to move it (*grab the cup but leave it on the table*): refused."""
ADDENDUM_OPENERS = frozenset({"also", "and", "plus"})
"""A line opening so after a list of lines (*Also check the TV.*, *P.S. ...*, *Oh and ...*) adds to it, in
no order the list says."""
BESIDE_VERBS = word_set("park parking stand standing stop pull up sit")
"""Before *next to / beside / near X* (an object): X is where to be (*park next to the bed*); not a verb
that takes *to* (*come next to X* may be *next, come to X*)."""
BASE_VERBS_IN_ING = word_set("bring ring sing sting swing string wring fling cling")
"""Verbs whose plain form ends in *-ing* (*and after bring it ...* is no gerund)."""

# -------------------------------------------------------------------------------------------- negation
NEGATED_NEED_WORDS = frozenset({"need", "needs", "have", "has", "got"})
"""After a negation, before *to* (*you don't need to / have to go to X*, *no need to X*): X is not needed,
which forbids nothing."""
NOT_NEEDED = Phrases((("no", "need", "to"), ("there", "is", "no", "need", "to"),
                     ("no", "need", "for", "you", "to"), ("you", "do", "not", "need", "to"),
                     ("you", "do", "not", "have", "to"), ("you", "need", "not"), ("do", "not", "need", "to"),
                     ("you", "will", "not", "need", "to"), ("there", "'s", "no", "need", "to"),
                     ("it", "is", "not", "necessary", "to"),
                     ("do", "not", "bother"), ("no", "need", "for")))
"""A clause that says a goal is not needed (*No need to go into the office.*, *..., you don't have to check
the oven*): it asks nothing, so it is set aside and said back (:mod:`.syntax.not_needed`)."""
NOT_NEEDED_VERBS = frozenset({"bother"})
"""After a negation (*don't bother going to X*, *don't bother with X*): X is not needed, which forbids
nothing."""
NOT_NEEDED_STOPS = word_set("if unless until till only when whenever except but then before after first once "
                            "while so or otherwise instead")
"""Words that make a not-needed clause say more than *not needed* (*no need to go there unless ...*,
*... before the office*): such a clause is parsed, and so refused."""
NEG_STARTS = Phrases((
    ("always", "avoid"), ("always", "stay", "away", "from"), ("always", "keep", "away", "from"),
    ("always", "stay", "out", "of"), ("always", "keep", "out", "of"), ("never",), ("do", "not"),
    ("does", "not"), ("must", "not"), ("should", "not"), ("can", "not"), ("cannot",), ("may", "not"),
    ("will", "not"), ("not",), ("avoid",), ("avoiding",), ("stay", "away", "from"), ("keep", "away", "from"),
    ("stay", "out", "of"), ("keep", "out", "of"), ("without",), ("while", "avoiding"),
    ("always", "do", "not"),
    ("and", "avoid"), ("but", "avoid"), ("but", "never"), ("and", "never"), ("but", "do", "not"),
    ("and", "do", "not"), ("but", "not"), ("no",), ("neither",), ("nor",), ("and", "nor"),
    ("keep", "clear", "of"), ("steer", "clear", "of"), ("stay", "clear", "of"),
    ("kept", "out", "of"), ("stayed", "out", "of"), ("kept", "away", "from"), ("stayed", "away", "from"),
    ("staying", "out", "of"), ("keeping", "out", "of"), ("staying", "away", "from"),
    ("keeping", "away", "from"), ("staying", "clear", "of"), ("keeping", "clear", "of"),
    ("steering", "clear", "of"),
    ("skip",), ("skipping",),
    ("avoided",), ("kept", "clear", "of"), ("stayed", "clear", "of"),
    ("under", "no", "circumstances"),
    ("at", "no", "point"), ("at", "no", "time"), ("keep", "off"), ("stay", "off"), ("always", "keep", "off"),
    ("always", "stay", "off")))
"""Words that start a prohibition."""
GLOBAL_NEG = frozenset({"always", "never", "do", "does", "must", "should", "can", "cannot", "may", "will",
                        "no", "stay", "keep", "neither", "nor", "steer", "circumstances", "point", "time",
                        "kept", "stayed", "avoided", "skip", "skipping"})
"""A negation with one of these words holds for the whole mission (G !x); 'avoid' and 'without' after an
action only constrain the moment that action is done (F(x & !y)), as in the authors' missions."""
AVOID_VERBS = word_set(
    """disturb disturbing bother bothering wake waking knock knocking bump bumping step stepping set setting
    trip tripping break breaking lean leaning spill spilling block blocking approach approaching cross
    crossing trouble troubling mess messing near nearing pass wander wandering stray straying venture
    venturing sneak sneaking wash move handle handling hit hitting damage damaging scratch knock stand
    standing climb climbing tread treading pop popping nip swing swinging poke poking cut cutting roam
    roaming dash dashing hurry hurrying rush rushing detour detouring stroll strolling via
    allowed permitted"""
) | POSITIVE_VERBS
"""Verbs a prohibition is read with (*don't touch / disturb / go near X*): not being at X keeps each of them
from happening. A negation before any other verb is refused, naming it (*don't xyzzy the sink*): read as
*never at X* it could reverse what was asked."""
FORGET_VERBS = word_set("forget forgetting neglect neglecting miss missing skip skipping overlook "
                        "overlooking omit omitting ignore ignoring fail failing")
"""Verbs that negate a goal: *don't forget the sink*, *never miss the kitchen*, *don't fail to visit X* ask
for X (it is a goal, not a place to avoid)."""
FORGOTTEN_LINKS = word_set("to about out of visiting going checking")
"""After a goal-negating verb: *don't forget to / about X*, *don't fail to visit X*."""
NEGATION_EVER = ("ever",)
NEGATION_NEUTRAL = (FILLERS | DETERMINERS | VERB_IDIOMS.words() | HESITATIONS | MODALS | POLITE.words()
                    | frozenset(RELATIVE_FLOORS) | frozenset({"even", "ever"}))
"""Words between a negation and what it forbids that are no verb of their own (*don't even go into X*)."""
NEGATION_JOINERS = ("and", "but")
"""Before a negation (*... and don't touch X*): not quoted with it."""
"""*never ever* / *don't ever*: the same as *never* / *don't*."""
NEGATING = ("not", "never")
PARTIAL_PROHIBITION = ("after", "once", "when", "during", "afterwards", "afterward", "later", "again")
"""After what to avoid: a prohibition for part of the mission, which is refused."""
PARTIAL_FROM = (("from", "then"), ("from", "now"), ("at", "some", "point"))
UNTIL_WORDS = ("until", "before", "till")
"""After what to avoid: ``!X U Y``."""
UNTIL_DONE_LINKS = ("is", "are", "has", "have")
UNTIL_DONE_WORDS = DONE | {"been", "visited"}
UNTIL_DONE_VERBS = ("visited", "checked", "cleaned")
"""``until both bathrooms are done / have been visited``."""
IRREGULAR_PARTICIPLES = word_set("made set put shut swept fed taken brought seen")
"""Past participles of chores not in *-ed* (*until the bed is made*, *once the table is set, ...*)."""
OFF_LIMITS = Phrases(
    tuple((*be, *said) for be in ((), ("is",), ("are",), ("is", "strictly"), ("are", "strictly"), ("=",))
          for said in (("off", "limits"), ("out", "of", "bounds"), ("forbidden",), ("prohibited",),
                       ("banned",), ("not", "allowed"), ("a", "no", "go"), ("no", "go"),
                       ("not", "to", "be", "entered"), ("to", "be", "avoided"),
                       ("not", "to", "be", "touched"),
                       ("out", "of", "limits")))
    + tuple((modal, "be", "avoided") for modal in ("should", "must", "has", "have", "will"))
    + (("=", "no"),))  # notes: "office = off limits", "other bathrm = NO"
"""``The kitchen is off limits``: never enter / reach what the sentence names (``G !x``)."""
BARE_PROHIBITIONS = frozenset({("never",), ("keep", "out"), ("stay", "out"), ("avoid",), ("off", "limits"),
                               ("no", "entry"), ("no", "go"), ("out", "of", "bounds"), ("forbidden",),
                               ("do", "not", "enter"), ("not", "allowed"), ("keep", "away"), ("avoid", "it"),
                               ("stay", "away"), ("no", "entering")})
"""A sentence that only says to keep out, under a room heading (*LR: never.*, *bathrms fl2: keep out*):
that room is off limits."""
COPULAS = frozenset({"is", "are", "was", "were", "should", "must", "will", "has", "have", "seems", "looks",
                     "might", "may", "can", "could", "needs", "need"})
"""After a sentence's first noun phrase: a statement ("the bowl is in the kitchen"), never a goal."""

# ------------------------------------------------------------------------------------------ conditions
CONDITION_WORDS = Phrases((("if",), ("when",), ("in", "case")))
"""Conditions; *once* is temporal ('once you have been to X' = after X), not a condition."""
ONLY_IF = ("only", "if")
WHENEVER = Phrases((("whenever",), ("every", "time"), ("each", "time"), ("any", "time"), ("anytime",)))
ONLY_AFTER = Phrases((("only", "after"), ("only", "once"), ("not", "before"), ("not", "until")))
EVER_ONCE = Phrases((("at", "any", "point"), ("at", "any", "time"), ("at", "some", "point")))
"""In a condition ("if you go into X at any point, Y afterwards"): the condition is met once; every writer
since the second set read it so (28 missions), as the brief's "if you go into A, B afterwards" (once)."""
EVER_UNCLEAR = Phrases((("ever",), ("every", "time"), ("each", "time"), ("anytime",)))
"""In a condition ("if you ever go into X"): once or on each visit? Writers read it both ways: refused."""
EVER = EVER_UNCLEAR + EVER_ONCE
"""Words of how often a condition may be met, skipped before its subject."""
OBLIGED = Phrases((("must",), ("have", "to"), ("has", "to"), ("need", "to"), ("needs", "to")))
"""*Before you enter Y, you must X*: an obligation, so Y is not entered before X (not only X, then Y)."""
CONDITION_AFTERWARDS = frozenset({"afterwards", "afterward", "after", "later"})
"""Between the visit and *and* of one errand a condition asks for (*swing by the kitchen afterwards and check
the microwave*): the condition's *afterwards*, no step of its own."""
VISIT_NOUNS = frozenset({"visit", "visits", "trip", "trips", "entry", "entries"})
"""After *no X* (*No kitchen visits.*, *no office trips please*): going into X, as *no visits to X*."""
OBLIGED_SUBJECTS = frozenset({"you", "u", "we", "robot"})
"""Before an obligation after *after* (*after you must go to X*): *after that, you must ...*."""
TOO = Phrases((("too",), ("also",), ("as", "well")))
"""Closing an addition (*check X afterwards too*): adds nothing to the order said before it."""
ALSO_AFTER = ("too", "also", "as well")
"""After *that X* in a step at another room (*go to the office and water that plant too*): another X, the
one of that room."""
CONDITION_END = frozenset({"after", "before", "and", "or", "until", "but", "while", "without", "when", "if",
                           "once", "whenever", "unless"})
"""Words that would continue a condition past its one action (a comma or *then* ends it)."""
CONDITION_OPENERS = ("and", "but", "so")
"""*And whenever ...*, *But if ...*: a new condition, not a continuation."""
RULE_JOINERS = (",", "and", "but", "also")
"""Between condition rules of one sentence."""
UNTIL_OPENERS = ("until", "till")

# ------------------------------------------------------------------------------------------ qualifiers
QUAL_IN = ("in", "inside", "within", "of", "from")
SCOPE_IN = ("in", "inside", "within")
"""``In the living room, ...``: the room of the whole sentence."""
DIRECTION_BEFORE_IN = ("up", "down", "over", "out", "back")
"""*the teddy bear up in the bedroom*: a direction before *in* after an object; the room says where."""
QUAL_CONTAINS = Phrases((("with",), ("having",), ("containing",), ("that", "has"), ("that", "have"),
                         ("with", "just"), ("that", "just", "has"), ("which", "just", "has"),
                         ("with", "nothing", "but"), ("with", "only", "just"),
                         ("which", "has"), ("which", "have"), ("that", "contains"), ("which", "contains"),
                         ("where", "there", "is"), ("where", "there", "are"), ("that", "holds"),
                         ("that", "only", "has"), ("which", "only", "has"), ("that", "only", "have"),
                         ("with", "only"), ("that", "has", "only"), ("containing", "only"),
                         ("which", "has", "only"), ("which", "have", "only"), ("that", "have", "only")))
RELATIVE_PRONOUNS = ("that", "which", "where", "who")
"""Open a relative clause about a room's contents in any tense or form of *have* (:data:`HAVE_FORMS`)."""
HAVE_FORMS = word_set("has have had having holds hold held contains contain contained keeps keep got")
"""*the bathroom which has / is having / has got / had / holds a vase*: the verbs of a room's contents."""
LEARNERS_RELATIVES = ("what",)
"""Relative pronouns as learners write them before a form of *have* (*the bathroom what has the vase*): as
*which*."""
RELATIVE_ADVERBS = ("also", "too", "still")
"""Between the relative pronoun and *have*, saying nothing of the contents (*the bathroom that also has a
vase*: the bathroom with a vase)."""
HAVE_AUXILIARIES = word_set("is are was were has have had does do did 's")
"""Before a form of *have* (*is having*, *has got*) or *not* (*does not have*, *is not having*)."""
SINGLE_COUNT = Phrases((("a", "single"), ("one", "single"), ("just", "the", "one"), ("only", "the", "one"),
                        ("just", "a", "single"), ("only", "a", "single"), ("the", "one", "single"),
                        ("the", "one")))
"""*the bathroom with a single sink / that has just the one sink*: exactly one."""
QUAL_LACKS = Phrases((("that", "does", "not", "have"), ("which", "does", "not", "have"), ("with", "no"),
                      ("that", "has", "no"), ("that", "does", "not", "contain"),
                      ("where", "there", "is", "no")))
QUAL_NEXT = Phrases((("next", "to"), ("adjacent", "to"), ("beside",), ("near",), ("connected", "to"),
                     ("by",), ("off",), ("close", "to"), ("joined", "to"), ("linked", "to"),
                     ("attached", "to"),
                     ("that", "connects", "to"), ("leading", "to"), ("that", "leads", "to"),
                     ("outside",), ("outside", "of"), ("just", "outside"), ("right", "outside"),
                     ("just", "outside", "of"), ("right", "outside", "of"), ("just", "off"), ("right", "off"),
                     ("just", "next", "to"), ("right", "next", "to"), ("right", "by"), ("just", "by"),
                     ("next", "of"), ("near", "of"), ("close", "of")))
"""*the hallway outside / just off / next to the kitchen*: a room located by a room connected to it (the
neighbour only locates it, it is no goal)."""
NEXT_DOOR = Phrases((("next", "door"), ("right", "next", "door"), ("just", "next", "door")))
"""*the bathroom next door*: next to the room of the place named last (a door joins rooms, so after an object
it is the object's room)."""
QUAL_EXCEPT = Phrases((("except", "for"), ("except",), ("but", "not"), ("other", "than"), ("apart", "from"),
                       ("excluding",), ("besides",)))
ONLY_WORDS = frozenset({"only", "just", "but"})
"""In a room's contents (*with only / just the bed*, *with nothing but a bed*): nothing else is in it."""
ONLY_FOLLOWERS = ("after", "if", "once", "when", "before")
"""After *only*: *only after X*, *only if X* ... (not *the bedroom with a bed only*: its contents)."""
ONLY_AS_BUT_AFTER = frozenset({"please", ","})
"""Between a sentence's first word *only* and a prohibition (*Only please stay out of X*, *Only, keep out of
X*): *only* is the joiner *but*, not *only <do X> after Y* (unless the sentence has an order word, see
:data:`ONLY_ORDER_WORDS`)."""
ONLY_ORDER_WORDS = frozenset({*ONLY_FOLLOWERS, "until", "till", "til", "unless", "then"})
"""In a sentence opening with *only*: *only* may be *only <do X> after Y*, so it is not read as *but*."""
IN_IT = ("in", "inside")
"""``the bedroom that only has a bed in it``: the trailing *in it* repeats the room."""
CONTENTS_BEFORE_COUNT = ONLY_WORDS | word_set("with has have having containing contains")
"""Before a count of a room's contents (*with one sink*, *that has only one sink*): the count an elided
noun refers back to (*then the one with two*)."""
NOTHING_ELSE = Phrases((("and", "nothing", "else"), ("and", "nothing", "more"),
                       ("and", "no", "other", "things"), ("and", "nothing", "else", "in", "it"),
                       ("and", "nothing", "else", "inside")))
"""*the bedroom where is only one bed and nothing else*: the room holds nothing of another category."""
ASIDE = Phrases(tuple((",", rel, be, *also) for rel, be in (("which", "is"), ("which", "are"), ("that", "is"),
                                                             ("that", "are"), ("it", "is"), ("it", "'s"),
                                                             ("that", "'s"), ("they", "are"))
                      for also in ((), ("also",), ("located",), ("also", "located"))))
RELATIVE_THAT = Phrases((("that", "is"), ("which", "is"), ("that", "are"), ("which", "are"), ("who", "is"),
                        ("what", "is"), ("what", "are")))
"""*the bathroom that is next to the bedroom*: a relative clause stating a qualifier (*the clock what is in
the bedroom*, as learners write *that*)."""
ASIDE_QUALIFIERS = frozenset({"in", "inside", "on", "next", "beside", "upstairs", "downstairs", "near",
                              "adjacent", "connected", "attached"})
"""``the couch, which is in the living room`` / ``the bowl (it's in the kitchen)``: an aside read as the
qualifier it states."""
RELATIVE_BE = ("is", "are", "was", "were", "sits", "lives", "stands")
PLURAL_BE = ("are", "were")
FINDING_VERBS = word_set("find see spot notice")
"""*<room>, where you can find / see X*: says where X is, or asks for X? (refused)"""
PERMISSION_WORDS = ("allowed", "permitted", "welcome")
"""*you are allowed / welcome to go into X* gives leave, which neither asks for X nor forbids it (refused);
after a negation they forbid (*you are not allowed into X*)."""
"""After several things in a relative clause (*the bedroom where the book and the vase are*)."""
RELATIVE_PARTICIPLES = ("located", "kept", "stored", "placed", "found", "standing", "sitting")
"""``the room where the book is (kept)``."""
STATEMENT_LINKS = ("is", "are", "was", "were")
"""``it is`` / ``there are``: a statement, not a reference."""
WHOLE_BUILDING_PREPOSITIONS = ("in", "inside", "throughout", "of", "around")
WHOLE_BUILDING_DETERMINERS = ("the", "this", "our", "my", "your")

# --------------------------------------------------------------------------------------------- context
EVENT_WORDS = word_set(
    """breakfast brunch lunch lunchtime dinner dinnertime supper tea teatime morning afternoon evening night
    tonight today tomorrow weekend noon midday midnight bedtime monday tuesday wednesday thursday friday
    saturday sunday work school class meeting party guests visitors dawn dusk sunset sunrise now later soon
    daily weekly mornings evenings nights day week call appointment shift"""
)
"""Times of day, meals and events: *Before lunch, ...*, *After dinner, ...*, *Tonight, ...* only say when,
which a mission cannot require; said at the start of a sentence they are set aside (said back), never read
as the goal of *before / after*. A clock time (*at 6 pm*) or a delay (*in ten minutes*) is refused."""
MEALS = word_set("breakfast brunch lunch lunchtime dinner dinnertime supper tea teatime bedtime")
"""Meals and bedtime: *After breakfast go ...* says when, as *This morning go ...* does."""
PAST_TIMES = word_set("yesterday earlier")
"""Times gone by, in a time expression (*the office is a mess since yesterday*); *last* counts too before a
word of :data:`EVENT_WORDS` (*after last night*, *since last week*), never alone (*do the kitchen last*)."""
NAMED_DAYS = ("day", "night", "week", "weekend")
"""After a thing, a day named for it (*Plant day!*): context, not the thing as a goal."""
TIME_WORDS = word_set("this next tomorrow today tonight later soon early late right now for the at some "
                      "point sometime first thing in a bit while before after by during around all long"
                      ) | EVENT_WORDS
"""Words of a time expression (*later this afternoon*, *at some point this evening*, *first thing
tomorrow*); one with an event word (:data:`EVENT_WORDS`) only says when."""
EVENT_VERBS = word_set("arrive arrives come comes leave leaves get gets back home start starts finish "
                       "finishes end ends wake wakes up go goes out begin begins gone away asleep sleeping "
                       "napping here working 's")
"""In a time expression of an event (*before the guests arrive*, *after I get back*)."""
EVENT_VERBS = EVENT_VERBS | word_set("over done finished ready served up awake")
"""(*once lunch is over*, *when dinner's ready*)."""
DAY_OPENERS = ("this", "tonight", "today", "tomorrow", "for", "in")
"""The words a time of day that opens an order without a comma starts with (*This evening stay ...*,
*Tonight check ...*, *In the morning check ...*, *for now* (not *for the kitchen*: no time); not *the guests
arrive*, an event)."""
SPAN_OPENERS = ("during",)
"""Like :data:`DAY_OPENERS`, a time over a span, which cannot order the steps (*During the party tonight keep
out of ...*)."""
EVENT_ENDS = (("is", "over"), ("are", "over"), ("has", "finished"), ("have", "finished"), ("finishes",),
              ("ends",), ("is", "done"), ("are", "done"), ("stops",), ("goes", "off"), ("go", "off"),
              ("is", "ready"), ("are", "ready"), ("'s", "ready"), ("'s", "finished"))
"""The end of an event of others closing a clause (*once the match has finished*): something to wait for
(only words the lexicon knows already: a new word here would stop *the clock stopped* being a statement)."""
EVENT_OPENERS = ("before", "after", "by", "while", "once", "when")
"""The words a time expression of an event starts with (*before the guests arrive*, *once lunch is over*)."""
EVENT_TAILS = word_set("up over by in out off round around back home away")
"""The particles after the verb of an event of people said by its shape (*before the cleaners show up*, *once
my sister drops by*); any other word after the verb leaves the event to the parser."""
EVENT_AUXILIARIES = word_set("am are is was were have has had will would been just already finally")
"""Words before the verb of an event of people (*once the dog has been fed*, *after the kids have just
left*)."""
EVENT_LINKS = ("from", "on", "at", "after", "for")
"""Words that join an event word to the verb of an event of people (*gets home from work*, *show up on
Sunday*, *leave for school*)."""
MANNER_INTENSIFIERS = word_set("extra very really super so")
MANNER_WORDS = MANNER_INTENSIFIERS | word_set("careful gentle quiet quick patient nice good polite tidy")
"""*..., so be gentle*, *please be extra careful*: how to behave, set aside when nothing else is said."""
FEW = ("few", "couple", "several")
TIME_UNITS = word_set("second seconds minute minutes min mins hour hours hr hrs sec secs")
"""*in ten minutes*, *wait 5 min*: a delay, which a mission cannot require (refused)."""
THING_STOPS = (DETERMINERS | frozenset(PRONOUNS) | frozenset(NUMBER_WORDS) | TIME_UNITS | PARTICLES
               | frozenset(HANDLED_AT)
               | word_set("and or nor then but if when whenever once while until till before after not no "
                          "never to from of for with without through via past there here"))
"""Words that end the name of a thing the scene does not hold (:data:`HANDLED_AT`): grammar, not a name."""
TIME_OPENERS = ("before", "after", "by", "during", "for", "at", "around", "this", "tonight", "today",
                "tomorrow", "later", "right", "first", "sometime", "some", "next", "early", "in", "all",
                "while")
"""Words a time expression that opens a sentence starts with (*Before lunch, ...*, *Tonight, ...*)."""
SUBJECT_PRONOUNS = word_set("i we he she they it there that this everyone everybody someone somebody "
                            "nobody everything something nothing")
"""The subject of a statement (*We're hosting dinner tonight*, *It's laundry day*, *I think ...*): a sentence
starting with one of them asks nothing of the robot, unless it is a polite wrapper (*I need you to ...*)."""
STATEMENT_VERBS = word_set("is are was were am be been being 's has have had will would shall can could "
                           "might may must should do does did keeps keep kept seems seem looks look gets got "
                           "needs need")
"""Verbs right after a subject that make a sentence a statement (*the cat keeps ...*, *my mum's staying*)."""
STATED_VERBS = word_set(
    """arrive arrives arrived come comes coming came leave leaves leaving left made make makes making
    went goes going think thinks thought know knows knew love loves loved hate hates like likes said says
    told tells broke broken fell fallen ate eaten slept sleeps sleeping napping stays staying stayed lives
    lived works working worked visiting visits moved moving arriving returns returned starts started begins
    began finished"""
)
"""Verbs of statements about other people or things (*the guests arrive at seven*, *the kids made a mess*):
after a subject of no room or object, a statement."""
NEED_WORDS = word_set("need needs needed want wants wanted should must ought require requires")
"""A statement of a need (*the plants need watering*): about a room or object of the scene it may ask for a
goal that is not said, so it is refused; about anything else it is set aside."""
PEOPLE_NOUNS = word_set("""cleaner cleaners plumber plumbers builder builders electrician kids children
    family mum mom dad grandma grandpa granny nan baby neighbour neighbours neighbor neighbors friend friends
    boss wife husband partner sister brother parents folks delivery courier postman""")
"""People of an event (*before the cleaners come*, *while my mum's here*): not the robot, not a place."""
PEOPLE_NOUNS = PEOPLE_NOUNS | word_set("""inlaws relatives relations son sons daughter daughters niece nephew
    aunt uncle cousin cousins grandson granddaughter grandkids grandparents flatmate roommate housemate lodger
    tenant landlord nanny babysitter gardener vet""")
"""More people (*In-laws coming round!*, *my niece can't decide*)."""
PEOPLE_NOUNS = PEOPLE_NOUNS | word_set("child kid toddler teenager teen hubby missus")
"""More people (*my little one* is read *my child*: :data:`PHRASE_ALIASES`)."""
STATED_VERBS = STATED_VERBS | word_set("want wants wanted wish wishes asked asks swears swore reckons")
"""More verbs of statements about people (*My son wants it.*, *she asked for it*)."""
STATED_VERBS = STATED_VERBS | word_set("forgot forgets forgotten bought buys brought brings spilled spilt "
                                      "spills follows followed borrowed borrows")
"""More verbs of statements about people and pets, past and present (*My son forgot his homework.*, *our cat
follows everyone around*)."""
STATED_ADVERBS = word_set("just already finally recently")
"""Between a bare subject and its verb (*Groceries just got delivered*, *Mum finally called*)."""
WANTED_WHERE = word_set("here there back down up upstairs downstairs")
"""Where a thing is wanted (*she wants it back*, *he needs it upstairs*): a need that may ask for a goal."""
HOW_MANY = word_set("a few couple several some lots loads plenty of them one more")
"""Words of a clause that only says how many there are (*there's a few*, *there are a couple of them*)."""
PEOPLE = word_set("i we he she they")
"""The people of an event (*after I get back*, *before we leave*): not the robot, not a place."""
DEICTIC_SUBJECTS = ("it", "there", "this", "that")
"""Subjects that are a statement's only with a verb of being after them (*it's laundry day*, not *this
bathroom*)."""
SEQUENCE_TIMES = ("later", "soon", "now")
"""Time words that alone order the steps (*Later, go to X*) rather than say when."""
WHOLE_PERIODS = ({("all", period) for period in ("day", "morning", "afternoon", "evening", "night", "week",
                                                  "weekend")}
                 | {("all", "day", "long"), ("all", "night", "long")})
"""*Don't go in the bathroom all day*: the whole mission's time, which orders nothing."""
GREETING_TIMES = {(*good, period) for good in ((), ("good",))
                  for period in ("morning", "afternoon", "evening")}
"""*Morning!*, *Good evening*: a greeting, said back, which orders nothing."""
NOW_SAID = {("right", "now"), ("for", "now"), ("just", "now")} | WHOLE_PERIODS | GREETING_TIMES
"""Times that say when the whole mission is (now, a whole period), so that they put no goals in an order."""
OCCASIONS = {("this", "time"), ("this", "time", "round"), ("just", "this", "once")}
"""*stay downstairs this time*: the occasion of the whole mission, which orders nothing (a time, like
:data:`NOW_SAID`)."""
STATEMENT_JOINERS = ("so", "but", "and", "because", "as")
REASONS = Phrases((("because",), ("cause",), ("'cause",), ("so", "that"), ("since",),
                   *(("so", who, what) for who in ("i", "we") for what in ("know", "can", "see")),
                   ("so", "you", "can"), ("so", "you", "could"),  # "... so you can compare" (no place after)
                   *(("to", *check, whether) for check in (("see",), ("check",), ("find", "out"))
                     for whether in ("if", "whether")), ("to", "make", "sure"), ("to", "test"),
                   # "to check it's clean": a check of the state of what was just named, not a goal ("to
                   # check that the oven is off" names the oven: people mean it as a goal, so it is read)
                   *(("to", check, *who) for check in ("check", "see", "confirm", "verify", "ensure")
                     for who in (("it", "is"), ("it", "'s"), ("they", "are"), ("it", "has"), ("they", "have"),
                                 ("nothing", "is"), ("everything", "is"), ("everything", "'s")))))
"""A reason for an order, set aside to its clause's end (*... because the coffee's in there*, *... so I know
you made it*, *... to see if anyone needs anything*): it asks nothing. A check of whether that names a room or
object (*... to see if the oven is off*: the oven a goal too?) is left to the parser."""
CHECK_WHETHER = Phrases(tuple(("to", *check, whether) for check in (("see",), ("check",), ("find", "out"))
                              for whether in ("if", "whether")))
"""The reasons of :data:`REASONS` that check whether something holds (*to see if ...*)."""
_CHECKED_STATE = (("it", "is"), ("it", "'s"), ("they", "are"), ("it", "has"), ("they", "have"),
                  ("nothing", "is"), ("nothing", "'s"), ("everything", "is"), ("everything", "'s"))
REASONS = REASONS + Phrases(tuple((*just, *checking, *that, *who) for just in ((), ("just",))
                                  for checking in (("checking",), ("making", "sure"), ("double", "checking"))
                                  for that in ((), ("that",)) for who in _CHECKED_STATE))
"""The same reason said as what the speaker is doing (*..., just checking nothing's chipped*, *..., making
sure it's off*): the state of what was just named, set aside like *to check it's ...*."""
AFTER_ORDER_REASONS = Phrases((*(("as", who) for who in ("i", "we", "it", "they", "she", "he", "there", "the",
                                                        "my", "our", "everyone", "nobody")),
                                ("in", "case"), ("just", "in", "case")))
"""Reasons only after an order in the same sentence (*check the laptop as it needs charging*, *check the
oven in case it was left on*): opening a sentence they may say when or if (*as we leave*, *in case of ...*),
which is left to the parser."""
AFTER_ORDER_REASONS = AFTER_ORDER_REASONS + Phrases((
    ("seeing", "as"), ("seeing", "that"), ("given", "that"), ("now", "that"), ("considering", "that")))
"""(*check the oven, seeing as we're cooking tonight*, *... now that dinner is done*)."""
STATE_RESULTS = Phrases(tuple(("so", *who) for who in (*_CHECKED_STATE, ("they", "'re"))))
SENSED_STATES = word_set("looks stays feels smells")
"""Verbs of how a thing seems (*it looks tidy*, *the bathroom smells*)."""
STATE_RESULTS = STATE_RESULTS + Phrases(tuple(
    ("so", who, verb) for who, verbs in (("it", SENSED_STATES), ("everything", SENSED_STATES),
                                         ("they", ("look", "stay", "feel", "smell")))
    for verb in sorted(verbs)))
"""(*check the living room so it looks tidy*, *... so everything stays dry*)."""
"""The state an order leaves what it names in, said after it (*check the bedroom so it's tidy*, *... so
nothing's burning*): a reason like *so that ...*, set aside only after an order and when it names no room,
object or floor."""
_PAST_TALK = ("discussed", "agreed", "promised", "planned", "requested", "asked", "arranged", "instructed",
              "mentioned", "said")
CLOSING = CLOSING + Phrases((
    # asides that ask nothing: "honestly", "(don't ask)", "no matter what" (after a prohibition: emphasis)
    ("honestly",), ("do", "not", "ask"), ("no", "matter", "what"),
    # what was said before: "as discussed", "like I asked", "same as always"
    *((as_, said) for as_ in ("as", "like") for said in _PAST_TALK),
    *((as_, who, said) for as_ in ("as", "like") for who in ("i", "we") for said in _PAST_TALK),
    *((*the, "same", "as", *when) for the in ((), ("the",))
      for when in (("always",), ("usual",), ("yesterday",), ("last", "time"), ("last", "week"))),
    ("like", "always"), ("like", "usual"),
    # encouragement: "you know the drill", "you've got this", "over to you"
    ("you", "know", "the", "drill"), *(("you", be, "doing", great) for be in ("are", "'re")
                                        for great in ("great", "well", "amazing", "brilliant")),
    ("you", "have", "got", "this"), ("you", "got", "this"), ("you", "can", "do", "it"), ("over", "to", "you"),
    ("all", "yours"), ("it", "is", "all", "yours")))
"""More of :data:`CLOSING`: what was said before (*as discussed*, *like I asked*, *same as always*) and
encouragement (*you know the drill*, *you've got this*), which ask nothing wherever they close a clause."""
CLOSING = CLOSING + Phrases((
    # notice given before a statement: "Heads up, the dog is loose.", "Just so you know, ..."
    *((*just, *a, "heads", "up") for just in ((), ("just",)) for a in ((), ("a",))),
    ("just", "so", "you", "know"), ("so", "you", "know"), ("for", "your", "information"),
    ("for", "the", "record"), ("quick", "note"), ("just", "a", "note"), ("a", "note"), ("fair", "warning"),
    ("just", "fyi"),
    # thinking aloud: "Hmm let me see, ...", "Where was I?", "what else... oh yeah, ..."
    *(("let", "me", "see", *now) for now in ((), ("now",))),
    *((*now, "where", "was", "i") for now in ((), ("now",))),
    ("what", "else"), ("what", "was", "i", "saying"), ("what", "am", "i", "forgetting"), ("oh", "yes"),
    ("ah", "yes")))
"""More of :data:`CLOSING`: notice given before a statement and thinking aloud, which ask nothing."""
_THAT = ((), ("that",))
NOTICE_THAT = Phrases((*((*please, "note", *that) for please in ((), ("please",)) for that in _THAT),
                       *((*please, "be", "aware", "that") for please in ((), ("please",))),
                       *((verb, "in", "mind", *that) for verb in ("bear", "keep") for that in _THAT),
                       ("remember", "that"), ("know", "that")))
"""Words that open a statement to be noted (*Note that the kitchen is wet.*, *Bear in mind the dog is
asleep*): the statement after them is context like any other (*remember* without *that* may ask to go:
left to the parser)."""
APOLOGY_WORDS = ("sorry", "oops", "whoops", "apologies")
THANKS_FOR = Phrases((
    ("thanks", "for"), ("thank", "you", "for"), ("many", "thanks", "for"), ("cheers", "for"),
    ("thanks", "so", "much", "for"), ("thank", "you", "so", "much", "for")))
"""Thanks for something that names nothing (*Thanks for all your help this week*): a remark, like an apology
for something (:func:`.syntax.context.apology_for`); thanks for something of the scene (*thanks for
cleaning the kitchen*) is left to the parser."""
KISSES = frozenset({"x", "xx", "xxx"})
"""Kisses signing off a message (*Love, Dad x*): a remark only as the last word of a sentence, as *x* is also
operators' shorthand for *not* (*x kitchen*)."""
_LEAVE_GIVEN: tuple[tuple[str, ...], ...] = (
    *((fine, to, "you") for fine in ("okay", "ok", "alright", "fine") for to in ("with", "by", "for")),
    ("all", "right", "with", "you"), ("convenient",), ("possible",), ("no", "trouble"), ("no", "bother"),
    ("no", "problem"), ("not", "a", "problem"), ("not", "too", "much", "bother"),
    ("not", "too", "much", "trouble"))
CLOSING = CLOSING + Phrases((
    # the robot's leave asked as a condition on nothing it could sense: "if it's okay with you", "whenever
    # it's convenient" (not "if it's okay", which after "check the oven" may ask what the robot finds)
    *((when, it, *be, *fine) for when in ("if", "when", "whenever") for it in ("it", "that", "this")
      for be in (("is",), ("'s",), ("would", "be"), ("will", "be")) for fine in _LEAVE_GIVEN),
    # nothing urgent: "just a routine check, nothing urgent", "..., I promise"
    *(("nothing", what) for what in ("urgent", "major", "serious", "big", "fancy", "special")),
    ("no", "big", "deal"), ("i", "promise"), ("i", "swear")))
"""More of :data:`CLOSING`: leave asked as a condition (*if it's okay with you*, *whenever it's
convenient*), *nothing urgent*, *I promise*, which ask nothing wherever they close a clause. A condition on
the state of a thing (*if it is not locked*) is no remark: refused as a condition the robot cannot sense."""
CLOSING = CLOSING + Phrases((
    # the robot's time as a condition on nothing it could sense: "when you've got a minute", "if you get a
    # chance"
    *((when, "you", *have, "a", *spare, time) for when in ("when", "whenever", "if", "once")
      for have in (("have", "got"), ("have",), ("get",), ("got",), ("find",))
      for spare in ((), ("spare",), ("free",), ("quick",))
      for time in ("minute", "moment", "second", "chance", "sec", "mo", "min")),
    *((when, "you", *be, "free") for when in ("when", "whenever", "if", "once")
      for be in (("are",), ("get",))),
))
"""More of :data:`CLOSING`: the robot's time asked as a condition (*when you've got a minute*, *if you get
a chance*, *once you're free*), which asks nothing wherever it closes or opens a clause."""
CLOSING = CLOSING + Phrases(tuple(
    (when, "you", *be, *fully, *charged) for when in ("when", "once", "after")
    for be in (("are",), ("have", "been"), ("have",), ("get",))
    for fully in ((), ("fully",), ("all",))
    for charged in (("charged",), ("recharged",), ("charged", "up"), ("done", "charging"),
                    ("finished", "charging"))))
"""More of :data:`CLOSING`: the robot's own charge as the time of the orders (*Once you're charged, ...*,
*when you've fully recharged*): nothing of the scene, said back wherever it opens or closes a clause."""
CLOSING = CLOSING + Phrases((("obviously",), ("of", "course"), ("roughly",), ("not", "urgent"),
                             ("not", "a", "priority"), ("not", "a", "big", "deal")))
"""More of :data:`CLOSING`: hedges alone in their clause (*Check the oven, obviously.*, *Morning routine,
roughly: ...*, *Not urgent, but check the oven.*)."""
CLOSING = CLOSING + Phrases((
    *((indulge, "me") for indulge in ("humor", "humour", "indulge", "trust")),
    ("bear", "with", "me"), ("just", "saying")))
"""More of :data:`CLOSING`: asking to be indulged, which asks nothing of the scene (*avoid the lobby (humor
me)*, *check it twice, just saying*); not *not really*, which may take back what came before it."""
IGNORED = Phrases((("ignore",), ("never", "mind"), ("do", "not", "mind"), ("do", "not", "worry", "about")))
"""Words that tell the robot to pay no heed to a thing the scene does not hold (*btw ignore the mess*, *don't
mind the noise*): set aside (:func:`.syntax.context.ignored_thing`); *ignore the kitchen* may mean skip or
avoid, and is refused."""
WELL_WISHING = word_set("hope hoping trust")
"""A wish said without its subject (*hope you're charged up*, *hope your day's going ok*, *trust all is
well*): a remark when the words after it name nothing and ask nothing
(:func:`.syntax.context.well_wishing`)."""
WISH_STOPS = word_set("then after before first last next finally again once twice when whenever if until")
"""Words of order or condition, which a wish never holds (*hope you're going first*: refused)."""
CLOSING_TAILS = Phrases((("at", "all"), ("indeed",), ("with", "it"), ("with", "you"), ("with", "that"),
                         ("with", "this"), ("by", "me"), ("for", "me")))
"""Words that only make a remark of :data:`CLOSING` stronger or say to whom (*no rush at all*, *thank you very
much indeed*, *take your time with it*, *if that's okay with you*): part of the remark, right after it."""
UNSURE = Phrases((("not", "sure"), ("not", "certain"), ("can", "not", "remember"), ("can", "not", "recall"),
                  ("do", "not", "remember"), ("do", "not", "know"), ("dunno",), ("no", "idea"),
                  ("just", "wondering"), ("wondering",), ("not", "sure", "but")))
"""A speaker's doubt said without its subject (*Not sure if I turned it off.*, *Can't remember whether the
oven's on*): before *if* / *whether* the clause after it is a statement like any other."""
SURE_WITHOUT_SUBJECT = Phrases((("pretty", "sure"), ("fairly", "sure"), ("quite", "sure"),
                                ("pretty", "certain"), ("fairly", "certain"), ("almost", "certain"),
                                ("100", "%", "sure"),
                                ("bet",), ("i", "bet"), ("i", "reckon"), ("reckon",), ("looks", "like"),
                                ("seems", "like"), ("apparently",)))
"""A speaker's belief said without its subject (*Pretty sure we're out of milk.*, *Looks like it rained.*):
the statement after it (and after *that*) is context like any other."""

CORRECTING_WORDS = word_set("mean meant means wrong mistake instead rather actually not other else said "
                            "say wanted want need needed")
"""After *Sorry,* words that may say what was meant (*Sorry, I meant ...*, *Sorry, wrong one*): the sentence
is then a correction, not an apology."""
STATES = word_set("wet slippery busy occupied closed locked flooded painted drying messy dirty filthy "
                  "cluttered noisy dark cold freezing hot smelly blocked broken")
"""States a note gives a place without a verb (*office wet - avoid it*, *NB: lobby busy*): context."""
STATEMENT_HEDGES = word_set("probably maybe perhaps possibly likely definitely surely somewhere")
"""Words that open a clause adding a guess to the statement before it (*I lost my glasses, probably somewhere
upstairs*): with no verb, place, object or pronoun after them it is part of that context."""
HEDGE_INTENSIFIERS = word_set("most very quite pretty almost")
"""Before a hedge of :data:`STATEMENT_HEDGES` (*most likely*, *quite possibly*)."""
GOING_VERBS = word_set("go come get head move walk run travel proceed return pop nip stop pass drive "
                       "navigate arrive stay remain keep")
"""Verbs of going or staying: after *, to* they may say where to go (*..., to go upstairs*), never a mere
purpose (:func:`.syntax.context.purpose_infinitive`)."""
PURPOSE_TAILS = word_set("off up out it them yourself myself")
"""After the verb of a purpose *, to rinse off* / *, to check it*: words that name nothing."""
OWN_PARTS_OF = word_set("your its")
"""Whose parts a purpose is about when it is the robot's upkeep (*... to wash your wheels*)."""
NOW_WORDS = word_set("now atm rn today still again")
PRAISE = word_set("cool great perfect lovely nice sweet awesome brilliant excellent super fab fantastic "
                  "wonderful splendid marvellous ace grand good ok okay alright")
"""Praise said as a sentence of its own (*Perfect.*, *Cool cool.*): said back; never skipped inside a clause
(*Is the kitchen lovely?* asks something)."""
COMPARED = ("same", "such", "as", "so", "far", "much", "many", "long")
"""Before *as* in a comparison (*the same floor as*, *as far as*), where it gives no reason."""
ROOM_PARTS = word_set("floor floors door doors wall walls window windows carpet carpets rug ceiling tiles "
                      "paint lights light heating")
"""The parts of a room a statement is about (*the lobby floor is still wet*): context, not the room as a
goal."""
ORDER_JOINERS = ("so", "but")
"""Before an order, a clause boundary even without a comma (*my son is asleep so don't go up there*)."""
LOCATIVE = word_set("in into on onto at inside under beside near by behind")
"""Prepositions of place: a statement that places an object of the scene is no mere context."""
"""Between a statement and an order in one sentence (*Grandpa's napping, so stay out of there*)."""


# ------------------------------------------------------------------------------------------- chit-chat
ARTICLES = frozenset({"a", "an", "the", "my", "your", "our"})
TALK_NOUNS = frozenset({"plan", "few", "couple", "thing", "things", "favour", "favor", "request", "job",
                        "task", "tasks", "lot", "bit", "moment", "minute", "second", "question", "list",
                        "day", "morning", "afternoon", "evening", "idea", "deal", "drill", "lowdown", "hand"})
"""After an article, only these say nothing (*here's the plan*, *I need a few things done*): any other word
there could name something to go to (*feed the cat* where the scene has no cat must be refused, not
skipped)."""
OPENERS = frozenset({"hi", "hello", "hey", "okay", "ok", "alright", "well", "so", "good", "thanks", "thank",
                     "i", "we", "here", "right", "cheers", "morning", "evening", "afternoon", "sorry",
                     "alexa", "siri", "google", "robot", "buddy", "yo", "yeah", "hiya", "heya", "howdy",
                     "yes", "yep", "oi", "oy", "ahoy"})
"""Chit-chat starts with a greeting, an interjection or the speaker (*I'm hungry*, *here's the plan*); a
sentence starting otherwise may be an order about something the scene lacks (*feed pets*), so it is parsed
(and refused) instead."""
OPENERS = OPENERS | {"oh"} | EXCLAMATIONS  # "Oh gosh, ...", "Phew, ...": a remark that opens chit-chat too
FRAGMENT_HEADS = (TALK_NOUNS | LIST_NOUNS | EVENT_WORDS | frozenset(NAMED_DAYS)
                  | word_set("time party occasion emergency visit stuff business")) - word_set(
    "do dos donts order sequence steps step now later soon first")
"""The head of a sentence with no verb that only sets the scene (*Time for the evening round.*, *Quick errands
before I get home.*, *Busy day.*; :mod:`.syntax.fragments`): a word of talk, of a list or of a time, never
one that orders (*Reverse order.*, *Later.*)."""
FRAGMENT_ARTICLES = word_set("a an the my our another some")
FRAGMENT_MODIFIERS = word_set("quick little good big small busy usual routine long short lovely more")
"""Words of the lexicon that may still stand before the head of such a fragment (*a quick one*, *a little
favour*); *last* too, in a sentence before any goal (*Last thing before you charge.*)."""
REMARK_CHOOSERS = word_set("any either whichever")
REMARK_ENDS = word_set("fine ok okay good works do")
"""A remark that leaves the choice to the robot: *any chair's fine*, *either bathroom will do*."""
CONTENT_WORDS = word_set("with has have holding holds containing contains")
"""Words that say a room by what it holds (*the bedroom with the plant*, *the one that has the vase*)."""
PLACING_WORDS = word_set("in inside on of from at there here upstairs downstairs")
"""Words that place an object by its own phrase (*the vase in the lobby*, *the vase there*)."""
FRAGMENT_TIMES = word_set("late early lately today tonight tomorrow soon now")
FRAGMENT_AWAY = Phrases((("out",), ("off",), ("away",), ("home",), ("from", "home"), ("late",)))
"""After a fragment's verb in *-ing*: the speaker goes out, stays away or is late (*Heading out soon.*,
*Working from home today.*, *Running late!*): the verb is the speaker's own doing, even one the grammar reads
as an order (*head*, *run*)."""
FRAGMENT_PEOPLE = word_set("you me us")
"""Whom such a fragment is for (*A little job for you.*)."""
AUXILIARIES = frozenset({"am", "are", "is", "was", "were", "have", "has", "will", "would"})
"""In chit-chat (*hope you're well*): no role, although *are* is a word of the grammar elsewhere."""
GREETINGS = frozenset({"hi", "hello", "hey", "hiya", "heya", "howdy", "oi", "oy", "yo", "ahoy"})
INTERJECTIONS = HESITATIONS | GREETINGS | frozenset({"ok", "okay", "oh", "oops", "hmm", "fyi", "btw", "ps"})
"""Words before a statement that say nothing (*ok I dropped my keys somewhere, ...*)."""
INTERJECTIONS = INTERJECTIONS | EXCLAMATIONS  # "gosh, the cat's been sick again, ..."
"""*Hi there!*: after a greeting, *there* is no place."""

# -------------------------------------------------------------------------------------- phrase aliases
PHRASE_ALIASES: dict[tuple[str, ...], tuple[str, ...]] = {
    ("prior", "to"): ("before",),
    ("ahead", "of"): ("before",),
    ("in", "advance", "of"): ("before",),
    ("as", "soon", "as"): ("once",),
    ("as", "soon", "as", "possible"): ("asap",),
    ("as", "soon", "as", "you", "can"): ("asap",),
    ("the", "moment"): ("once",),
    ("right", "after"): ("after",),
    ("straight", "after"): ("after",),
    ("immediately", "after"): ("after",),
    ("start", "with"): ("first",),
    ("first", "things", "first"): ("first",),
    ("begin", "with"): ("first",),
    ("start", "off", "with"): ("first",),
    ("keep", "your", "hands", "off"): ("never", "touch"),  # "keep your hands off the TVs"
    # "the middle floor's kitchen": the middle floor kitchen (not "the floor's wet": the floor is)
    **{("floor", "'s", room): ("floor", room) for room in (
        "kitchen", "bathroom", "bedroom", "corridor", "hallway", "hall", "living", "dining", "lobby",
        "office", "home", "staircase", "utility", "empty", "toilet", "loo", "bath", "bed", "sink", "tv")},
    **{(kid, "'s", "rm"): (kid, "'s", "room") for kid in ("kid", "kids")},  # "kid's rm w/ teddy"
    # "start at the fridge, then ...": blind writers read the place as the first goal, never the robot's start
    **{(verb, *off, where): ("first", "go", "to") for verb in ("start", "begin") for off in ((), ("off",))
       for where in ("at", "in")},
    ("to", "start", ","): ("first", ","),
    ("to", "begin", ","): ("first", ","),
    ("to", "start", "with", ","): ("first", ","),
    ("to", "begin", "with", ","): ("first", ","),
    ("first", "of", "all"): ("first",),
    ("before", "anything", "else"): ("first",),
    ("before", "everything", "else"): ("first",),
    ("first", "and", "foremost"): ("first",),
    ("first", "off"): ("first",),
    ("last", "of", "all"): ("finally",),
    ("to", "finish", ","): ("finally", ","),
    ("to", "finish", "off", ","): ("finally", ","),
    ("to", "wrap", "up", ","): ("finally", ","),
    ("every", "time", "when"): ("every", "time"),
    ("each", "time", "when"): ("each", "time"),
    ("any", "time", "when"): ("any", "time"),
    ("should", "you"): ("if", "you"),
    ("in", "the", "end"): ("finally",),
    ("ultimately",): ("finally",),
    ("thereafter",): ("after", "that"),
    ("beforehand",): ("before", "that"),
    ("previously",): ("before", "that"),
    ("at", "the", "end", ","): ("finally", ","),
    ("at", "the", "end"): ("last",),
    ("at", "the", "very", "end"): ("last",),
    ("last", "but", "not", "least"): ("finally",),
    ("after", "this"): ("after", "that"),
    ("following", "that"): ("after", "that"),
    ("following", "this"): ("after", "that"),
    ("after", "doing", "that"): ("after", "that"),
    ("after", "doing", "this"): ("after", "that"),
    ("with", "that", "done"): ("after", "that"),
    ("with", "that", "out", "of", "the", "way"): ("after", "that"),
    # a visit said again: "then the lounge once more" / "one more time" is "again"; "at least once" asks what
    # any goal asks (one visit or more), so it says nothing ("at least twice" stays refused)
    ("once", "more"): ("again",),
    ("one", "more", "time"): ("again",),
    ("at", "least", "once"): ("at", "some", "point"),
    # an ordinal counting the steps with no comma after it ("first the oven, second the laptop, third the
    # couch") is the ordinal with a comma ("second, ..."), before an article only (not "second bedroom")
    **{(nth, article): (nth, ",", article) for nth in ("second", "third", "fourth", "fifth")
       for article in ("the", "a", "an")},
    # steps numbered in words: "Step 1: ..., Step 2: ..." / "step one" are the ordinals ("first: ...")
    **{("step", said): (nth,) for n, nth in enumerate(("first", "second", "third", "fourth"), 1)
       for said in (str(n), ("one", "two", "three", "four")[n - 1])},
    # the return said as a time, closing with a comma: "when you come back (down), X" / "once you're back,
    # X" / "after you get back downstairs, X" is "on your way back (down), X" (X after what came before: the
    # floor is where X is, which X's own words must single out); naming where ("when you come back to the
    # kitchen, X") it is not this phrase
    **{(when, "you", *verb, "back", *said, ","): ("on", "your", "way", "back", *way, ",")
       for when in ("when", "once", "after")
       for verb in (("come",), ("get",), ("are",), ("have", "come"), ("have", "got"), ("got",), ("came",))
       for said, way in (((), ()), (("down",), ("down",)), (("up",), ("up",)), (("downstairs",), ("down",)),
                         (("upstairs",), ("up",)))},
    ("along", "with"): ("and",),
    ("together", "with"): ("and",),
    ("plus",): ("and",),
    ("anywhere", "near"): ("into",),
    ("up", "here"): ("on", "this", "floor"),
    # "the bathroom up top", "go up top": the top floor (after a thing it may be a top shelf: not read)
    **{(said, "up", "top"): (said, "on", "the", "top", "floor")
       for said in ("room", "bathroom", "bedroom", "kitchen", "office", "corridor", "hallway")},
    **{(go, "up", "top"): (go, "up", "to", "the", "top", "floor") for go in ("go", "head", "come", "pop")},
    ("down", "here"): ("on", "this", "floor"),
    ("where", "you", "can", "find"): ("containing",),
    ("where", "you", "will", "find"): ("containing",),
    ("where", "you", "find"): ("containing",),
    ("holding",): ("containing",),
    ("and", "also"): ("and",),
    ("after", ","): ("afterwards", ","),
    ("after", ":"): ("then", ":"),  # notes: "dining tbl 1st. after: oven"
    # learners: "make a check of the toilet", "do the checking of the fridge", "clean them all"
    ("make", "a", "check", "of"): ("check",), ("do", "a", "check", "of"): ("check",),
    ("do", "the", "checking", "of"): ("check",), ("make", "the", "checking", "of"): ("check",),
    ("them", "all", ","): ("all", "of", "them", ","), ("them", "all", "."): ("all", "of", "them", "."),
    ("not", "go", "to", "down"): ("not", "go", "downstairs"),
    ("not", "go", "to", "up"): ("not", "go", "upstairs"),
    ("not", "go", "down", "."): ("not", "go", "downstairs", "."),
    ("not", "go", "up", "."): ("not", "go", "upstairs", "."),
    ("in", "floor", "down"): ("downstairs",), ("of", "floor", "down"): ("downstairs",),  # "in floor down"
    ("no", "matter", "the", "order"): ("in", "any", "order"),
    ("order", "is", "free"): ("any", "order"), ("no", "need", "order"): ("any", "order"),  # learners
    ("on", "your", "floor"): ("on", "this", "floor"),  # "please stay on your floor": the robot's
    ("finish", "with"): ("end", "at"),
    ("end", "with"): ("end", "at"),
    ("finishing", "with"): ("ending", "at"),
    ("any", "one", "of"): ("one", "of"),
    ("near", "of"): ("near",),
    ("next", "of"): ("next", "to"),
    ("close", "of"): ("close", "to"),
    ("i", "want", "that", "you"): ("i", "want", "you", "to"),
    # "I'd just like you to ...": "just" softens the request, it narrows nothing
    **{("i", modal, "just", "like", "you", "to"): ("i", "would", "like", "you", "to")
       for modal in ("d", "would")},
    ("i", "would", "like", "that", "you"): ("i", "would", "like", "you", "to"),
    ("without", "to"): ("without",),
    ("for", "to"): ("to",),
    ("just", "one", "of"): ("one", "of"),
    ("only", "one", "of"): ("one", "of"),
    ("try", "not", "to"): ("do", "not"),
    ("be", "careful", "not", "to"): ("do", "not"),
    ("take", "care", "not", "to"): ("do", "not"),
    ("be", "sure", "not", "to"): ("do", "not"),
    ("mind", "you", "do", "not"): ("do", "not"),
    ("mind", "not", "to"): ("do", "not"),
    ("be", "careful", "to", "avoid"): ("avoid",),
    ("take", "care", "to", "avoid"): ("avoid",),
    ("hold", "off"): ("postpone",), ("holding", "off"): ("postpone",),  # refused: later, or not at all?
    ("whatever", "you", "do", ","): ("please",),
    ("whatever", "you", "do"): ("please",),
    ("try", "to", "avoid"): ("avoid",),
    ("try", "and", "avoid"): ("avoid",),
    ("try", "to", "stay", "out", "of"): ("stay", "out", "of"),
    ("try", "to", "keep", "out", "of"): ("keep", "out", "of"),
    ("try", "to", "stay", "away", "from"): ("stay", "away", "from"),
    # learners' prepositions: "stay out from X", "keep away of X"; "stay far from X"
    **{(keep, "out", "from"): (keep, "out", "of") for keep in ("stay", "keep")},
    **{(keep, away, "of"): (keep, "away", "from") for keep in ("stay", "keep") for away in ("away", "far")},
    **{(keep, "far", "from"): (keep, "away", "from") for keep in ("stay", "keep")},
    ("either", "way"): ("also",),
    ("in", "any", "case"): ("also",),
    ("regardless",): ("also",),
    # contractions and spellings of speech: "till" / "til" is "until"; "'s got" is "has"
    ("till",): ("until",),
    ("til",): ("until",),
    ("'s", "got"): ("has",),
    ("is", "got"): ("has",),
    ("is", "only", "got"): ("only", "has"),
    ("is", "just", "got"): ("only", "has"),
    ("has", "got"): ("has",),
    ("have", "got"): ("have",),
    ("has", "not", "got"): ("does", "not", "have"),
    ("have", "not", "got"): ("do", "not", "have"),
    ("'s", "only", "got"): ("only", "has"),
    ("has", "only", "got"): ("only", "has"),
    ("'s", "just", "got"): ("only", "has"),
    ("has", "just", "got"): ("only", "has"),
    ("oh", "and"): ("and",),
    # remarks that start a sentence: "P.S." / "btw" / "by the way" add to the mission ("also"); "no worries if
    # not" makes a goal optional, which is refused as "optionally" is
    ("p", ".", "s", "."): ("also",),
    ("ps",): ("also",),
    ("one", "more", "thing"): ("also",),
    # punctuation dictated as words ("go to the kitchen comma then the office period")
    ("comma",): (",",),
    ("full", "stop"): (".",),
    ("period",): (".",),
    ("question", "mark"): ("?",),
    ("exclamation", "mark"): ("!",),
    ("exclamation", "point"): ("!",),
    ("new", "line"): (".",),
    ("new", "paragraph"): (".",),
    ("just", "one", "more", "thing"): ("also",),
    ("btw",): ("also",),
    ("by", "the", "way"): ("also",),
    ("if", "so"): ("depending",),  # "check if the oven is hot, and if so turn it off": sensing
    ("if", "yes"): ("depending",),
    ("through", "to"): ("to",),  # British "take it through to the living room": to it
    ("no", "worries", "if", "not"): ("optionally",),
    ("no", "problem", "if", "not"): ("optionally",),
    ("if", "not", ",", "no", "worries"): ("optionally",),
    ("if", "not", ",", "no", "problem"): ("optionally",),
    # operator shorthand of words that are no room or object: "chk" is "check", "GF" the ground floor
    ("chk",): ("check",),
    ("chck",): ("check",),
    ("chkd",): ("checked",),  # "no dining rm til oven chkd"
    ("'s", "been"): ("has", "been"),  # "until the oven's been checked": never a possessive before "been"
    ("pls",): ("please",),
    ("plz",): ("please",),
    ("gf",): ("ground", "floor"),
    # "stay on flr.": the floor it is on (not "stay on flr 1")
    **{("stay", "on", "flr", end): ("stay", "on", "this", "floor", end)
       for end in (".", ",", "!", ";", "and")},
    ("wondering", "whether"): ("wondering", "if"), ("wonder", "whether"): ("wonder", "if"),
    ("you", "mind", "terribly"): ("you", "mind"),  # "Would you mind terribly going ..."
    ("possible", "not", "to"): ("possible", "to", "not"),  # "Would it be possible not to go into X ...?"
    # "do me a small favour": a favour (the size is no word of the wrapper)
    **{(who, "a", small, favour): (who, "a", favour) for who in ("me", "us")
       for small in ("small", "little", "quick", "big", "huge") for favour in ("favour", "favor")},
    # "Main thing today is to ...": the main thing (of today: the whole mission)
    **{("thing", *today, "is"): ("thing", "is") for today in (("today",), ("for", "today"), ("tonight",),
                                                             ("though",))},
    ("what", "i", "really", "need"): ("what", "i", "need"),  # "What I really need is for you to ..."
    # "check the fridge every time after you go into the kitchen": each time you go in, afterwards
    **{(every, "time", "after", "you"): (every, "time", "you") for every in ("every", "each")},
    # "Would it be alright if you went to X": a wish said in the past tense, an order
    **{("would", "it", "be", *fine, "if", "you", past): ("please", present)
       for fine in (("alright",), ("all", "right"), ("okay",), ("ok",), ("possible",))
       for past, present in (("went", "go"), ("checked", "check"), ("looked", "look"), ("visited", "visit"),
                             ("watered", "water"))},
    # learners' choice remarks: "the toilet, any of two", "either of two": of the two ("anyone" is kept out:
    # a word of an alias is a word of the grammar, and "before anyone is up" is about people)
    **{(chooser, "of", number): (chooser, "of", "the", number) for chooser in ("any", "either", "whichever")
       for number in ("two", "three", "four", "2", "3", "4")},
    # "the vases that are there", as learners say it "what are there": the vases there
    **{(that, be, "there"): ("there",) for that in ("that", "which", "what") for be in ("is", "are")},
    # "gnd flr bath", "gnd: empty rm -> ...", "gnd bath toilet": the ground floor
    ("gnd", "flr"): ("ground", "floor"), ("gnd", "fl"): ("ground", "floor"),
    ("gnd", "floor"): ("ground", "floor"), ("gnd",): ("ground", "floor"),
    ("dn",): ("down",),  # "=> dn to DR chair"
    ("dwn",): ("down",),  # "dwn to kit", "dwn 1 flr"
    ("something", "out", "of"): ("something", "from"),  # "get something out of the fridge": from it
    # "bthrm f0 sink": floor 0 (the letter before a digit, as in "f1", "f2")
    **{("f", str(n)): ("floor", str(n)) for n in range(10)},
    ("order", "nvm"): ("any", "order"),  # "order nvm": never mind the order
    ("upstrs",): ("upstairs",),
    ("dwnstrs",): ("downstairs",),
    ("downstrs",): ("downstairs",),
    ("dnstrs",): ("downstairs",),
    ("upstair",): ("upstairs",),  # learners' singular
    ("downstair",): ("downstairs",),
    ("to", "1st"): ("to", "the", "first"), ("to", "2nd"): ("to", "the", "second"),  # "-> back to 1st"
    # "empty rm 1st, only then kit", "1st LR couch", "2nd flr": ordinals in digits read as in words
    ("1st",): ("first",), ("2nd",): ("second",), ("3rd",): ("third",), ("4th",): ("fourth",),
    ("5th",): ("fifth",),
    ("whilst",): ("while",),  # British: "... whilst you're about it"
    ("thanks", "a", "mil"): ("thanks", "a", "million"),
    # "the TV in the office, then any in the living room": any one of the kind named last
    ("any", "in"): ("any", "one", "in"), ("any", "on"): ("any", "one", "on"),
    # "one of the living room chairs, then one in the dining room": any one of that kind there
    **{(joiner, "one", where): (joiner, "any", "one", where)
       for joiner in (",", "then", "and") for where in ("in", "on", "from")},
    ("nxt",): ("next",),
    ("u",): ("you",),
    ("ur",): ("your",),
    ("thru",): ("through",),
    ("tonite",): ("tonight",),
    ("tmrw",): ("tomorrow",),
    ("tmr",): ("tomorrow",),
    ("rn",): ("right", "now"),
    ("lmk",): ("let", "me", "know"),
    # light verbs: "have / having a look at X" is "take a look at X" (wherever the verb stands)
    **{(have, "a", *quick, look): (take, "a", *quick, look)
       for have, take in (("have", "take"), ("having", "taking"), ("had", "took"))
       for quick in ((), ("quick",), ("little",), ("good",), ("proper",))
       for look in ("look", "peek", "glance")},
    # times that only give context: "first thing (in the morning)" opens the day, that is first; "before bed
    # tonight" is bedtime (not the bed)
    ("first", "thing"): ("first",),
    ("first", "thing", "in", "the", "morning"): ("first",),
    ("before", "bed", "tonight"): ("before", "bedtime", "tonight"),
    ("before", "going", "to", "bed"): ("before", "bedtime"),
    ("before", "you", "go", "to", "bed"): ("before", "bedtime"),
    ("set", "foot", "in"): ("enter",),
    ("set", "foot", "into"): ("enter",),
    ("set", "foot", "on"): ("enter",),
    ("go", "near"): ("go", "into"),
    ("come", "near"): ("go", "into"),
    # "take the stairs down to the ground floor": the stairs are the way there, not a goal; where to is
    # said after them
    **{("take", "the", stairs, way, "to"): ("go", way, "to")
       for stairs in ("stairs", "staircase") for way in ("down", "up")},
    **{(verb, way, "the", "stairs", "to"): ("go", way, "to")
       for verb in ("go", "walk", "head") for way in ("down", "up")},
    # "take the stairs up and look at the TV": a move between floors (the stairs are the way): "go upstairs"
    **{("take", "the", stairs, way): ("go", f"{way}stairs")
       for stairs in ("stairs", "staircase") for way in ("down", "up")},
    **{(verb, way, "the", "stairs"): ("go", f"{way}stairs")
       for verb in ("go", "walk", "head") for way in ("down", "up")},
}
"""Phrases read as another (``prior to`` is ``before``, ``as soon as`` is ``once``), rewritten on the tokens
before parsing (:func:`.text.rewrite`), so that no unknown word of such a phrase is taken for a verb."""
PHRASE_ALIASES.update({
    ("in", "laws"): ("inlaws",),  # "In-laws coming round!": people, not "in"
    ("cos",): ("because",), ("coz",): ("because",), ("cuz",): ("because",), ("bc",): ("because",),
    ("tho",): ("though",), ("altho",): ("although",), ("em",): ("them",),
    ("outta",): ("out", "of"), ("outa",): ("out", "of"),  # "stay outta the garage"
    ("do", "try", "not", "to"): ("do", "not"),  # "Do try not to touch the vase": emphatic "try not to"
    ("nothing", "except"): ("nothing", "but"),  # "the bedroom with nothing except a bed"
    # bedtime and the start of the day said otherwise: "before you turn in", "start the day by ..."
    **{("before", who, *turn_in): ("before", "bedtime") for who in ("you", "i", "we", "everyone")
       for turn_in in (("turn", "in"), ("head", "to", "bed"), ("go", "to", "sleep"), ("hit", "the", "sack"))},
    ("start", "the", "day", "by"): ("start", "by"), ("to", "start", "the", "day"): ("first",),
    # operator shorthand for the order: "order n/a", "any ord."
    ("order", "n", "/", "a"): ("in", "any", "order"), ("any", "ord"): ("in", "any", "order"),
    # "Apart from that, ...": what follows is more to do (only before a comma: "other than that room")
    **{(*besides, "that", ","): ("also", ",") for besides in (("apart", "from"), ("aside", "from"),
                                                             ("other", "than"), ("besides",))},
})
_LEARNERS: dict[tuple[str, ...], tuple[str, ...]] = {
    **{("where", "is", "nothing", but): ("with", "nothing", "but") for but in ("but", "except")},
    # "at" left out: "look all three TVs", "look the vase"
    **{("look", det): ("look", "at", det) for det in ("the", "both", "all", "every", "each", "one")},
}
PHRASE_ALIASES.update(_LEARNERS)
PHRASE_ALIASES.update({  # chat's "k?" closing a sentence: "..., k?" is "..., okay?"
    ("k", "?"): ("okay", "?"),
    ("robo",): ("robot",),  # "OK robo, ...": the wake word
    ("any", "order", "whatever"): ("any", "order"),
})
PHRASE_ALIASES.update({  # bedtime before a comma or a colon, or with "tonight": "Tonight before bed: ..."
    **{(*tonight, "before", "bed", *mark): (*tonight, "before", "bedtime", *mark)
       for tonight, mark in ((("tonight",), ()), ((), (",",)), ((), (":",)))},
})
_DAY_PERIODS = (("today",), ("tonight",), ("on",), ("on", "today"), ("in", "the", "day"),
                *((this, period) for this in ("this", "in", "the") for period in ("morning", "afternoon",
                                                                                   "evening")))
PHRASE_ALIASES.update({
    # "Later this morning, check ...": after what was said before, as "Later, check ..." (the time orders
    # nothing more; set aside whole, the order of "later" was lost); "Sometime this afternoon check ...":
    # the time alone
    **{("later", *period, ","): ("later", ",") for period in _DAY_PERIODS},
    **{(*some, "this", period): ("this", period) for some in (("sometime",), ("anytime",), ("some", "time"))
       for period in ("morning", "afternoon", "evening")},
    # "for the rest of the day": the whole mission's time, as "all day"
    **{(*lead, "the", "rest", "of", "the", period): ("all", period) for lead in ((), ("for",))
       for period in ("day", "morning", "afternoon", "evening", "night", "week")},
})
PHRASE_ALIASES.update({  # "stay up here on this floor": the floor said twice
    (here, "here", "on", "this", "floor"): ("on", "this", "floor") for here in ("up", "down", "right")
})

_WISHES = (("rather",), ("prefer",), ("prefer", "it", "if"), ("prefer", "if"), ("appreciate", "it", "if"),
           ("like", "it", "if"), ("love", "it", "if"), ("be", "grateful", "if"), ("be", "thankful", "if"),
           ("be", "so", "grateful", "if"))
"""After *I'd* / *we'd* and before *you*: a wish about what the robot does (*I'd rather you didn't ...*)."""
_SAID_OTHERWISE: dict[tuple[str, ...], tuple[str, ...]] = {
    # a prohibition wrapped as a wish: "I'd rather you didn't go into X", "I'd prefer it if you stayed out"
    **{(*who, *wish, "you", *did): ("do", "not") for who in (("i", "would"), ("we", "would"))
       for wish in _WISHES for did in (("did", "not"), ("not",), ("did", "not", "ever"))},
    # "I'd be grateful if you didn't mind checking X": asked politely, as "would you mind checking X"
    **{(*who, *wish, "you", *did, "mind"): ("would", "you", "mind")
       for who in (("i", "would"), ("we", "would")) for wish in _WISHES
       for did in (("did", "not"), ("not",))},
    **{(*who, *wish, "you", stayed): (stay,) for who in (("i", "would"), ("we", "would"))
       for wish in (("rather",), ("prefer",), ("prefer", "it", "if"), ("prefer", "if"))
       for stayed, stay in (("stayed", "stay"), ("kept", "keep"), ("steered", "steer"),
                            ("avoided", "avoid"))},
    # the same wish said of the robot's conduct: "It would be lovely if you didn't go into X", "It'd be
    # great if you avoided X"
    **{("it", "would", "be", *great, "if", "you", *did): done
       for great in (("lovely",), ("great",), ("nice",), ("good",), ("best",), ("better",), ("ideal",),
                     ("wonderful",), ("brilliant",), ("perfect",), ("helpful",), ("so", "helpful"))
       for did, done in ((("did", "not"), ("do", "not")), (("stayed",), ("stay",)), (("kept",), ("keep",)),
                         (("avoided",), ("avoid",)), (("steered",), ("steer",)))},
    # "at any cost", "at all costs": "at all" (emphasis of a prohibition)
    ("at", "any", "cost"): ("at", "all"), ("at", "all", "costs"): ("at", "all"),
    # neither floor direction: "don't go up and don't go down", "don't go upstairs or downstairs"
    **{("do", "not", "go", a, conj, *again, b): ("stay", "on", "this", "floor")
       for a, b in (("up", "down"), ("down", "up"), ("upstairs", "downstairs"), ("downstairs", "upstairs"))
       for conj in ("and", "or", "nor") for again in ((), ("go",), ("do", "not", "go"))},
    # "the lobby downstairs all the way down": on the lowest floor (not a floor move of its own)
    **{(where, "all", "the", "way", way): ("on", "the", end, "floor")
       for where, way, end in (("downstairs", "down", "bottom"), ("upstairs", "up", "top"))},
    # a prohibition said again for emphasis: "don't go in the living room at all like at all / like never"
    **{("at", "all", *like, *again): ("at", "all") for like in ((), ("like",), ("i", "mean"))
       for again in (("at", "all"), ("never",), ("ever",), ("never", "ever"))},
    # an order made emphatic: "do stay away from X", "please do avoid X" (as "do check X" is read)
    **{("do", verb): (verb,) for verb in ("stay", "keep", "avoid", "steer", "remember")},
    # "my little one" is a child (not the smaller of two things, as "the little one" may be)
    **{(my, "little", one): (my, child) for my in ("my", "our", "your")
       for one, child in (("one", "child"), ("ones", "children"))},
}
PHRASE_ALIASES.update(_SAID_OTHERWISE)
"""More of :data:`PHRASE_ALIASES`: wishes that forbid, emphatic orders, *my little one*."""
_LEARNERS_SAID: dict[tuple[str, ...], tuple[str, ...]] = {  # learners' word orders, notes' set phrases
    ("is", "not", "matter"): ("does", "not", "matter"),  # "the order is not matter"
    ("every", "time", "that"): ("every", "time"),  # "every time that you enter ..."
    ("avoid", "absolutely"): ("avoid",),  # "avoid absolutely the bathrooms"
    ("stay", "please"): ("please", "stay"), ("keep", "please"): ("please", "keep"),  # "stay please on ..."
    ("of", "down"): ("downstairs",), ("of", "up"): ("upstairs",),  # "the bathroom of down"
    ("the", "last", "floor"): ("the", "top", "floor"),  # "the bathroom of the last floor" (ultimo piano)
    # notes: "order whatever", "order dc" ((I) don't care)
    ("order", "whatever"): ("any", "order"), ("whatever", "order"): ("any", "order"),
    ("order", "dc"): ("any", "order"), ("order", "idc"): ("any", "order"),
    ("no", "order"): ("any", "order"),
    ("either", "one", ",", "does", "not", "matter"): ("either", "one"),  # "either one, doesn't matter"
    ("once", "you", "have", ","): ("after", "that", ","),
    ("when", "you", "have", ","): ("after", "that", ","),
    ("either", "one", "of", "them"): ("either", "one"),  # "the toilet in that bathroom, either one of them"
    ("order", "not", "important"): ("any", "order"), ("order", "no", "matter"): ("any", "order"),
    **{("which", *one, "first", *verb, "matter"): ("any", "order")  # "which one first is not matter"
       for one in ((), ("one",)) for verb in (("is", "not"), ("does", "not"))},
    **{("for", verb): ("to", verb)  # learners' purpose "go to the kitchen for check the oven"
       for verb in ("see", "check", "look", "wash", "watch", "clean", "touch", "wipe")},  # not "for water"
    **{("all", digit): ("all", word)  # a note's "lobby vases, all 4"
       for digit, word in (("2", "two"), ("3", "three"), ("4", "four"), ("5", "five"), ("6", "six"))},
    ("when", "ever"): ("whenever",),  # "When ever you go in the kitchen"
    ("up", "floor"): ("upper", "floor"), ("down", "floor"): ("lower", "floor"),  # "of the up floor"
    ("in", "any", "moment"): ("at", "any", "time"), ("at", "any", "moment"): ("at", "any", "time"),
    ("do", "not", "going"): ("do", "not", "go"),  # "Don't going in the dining room"
    ("the", "one", "or", "the", "other"): ("either", "one"),  # "an apple, the one or the other"
    ("give", "water", "to"): ("water",),  # "give water to the plant"
    ("one", "or", "the", "other"): ("either", "one"),  # "take a bottle, one or the other"
    ("bear", "teddy"): ("teddy", "bear"),  # "the bedroom with the bear teddy" (ours teddy-bear, theirs bear)
    ("remain", "on"): ("stay", "on"),  # "remain on this same floor"
    ("this", "same", "floor"): ("this", "floor"),
    ("on", "this", "floor", "only"): ("on", "this", "floor"),  # "stay on this floor only": the same
    **{(*one, last, "thing", mark): ("lastly", ",")  # "Last thing, water the plant": the last step
       for one in ((), ("one",)) for last in ("last", "final") for mark in (",", ":")},
    ("is", "next", "the"): ("is", "next", "to", "the"),  # "the bathroom which is next the kitchen": beside it
    ("are", "next", "the"): ("are", "next", "to", "the"),
    ("where", "is", "also"): ("where", "is"), ("where", "are", "also"): ("where", "are"),
    ("that", "it", "has"): ("that", "has"), ("which", "it", "has"): ("which", "has"),  # a resumptive "it"
    **{(prep, floor, word): (prep, "the", floor, word)  # "go up on top floor", "no grnd flr": no article
       for prep in ("on", "to", "at", "in", "of", "avoid", "no", "off", "from", "into")
       for floor in ("top", "middle", "bottom", "upper", "lower", *FLOOR_NAMED) for word in FLOOR_WORDS},
}
PHRASE_ALIASES.update(_LEARNERS_SAID)
PHRASE_ALIASES.update({  # "the baby's napping in the living room, so keep out.": out of the place just said
    ("so", verb, "out", end): ("so", verb, "out", "of", "there", end)
    for verb in ("keep", "stay") for end in (".", "!", ",", ";")
})
PHRASE_ALIASES.update({  # "and when you finish, go to the lobby": when you have finished (that)
    (w, "you", finish): (w, "you", "have", "finished")
    for w in ("when", "once", "after") for finish in ("finish", "finishes", "complete")
})
PHRASE_ALIASES.update({  # "wipe the toilet, then do the same in the bathroom upstairs": that kind there
    ("the", "same", where): ("the", "one", where)
    for where in ("in", "inside", "upstairs", "downstairs", "on")
})
PHRASE_ALIASES.update({  # "set it down by X", "pop it on X", "stick them in X": the thing carried put there
    (verb, it, *down, where): ("put", it, *down, where)
    for verb in ("set", "pop", "stick", "lay", "plonk", "rest")
    for it in ("it", "them")
    for down in ((), ("down",), ("back",), ("back", "down"))
    for where in ("on", "onto", "in", "into", "by", "beside", "near", "next", "inside")
})

# ------------------------------------------------------------------------------------ grammar words
STRUCTURAL = (
    (SEQ_WORDS + NEG_STARTS + QUAL_CONTAINS + QUAL_LACKS + QUAL_NEXT + QUAL_EXCEPT + ORDER_MODIFIERS).words()
    | frozenset(QUAL_IN) | CONDITION_WORDS.words() | DETERMINERS
    | frozenset(FLOOR_WORDS) | frozenset(FLOOR_ORDINALS) | frozenset(FLOOR_NAMED)
    | frozenset(FLOOR_TOP) | frozenset(FLOOR_MIDDLE) | frozenset(NUMBER_WORDS)
    | frozenset(PRONOUNS)
    | frozenset(GENERIC_ROOM_WORDS)
    | frozenset({"whenever", "only", "than", "zero", "ever", "again", "twice", "once", "times", "anytime"})
) - POSITIVE_VERBS - {"first", "also", "please", "eventually", "finally"}
"""Words with a role in the grammar: in the verb slot they signal a sentence that was not understood."""


def _words_of(value: object) -> frozenset[str]:
    """The words of a lexicon table: its strings, phrases and keys, split at spaces."""
    if isinstance(value, str):
        return frozenset(value.split())
    if isinstance(value, Phrases):
        return value.words()
    if isinstance(value, dict):
        return _words_of(tuple(value)) | _words_of(tuple(value.values()))
    if isinstance(value, (tuple, frozenset, set, list)):
        return frozenset().union(*(_words_of(v) for v in value)) if value else frozenset()
    return frozenset()


LEXICON_WORDS = frozenset().union(*(_words_of(v) for k, v in list(globals().items())
                                    if k.isupper() and not k.startswith("_")))
"""Every word of every table above: the words the translator knows, besides the scene's names (what *did you
mean* suggests from, with those names; :mod:`.spelling`)."""
_NOUN_TABLES = ("SYNONYMS", "IRREGULAR_PLURALS", "EVERYDAY_NAMES", "PEOPLE_NOUNS")
NOUN_WORDS = (frozenset().union(*(_words_of(globals()[k]) for k in _NOUN_TABLES))
              - frozenset().union(*(_words_of(v) for k, v in list(globals().items())
                                    if k.isupper() and not k.startswith("_") and k not in _NOUN_TABLES
                                    and k != "LEXICON_WORDS")))
"""Words the lexicon knows only as nouns (*people*, *laundry*, *coffee*): a bare subject of a statement
(*Laundry's done*, *people are still asleep*) may be one; a word of any other table may have a role."""
