// ctest label `browser`: the page of `gyrostab view --lcm-url` (a passive listener on a running bus) in Debian's
// headless chromium, driven by puppeteer-core.
//   node view_lcm_page_test.cjs GYROSTAB SOURCE_DIR WORKDIR
// Runs itself inside a private network namespace (unshare -n, loopback multicast; exit 77 where that is not
// permitted): the viewer listens (--scene: the active ship, 20 000 ticks), the page opens, then the plant and
// controller run over LCM with a bus log. Checks: two channels, the sensor and the actuator frames, with a chart
// per signal of the device's signal table labelled with its name, element and unit (header fields listed, not
// charted); every frame reached the page; the sensor channel's buckets against the bus log's frames (decoded
// here: the same min/max per bucket, bit for bit); the controller's status panel from the actuator frames
// ("running"); the bus panel: device, session, NOT authenticated (no key). Writes WORKDIR/view-lcm.png
// (docs/view.md has it).
"use strict";
const { spawn, spawnSync, execFileSync } = require("child_process");
const fs = require("fs");
const path = require("path");

const failures = [];
function check(cond, what) {
  console.log((cond ? "ok   " : "FAIL ") + what);
  if (!cond) failures.push(what);
}

const TICKS = 20000;

// LCM's event log, as tests/mcap/mcap_readback.cjs reads it: the sensor frames by tick.
function sensorFrames(file) {
  const b = fs.readFileSync(file);
  const out = new Map();
  let at = 0;
  while (at + 28 <= b.length && b.readUInt32BE(at) === 0xeda1da01) {
    const chLen = b.readInt32BE(at + 20), dataLen = b.readInt32BE(at + 24);
    const channel = b.toString("latin1", at + 28, at + 28 + chLen);
    const d = b.subarray(at + 28 + chLen, at + 28 + chLen + dataLen);
    at += 28 + chLen + dataLen;
    if (!channel.startsWith("GYROSTAB_SENSOR")) continue;
    const n = (d.length - 88) / 8;
    const tick = Number(d.readBigInt64BE(8));
    // The row as the viewer pushes it after t_s: time_ns, sample_time_ns, sequence, status, the signals.
    out.set(tick, [Number(d.readBigInt64BE(16)), Number(d.readBigInt64BE(24)), d.readUInt32BE(32), d.readUInt32BE(36),
                   ...Array.from({ length: n }, (_, i) => d.readDoubleBE(40 + 8 * i))]);
  }
  return out;
}

