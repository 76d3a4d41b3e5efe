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
