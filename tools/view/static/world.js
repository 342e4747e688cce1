// teleo view: drawing a world on a canvas from a frame's snapshot and the run's static map
// (tools/view/scene.py), domain by domain. Units: metres in the world, y up.
"use strict";

const COLOURS = {
  grass: "#c4deb4", walk: "#d6d6d0", road: "#4e5056", yellow: "#f6c828", white: "#f0f0f0",
  building: "#ceaa7e", outline: "#785a3c", ped: "#008c78", down: "#dc1e1e",
  traffic: "#3c6ec8", agent: "#f58214", me: "#d01f1f", trail: "#e0303080",
  pkg: "#9628aa", delivered: "#1ea03c", table: "#8b6b4a", floor: "#e8e2d6", named: "#7a1f8f",
};
const BLOCK_COLOURS = ["#d9534f", "#5b8def", "#4cae4c", "#f0ad4e", "#8e6bbf", "#2bb5b5"];

function fitCanvas(canvas, x0, y0, x1, y1) {
  // size the canvas to the largest box of the world box's aspect that its section holds
  // (so the whole world is in the window), and return the world -> canvas transform
  const box = canvas.parentElement, w = x1 - x0, h = y1 - y0;
  const s = Math.min(box.clientWidth / w, (box.clientHeight || box.clientWidth) / h);
  canvas.width = Math.max(40, Math.floor(w * s));
  canvas.height = Math.max(40, Math.floor(h * s));
  return fitView(canvas, x0, y0, x1, y1);
}

function fitView(canvas, x0, y0, x1, y1) {
  // world box -> canvas transform keeping the aspect ratio
  const s = Math.min(canvas.width / (x1 - x0), canvas.height / (y1 - y0));
  return { s, p: (x, y) => [(x - x0) * s, (y1 - y) * s] };
}

function strokeLine(ctx, v, a, b, colour, widthM, dash) {
  ctx.strokeStyle = colour;
  ctx.lineWidth = Math.max(1, widthM * v.s);
  ctx.setLineDash(dash ? dash.map((d) => d * v.s) : []);
  ctx.beginPath();
  ctx.moveTo(...v.p(a[0], a[1]));
  ctx.lineTo(...v.p(b[0], b[1]));
  ctx.stroke();
  ctx.setLineDash([]);
}

function offset(seg, lateral) {
  // the segment's axis moved sideways by `lateral` metres (+ = left of a -> b)
  const dx = seg.b[0] - seg.a[0], dy = seg.b[1] - seg.a[1];
  const n = Math.hypot(dx, dy) || 1, ox = (-dy / n) * lateral, oy = (dx / n) * lateral;
  return [[seg.a[0] + ox, seg.a[1] + oy], [seg.b[0] + ox, seg.b[1] + oy]];
}

function box(ctx, v, x, y, headingDeg, length, width, fill, minPx = 0) {
  // a rotated rectangle (a car, a block), at least minPx long so a small one stays visible
  const [px, py] = v.p(x, y), k = Math.max(v.s, minPx / length);
  ctx.save();
  ctx.translate(px, py);
  ctx.rotate((-headingDeg * Math.PI) / 180);
  ctx.fillStyle = fill;
  ctx.fillRect((-length / 2) * k, (-width / 2) * k, length * k, width * k);
  ctx.restore();
}

