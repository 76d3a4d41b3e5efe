"""Sets of labels as Boolean expressions (sum of cubes), for HOA edge labels and drawings.

A set of labels over ``n`` propositions is a ``(2**n,)`` bool array. A cube is a pair
``(care, value)`` of bitmasks: the labels ``l`` with ``l & care == value``.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

Cube = tuple[int, int]


def label_cover(members: np.ndarray) -> list[Cube]:
    """Cubes whose union is exactly the set ``members`` (Shannon expansion, shared cubes merged).

    ``[]`` for the empty set, ``[(0, 0)]`` (the cube "true") for the full set.
    """
    members = np.asarray(members, dtype=bool)
    n = int(members.size).bit_length() - 1
    if members.size != 1 << n:
        raise ValueError(f"label set of size {members.size} is not a power of two")
    return _cover(members, n)


def _cover(members: np.ndarray, n: int) -> list[Cube]:
    if members.all():
        return [(0, 0)]
    if not members.any():
        return []
    half = members.size // 2
    bit = 1 << (n - 1)  # the top proposition splits the array in halves (false, true)
    low, high = _cover(members[:half], n - 1), _cover(members[half:], n - 1)
    common = set(low) & set(high)
    cubes = [c for c in low if c in common]
    cubes += [(care | bit, value) for care, value in low if (care, value) not in common]
    cubes += [(care | bit, value | bit) for care, value in high if (care, value) not in common]
    return cubes


def format_cover(cubes: Sequence[Cube], names: Sequence[str], negate: str = "!", conj: str = "&",
                 disj: str = " | ", true: str = "t", false: str = "f") -> str:
    """The expression of a cover, e.g. ``"0&!1 | 2"`` with ``names = ["0", "1", "2"]``.

    Literals appear in proposition order; an empty cover prints ``false``, the full cube ``true``.
    """
    if not cubes:
        return false
    terms = []
    for care, value in cubes:
        literals = [("" if value >> i & 1 else negate) + name
                    for i, name in enumerate(names) if care >> i & 1]
        terms.append(conj.join(literals) if literals else true)
    return disj.join(terms)
