"""Load and faults of ``sgplan serve`` on loopback: throughput, latency per endpoint, errors, server RSS.

The server runs as a child process (``sgplan serve --scene <scene>``, a fresh state folder); clients are
threads with their own HTTP connection (httpx), each looping for ``--seconds``. Phases (``--phases``):

- ``quiet``: one client, ``explain`` and ``observe`` (100 poses) alone: the latencies without load;
- ``plan-alone``: one client, one-shot A* ``plan`` requests one after the other (a warm plan's latency);
- ``beside-plans``: one client planning without pause and one sending ``explain`` and ``observe``: what a
  plan in a worker thread costs the requests served beside it (the GIL held by the planner's kernels, a
  core taken);
- ``mixed``: ``--clients`` clients mixing ``explain`` (30 %), one-shot A* ``plan`` (30 %), and a run
  each: created (A*), ``observe`` 100 poses at a time along its plan (30 %), a door on its remaining path
  closed and opened again (``change``, 10 %), a new run once it is done;
- ``plans``: ``--clients`` clients sending only ``plan`` (throughput of warm A* plans);
- ``faults``: a client that leaves an event stream mid-way (the server drops its queue); malformed and
  oversized bodies (422 / 413, never 500); a flood of ``4 x (workers + backlog)`` concurrent plans (503
  with Retry-After beyond the pool, never a crash); SIGKILL of the server under load and a restart on the
  same state folder (every run acknowledged before the kill is back, at the same status, position,
  automaton state and plan).

Missions: the scene's five Gibson missions (their GPT-4 token lists, over ``enter(room_N)`` /
``reach(object_N)``), from the scene's initial positions. Peak RSS is the server's ``VmHWM``, sampled
RSS every 0.5 s. Latencies are wall-clock per request as the client sees it.

    .venv/bin/python benchmarks/serve_load.py --scene Benevolence --clients 4 --seconds 60 \\
        > benchmarks/results/serve_load.md

Needs the serve extra and the Gibson data.
"""

from __future__ import annotations

import argparse
import ast
import json
import os
import random
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from collections import defaultdict
from collections.abc import Callable
from pathlib import Path
from typing import Any

import httpx
import numpy as np

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO))

from sgplan.datasets import find_gibson_root

BATCH = 100
"""Poses per observe request."""


class Server:
    """``sgplan serve`` as a child process on a free loopback port."""

    def __init__(self, scene: str, state: Path, workers: int, backlog: int) -> None:
        with socket.socket() as s:
            s.bind(("127.0.0.1", 0))
            self.port = s.getsockname()[1]
        self.url = f"http://127.0.0.1:{self.port}"
        self.command = [
            sys.executable,
            "-m",
            "sgplan.cli",
            "--quiet",
            "serve",
            "--scene",
            scene,
            "--port",
            str(self.port),
            "--state",
            str(state),
            "--workers",
            str(workers),
            "--backlog",
            str(backlog),
        ]
        self.process: subprocess.Popen[bytes] | None = None
        self.rss_mb: list[float] = []

    def start(self) -> float:
        """Start and wait until it answers; the seconds it took."""
        t0 = time.perf_counter()
        self.process = subprocess.Popen(self.command, stderr=subprocess.DEVNULL)
        while True:
            try:
                httpx.get(self.url + "/api/health", timeout=1).raise_for_status()
                break
            except httpx.HTTPError:
                if self.process.poll() is not None or time.perf_counter() - t0 > 300:
                    raise SystemExit("the server did not start") from None
                time.sleep(0.2)
        threading.Thread(target=self._sample, daemon=True).start()
        return time.perf_counter() - t0

    def _sample(self) -> None:
        process = self.process
        while process is not None and process.poll() is None:
            self.rss_mb.append(self.status("VmRSS"))
            time.sleep(0.5)

    def status(self, field: str) -> float:
        """A ``/proc/<pid>/status`` field in MB (0 once the process is gone)."""
        try:
            text = Path(f"/proc/{self.process.pid}/status").read_text()  # type: ignore[union-attr]
        except OSError:
            return 0.0
        lines = [line for line in text.splitlines() if line.startswith(field + ":")]
        return int(lines[0].split()[1]) / 1024 if lines else 0.0  # a zombie has no memory fields

    def kill(self) -> None:
        if self.process is not None and self.process.poll() is None:
            self.process.send_signal(signal.SIGKILL)
            self.process.wait()


