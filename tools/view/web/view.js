// The live view's page: one strip chart per recorded signal over the run's whole span (a min/max envelope per
// bucket, so every peak shows), the scene's limits as lines, the controller's status and safe state, the rates,
// and at the end the report's figures beside their predictions. It only listens: nothing is ever sent.
"use strict";

const state = {
  meta: null,          // the server's first message
  buckets: new Map(),  // bucket index -> {t0, t1, n, lo, hi, lo_first}
  latest: null,
  ended: false,
  report: null,
  charts: [],          // {signal, index, plot, el}
  refused: false,
  messages: 0,
  pendingPanels: null,
};
window.gyrostabView = state;  // read by the browser test (tests/browser/)

const $ = (id) => document.getElementById(id);
const token = new URLSearchParams(location.search).get("token") || "";

function fmt(v, digits = 4) {
  if (v === null || v === undefined) return "—";
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v) && Math.abs(v) < 1e15) return String(v);
  if (v !== 0 && (Math.abs(v) >= 1e5 || Math.abs(v) < 1e-3)) return v.toExponential(digits - 1);
  return Number(v.toPrecision(digits)).toString();
}
function label(s) { return s.unit ? `${s.name} [${s.unit}]` : s.name; }
function setList(el, rows) {
  el.replaceChildren();
  for (const [k, v] of rows) {
    const dt = document.createElement("dt"); dt.textContent = k;
    const dd = document.createElement("dd"); dd.textContent = v;
    el.append(dt, dd);
  }
}

// Horizontal lines at ±limit for the limits placed on this signal; a limit far outside the data is a note.
function limitHook(chart) {
  return (u) => {
    const ctx = u.ctx;
    const [ymin, ymax] = [u.scales.y.min, u.scales.y.max];
    ctx.save();
    ctx.lineWidth = 1.5 * devicePixelRatio;
    for (const l of chart.limits) {
      ctx.strokeStyle = l.label.includes("soft") ? "#d08a00" : "#c0392b";
      ctx.setLineDash(l.label.includes("soft") ? [6 * devicePixelRatio, 4 * devicePixelRatio] : []);
      for (const v of [l.value, -l.value]) {
        if (v < ymin || v > ymax) continue;
        const y = u.valToPos(v, "y", true);
        ctx.beginPath(); ctx.moveTo(u.bbox.left, y); ctx.lineTo(u.bbox.left + u.bbox.width, y); ctx.stroke();
      }
    }
    ctx.restore();
  };
}

function yRange(chart) {
  return (u, dmin, dmax) => {
    if (dmin === null || dmax === null || !isFinite(dmin) || !isFinite(dmax)) return [-1, 1];
    let lo = dmin, hi = dmax;
    const peak = Math.max(Math.abs(lo), Math.abs(hi));
    // A limit within 2.5x of the peak is drawn, so the chart shows how close the signal comes to it.
    for (const l of chart.limits) {
      if (l.value <= 2.5 * peak || peak === 0) { lo = Math.min(lo, -l.value); hi = Math.max(hi, l.value); }
    }
    if (lo === hi) { lo -= 1; hi += 1; }
    const pad = 0.05 * (hi - lo);
    return [lo - pad, hi + pad];
  };
}

function buildCharts(meta) {
  const signals = meta.channels[0].signals;
  const duration = meta.scene.duration_s;
  const root = $("charts");
  root.replaceChildren();
  state.charts = [];
  const width = Math.max(400, root.clientWidth - 20);
  signals.forEach((s, index) => {
    if (index === 0) return;  // t_s is the x axis
    const el = document.createElement("div");
    el.className = "chart";
    el.dataset.signal = s.name;
    const head = document.createElement("div"); head.className = "head";
    const name = document.createElement("span"); name.className = "label"; name.textContent = label(s);
    if (s.description) name.title = s.description;
    const value = document.createElement("span"); value.className = "value";
    head.append(name, value);
    const note = document.createElement("div"); note.className = "note";
    el.append(head, note);
    root.append(el);
    const chart = { signal: s, index, el, value, note, limits: meta.limits.filter((l) => l.signal === s.name) };
    const opts = {
      width, height: 140,
      legend: { show: false },
      cursor: { drag: { x: false, y: false } },
      scales: { x: { time: false, range: [0, duration] }, y: { range: yRange(chart) } },
      axes: [{ label: "t [s]", size: 30, labelSize: 14 }, { size: 70 }],
      series: [{}, { stroke: "#1f5fa8", width: 1.2, points: { show: false }, spanGaps: false }],
      hooks: { draw: [limitHook(chart)] },
    };
    chart.plot = new uPlot(opts, [[], []], el);
    chart.visible = true;
    state.charts.push(chart);
    visibility.observe(el);
  });
}

