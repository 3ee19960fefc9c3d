// The sweep's live view: progress, and per variant a heat map over (Hs, Tp) that fills as tasks finish.
"use strict";
const state = { meta: null, last: null, ended: false };
window.gyrostabSweep = state;
const $ = (id) => document.getElementById(id);
const token = new URLSearchParams(location.search).get("token") || "";

// A perceptual-ish ramp from dark blue (0) to yellow (1): the colour of a roll reduction.
function colour(x) {
  const t = Math.max(0, Math.min(1, x));
  return `hsl(${240 - 180 * t}, 70%, ${25 + 45 * t}%)`;
}

function render(msg) {
  const meta = state.meta;
  const dl = $("progress");
  dl.replaceChildren();
  for (const [k, v] of [["done", `${msg.done} of ${meta.total}`], ["failed", String(msg.failed)],
                        ["elapsed", msg.elapsed_s.toFixed(1) + " s"], ["state", msg.ended ? "merged" : "running"]]) {
    const dt = document.createElement("dt"); dt.textContent = k;
    const dd = document.createElement("dd"); dd.textContent = v;
    dl.append(dt, dd);
  }
  $("bar").value = meta.total ? msg.done / meta.total : 0;
  const hs = [...new Set(meta.cells.map((c) => c.Hs))].sort((a, b) => b - a);
  const tp = [...new Set(meta.cells.map((c) => c.Tp))].sort((a, b) => a - b);
  const perCell = meta.headings * meta.seeds;
  const root = $("maps");
  root.replaceChildren();
  meta.variants.forEach((name, v) => {
    const sum = new Map(), n = new Map(), bad = new Map();
    for (const t of msg.tasks) {
      if (t.variant !== v) continue;
      if (!t.ok) { bad.set(t.cell, (bad.get(t.cell) || 0) + 1); continue; }
      if (typeof t.roll_reduction !== "number") continue;
      sum.set(t.cell, (sum.get(t.cell) || 0) + t.roll_reduction);
      n.set(t.cell, (n.get(t.cell) || 0) + 1);
    }
    const box = document.createElement("div"); box.className = "box heat";
    const h = document.createElement("h2"); h.textContent = `${name}: roll reduction over (Hs, Tp)`;
    const table = document.createElement("table");
    const head = document.createElement("tr");
    head.append(Object.assign(document.createElement("th"), { textContent: "Hs \\ Tp [m, s]" }));
    for (const p of tp) head.append(Object.assign(document.createElement("th"), { textContent: String(p) }));
    table.append(head);
    for (const H of hs) {
      const tr = document.createElement("tr");
      tr.append(Object.assign(document.createElement("th"), { textContent: String(H) }));
      for (const p of tp) {
        const td = document.createElement("td");
        const c = meta.cells.findIndex((x) => x.Hs === H && x.Tp === p);
        if (c >= 0 && n.get(c)) {
          const mean = sum.get(c) / n.get(c);
          td.style.background = colour(mean);
          td.style.color = mean > 0.6 ? "#111" : "#fff";
          td.textContent = `${mean.toFixed(2)} (${n.get(c)}/${perCell})`;
        } else if (c >= 0) {
          td.textContent = bad.get(c) ? `failed ${bad.get(c)}` : "…";
        }
        td.dataset.cell = String(c);
        tr.append(td);
      }
      table.append(tr);
    }
    box.append(h, table);
    root.append(box);
  });
  if (msg.summary && msg.summary.summary_csv && msg.summary.summary_csv.length > 1) {
    // A few of results/summary.csv's columns, a row per variant; the file has them all.
    const rows = msg.summary.summary_csv.map((l) => l.split(","));
    const want = ["variant", "completed", "failed", "missing", "roll_rms_rad", "roll_reduction", "stop_contacts",
                  "precession_max_rad", "operability_nordforsk_merchant"];
    const cols = want.map((w) => rows[0].indexOf(w)).filter((i) => i >= 0);
    const table = $("summary-table");
    table.replaceChildren();
    rows.forEach((r, k) => {
      const tr = document.createElement("tr");
      for (const i of cols) {
        const cell = document.createElement(k === 0 ? "th" : "td");
        const v = Number(r[i]);
        cell.textContent = k > 0 && i > 0 && r[i] !== "" && isFinite(v) ? Number(v.toPrecision(4)).toString() : r[i];
        tr.append(cell);
      }
      table.append(tr);
    });
    $("summary").hidden = false;
  }
}

const ws = new WebSocket(`ws://${location.host}/ws?token=${encodeURIComponent(token)}`);
ws.onopen = () => { $("connection").textContent = "live"; $("connection").className = "pill ok"; };
ws.onmessage = (ev) => {
  const msg = JSON.parse(ev.data);
  if (msg.type === "meta") {
    state.meta = msg;
    $("title").textContent = `sweep ${msg.study}`;
  } else if (msg.type === "sweep") {
    state.last = msg;
    state.ended = msg.ended;
    if (msg.ended) { $("connection").textContent = "sweep done"; $("connection").className = "pill warn"; }
    render(msg);
  }
};
ws.onclose = () => {
  if (state.ended) return;
  $("connection").textContent = state.meta ? "disconnected" : "refused (wrong token?)";
  $("connection").className = "pill bad";
};