class Tally:
    """Latencies (ms) and statuses per endpoint, from every client thread."""

    def __init__(self) -> None:
        self.ms: dict[str, list[float]] = defaultdict(list)
        self.codes: dict[str, dict[int, int]] = defaultdict(lambda: defaultdict(int))
        self.lock = threading.Lock()

    def call(self, client: httpx.Client, name: str, method: str, path: str, **kwargs: Any) -> httpx.Response:
        t0 = time.perf_counter()
        response = client.request(method, path, **kwargs)
        ms = 1000 * (time.perf_counter() - t0)
        with self.lock:
            self.ms[name].append(ms)
            self.codes[name][response.status_code] += 1
        return response

    def rows(self, seconds: float) -> list[str]:
        lines = [
            "| endpoint | requests | per s | p50 ms | p95 ms | p99 ms | statuses |",
            "|---|---|---|---|---|---|---|",
        ]
        for name in sorted(set(self.ms) | set(self.codes)):
            ms = np.array(self.ms.get(name) or [np.nan])
            codes = ", ".join(f"{code}: {n}" for code, n in sorted(self.codes[name].items()))
            lines.append(
                f"| {name} | {sum(self.codes[name].values())} | {len(ms) / seconds:.1f} "
                f"| {np.percentile(ms, 50):.1f} | "
                f"{np.percentile(ms, 95):.1f} | {np.percentile(ms, 99):.1f} | {codes} |"
            )
        return lines

    def errors(self) -> int:
        return sum(n for codes in self.codes.values() for code, n in codes.items() if code >= 400)


def mission_body(scene: str, formula: str, start: int, setup: str = "A*") -> dict[str, Any]:
    """The JSON of a plan or run request: a formula from initial position ``start``."""
    return {"scene": scene, "formula": formula, "start": {"index": start}, "options": {"setup": setup}}


def missions(scene: str) -> list[str]:
    """The scene's Gibson missions as formula token lists (their GPT-4 outputs)."""
    root = find_gibson_root()
    if root is None:
        raise SystemExit("the Gibson data is needed (see sgplan.datasets)")
    folders = sorted((root / scene / "missions").iterdir())
    return [json.dumps(ast.literal_eval((f / "GPT_LTL_formula.txt").read_text())) for f in folders]


def plannable(url: str, scene: str, formulas: list[str]) -> list[tuple[str, int]]:
    """The (mission, initial position) pairs that have a plan (some starts lie in a room a mission
    forbids: those are 422s, bad input, not load); planned once each, which also warms the server."""
    cases = []
    with httpx.Client(base_url=url, timeout=300) as c:
        for formula in formulas:
            for k in range(5):
                body = mission_body(scene, formula, k)
                if c.post("/api/plan", json=body).status_code == 200:
                    cases.append((formula, k))
    return cases


class Robot:
    """One client's run: created, driven 100 poses at a time, a door on its way closed and opened."""

    def __init__(
        self,
        client: httpx.Client,
        tally: Tally,
        scene: str,
        cases: list[tuple[str, int]],
        doors: list[dict[str, Any]],
        rng: random.Random,
    ) -> None:
        self.client, self.tally, self.scene, self.cases, self.doors, self.rng = (
            client,
            tally,
            scene,
            cases,
            doors,
            rng,
        )
        self.run: dict[str, Any] | None = None
        self.plan: dict[str, Any] | None = None
        self.closed: list[str] | None = None

    def _adopt(self, response: httpx.Response, ok: int = 200) -> None:
        self.run = response.json() if response.status_code == ok else None
        self.plan = None if self.run is None else self.run["plan"]

    def create(self) -> None:
        formula, start = self.rng.choice(self.cases)
        body = mission_body(self.scene, formula, start)
        self._adopt(self.tally.call(self.client, "run create", "POST", "/api/runs", json=body), ok=201)
        self.closed = None

    def observe(self) -> None:
        if self.run is None or self.plan is None or self.run["status"] != "in-progress":
            self.create()
            return
        waypoints = self.plan["waypoints"]
        at = self.run["plan_offset"]
        batch = waypoints[at + 1 : at + 1 + BATCH] or waypoints[-1:]
        poses = [[w["x_m"], w["y_m"], w["floor"]] for w in batch]
        while len(poses) < BATCH:  # a robot standing still at the end reports the same pose
            poses.append(poses[-1])
        response = self.tally.call(
            self.client,
            "observe (100 poses)",
            "POST",
            f"/api/runs/{self.run['id']}/observe",
            json={"poses": poses},
        )
        self.run = response.json()["run"] if response.status_code == 200 else None

    def change(self) -> None:
        if self.run is None or self.run["status"] != "in-progress":
            self.create()
            return
        if self.closed is None:
            kind, rooms = "close_door", self.rng.choice(self.doors)["rooms"]
        else:
            kind, rooms = "open_door", self.closed
        response = self.tally.call(
            self.client,
            f"change ({kind})",
            "POST",
            f"/api/runs/{self.run['id']}/changes",
            json={"changes": [{"kind": kind, "rooms": rooms}]},
        )
        if response.status_code == 200:
            self._adopt(response)
            self.closed = rooms if kind == "close_door" else None


