"""Lists: numbered or bulleted items (*1. the lobby*, *- the fridge*), what their heading says (*Morning
round*, *Top floor tasks:*, *Any order is fine:*), and lists announced before a colon (*three things: A, B
and C*, *visit two rooms: the kitchen and the office*, *never enter these: ...*).

**Items.** Each item is a sentence of its own. The items of a numbered list are done in the order written
(each continues the sequence of the one before it, as a sentence starting with *Then* does); a bulleted
list is a set, done in any order. An order remark in the heading (*in order*, *any order is fine*) or in a
sentence right after the list (*The order doesn't matter.*) says otherwise. *In that order.* after
sentences of one goal each (*Fridge. Oven. Microwave. In that order.*) orders them as a numbered list is; an
order remark after one sentence listing goals (*Check the oven and the fridge. Do them in any order.*) is
read with it. An
item that says *eventually* / *at some point* first is not ordered after the one before it.

**Headings.** The sentence before a list's first item heads it when it ends with a colon or stands on a
line of its own. A heading that announces the list (*three things:*, *visit these rooms:*, *never enter
these:*) is read with each item: its verb or negation before each, its number and noun checked against the
items (:class:`.tree.Announced`). A heading that only labels the list (*Morning round*, *Shopping list
check*, *Please do these, in order:*) is set aside, except what it says of the order and of the floor the
items are on (*Top floor tasks*: every goal of the list is on the top floor); a clause after its comma
(*Checklist, stay on this floor:*) is read as a sentence. Words before a colon that ask nothing (*Here's
the plan:*, *Remember:*) are dropped. Any other colon ends a sentence, as ``.`` does.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Literal

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline import refusals as rf
from sgplan.llm.offline.syntax.actions import left_things_put
from sgplan.llm.offline.syntax.context import closing_only, is_time
from sgplan.llm.offline.syntax.floors import floor_words
from sgplan.llm.offline.syntax.fragments import context_fragment
from sgplan.llm.offline.syntax.noun_slot import noun_phrase
from sgplan.llm.offline.syntax.preamble import is_chitchat
from sgplan.llm.offline.syntax.qualifiers import head_kind
from sgplan.llm.offline.syntax.reader import Match, Reader
from sgplan.llm.offline.syntax.tree import Announced, Described
from sgplan.llm.offline.text import Tok

Order = Literal["ordered", "any"]


def read_lists(readers: list[Reader]) -> list[Reader]:
    """``readers`` (sentences, some ending with a colon, some list items) with each list's heading read
    and its items ordered (see the module docstring)."""
    readers = items_with_room_heading(readers)
    out: list[Reader] = []
    k = 0
    while k < len(readers):
        r = readers[k]
        heading = r if r.marker is None and heads(r, readers, k) else None
        lines = line_items(readers, k) if heading is None else []
        heading = r if lines else heading
        first = k + (1 if heading is not None else 0)
        run = lines or (list_run(readers, first) if heading is not None or r.marker is not None else [])
        if not run:
            said = only_order_remark(r) if r.marker is None else None
            ordered = (ordered_before(out, r) if said == "ordered"
                       else remark_joined(out, r, _ANY_ORDER_ALLOWS) if said == "any" else None)
            out = ordered if ordered is not None else out + colon(r, readers[k + 1] if k + 1 < len(readers)
                                                                  else None)
            k += 1
            continue
        after = readers[first + len(run)] if first + len(run) < len(readers) else None
        remark = only_order_remark(after) if after is not None and after.marker is None else None
        out += list_items(heading, run, remark)
        k = first + len(run) + (1 if remark else 0)
    return left_things_put(merged(out))  # an item may leave what the item before it fetched


def ordered_before(out: list[Reader], remark: Reader) -> list[Reader] | None:
    """``out`` (the sentences before the remark *In that order.*) with each sentence of one goal after the one
    before it (*Fridge. Oven. Microwave. In that order.*), or the one sentence of goals before it, a list
    with no order words of its own, read with the remark after a comma (*Check the oven, the fridge and the
    couch. In that order.*); ``None`` (the remark is left to the parser, which refuses it) otherwise: with a
    list or an order of its own, which order is meant is not known."""
    goals = [n for n, r in enumerate(out) if not r.aside and r.phrase(0, lx.NEG_STARTS) is None]
    if len(goals) == 1 and goals[0] == len(out) - 1:
        joined = remark_joined(out, remark)
        if joined is not None:
            return joined
    plain = all(out[n].marker is None and out[n].announced is None and not set(out[n].words) & lx.LIST_JOINERS
                for n in goals)
    if len(goals) < 2 or not plain:
        return None
    return [replace(r, after_item=True) if n in goals[1:] else r for n, r in enumerate(out)]


_ANY_ORDER_ALLOWS = frozenset({",", "and", "all", "both", "also", "too"})
"""Words of a list that an *any order* remark after it may follow (*The oven and the fridge both need a look.
Do them in any order.*); the others order the goals, or say when (which order is meant?)."""


def remark_joined(out: list[Reader], remark: Reader,
                  allows: frozenset[str] = frozenset({",", "and"})) -> list[Reader] | None:
    """``out`` with its last sentence, a list of goals with no words of :data:`.lexicon.LIST_JOINERS` but
    ``allows`` (*Check the oven and the fridge.*), read with the order remark after it (*Do them in any
    order.*) after a comma; ``None`` when the last sentence is no such list (the remark is then read, or
    refused, on its own)."""
    listed = out[-1] if out else None
    if listed is None or listed.aside or listed.marker is not None or not set(listed.words) & {",", "and"} \
            or set(listed.words) & (lx.LIST_JOINERS - allows):
        return None
    said = next(k for k in range(len(remark))  # "Do them in any order.": "in any order"
                if remark.phrase(k, lx.ANY_ORDER) or remark.phrase(k, lx.ORDER_MODIFIERS))
    comma = Tok(",", listed.toks[-1].end, listed.toks[-1].end)
    return [*out[:-1], replace(listed, toks=(*listed.toks, comma, *remark.toks[said:]))]


def items_with_room_heading(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each list item that is a room and a colon joined to the words after the colon on
    its line (*- kitchen: check the microwave*, *2) bedroom with the clock: the clock*): one item, read in
    that room, as *Kitchen: check the microwave* is on a line of its own; a word of the order and a colon
    (*3. last: the couch*) is joined to them as if a comma stood there. An item's colon before anything else
    is left as it is (and refused)."""
    out: list[Reader] = []
    for r in readers:
        last = out[-1] if out else None
        colon_end = last is not None and last.word(len(last) - 1) == ":"
        said = replace(last, toks=last.toks[:-1]) if last is not None and colon_end else None
        heading = room_heading(labelled(said)) if said is not None and said.marker and said.toks else None
        if last is not None and heading is not None and r.marker is None and not r.new_line and r.toks:
            item = heading_kept_out(heading, r) or replace(r, toks=heading.prefix + r.toks)
            out[-1] = replace(item, marker=last.marker, new_line=last.new_line)
            continue
        if last is not None and said is not None and said.marker and len(said) == 1 \
                and said.word(0) in lx.ORDER_HEADS and r.marker is None and not r.new_line and r.toks:
            # "3. last: the couch": the order word read as if a comma stood for the colon ("3. last, ...")
            comma = Tok(",", said.toks[-1].end, said.toks[-1].end)
            out[-1] = replace(r, toks=(*said.toks, comma, *r.toks), marker=last.marker,
                              new_line=last.new_line)
            continue
        out.append(r)
    return out



