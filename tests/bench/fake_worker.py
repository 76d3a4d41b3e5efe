"""A stand-in worker for executor tests: mission "crash" kills itself with SIGSEGV, mission "hang" sleeps
past any timeout, any other mission prints a canned optimal result at once (with this process's pid and
how many cases it has run). With $FAKE_WORKER_ONCE set to a path, only the first request of the sweep
(the one whose worker creates that file) is answered; every later one hangs. With ``--serve`` it answers
one request per stdin line, as ``sgplan.bench.worker --serve`` does."""

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


def answer(text: str, served: int) -> None:
    mission = json.loads(text)["case"]["mission"]
    if mission == "crash":
        print("about to crash", file=sys.stderr, flush=True)
        os.kill(os.getpid(), signal.SIGSEGV)
    elif mission == "hang" or _answered_before():
        time.sleep(600)
    reason = f"pid {os.getpid()} case {served}"  # lets tests see which process ran which case
    print(json.dumps({"status": "optimal", "reason": reason, "cost_m": 1.0, "peak_rss_mb": 1.0}), flush=True)


exit_when_orphaned()
if "--serve" in sys.argv[1:]:
    for served, line in enumerate(iter(sys.stdin.readline, ""), 1):
        answer(line, served)
else:
    answer(sys.stdin.read(), 1)
