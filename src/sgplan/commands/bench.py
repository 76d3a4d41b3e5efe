"""``sgplan bench``: sweep scenes x missions x starts x setups and report the paper's tables and figures.

``sgplan bench [run]`` runs (or resumes) a sweep into ``--out`` and writes the report at the end;
``sgplan bench report --out DIR`` rewrites the report from the results already in DIR.
"""

from __future__ import annotations

import argparse
import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

from sgplan.commands.common import (
    DEFAULT_PROFILE,
    add_profile_argument,
    add_reach_model_argument,
    positive_int,
    positive_seconds,
    say,
    split_list,
)
from sgplan.english import count
from sgplan.planning.setups import SETUPS

if TYPE_CHECKING:
    from sgplan.bench.cases import Case
    from sgplan.bench.results import ResultStore


class _HelpNamingTheCaseTimeout(argparse.HelpFormatter):
    """Help that names the ``--case-timeout`` default, read from :mod:`sgplan.bench.executors` only when
    the help is shown: importing the bench machinery to build the parser would cost every sgplan command
    (``plan`` included) its import time."""

    def _get_help_string(self, action: argparse.Action) -> str | None:
        if action.dest != "case_timeout":
            return action.help
        from sgplan.bench.executors import DEFAULT_CASE_TIMEOUT_S

        return f"{action.help} (default: {DEFAULT_CASE_TIMEOUT_S:g})"


def register(sub: argparse._SubParsersAction) -> None:
    from sgplan.datasets import ENV_VAR

    parser = sub.add_parser(
        "bench", formatter_class=_HelpNamingTheCaseTimeout,
        help="benchmark sweep with the paper's tables and figures (run, resume or report)",
        description="Run scenes x missions x starts x setups in worker processes apart from the sweep, and "
                    "write results (CSV, JSON), the paper's Tables II/III beside ours, and its two figures. "
                    "Without selection flags the sweep is the paper's. Re-running resumes.",
    )
    parser.add_argument("action", nargs="?", choices=("run", "report"), default="run",
                        help="run (default): run or resume the sweep, then report; report: report only")
    parser.add_argument(
        "--out", metavar="DIR", default="bench-out", help="results folder (default: bench-out)"
    )
    parser.add_argument(
        "--data", metavar="DIR",
        help=f"data folder of <scene>/missions/<m>/ (default: ${ENV_VAR}, "
        "else ../shared/datasets/gibson-3dsg)",
    )
    parser.add_argument("--scenes", nargs="+", metavar="NAME",
                        help="scenes, any case, space- or comma-separated (default: all in the data folder)")
    parser.add_argument("--missions", nargs="+", metavar="NAME", help="mission folder names (default: all)")
    parser.add_argument(
        "--starts", metavar="LIST", help="initial-position indices, e.g. 0,2-4 (default: all)"
    )
    parser.add_argument("--setups", nargs="+", metavar="NAME",
                        help=f"planner setups among {', '.join(SETUPS)}, any case "
                        "(default: ALL NO-LLM A*)")
    add_profile_argument(
        parser,
        default=None,
        extra_help=f"; recorded in every row (run: default {DEFAULT_PROFILE}, as for plan; the "
        "paper's tables were made with authors). With report: the rows to report "
        "(default: the newest row's profile)",
    )
    add_reach_model_argument(parser, extra_help="; recorded in every row. With report: the rows to report "
                             "(default: the newest row's among those of --profile)")
    parser.add_argument(
        "--time-limit",
        type=positive_seconds,
        metavar="S",
        help="search time budget per case (seconds). With report: the rows to report (default: the newest "
        "row's time limit among those of --profile)",
    )
    parser.add_argument(
        "--case-timeout", type=positive_seconds, metavar="S",
        help="kill a case's worker after S wall seconds",  # its default: see _HelpNamingTheCaseTimeout
    )
    parser.add_argument("--jobs", "-j", type=positive_int, metavar="N",
                        help=f"cases run at once (default: the number of cores, {os.cpu_count()})")
    parser.add_argument("--executor", choices=("local", "ray"), default="local",
                        help="local process pool (default) or Ray (pip install 'sgplan[ray]')")
    parser.add_argument("--address", metavar="ADDR", help="Ray cluster address (default: start a local Ray)")
    parser.add_argument(
        "--fresh-workers", action="store_true",
        help="local executor: a fresh worker process per case (each case's peak memory is then its own "
        "process's; slower) instead of one long-lived worker per job",
    )
    parser.add_argument(
        "--gallery", action="store_true", help="draw each case's path, one PNG per floor, under OUT/gallery"
    )
    parser.add_argument(
        "--retry", action="store_true", help="also re-run cases recorded as error, crashed or wall-timeout"
    )
    parser.add_argument("--no-report", action="store_true", help="do not write the report after the sweep")
    # SIGTERM and SIGHUP stop a sweep like Ctrl-C: its workers are stopped and its results exported.
    parser.set_defaults(run=run, termination_as_interrupt=True)


def run(args: argparse.Namespace) -> int:
    if args.action == "report":
        from sgplan.bench.report import choose_condition
        from sgplan.bench.results import load_rows

        _print_report(args.out, choose_condition(load_rows(args.out), args.profile, args.time_limit,
                                                 args.reach_model))
        return 0
    return _sweep(args)