def list_run(readers: list[Reader], k: int) -> list[Reader]:
    """The items of the list starting at ``readers[k]`` (consecutive sentences with a list marker)."""
    end = k
    while end < len(readers) and readers[end].marker is not None:
        end += 1
    return readers[k:end]


def line_items(readers: list[Reader], k: int) -> list[Reader]:
    """The lines without list markers after ``readers[k]`` when it ends with a colon and its words say an
    order (*ok list, in that order:* over a line per goal): each is an item of that list, as a bulleted one
    is; ``[]`` when the heading says no order or fewer than two lines follow it. A line holding several
    sentences under such a heading, and lines with and without list markers under one that orders them,
    are refused: which of them are steps of the order is not known."""
    heading = readers[k]
    if heading.marker is not None or heading.word(len(heading) - 1) != ":":
        return []
    run: list[Reader] = []
    for r in readers[k + 1:]:
        if r.marker is not None or r.word(len(r) - 1) == ":" or (run and r.word(0) in lx.ADDENDUM_OPENERS):
            break  # a list, a heading of its own, or a line added after the list ("Also check the TV.")
        run.append(r)
    marked = k + 1 + len(run) < len(readers) and readers[k + 1 + len(run)].marker is not None
    if run and run[0].new_line and marked and heading_of(heading)[2] == "ordered":
        rf.refuse(rf.line_of_sentences(heading.quote(0, len(heading)), run[-1].quote(0, len(run[-1]))))
    if len(run) < 2 or not run[0].new_line or heading_of(heading)[2] is None:
        return []
    for r in run:
        if not r.new_line:
            rf.refuse(rf.line_of_sentences(heading.quote(0, len(heading)), r.quote(0, len(r))))
    return run


def heads(r: Reader, readers: list[Reader], k: int) -> bool:
    """Whether ``r`` (``readers[k]``) heads the list after it: it ends with a colon, or it stands on a line of
    its own right before the list's first item."""
    after = readers[k + 1] if k + 1 < len(readers) else None
    if after is None or after.marker is None:
        return False
    return r.word(len(r) - 1) == ":" or (r.new_line and after.new_line)