async function inside(gyrostab, src, work) {
  const puppeteer = require("puppeteer-core");
  execFileSync("ip", ["link", "set", "lo", "up", "multicast", "on"]);
  execFileSync("ip", ["route", "add", "224.0.0.0/4", "dev", "lo"]);
  const scene = path.join(src, "sim/scenes/ship-roll-damper-active.toml");
  const env = { ...process.env, GYROSTAB_PLOT_SCRIPT: "" };
  const url = "udpm://239.255.76.67:7667?ttl=0";
  const viewer = spawn(gyrostab, ["view", "--lcm-url", url, "--scene", scene, "--ticks", String(TICKS)],
                       { env, stdio: ["ignore", "pipe", "pipe"] });
  const pageUrl = await new Promise((resolve, reject) => {
    let err = "";
    const timer = setTimeout(() => reject(new Error("no URL printed: " + err)), 30000);
    viewer.stderr.on("data", (d) => {
      err += d.toString();
      const m = err.match(/ at (http\S+)/);
      if (m) { clearTimeout(timer); resolve(m[1]); }
    });
  });
  const browser = await puppeteer.launch({
    executablePath: "/usr/bin/chromium",
    headless: true,
    userDataDir: path.join(work, "profile"),
    args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--no-first-run", "--disable-dev-shm-usage"],
  });
  try {
    const page = await browser.newPage();
    await page.setViewport({ width: 1280, height: 1400 });
    const res = await page.goto(pageUrl, { waitUntil: "load" });
    check(res.status() === 200, "the viewer's page loads (200)");
    await page.waitForFunction(() => window.gyrostabView && window.gyrostabView.meta, { timeout: 30000 });
    const log = path.join(work, "bus.lcmlog");
    const run = spawnSync(gyrostab, ["run", scene, "--no-progress", "--ticks", String(TICKS), "--out",
                                     path.join(work, "out"), "--transport", "lcm", "--lcm-url", url, "--log", log],
                          { env, encoding: "utf8", timeout: 300000 });
    check(run.status === 0, `the plant/controller pair runs with the page attached (${run.status})`);
    await page.waitForFunction((n) => {
      const s = window.gyrostabView;
      return s.channels.length === 2 && s.channels.every((c) => c.msg && c.msg.rows >= n);
    }, { timeout: 60000 }, TICKS);
    await new Promise((r) => setTimeout(r, 1200));  // one more redraw (at most twice a second)
    const view = await page.evaluate(() => {
      const s = window.gyrostabView;
      return {
        meta: s.meta,
        rows: s.channels.map((c) => c.msg.rows),
        buckets: [...s.channels[0].buckets.values()].sort((a, b) => a.i - b.i),
        headings: [...document.querySelectorAll("h2.channel")].map((e) => e.textContent),
        labels: [...document.querySelectorAll(".chart")].map((e) => [e.dataset.channel, e.querySelector(".label").textContent]),
        safe: document.getElementById("safe").textContent,
        status: document.getElementById("status").textContent,
        link: document.getElementById("link").textContent,
        auth: document.getElementById("auth").textContent,
        header: document.getElementById("header-1").textContent,
      };
    });
    await page.screenshot({ path: path.join(work, "view-lcm.png"), fullPage: false });
    const out = JSON.parse(fs.readFileSync(path.join(work, "out", "report.json"), "utf8"));
    const ctl = JSON.parse(fs.readFileSync(path.join(work, "out", "controller", "report.json"), "utf8"));
    // Every frame of the run's ticks; the end-of-run frame and its answer are counted by the listener, not charted.
    check(view.rows[0] >= TICKS && view.rows[0] <= out.link.counters.sent - 1 &&
          view.rows[1] >= TICKS && view.rows[1] <= ctl.link.counters.sent - 1,
          `every frame of the run's ticks reached the page: ${view.rows.join(", ")} (sent ${out.link.counters.sent}, ${ctl.link.counters.sent})`);
    check(JSON.stringify(view.meta.channels.map((c) => c.topic)) === '["/gyrostab/sensor","/gyrostab/actuator"]' &&
          view.headings.length === 2, `two channels: ${view.headings.join(" | ")}`);
    // Every charted signal is one of the table's, labelled with its element and unit.
    const expected = [];
    for (const ch of view.meta.channels) {
      ch.signals.slice(1).filter((s) => !s.integer).forEach((s) => {
        expected.push([ch.topic, s.unit && s.unit !== "-" ? `${s.label} [${s.unit}]` : s.label]);
      });
    }
    check(JSON.stringify(view.labels) === JSON.stringify(expected), `a chart per signal of the table (${view.labels.length})`);
    const has = (t, l) => view.labels.some(([c, x]) => c === t && x === l);
    check(has("/gyrostab/sensor", "roll_rad [rad]") && has("/gyrostab/sensor", "precession_angle_rad [rad]") &&
          has("/gyrostab/actuator", "precession_torque_Nm [N m]") && has("/gyrostab/actuator", "precession_brake"),
          "the ship's roll, precession and torque are charted with their units");
    const torque = view.meta.channels[1].signals.find((s) => s.label === "precession_torque_Nm");
    check(torque && torque.min === -1e7 && torque.max === 1e7 && torque.symbol && torque.description,
          "the torque's range, symbol and description come from the table");

    // The sensor channel's buckets against the bus log: span TICKS (no growth), 2000 buckets.
    const frames = sensorFrames(log);
    const B = view.meta.channels[0].buckets, span = view.meta.channels[0].span_ticks;
    check(span === TICKS && B === 2000, `the span is the scene's run (${span} ticks, ${B} buckets)`);
    const want = new Map();
    for (const [tick, row] of frames) {
      const i = Math.min(Math.floor((tick * B) / (span + 1)), B - 1);
      let e = want.get(i);
      if (!e) { e = { lo: row.slice(), hi: row.slice() }; want.set(i, e); }
      row.forEach((v, j) => { e.lo[j] = Math.min(e.lo[j], v); e.hi[j] = Math.max(e.hi[j], v); });
    }
    let bad = "";
    for (const b of view.buckets.slice(0, 50)) {
      const e = want.get(b.i);
      for (let j = 0; j < e.lo.length && !bad; j++) {
        if (!Object.is(e.lo[j], b.lo[j] ?? NaN) && !(b.lo[j] === null && !Number.isFinite(e.lo[j]))) bad = `bucket ${b.i} value ${j}: ${b.lo[j]} vs ${e.lo[j]}`;
        if (!Object.is(e.hi[j], b.hi[j] ?? NaN) && !(b.hi[j] === null && !Number.isFinite(e.hi[j]))) bad = `bucket ${b.i} value ${j}: ${b.hi[j]} vs ${e.hi[j]}`;
      }
      if (bad) break;
    }
    check(view.buckets.length === want.size && bad === "",
          `the sensor frames' buckets equal the bus log's frames, bit for bit (${view.buckets.length} buckets)` + (bad ? ": " + bad : ""));
    check(view.safe === "running" && view.status.includes("status word"), `the controller's status from the actuator frames: ${view.safe}`);
    check(view.auth.includes("NOT authenticated") && view.link.includes("ship_roll_damper") && view.link.includes("0x"),
          `the bus panel: ${view.auth}; ${view.link.slice(0, 120)}`);
    check(view.header.includes("NOT authenticated") && view.header.includes("status 0x"), `the actuator header line: ${view.header}`);
  } finally {
    await browser.close();
    viewer.kill("SIGTERM");
  }
}

async function main() {
  const [gyrostab, src, work] = process.argv.slice(2, 5);
  if (process.argv.includes("--inside")) {
    const t0 = Date.now();
    await inside(gyrostab, src, work);
    console.log(`${failures.length === 0 ? "all checks passed" : failures.length + " checks failed"} in ` +
                `${((Date.now() - t0) / 1000).toFixed(1)} s; screenshot ${path.join(work, "view-lcm.png")}`);
    process.exit(failures.length ? 1 : 0);
  }
  if (!fs.existsSync("/usr/bin/chromium")) {
    console.log("skip: /usr/bin/chromium missing (tools/setup installs Debian's chromium)");
    process.exit(77);
  }
  if (spawnSync("unshare", ["-n", "true"]).status !== 0) {
    console.log("skip: no private network namespace here (unshare -n)");
    process.exit(77);
  }
  fs.rmSync(work, { recursive: true, force: true });
  fs.mkdirSync(work, { recursive: true });
  const r = spawnSync("unshare", ["-n", process.execPath, __filename, gyrostab, src, work, "--inside"], { stdio: "inherit" });
  process.exit(r.status === null ? 1 : r.status);
}

main().catch((e) => { console.error(e); process.exit(1); });
