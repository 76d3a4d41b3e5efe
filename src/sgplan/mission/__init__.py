"""Missions: what a robot must do, as a formula and its automaton over the scene's propositions.

- :mod:`sgplan.mission.model`: :class:`Mission` and :func:`compile_mission` (a formula's minimal DFA);
- :mod:`sgplan.mission.folder`: the authors' mission folders, read and written;
- :mod:`sgplan.mission.identity`: which scene a mission folder was made for, and whether it fits another.

The public way to make one is :func:`sgplan.mission_from_formula`, :func:`sgplan.mission_from_text` or
:func:`sgplan.load_mission`; the names below are the layer underneath.
"""

from sgplan.mission.folder import (
    MAX_MISSION_FILE_BYTES,
    load_mission_folder,
    read_ap_desc,
    read_guidance,
    save_mission_folder,
    write_guidance,
)
from sgplan.mission.model import Guidance, Mission, compile_mission, parse_formula

__all__ = [
    "MAX_MISSION_FILE_BYTES", "Guidance", "Mission", "compile_mission", "load_mission_folder",
    "parse_formula", "read_ap_desc", "read_guidance", "save_mission_folder", "write_guidance",
]
