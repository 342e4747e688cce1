// teleo view: the page. Frames arrive as server-sent events ("frame", "status"); the
// timeline asks for past cycles at /api/frame?cycle=N. One agent is shown at a time (the
// tabs); panel.js draws its panel, world.js the world. Following a live launch, the timeline's
// pause, step and resume ask its world at /api/control, as `teleo pause`, `step-run` and
// `resume` do, and show the world's verdict.
"use strict";

const $ = (id) => document.getElementById(id);
const STATUS_COLOURS = { satisfied: "#3a9a48", active: "#2f6fd6", suspended: "#e59a1d",
  impasse: "#d23c3c", failed: "#222", pending: "#c9c9c9", cancelled: "#bbb" };
const STATES = { waiting: "waiting", live: "live", ended: "run ended", record: "record",
  offline: "view offline" };
const RENDER_MS = 1000; // the domain's own picture at most once a second
const ROW = 11, LABEL_W = 90; // timeline: row height, label width [px]
const view = { live: true, map: null, mapId: "", frame: null, status: null, agent: null,
  online: false, lastRender: -Infinity, renderTimer: null };

async function ensureMap(frame) {
  if (frame.map_id && frame.map_id !== view.mapId) {
    view.mapId = frame.map_id;
    view.map = await (await fetch("/api/map")).json();
  }
}

async function show(frame) {
  if (!frame) return;
  view.frame = frame;
  await ensureMap(frame);
  document.body.dataset.cycle = frame.cycle;
  $("clock").textContent = `cycle ${frame.cycle}, t = ${frame.time.toFixed(1)} s`;
  const names = Object.keys(frame.agents);
  if (!names.includes(view.agent)) view.agent = names[0] || null;
  drawTabs(names);
  drawMap();
  markPicture($("render"), frame.cycle);
  const a = view.agent && frame.agents[view.agent];
  $("panel").replaceChildren(a ? agentPanel(view.agent, a) : el("p", "hint", "no agent yet"));
  if (!view.live) $("slider").value = frame.cycle;
  showAt();
  drawStrip();
}

function drawTabs(names) {
  const tabs = $("tabs");
  tabs.hidden = names.length < 2;
  if (tabs.dataset.names !== names.join(" ")) {
    tabs.dataset.names = names.join(" ");
    tabs.replaceChildren(...names.map((n) => {
      const b = el("button", "", n);
      b.dataset.agent = n;
      b.addEventListener("click", () => { view.agent = n; view.lastRender = -Infinity; show(view.frame); });
      return b;
    }));
  }
  for (const b of tabs.children) b.classList.toggle("on", b.dataset.agent === view.agent);
  if (view.agent) $("graph").href = "/api/graph.svg?agent=" + encodeURIComponent(view.agent);
}

function drawMap() {
  // the page draws driving and blocks itself; any other domain is its own PNG, fetched at
  // most once a second and always for the newest frame shown (a trailing redraw)
  const frame = view.frame;
  if (!frame || !view.map) return;
  const wait = view.map.drawn ? 0 : view.lastRender + RENDER_MS - performance.now();
  if (wait <= 0) {
    view.lastRender = performance.now();
    drawWorld($("map"), $("render"), view.map, frame, view.agent, named(frame.agents[view.agent]));
  } else if (!view.renderTimer) {
    view.renderTimer = setTimeout(() => { view.renderTimer = null; drawMap(); }, wait);
  }
}

function named(agent) {
  // the ids in the beliefs that make the agent's goals false (a pedestrian, a car)
  const ids = new Set(), walk = (clauses) => clauses.forEach((c) => {
    (c.because || []).forEach((h) => h.belief.slice(1, -1).split(" ").slice(1).forEach((a) => ids.add(a)));
    walk(c.below || []);
  });
  ((agent && agent.why && agent.why.goals) || []).forEach((g) => walk(g.clauses));
  return ids;
}

function runState() {
  if (!view.online) return "offline";
  return view.status ? view.status.state : "waiting";
}

function showAt() {
  const state = runState(), f = view.frame;
  const following = view.live && (state === "live" || state === "waiting");
  $("live").textContent = state === "record" || state === "ended" ? "last" : "live";
  if (f) $("at").textContent = following ? `live, cycle ${f.cycle}` : `cycle ${f.cycle}`;
}

function showState() {
  const state = runState(), badge = $("state");
  badge.dataset.state = state;
  badge.textContent = STATES[state] || state;
  badge.title = state === "offline" ? "the view server does not answer"
    : view.status ? view.status.state_note : "";
  showAt();
}

function niceStep(span, most) {
  // the smallest of 1, 2, 5 x 10^k cycles that gives at most `most` ticks over `span`
  for (let p = 1; ; p *= 10) for (const m of [1, 2, 5]) if (span / (m * p) <= most) return m * p;
}

function drawAxis(first, last, x, width) {
  // cycle labels under the strip, as DOM elements (readable and selectable)
  const axis = $("axis"), step = niceStep(Math.max(1, last - first), Math.max(2, Math.floor(width / 70)));
  const ticks = [el("span", "unit", "cycle")];
  for (let c = Math.ceil(first / step) * step; c <= last; c += step) {
    if (x(c) < LABEL_W + 10) continue;
    const t = el("span", "tick", String(c));
    t.dataset.cycle = c;
    t.style.left = `${x(c)}px`;
    ticks.push(t);
  }
  axis.replaceChildren(...ticks);
}

