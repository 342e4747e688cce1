// teleo view: one agent's panel for the cycle shown: its goal table (the goals that failed
// before that cycle too, with their reason), its actions, the beliefs panel (why each
// unsatisfied goal is false, what the skill path depends on: tools/view/beliefs.py) and the
// decision tree (tools/tree.py to_json), drawn as nested lists.
"use strict";

const MARKS = { satisfied: "[o]", active: "[*]", suspended: "[~]", impasse: "[!]",
  failed: "[x]", pending: "[ ]", skipped: "[-]" };

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
function list(items) {
  const ul = el("ul");
  items.forEach((i) => ul.append(i));
  return ul;
}

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
    const ul = list(node.children.filter((c) => !passed.includes(c)).map(treeNode));
    if (passed.length) {
      const details = el("details", "passed");
      details.append(el("summary", "", `${passed.length} skill${passed.length > 1 ? "s" : ""} passed over`));
      details.append(list(passed.map(treeNode)));
      const item = el("li");
      item.append(details);
      ul.append(item);
    }
    li.append(ul);
  }
  return li;
}

function goalTable(goals) {
  const table = el("table", "goals");
  table.append(Object.assign(el("tr"), { innerHTML: "<th>status</th><th>id</th><th>goal</th><th>p</th><th>note</th>" }));
  for (const g of goals) {
    const ended = g.failed_at !== undefined;
    const tr = el("tr", "goal" + (ended ? " ended" : ""));
    tr.dataset.id = g.id;
    tr.dataset.status = g.status;
    const st = el("td");
    st.append(el("span", `status s-${g.status}`, g.status));
    const note = ended ? `failed at cycle ${g.failed_at}: ${g.note}` : g.note;
    tr.append(st, el("td", "id", g.id), el("td", "", g.goal), el("td", "", g.priority),
      el("td", "note", note));
    table.append(tr);
  }
  return table;
}

function holdsBelief(h) {
  // a belief that holds, with the percepts (values included) and relations behind it
  const li = el("li", "because");
  const b = el("span", "belief", h.belief);
  b.dataset.belief = h.belief;
  li.append(b);
  if (h.clause) li.append(" ", el("span", "where", `by ${h.clause}`));
  const from = [...h.percepts.map((p) => el("span", "percept", p)),
    ...h.relations.map((r) => el("span", "", r))];
  if (from.length) {
    li.append(" <- ");
    from.forEach((f, i) => li.append(...(i ? [" ", f] : [f])));
  }
  if (h.note) li.append(" ", el("span", "note", h.note));
  return li;
}

function failure(c) {
  // one clause of a concept and the first of its conditions that fails, with why
  const li = el("li", "clause");
  li.append(el("span", "", `${c.clause}: `), el("span", "cond", c.cond || "-"), " ");
  const kids = [];
  if (c.kind === "negated") {
    li.append(el("span", "no", "fails: it holds for"));
    kids.push(...c.because.map(holdsBelief));
    if (c.more) kids.push(el("li", "note", `... ${c.more} more`));
  } else if (c.kind === "missing") {
    li.append(el("span", "no", "does not hold"));
    kids.push(...(c.below || []).map(failure));
  } else if (c.kind === "unseen") {
    li.append(el("span", "no", c.seen.length ? "no percept matches; seen:" : "no such percept"));
    kids.push(...c.seen.map((p) => el("li", "percept", p)));
  } else if (c.kind === "test") {
    li.append(el("span", "no", "is false"), " ", el("span", "bind", bindings(c.values)));
  } else li.append(el("span", "note", c.note || ""));
  if (c.every) li.append(" ", el("span", "note", "(for every match)"));
  if (kids.length) li.append(list(kids));
  return li;
}

function need(n) {
  // a :start or :requires condition of a skill on the path, under the path's bindings
  const li = el("li", "need");
  const mark = n.holds === null ? ["note", "?"] : n.holds ? ["yes", "holds"] : ["no", "does not hold"];
  li.append(el("span", "", `${n.part}: `), el("span", "cond", n.cond), " ", el("span", mark[0], mark[1]));
  if (n.values && Object.keys(n.values).length) li.append(" ", el("span", "bind", bindings(n.values)));
  if (n.note) li.append(" ", el("span", "note", n.note));
  if (n.because.length) li.append(list(n.because.map(holdsBelief)));
  return li;
}

function beliefsPanel(w) {
  const box = el("div", "beliefs");
  if (!w) {
    box.append(el("p", "hint", "no beliefs recorded for this cycle"));
    return box;
  }
  if (w.error) box.append(el("p", "warn", w.error));
  if (w.warning) box.append(el("p", "warn", w.warning));
  box.append(el("h3", "", "why not satisfied"));
  if (!w.goals.length) box.append(el("p", "hint", "no goal of this cycle's decision is unsatisfied"));
  for (const g of w.goals) {
    const li = el("li", "why-goal");
    li.dataset.id = g.id;
    li.append(el("span", `status s-${g.status}`, g.status), ` ${g.id} `, el("span", "cond", g.instance));
    if (g.note) li.append(" ", el("span", "note", g.note));
    li.append(list(g.clauses.map(failure)));
    box.append(list([li]));
  }
  if (w.path.length) {
    box.append(el("h3", "", "the skill path depends on"));
    box.append(list(w.path.map((s) => {
      const li = el("li", "step");
      li.append(`${s.goal_id}: ${s.skill} `, el("span", "where", `[${s.mode}] for ${s.goal}`));
      if (s.note) li.append(" ", el("span", "note", s.note));
      else if (!s.needs.length) li.append(" ", el("span", "note", "(no :start or :requires)"));
      if (s.needs.length) li.append(list(s.needs.map(need)));
      return li;
    })));
  }
  const all = el("details", "all");
  const more = w.count > w.beliefs.length ? ` (the first ${w.beliefs.length})` : "";
  all.append(el("summary", "", `all ${w.count} beliefs${more}`),
    list(w.beliefs.map((b) => el("li", "", b))));
  box.append(all);
  if (w.program) box.append(el("p", "note", `reasons from ${w.program}`));
  return box;
}

function agentPanel(name, a) {
  const box = el("div", "agent");
  box.dataset.agent = name;
  box.append(el("h2", "", name));
  const self = Object.entries(a.self || {}).map(([k, v]) => `${k} ${fmt(v)}`).join(", ");
  if (self) box.append(el("div", "self", "self: " + self));
  box.append(goalTable(a.goals));
  box.append(el("div", "actions", "actions: " + (a.actions.map(action).join(" ") || "none")));
  box.append(beliefsPanel(a.why));
  box.append(el("h3", "", "decision"));
  const tree = el("div", "tree");
  if (a.tree) tree.append(list([treeNode(a.tree)]));
  else tree.append(el("p", "hint", "no decision recorded for this cycle"));
  box.append(tree);
  return box;
}
