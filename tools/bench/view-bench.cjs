// The ticks-per-second cost of the live view, in one invocation, alternating the ways of running in every repeat
// and printing the medians of report.json timing.ticks_per_second (the loop alone: set-up and outputs excluded),
// their spread (min–max) and the ratios of the medians.
//
//   tools/bench/view-bench [SCENE] [TICKS] [REPEATS]          in process (default the active ship, 900000, 7):
//     without the view; --view and no page (the loop's own cost: the feed and the server's thread); --view with a
//     headless chromium page attached from tick 0 (puppeteer-core; --view-wait). The loop thread's own CPU time
//     per tick (timing.ticks_per_cpu_second) separates the loop's cost from the cores the page takes.
//   tools/bench/view-bench --lcm [SCENE] [TICKS] [REPEATS]    over LCM (default the active ship, 200000, 5), plant
//     and controller processes in a private network namespace (the bench re-runs itself under unshare -n):
//     without a view; run --view (the plant process serves its rows' view) with a page; the passive listener
//     `gyrostab view --lcm-url` without a page; the listener with a page. For the listener and the browser it also
//     prints the CPU time they took, as a share of one core over the run (the cores the loop's two processes
//     could not have).
// On a 2-core machine every process of the view competes with the loop's for the cores: the ratios say how much.
"use strict";
const { spawn, spawnSync, execFileSync } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");

const HZ = 100;  // USER_HZ: /proc's clock ticks

// Runs gyrostab; with `cpu`, through sh, which prints the CPU seconds of gyrostab and every process it waited
// for (its children's user + system time, /proc/PID/stat cutime + cstime) on the line "GYROSTAB_CPU <stat>".
function run(bin, args, onUrl, cpu) {
  return new Promise((resolve, reject) => {
    const [exe, argv] = cpu
      ? ["sh", ["-c", 'exec 3>&2; "$@"; rc=$?; read -r s < /proc/$$/stat; echo "GYROSTAB_CPU $s" >&3; exit $rc', "sh", bin, ...args]]
      : [bin, args];
    const p = spawn(exe, argv, { env: { ...process.env, GYROSTAB_PLOT_SCRIPT: "" }, stdio: ["ignore", "pipe", "pipe"] });
    let err = "", out = "";
    p.stdout.on("data", (d) => { out += d; });
    p.stderr.on("data", (d) => {
      err += d;
      const m = err.match(/live view of .* at (http\S+)/);
      if (m && onUrl) { onUrl(m[1], p); onUrl = null; }
    });
    p.on("exit", (code, signal) => {
      if (code !== 0) return reject(new Error(`exit ${code} ${signal}: ${err}`));
      const m = err.match(/GYROSTAB_CPU (.*)/);
      let cpuS = null;
      if (m) {
        const f = m[1].slice(m[1].lastIndexOf(")") + 2).split(" ");
        cpuS = (Number(f[13]) + Number(f[14])) / HZ;
      }
      resolve({ out, err, cpu: cpuS });
    });
  });
}

// CPU seconds (user + system) of a process and every descendant, from /proc.
function treeCpu(root) {
  const procs = new Map();
  for (const d of fs.readdirSync("/proc")) {
    if (!/^\d+$/.test(d)) continue;
    try {
      const s = fs.readFileSync(`/proc/${d}/stat`, "utf8");
      const f = s.slice(s.lastIndexOf(")") + 2).split(" ");
      procs.set(Number(d), { ppid: Number(f[1]), cpu: (Number(f[11]) + Number(f[12])) / HZ });
    } catch (e) { /* gone */ }
  }
  const inTree = (pid) => { for (let p = pid, n = 0; p > 1 && n < 64; p = procs.get(p)?.ppid ?? 0, n++) if (p === root) return true; return false; };
  let total = 0;
  for (const [pid, p] of procs) if (inTree(pid)) total += p.cpu;
  return total;
}

// The ratio of each repeat's run to the same repeat's run without the view (runs adjacent in time, so a load that
// drifts over the bench moves both): median and min–max over the repeats.
function paired(a, base) {
  const r = a.map((x, i) => x / base[i]);
  return `per-repeat ratio median ${median(r).toFixed(4)} (min–max ${Math.min(...r).toFixed(4)}–${Math.max(...r).toFixed(4)})`;
}

const median = (v) => { const s = [...v].sort((a, b) => a - b); const n = s.length; return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2; };
const spread = (v, d = 0) => `${Math.min(...v).toFixed(d)}–${Math.max(...v).toFixed(d)}`;

async function launch(work) {
  const puppeteer = require("puppeteer-core");
  return puppeteer.launch({
    executablePath: "/usr/bin/chromium", headless: true, userDataDir: path.join(work, "profile"),
    args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--no-first-run", "--disable-dev-shm-usage"],
  });
}