function drawDriving(canvas, map, frame, focus, named) {
  const ctx = canvas.getContext("2d"), m = 30;
  const v = fitCanvas(canvas, -m, -m, map.size[0] + m, map.size[1] + m);
  ctx.fillStyle = COLOURS.grass;
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  for (const seg of map.segments) strokeLine(ctx, v, seg.a, seg.b, COLOURS.walk, 2 * map.sidewalk);
  for (const seg of map.segments) strokeLine(ctx, v, seg.a, seg.b, COLOURS.road, 2 * map.road_half);
  for (const seg of map.segments) {
    strokeLine(ctx, v, seg.a, seg.b, COLOURS.yellow, 0.3);
    for (const lat of [map.lane_width, -map.lane_width]) {
      const [a, b] = offset(seg, lat);
      strokeLine(ctx, v, a, b, COLOURS.white, 0.2, [3, 3]);
    }
  }
  ctx.font = `${Math.max(9, 3 * v.s)}px sans-serif`;
  ctx.textAlign = "center";
  const curb = {};
  for (const b of map.buildings) {
    ctx.fillStyle = COLOURS.building;
    ctx.strokeStyle = COLOURS.outline;
    ctx.beginPath();
    b.corners.forEach((c, i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, ...v.p(c[0], c[1])));
    ctx.closePath();
    ctx.fill();
    ctx.stroke();
    const cx = b.corners.reduce((s, c) => s + c[0], 0) / 4;
    const cy = b.corners.reduce((s, c) => s + c[1], 0) / 4;
    ctx.fillStyle = "#333";
    ctx.fillText(`${b.address} ${b.street}`, ...v.p(cx, cy));
    curb[`${b.street} ${b.address}`] = b.curb;
  }
  const w = frame.world;
  for (const pkg of w.packages || []) {
    const c = curb[`${pkg.street} ${pkg.address}`];
    if (!c) continue;
    const [x, y] = v.p(c[0], c[1]), r = Math.max(4, 2.5 * v.s);
    ctx.fillStyle = pkg.delivered ? COLOURS.delivered : COLOURS.pkg;
    ctx.beginPath();
    ctx.moveTo(x, y - r); ctx.lineTo(x + r, y); ctx.lineTo(x, y + r); ctx.lineTo(x - r, y);
    ctx.fill();
    ctx.fillText(pkg.id, x, y - r - 2);
  }
  for (const [agent, pts] of Object.entries(frame.trails || {})) {
    if (pts.length < 2) continue;
    ctx.strokeStyle = agent === focus ? COLOURS.me : COLOURS.agent;
    ctx.lineWidth = 2;
    ctx.beginPath();
    pts.forEach((p, i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, ...v.p(p[0], p[1])));
    ctx.stroke();
  }
  for (const p of w.pedestrians || []) {
    const [x, y] = v.p(p.x, p.y), r = Math.max(3, 0.8 * v.s);
    ctx.fillStyle = p.mode === "down" ? COLOURS.down : COLOURS.ped;
    ctx.beginPath();
    ctx.arc(x, y, r, 0, 2 * Math.PI);
    ctx.fill();
    if (named.has(p.id)) ring(ctx, x, y, r + 4, p.id);
  }
  for (const car of w.cars || []) {
    // a car off the drawn map (a record made before the world kept cars in the city) is
    // drawn at the map's edge, marked "off map" (issue 31, N18)
    const cx = Math.min(Math.max(car.x, -m), map.size[0] + m);
    const cy = Math.min(Math.max(car.y, -m), map.size[1] + m);
    const off = cx !== car.x || cy !== car.y, c = { ...car, x: cx, y: cy };
    const colour = c.kind !== "agent" ? COLOURS.traffic : c.id === focus ? COLOURS.me : COLOURS.agent;
    box(ctx, v, c.x, c.y, c.heading, 4.6, 2.0, colour, 11);
    if (named.has(c.id) && c.id !== focus) ring(ctx, ...v.p(c.x, c.y), 10, c.id);
    if (c.kind === "agent") {
      ctx.fillStyle = "#111";
      const [x, y] = v.p(c.x, c.y);
      const where = off ? ` (off map at ${car.x.toFixed(0)}, ${car.y.toFixed(0)})` : "";
      ctx.fillText(`${c.id} ${c.speed.toFixed(1)} m/s${where}`, x, y - 8);
    }
  }
}

