"""The sweep report: ``report.md`` (the paper's tables beside ours, excluded cases, checks) and the two
figures under ``figures/``, written into a results folder."""

from __future__ import annotations

from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sgplan.bench import figures, findings, tables
from sgplan.bench.cases import BenchError, exact_number
from sgplan.bench.results import ResultStore, counts, load_rows, load_sweeps
from sgplan.english import count
from sgplan.files import write_text_atomically

REPORT_FILE = "report.md"
FIGURES_DIR = "figures"


@dataclass
class Report:
    """Files written by :func:`write_report`: the Markdown report, figure files, and the tables' text."""

    markdown: Path
    figures: list[Path] = field(default_factory=list)
    table2: str = ""
    table3: str = ""


Condition = tuple[str, str, float | None]
"""What makes numbers comparable: (semantics profile, reach model, search time limit in seconds or
``None``)."""


def condition_of(row: dict[str, Any]) -> Condition:
    # Rows made before there was a choice of reach model used the authors' window.
    return (row["profile"], row.get("reach_model") or "box", row.get("time_limit_s"))


def _describe(condition: Condition) -> str:
    profile, reach_model, limit = condition
    return f"profile {profile}, reach model {reach_model}, " + (
        "no time limit" if limit is None else f"time limit {exact_number(limit)} s"
    )


def choose_condition(rows: Sequence[dict[str, Any]], profile: str | None = None,
                     time_limit_s: float | None = None, reach_model: str | None = None) -> Condition:
    """The condition of the newest row among those with the given ``profile``, ``time_limit_s`` and
    ``reach_model`` (``None``: any).

    Raises
    ------
    BenchError
        no row matches.
    """
    matching = [r for r in rows if (profile is None or r["profile"] == profile)
                and (time_limit_s is None or r.get("time_limit_s") == time_limit_s)
                and (reach_model is None or condition_of(r)[1] == reach_model)]
    if not matching:
        recorded = sorted({_describe(condition_of(r)) for r in rows})
        parts = ([f"profile {profile}"] if profile else []) + (
            [f"reach model {reach_model}"] if reach_model else []) + (
            [] if time_limit_s is None else [f"time limit {exact_number(time_limit_s)} s"])
        wanted = ", ".join(parts)
        raise BenchError(f"no results with {wanted}; recorded: {'; '.join(recorded) or 'none'}")
    return condition_of(max(matching, key=lambda r: r.get("finished_at") or ""))


def write_report(folder: str | Path, rows: Sequence[dict[str, Any]] | None = None, *,
                 condition: Condition | None = None) -> Report:
    """Write ``report.md`` and the figures into ``folder`` from its ``results.jsonl`` (or ``rows``), and
    refresh ``results.csv`` / ``results.json``. The sweep calls of ``sweeps.jsonl`` are listed with their
    wall time.

    Tables and figures cover one ``condition`` (default: the newest row's, :func:`choose_condition`), so
    that means never mix semantics profiles, reach models or time limits; rows of other conditions are
    counted in a note. Every sentence that states a finding (what the comparison with the paper shows, which
    paths break the mission as written) is computed from these rows (:mod:`sgplan.bench.findings`).

    Raises
    ------
    BenchError
        the folder holds no results, or none under ``condition``.
    """
    out = Path(folder).expanduser()
    if rows is None:
        rows = load_rows(out)
        ResultStore(out).export()
    if not rows:
        raise BenchError(f"no results to report in {out}")
    condition = condition or choose_condition(rows)
    others = Counter(_describe(condition_of(r)) for r in rows if condition_of(r) != condition)
    rows = [r for r in rows if condition_of(r) == condition]
    if not rows:
        raise BenchError(f"no results under {_describe(condition)} in {out}; recorded: {', '.join(others)}")
    report = Report(markdown=out / REPORT_FILE)
    case = tables.table2_case(rows)
    if case is not None:
        report.table2 = tables.table2(rows, *case)
    report.table3 = tables.table3(rows)
    report.figures = _figures(rows, case, out / FIGURES_DIR)
    text = (_head(rows, condition, others, load_sweeps(out)) + findings.timing_section(rows)
            + findings.comparison_section(rows, case) + findings.semantics_section(rows)
            + _tables(rows, case, report) + _figure_links(report.figures, out))
    try:
        write_text_atomically(report.markdown, "\n".join(text))
    except OSError as error:
        raise BenchError(f"cannot write the report ({error.strerror or error})", report.markdown) from None
    return report


def _figures(rows: Sequence[dict[str, Any]], case: tuple[str, str] | None, fig_dir: Path) -> list[Path]:
    if case is None:
        return []
    scene, mission = case
    written = figures.cost_vs_time(rows, scene, mission, fig_dir)
    start = figures.default_expansion_case(rows, scene, mission)
    if start is not None:
        written += figures.expansions_per_iteration(rows, scene, mission, start, fig_dir)
    return written


def _head(rows: Sequence[dict[str, Any]], condition: Condition, others: Counter[str],
          sweeps: Sequence[dict[str, Any]]) -> list[str]:
    status_counts = ", ".join(f"{n} {s}" for s, n in sorted(counts(rows).items()))
    text = ["# sgplan benchmark report", "",
            f"{count(len(rows), 'case')} ({status_counts}); {_describe(condition)}."]
    if others:
        text += [
            "",
            "Not in this report (other conditions; choose with `sgplan bench report --profile P "
            "--reach-model R --time-limit S`): "
            + "; ".join(f"{count(n, 'case')} under {c}" for c, n in sorted(others.items())) + ".",
        ]
    if sweeps:
        text += ["", "Sweep calls (whole `sgplan bench` run, wall clock):", ""]
        text += [f"- {s['finished_at']}: {count(s['ran'], 'case')} run, {s['skipped']} already recorded, "
                 f"{s['wall_s']:.0f} s wall ({s['executor']} executor, "
                 f"{count(s['jobs'], 'job') if isinstance(s['jobs'], int) else s['jobs']})"
                 + (", interrupted" if s.get("interrupted") else "") for s in sweeps]
    return [*text, ""]


def _tables(rows: Sequence[dict[str, Any]], case: tuple[str, str] | None, report: Report) -> list[str]:
    text = []
    if case is not None:
        text += [f"## Table II - {case[0]} mission {case[1]}, per setup (mean over starts)", "",
                 report.table2, ""]
    compared, disagreements = tables.cost_disagreements(rows)
    text += [
        "## Table III - per scene: 1st iter. time (s) / 1st cost ÷ opt. cost / opt. time (s), mean over "
        "missions x starts",
        "",
        report.table3,
        "",
        "## Loading, precomputation, wall time and memory",
        "",
        tables.resources_table(rows),
        "",
        "## Excluded cases (not in the means)",
        "",
        tables.excluded_table(rows),
        "",
        "## Cross-check of optimal costs",
        "",
        (
            f"All setups found the same optimal cost in each of the {compared} (scene, mission, start) "
            "groups run with more than one setup."
            if not disagreements
            else f"{len(disagreements)} of {compared} groups disagree:\n\n"
            + "\n".join(f"- {d}" for d in disagreements)
        ),
        "",
    ]
    return text


def _figure_links(written: Sequence[Path], out: Path) -> list[str]:
    if not written:
        return []
    return ["## Figures", "", *(f"![{p.stem}]({p.relative_to(out).as_posix()})" for p in written
                                if p.suffix == ".png"), ""]
