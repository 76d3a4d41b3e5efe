"""``sgplan serve``: the mission service, a JSON API and a live web page over warm scenes (docs/serve.md).

Modules, each with one job: :mod:`~sgplan.serve.config` (what a server serves and who may talk to it),
:mod:`~sgplan.serve.scenes` (the warm scenes), :mod:`~sgplan.serve.missions` (missions understood and said
back), :mod:`~sgplan.serve.pool` and :mod:`~sgplan.serve.planning` (plans off the event loop, bounded,
under a time limit), :mod:`~sgplan.serve.runs`, :mod:`~sgplan.serve.progress`,
:mod:`~sgplan.serve.store` and :mod:`~sgplan.serve.streams` (runs, their database and their event
streams), :mod:`~sgplan.serve.views` (the page's drawings, by the HTML report's renderer),
:mod:`~sgplan.serve.guards` (token, body size), :mod:`~sgplan.serve.errors` (HTTP answers),
:mod:`~sgplan.serve.models` (request and response bodies), :mod:`~sgplan.serve.service` (all of it
without HTTP) and :mod:`~sgplan.serve.app` (the routes).

Needs the ``serve`` extra: ``pip install 'sgplan[serve]'``.
"""
