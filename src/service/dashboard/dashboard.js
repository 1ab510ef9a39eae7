// The rondo dashboard: today's schedule (planned against actual, one lane per robot), the map
// with every robot, the fleet's totals, the task list with cancel buttons, a form to add a task,
// one path's rhythm over the day, and the live event feed. A fleet of one robot looks as a lone
// robot always did: no lane titles, no totals, no names. Plain JavaScript and SVG, served by the
// binary itself; no build step.
// The token (when the service has one) is asked for once and kept in this tab's session storage.
"use strict";

const SVG = "http://www.w3.org/2000/svg";
const FINAL = new Set(["succeeded", "failed", "cancelled", "dropped", "preempted"]);
const STATE_WORDS = {
  queued: "waiting its turn", waiting: "waiting to start", navigating: "on the way", acting: "being done",
  succeeded: "done", failed: "failed", cancelled: "cancelled", dropped: "dropped", preempted: "interrupted",
};
const PHASE_WORDS = {
  idle: "is free", waiting: "is waiting for a task's time", navigating: "is on the way to a task",
  acting: "is doing a task", docking: "is going back to its charger",
};
// The event log's words in the feed ("<time>: <who> <words>"); states use STATE_WORDS.
const EVENT_WORDS = {
  queued: "was added", scheduled: "is planned", navigating: "is being travelled to", acting: "is being done",
  succeeded: "is done", failed: "failed", cancelled: "was cancelled", dropped: "was dropped",
  preempted: "was interrupted", changed: "was changed",
};
// Events whose reason is the scheduler's own note, not worth a manager's time.
const QUIET_REASONS = new Set(["queued", "scheduled", "navigating", "acting", "succeeded"]);
// Each robot's colour on the map and in its lane, by its place in the fleet's list; a fleet of one
// keeps the colours the dashboard always had.
const ROBOT_COLOURS = ["#1d70b8", "#d4351c", "#2e8540", "#912b88", "#f47738", "#28a197", "#6f72af", "#85994b",
                       "#b58840", "#5694ca"];
const view = { zone: "UTC", tasks: [], names: new Map(), map: null, robots: [], schedule: null };

const $ = (selector) => document.querySelector(selector);
function el(tag, attrs = {}, text) {
  const node = tag.startsWith("svg:") ? document.createElementNS(SVG, tag.slice(4)) : document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== undefined) node.textContent = text;
  return node;
}

async function api(method, path, body) {
  for (let attempt = 0; attempt < 2; attempt++) {
    const headers = { "Content-Type": "application/json" };
    const token = sessionStorage.getItem("rondo-token");
    if (token && method !== "GET") headers.Authorization = "Bearer " + token;
    const res = await fetch(path, { method, headers, body: body === undefined ? undefined : JSON.stringify(body) });
    if ((res.status === 401 || res.status === 403) && method !== "GET" && attempt === 0) {
      const given = window.prompt("Changes need this service's access token:");
      if (!given) throw new Error("no access token given");
      sessionStorage.setItem("rondo-token", given.trim());
      continue;
    }
    const data = await res.json().catch(() => ({}));
    if (!res.ok) throw new Error(data.error ? data.error.message : "the service answered " + res.status);
    return data;
  }
  throw new Error("the access token was not accepted");
}

