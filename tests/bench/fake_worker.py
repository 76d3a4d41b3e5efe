"""A stand-in worker for executor tests: mission "crash" kills itself with SIGSEGV, mission "hang" sleeps
past any timeout, any other mission prints a canned optimal result at once. With $FAKE_WORKER_ONCE set to
a path, only the first worker (the one that creates that file) answers; every later one hangs."""

from __future__ import annotations

import json
import os
import signal
import sys
import time

from sgplan.bench.worker import exit_when_orphaned


def _answered_before() -> bool:
    once = os.environ.get("FAKE_WORKER_ONCE")
    if not once:
        return False
    try:
        with open(once, "x"):
            return False
    except FileExistsError:
        return True


exit_when_orphaned()
request = json.loads(sys.stdin.read())
mission = request["case"]["mission"]
if mission == "crash":
    print("about to crash", file=sys.stderr, flush=True)
    os.kill(os.getpid(), signal.SIGSEGV)
elif mission == "hang" or _answered_before():
    time.sleep(600)
print(json.dumps({"status": "optimal", "reason": None, "cost_m": 1.0, "peak_rss_mb": 1.0}))