const timing = (dir) => JSON.parse(fs.readFileSync(path.join(dir, "report.json"), "utf8")).timing;

async function inProcess(bin, scene, ticks, repeats, work) {
  const browser = await launch(work);
  const modes = ["without", "view", "page"];
  const tps = { without: [], view: [], page: [] }, cpu = { without: [], view: [], page: [] }, chrome = [];
  for (let i = 0; i < repeats; i++) {
    const line = [];
    for (const mode of modes) {
      const dir = path.join(work, `${mode}-${i}`);
      const args = ["run", scene, "--ticks", ticks, "--no-progress", "--out", dir];
      if (mode !== "without") args.push("--view", "--view-linger", "0");
      let page = null, c0 = 0, t0 = 0;
      if (mode === "page") {
        args.push("--view-wait", "30");
        await run(bin, args, async (url) => {
          page = await browser.newPage();
          c0 = treeCpu(browser.process().pid); t0 = Date.now();
          await page.goto(url);
        });
        chrome.push((treeCpu(browser.process().pid) - c0) / ((Date.now() - t0) / 1000));
        await page.close();
      } else {
        await run(bin, args);
      }
      tps[mode].push(timing(dir).ticks_per_second);
      cpu[mode].push(timing(dir).ticks_per_cpu_second);
      line.push(`${mode} ${tps[mode][i].toFixed(0)}`);
      fs.rmSync(dir, { recursive: true, force: true });
    }
    console.log(`  ${i + 1}: ${line.join(", ")} ticks/s`);
  }
  await browser.close();
  const m = Object.fromEntries(modes.map((k) => [k, median(tps[k])]));
  console.log(`without --view:            median ${m.without.toFixed(0)} ticks/s (min–max ${spread(tps.without)})`);
  console.log(`with --view, no page:      median ${m.view.toFixed(0)} ticks/s (min–max ${spread(tps.view)})`);
  console.log(`with --view and a browser: median ${m.page.toFixed(0)} ticks/s (min–max ${spread(tps.page)})`);
  console.log(`ratio of medians, --view without a page: ${(m.view / m.without).toFixed(4)} (cost ${(100 * (1 - m.view / m.without)).toFixed(2)} %); ${paired(tps.view, tps.without)}`);
  console.log(`ratio of medians, --view with a browser: ${(m.page / m.without).toFixed(4)} (cost ${(100 * (1 - m.page / m.without)).toFixed(2)} %); ${paired(tps.page, tps.without)}`);
  const c = Object.fromEntries(modes.map((k) => [k, median(cpu[k])]));
  console.log(`the loop thread's own CPU time (ticks per CPU second, medians; min–max): without ${c.without.toFixed(0)} ` +
              `(${spread(cpu.without)}), --view without a page ${c.view.toFixed(0)} (${spread(cpu.view)}), with a browser ` +
              `${c.page.toFixed(0)} (${spread(cpu.page)}); ratios ${(c.view / c.without).toFixed(4)} and ${(c.page / c.without).toFixed(4)}`);
  console.log(`chromium's CPU over a run with its page: median ${(100 * median(chrome)).toFixed(1)} % of a core (min–max ${spread(chrome.map((x) => 100 * x), 1)})`);
}