function ring(ctx, x, y, r, label) {
  // an object the beliefs panel names (why a goal is not satisfied): circled and labelled
  ctx.strokeStyle = COLOURS.named;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.stroke();
  ctx.fillStyle = COLOURS.named;
  ctx.fillText(label, x, y + r + 11);  // below: a car's label is above it
}

function drawBlocks(canvas, map, frame, focus) {
  const ctx = canvas.getContext("2d"), t = map.table, w = frame.world;
  const lo = -t.pitch / 2, hi = (t.columns - 0.5) * t.pitch;
  const top = Math.max(t.height + 8, ...(w.blocks || []).map((b) => b.y + b.height),
    ...(w.hands || []).map((h) => h.y + 2));
  const v = fitCanvas(canvas, lo - 3, -1, hi + 3, top + 1);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = COLOURS.floor;
  ctx.fillRect(...v.p(lo - 3, 0), canvas.width, canvas.height);
  ctx.fillStyle = COLOURS.table;
  const [tx, ty] = v.p(lo, t.height);
  ctx.fillRect(tx, ty, (hi - lo) * v.s, t.height * v.s);
  ctx.font = `${Math.max(10, 0.7 * v.s)}px sans-serif`;
  ctx.textAlign = "center";
  ctx.textBaseline = "middle";
  (w.blocks || []).forEach((b, i) => {
    box(ctx, v, b.x, b.y, b.angle || 0, b.width, b.height, BLOCK_COLOURS[i % BLOCK_COLOURS.length]);
    ctx.fillStyle = "#fff";
    ctx.fillText(b.name, ...v.p(b.x, b.y));
  });
  for (const h of w.hands || []) {
    const [x, y] = v.p(h.x, h.y);
    ctx.strokeStyle = h.agent === focus ? COLOURS.me : "#444";
    ctx.lineWidth = 3;
    ctx.beginPath();
    ctx.moveTo(x, 0); ctx.lineTo(x, y - 0.6 * v.s);
    ctx.moveTo(x - 1.1 * v.s, y); ctx.lineTo(x - 1.1 * v.s, y - 0.6 * v.s);
    ctx.lineTo(x + 1.1 * v.s, y - 0.6 * v.s); ctx.lineTo(x + 1.1 * v.s, y);
    ctx.stroke();
    ctx.fillStyle = "#111";
    ctx.fillText(`${h.agent} ${h.holding ? "holds " + h.holding : "empty"}`, x, y - 1.3 * v.s);
  }
}

const DRAWERS = { driving: drawDriving, blocks: drawBlocks };

function drawWorld(canvas, img, map, frame, focus, named = new Set()) {
  // a domain whose map is "drawn" (its Domain has a scene hook, tools/view/scene.py) and that
  // the page has a drawer for is drawn here; any other is the domain's own PNG (server-side).
  // `named`: ids of the objects the beliefs panel names, marked on the map
  const draw = map && map.drawn && DRAWERS[map.domain];
  canvas.hidden = !draw;
  img.hidden = !!draw;
  if (draw) draw(canvas, map, frame, focus, named);
  else if (frame) {
    img.onload = () => {
      img.dataset.shown = new URL(img.currentSrc).searchParams.get("cycle");
      markPicture(img, document.body.dataset.cycle);
    };
    img.src = `/api/render.png?cycle=${frame.cycle}&agent=${encodeURIComponent(focus || "")}`;
  }
}

function markPicture(img, cycle) {
  // the domain's own picture is fetched at most once a second and takes a while to draw:
  // until the one of the cycle shown has loaded, the older one is dimmed and says whose
  // cycle it is, never passing for the cycle in the header (issue 31, N17)
  const stale = !img.hidden && img.dataset.shown !== undefined && img.dataset.shown !== String(cycle);
  img.classList.toggle("stale", stale);
  img.title = stale ? `picture of cycle ${img.dataset.shown}; cycle ${cycle} is being drawn` : "";
}