def client_loop(
    url: str,
    scene: str,
    cases: list[tuple[str, int]],
    doors: list[dict[str, Any]],
    tally: Tally,
    until: float,
    seed: int,
    mix: str,
) -> list[str]:
    """One client until ``until``; returns the ids of its runs."""
    rng = random.Random(seed)
    runs: list[str] = []
    with httpx.Client(base_url=url, timeout=120) as client:
        robot = Robot(client, tally, scene, cases, doors, rng)

        def explain() -> None:
            tally.call(
                client,
                "explain",
                "POST",
                "/api/explain",
                json={"scene": scene, "formula": rng.choice(cases)[0]},
            )

        def plan() -> None:
            formula, start = rng.choice(cases)
            tally.call(
                client,
                "plan (A*)",
                "POST",
                "/api/plan",
                json=mission_body(scene, formula, start),
            )

        choices: dict[str, list[tuple[float, Callable[[], None]]]] = {
            "mixed": [(0.3, explain), (0.3, plan), (0.3, robot.observe), (0.1, robot.change)],
            "plans": [(1.0, plan)],
            "quiet": [(0.5, explain), (0.5, robot.observe)],
        }
        weights, actions = zip(*choices[mix])
        while time.perf_counter() < until:
            try:
                rng.choices(actions, weights)[0]()
            except httpx.TransportError:  # the server was killed (the faults phase): wait for it
                with tally.lock:
                    tally.codes["(no answer: server down)"][0] += 1
                robot.run = None
                time.sleep(0.2)
            if robot.run is not None and (not runs or runs[-1] != robot.run["id"]):
                runs.append(robot.run["id"])
    return runs


def load(
    server: Server, scene: str, cases: list[tuple[str, int]], clients: int, seconds: float, mix: str
) -> tuple[Tally, list[str]]:
    doors = httpx.get(f"{server.url}/api/scenes/{scene}", timeout=60).json()["doors"]
    tally = Tally()
    until = time.perf_counter() + seconds
    results: list[list[str]] = [[] for _ in range(clients)]

    def work(k: int) -> None:
        # "beside-plans": client 0 plans without pause, the others send explain and observe beside it.
        own = mix if mix != "beside-plans" else ("plans" if k == 0 else "quiet")
        results[k] = client_loop(server.url, scene, cases, doors, tally, until, k, own)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return tally, [run for ids in results for run in ids]


def stream_and_bad_bodies(url: str, scene: str, cases: list[tuple[str, int]]) -> list[str]:
    """A client leaving an event stream mid-way; malformed and oversized bodies."""
    with httpx.Client(base_url=url, timeout=120) as c:
        formula, start = cases[0]
        run = c.post(
            "/api/runs",
            json=mission_body(scene, formula, start),
        ).json()
        with c.stream("GET", f"/api/runs/{run['id']}/events") as stream:
            next(stream.iter_lines())
        time.sleep(0.5)
        health = c.get("/api/health").json()
        json_type = {"content-type": "application/json"}
        bad = [
            c.post("/api/plan", content=b"{not json", headers=json_type).status_code,
            c.post("/api/plan", json={"scene": scene}).status_code,
            c.post("/api/plan", json={"scene": scene, "formula": "F (("}).status_code,
            c.post(
                "/api/runs/x/observe", content=b"[" + b"1," * (2 << 20) + b"1]", headers=json_type
            ).status_code,
            c.post("/api/runs/x/observe", json={"poses": [[0, 0, 0]] * 20_000}).status_code,
        ]
    return [
        f"- client left an event stream mid-way: server up ({health['status']}), "
        f"{health['plans_in_flight']} plans in flight",
        f"- malformed / oversized bodies: statuses {bad} (no 500)",
    ]