async function overLcm(bin, scene, ticks, repeats, work) {
  execFileSync("ip", ["link", "set", "lo", "up", "multicast", "on"]);
  execFileSync("ip", ["route", "add", "224.0.0.0/4", "dev", "lo"]);
  const browser = await launch(work);
  const url = "udpm://239.255.76.67:7667?ttl=0";
  const modes = ["without", "view_page", "listener", "listener_page"];
  const tps = Object.fromEntries(modes.map((k) => [k, []]));
  const loopCpu = Object.fromEntries(modes.map((k) => [k, []]));  // the pair's CPU seconds per million ticks
  const listenerCpu = { listener: [], listener_page: [] }, chrome = { view_page: [], listener_page: [] };
  for (let i = 0; i < repeats; i++) {
    const line = [];
    for (const mode of modes) {
      const dir = path.join(work, `${mode}-${i}`);
      const args = ["run", scene, "--ticks", ticks, "--no-progress", "--out", dir, "--transport", "lcm", "--lcm-url", url];
      let listener = null, page = null, c0 = 0, t0 = 0, l0 = 0;
      if (mode.startsWith("listener")) {
        await new Promise((resolve, reject) => {
          listener = spawn(bin, ["view", "--lcm-url", url, "--scene", scene, "--ticks", ticks], { stdio: ["ignore", "pipe", "pipe"] });
          let err = "";
          listener.stdout.on("data", () => {});
          listener.stderr.on("data", async (d) => {
            err += d;
            const m = err.match(/ at (http\S+)/);
            if (m && !page && mode === "listener_page") {
              page = await browser.newPage();
              await page.goto(m[1]);
              await page.waitForFunction(() => window.gyrostabView && window.gyrostabView.meta);
              resolve();
            } else if (m && mode === "listener") {
              resolve();
            }
          });
          listener.on("exit", (code) => reject(new Error(`the listener exited ${code}: ${err}`)));
        });
        l0 = treeCpu(listener.pid);
      }
      if (page || mode === "view_page") { c0 = treeCpu(browser.process().pid); }
      t0 = Date.now();
      let r;
      if (mode === "view_page") {
        args.push("--view", "--view-wait", "30", "--view-linger", "0");
        r = await run(bin, args, async (u) => { page = await browser.newPage(); await page.goto(u); }, true);
      } else {
        r = await run(bin, args, null, true);
      }
      loopCpu[mode].push(r.cpu / Number(ticks) * 1e6);
      const wall = (Date.now() - t0) / 1000;
      if (page) {
        chrome[mode].push((treeCpu(browser.process().pid) - c0) / wall);
        await page.close();
      }
      if (listener) {
        listenerCpu[mode].push((treeCpu(listener.pid) - l0) / wall);
        listener.removeAllListeners("exit");
        listener.kill("SIGTERM");
        await new Promise((r) => listener.on("exit", r));
      }
      tps[mode].push(timing(dir).ticks_per_second);
      line.push(`${mode} ${tps[mode][i].toFixed(0)}`);
      fs.rmSync(dir, { recursive: true, force: true });
    }
    console.log(`  ${i + 1}: ${line.join(", ")} ticks/s`);
  }
  await browser.close();
  const m = Object.fromEntries(modes.map((k) => [k, median(tps[k])]));
  const what = { without: "without a view", view_page: "run --view, a browser on it", listener: "gyrostab view, no page",
                 listener_page: "gyrostab view, a browser on it" };
  for (const k of modes) console.log(`${what[k].padEnd(32)} median ${m[k].toFixed(0)} ticks/s (min–max ${spread(tps[k])})` +
                                     (k === "without" ? "" : `; ratio ${(m[k] / m.without).toFixed(4)} (cost ${(100 * (1 - m[k] / m.without)).toFixed(2)} %); ${paired(tps[k], tps.without)}`));
  const c = Object.fromEntries(modes.map((k) => [k, median(loopCpu[k])]));
  console.log(`the plant's and the controller's processes' CPU (user + system) per million ticks, medians (min–max): ` +
              modes.map((k) => `${what[k]} ${c[k].toFixed(1)} s (${spread(loopCpu[k], 1)})` + (k === "without" ? "" : ` ratio ${(c[k] / c.without).toFixed(3)}`)).join("; "));
  for (const k of ["listener", "listener_page"]) {
    console.log(`the listener's CPU (${what[k]}): median ${(100 * median(listenerCpu[k])).toFixed(1)} % of a core (min–max ${spread(listenerCpu[k].map((x) => 100 * x), 1)})`);
  }
  for (const k of ["view_page", "listener_page"]) {
    console.log(`chromium's CPU (${what[k]}): median ${(100 * median(chrome[k])).toFixed(1)} % of a core (min–max ${spread(chrome[k].map((x) => 100 * x), 1)})`);
  }
}

async function main() {
  const argv = process.argv.slice(2).filter((a) => a !== "--lcm" && a !== "--inside");
  const lcm = process.argv.includes("--lcm");
  if (lcm && !process.argv.includes("--inside")) {
    const r = spawnSync("unshare", ["-n", process.execPath, __filename, ...process.argv.slice(2), "--inside"], { stdio: "inherit" });
    process.exit(r.status === null ? 1 : r.status);
  }
  const [scene = "sim/scenes/ship-roll-damper-active.toml", ticks = lcm ? "200000" : "900000", repeats = lcm ? "5" : "7"] = argv;
  const bin = path.resolve(process.env.GYROSTAB_BUILD_DIR || "build", "bin/gyrostab");
  const work = fs.mkdtempSync(path.join(os.tmpdir(), "gyrostab-view-bench-"));
  console.log(`view-bench${lcm ? " --lcm" : ""}: ${scene}, ${ticks} ticks, ${repeats} repeats of each, in turn ` +
              `(load average: ${os.loadavg().map((x) => x.toFixed(2)).join(" ")}; ${os.cpus().length} cores)`);
  if (lcm) await overLcm(bin, scene, ticks, Number(repeats), work);
  else await inProcess(bin, scene, ticks, Number(repeats), work);
  console.log(`(load average at the end: ${os.loadavg().map((x) => x.toFixed(2)).join(" ")})`);
  fs.rmSync(work, { recursive: true, force: true });
}

main().catch((e) => { console.error(e); process.exit(1); });