function clock(iso) {
  if (!iso) return "";
  return new Intl.DateTimeFormat(undefined, { timeZone: view.zone, hour: "2-digit", minute: "2-digit" })
    .format(new Date(iso));
}
function dayAndClock(iso) {
  if (!iso) return "";
  return new Intl.DateTimeFormat(undefined, { timeZone: view.zone, weekday: "short", hour: "2-digit", minute: "2-digit" })
    .format(new Date(iso));
}
// The offset of the deployment's time zone from UTC at the instant t (ms since the epoch), in ms.
function zoneOffset(t) {
  const parts = Object.fromEntries(new Intl.DateTimeFormat("en-US", { timeZone: view.zone, hourCycle: "h23",
    year: "numeric", month: "2-digit", day: "2-digit", hour: "2-digit", minute: "2-digit", second: "2-digit" })
    .formatToParts(new Date(t)).map((p) => [p.type, p.value]));
  const wall = Date.UTC(Number(parts.year), Number(parts.month) - 1, Number(parts.day), Number(parts.hour),
    Number(parts.minute), Number(parts.second));
  return wall - Math.floor(t / 1000) * 1000;
}
// A datetime-local field's value ("2026-12-02T09:30") for the instant t, in the deployment's zone.
function toLocalInput(t) { return new Date(t + zoneOffset(t)).toISOString().slice(0, 16); }
// The instant a datetime-local value names in the deployment's zone (twice: the offset may change).
function fromLocalInput(value) {
  const wall = Date.parse(value + ":00Z");
  return wall - zoneOffset(wall - zoneOffset(wall));
}
function taskName(task) { return task.activity || task.id; }
// The fleet's robots by name, in the deployment's order: the schedule's list (it comes first) or
// the robots' views.
function robotNames() {
  if (view.robots.length) return view.robots.map((r) => r.name);
  return view.schedule && view.schedule.robots ? view.schedule.robots.map((r) => r.name) : [];
}
function isFleet() { return robotNames().length > 1; }
function robotColour(name) {
  const i = robotNames().indexOf(name);
  return i < 0 ? "#666" : ROBOT_COLOURS[i % ROBOT_COLOURS.length];
}
// The service's clock as last read: the robot's line (every 2 s) or the schedule (on events),
// whichever is newer. Only events refresh the schedule, and a quiet night has none: the form's
// window must not stay at the time of the last one.
function serviceNow() {
  const read = [view.schedule && view.schedule.now, view.robots.length && view.robots[0].time].filter(Boolean).map(Date.parse);
  return read.length ? Math.max(...read) : Date.now();
}
function showProblem(message) {
  const p = $("#problem");
  p.hidden = !message;
  p.textContent = message || "";
}

// --- the robots -------------------------------------------------------------------------------
async function refreshRobots() {
  const r = await api("GET", "/api/v1/robots");
  view.robots = r.robots;
  $("#robot-line").textContent = isFleet() ? fleetLine(view.robots) : robotLine(view.robots[0]);
  drawTotals();
  drawMap();
  followClock();
}

// A lone robot's line, as it always read.
function robotLine(r) {
  let line = `The robot ${PHASE_WORDS[r.phase] || r.phase}`;
  if (r.current_task) line += `: ${view.names.get(r.current_task) || "a task"}`;
  line += `. It is at ${r.node}, battery ${Math.round(r.battery * 100)} %${r.charging ? ", charging" : ""}.`;
  line += ` Its clock: ${dayAndClock(r.time)}${view.zone === "UTC" ? " UTC" : ""}.`;
  if (r.faults.length) line += ` Problem: ${r.faults.map((f) => f.message).join("; ")}.`;
  if (r.dispatch_paused) line += " It takes no new task until the problem is cleared.";
  return line;
}

// A fleet's line: how many robots do what, and which have a problem.
const PHASE_COUNTS = { idle: "free", waiting: "waiting", navigating: "on the way", acting: "doing a task", docking: "docking" };
function fleetLine(robots) {
  const counts = new Map();
  for (const r of robots) counts.set(r.phase, (counts.get(r.phase) || 0) + 1);
  const parts = [...counts].map(([phase, n]) => `${n} ${PHASE_COUNTS[phase] || phase}`);
  let line = `The fleet's ${robots.length} robots: ${parts.join(", ")}.`;
  line += ` Their clock: ${dayAndClock(robots[0].time)}${view.zone === "UTC" ? " UTC" : ""}.`;
  const troubled = robots.filter((r) => r.faults.length || r.out_of_service);
  for (const r of troubled)
    line += ` ${r.name}: ${r.faults.length ? r.faults.map((f) => f.message).join("; ") : "out of service"}.`;
  return line;
}

