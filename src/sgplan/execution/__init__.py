"""Carrying a mission through a run: the runtime monitor of the poses a robot drove, trajectory files.

See docs/execution.md. Typical use::

    from sgplan.execution.monitor import Monitor
    monitor = Monitor.in_session(sgplan.Session(building), mission)
    status = monitor.observe_xy(poses)        # (n, 3): x_m, y_m, floor
    print(status.summary())
"""