def flood(url: str, scene: str, cases: list[tuple[str, int]], workers: int, backlog: int) -> str:
    """``4 x (workers + backlog)`` concurrent ALL plans: the pool takes what it can, 503 for the rest."""
    tally = Tally()
    count = 4 * (workers + backlog)

    def one(k: int) -> None:
        formula, start = cases[k % len(cases)]
        with httpx.Client(base_url=url, timeout=120) as client:
            tally.call(
                client,
                "flood plan",
                "POST",
                "/api/plan",
                json=mission_body(scene, formula, start, "ALL"),
            )

    threads = [threading.Thread(target=one, args=(k,)) for k in range(count)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return (
        f"- flood of {count} concurrent ALL plans ({workers} workers, backlog {backlog}): statuses "
        f"{dict(tally.codes['flood plan'])}; server up: {httpx.get(url + '/api/health').status_code == 200}"
    )


def sigkill_under_load(server: Server, scene: str, cases: list[tuple[str, int]]) -> str:
    """4 clients mixing requests for 8 s, SIGKILL, restart on the same state, every run compared."""
    url = server.url
    doors = httpx.get(f"{url}/api/scenes/{scene}", timeout=60).json()["doors"]
    tally = Tally()
    until = time.perf_counter() + 8
    for k in range(4):  # they go on after the kill and the restart, until the process ends
        threading.Thread(
            target=client_loop, args=(url, scene, cases, doors, tally, until + 30, k, "mixed"), daemon=True
        ).start()
    time.sleep(8)
    with httpx.Client(base_url=url, timeout=120) as c:
        seen = {r["id"]: c.get(f"/api/runs/{r['id']}").json() for r in c.get("/api/runs").json()}
    server.kill()
    restart_s = server.start()
    with httpx.Client(base_url=url, timeout=120) as c:
        after = {r["id"] for r in c.get("/api/runs").json()}
        now = {run_id: c.get(f"/api/runs/{run_id}").json() for run_id in seen if run_id in after}
    # A run answered before the kill may have moved on by a request answered after the snapshot: its
    # revision (changes committed) is then higher. At the same revision it must be the same run.
    corrupt = [
        run_id
        for run_id, run in now.items()
        if run["revision"] < seen[run_id]["revision"]
        or (run["revision"] == seen[run_id]["revision"] and run != seen[run_id])
    ]
    moved_on = sum(run["revision"] > seen[run_id]["revision"] for run_id, run in now.items())
    return (
        f"- SIGKILL under load ({sum(len(v) for v in tally.ms.values())} requests in 8 s, 4 clients), "
        f"restart in {restart_s:.1f} s: {len(seen)} runs before, {len(after)} after, "
        f"{len(seen) - len(now)} lost, "
        f"{len(corrupt)} corrupted ({moved_on} moved on by requests answered after the snapshot)"
    )


def faults(server: Server, scene: str, cases: list[tuple[str, int]], workers: int, backlog: int) -> list[str]:
    """The fault runs; one line each."""
    return [
        *stream_and_bad_bodies(server.url, scene, cases),
        flood(server.url, scene, cases, workers, backlog),
        sigkill_under_load(server, scene, cases),
    ]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="Benevolence")
    parser.add_argument("--clients", type=int, default=4)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--backlog", type=int, default=8)
    parser.add_argument("--phases", default="quiet,plan-alone,beside-plans,mixed,plans,faults")
    args = parser.parse_args()
    state = Path(tempfile.mkdtemp(prefix="sgplan-serve-load-"))
    server = Server(args.scene, state, args.workers, args.backlog)
    start_s = server.start()
    t0 = time.perf_counter()
    cases = plannable(server.url, args.scene, missions(args.scene))
    warm_s = time.perf_counter() - t0
    print(f"# sgplan serve under load: {args.scene}\n")
    print(
        f"Command: `.venv/bin/python benchmarks/serve_load.py {' '.join(sys.argv[1:])}`; "
        f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} (other work on the machine); "
        f"server start (scene loaded, grid built) {start_s:.1f} s; "
        f"workers {args.workers}, backlog {args.backlog}; "
        f"{len(cases)} (mission, start) pairs with a plan, each planned once first ({warm_s:.1f} s).\n"
    )
    try:
        for phase in args.phases.split(","):
            if phase == "faults":
                print("## faults\n")
                print("\n".join(faults(server, args.scene, cases, args.workers, args.backlog)))
                print()
                continue
            clients = {"quiet": 1, "plan-alone": 1, "beside-plans": 2}.get(phase, args.clients)
            seconds = min(args.seconds, 20) if clients < args.clients else args.seconds
            rss0 = server.rss_mb[-1] if server.rss_mb else 0.0
            tally, runs = load(
                server, args.scene, cases, clients, seconds, "plans" if phase == "plan-alone" else phase
            )
            print(f"## {phase}: {clients} client(s), {seconds:g} s, {len(runs)} runs\n")
            print("\n".join(tally.rows(seconds)))
            print(
                f"\nerrors (status >= 400): {tally.errors()}; server RSS {rss0:.0f} MB before, "
                f"{server.status('VmRSS'):.0f} MB after, peak {server.status('VmHWM'):.0f} MB\n"
            )
            sys.stdout.flush()
    finally:
        server.kill()


if __name__ == "__main__":
    main()
