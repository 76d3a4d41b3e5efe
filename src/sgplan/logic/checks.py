"""Fragment checks and warnings about finite-trace meanings that surprise users.

Syntactic co-safety: in negation normal form the formula uses only ``X``, ``F`` and ``U`` as temporal
operators (no ``G``, ``R`` or weak next). Every co-safe formula is decided by a finite prefix, so the
planner may stop as soon as it is satisfied. sgplan's finite-trace semantics also gives ``G``/``R`` a
useful meaning (``G !p``: p is false at every cell of the path), so a non-co-safe formula is reported,
not refused; callers decide.
"""

from __future__ import annotations

from sgplan.logic.formula import (
    Always,
    Equiv,
    Formula,
    Implies,
    Next,
    Or,
    Release,
    WeakNext,
    conjuncts,
    is_temporal,
    to_infix,
    walk,
)
from sgplan.logic.normal import nnf


def non_cosafe_parts(formula: Formula) -> list[Formula]:
    """The outermost sub-formulas of ``nnf(formula)`` rooted at ``G``, ``R`` or weak next.

    Empty iff ``formula`` is syntactically co-safe.
    """
    found: list[Formula] = []
    stack = [nnf(formula)]
    while stack:
        node = stack.pop()
        if isinstance(node, (Always, Release, WeakNext)):
            found.append(node)
        else:
            stack.extend(reversed(node.children()))
    return found


def is_cosafe(formula: Formula) -> bool:
    """Whether ``formula`` is syntactically co-safe (NNF with only X, F, U)."""
    return not non_cosafe_parts(formula)


def formula_warnings(formula: Formula) -> list[str]:
    """Plain-language warnings about parts of ``formula`` whose finite-path meaning may surprise.

    - A top-level conjunct without any temporal operator only constrains the first cell of the path.
    - A non-temporal operand of a top-level ``->``, ``<->`` or ``|`` is read at the first cell only.
    - ``X`` is the strong next: ``X f`` is false at the last cell, and consecutive cells of a grid path
      are a few centimetres apart, so ``X`` rarely expresses "afterwards" (use ``F``).
    """
    warnings: list[str] = []
    for part in conjuncts(formula):
        if not is_temporal(part):
            warnings.append(
                f"'{to_infix(part)}' has no temporal operator, so it only constrains the first cell of "
                f"the path"
            )
        elif isinstance(part, (Implies, Equiv, Or)):
            for operand in part.children():
                if not is_temporal(operand):
                    warnings.append(
                        f"'{to_infix(operand)}' in '{to_infix(part)}' has no temporal operator, so it is "
                        f"read at the first cell of the path only"
                    )
    if any(isinstance(node, Next) for node in walk(formula)):
        warnings.append(
            "X (NEXT) refers to the very next grid cell and is false at the last cell of a path; "
            "use F (EVENTUALLY) for 'afterwards'"
        )
    return warnings
