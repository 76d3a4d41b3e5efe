"""Meaning: from the grounded syntax tree of a mission to steps, tasks and constraints, and to one LTL
formula (:func:`.mission.mission_formula`)."""
