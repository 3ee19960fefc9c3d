// ctest label `browser`: the live view's page in a real browser — Debian's chromium, headless, driven by
// puppeteer-core (npm; it never downloads a browser of its own).
//   node view_page_test.cjs GYROSTAB SOURCE_DIR WORKDIR
// Starts `gyrostab run sim/scenes/ship-roll-damper-active.toml --view --view-wait 30` (the loop starts once the
// page is connected, so the page sees it live), opens the printed URL, waits for the charts to fill and the run
// to end, then checks: one chart per recorded column, labelled with the column's name and unit; the page's
// buckets and the first points of every chart against signals.csv's rows (the same min/max per bucket, exact);
// the limits drawn on the precession and torque charts; the status panel; the figures table against
// report.json; and that a wrong token (page and WebSocket) and a foreign Origin (a page of another origin
// opening the WebSocket with the right token) are refused. Then `gyrostab sweep --view` on a 12-task study of
// the same ship (3 s a task): the page's heat maps fill and, once merged, show each cell's mean roll reduction
// as results/<variant>/cells.csv has it. Writes WORKDIR/view.png and WORKDIR/sweep.png (docs/ has both).
"use strict";
const { spawn } = require("child_process");
const fs = require("fs");
const path = require("path");
const puppeteer = require("puppeteer-core");

const failures = [];
function check(cond, what) {
  console.log((cond ? "ok   " : "FAIL ") + what);
  if (!cond) failures.push(what);
}

function startRun(gyrostab, scene, out, args) {
  const p = spawn(gyrostab, args || ["run", scene, "--no-progress", "--out", out, "--view", "--view-wait", "30",
                                     "--view-linger", "120"],
                  { env: { ...process.env, GYROSTAB_PLOT_SCRIPT: "", GYROSTAB_SWEEP_PLOT_SCRIPT: "" },
                    stdio: ["ignore", "pipe", "pipe"] });
  return new Promise((resolve, reject) => {
    let err = "";
    const timer = setTimeout(() => reject(new Error("no URL printed: " + err)), 30000);
    p.stderr.on("data", (d) => {
      err += d.toString();
      const m = err.match(/live view (?:of \S+ )?at (\S+)/);
      if (m) { clearTimeout(timer); resolve({ proc: p, url: m[1] }); }
    });
    p.on("exit", (code) => reject(new Error(`gyrostab exited ${code}: ${err}`)));
  });
}

function csvTable(text) {
  const lines = text.split("\n").filter((l) => l.length > 0);
  return { columns: lines[0].split(","), rows: lines.slice(1).map((l) => l.split(",").map(Number)) };
}

