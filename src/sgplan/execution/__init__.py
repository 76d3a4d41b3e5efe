"""Carrying a mission through a changing building: scene changes, their effect on the planner's parts,
exact replanning from any (position, automaton state), amendments, and the :class:`Run` that holds it
all (docs/execution.md)."""