// A chart scrolled out of sight is not redrawn until it comes back.
const visibility = new IntersectionObserver((entries) => {
  for (const e of entries) {
    const c = state.charts.find((x) => x.el === e.target);
    if (!c) continue;
    c.visible = e.isIntersecting;
    if (c.visible) scheduleDraw();
  }
});

// Per bucket two points in the order they occurred (the minimum and the maximum), one for a single row. The
// arrays grow at their end: only the last bucket (still filling) is rewritten; a bucket out of order (a page
// that reconnected) rebuilds them.
const series = { xs: [], ys: [], last: -1, lastStart: 0 };
function pointsOf(b, j, xs, ys) {
  const lo = b.lo[j], hi = b.hi[j];
  if (b.n === 1 || lo === hi) { xs.push(b.t0); ys.push(lo); return; }
  const [first, second] = b.lo_first[j] ? [lo, hi] : [hi, lo];
  xs.push(b.t0, b.t1); ys.push(first, second);
}
function addBuckets(list) {
  const signals = state.meta.channels[0].signals.length - 1;
  if (series.xs.length !== signals) {
    series.xs = Array.from({ length: signals }, () => []);
    series.ys = Array.from({ length: signals }, () => []);
  }
  for (const b of list) {
    if (b.i < series.last) {  // out of order: rebuild from every bucket held
      series.last = -1;
      series.xs.forEach((a) => (a.length = 0));
      series.ys.forEach((a) => (a.length = 0));
      addBuckets([...state.buckets.values()].sort((x, y) => x.i - y.i));
      return;
    }
    for (let j = 0; j < signals; j++) {
      if (b.i === series.last) { series.xs[j].length = series.lastStart[j]; series.ys[j].length = series.lastStart[j]; }
    }
    if (b.i !== series.last) series.lastStart = series.xs.map((a) => a.length);
    for (let j = 0; j < signals; j++) pointsOf(b, j, series.xs[j], series.ys[j]);
    series.last = b.i;
  }
}

// The page shares the machine with the loop: while the run goes on it redraws at most 5 times a second and
// spends at most about 5 % of its time drawing (the interval grows to 20 times the last draw's duration); at
// the end it draws at once; never while the tab is hidden (requestAnimationFrame does not fire there).
let drawPending = false, lastDraw = 0, drawCost = 0;
function scheduleDraw() {
  if (drawPending) return;
  drawPending = true;
  const interval = Math.max(200, 20 * drawCost);
  const wait = state.ended ? 0 : Math.max(0, interval - (performance.now() - lastDraw));
  setTimeout(() => requestAnimationFrame(draw), wait);
}
function draw() {
  {
    drawPending = false;
    lastDraw = performance.now();
    if (state.pendingPanels) { state.pendingPanels(); state.pendingPanels = null; }
    for (const c of state.charts) {
      if (!c.visible && !state.ended) continue;
      c.plot.setData([series.xs[c.index - 1].slice(), series.ys[c.index - 1].slice()]);
      const v = state.latest ? state.latest.values[c.index] : null;
      c.value.textContent = fmt(v) + (c.signal.unit ? " " + c.signal.unit : "");
      const far = c.limits.filter((l) => {
        const d = c.plot.scales.y;
        return d.max !== undefined && l.value > Math.max(Math.abs(d.min), Math.abs(d.max));
      });
      c.note.textContent = far.map((l) => `${l.label} ±${fmt(l.value)} off scale`).join("; ");
    }
    drawCost = performance.now() - lastDraw;
  }
}

function showStatus(msg) {
  const meta = state.meta;
  if (!meta.has_status) {
    $("safe").textContent = "not known here";
    setList($("status"), [["why", "the controller runs in another process; its status comes with its frames"]]);
    return;
  }
  const l = msg.latest;
  if (!l) return;
  const names = (word) => meta.status_bits.filter((b) => (word & b.mask) !== 0).map((b) => b.name);
  const causes = meta.status_bits.filter((b) => b.kind === "cause" && (l.status & b.mask) !== 0).map((b) => b.name);
  const safe = $("safe");
  safe.textContent = l.safe ? "SAFE STATE" : "running";
  safe.className = "pill " + (l.safe ? "bad" : "ok");
  setList($("status"), [
    ["status word", "0x" + l.status.toString(16).padStart(8, "0")],
    ["bits now", names(l.status).join(", ") || "none"],
    ["safe-state reason", l.safe ? (causes.join(", ") || "start-up: no good frame yet") : "—"],
    ["bits seen in the run", names(msg.status_seen).join(", ") || "none"],
    ["rows in safe state", String(msg.safe_rows)],
  ]);
}