// The fleet's totals: per robot and in all, the tasks done, failed and dropped (every stored
// task, GET /api/v1/robots) and those still to do; hidden for a fleet of one.
function drawTotals() {
  const section = $("#fleet-section");
  section.hidden = !isFleet();
  if (section.hidden) return;
  const body = $("#fleet-totals tbody");
  body.replaceChildren();
  const count = (r, state) => (r.tasks && r.tasks[state]) || 0;
  const total = { done: 0, failed: 0, dropped: 0, open: 0, busy: 0 };
  const row = (attrs, cells) => {
    const tr = el("tr", attrs);
    for (const [cls, text, swatch] of cells) {
      const td = el("td", { class: cls }, text);
      if (swatch) {
        // Through the style object, not a style attribute: the page's CSP refuses inline styles.
        const dot = el("span", { class: "swatch" });
        dot.style.background = swatch;
        td.prepend(dot);
      }
      tr.append(td);
    }
    body.append(tr);
  };
  for (const r of view.robots) {
    const figures = { done: count(r, "succeeded"), failed: count(r, "failed"), dropped: count(r, "dropped"), open: r.open_tasks };
    for (const k of Object.keys(figures)) total[k] += figures[k];
    if (r.phase !== "idle") total.busy++;
    const now = `${PHASE_COUNTS[r.phase] || r.phase} at ${r.node}` + (r.current_task ? `: ${view.names.get(r.current_task) || "a task"}` : "");
    row({ "data-robot": r.name }, [["name", r.name, robotColour(r.name)], ["now", now],
      ["number battery", `${Math.round(r.battery * 100)} %${r.charging ? " charging" : ""}`],
      ["number done", String(figures.done)], ["number failed", String(figures.failed)],
      ["number dropped", String(figures.dropped)], ["number open", String(figures.open)]]);
  }
  const lowest = Math.min(...view.robots.map((r) => r.battery));
  row({ class: "total" }, [["name", "All robots"], ["now", `${total.busy} of ${view.robots.length} busy`],
    ["number battery", `lowest ${Math.round(lowest * 100)} %`], ["number done", String(total.done)],
    ["number failed", String(total.failed)], ["number dropped", String(total.dropped)], ["number open", String(total.open)]]);
}

// --- the schedule as a Gantt chart ----------------------------------------------------------------
async function refreshSchedule() {
  const s = await api("GET", "/api/v1/schedule");
  view.schedule = s;
  view.zone = s.zone || "UTC";
  drawGantt();
  followClock();
}

// The lanes of the chart: one per robot, each with the tasks allocated to it (and one for tasks
// given to none, when there are any). A fleet of one has one lane without a title.
function ganttLanes(s) {
  const names = s.robots ? s.robots.map((r) => r.name) : [];
  if (names.length <= 1) return [{ name: names[0] || "", title: null, tasks: s.tasks }];
  const by = new Map(names.map((n) => [n, []]));
  const none = [];
  for (const t of s.tasks) (by.has(t.robot) ? by.get(t.robot) : none).push(t);
  const lanes = names.map((n) => ({ name: n, title: n, tasks: by.get(n) }));
  if (none.length) lanes.push({ name: "", title: "given to no robot", tasks: none });
  return lanes;
}

// A lane's title: the robot and what its day holds so far.
function laneTitle(lane) {
  const n = (state) => lane.tasks.filter((t) => t.state === state).length;
  const open = lane.tasks.filter((t) => !FINAL.has(t.state)).length;
  if (!lane.tasks.length) return `${lane.title}: nothing today`;
  return `${lane.title}: ${lane.tasks.length} today, ${n("succeeded")} done, ${n("failed")} failed, ${open} to do`;
}

