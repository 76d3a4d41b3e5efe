"""The numbers the paper reports (Dai et al., ICRA 2024; copied in reference-algorithm.md §7.3).

Each entry is (first-solution search time in s, first cost / optimal cost, search time to the optimum in
s), averaged over the cases of the table. The paper's times exclude loading and precomputation.
"""

from __future__ import annotations

PaperCell = tuple[float, float, float]

TABLE2: dict[str, PaperCell] = {
    "ALL": (0.0007, 1.3763, 8.9062),
    "OCC": (0.0244, 1.0827, 8.3144),
    "OBJ": (3.7460, 1.0387, 24.936),
    "ROOM": (3.6878, 1.0306, 13.1352),
    "FLR": (3.8106, 1.0369, 13.3287),
    "NO-LLM": (3.3260, 1.0318, 24.2516),
    "A*": (1.1202, 1.0997, 11.7594),
}
"""Table II: Benevolence mission 1, mean over its 5 starts, per setup."""

TABLE3: dict[tuple[str, str], PaperCell] = {
    ("Allensville", "ALL"): (0.24, 1.69, 3.50),
    ("Benevolence", "ALL"): (0.32, 1.24, 11.82),
    ("Collierville", "ALL"): (0.009, 1.26, 5.48),
    ("Allensville", "NO-LLM"): (0.36, 1.34, 6.33),
    ("Benevolence", "NO-LLM"): (2.82, 1.18, 21.57),
    ("Collierville", "NO-LLM"): (1.16, 1.38, 8.13),
    ("Allensville", "A*"): (0.15, 1.08, 3.23),
    ("Benevolence", "A*"): (1.33, 1.16, 14.22),
    ("Collierville", "A*"): (1.19, 1.06, 7.04),
}
"""Table III: per (scene, setup), mean over 5 missions x 5 starts."""