function onData(msg) {
  for (const b of msg.buckets) state.buckets.set(b.i, b);
  addBuckets(msg.buckets);
  state.latest = msg.latest;
  state.pendingPanels = () => panels(msg);  // the panels are redrawn with the charts
  scheduleDraw();
}

function panels(msg) {
  const meta = state.meta;
  setList($("rate"), [
    ["ticks per second", fmt(msg.ticks_per_s, 3)],
    ["real-time factor", fmt(msg.real_time_factor, 3) + "×"],
    ["progress", (100 * msg.progress).toFixed(1) + " %"],
    ["rows received", String(msg.rows)],
    ["rows dropped (ring full)", String(msg.dropped)],
  ]);
  if (msg.latest) {
    setList($("run"), [
      ["device", meta.scene.device],
      ["simulated", fmt(msg.latest.values[0], 5) + " s of " + meta.scene.duration_s + " s"],
      ["tick", `${msg.latest.tick} (${meta.scene.tick_ns / 1e6} ms)`],
      ["seed", String(meta.scene.seed)],
    ]);
  }
  showStatus(msg);
}

function onEnd(msg) {
  if (state.pendingPanels) { state.pendingPanels(); state.pendingPanels = null; }
  state.ended = true;
  state.report = msg.report;
  scheduleDraw();
  const conn = $("connection");
  conn.textContent = "run ended";
  conn.className = "pill warn";
  const figures = (msg.report && msg.report.figures) || {};
  const body = $("figure-table").tBodies[0];
  body.replaceChildren();
  const keys = Object.keys(figures).filter((k) => !/_predicted(_sampled)?$/.test(k));
  // Figures with a prediction first, then the rest.
  keys.sort((a, b) => (figures[b + "_predicted"] !== undefined) - (figures[a + "_predicted"] !== undefined));
  for (const k of keys) {
    const v = figures[k], p = figures[k + "_predicted"], ps = figures[k + "_predicted_sampled"];
    if (typeof v === "object" && v !== null) continue;
    const tr = document.createElement("tr");
    tr.dataset.figure = k;
    const ratio = typeof v === "number" && typeof p === "number" && p !== 0 ? fmt(v / p, 4) : "";
    for (const text of [k, fmt(v, 6), fmt(p, 6), fmt(ps, 6), ratio]) {
      const td = document.createElement("td"); td.textContent = text;
      tr.append(td);
    }
    body.append(tr);
  }
  const predicted = keys.some((k) => figures[k + "_predicted"] !== undefined);
  $("figures-note").textContent = predicted ? "" : "This scene's report has no predicted figures: measured values only.";
  $("figures").hidden = false;
  const t = (msg.report && msg.report.timing) || {};
  setList($("rate"), [
    ["ticks per second", fmt(t.ticks_per_second, 4)],
    ["real-time factor", fmt(t.real_time_factor, 4) + "×"],
    ["ticks", String(t.ticks)],
    ["wall time", fmt(t.wall_s, 4) + " s"],
  ]);
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/ws?token=${encodeURIComponent(token)}`);
  ws.onopen = () => { $("connection").textContent = "live"; $("connection").className = "pill ok"; };
  ws.onmessage = (ev) => {
    state.messages++;
    const msg = JSON.parse(ev.data);
    if (msg.type === "meta") {
      state.meta = msg;
      document.title = `gyrostab — ${msg.scene.name}`;
      $("title").textContent = `${msg.scene.name} — live`;
      buildCharts(msg);
    } else if (msg.type === "data") {
      onData(msg);
    } else if (msg.type === "end") {
      onEnd(msg);
    }
  };
  ws.onclose = () => {
    if (state.ended) return;
    const conn = $("connection");
    if (state.meta === null) { state.refused = true; conn.textContent = "refused (wrong token?)"; }
    else conn.textContent = "disconnected (the run's process ended)";
    conn.className = "pill bad";
  };
}

connect();