function drawGantt() {
  const s = view.schedule;
  const box = $("#gantt");
  box.replaceChildren();
  if (!s) return;
  const lanes = ganttLanes(s);
  const lines = lanes.reduce((n, lane) => n + lane.tasks.length + (lane.title ? 1 : 0), 0);
  const width = 1300, label = 320, stateW = 120, rowH = 20, top = 22;
  const from = Date.parse(s.from), to = Date.parse(s.to);
  const x = (iso) => label + stateW + Math.max(0, Math.min(1, (Date.parse(iso) - from) / (to - from))) * (width - label - stateW - 10);
  const svg = el("svg:svg", { width, height: top + lines * rowH + 10, role: "img", "aria-label": "today's schedule" });
  for (let h = 0; h <= 24; h += 2) {
    const t = new Date(from + h * 3600e3).toISOString();
    svg.append(el("svg:line", { x1: x(t), x2: x(t), y1: top - 4, y2: top + lines * rowH, stroke: "#e3e6ea" }));
    if (h < 24) svg.append(el("svg:text", { x: x(t) + 2, y: 12 }, clock(t)));
  }
  let line = 0;
  for (const lane of lanes) {
    const g = el("svg:g", { class: "gantt-lane", "data-robot": lane.name });
    if (lane.title) {
      const y = top + line * rowH;
      const colour = lane.name ? robotColour(lane.name) : "#666";
      g.append(el("svg:rect", { x: 0, y: y + 1, width: width, height: rowH - 2, fill: colour, "fill-opacity": 0.1 }));
      g.append(el("svg:circle", { cx: 7, cy: y + rowH / 2, r: 5, fill: colour }));
      g.append(el("svg:text", { x: 18, y: y + 14, class: "gantt-lane-title" }, laneTitle(lane)));
      line++;
    }
    for (const t of lane.tasks) g.append(ganttRow(t, top + line++ * rowH, x, rowH, label, s.now));
    svg.append(g);
  }
  svg.append(el("svg:line", { x1: x(s.now), x2: x(s.now), y1: top - 6, y2: top + lines * rowH, stroke: "#d4351c", "stroke-width": 2 }));
  box.append(svg);
  if (!s.tasks.length) box.append(el("p", {}, "Nothing is planned for today."));
}

// One task's row at height y: its name and state, its window, planned and actual spans.
function ganttRow(t, y, x, rowH, label, now) {
  const g = el("svg:g", { class: "gantt-row", "data-task": t.id, "data-name": taskName(t), "data-robot": t.robot || "" });
  const name = `${taskName(t)}${t.start_node ? " at " + t.start_node : ""}`;
  g.append(el("svg:text", { x: 0, y: y + 14 }, name.length > 52 ? name.slice(0, 51) + "…" : name));
  g.append(el("svg:text", { x: label, y: y + 14, class: "gantt-state s-" + t.state }, STATE_WORDS[t.state] || t.state));
  if (t.window) {
    g.append(el("svg:rect", { x: x(t.window.release), y: y + 3, height: rowH - 6, fill: "#dde3ea",
      width: Math.max(2, x(t.window.deadline) - x(t.window.release)) }));
  }
  if (t.planned.start) {
    g.append(el("svg:rect", { x: x(t.planned.start), y: y + 5, height: rowH - 10, fill: "none", stroke: "#1d70b8",
      "stroke-width": 2, width: Math.max(3, x(t.planned.end || t.planned.start) - x(t.planned.start)) }));
  }
  if (t.actual.start) {
    const end = t.actual.end || now;
    const colour = t.state === "succeeded" ? "#2e8540" : t.state === "failed" ? "#b00020" : t.state === "cancelled" ? "#888" : "#1d70b8";
    g.append(el("svg:rect", { x: x(t.actual.start), y: y + 8, height: rowH - 16, fill: colour,
      width: Math.max(3, x(end) - x(t.actual.start)) }));
  }
  g.append(el("svg:title", {}, `${name}: ${STATE_WORDS[t.state] || t.state}${t.reason ? " (" + t.reason + ")" : ""}` +
    (t.robot && isFleet() ? `, by ${t.robot}` : "") +
    (t.planned.start ? `, planned ${clock(t.planned.start)}` : "") + (t.actual.start ? `, started ${clock(t.actual.start)}` : "")));
  return g;
}

