"""Evaluation: sweeps, executors, tables and figures (``sgplan bench``; docs/bench.md).

Data flows one way: :mod:`~sgplan.bench.cases` (what to run) -> :mod:`~sgplan.bench.executors` (each case
in a :mod:`~sgplan.bench.worker` process, locally or on Ray) -> :mod:`~sgplan.bench.sweep` and
:mod:`~sgplan.bench.results` (resumable store, CSV/JSON) -> :mod:`~sgplan.bench.report`
(:mod:`~sgplan.bench.tables` beside :mod:`~sgplan.bench.paper`, :mod:`~sgplan.bench.figures`).
"""
