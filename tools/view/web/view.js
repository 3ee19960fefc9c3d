// The live view's page: per channel (a run's recorded signals; a bus's sensor and actuator frames) one strip
// chart per signal over the run's span (a min/max envelope per bucket, so every peak shows), the scene's limits
// and the signals' declared ranges as lines, the controller's status and safe state, the rates, a bus's link
// (sessions, authentication, refusals), and at the end the report's figures beside their predictions. It only
// listens: nothing is ever sent.
"use strict";

const state = {
  meta: null,          // the server's latest meta message
  channels: [],        // per channel: {buckets: Map(i -> bucket), series, latest, msg}
  ended: false,
  report: null,
  charts: [],          // {channel, signal, index, plot, el, lines}
  refused: false,
  messages: 0,
  metas: 0,
  pendingPanels: null,
};
window.gyrostabView = state;  // read by the browser test (tests/browser/)

const $ = (id) => document.getElementById(id);
const token = new URLSearchParams(location.search).get("token") || "";
const kAuthenticated = 4;

function fmt(v, digits = 4) {
  if (v === null || v === undefined) return "—";
  if (typeof v !== "number") return String(v);
  if (Number.isInteger(v) && Math.abs(v) < 1e15) return String(v);
  if (v !== 0 && (Math.abs(v) >= 1e5 || Math.abs(v) < 1e-3)) return v.toExponential(digits - 1);
  return Number(v.toPrecision(digits)).toString();
}
function label(s) { return s.unit && s.unit !== "-" ? `${s.label} [${s.unit}]` : s.label; }
function setList(el, rows) {
  el.replaceChildren();
  for (const [k, v] of rows) {
    const dt = document.createElement("dt"); dt.textContent = k;
    const dd = document.createElement("dd"); dd.textContent = v;
    el.append(dt, dd);
  }
}

// The lines of a chart: each placed limit at ±value, and the signal's declared range (a frame's signal: the
// fault monitor's plausible range, a command's drive limit) at its two ends.
function linesOf(meta, channel, s) {
  const lines = [];
  for (const l of meta.limits) {
    if (l.channel !== channel.topic || l.signal !== s.label) continue;
    const style = l.label.includes("soft") ? "soft" : "limit";
    lines.push({ key: l.key, label: l.label, value: l.value, style }, { key: l.key, label: l.label, value: -l.value, style });
  }
  if (s.min !== null && s.max !== null && s.min < s.max) {
    lines.push({ key: "range", label: "range", value: s.min, style: "range" },
               { key: "range", label: "range", value: s.max, style: "range" });
  }
  return lines;
}

const lineStyle = {
  limit: { color: "#c0392b", dash: [] },
  soft: { color: "#d08a00", dash: [6, 4] },
  range: { color: "#8e44ad", dash: [2, 3] },
};
function lineHook(chart) {
  return (u) => {
    const ctx = u.ctx;
    const [ymin, ymax] = [u.scales.y.min, u.scales.y.max];
    ctx.save();
    ctx.lineWidth = 1.5 * devicePixelRatio;
    for (const l of chart.lines) {
      if (l.value < ymin || l.value > ymax) continue;
      const st = lineStyle[l.style];
      ctx.strokeStyle = st.color;
      ctx.setLineDash(st.dash.map((d) => d * devicePixelRatio));
      const y = u.valToPos(l.value, "y", true);
      ctx.beginPath(); ctx.moveTo(u.bbox.left, y); ctx.lineTo(u.bbox.left + u.bbox.width, y); ctx.stroke();
    }
    ctx.restore();
  };
}

// A line within 2.5x of the data's peak is drawn, so the chart shows how close the signal comes to it.
function near(l, peak) { return Math.abs(l.value) <= 2.5 * peak && peak !== 0; }
function yRange(chart) {
  return (u, dmin, dmax) => {
    if (dmin === null || dmax === null || !isFinite(dmin) || !isFinite(dmax)) return [-1, 1];
    let lo = dmin, hi = dmax;
    const peak = Math.max(Math.abs(lo), Math.abs(hi));
    for (const l of chart.lines) if (near(l, peak)) { lo = Math.min(lo, l.value); hi = Math.max(hi, l.value); }
    if (lo === hi) { lo -= 1; hi += 1; }
    const pad = 0.05 * (hi - lo);
    return [lo - pad, hi + pad];
  };
}

