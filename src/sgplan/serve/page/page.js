"use strict";
// The live page of `sgplan serve`: scene and start, the mission said back as one types, a run planned
// and drawn (the HTML report's floors and overlays, from the server), doors to close and open, and a
// simulated robot driven along the path while the run's events stream in. No library, no network
// beyond this server.
(function () {
  const $ = function (id) { return document.getElementById(id); };
  const params = new URLSearchParams(location.search);
  if (params.get("token")) {  // keep the token for this tab only, and out of the address bar
    sessionStorage.setItem("sgplan-token", params.get("token"));
    history.replaceState(null, "", location.pathname);
  }
  const token = sessionStorage.getItem("sgplan-token");
  const state = { scene: null, floors: null, doors: [], closed: new Set(), start: null, run: null,
                  plan: null, explained: null, events: null, playing: null, robotAt: 0 };

  async function api(method, path, body, signal) {
    const headers = { "Content-Type": "application/json" };
    if (token) { headers.Authorization = "Bearer " + token; }
    const response = await fetch(path, { method: method, headers: headers,
                                         body: body === undefined ? undefined : JSON.stringify(body),
                                         signal: signal });
    const data = await response.json();
    if (!response.ok) {
      const error = new Error(data.error ? data.error.message : response.statusText);
      error.status = response.status;
      throw error;
    }
    return data;
  }
  function setText(id, text, className) {
    const element = $(id);
    element.textContent = text;
    if (className !== undefined) { element.className = className; }
  }
  function list(id, items, classOf) {
    const element = $(id);
    element.textContent = "";
    items.forEach(function (item) {
      const li = document.createElement("li");
      li.textContent = typeof item === "string" ? item : item.message;
      if (classOf) { li.className = classOf(item); }
      element.appendChild(li);
    });
  }
  function log(text) {
    const li = document.createElement("li");
    li.textContent = new Date().toLocaleTimeString() + "  " + text;
    $("log").appendChild(li);
    li.scrollIntoView({ block: "nearest" });
  }

  // -- the mission and the start -------------------------------------------------------------------
  function missionBody() {
    const text = $("mission").value.trim();
    if (!text) { return null; }
    const body = { scene: state.scene, options: { setup: $("setup").value } };
    // A formula is written with quoted propositions or as a token list; anything else is words.
    if (/^\[|"(enter|reach)\(/.test(text)) { body.formula = text; } else { body.text = text; }
    if (state.start) { body.start = state.start; }
    return body;
  }
  let explainTimer = null, explainAbort = null;
  function explainSoon() {
    clearTimeout(explainTimer);
    explainTimer = setTimeout(explain, 300);
  }
  async function explain() {
    const body = missionBody();
    $("plan").disabled = true;
    if (!body) { setText("explanation", "Type a mission to see it said back.", "empty"); list("checks", []); return; }
    if (explainAbort) { explainAbort.abort(); }
    explainAbort = new AbortController();
    const signal = explainAbort.signal;
    try {
      const answer = await api("POST", "/api/explain", body, signal);
      if (signal.aborted) { return; }
      state.explained = answer;
      setText("explanation", answer.explanation + (answer.formula ? "\nFormula: " + answer.formula : ""), "");
      list("checks", answer.scene_check, function (f) { return f.severity; });
      $("plan").disabled = answer.scene_check.some(function (f) { return f.severity === "error"; });
    } catch (error) {
      if (signal.aborted) { return; }
      setText("explanation", error.message, "error");
      list("checks", []);
    }
  }
  function setStart(start, words) {
    state.start = start;
    setText("start-shown", words);
    drawMarks();
    explainSoon();
  }

  // -- the scene and its floors --------------------------------------------------------------------
  async function loadScenes() {
    const scenes = await api("GET", "/api/scenes");
    scenes.forEach(function (s) {
      const option = document.createElement("option");
      option.value = s.name;
      option.textContent = s.name + " (" + s.floors + " floors, " + s.rooms + " rooms)";
      $("scene").appendChild(option);
    });
    await loadScene(scenes[0].name);
  }
  async function loadScene(name) {
    stopRun();
    state.scene = name;
    state.closed = new Set();
    const [summary, layers] = await Promise.all([api("GET", "/api/scenes/" + encodeURIComponent(name)),
                                                 api("GET", "/api/scenes/" + encodeURIComponent(name) + "/layers")]);
    state.doors = summary.doors;
    $("layers").innerHTML = layers.html;
    state.floors = window.sgplanFloors($("layers"), JSON.parse(layers.entities));
    document.querySelectorAll("#layers .floor").forEach(function (layer) {
      const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
      svg.setAttribute("class", "marks");
      svg.setAttribute("viewBox", layer.querySelector("svg.overlay").getAttribute("viewBox"));  // the report's frame
      svg.setAttribute("preserveAspectRatio", "none");
      layer.querySelector(".stage").appendChild(svg);
      layer.querySelector(".stage").addEventListener("click", function (event) {
        if (event.target.classList && event.target.classList.contains("door")) { return; }
        const cell = state.floors.cellAt(layer, event);
        if (cell) {
          $("start-room").value = "";
          setStart({ cell: [cell.row, cell.col, cell.floor] }, "cell row " + cell.row + ", column " + cell.col + ", floor " + cell.floor);
        }
      });
    });
    setStart(null, "the scene's first initial position");
  }
  function svgElement(name, attributes) {
    const element = document.createElementNS("http://www.w3.org/2000/svg", name);
    Object.keys(attributes).forEach(function (key) { element.setAttribute(key, attributes[key]); });
    return element;
  }
  function drawMarks() {
    document.querySelectorAll("#layers .floor").forEach(function (layer) {
      const svg = layer.querySelector("svg.marks");
      const floor = Number(layer.dataset.floor);
      const unit = Math.max(Number(layer.dataset.rows), Number(layer.dataset.cols)) / 1000;
      const at = function (row, col) { return state.floors.svgXY(layer, row, col); };
      svg.textContent = "";
      state.doors.filter(function (d) { return d.floor === floor; }).forEach(function (door) {
        const key = door.rooms.join("|");
        const closed = state.closed.has(key);
        const size = 7 * unit, p = at(door.row, door.col);
        const mark = svgElement("rect", { class: "door" + (closed ? " closed" : ""), x: p.x - size, y: p.y - size,
                                          width: 2 * size, height: 2 * size, tabindex: "0", role: "button",
                                          "aria-label": (closed ? "open" : "close") + " the door between the " + door.names[0] + " and the " + door.names[1] });
        const title = svgElement("title", {});
        title.textContent = (closed ? "closed: " : "open: ") + "door between the " + door.names[0] + " (" + door.rooms[0] + ") and the " + door.names[1] + " (" + door.rooms[1] + "); click to " + (closed ? "open" : "close");
        mark.appendChild(title);
        mark.addEventListener("click", function () { toggleDoor(door); });
        mark.addEventListener("keydown", function (event) {
          if (event.key === "Enter" || event.key === " ") { event.preventDefault(); toggleDoor(door); }
        });
        svg.appendChild(mark);
      });
      if (state.start && state.start.cell && state.start.cell[2] === floor) {
        const p = at(state.start.cell[0], state.start.cell[1]);
        svg.appendChild(svgElement("circle", { class: "chosen-start", cx: p.x, cy: p.y, r: 9 * unit }));
      }
      const robot = robotCell();
      if (robot && robot.floor === floor) {
        const p = at(robot.row, robot.col);
        svg.appendChild(svgElement("circle", { class: "robot", cx: p.x, cy: p.y, r: 6 * unit }));
      }
    });
  }

  // -- the run: plan, draw, doors, play ------------------------------------------------------------
  function showRun(run) {
    state.run = run;
    state.plan = run.plan;
    const plan = run.plan;
    const open = run.status === "in-progress";
    setText("status", "Run " + run.id + " (" + run.status + "): " + (plan ? plan.status + ", cost " +
            (plan.cost_m === null ? "-" : plan.cost_m.toFixed(2) + " m") + ", " + (plan.path ? plan.path.length : 0) +
            " cells, setup " + plan.setup : "no plan") + (run.why ? ". " + run.why : ""));
    setText("verdict", "Monitor: " + run.status + " (" + run.monitor.poses + " poses seen, " +
            run.monitor.length_m.toFixed(1) + " m driven)", run.status);
    list("left", [run.left ? "Left: " + run.left : run.status === "done" ? "Nothing is left: the mission is done." : "-"]);
    $("play").disabled = !open || !plan || !plan.path;
    $("cancel-run").disabled = !open;
  }
  async function refreshView() {
    const run = await api("GET", "/api/runs/" + state.run.id + "?view=true");
    state.robotAt = run.plan_offset;
    document.querySelectorAll("#layers .floor").forEach(function (layer, k) {
      const old = layer.querySelector("svg.overlay");
      const holder = document.createElement("div");
      holder.innerHTML = run.overlays[k];
      old.replaceWith(holder.firstChild);
    });
    showRun(run);
    drawMarks();
    const first = run.plan && run.plan.path && run.plan.path.length ? run.plan.path[run.plan_offset][2] : null;
    if (first !== null) { state.floors.showFloor(first); }
  }
  function follow(runId) {
    if (state.events) { state.events.close(); }
    const url = "/api/runs/" + runId + "/events" + (token ? "?token=" + encodeURIComponent(token) : "");
    state.events = new EventSource(url);
    ["replanned", "progress", "changed", "amended", "refused", "impossible", "violated", "done", "cancelled"].forEach(function (kind) {
      state.events.addEventListener(kind, function (message) {
        log(kind + ": " + JSON.parse(message.data).message);
        if (kind === "done" || kind === "violated" || kind === "cancelled") { state.events.close(); }
      });
    });
  }
  async function plan() {
    const body = missionBody();
    if (!body) { return; }
    stopRun();
    $("plan").disabled = true;
    setText("status", "Planning...");
    try {
      const run = await api("POST", "/api/runs", body);
      state.run = run;
      log("run " + run.id + " started: " + (run.plan ? "planned " + run.plan.cost_m.toFixed(2) + " m" : run.status));
      follow(run.id);
      await refreshView();
    } catch (error) {
      setText("status", error.message);
    } finally {
      $("plan").disabled = false;
    }
  }
  async function toggleDoor(door) {
    if (!state.run || state.run.status !== "in-progress") { setText("status", "Plan first: a door changes a run's scene."); return; }
    const key = door.rooms.join("|");
    const kind = state.closed.has(key) ? "open_door" : "close_door";
    setText("status", (kind === "close_door" ? "Closing" : "Opening") + " the door between the " + door.names[0] + " and the " + door.names[1] + "; replanning...");
    try {
      await api("POST", "/api/runs/" + state.run.id + "/changes", { changes: [{ kind: kind, rooms: door.rooms }] });
      if (kind === "close_door") { state.closed.add(key); } else { state.closed.delete(key); }
      await refreshView();
    } catch (error) {
      setText("status", error.message);
    }
  }
  function robotCell() {
    const w = state.plan && state.plan.waypoints;
    if (!w || !w.length || !state.run) { return null; }
    const at = w[Math.min(state.robotAt, w.length - 1)];
    return { row: at.row, col: at.col, floor: at.floor };
  }
  async function step() {
    const w = state.plan.waypoints;
    const batch = w.slice(state.robotAt + 1, state.robotAt + 6);
    if (!batch.length) { pause(); return; }
    try {
      const answer = await api("POST", "/api/runs/" + state.run.id + "/observe",
                               { poses: batch.map(function (p) { return [p.x_m, p.y_m, p.floor]; }) });
      state.robotAt = batch[batch.length - 1].index;
      showRun(Object.assign({}, answer.run, { plan: state.plan }));  // a pose report leaves the plan out
      drawMarks();
      state.floors.showFloor(batch[batch.length - 1].floor);
      if (answer.run.status !== "in-progress") { pause(); }
    } catch (error) {
      setText("status", error.message);
      pause();
    }
  }
  function play() {
    if (state.playing) { pause(); return; }
    $("play").textContent = "Pause";
    $("play").setAttribute("aria-pressed", "true");
    state.playing = setInterval(function () { if (!state.stepping) { state.stepping = true; step().finally(function () { state.stepping = false; }); } }, 200);
  }
  function pause() {
    clearInterval(state.playing);
    state.playing = null;
    $("play").textContent = "Play";
    $("play").setAttribute("aria-pressed", "false");
  }
  function stopRun() {
    pause();
    if (state.events) { state.events.close(); state.events = null; }
    state.run = null;
    state.plan = null;
  }
  async function cancelRun() {
    if (!state.run) { return; }
    try { showRun(await api("POST", "/api/runs/" + state.run.id + "/cancel")); pause(); } catch (error) { setText("status", error.message); }
  }

  $("scene").addEventListener("change", function () { loadScene($("scene").value).catch(function (e) { setText("status", e.message); }); });
  $("mission").addEventListener("input", explainSoon);
  $("setup").addEventListener("change", explainSoon);
  $("start-room").addEventListener("input", function () {
    const room = $("start-room").value.trim();
    setStart(room ? { room: room } : null, room ? "room " + room : "the scene's first initial position");
  });
  $("plan").addEventListener("click", plan);
  $("play").addEventListener("click", play);
  $("cancel-run").addEventListener("click", cancelRun);
  loadScenes().catch(function (error) { setText("status", "Cannot load the scenes: " + error.message); });
})();