def list_items(heading: Reader | None, run: list[Reader], remark: Order | None) -> list[Reader]:
    """The sentences of a list: its heading read (see :func:`heading_of`) and its items, each after the one
    before it when the list is in order (see the module docstring)."""
    label = place_label(heading, run) if heading is not None else None
    out, announced, said_order, scope = ([], None, None, ()) if heading is None else (
        ([label], None, None, ()) if label is not None else heading_of(heading))
    order = remark or said_order or ("ordered" if any(r.marker == "number" for r in run) else "any")
    if order == "ordered" and not remark and not said_order:
        check_no_bulleted_goal(run)
        check_no_order_remark(run)
    prefix = scope + (announced.prefix if announced is not None else ())
    check_order_words(run, order)
    for n, item in enumerate(run):
        after = order == "ordered" and n > 0 and not (item.word(0) == "eventually"
                                                      or item.at(0, "at", "some", "point"))
        said = prefix[len(scope):] if scope[:1] and scope[0].text == "in" and outside_room(item) else prefix
        if set(t.text for t in said[len(scope):]) <= lx.LIGHT_PREFIX and keeps_out(item):
            said = said[:len(scope)]  # "Please do these: ... - stay out of X": no "do" before it
        lead = len(item.phrase(0, lx.SEQ_WORDS) or ())  # "- then the plant": the scope after "then"
        lead += 1 if lead and item.word(lead) == "," else 0
        out.append(replace(item, toks=item.toks[:lead] + said + item.toks[lead:], announced=announced,
                           after_item=after))
    return out


def place_label(heading: Reader, run: list[Reader]) -> Reader | None:
    """A heading that names a room before a word of its own (*Kitchen tidy*, *Garage trip:*) over items one
    of which names that room (*1. fetch the chair from the garage*), or before a word naming a list (*Lobby
    check*, *Office run:*) over items that name that room and another one (*1. Lobby 2. Either bedroom*),
    or a kind of object before a word naming a list (*Plant round:*) over items naming that kind: the place
    is where an item goes, the heading a label, set aside and said back (``None`` otherwise: *Kitchen jobs:
    - the oven* is the room of each item, and a heading whose place no item names is read as it was)."""
    said = replace(heading, toks=heading.toks[:-1]) if heading.word(len(heading) - 1) == ":" else heading
    head = said.head(0)
    rest = said.words[head.words:] if head is not None else []
    if (head is None or not 0 < len(rest) <= 2
            or any(not w.isalpha() or (w in lx.STRUCTURAL and w not in lx.LIST_NOUNS) or w in lx.LABEL_STOPS
                   or said.head(head.words + n) for n, w in enumerate(rest))):
        return None  # ("Garage first:" says an order: never a label)
    places = [h.categories for item in run for k in range(len(item))
              if (h := item.head(k)) is not None and h.kind == head.kind]
    listed = all(w in lx.LIST_NOUNS for w in rest)
    if head.kind != "room":  # "Plant round: 1. water the plant in ...": a round of plants
        return replace(said, aside=True) if listed and head.categories in places else None
    named = head.categories in places and (not listed or any(c != head.categories for c in places))
    return replace(said, aside=True) if named and not any(widened(item) for item in run) else None


def widened(item: Reader) -> bool:
    """Whether a list item names no room but a choice or several of a kind (*any of the TVs*, *a plant*, *the
    vases*), which the heading's room would narrow if it were the items' room (*Office stuff: - any of the
    TVs - the office chair*: the office's TVs): then the heading is no mere label."""
    heads = [(k, h) for k in range(len(item)) if (h := item.head(k)) is not None]
    return not any(h.kind == "room" for _, h in heads) and any(
        h.plural or item.word(k - 1) in lx.CHOICE_WORDS for k, h in heads)


def check_order_words(run: list[Reader], order: Order) -> None:
    """An item opening with *first* is the first of a list in order, one opening with *last* / *finally* the
    last of its list (*- A - B - last, C*: C after all of them); anywhere else (*- first: the oven - the
    couch*, *1. last: A 2. B*) which items it comes before or after is not read: refused, naming it (not
    *- first A, then B*, an order inside the item, nor *- first A - then B*, the next item after it)."""
    for n, item in enumerate(run):
        inner = any(item.phrase(j, lx.SEQ_WORDS) for j in range(1, len(item)))  # "- first A, then B"
        # "- first A - then B": the next item says it comes after
        then_next = n + 1 < len(run) and run[n + 1].phrase(0, lx.SEQ_WORDS) is not None
        if item.word(0) in lx.FIRST and (n > 0 or (order == "any" and not then_next)) and not inner:
            rf.refuse(rf.order_word_in_list(item.quote(0, len(item)), item.word(0), "first"))
        if item.word(0) in (*lx.LAST, "finally") and n < len(run) - 1:
            rf.refuse(rf.order_word_in_list(item.quote(0, len(item)), item.word(0), "last"))