// --- the map ------------------------------------------------------------------------------------
let edgeColours = new Map();
async function refreshEdges() {
  const e = await api("GET", "/api/v1/edges");
  edgeColours = new Map(e.edges.map((d) => [d.id, d.p]));
  drawMap();
}

function drawMap() {
  const m = view.map;
  if (!m) return;
  const box = $("#map");
  box.replaceChildren();
  const xs = m.nodes.map((n) => n.pose.x), ys = m.nodes.map((n) => n.pose.y);
  const minX = Math.min(...xs), maxX = Math.max(...xs), minY = Math.min(...ys), maxY = Math.max(...ys);
  const W = 560, H = 420, pad = 20;
  const k = Math.min((W - 2 * pad) / Math.max(1e-6, maxX - minX), (H - 2 * pad) / Math.max(1e-6, maxY - minY));
  const px = (x) => pad + (x - minX) * k, py = (y) => H - pad - (y - minY) * k;
  const at = new Map(m.nodes.map((n) => [n.name, n.pose]));
  const svg = el("svg:svg", { width: W, height: H, role: "img", "aria-label": "map" });
  for (const e of m.edges) {
    const a = at.get(e.from), b = at.get(e.to);
    const p = edgeColours.has(e.id) ? edgeColours.get(e.id) : 1;
    const line = el("svg:line", { x1: px(a.x), y1: py(a.y), x2: px(b.x), y2: py(b.y),
      stroke: `hsl(${Math.round(p * 120)}, 70%, 42%)`, "stroke-width": 2 });
    line.append(el("svg:title", {}, `${e.from} to ${e.to}: gets through ${Math.round(p * 100)} % of the time now`));
    svg.append(line);
  }
  // Each robot's route now: its path drawn over the edges, thick, in its colour (a lone robot's
  // dark blue).
  const fleet = isFleet();
  for (const robot of view.robots) {
    for (const step of robot.route || []) {
      const a = at.get(step.from), b = at.get(step.to);
      const line = el("svg:line", { class: "route", "data-robot": robot.name, x1: px(a.x), y1: py(a.y), x2: px(b.x),
        y2: py(b.y), stroke: fleet ? robotColour(robot.name) : "#1d3557", "stroke-width": 6, "stroke-opacity": 0.55,
        "stroke-linecap": "round" });
      line.append(el("svg:title", {}, `${fleet ? robot.name : "the robot"}'s way now: ${step.from} to ${step.to}`));
      svg.append(line);
    }
  }
  const targets = new Set(view.robots.filter((r) => r.current_task)
    .map((r) => (view.tasks.find((t) => t.id === r.current_task) || {}).start_node).filter(Boolean));
  for (const n of m.nodes) {
    const target = targets.has(n.name);
    const c = el("svg:circle", { cx: px(n.pose.x), cy: py(n.pose.y), r: target ? 7 : 3.5, fill: target ? "#ffbf47" : "#1d3557" });
    c.append(el("svg:title", {}, n.name));
    svg.append(c);
  }
  // One marker per robot; robots standing together are spread on a small ring so that each shows.
  const together = new Map();
  for (const robot of view.robots) {
    if (!robot.pose) continue;
    const key = `${Math.round(px(robot.pose.x))},${Math.round(py(robot.pose.y))}`;
    together.set(key, [...(together.get(key) || []), robot]);
  }
  for (const group of together.values()) {
    group.forEach((robot, i) => {
      const angle = (2 * Math.PI * i) / group.length;
      const spread = group.length > 1 ? 9 : 0;
      const cx = px(robot.pose.x) + spread * Math.cos(angle), cy = py(robot.pose.y) + spread * Math.sin(angle);
      const g = el("svg:g", { class: "robot-marker", "data-robot": robot.name });
      const dot = el("svg:circle", { class: "robot-dot", cx, cy, r: 8, fill: fleet ? robotColour(robot.name) : "#d4351c",
        stroke: "white", "stroke-width": 2 });
      if (!fleet) dot.id = "robot-dot";
      dot.append(el("svg:title", {}, `${fleet ? robot.name : "the robot"}, at ${robot.node}`));
      g.append(dot);
      if (fleet) g.append(el("svg:text", { class: "robot-label", x: cx + 10, y: cy - 8 }, robot.name));
      svg.append(g);
    });
  }
  box.append(svg);
}

