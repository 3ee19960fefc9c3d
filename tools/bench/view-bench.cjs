// The ticks-per-second cost of `--view`, in process, in one invocation: runs SCENE for TICKS ticks REPEATS times
// in each of three ways, in turn — without the view; with --view and no page (the loop's own cost: the feed and
// the server's thread); with --view and a headless chromium page open on it (puppeteer-core; the loop starts
// once the page is connected: --view-wait) — and prints the medians of report.json timing.ticks_per_second
// (the loop alone: set-up and outputs excluded), their spread (min–max) and the ratios of the medians. On a
// 2-core machine the page's rendering competes with the loop for the cores: the third ratio says how much. The
// loop thread's own CPU time per tick (timing.ticks_per_cpu_second) separates the loop's cost from that sharing.
//   tools/bench/view-bench [SCENE] [TICKS] [REPEATS]   (default sim/scenes/ship-roll-damper-active.toml 900000 7)
"use strict";
const { spawn } = require("child_process");
const fs = require("fs");
const os = require("os");
const path = require("path");
const puppeteer = require("puppeteer-core");

function run(bin, args) {
  return new Promise((resolve, reject) => {
    const p = spawn(bin, args, { env: { ...process.env, GYROSTAB_PLOT_SCRIPT: "" }, stdio: ["ignore", "ignore", "pipe"] });
    let err = "";
    p.stderr.on("data", (d) => { err += d; });
    p.on("exit", (code) => (code === 0 ? resolve(err) : reject(new Error(`exit ${code}: ${err}`))));
    p.url = new Promise((res) => {
      p.stderr.on("data", () => { const m = err.match(/live view of \S+ at (\S+)/); if (m) res(m[1]); });
    });
    run.last = p;
  });
}

const median = (v) => { const s = [...v].sort((a, b) => a - b); const n = s.length; return n % 2 ? s[(n - 1) / 2] : (s[n / 2 - 1] + s[n / 2]) / 2; };

async function main() {
  const [scene = "sim/scenes/ship-roll-damper-active.toml", ticks = "900000", repeats = "7"] = process.argv.slice(2);
  const bin = path.join(process.env.GYROSTAB_BUILD_DIR || "build", "bin/gyrostab");
  const work = fs.mkdtempSync(path.join(os.tmpdir(), "gyrostab-view-bench-"));
  const browser = await puppeteer.launch({
    executablePath: "/usr/bin/chromium", headless: true, userDataDir: path.join(work, "profile"),
    args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
           "--disable-sync", "--no-first-run", "--disable-dev-shm-usage"],
  });
  const plain = [], viewed = [], bare = [];
  const timing = (dir) => JSON.parse(fs.readFileSync(path.join(dir, "report.json"), "utf8")).timing;
  const tps = (dir) => timing(dir).ticks_per_second;
  const cpu = { plain: [], bare: [], viewed: [] };  // ticks per second of the loop thread's own CPU time
  console.log(`view-bench: ${scene}, ${ticks} ticks, ${repeats} repeats each (load average: ${os.loadavg().map((x) => x.toFixed(2)).join(" ")})`);
  for (let i = 0; i < Number(repeats); i++) {
    const a = path.join(work, `plain-${i}`), b = path.join(work, `view-${i}`);
    await run(bin, ["run", scene, "--ticks", ticks, "--no-progress", "--out", a]);
    plain.push(tps(a));
    cpu.plain.push(timing(a).ticks_per_cpu_second);
    const c = path.join(work, `bare-${i}`);
    await run(bin, ["run", scene, "--ticks", ticks, "--no-progress", "--out", c, "--view", "--view-linger", "0"]);
    bare.push(tps(c));
    cpu.bare.push(timing(c).ticks_per_cpu_second);
    const done = run(bin, ["run", scene, "--ticks", ticks, "--no-progress", "--out", b, "--view", "--view-wait", "30",
                           "--view-linger", "0"]);
    const url = await run.last.url;
    const page = await browser.newPage();
    await page.goto(url);
    await done;
    const got = await page.evaluate(() => window.gyrostabView.messages);
    await page.close();
    viewed.push(tps(b));
    cpu.viewed.push(timing(b).ticks_per_cpu_second);
    console.log(`  ${i + 1}: without ${plain[i].toFixed(0)}, --view without a page ${bare[i].toFixed(0)}, ` +
                `with a page attached ${viewed[i].toFixed(0)} ticks/s (${got} messages)`);
  }
  await browser.close();
  fs.rmSync(work, { recursive: true, force: true });
  const mp = median(plain), mv = median(viewed), mb = median(bare);
  const spread = (v) => `${Math.min(...v).toFixed(0)}–${Math.max(...v).toFixed(0)}`;
  console.log(`without --view:            median ${mp.toFixed(0)} ticks/s (min–max ${spread(plain)})`);
  console.log(`with --view, no page:      median ${mb.toFixed(0)} ticks/s (min–max ${spread(bare)})`);
  console.log(`with --view and a browser: median ${mv.toFixed(0)} ticks/s (min–max ${spread(viewed)})`);
  console.log(`ratio of medians, --view without a page: ${(mb / mp).toFixed(4)} (cost ${(100 * (1 - mb / mp)).toFixed(2)} %)`);
  console.log(`ratio of medians, --view with a browser: ${(mv / mp).toFixed(4)} (cost ${(100 * (1 - mv / mp)).toFixed(2)} %)`);
  const [cp, cb, cv] = [median(cpu.plain), median(cpu.bare), median(cpu.viewed)];
  console.log(`the loop thread's own CPU time (ticks per CPU second, medians; min–max): without ${cp.toFixed(0)} ` +
              `(${spread(cpu.plain)}), --view without a page ${cb.toFixed(0)} (${spread(cpu.bare)}), with a browser ` +
              `${cv.toFixed(0)} (${spread(cpu.viewed)}); ratios ${(cb / cp).toFixed(4)} and ${(cv / cp).toFixed(4)}`);
}

main().catch((e) => { console.error(e); process.exit(1); });
