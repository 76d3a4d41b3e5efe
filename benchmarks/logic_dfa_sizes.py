"""DFA sizes and construction times: the 15 shipped missions, goal-count scaling, "stay on this floor"
with many rooms, largest random formulas.

Usage: ``python benchmarks/logic_dfa_sizes.py [--random N] [--seed S]``. Times are the best of 5 runs
(milliseconds, single thread). "pruned" builds with every mission's enter(room) propositions mutually
exclusive (one room at a time), read from ap_desc.yaml.
"""

from __future__ import annotations

import argparse
import random
import time
from functools import partial
from pathlib import Path

import yaml

from sgplan.datasets import SCENES, find_gibson_root
from sgplan.errors import AutomatonError
from sgplan.logic import Atom, Formula, ltlf_to_dfa, parse_infix, parse_prefix, read_hoa
from sgplan.logic.formula import Always, And, Equiv, Eventually, Implies, Next, Not, Or, Release, Until


def best_ms(build, repeat: int = 5) -> tuple[object, float]:
    best, result = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        result = build()
        best = min(best, time.perf_counter() - start)
    return result, best * 1e3


def missions(root: Path) -> None:
    print("| mission | APs | states | ms | states (rooms exclusive) | ms | Spot states (+sink) |")
    print("|---|---|---|---|---|---|---|")
    for scene in SCENES:
        for k in range(1, 6):
            folder = root / scene / "missions" / str(k)
            formula = parse_prefix((folder / "Spot_LTL_formula.txt").read_text())
            desc = yaml.safe_load((folder / "ap_desc.yaml").read_text())
            rooms = [name for name, d in desc.items() if d["type"] == "kEnterRoom"]
            dfa, ms = best_ms(partial(ltlf_to_dfa, formula))
            pruned, ms_pruned = best_ms(partial(ltlf_to_dfa, formula, exclusive=[rooms]))
            spot = read_hoa(folder / "automaton.aut")
            print(f"| {scene} {k} | {len(dfa.aps)} | {dfa.num_states} | {ms:.1f} | {pruned.num_states} | "
                  f"{ms_pruned:.1f} | {spot.num_states} |")


def scaling() -> None:
    print("\n| family | k | states | labels | ms |")
    print("|---|---|---|---|---|")
    for k in (4, 6, 8, 9, 10, 12):
        families = {
            "unordered F p1 & ... & F pk": parse_infix(" & ".join(f"F p{i}" for i in range(k))),
            "ordered F(p1 & F(p2 & ...))": parse_infix(
                "F(" + " & F(".join(f"p{i}" for i in range(k)) + ")" * k
            ),
        }
        for family, formula in families.items():
            start = time.perf_counter()
            try:
                dfa = ltlf_to_dfa(formula)
            except AutomatonError as exc:
                ms = (time.perf_counter() - start) * 1e3
                size = str(exc).split(" would need ")[1].split(", more than")[0]
                print(f"| {family} | {k} | refused after {ms:.0f} ms: {size} | | |")
                continue
            ms = (time.perf_counter() - start) * 1e3
            print(f"| {family} | {k} | {dfa.num_states} | {dfa.num_labels} | {ms:.1f} |")


_UNARY = (Not, Next, Eventually, Always)
_BINARY = (Implies, Equiv, Until, Release)


def random_formula(rng: random.Random, aps: tuple[str, ...], depth: int) -> Formula:
    if depth == 0 or rng.random() < 0.2:
        return Atom(rng.choice(aps))
    kind = rng.random()
    if kind < 0.4:
        return rng.choice(_UNARY)(random_formula(rng, aps, depth - 1))
    left, right = random_formula(rng, aps, depth - 1), random_formula(rng, aps, depth - 1)
    if kind < 0.7:
        return (And if rng.random() < 0.5 else Or)((left, right))
    return rng.choice(_BINARY)(left, right)


def largest_random(count: int, seed: int) -> None:
    rng = random.Random(seed)
    aps = tuple(f"p{i}" for i in range(6))
    rows = []
    start = time.perf_counter()
    for _ in range(count):
        formula = random_formula(rng, aps, depth=6)
        dfa, ms = best_ms(partial(ltlf_to_dfa, formula), repeat=1)
        rows.append((dfa.num_states, ms, len(dfa.aps), formula))
    total = time.perf_counter() - start
    rows.sort(key=lambda r: (-r[0], -r[1]))
    print(f"\n{count} random formulas (depth <= 6, <= 6 APs) built in {total:.1f} s; "
          f"slowest {max(r[1] for r in rows):.1f} ms. Largest:")
    print("| states | APs | ms | formula |")
    print("|---|---|---|---|")
    for states, ms, num_aps, formula in rows[:5]:
        text = str(formula)
        print(f"| {states} | {num_aps} | {ms:.1f} | `{text[:90]}{'...' if len(text) > 90 else ''}` |")


def stay_on_floor(other_rooms: int = 11) -> None:
    """'Stay on this floor' in a three-floor building forbids every room of the other floors (11 in
    Benevolence seen from floor 0): many propositions, of which few labels are possible (one room at a
    time)."""
    print(f"\n| stay on one floor ({other_rooms} rooms forbidden) + ordered goals | APs | states | labels "
          "| ms |")
    print("|---|---|---|---|---|")
    rooms = [f"room_{i}" for i in range(other_rooms)]
    for goals in range(1, 8):
        names = [f"g{i}" for i in range(goals)]
        sequence = names[-1]
        for name in reversed(names[:-1]):
            sequence = f"{name} & F({sequence})"
        formula = parse_infix(f"F({sequence}) & G !({' | '.join(rooms)})")
        dfa, ms = best_ms(partial(ltlf_to_dfa, formula, aps=[*names, *rooms], exclusive=[rooms]))
        print(f"| {goals} | {len(names) + other_rooms} | {dfa.num_states} | {dfa.num_labels:,} | {ms:.1f} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--random", type=int, default=300, help="number of random formulas")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    root = find_gibson_root()
    if root is None:
        print("Gibson data not found: skipping the mission table (set SGPLAN_GIBSON_DIR)")
    else:
        missions(root)
    scaling()
    stay_on_floor()
    largest_random(args.random, args.seed)


if __name__ == "__main__":
    main()