// --- tasks --------------------------------------------------------------------------------------
async function refreshTasks() {
  const filter = $("#state-filter").value;
  const t = await api("GET", "/api/v1/tasks?limit=1000" + (filter ? "&state=" + filter : ""));
  view.tasks = t.tasks;
  for (const task of t.tasks) view.names.set(task.id, taskName(task));
  for (const item of document.querySelectorAll("#feed li[data-unnamed=yes]")) nameFeedItem(item);
  const body = $("#tasks tbody");
  body.replaceChildren();
  $("#tasks-robot").hidden = !isFleet();
  for (const task of t.tasks.slice().reverse()) {
    const row = el("tr", { "data-task": task.id, "data-name": taskName(task) });
    const place = task.start_node || (task.spec ? `the way that satisfies ${task.spec.formula}` : "where the robot is");
    row.append(el("td", {}, taskName(task)), el("td", {}, place));
    row.append(el("td", {}, task.window ? `${dayAndClock(task.window.release)} to ${clock(task.window.deadline)}` : "now"));
    row.append(el("td", { class: "state s-" + task.state }, STATE_WORDS[task.state] || task.state));
    row.append(el("td", { class: "reason" }, plainReason(task)));
    if (isFleet()) row.append(el("td", { class: "robot" }, task.robot || ""));
    const cell = el("td");
    if (!FINAL.has(task.state)) {
      const b = el("button", { type: "button", class: "cancel" }, "Cancel");
      b.addEventListener("click", async () => {
        if (!window.confirm(`Cancel "${taskName(task)}"?`)) return;
        try { await api("POST", `/api/v1/tasks/${encodeURIComponent(task.id)}/cancel`, { reason: "asked on the dashboard" }); showProblem(""); }
        catch (err) { showProblem(err.message); }
        refreshSoon();
      });
      cell.append(b);
    }
    row.append(cell);
    body.append(row);
  }
}

function setUpForm() {
  const select = $("#add-form select[name=place]");
  for (const name of view.map.nodes.map((n) => n.name).sort()) select.append(el("option", { value: name }, name));
  for (const field of ["from", "to"]) {
    const input = $(`#add-form input[name=${field}]`);
    input.addEventListener("input", () => { input.dataset.edited = "yes"; });
  }
  $("#zone-note").textContent = `Times are the building's local time (${view.zone}).`;
  followClock();
  $("#add-form").addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const f = new FormData(ev.target);
    const task = {
      id: "web-" + Date.now().toString(36),
      activity: f.get("activity"),
      window: { release: new Date(fromLocalInput(f.get("from"))).toISOString(),
                deadline: new Date(fromLocalInput(f.get("to"))).toISOString() },
      duration: Number(f.get("minutes")) * 60,
      priority: Number(f.get("priority")),
      start_node: f.get("place"),
    };
    const result = $("#add-result");
    try {
      await api("POST", "/api/v1/tasks", { tasks: [task] });
      result.textContent = `Added "${task.activity}".`;
      showProblem("");
      for (const input of document.querySelectorAll("#add-form input[type=datetime-local]")) delete input.dataset.edited;
    } catch (err) {
      result.textContent = "Not added: " + err.message;
    }
    refreshSoon();
  });
}