function stripScale() {
  const st = view.status, c = $("strip");
  const span = Math.max(1, st.last - st.first);
  return (cycle) => LABEL_W + ((cycle - st.first) / span) * (c.width - LABEL_W - 4);
}

function drawStrip() {
  // each goal's status over the cycles held, one row per goal; a line at the shown cycle
  const st = view.status, c = $("strip");
  if (!st || st.first === null) return;
  const rows = [];
  for (const [agent, goals] of Object.entries(st.goals))
    for (const [gid, changes] of Object.entries(goals)) rows.push([`${agent} ${gid}`, changes]);
  c.width = c.clientWidth || 800;
  c.height = Math.max(14, rows.length * ROW + 4);
  const ctx = c.getContext("2d"), x = stripScale();
  ctx.clearRect(0, 0, c.width, c.height);
  ctx.font = "9px sans-serif";
  rows.forEach(([label, changes], i) => {
    ctx.fillStyle = "#333";
    ctx.fillText(label, 2, i * ROW + 10);
    changes.forEach((ch, k) => {
      const end = k + 1 < changes.length ? changes[k + 1].cycle : st.last + 1;
      ctx.fillStyle = STATUS_COLOURS[ch.status] || "#888";
      const from = x(Math.max(ch.cycle, st.first));
      ctx.fillRect(from, i * ROW + 2, Math.max(1, x(end) - from), 9);
    });
  });
  if (view.frame) {
    ctx.fillStyle = "#000";
    ctx.fillRect(x(view.frame.cycle), 0, 1.5, c.height);
  }
  drawAxis(st.first, st.last, x, c.width);
}

function showStatus(st) {
  view.status = st;
  $("run").textContent = st.run ? `run ${st.run}` : "waiting for a run";
  $("source").textContent = st.source;
  const slider = $("slider");
  if (st.first !== null) {
    slider.min = st.first;
    slider.max = st.last;
    if (view.live) slider.value = st.last;
  }
  const procs = $("procs");
  procs.innerHTML = "<tr><th>process</th><th>up</th><th>appeared</th><th>cycle</th><th>compute ms</th><th>late</th></tr>";
  for (const p of st.processes) {
    const up = p.up === null ? "-" : p.up ? "up" : "GONE";
    const tr = el("tr", p.up === false ? "gone" : "");
    [p.name, up, p.appeared, p.cycle ?? "-", p.compute_ms === undefined ? "-" : p.compute_ms.toFixed(2),
      p.late ?? "-"].forEach((v) => tr.append(el("td", "", v)));
    procs.append(tr);
  }
  const keys = $("keys");
  keys.innerHTML = "<tr><th>key</th><th>msgs</th><th>rate /s</th><th>bytes</th></tr>";
  for (const k of st.keys) {
    const tr = el("tr");
    [k.key, k.count, k.rate || "-", k.bytes || "-"].forEach((v) => tr.append(el("td", "", v)));
    keys.append(tr);
  }
  $("hold").hidden = !st.control;
  showState();
  drawStrip();
}

async function control(op) {
  const held = $("held");
  held.textContent = "asking the world...";
  held.className = "";
  try {
    const r = await fetch("/api/control", { method: "POST",
      headers: { "Content-Type": "application/json" }, body: JSON.stringify({ op }) });
    const said = await r.json();
    held.textContent = said.ok ? said.text : said.error;
    held.className = said.ok ? "" : "refused";
    held.dataset.cycle = said.ok ? said.outcome.cycle : "";
    held.dataset.paused = said.ok ? said.outcome.paused : "";
  } catch (e) {
    held.textContent = `no answer from the view: ${e}`;
    held.className = "refused";
  }
}

async function goTo(cycle) {
  view.live = false;
  $("live").classList.remove("on");
  const r = await fetch(`/api/frame?cycle=${cycle}`);
  if (r.ok) await show(await r.json());
}

function connect() {
  const events = new EventSource("/events");
  events.onopen = () => { view.online = true; showState(); };
  events.onerror = () => { view.online = false; showState(); };
  events.addEventListener("frame", (e) => { if (view.live) show(JSON.parse(e.data)); });
  events.addEventListener("status", (e) => { view.online = true; showStatus(JSON.parse(e.data)); });
}

$("slider").addEventListener("input", (e) => goTo(+e.target.value));
$("back").addEventListener("click", () => view.frame && goTo(view.frame.cycle - 1));
$("fwd").addEventListener("click", () => view.frame && goTo(view.frame.cycle + 1));
$("live").addEventListener("click", async () => {
  view.live = true;
  $("live").classList.add("on");
  const r = await fetch("/api/frame");
  if (r.ok) await show(await r.json());
});
for (const op of ["pause", "step", "resume"]) $(op).addEventListener("click", () => control(op));
$("strip").addEventListener("click", (e) => {
  const st = view.status, c = $("strip");
  if (!st || st.first === null || e.offsetX < LABEL_W) return;
  const span = Math.max(1, st.last - st.first);
  goTo(Math.round(st.first + ((e.offsetX - LABEL_W) / (c.width - LABEL_W - 4)) * span));
});
document.addEventListener("keydown", (e) => {
  if (e.key === "ArrowLeft") $("back").click();
  if (e.key === "ArrowRight") $("fwd").click();
});
window.addEventListener("resize", () => { if (view.map && view.map.drawn) drawMap(); drawStrip(); });
connect();