async function main() {
  const [gyrostab, src, work] = process.argv.slice(2);
  if (!fs.existsSync("/usr/bin/chromium")) {
    console.log("skip: /usr/bin/chromium missing (tools/setup installs Debian's chromium)");
    process.exit(77);
  }
  const t0 = Date.now();
  fs.rmSync(work, { recursive: true, force: true });
  fs.mkdirSync(work, { recursive: true });
  const scene = path.join(src, "sim/scenes/ship-roll-damper-active.toml");
  const out = path.join(work, "out");
  const { proc, url } = await startRun(gyrostab, scene, out);
  const exited = new Promise((resolve) => proc.on("exit", (code) => resolve(code)));
  const browser = await puppeteer.launch({
    executablePath: "/usr/bin/chromium",
    headless: true,
    userDataDir: path.join(work, "profile"),
    args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--no-first-run", "--disable-dev-shm-usage"],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1280, height: 1500 });
    const res = await page.goto(url, { waitUntil: "load" });
    check(res.status() === 200, "the page with its token loads (200)");
    // The charts fill while the run goes on; the end message follows the last rows.
    await page.waitForFunction(() => window.gyrostabView && window.gyrostabView.ended, { timeout: 120000 });
    await new Promise((r) => setTimeout(r, 300));  // one more animation frame for the last draw
    const view = await page.evaluate(() => {
      const s = window.gyrostabView;
      return {
        meta: s.meta,
        buckets: [...s.channels[0].buckets.values()].sort((a, b) => a.i - b.i),
        labels: [...document.querySelectorAll(".chart .label")].map((e) => e.textContent),
        charts: s.charts.map((c) => ({ name: c.signal.name, limits: c.limits.map((l) => l.key),
                                        x: Array.from(c.plot.data[0].slice(0, 6)),
                                        y: Array.from(c.plot.data[1].slice(0, 6)) })),
        figureRows: [...document.querySelectorAll("#figure-table tbody tr")].map(
          (tr) => [...tr.children].map((td) => td.textContent)),
        safe: document.getElementById("safe").textContent,
        status: document.getElementById("status").textContent,
        messages: s.messages,
      };
    });
    await page.screenshot({ path: path.join(work, "view.png"), fullPage: true });

    const csv = csvTable(fs.readFileSync(path.join(out, "signals.csv"), "utf8"));
    const report = JSON.parse(fs.readFileSync(path.join(out, "report.json"), "utf8"));
    const signals = view.meta.channels[0].signals;
    check(JSON.stringify(signals.map((s) => s.name)) === JSON.stringify(csv.columns), "the meta message names the CSV's columns");
    const expectedLabels = signals.slice(1).map((s) => (s.unit && s.unit !== "-" ? `${s.name} [${s.unit}]` : s.name));
    check(JSON.stringify(view.labels) === JSON.stringify(expectedLabels),
          `one chart per column, labelled with name and unit: ${view.labels.join(" | ")}`);
    check(view.labels.includes("roll_rad [rad]") && view.labels.includes("precession_torque_Nm [N m]") &&
          view.labels.includes("wave_moment_Nm [N m]") && view.labels.includes("precession_rad [rad]"),
          "roll, precession, torque and wave moment are charted");

    // The buckets against the CSV: the same rule as the server (tools/view/view_store.cpp), in doubles.
    const B = view.meta.channels[0].buckets, tickS = view.meta.scene.tick_ns * 1e-9;
    const total = report.timing.ticks;
    const expected = new Map();
    for (const r of csv.rows) {
      const tick = Math.round(r[0] / tickS);
      const i = Math.min(Math.floor((tick * B) / (total + 1)), B - 1);
      let e = expected.get(i);
      if (!e) { e = { t0: r[0], t1: r[0], n: 0, lo: r.slice(1), hi: r.slice(1) }; expected.set(i, e); }
      e.t1 = r[0]; e.n++;
      r.slice(1).forEach((v, j) => { e.lo[j] = Math.min(e.lo[j], v); e.hi[j] = Math.max(e.hi[j], v); });
    }
    check(view.buckets.length === expected.size, `every bucket reached the page (${view.buckets.length} of ${expected.size})`);
    let bad = "";
    for (const b of view.buckets.slice(0, 50)) {
      const e = expected.get(b.i);
      if (!e || e.n !== b.n || e.t0 !== b.t0 || e.t1 !== b.t1) { bad = `bucket ${b.i}: rows or times`; break; }
      for (let j = 0; j < e.lo.length && !bad; j++) {
        if (!Object.is(e.lo[j], b.lo[j]) || !Object.is(e.hi[j], b.hi[j])) bad = `bucket ${b.i} ${csv.columns[j + 1]}`;
      }
      if (bad) break;
    }
    check(bad === "", "the first 50 buckets equal the min/max of signals.csv's rows, bit for bit" + (bad ? ": " + bad : ""));
    // The drawn series: each chart's first points are the first bucket's extremes, in the order they occurred.
    const first = view.buckets[0];
    let drawn = "";
    view.charts.forEach((c, j) => {
      const lo = first.lo[j], hi = first.hi[j];
      const pair = first.n === 1 || lo === hi ? [lo] : first.lo_first[j] ? [lo, hi] : [hi, lo];
      pair.forEach((v, k) => { if (!Object.is(c.y[k], v)) drawn = `${c.name} point ${k}: ${c.y[k]} vs ${v}`; });
      if (c.x[0] !== first.t0) drawn = `${c.name}: x ${c.x[0]} vs ${first.t0}`;
    });
    check(drawn === "", "every chart starts with the first rows' values" + (drawn ? ": " + drawn : ""));

    const limitsOf = Object.fromEntries(view.charts.map((c) => [c.name, c.limits.sort().join(",")]));
    check(limitsOf.precession_rad === "precession_soft_limit_rad,precession_stop_rad",
          `the precession chart draws the soft limit and the end stop (${limitsOf.precession_rad})`);
    check(limitsOf.precession_torque_Nm === "precession_torque_limit_Nm", "the torque chart draws the torque limit");
    check(view.safe === "running" && view.status.includes("status word"), `the status panel: ${view.safe}`);
    const figures = Object.fromEntries(view.figureRows.map((r) => [r[0], r]));
    const measured = Object.keys(report.figures).filter(
      (k) => !/_predicted(_sampled)?$/.test(k) && typeof report.figures[k] !== "object");
    const withPrediction = measured.filter((k) => report.figures[k + "_predicted"] !== undefined);
    check(measured.length > 0 && measured.every((k) => figures[k]),
          `the figures table has a row for each of report.json's ${measured.length} figures`);
    check(withPrediction.every((k) => figures[k][2] !== "—"),
          `the ${withPrediction.length} figures with a prediction show it beside the measured value`);

    // A wrong token: the page is refused, and so is a WebSocket from the right page with a wrong token.
    const base = url.split("/?token=")[0];
    const token = url.split("/?token=")[1];
    const wrong = await browser.newPage();
    const res2 = await wrong.goto(base + "/?token=" + "0".repeat(32));
    check(res2.status() === 403, `a wrong token: the page is refused (${res2.status()})`);
    const wsResult = (p, u) => p.evaluate((wsUrl) => new Promise((resolve) => {
      const ws = new WebSocket(wsUrl);
      ws.onopen = () => { resolve("open"); ws.close(); };
      ws.onerror = () => resolve("refused");
      setTimeout(() => resolve("timeout"), 5000);
    }), u);
    const wsBase = base.replace("http://", "ws://");
    check(await wsResult(page, wsBase + "/ws?token=" + "1".repeat(32)) === "refused", "a wrong token: the WebSocket is refused");
    check(await wsResult(page, wsBase + "/ws?token=" + token) === "open", "the right token from the page's origin: open");
    // A page of another origin (a data: URL, Origin "null") that knows the token is refused all the same.
    const other = await browser.newPage();
    await other.goto("data:text/html,<title>other origin</title>");
    check(await wsResult(other, wsBase + "/ws?token=" + token) === "refused", "a foreign Origin: the WebSocket is refused");
    proc.kill("SIGTERM");
    const code = await exited;
    check(code === 0, `gyrostab exits 0 after SIGTERM (${code})`);

    // The sweep's view.
    const studyFile = path.join(work, "study.toml");
    fs.writeFileSync(studyFile, `[study]
name = "browser-test"
scene = "${scene}"
seed = 7
seeds_per_cell = 2
duration_s = 3
settle_s = 1
[[sea_state]]
Hs = 1.5
Tp = 8.0
probability = 0.5
[[sea_state]]
Hs = 2.5
Tp = 10.0
probability = 0.3
[[sea_state]]
Hs = 3.5
Tp = 9.0
probability = 0.2
[[variant]]
name = "H-1.018e6"
set = { "gyro.H" = 1.018e6 }
[[variant]]
name = "H-0.7e6"
set = { "gyro.H" = 0.7e6, "controller.roll_rate_gain" = 0.7e6 }
`);
    const sweepDir = path.join(work, "sweep");
    const sweep = await startRun(gyrostab, null, null, ["sweep", studyFile, "--out", sweepDir, "--jobs", "2", "--quiet",
                                                         "--view", "--view-linger", "120"]);
    const sweepExited = new Promise((resolve) => sweep.proc.on("exit", (c) => resolve(c)));
    const sp = await browser.newPage();
    await sp.setViewport({ width: 1000, height: 800 });
    await sp.goto(sweep.url);
    await sp.waitForFunction(() => window.gyrostabSweep && window.gyrostabSweep.ended, { timeout: 120000 });
    await new Promise((r) => setTimeout(r, 200));
    const cells = await sp.evaluate(() => [...document.querySelectorAll(".heat")].map((box) => ({
      title: box.querySelector("h2").textContent,
      cells: [...box.querySelectorAll("td")].filter((td) => td.dataset.cell !== "-1")
        .map((td) => [Number(td.dataset.cell), td.textContent]),
    })));
    await sp.screenshot({ path: path.join(work, "sweep.png"), fullPage: true });
    check(cells.length === 2, `a heat map per variant (${cells.length})`);
    let sweepBad = "";
    for (const [v, name] of [[0, "H-1.018e6"], [1, "H-0.7e6"]]) {
      const text = fs.readFileSync(path.join(sweepDir, "results", name, "cells.csv"), "utf8").trim().split("\n");
      const cols = text[0].split(",");
      const rr = cols.indexOf("roll_reduction"), hsCol = cols.indexOf("Hs_m"), tpCol = cols.indexOf("Tp_s");
      for (const line of text.slice(1)) {
        const f = line.split(",");
        const want = Number(f[rr]).toFixed(2) + " (2/2)";
        const c = [[1.5, 8], [2.5, 10], [3.5, 9]].findIndex(([h, t]) => h === Number(f[hsCol]) && t === Number(f[tpCol]));
        const got = cells[v] && cells[v].cells.find(([i]) => i === c);
        if (!got || got[1] !== want) sweepBad = `${name} cell ${c}: page ${got && got[1]} vs cells.csv ${want}`;
      }
    }
    check(sweepBad === "", "every heat-map cell shows cells.csv's mean roll reduction, 2 of 2 tasks in" +
                           (sweepBad ? ": " + sweepBad : ""));
    sweep.proc.kill("SIGTERM");
    check(await sweepExited === 0, "the sweep exits 0 after SIGTERM");
  } finally {
    await browser.close();
    proc.kill("SIGTERM");
  }
  const seconds = ((Date.now() - t0) / 1000).toFixed(1);
  console.log(`${failures.length === 0 ? "all checks passed" : failures.length + " checks failed"} in ${seconds} s; ` +
              `screenshot ${path.join(work, "view.png")}`);
  process.exit(failures.length ? 1 : 0);
}

main().catch((e) => { console.error(e); process.exit(1); });