// A command in words ("check WayPoint2 before 15:00", "cancel the check of WayPoint2"): the
// service reads it (POST /api/v1/commands) and says which word it did not understand.
function setUpSentence() {
  $('#say-form').addEventListener('submit', async (ev) => {
    ev.preventDefault();
    const text = new FormData(ev.target).get('text');
    const result = $('#say-result');
    try {
      const r = await api('POST', '/api/v1/commands', {text});
      // 200 "already queued: ..." when the same sentence was said in the same minute.
      result.textContent =
          r.message ? `Already queued: ${r.already_queued.join(', ')}.` :
          r.tasks ? `Added: ${r.tasks.map(taskName).join(', ')}.` :
          r.routines ? `Added routines: ${r.routines.map((x) => x.name).join(', ')}.` :
                       `Cancelled ${r.cancelled.length} task${r.cancelled.length === 1 ? '' : 's'}.`;
      showProblem('');
    } catch (err) {
      result.textContent = 'Not understood: ' + err.message;
    }
    refreshSoon();
  });
}

// The form's window is "from now for two hours" on the service's clock (which may run faster than
// the wall clock) until someone edits it.
function followClock() {
  const from = $("#add-form input[name=from]"), to = $("#add-form input[name=to]");
  if (!view.schedule || from.dataset.edited || to.dataset.edited) return;
  const now = serviceNow();
  from.value = toLocalInput(now);
  to.value = toLocalInput(now + 2 * 3600e3);
}

// A task's reason in words a facility manager reads: why it failed, was dropped or cancelled;
// the scheduler's own notes ("planned start ...") are left out.
function plainReason(task) {
  if (["failed", "dropped", "cancelled", "preempted"].includes(task.state)) return task.reason;
  if (task.dropped_for_now) return "not planned for now: " + task.dropped_for_now.reason;
  if (task.state === "queued" && task.planned && task.planned.start) return "planned for " + clock(task.planned.start);
  return "";
}

// --- one path's rhythm ----------------------------------------------------------------------------
async function drawRhythm() {
  const id = $("#edge-select").value;
  const box = $("#rhythm");
  box.replaceChildren();
  if (!id) return;
  const m = await api("GET", `/api/v1/edges/${encodeURIComponent(id)}/model?step_minutes=15`);
  const W = 560, H = 220, left = 40, bottom = 20;
  const n = m.points.length;
  const x = (i) => left + (i / Math.max(1, n - 1)) * (W - left - 10);
  const maxS = Math.max(1, ...m.points.map((p) => (p.quantiles_s ? p.quantiles_s.q90 : p.expected_s)));
  const yp = (p) => 10 + (1 - p) * (H - bottom - 20);
  const ys = (s) => 10 + (1 - s / maxS) * (H - bottom - 20);
  const svg = el("svg:svg", { width: W, height: H, role: "img", "aria-label": "the path over the day" });
  const line = (values, colour, dash) => el("svg:polyline", { fill: "none", stroke: colour, "stroke-width": 2,
    "stroke-dasharray": dash || "", points: values.map((v, i) => `${x(i)},${v}`).join(" ") });
  svg.append(line(m.points.map((p) => yp(p.p)), "#2e8540"));
  svg.append(line(m.points.map((p) => ys(p.expected_s)), "#1d70b8", "4 3"));
  if (m.points[0].quantiles_s) svg.append(line(m.points.map((p) => ys(p.quantiles_s.q90)), "#9bb8d8", "2 3"));
  for (let i = 0; i < n; i += 16) svg.append(el("svg:text", { x: x(i), y: H - 4 }, clock(m.points[i].time)));
  svg.append(el("svg:text", { x: 0, y: 14 }, "100 %"), el("svg:text", { x: 0, y: H - bottom - 10 }, "0 %"));
  box.append(svg);
  box.append(el("p", { class: "legend" },
    `Green: chance of getting through. Blue, dashed: expected time (up to ${Math.round(maxS)} s).` +
    (m.model === "learned" ? ` Learned from ${m.attempts} trips.` : " Nothing learned yet: an estimate from the distance.")));
}