def check_no_order_remark(run: list[Reader]) -> None:
    """A list in order by its numbers whose item of one place says the order is free (*1) the oven (any
    order) 2) the laptop*): which holds is not known: refused, naming the item (an item of several places
    may order its own: *1. the oven and the fridge, any order 2. the laptop*)."""
    for item in run:
        places = sum(1 for k in range(len(item)) if item.head(k) is not None)
        if places <= 1 and any(item.phrase(j, lx.ANY_ORDER) for j in range(len(item))):
            rf.refuse(rf.order_remark_in_numbered(item.quote(0, len(item))))


def check_no_bulleted_goal(run: list[Reader]) -> None:
    """A list in order by its numbers may hold bulleted prohibitions (*1. A 2. B - never enter C*), but a
    bulleted goal among numbered items (*1. Kitchen - check the oven - open the fridge 2. Office*) is a
    sub-item, in no order the numbers give: refused, naming it."""
    for item in run:
        if item.marker == "bullet" and item.phrase(0, lx.NEG_STARTS) is None and item.word(0) not in lx.STAY:
            rf.refuse(rf.bulleted_among_numbered(item.quote(0, len(item))))


def keeps_out(item: Reader) -> bool:
    """Whether a list item is a prohibition or a stay (*- never enter X*, *- stay out of X*, *- stay on this
    floor*)."""
    return item.phrase(0, lx.NEG_STARTS) is not None or item.word(0) in lx.STAY


def outside_room(item: Reader) -> bool:
    """Whether a list item is about more than the room of its heading (*Living room list: ... - don't go
    through the dining room*, *- stay on this floor*): a stay, or a prohibition whose first place is a
    room."""
    if item.word(0) in lx.STAY:
        return True
    negation = item.phrase(0, lx.NEG_STARTS)
    place = next((h for k in range(len(item)) if (h := item.head(k)) is not None), None)
    return negation is not None and place is not None and place.kind == "room"


def heading_of(heading: Reader) -> tuple[list[Reader], Announced | None, Order | None, tuple[Tok, ...]]:
    """What a list's heading says: the sentences to read from it (a label said back, a clause of its own),
    what it announces of each item, the order it says and the floor it puts the items on (as words opening
    each item)."""
    said = replace(heading, toks=heading.toks[:-1]) if heading.word(len(heading) - 1) == ":" else heading
    said, remark = without_order_remark(said)  # "Visit these rooms in order:"
    order = order_said(remark, 0, len(remark)) if remark is not None else None
    order = order or named_order(said)
    if said.says(lx.CORRECTIONS, 0, len(said)):
        return [said], None, None, ()  # "Change of plan:": takes back what was said before (refused)
    if set(said.words) & lx.ORDER_HEADS and all(w in lx.FILLERS for w in said.words):
        return [said], None, None, ()  # "Then:" before a list: read alone (and refused), never dropped
    if said.toks and (closing_only(said, 0, len(said)) or is_time(said, 0, len(said))):
        return [replace(said, aside=True)], None, order, ()  # "Heads up:", "Evening:": said back
    if is_chitchat(said, 0, len(said)) or all(w in lx.HEADS_UP or w in lx.FILLERS for w in said.words) \
            or len(said.phrase(0, lx.WISH_HEADINGS) or ()) == len(said):
        return [], None, order, ()  # "Here's the plan:", "Remember:": they ask nothing
    announced = (announcement(said) or verb_prefix(said) or room_heading(labelled(said))
                 or floor_heading(said))
    if announced is not None:  # a room heading ("Kitchen stuff:") is the room of each item
        return [], None if announced.scope else announced, order, announced.prefix if announced.scope else ()
    label = label_end(said)
    if label is None and list_name(said, lx.MAX_LABEL_WORDS):
        # "Kids' stuff:", "Shopping prep:": a list's name ("Today's list, in this order:": the order kept)
        return [replace(said, aside=True)], None, order, ()
    if label is None:  # an ordinary sentence before the list: read (or refused) as one; its order kept
        return [said], None, order, ()
    out = [replace(said, toks=said.toks[:label], aside=True)] if names_more(said, label) else []
    if label < len(said) - 1:  # "Checklist, stay on this floor": a sentence of its own
        out.append(replace(said, toks=said.toks[label + 1:]))
    return out, None, order or order_said(said, 0, label), floor_scope(said, 0, label)


