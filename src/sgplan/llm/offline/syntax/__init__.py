"""The syntax of the offline translator: mission text -> sentences -> typed syntax trees, no scene lookups.

The grammar is a set of small named rules (:class:`.rules.RuleSet`), each reading one construct from a
position of a sentence and returning a node, ``None`` (not here) or a refusal (:mod:`.reader`); the
nodes are the dataclasses of :mod:`.tree`. The only thing the syntax knows of the scene is its head nouns
(:class:`~sgplan.llm.offline.nouns.NounLexicon`), which tell a noun from a verb.

Why not a parsing library: a grammar in Lark with explicit ambiguity was considered and not used. The
language here is lexical more than structural (hundreds of fixed phrases: *in whichever order you like*,
*make sure that you*, *at no point*), read longest-first with an order of precedence between rules, which a
context-free grammar expresses as large alternations with its ambiguity resolved afterwards; the scene
supplies the nouns, so the grammar would have to be rebuilt per scene; and a refusal must name the words
that could not be read, which a PEG-style reader of ordered rules gives directly. The few real attachment
ambiguities (*the bedroom without a plant*) are explicit in the tree instead (:class:`.tree.Attachment`)
and decided against the scene by the caller of :func:`parse_sentence`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

from sgplan.llm.offline import lexicon as lx
from sgplan.llm.offline.nouns import NounLexicon
from sgplan.llm.offline.spelling import Spelling
from sgplan.llm.offline.syntax.any_time import any_time_goal
from sgplan.llm.offline.syntax.brackets import bracketed_remarks, bracketed_rooms
from sgplan.llm.offline.syntax.contents import contents_aside
from sgplan.llm.offline.syntax.context import (
    mentions,
    run_on_statements,
    set_aside_context,
    statement,
    timed_heading,
)
from sgplan.llm.offline.syntax.corrections import corrected, joined_appositions
from sgplan.llm.offline.syntax.fine_choice import fine_choice, remark_after_closing, remark_commas
from sgplan.llm.offline.syntax.floor_goal import floor_goal_last
from sgplan.llm.offline.syntax.floor_only import floor_only
from sgplan.llm.offline.syntax.fragments import context_fragment
from sgplan.llm.offline.syntax.fronted import fronted_prohibition
from sgplan.llm.offline.syntax.lists import read_lists
from sgplan.llm.offline.syntax.needs import need_as_order
from sgplan.llm.offline.syntax.not_needed import split_not_needed
from sgplan.llm.offline.syntax.object_first import object_first
from sgplan.llm.offline.syntax.only_clause import only_clause
from sgplan.llm.offline.syntax.preamble import is_chitchat, leading_clause, stated_start
from sgplan.llm.offline.syntax.reader import Match, Parse, Reader, Refusal
from sgplan.llm.offline.syntax.remark_sentences import join_remarks
from sgplan.llm.offline.syntax.reordered import reordered
from sgplan.llm.offline.syntax.sentences import mission_sentence
from sgplan.llm.offline.syntax.tree import Attachment, Sentence, SetAside, nodes
from sgplan.llm.offline.syntax.visit_rule import each_visit_rule
from sgplan.llm.offline.syntax.wanted_done import wanted_done
from sgplan.llm.offline.text import rewrite, sentences, tokenize

__all__ = ["Match", "Reader", "Refusal", "parse_sentence", "split_mission"]


def split_mission(text: str, nouns: NounLexicon, spelling: Spelling | None = None) -> list[Reader]:
    """The sentences of ``text`` to parse, its lists and what a colon announced read with them
    (:mod:`.lists`), its context set aside (:mod:`.context`), and its leading chit-chat set aside (said back,
    never read): sentences before the first one with content (*Hi!*), and the chit-chat clause before the
    first comma of that one (*Okay, go ...*). Sentences that say where the robot is (*I'm downstairs right
    now.*) and those set aside are kept wherever they are."""
    tokens = [t for t in rewrite(tokenize(text), lx.PHRASE_ALIASES) if t.text not in lx.SOUNDS]
    out: list[Reader] = []
    content = False
    parts = sentences(tokens)
    spelling = spelling or Spelling(nouns)
    readers = [Reader(p.toks, text, nouns, marker=p.marker, new_line=p.new_line, spelling=spelling)
               for p in parts]
    readers = [floor_only(r) for r in readers]  # "this flr only": "stay on this flr"
    readers = floor_goal_last(readers)  # "check the fridge, then go upstairs": "... go to the floor above"
    readers = [fronted_prohibition(r) for r in readers]  # "Kitchen never go.": "never enter kitchen"
    readers = [bracketed_rooms(r) for r in readers]  # "bowl (LR)": "bowl in LR"
    readers = [said for r in readers for said in bracketed_remarks(r)]  # "(it's the cough syrup)": said back
    readers = [said for r in readers for said in contents_aside(r)]  # "a bottle of water": the bottle
    readers = [run_on_statements(r) for r in readers]  # "... at all the floor is wet": ", the floor is wet"
    readers = [each_visit_rule(r) for r in readers]  # "each kit visit -> DR after": "whenever you visit kit"
    readers = [remark_commas(r) for r in readers]  # "an apple any apple is fine then": ", any apple is fine,"
    readers = [fine_choice(r) for r in readers]  # "then either bedroom is fine": then either bedroom
    readers = [remark_after_closing(r) for r in readers]  # "chk tv after (either)": "chk tv (either) after"
    readers = [said for r in readers for said in only_clause(r)]  # ", and only go to X after Y": its own
    readers = [said for r in readers for said in wanted_done(r)]  # "I need the kitchen sorted": the kitchen
    readers = [said for r in readers for said in any_time_goal(r)]  # "whenever X, Y, and at some point Z"
    readers = [said for r in readers for said in timed_heading(r)]  # "A couple of things before dinner:"
    for r in joined_appositions(reordered(read_lists(_greeting_before_heading(readers)))):
        if stated_start(r) is not None or r.aside:
            out.append(r)
            continue
        r = object_first(r)  # "Garage chair first sit": "sit on garage chair first" (not a list's heading)
        if context_fragment(r, opener=not content):
            out.append(replace(r, aside=True))  # "Time for the evening round.": said back
            continue
        if not content:
            if is_chitchat(r, 0, len(r)) and statement(r, 0, len(r)) is None:
                out.append(replace(r, aside=True))  # "Hi!", "Okay, here's the plan.": said back
                continue
            cut = leading_clause(r)
            if cut and statement(r, 0, cut - 1) is None:
                out.append(replace(r, toks=r.toks[:cut - 1], aside=True))  # "Okay, go to ...": "Okay"
                r = replace(r, toks=r.toks[cut:])  # ("I'm hungry, ..." is said back as a statement)
            content = True
        out += corrected(r, out)  # "go to the kitchen, no wait, the dining room": the dining room
    # "The bathroom needs a check.": the check, when no order after it names the bathroom (else a reason)
    said = set_aside_context(out)
    return join_remarks(split_not_needed([need_as_order(r, said[k + 1:]) for k, r in enumerate(said)]))


def _greeting_before_heading(readers: list[Reader]) -> list[Reader]:
    """The mission's first heading (a sentence ending with a colon), when it opens with chit-chat (*Hey
    buddy - dining room: ...*, *Hi, kitchen: ...*): the chit-chat set aside first, so that the rest is read
    as the heading it is."""
    out: list[Reader] = []
    for k, r in enumerate(readers):
        if r.aside or not r.words or r.words[-1] != ":":
            out.append(r)
            continue
        cut = next((j for j, w in enumerate(r.words) if w in (",", "\u2014")), 0)
        if cut and is_chitchat(r, 0, cut) and statement(r, 0, cut) is None:
            out += [replace(r, toks=r.toks[:cut], aside=True), replace(r, toks=r.toks[cut + 1:])]
        else:
            out.append(r)
        out += readers[k + 1:]
        break
    return out


def parse_sentence(r: Reader, decide: Callable[[Attachment], bool]) -> Parse[Sentence]:
    """The syntax tree of one sentence, its attachments decided by ``decide`` (the scene's reading of
    each :class:`.tree.Attachment`, in text order): the sentence is read again with each decision until
    none is left open."""
    if r.aside:
        return Match(SetAside(r.quote(0, len(r)), mentions(r)), len(r))
    choices: dict[int, bool] = {}
    while True:
        start = stated_start(r)
        if start is not None:
            return Match(start, len(r))
        tree = mission_sentence(replace(r, choices=dict(choices)))
        if not isinstance(tree, Match):
            return tree
        open_ = next((a for a in nodes(tree.node, Attachment) if a.at not in choices), None)
        if open_ is None:
            return tree
        choices[open_.at] = decide(open_)