function buildCharts(meta) {
  const root = $("charts");
  root.replaceChildren();
  for (const c of state.charts) c.plot.destroy();
  state.charts = [];
  state.channels = meta.channels.map(() => ({ buckets: new Map(), series: newSeries(), latest: null, msg: null }));
  const width = Math.max(400, root.clientWidth - 20);
  const several = meta.channels.length > 1;
  meta.channels.forEach((ch, c) => {
    if (several) {
      const h = document.createElement("h2");
      h.className = "channel";
      h.textContent = `${ch.topic} — ${ch.title}`;
      const head = document.createElement("div");
      head.className = "note";
      head.id = `header-${c}`;
      root.append(h, head);
    }
    ch.signals.forEach((s, index) => {
      if (index === 0 || s.integer) return;  // t_s is the x axis; header fields are listed, not charted
      const el = document.createElement("div");
      el.className = "chart";
      el.dataset.channel = ch.topic;
      el.dataset.signal = s.label;
      const head = document.createElement("div"); head.className = "head";
      const name = document.createElement("span"); name.className = "label"; name.textContent = label(s);
      name.title = [s.symbol, s.description].filter((x) => x).join(": ");
      const value = document.createElement("span"); value.className = "value";
      head.append(name, value);
      const note = document.createElement("div"); note.className = "note";
      el.append(head, note);
      root.append(el);
      const chart = { channel: c, signal: s, index, el, value, note, lines: linesOf(meta, ch, s) };
      chart.limits = meta.limits.filter((l) => l.channel === ch.topic && l.signal === s.label);
      const opts = {
        width, height: several ? 110 : 140,
        legend: { show: false },
        cursor: { drag: { x: false, y: false } },
        scales: { x: { time: false, range: [0, ch.span_s] }, y: { range: yRange(chart) } },
        axes: [{ label: "t [s]", size: 30, labelSize: 14 }, { size: 70 }],
        series: [{}, { stroke: c === 0 ? "#1f5fa8" : "#2a7d4f", width: 1.2, points: { show: false }, spanGaps: false }],
        hooks: { draw: [lineHook(chart)] },
      };
      chart.plot = new uPlot(opts, [[], []], el);
      chart.visible = true;
      state.charts.push(chart);
      visibility.observe(el);
    });
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
function newSeries() { return { xs: [], ys: [], last: -1, lastStart: [] }; }
function pointsOf(b, j, xs, ys) {
  const lo = b.lo[j], hi = b.hi[j];
  if (b.n === 1 || lo === hi) { xs.push(b.t0); ys.push(lo); return; }
  const [first, second] = b.lo_first[j] ? [lo, hi] : [hi, lo];
  xs.push(b.t0, b.t1); ys.push(first, second);
}
function addBuckets(c, list) {
  const ch = state.channels[c];
  const series = ch.series;
  const signals = state.meta.channels[c].signals.length - 1;
  if (series.xs.length !== signals) {
    series.xs = Array.from({ length: signals }, () => []);
    series.ys = Array.from({ length: signals }, () => []);
  }
  for (const b of list) {
    if (b.i < series.last) {  // out of order: rebuild from every bucket held
      ch.series = newSeries();
      addBuckets(c, [...ch.buckets.values()].sort((x, y) => x.i - y.i));
      return;
    }
    if (b.i === series.last) {
      for (let j = 0; j < signals; j++) { series.xs[j].length = series.lastStart[j]; series.ys[j].length = series.lastStart[j]; }
    } else {
      series.lastStart = series.xs.map((a) => a.length);
    }
    for (let j = 0; j < signals; j++) pointsOf(b, j, series.xs[j], series.ys[j]);
    series.last = b.i;
  }
}

// The page shares the machine with the loop: while the run goes on it redraws at most once a second and
// spends at most about 1 % of its time drawing (the interval grows to 100 times the last draw's duration); at
// the end it draws at once; never while the tab is hidden (requestAnimationFrame does not fire there, and the
// page tells nothing to draw until it is shown again).
let drawPending = false, lastDraw = 0, drawCost = 0;
function scheduleDraw() {
  if (drawPending || document.hidden) return;
  drawPending = true;
  const interval = Math.max(1000, 100 * drawCost);
  const wait = state.ended ? 0 : Math.max(0, interval - (performance.now() - lastDraw));
  setTimeout(() => requestAnimationFrame(draw), wait);
}
document.addEventListener("visibilitychange", () => { if (!document.hidden) scheduleDraw(); });
function draw() {
  drawPending = false;
  lastDraw = performance.now();
  if (state.pendingPanels) { state.pendingPanels(); state.pendingPanels = null; }
  for (const c of state.charts) {
    if (!c.visible && !state.ended) continue;
    const series = state.channels[c.channel].series;
    if (series.xs.length === 0) continue;
    c.plot.setData([series.xs[c.index - 1].slice(), series.ys[c.index - 1].slice()]);
    const latest = state.channels[c.channel].latest;
    const v = latest ? latest.values[c.index] : null;
    c.value.textContent = fmt(v) + (c.signal.unit && c.signal.unit !== "-" ? " " + c.signal.unit : "");
    const d = c.plot.scales.y;
    const far = c.lines.filter((l) => l.value > 0 && (l.value < d.min || l.value > d.max));
    const seen = new Set();
    c.note.textContent = far.filter((l) => !seen.has(l.key) && seen.add(l.key))
      .map((l) => `${l.label} ${l.style === "range" ? "" : "±"}${fmt(l.value)} off scale`).join("; ");
  }
  drawCost = performance.now() - lastDraw;
}

function bitNames(list, word) { return list.filter((b) => (word & b.mask) !== 0).map((b) => b.name); }

function showStatus(msg) {
  const meta = state.meta;
  const c = meta.channels.findIndex((ch) => ch.status === "fault");
  if (c < 0) {
    $("safe").textContent = "not known here";
    setList($("status"), [["why", "the controller runs in another process; its status comes with its frames " +
                                  "(gyrostab view --lcm-url shows them)"]]);
    return;
  }
  const m = msg.channels[c];
  const l = m.latest;
  if (!l) return;
  const causes = meta.status_bits.filter((b) => b.kind === "cause" && (l.status & b.mask) !== 0).map((b) => b.name);
  const safe = $("safe");
  safe.textContent = l.safe ? "SAFE STATE" : "running";
  safe.className = "pill " + (l.safe ? "bad" : "ok");
  const rows = [
    ["status word", "0x" + l.status.toString(16).padStart(8, "0")],
    ["bits now", bitNames(meta.status_bits, l.status).join(", ") || "none"],
    ["safe-state reason", l.safe ? (causes.join(", ") || "start-up: no good frame yet") : "—"],
    ["bits seen in the run", bitNames(meta.status_bits, m.status_seen).join(", ") || "none"],
    [meta.source === "run" ? "rows in safe state" : "frames in safe state", String(m.safe_rows)],
  ];
  const s = meta.channels.findIndex((ch) => ch.status === "sensor");
  if (s >= 0 && msg.channels[s].latest) {
    rows.push(["sensor status", bitNames(meta.sensor_status_bits, msg.channels[s].latest.status).join(", ") || "none"]);
  }
  setList($("status"), rows);
}

function showLink(msg) {
  const box = $("link-box");
  if (!msg.link) { box.hidden = true; return; }
  box.hidden = false;
  const l = msg.link;
  const auth = $("auth");
  auth.textContent = l.authentication;
  auth.className = "pill " + (l.authenticated ? "ok" : "warn");
  const rows = [["bus", l.url], ["channels", l.channels], ["device", l.device], ["session", l.session]];
  for (const k of ["sensor", "actuator"]) {
    const d = l[k];
    if (d) rows.push([`${k} frames`, `${d.shown} shown of ${d.received}` + (d.refused ? `; ${d.refused} refused (${d.why})` : "")]);
  }
  if (l.other) rows.push(["other datagrams", l.other]);
  setList($("link"), rows);
}

function headerLine(c) {
  const el = $(`header-${c}`);
  const ch = state.channels[c], meta = state.meta.channels[c];
  if (!el || !ch.latest) return;
  const parts = [`tick ${ch.latest.tick}`];
  meta.signals.forEach((s, i) => { if (s.integer) parts.push(`${s.name} ${s.name === "status" ? "0x" + (ch.latest.values[i] >>> 0).toString(16) : fmt(ch.latest.values[i])}`); });
  if (state.meta.source !== "run") parts.push(ch.latest.flags & kAuthenticated ? "authenticated" : "NOT authenticated");
  el.textContent = parts.join(" · ");
}

function onData(msg) {
  msg.channels.forEach((m, c) => {
    const ch = state.channels[c];
    if (!ch) return;
    for (const b of m.buckets) ch.buckets.set(b.i, b);
    addBuckets(c, m.buckets);
    ch.latest = m.latest;
    ch.msg = m;
  });
  state.latest = msg.channels[0] ? msg.channels[0].latest : null;
  state.pendingPanels = () => panels(msg);  // the panels are redrawn with the charts
  scheduleDraw();
}

function panels(msg) {
  const meta = state.meta;
  const rows = [
    ["ticks per second", fmt(msg.ticks_per_s, 3)],
    ["real-time factor", fmt(msg.real_time_factor, 3) + "×"],
  ];
  if (msg.progress !== null) rows.push(["progress", (100 * msg.progress).toFixed(1) + " %"]);
  msg.channels.forEach((m, c) => {
    const what = meta.source === "run" ? "rows" : meta.channels[c].topic.split("/").pop() + " frames";
    rows.push([`${what} received`, String(m.rows)], [`${what} dropped (ring full)`, String(m.dropped)]);
  });
  setList($("rate"), rows);
  const first = msg.channels.find((m) => m.latest);
  if (first) {
    const l = first.latest;
    setList($("run"), [
      ["device", meta.scene.device],
      ["simulated", fmt(l.values[0], 5) + " s" + (meta.scene.duration_s ? " of " + meta.scene.duration_s + " s" : "")],
      ["tick", `${l.tick}` + (meta.scene.tick_ns ? ` (${meta.scene.tick_ns / 1e6} ms)` : "")],
      ["seed", meta.scene.seed === undefined ? "—" : String(meta.scene.seed)],
    ]);
  }
  meta.channels.forEach((_, c) => headerLine(c));
  showStatus(msg);
  showLink(msg);
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

function onMeta(msg) {
  state.meta = msg;
  state.metas++;
  document.title = `gyrostab — ${msg.scene.name}`;
  $("title").textContent = `${msg.scene.name} — ${msg.source === "run" ? "live" : "heard on the bus"}`;
  buildCharts(msg);
  const unplaced = msg.limits.filter((l) => l.signal === null);
  $("limits-note").textContent = unplaced.length
    ? "Scene limits on no charted signal: " + unplaced.map((l) => `${l.key} ${fmt(l.value)}`).join(", ") : "";
  const undeclared = msg.channels.flatMap((ch) => ch.signals.filter((s) => !s.declared).map((s) => s.name));
  $("table-note").textContent = undeclared.length
    ? "Signals no signal table declares (no unit, no limits): " + undeclared.join(", ") : "";
}

function connect() {
  const ws = new WebSocket(`ws://${location.host}/ws?token=${encodeURIComponent(token)}`);
  ws.onopen = () => { $("connection").textContent = "live"; $("connection").className = "pill ok"; };
  ws.onmessage = (ev) => {
    state.messages++;
    const msg = JSON.parse(ev.data);
    if (msg.type === "meta") onMeta(msg);
    else if (msg.type === "data") onData(msg);
    else if (msg.type === "end") onEnd(msg);
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