def named_order(said: Reader) -> Order | None:
    """``"ordered"`` when the heading ``said`` is only the name of an order (*Order:*, *Order of stops:*,
    *Sequence of jobs:*, *Running order:*): its items are done in the order written, as a numbered list's
    are. Any other word (*Order of preference:*, *Order of stops is up to you:*) makes it no such name."""
    words = said.words[1:] if said.words[:1] == ("running",) else said.words
    named = words[:1] and words[0] in lx.ORDER_NAMES
    listed = len(words) == 1 or (len(words) == 3 and words[1] == "of"
                                 and words[2] in lx.LIST_NOUNS | lx.ANNOUNCED)
    return "ordered" if named and listed else None


def list_name(said: Reader, most: int) -> bool:
    """Whether ``said`` (at most ``most`` words, before a colon) only names a list or a chore in words of its
    own (*Kids' stuff*, *Dishes*): no room or object, verb, prohibition, condition or order word."""
    return (0 < len(said) <= most and label_clause(said, 0, len(said)) is False
            and not set(said.words) & (lx.POSITIVE_VERBS | lx.AVOID_VERBS))


def without_order_remark(r: Reader) -> tuple[Reader, Reader | None]:
    """``r`` without the order remark it ends with (*Do these in any order*), and that remark."""
    for k in range(len(r)):
        if (r.phrase(k, lx.ANY_ORDER) or r.phrase(k, lx.ORDER_MODIFIERS)) and only_order_remark(
                replace(r, toks=r.toks[k:], marker=None)) is not None:
            cut = k - (1 if r.word(k - 1) == "," else 0)
            return replace(r, toks=r.toks[:cut]), replace(r, toks=r.toks[k:])
    return r, None


def labelled(r: Reader) -> Reader:
    """``r`` without the words naming a list it ends with (*Kitchen stuff* -> *Kitchen*)."""
    end = len(r)
    while end > 1 and r.word(end - 1) in lx.LIST_NOUNS | {"stuff"}:
        end -= 1
    return replace(r, toks=r.toks[:end])


def colon(r: Reader, after: Reader | None) -> list[Reader]:
    """A sentence that is no list's heading: before a colon, words that ask nothing are dropped, and an
    announcement is read with the sentence after it (:func:`merged`)."""
    if r.word(len(r) - 1) != ":":
        return [r]
    said, remark = without_order_remark(replace(r, toks=r.toks[:-1]))
    if said.says(lx.CORRECTIONS, 0, len(said)):
        return [said]  # "Change of plan: the office": takes back what was said before (refused)
    if after is not None and (split := room_heading_after_step(said)) is not None:
        return split  # "DR: wipe a table -> kit: bottle": the kitchen heads the words after its colon
    if len(said) > 2 and context_fragment(said, opener=False):
        return [replace(said, aside=True)]  # "Quick errands before I'm back: ...": said back
    if said.toks and set(said.words) & lx.ORDER_HEADS:  # "Then: the kitchen" reads "Then, the kitchen"
        comma = Tok(",", said.toks[-1].end, said.toks[-1].end)
        order = Announced(said.quote(0, len(said)), (*said.toks, comma), None, None, said.toks[0].start,
                          scope=True)
        return [replace(said, toks=(), announced=order)] if after is not None else [said]
    if said.toks and (closing_only(said, 0, len(said)) or is_time(said, 0, len(said))):
        return [replace(said, aside=True)]  # "Heads up:", "Morning:": a remark or a time, said back
    if is_chitchat(said, 0, len(said)) or all(w in lx.HEADS_UP or w in lx.FILLERS for w in said.words) \
            or len(said.phrase(0, lx.WISH_HEADINGS) or ()) == len(said):
        said = replace(said, toks=())  # "Here's the plan:", "Remember:": they ask nothing
    if after is not None and (label := work_label(said, after)) is not None:
        return [label]  # "Bathroom duty: go to the bathroom with the vase ...": the steps name their rooms
    # "Kitchen jobs: the oven, then ...": the kitchen's oven
    announced = (announcement(said) or verb_prefix(said) or room_heading(labelled(said))
                 or chosen_room_heading(said) or floor_heading(said) if said.toks else None)
    if announced is None and said.toks and label_end(said) == len(said):
        # a label of what follows: "Route for today:" is said back, "Rules:" says nothing
        said = replace(said, aside=True) if names_more(said, len(said)) else replace(said, toks=())
    elif announced is None and after is not None and list_name(said, 2) \
            and not set(said.words) & lx.STRUCTURAL:
        said = replace(said, aside=True)  # "Dishes: look at the sink, then ...": the chore's name, said back
    if remark is not None and after is not None:  # "Do these in order: A, B": the remark after the list
        announced = replace(announced or Announced(remark.quote(0, len(remark)), (), None, None,
                                                   remark.toks[0].start, scope=True), suffix=remark.toks)
    if announced is not None and after is not None:
        return [replace(said, toks=(), announced=announced)]
    return [said] if said.toks else []


