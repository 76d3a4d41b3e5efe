"""Logic: LTL syntax, checks, LTLf -> DFA, HOA, automaton utilities, equivalence.

Semantics and formats: docs/logic.md. Typical use::

    from sgplan.logic import parse_tokens, ltlf_to_dfa, remaining_mission
    formula = parse_tokens(['AND', 'EVENTUALLY', 'enter(room_2)', 'ALWAYS', 'NOT', 'enter(room_3)'],
                           known={"room_2", "room_3"})
    dfa = ltlf_to_dfa(formula, exclusive=[["enter(room_2)", "enter(room_3)"]])
"""

from sgplan.logic.automaton import Automaton
from sgplan.logic.checks import formula_warnings, is_cosafe, non_cosafe_parts
from sgplan.logic.dot import to_dot
from sgplan.logic.equivalence import (
    compact_difference_word,
    difference_word,
    equivalent,
    included,
    inclusion_counterexample,
)
from sgplan.logic.formula import (
    FALSE,
    TRUE,
    Always,
    And,
    Atom,
    Const,
    Equiv,
    Eventually,
    Formula,
    Implies,
    Next,
    Not,
    Or,
    Release,
    Until,
    WeakNext,
    atoms,
    to_infix,
)
from sgplan.logic.hoa import parse_hoa, read_hoa, write_hoa
from sgplan.logic.infix import parse_infix
from sgplan.logic.ltlf import (
    DEFAULT_MAX_ENTRIES,
    CompactDfa,
    ltlf_to_compact_dfa,
    ltlf_to_dfa,
    possible_labels,
)
from sgplan.logic.minimize import minimize, product
from sgplan.logic.normal import nnf
from sgplan.logic.paths import (
    AutomatonPath,
    MissionStep,
    RemainingMission,
    distances_to_accept,
    remaining_mission,
    shortest_path,
)
from sgplan.logic.prefix import parse_prefix, to_prefix
from sgplan.logic.progression import progress
from sgplan.logic.tokens import number_aps, parse_tokens, to_tokens

__all__ = [
    "Automaton", "AutomatonPath", "CompactDfa", "MissionStep", "RemainingMission", "DEFAULT_MAX_ENTRIES",
    "Formula", "Const", "TRUE", "FALSE", "Atom", "Not", "And", "Or", "Implies", "Equiv", "Next",
    "WeakNext", "Eventually", "Always", "Until", "Release", "atoms", "nnf",
    "parse_infix", "to_infix", "parse_prefix", "to_prefix", "parse_tokens", "to_tokens", "number_aps",
    "is_cosafe", "non_cosafe_parts", "formula_warnings",
    "ltlf_to_dfa", "ltlf_to_compact_dfa", "possible_labels", "minimize", "product", "progress",
    "parse_hoa", "read_hoa", "write_hoa", "to_dot",
    "distances_to_accept", "shortest_path", "remaining_mission",
    "equivalent", "included", "difference_word", "compact_difference_word", "inclusion_counterexample",
]