def _cases(args: argparse.Namespace) -> list[Case]:
    from sgplan.bench.cases import Grid, discover, expand, paper_grids, parse_selection
    from sgplan.datasets import SCENES, find_gibson_root
    from sgplan.errors import SceneError

    root = find_gibson_root(args.data)
    if root is None:
        raise SceneError(
            f"cannot find the data folder: give --data DIR (a folder like ../shared/datasets/gibson-3dsg "
            f"holding {', '.join(SCENES)})"
        )
    names, missions, setups = split_list(args.scenes), split_list(args.missions), split_list(args.setups)
    scenes = discover(root, _scene_folders(root, names))
    selected = any(v is not None for v in (names, missions, args.starts, setups))
    if selected:
        grids = [Grid(missions=tuple(missions) if missions else None,
                      starts=parse_selection(args.starts) if args.starts else None,
                      **({"setups": tuple(setups)} if setups else {}))]
    else:
        grids = paper_grids(s.name for s in scenes)
    say(f"data: {root}")
    return expand(scenes, grids, profile=args.profile or DEFAULT_PROFILE, time_limit_s=args.time_limit,
                  reach_model=args.reach_model)


def _scene_folders(root: Path, names: list[str] | None) -> list[str] | None:
    """The folder names under ``root`` of scenes named in any case (``collierville`` -> ``Collierville``);
    unknown names are kept as given, for :func:`~sgplan.bench.cases.discover` to refuse."""
    if names is None:
        return None
    folders = {p.name.lower(): p.name for p in root.iterdir() if p.is_dir()}
    return [folders.get(name.lower(), name) for name in names]


def _sweep(args: argparse.Namespace) -> int:
    from sgplan.bench.results import ResultStore, make_folder, writing_lock
    from sgplan.runtime.jit import announce_compile

    cases = _cases(args)
    announce_compile()  # the workers compile on first use; said once here rather than by each of them
    with writing_lock(make_folder(args.out)):
        store = ResultStore(args.out)
        executor, summary, (csv_path, json_path) = _run_with_progress(args, cases, store)
    jobs = count(executor.jobs, "job") if executor.jobs else "cluster"
    recorded = f"{summary.skipped} {'was' if summary.skipped == 1 else 'were'} already recorded"
    say(f"ran {count(summary.ran, 'case')} in {summary.wall_s:.1f} s wall ({executor.name}, {jobs}); "
        f"{recorded}; results: {csv_path}, {json_path}")
    if not args.no_report:
        _print_report(args.out, (cases[0].profile, cases[0].effective_reach_model, args.time_limit))
    return 0


def _run_with_progress(
    args: argparse.Namespace, cases: list[Case], store: ResultStore
) -> tuple[Any, Any, Any]:
    """Run the sweep with a progress bar; returns (executor, sweep summary, exported file paths)."""
    from rich.console import Console
    from rich.markup import escape
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    from sgplan.bench.executors import DEFAULT_CASE_TIMEOUT_S, LocalExecutor, RayExecutor
    from sgplan.bench.results import FAILED, record_sweep
    from sgplan.bench.sweep import SweepInterrupted, run_sweep

    gallery = str(store.folder.resolve() / "gallery") if args.gallery else None
    timeout_s: float = DEFAULT_CASE_TIMEOUT_S if args.case_timeout is None else args.case_timeout
    options: dict[str, Any] = {"timeout_s": timeout_s, "gallery_dir": gallery}
    executor = (RayExecutor(args.jobs, address=args.address, **options) if args.executor == "ray"
                else LocalExecutor(args.jobs, reuse_workers=not args.fresh_workers, **options))
    console = Console(stderr=True)
    statuses: dict[str, int] = {}
    with Progress(TextColumn("[bold]bench"), BarColumn(), MofNCompleteColumn(), TimeElapsedColumn(),
                  TextColumn("ETA"), TimeRemainingColumn(), TextColumn("{task.fields[statuses]}"),
                  console=console, transient=False, disable=args.quiet) as progress:
        task = progress.add_task("bench", total=None, statuses="")

        def on_start(to_run: int, already: int) -> None:
            progress.update(task, total=to_run)
            progress.console.print(f"{count(len(cases), 'case')} ({cases[0].profile} profile): {already} "
                                   f"already in {store.path}, {to_run} to run with the {executor.name} "
                                   "executor")

        def on_row(row: dict[str, Any]) -> None:
            statuses[row["status"]] = statuses.get(row["status"], 0) + 1
            progress.update(
                task, advance=1, statuses=" ".join(f"{s}:{n}" for s, n in sorted(statuses.items()))
            )
            if row["status"] in FAILED:
                progress.console.print(
                    f"[yellow]{escape(row['key'])}: {row['status']}[/] - {escape(str(row.get('reason')))}"
                )

        summary = None
        try:
            summary = run_sweep(cases, store, executor, retry=args.retry, on_start=on_start, on_row=on_row)
        except SweepInterrupted as stop:
            summary = stop.summary  # logged too: its rows are in the results and its wall time is real
            raise
        finally:
            exported = store.export()
            if summary is not None:
                record_sweep(
                    store.folder,
                    {
                        "ran": summary.ran, "skipped": summary.skipped, "wall_s": summary.wall_s,
                        "executor": executor.name, "jobs": executor.jobs or "cluster",
                        "statuses": summary.statuses, "interrupted": summary.interrupted,
                    },
                )
    return executor, summary, exported


def _print_report(folder: str, condition: tuple[str, str, float | None] | None) -> None:
    from sgplan.bench.report import write_report

    report = write_report(folder, condition=condition)
    if report.table2:
        print(report.table2, end="\n\n")
    print(report.table3)
    say(f"wrote {report.markdown}" + "".join(f", {p}" for p in report.figures))