def work_label(said: Reader, after: Reader) -> Reader | None:
    """*Bathroom duty*, *Kitchen jobs* (a kind of room before words naming a list or a round of work, before
    a colon) over steps that name rooms of that kind themselves (*: go to the bathroom with the vase, then
    the one upstairs*): the heading names the work, not the room of the steps; it is set aside and said back.
    ``None`` (the heading is the room of the steps, as *Kitchen jobs: the oven* is) when the steps name no
    such room, or name a choice or several of a kind before it, which the heading's room could narrow."""
    head = said.head(0)
    rest = said.words[head.words:] if head is not None else ()
    if head is None or head.kind != "room" or not rest or not all(w in lx.LIST_NOUNS for w in rest):
        return None
    for k in range(len(after)):
        h = after.head(k)
        if h is not None and h.kind == "room" and h.categories == head.categories:
            return replace(said, aside=True)
        if h is not None and (h.plural or after.word(k - 1) in lx.CHOICE_WORDS):
            return None
    return None


def chosen_room_heading(r: Reader) -> Announced | None:
    """*Either top-floor bathroom is fine: wash up at a sink, ...*: a choice of room said fine before a colon
    is the room of the sentence after it, as *In either top-floor bathroom, ...* is (never set aside: the
    place would be lost)."""
    end = next((k for k in range(1, len(r))
                if (fine := r.phrase(k, lx.REMARK_FINE)) is not None and k + len(fine) == len(r)), None)
    if r.word(0) not in lx.CHOOSERS_OF_KIND or end is None:
        return None
    return room_heading(replace(r, toks=r.toks[:end]))


def room_heading(r: Reader) -> Announced | None:
    """*Kitchen: the fridge, then the sink*, *DR: any tbl -> ...*: a room before a colon is the room of the
    sentence after it, as *In the kitchen, ...* is."""
    room = noun_phrase(r, 0, "qualifier") if r.np_starts(0) else None
    if not (isinstance(room, Match) and room.end == len(r) and isinstance(room.node, Described)
            and head_kind(room.node) == "room"):
        return None
    said = r.toks
    prefix = (Tok("in", said[0].start, said[0].start), *said, Tok(",", said[-1].end, said[-1].end))
    return Announced(r.quote(0, len(r)), prefix, None, None, said[0].start, scope=True)


def room_heading_after_step(r: Reader) -> list[Reader] | None:
    """*wipe a table -> kit:* (the words before a colon, inside a line of steps): a step, then a room that
    heads what follows the colon, as a line of its own would (*DR: wipe a table -> kit: bottle* is the table,
    then the kitchen's bottle); ``None`` unless the words end with *then* (an arrow) and a room."""
    join = max((k for k in range(1, len(r)) if r.word(k) == "then"), default=None)
    tail = replace(r, toks=r.toks[join + 1:]) if join is not None else None
    heading = room_heading(tail) if tail is not None and tail.toks else None
    if join is None or heading is None:
        return None
    return [replace(r, toks=r.toks[:join]),
            replace(r, toks=(), announced=replace(heading, prefix=(r.toks[join], *heading.prefix)))]


def floor_heading(r: Reader) -> Announced | None:
    """*Top floor: the bathroom, then ...*, *Upstairs:*, *On floor 2:*: a floor (and nothing else) before a
    colon is the floor of the sentences after it, as *On the top floor, ...* is."""
    k = 1 if r.word(0) in ("on", "at") else 0
    k += 1 if r.word(k) == "the" else 0
    scope = floor_scope(r, k, k + 1)
    relative = r.word(k) in lx.RELATIVE_FLOORS
    said_end = k + 1 if relative else k + len(scope) - 2  # the scope is "on <floor words> ," or "upstairs ,"
    if not scope or said_end != len(r) or (relative and k > 0):
        return None
    return Announced(r.quote(0, len(r)), scope, None, None, r.toks[0].start, scope=True)


