"""Importers: scene graphs made by other tools, turned into sgplan buildings.

One module per source kind -- :mod:`.hydra` (spark-dsg DynamicSceneGraph files written by Hydra),
:mod:`.mp3d` (Matterport3D ``.house`` files), :mod:`.ros` (a ROS map_server map plus a rooms file) --
each reducing its source to the drafts of :mod:`.assemble`, which finishes the building the same way
for all. :mod:`.raster` rasterises metric shapes; :mod:`.detect` tells which kind a path is.
Every importer returns an :class:`~sgplan.importers.assemble.ImportResult` (the building and notes)
and raises :class:`~sgplan.errors.SceneError` naming the file, entity and field on bad input.

This module itself imports nothing heavy: the CLI reads the names below when it builds its parser.
"""

from typing import Literal

Kind = Literal["hydra", "mp3d", "ros"]
KINDS: tuple[Kind, ...] = ("hydra", "mp3d", "ros")
"""The importers, by the name ``sgplan import KIND`` takes."""

DEFAULT_OPEN_GAP_M = 0.14
"""Matterport3D: floor polygons closer than this share an open boundary (thinner than an interior wall)."""
