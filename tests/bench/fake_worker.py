"""A stand-in worker for executor tests: mission "crash" kills itself with SIGSEGV, mission "hang" sleeps
past any timeout, any other mission prints a canned optimal result at once."""

from __future__ import annotations

import json
import os
import signal
import sys
import time

request = json.loads(sys.stdin.read())
mission = request["case"]["mission"]
if mission == "crash":
    print("about to crash", file=sys.stderr, flush=True)
    os.kill(os.getpid(), signal.SIGSEGV)
elif mission == "hang":
    time.sleep(600)
print(json.dumps({"status": "optimal", "reason": None, "cost_m": 1.0, "peak_rss_mb": 1.0}))