def merged(readers: list[Reader]) -> list[Reader]:
    """``readers`` with each announcement (a reader without tokens) read with the sentence after it, and
    each sentence that only moves between floors (*Go upstairs.*, *1. Head back down*) read with the one after
    it, as *go upstairs, then ...* (the move says on which floor the goals after it are; in a list in no
    order it is left alone, and refused)."""
    out: list[Reader] = []
    for r in readers:
        if out and between_after_twice(out[-1], r):  # "Visit X two times; between, go to Y": X, Y, X
            comma = Tok(",", r.toks[0].start, r.toks[0].start)
            out[-1] = replace(out[-1], toks=(*out[-1].toks, comma, *r.toks))
            continue
        if (out and only_floor_move(out[-1]) and not r.aside and r.toks
                and (r.marker is None or r.after_item)):  # not in a bulleted list: in no order
            then = Tok("then", r.toks[0].start, r.toks[0].start)
            out[-1] = replace(out[-1], toks=(*out[-1].toks, Tok(",", then.start, then.start), then, *r.toks))
            continue
        if out and out[-1].announced is not None and not out[-1].toks and not r.toks and r.announced:
            # "DR: any chair -> LR again: couch": two announcements in a row head the sentence after them
            first, second = out[-1].announced, r.announced
            out[-1] = replace(r, announced=replace(second, prefix=first.prefix + second.prefix,
                                                   suffix=second.suffix + first.suffix,
                                                   scope=first.scope and second.scope))
            continue
        if out and out[-1].announced is not None and not out[-1].toks:
            announced = out[-1].announced
            kept = None if announced.scope else announced
            out[-1] = (heading_kept_out(announced, r)
                       or replace(r, toks=announced.prefix + r.toks + announced.suffix, announced=kept))
            continue
        out.append(r)
    return [r for r in out if r.toks]


def heading_kept_out(heading: Announced, r: Reader) -> Reader | None:
    """A room heading over nothing but a word of keeping out (*LR: never.*, *bathrms fl2: keep out*, *office
    - off limits*): that room is off limits, as *LR off limits* says; ``None`` otherwise."""
    said = heading.prefix
    if not (heading.scope and said[:1] and said[0].text == "in" and r.words in lx.BARE_PROHIBITIONS):
        return None
    room, end = said[1:-1], said[-2].end
    return replace(r, toks=(*room, Tok("off", end, end), Tok("limits", end, end)), announced=None)


def between_after_twice(before: Reader, r: Reader) -> bool:
    """Whether ``r`` opens with *(and) (in) between* and ``before`` says to visit something twice (*Visit the
    kitchen two times; between, go to the office.*): the visit between the two, as in one sentence."""
    k = 1 if r.word(0) == "and" else 0
    twice = "twice" in before.words or any(before.at(n, "two", "times") or before.at(n, "2", "times")
                                           for n in range(len(before)))
    return twice and not r.aside and r.marker is None and (r.word(k) == "between" or r.at(k, "in", "between"))


def only_floor_move(r: Reader) -> bool:
    """Whether ``r`` only says to go up or down a floor (*Go upstairs*, *Come back down*, *Please head
    downstairs*): a verb of going, then *upstairs* / *downstairs* / *up* / *down* closing it."""
    words = [w for w in r.words if w not in (".", "!")]
    return (len(words) >= 2 and (words[-1] in lx.RELATIVE_FLOORS or words[-1] in lx.UP_DOWN)
            and words[0] in lx.FLOOR_MOVE_VERBS | {"please"}
            and all(w in lx.FLOOR_MOVE_VERBS or w in ("back", "please") for w in words[:-1]))


def announcement(r: Reader) -> Announced | None:
    """What the words of ``r`` announce of the list after its colon, or ``None`` when they do not end with a
    noun group that counts or names the items."""
    end = len(r)
    while end > 0 and any(r.words[end - len(t):end] == t for t in lx.ANNOUNCE_TAIL):
        end -= next(len(t) for t in lx.ANNOUNCE_TAIL if r.words[end - len(t):end] == t)
    head = r.nouns.match(r.words, end - 1)
    if end == 0 or not (r.word(end - 1) in lx.ANNOUNCED or (head is not None and head.plural)):
        return None
    start = end - 1
    while start > 0 and (r.word(start - 1) in lx.ANNOUNCING or r.word(start - 1).isdigit()
                         or r.word(start - 1) in lx.NUMBER_WORDS):
        start -= 1
    if any(r.np_starts(k) or not verb_word(r, k) for k in range(start)):
        return None  # a phrase before the noun group (*Top floor jobs:*): not only an announcement
    count = next((lx.NUMBER_WORDS.get(w) or int(w) for w in r.words[start:end]
                  if w.isdigit() or w in lx.NUMBER_WORDS), None)
    return Announced(r.quote(start, end), r.toks[:start], count, head if head is not None and head.plural
                     and r.word(end - 1) not in lx.ANNOUNCED else None, r.toks[0].start)


def verb_prefix(r: Reader) -> Announced | None:
    """*Never enter:*, *Please visit:*, *Avoid:* before a list: the verb (or the negation) of each item."""
    last = len(r) - 1
    if last < 0 or not (r.word(last) in lx.POSITIVE_VERBS or r.phrase(last, lx.NEG_STARTS)):
        return None
    if any(r.np_starts(k) or not verb_word(r, k) for k in range(len(r))):
        return None  # a word of its own (*Shopping run:*): a label, not a verb for each item
    return Announced(r.quote(0, len(r)), r.toks, None, None, r.toks[0].start)


