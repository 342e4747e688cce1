// teleo view: the page. Frames arrive as server-sent events ("frame", "status"); the
// timeline asks for past cycles at /api/frame?cycle=N. The decision tree arrives as nodes
// (tools/tree.py to_json) and is drawn here as nested lists.
"use strict";

const $ = (id) => document.getElementById(id);
const STATUS_COLOURS = { satisfied: "#3a9a48", active: "#2f6fd6", suspended: "#e59a1d",
  impasse: "#d23c3c", failed: "#222", pending: "#c9c9c9" };
const MARKS = { satisfied: "[o]", active: "[*]", suspended: "[~]", impasse: "[!]",
  failed: "[x]", pending: "[ ]", skipped: "[-]" };
const view = { live: true, map: null, mapId: "", frame: null, status: null, lastRender: 0 };

function el(tag, cls, text) {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

function fmt(v) { return typeof v === "number" && !Number.isInteger(v) ? +v.toFixed(3) : v; }
function bindings(b) {
  const pairs = Object.entries(b || {});
  return pairs.length ? "{" + pairs.map(([k, v]) => `?${k}=${fmt(v)}`).join(", ") + "}" : "";
}
function action(a) { return "(" + a.map(fmt).join(" ") + ")"; }

function treeNode(node) {
  // one node of tools/tree.py's JSON: mark, label, bindings, where, note; children nested
  const li = el("li", node.kind + (node.tip ? " tip" : ""));
  const mark = node.tip ? "=> " : MARKS[node.status] ? MARKS[node.status] + " " : "";
  li.append(el("span", "label", mark + node.label));
  if (Object.keys(node.bindings).length) li.append(" ", el("span", "bind", bindings(node.bindings)));
  if (node.where) li.append(" ", el("span", "where", `(${node.where})`));
  if (node.note) li.append(" ", el("span", "note", (node.kind === "passed" ? ": " : "-- ") + node.note));
  if (node.children.length) {
    // skills passed over by a goal that does not act are folded (click to open)
    const fold = node.kind === "goal" && node.status !== "active";
    const passed = node.children.filter((c) => fold && c.kind === "passed");
    const ul = el("ul");
    node.children.filter((c) => !passed.includes(c)).forEach((c) => ul.append(treeNode(c)));
    if (passed.length) {
      const details = el("details", "passed");
      details.append(el("summary", "", `${passed.length} skill${passed.length > 1 ? "s" : ""} passed over`));
      const inner = el("ul");
      passed.forEach((c) => inner.append(treeNode(c)));
      details.append(inner);
      const item = el("li");
      item.append(details);
      ul.append(item);
    }
    li.append(ul);
  }
  return li;
}

function agentPanel(name, a) {
  const box = el("div", "agent");
  box.dataset.agent = name;
  box.append(el("h2", "", name));
  const self = Object.entries(a.self || {}).map(([k, v]) => `${k} ${fmt(v)}`).join(", ");
  if (self) box.append(el("div", "self", "self: " + self));
  const table = el("table", "goals");
  table.append(Object.assign(el("tr"), { innerHTML: "<th>status</th><th>id</th><th>goal</th><th>p</th><th>note</th>" }));
  for (const g of a.goals) {
    const tr = el("tr", "goal");
    tr.dataset.id = g.id;
    tr.dataset.status = g.status;
    const st = el("td");
    st.append(el("span", `status s-${g.status}`, g.status));
    tr.append(st, el("td", "id", g.id), el("td", "", g.goal), el("td", "", g.priority),
      el("td", "note", g.note));
    table.append(tr);
  }
  box.append(table);
  box.append(el("div", "actions", "actions: " + (a.actions.map(action).join(" ") || "none")));
  const tree = el("div", "tree");
  if (a.tree) {
    const ul = el("ul");
    ul.append(treeNode(a.tree));
    tree.append(ul);
  } else tree.append(el("p", "hint", "no decision recorded for this cycle"));
  box.append(tree);
  return box;
}

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
  const focus = Object.keys(frame.agents)[0];
  const now = performance.now();
  if (view.map && (view.map.drawn || now - view.lastRender > 1000)) {
    view.lastRender = now;
    drawWorld($("map"), $("render"), view.map, frame, focus);
  }
  const agents = $("agents");
  agents.replaceChildren(...Object.entries(frame.agents).map(([n, a]) => agentPanel(n, a)));
  if (!view.live) $("slider").value = frame.cycle;
  $("at").textContent = view.live ? `live, cycle ${frame.cycle}` : `cycle ${frame.cycle}`;
  drawStrip();
}

function drawStrip() {
  // each goal's status over the cycles held, one row per goal; a line at the shown cycle
  const st = view.status, c = $("strip");
  if (!st || st.first === null) return;
  const rows = [];
  for (const [agent, goals] of Object.entries(st.goals))
    for (const [gid, changes] of Object.entries(goals)) rows.push([`${agent} ${gid}`, changes]);
  c.width = c.clientWidth || 800;
  c.height = Math.max(30, rows.length * 11 + 4);
  const ctx = c.getContext("2d"), span = Math.max(1, st.last - st.first), lw = 90;
  const x = (cycle) => lw + ((cycle - st.first) / span) * (c.width - lw - 4);
  ctx.clearRect(0, 0, c.width, c.height);
  ctx.font = "9px sans-serif";
  rows.forEach(([label, changes], i) => {
    ctx.fillStyle = "#333";
    ctx.fillText(label, 2, i * 11 + 10);
    changes.forEach((ch, k) => {
      const end = k + 1 < changes.length ? changes[k + 1].cycle : st.last + 1;
      ctx.fillStyle = STATUS_COLOURS[ch.status] || "#888";
      const from = x(Math.max(ch.cycle, st.first));
      ctx.fillRect(from, i * 11 + 2, Math.max(1, x(end) - from), 9);
    });
  });
  if (view.frame) {
    ctx.fillStyle = "#000";
    ctx.fillRect(x(view.frame.cycle), 0, 1.5, c.height);
  }
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
  drawStrip();
}

async function goTo(cycle) {
  view.live = false;
  $("live").classList.remove("on");
  const r = await fetch(`/api/frame?cycle=${cycle}`);
  if (r.ok) await show(await r.json());
}

function connect() {
  const events = new EventSource("/events");
  events.onopen = () => { $("conn").textContent = "connected"; $("conn").classList.add("up"); };
  events.onerror = () => { $("conn").textContent = "offline"; $("conn").classList.remove("up"); };
  events.addEventListener("frame", (e) => { if (view.live) show(JSON.parse(e.data)); });
  events.addEventListener("status", (e) => showStatus(JSON.parse(e.data)));
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
document.addEventListener("keydown", (e) => {
  if (e.key === "ArrowLeft") $("back").click();
  if (e.key === "ArrowRight") $("fwd").click();
});
connect();
