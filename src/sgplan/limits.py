"""Upper bounds shared by the command line and the file readers, so a file can ask no more than a flag.

A value beyond these is refused wherever it comes from (``--robot-radius``, a scene's
``radius_config.bash`` or ``scene.json``, an ``ap_desc.yaml``), with a message naming its source.
"""

from __future__ import annotations

MAX_SECONDS = 1e6
"""Upper bound of a time option (about 11.6 days; larger values overflow the OS timers)."""
MAX_ROBOT_RADIUS_M = 2.0
"""Upper bound of the robot radius: a wider robot fits no door, and the footprint inflation grows with
the square of the radius (at 100 m it takes minutes)."""
MAX_REACH_RADIUS_M = 100.0
"""Upper bound of the reach radius: larger than any building (a reach of 1e5 m makes labelling spin
for minutes)."""
MAX_GRID_CELLS = 25_000_000
"""Upper bound of the cells of one floor's grid (5000 x 5000); the Gibson maps have about 0.3 M."""

# -- the mission service (sgplan serve): what one request may ask -------------------------------------

MAX_REQUEST_BYTES = 1 * 2**20
"""Upper bound of one request body to ``sgplan serve`` (1 MiB: a batch of the most poses below, as JSON
numbers, fits several times over)."""
MAX_MISSION_TEXT_CHARS = 4_000
"""Upper bound of a mission in natural language (a page of text; the Gibson missions have < 400)."""
MAX_FORMULA_CHARS = 20_000
"""Upper bound of a formula as text (the translator's longest Gibson formulas have < 1,000)."""
MAX_POSES_PER_BATCH = 10_000
"""Upper bound of the poses one ``observe`` request reports (a robot reports a few per second)."""
MAX_CHANGES_PER_REQUEST = 100
"""Upper bound of the scene changes one request applies."""
MAX_NAME_CHARS = 200
"""Upper bound of a name in a request (a room for the start, a scene, a door's room)."""