def verb_word(r: Reader, k: int) -> bool:
    """Whether the word at ``k`` may be read before each item of a list: a verb, a negation, a filler."""
    w = r.word(k)
    return (w in lx.AVOID_VERBS or w in lx.FILLERS or w in lx.NEG_STARTS.words() or w in lx.POLITE.words()
            or w == "doing")  # "Would you mind doing these:"


def label_end(r: Reader) -> int | None:
    """Where the words that only label a list end (at the comma before a clause of its own, or at the end of
    ``r``): clauses of no room or object, no prohibition, condition or order word but an order remark, with
    a word naming a list, an order remark or a floor among them (*Morning round*, *Top floor tasks*, *Please
    do these, in order*); ``None`` when ``r`` does not start with such words."""
    named, k, end = False, 0, 0
    while k < len(r):
        clause = r.words.index(",", k) if "," in r.words[k:] else len(r)
        said = label_clause(r, k, clause)
        if said is None:
            break
        named, end, k = named or said, clause, clause + 1
    return end if named and end else None


def label_clause(r: Reader, start: int, end: int) -> bool | None:
    """Whether the words ``[start, end)`` name a list, an order or a floor (``None``: they say more than a
    label does)."""
    named, k = False, start
    while k < end:
        remark = r.phrase(k, lx.ANY_ORDER) or r.phrase(k, lx.ORDER_MODIFIERS)
        floor = floor_words(r, k)
        if remark or floor is not None:
            named, k = True, k + len(remark) if remark else floor.end  # type: ignore[union-attr]
            continue
        w = r.word(k)
        if (r.head(k) is not None or w.startswith(("room_", "object_")) or w in lx.REFUSED_WORDS
                or r.phrase(k, lx.NEG_STARTS) or r.phrase(k, lx.CONDITION_WORDS) or r.phrase(k, lx.WHENEVER)
                or w in lx.LABEL_STOPS or not w.isalpha()):
            return None
        named = named or w in lx.LIST_NOUNS or w in lx.RELATIVE_FLOORS
        k += 1
    return named


def names_more(r: Reader, end: int) -> bool:
    """Whether a list's label says more than which list it is, its order and its floor (*Shopping list
    check*: said back as set aside), unlike *Tasks*, *To do*, *Any order is fine*."""
    k = 0
    while k < end:
        remark = r.phrase(k, lx.ANY_ORDER) or r.phrase(k, lx.ORDER_MODIFIERS)
        floor = floor_words(r, k)
        if remark or floor is not None:
            k += len(remark) if remark else floor.end - k  # type: ignore[union-attr]
            continue
        w = r.word(k)
        if not (w in lx.LIST_NOUNS or w in lx.FILLERS or w in lx.ANNOUNCING or w in lx.RELATIVE_FLOORS
                or w in (",", "is", "are", "fine", "these", "this")):
            return True
        k += 1
    return False


def order_said(r: Reader, start: int, end: int) -> Order | None:
    """The order a remark among the words ``[start, end)`` says: ``"ordered"`` (*in order*, *in this
    order*), ``"any"`` (*any order is fine*), or ``None``."""
    for k in range(start, end):
        if r.phrase(k, lx.ANY_ORDER):
            return "any"
        if r.phrase(k, lx.ORDER_MODIFIERS):
            return "ordered"
    return None


def only_order_remark(r: Reader) -> Order | None:
    """The order said by a sentence after a list that says nothing else (*The order doesn't matter.*, *In
    this order.*), else ``None``."""
    k = 0
    while k < len(r):
        remark = r.phrase(k, lx.ANY_ORDER) or r.phrase(k, lx.ORDER_MODIFIERS)
        if remark:
            k += len(remark)
        elif r.word(k) in lx.FILLERS or r.word(k) in lx.ORDER_FILLERS:
            k += 1
        else:
            return None
    return order_said(r, 0, len(r))


def floor_scope(r: Reader, start: int, end: int) -> tuple[Tok, ...]:
    """The words of the floor a heading puts its items on (*Top floor tasks*, *Upstairs run*), as an
    opening of each item (*on the top floor, ...*; *while you're upstairs, ...*: the heading names where the
    items are, so said on the top floor, *upstairs* is that floor), or nothing."""
    for k in range(start, end):
        if r.word(k) in lx.RELATIVE_FLOORS:
            at, end_at = r.toks[k].start, r.toks[k].end
            return (*(Tok(w, at, at) for w in ("while", "you", "are")), r.toks[k], Tok(",", end_at, end_at))
        found = floor_words(r, k)
        if found is not None:
            on = Tok("on", r.toks[k].start, r.toks[k].start)
            return on, *r.toks[k:found.end], Tok(",", r.toks[found.end - 1].end, r.toks[found.end - 1].end)
    return ()
