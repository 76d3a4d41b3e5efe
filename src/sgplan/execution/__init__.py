"""Carrying a mission through a changing building: the runtime monitor of the poses a robot drove,
trajectory files, scene changes and their effect on the planner's parts, exact replanning from any
(position, automaton state), amendments, and the run that holds it all. See docs/execution.md.

Typical use::

    from sgplan.execution.monitor import Monitor
    monitor = Monitor.in_session(sgplan.Session(building), mission)
    status = monitor.observe_xy(poses)        # (n, 3): x_m, y_m, floor
    print(status.summary())
"""