// --- the live feed --------------------------------------------------------------------------------
// One feed line; a task not listed yet is "A task" until the next refresh of the list names it.
function nameFeedItem(item) {
  const e = item.event;
  const known = e.task_id ? view.names.get(e.task_id) : undefined;
  const robot = e.robot || e.about;
  const who = e.task_id ? (known ? `"${known}"` : "A task")
            : e.subject === "robot" ? (isFleet() && robot ? `Robot ${robot}` : "The robot") : e.subject;
  const words = EVENT_WORDS[e.event] || STATE_WORDS[e.event] || e.event;
  const why = e.reason && !QUIET_REASONS.has(e.event) ? " (" + e.reason + ")" : "";
  // In a fleet a task's event says which robot it is about.
  const by = e.task_id && isFleet() && e.robot ? ` [${e.robot}]` : "";
  item.textContent = `${dayAndClock(e.time)}: ${who} ${words}${why}${by}`;
  item.dataset.unnamed = e.task_id && !known ? "yes" : "";
}
// The browser reconnects a dropped stream by itself (with Last-Event-ID, so nothing is missed or
// repeated), but gives up when an answer is not a stream (the service restarting, say): then the
// feed is opened again after a pause, from the last event it showed.
let lastEventId = null;
function startFeed() {
  const feed = $("#feed");
  const source = new EventSource(lastEventId === null ? "/api/v1/events?tail=50" : "/api/v1/events?after=" + lastEventId);
  source.onmessage = (msg) => {
    const e = JSON.parse(msg.data);
    lastEventId = msg.lastEventId || lastEventId;
    const item = el("li", e.task_id ? { "data-task": e.task_id } : {});
    item.event = e;
    feed.prepend(item);
    nameFeedItem(item);
    while (feed.children.length > 100) feed.lastChild.remove();
    refreshSoon();
  };
  source.onerror = () => {
    showProblem("Lost the connection to the service; trying again…");
    if (source.readyState === EventSource.CLOSED) setTimeout(startFeed, 5000);
  };
  source.onopen = () => showProblem("");
}

let pending = null;
function refreshSoon() {
  if (pending) return;
  pending = setTimeout(async () => {
    pending = null;
    try { await Promise.all([refreshTasks(), refreshSchedule(), refreshRobots()]); }
    catch (err) { showProblem(err.message); }
  }, 300);
}

async function start() {
  try {
    const health = await api("GET", "/healthz");
    view.map = await api("GET", "/api/v1/map");
    await refreshSchedule();
    await refreshTasks();
    await refreshRobots();
    $("#title").textContent = `${isFleet() ? "The fleet's day" : "The robot's day"}: ${health.deployment}`;
    if (isFleet()) $("#map-title").textContent = "Where the robots are";
    await refreshEdges();
    setUpForm();
    setUpSentence();
    const edges = $("#edge-select");
    for (const e of view.map.edges) edges.append(el("option", { value: e.id }, `${e.from} to ${e.to}`));
    edges.addEventListener("change", () => drawRhythm().catch((err) => showProblem(err.message)));
    await drawRhythm();
    $("#state-filter").addEventListener("change", () => refreshTasks().catch((err) => showProblem(err.message)));
    startFeed();
    setInterval(() => refreshRobots().catch((err) => showProblem(err.message)), 2000);
    // The feed refreshes the lists as events come; this catches what a dropped stream missed.
    setInterval(refreshSoon, 10000);
    setInterval(() => refreshEdges().catch((err) => showProblem(err.message)), 60000);
  } catch (err) {
    showProblem("The service does not answer: " + err.message);
  }
}

start();
