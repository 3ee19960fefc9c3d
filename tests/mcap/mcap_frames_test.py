#!/usr/bin/env python3
"""ctest label `mcap`: the frame channels against the bus log, and `gyrostab export`.

  mcap_frames_test.py GYROSTAB SOURCE_DIR WORKDIR NODE_MODULES CANDUMP_FROM_BUSLOG

1. `gyrostab run` the active ship for 20 000 ticks with --log and --mcap --mcap-frames-every 1: every message of
   /gyrostab/sensor and /gyrostab/actuator equals the bus log's frame of its tick, header and every signal bit for
   bit, decoded from the log by tests/mcap/mcap_readback.cjs itself (LCM's event-log format, big-endian frames),
   not by gyrostab's reader; /gyrostab/signals equals signals.csv. Then the default (--mcap alone): one frame per
   recorded row's tick. Over LCM (plant and controller processes in a private network namespace, 5000 ticks):
   the plant's frames reach the parent's file, equal to the bus log the plant wrote.
2. `gyrostab export LOG --mcap FILE`: the same frames, every tick; the scene event's text; the log complete.
   With --every 7: every 7th tick.
3. A log cut in the middle of an event and a log with a damaged event: exit 5 with the reader's message; the file
   holds every whole tick before the damage and its /gyrostab/log message says the log is incomplete and where.
   A log whose scene event is damaged: exit 5 and no file.
4. `gyrostab export` of a candump log of the same run (made from the bus log with the project's CAN codec by
   candump_from_buslog): every frame equals the bus log's, every tick and every 7th; a log cut inside a line, a
   malformed line and a damaged frame: exit 5, the whole ticks before (or around) it in the file, incomplete; a
   log of another CAN map: exit 5, nothing written; candump's own log without gyrostab's header: exit 2. And a
   committed candump log of a real 100-tick CAN run (recorded in the VM) against the in-process run's bus log.
Exit 77 (skip) without node or @mcap/core (tools/setup installs both). About 3 s."""
import os
import shutil
import subprocess
import sys
import time

FAILS = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        FAILS.append(what)


def main():
    gyrostab, src, work, node_modules, helper = sys.argv[1:6]
    node = shutil.which("node")
    if node is None or not os.path.isdir(os.path.join(node_modules, "@mcap", "core")):
        print("skip: node or @mcap/core missing (tools/setup installs them)")
        return 77
    t0 = time.time()
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    scene = os.path.join(src, "sim/scenes/ship-roll-damper-active.toml")
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    readback = os.path.join(os.path.dirname(os.path.abspath(__file__)), "mcap_readback.cjs")

    def read(mcap, *extra):
        r = subprocess.run([node, readback, mcap, *extra], env=dict(os.environ, NODE_PATH=node_modules),
                           capture_output=True, text=True, timeout=300)
        print("     " + (r.stdout + r.stderr).strip())
        return r.returncode == 0

    def run(*args, timeout=300):
        return subprocess.run([gyrostab, *args], env=env, capture_output=True, text=True, timeout=timeout)

    # 1. Every tick's frames against the bus log.
    out, log, mcap = (os.path.join(work, n) for n in ("out", "run.lcmlog", "run.mcap"))
    r = run("run", scene, "--no-progress", "--ticks", "20000", "--out", out, "--log", log, "--mcap", mcap,
            "--mcap-frames-every", "1")
    check(r.returncode == 0, f"run --log --mcap --mcap-frames-every 1 exits 0 ({r.returncode}) {r.stderr.strip()}")
    check(read(mcap, "--csv", f"{out}/signals.csv", "--report", f"{out}/report.json", "--frames-every", "1",
               "--bus-log", log), "every tick's sensor and actuator frame equals the bus log's, bit for bit")
    default = os.path.join(work, "default.mcap")
    r = run("run", scene, "--no-progress", "--ticks", "20000", "--out", os.path.join(work, "out2"), "--mcap", default)
    check(r.returncode == 0 and read(default, "--csv", f"{work}/out2/signals.csv", "--report",
                                     f"{work}/out2/report.json", "--frames-every", "50", "--bus-log", log),
          "by default the frames of the recorded ticks (record_every = 50), equal to the bus log's")
    none = os.path.join(work, "none.mcap")
    r = run("run", scene, "--no-progress", "--ticks", "2000", "--out", os.path.join(work, "out3"), "--mcap", none,
            "--mcap-frames-every", "0")
    check(r.returncode == 0 and read(none, "--csv", f"{work}/out3/signals.csv", "--report", f"{work}/out3/report.json"),
          "--mcap-frames-every 0: no frame channels")

    # Over LCM: the plant process keeps the frames; the parent writes them into its file.
    if subprocess.run(["unshare", "-n", "true"], capture_output=True).returncode == 0:
        lo, llog, lmcap = os.path.join(work, "lcm"), os.path.join(work, "lcm.lcmlog"), os.path.join(work, "lcm.mcap")
        cmd = ["unshare", "-n", "--", "sh", "-c", "ip link set lo up && ip link set lo multicast on && "
               "ip route add 224.0.0.0/4 dev lo && exec \"$@\"", "sh", gyrostab, "run", scene, "--no-progress",
               "--ticks", "5000", "--out", lo, "--transport", "lcm", "--log", llog, "--mcap", lmcap,
               "--mcap-frames-every", "1"]
        r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
        check(r.returncode == 0, f"over LCM with --log --mcap: exit 0 ({r.returncode}) {r.stderr.strip()[-300:]}")
        check(read(lmcap, "--csv", f"{lo}/signals.csv", "--report", f"{lo}/report.json", "--frames-every", "1",
                   "--bus-log", llog), "over LCM: the plant's frames in the parent's file equal its bus log")
        check(not any(n.startswith("frames_") for n in os.listdir(lo)), "the plant's frame CSVs are removed afterwards")
    else:
        print("skip the LCM case: no private network namespace (unshare -n)")

    # 2. Export.
    exported = os.path.join(work, "export.mcap")
    r = run("export", log, "--mcap", exported)
    check(r.returncode == 0, f"export exits 0 ({r.returncode}) {r.stderr.strip()}")
    check(read(exported, "--export", scene, "--frames-every", "1", "--bus-log", log),
          "export: every tick's frames equal the bus log's; the scene's text; the log complete")
    every7 = os.path.join(work, "export7.mcap")
    r = run("export", log, "--mcap", every7, "--every", "7")
    check(r.returncode == 0 and read(every7, "--export", scene, "--frames-every", "7", "--bus-log", log),
          "export --every 7: every 7th tick")

    # 3. Damaged logs: what came before the damage is exported, and the exit code and the file say so.
    data = open(log, "rb").read()
    cut = os.path.join(work, "cut.lcmlog")
    with open(cut, "wb") as f:
        f.write(data[: len(data) // 2 + 101])
    cut_mcap = os.path.join(work, "cut.mcap")
    r = run("export", cut, "--mcap", cut_mcap)
    check(r.returncode == 5 and "truncated" in r.stderr and "incomplete" in r.stderr,
          f"a cut log: exit 5 with the reader's message ({r.returncode}: {r.stderr.strip()[:160]})")
    check(os.path.exists(cut_mcap) and read(cut_mcap, "--export", scene, "--incomplete", "--frames-every", "1",
                                            "--bus-log", cut),
          "a cut log: every whole tick before the cut is in the file, marked incomplete")
    bad = bytearray(data)
    at = len(data) // 3
    at = data.index(b"\xed\xa1\xda\x01", at)  # an event's sync word
    bad[at] ^= 0xFF
    damaged = os.path.join(work, "damaged.lcmlog")
    with open(damaged, "wb") as f:
        f.write(bad)
    damaged_mcap = os.path.join(work, "damaged.mcap")
    r = run("export", damaged, "--mcap", damaged_mcap)
    check(r.returncode == 5 and "corrupt" in r.stderr, f"a damaged event: exit 5 ({r.returncode}: {r.stderr.strip()[:160]})")
    check(os.path.exists(damaged_mcap) and read(damaged_mcap, "--export", scene, "--incomplete", "--frames-every", "1",
                                                "--bus-log", damaged),
          "a damaged event: the ticks before it are in the file, marked incomplete")
    head = bytearray(data)
    head[40] ^= 0xFF  # inside the scene event
    headless = os.path.join(work, "headless.lcmlog")
    with open(headless, "wb") as f:
        f.write(head)
    r = run("export", headless, "--mcap", os.path.join(work, "headless.mcap"))
    check(r.returncode == 5 and not os.path.exists(os.path.join(work, "headless.mcap")),
          f"a damaged scene event: exit 5, nothing written ({r.returncode}: {r.stderr.strip()[:160]})")

    # 4. A candump log of the same run: made from the bus log with the project's CAN codec (candump_from_buslog:
    #    the header --can-log writes, every tick's sensor and command set as FrameEncoder puts them on the bus,
    #    the end of the run). Lockstep CAN is bit-identical to in process, so these are a CAN run's frames.
    dump = os.path.join(work, "run.candump")
    r = subprocess.run([helper, log, scene, dump], capture_output=True, text=True, timeout=300)
    check(r.returncode == 0, f"candump_from_buslog exits 0 ({r.returncode}) {r.stdout.strip()} {r.stderr.strip()}")
    dmcap = os.path.join(work, "candump.mcap")
    r = run("export", dump, "--mcap", dmcap)
    check(r.returncode == 0, f"export of the candump log exits 0 ({r.returncode}) {r.stderr.strip()}")
    check(read(dmcap, "--export", scene, "--frames-every", "1", "--bus-log", log),
          "candump export: every tick's frames, assembled from the CAN frames, equal the bus log's; the scene's text")
    dmcap7 = os.path.join(work, "candump7.mcap")
    r = run("export", dump, "--mcap", dmcap7, "--every", "7")
    check(r.returncode == 0 and read(dmcap7, "--export", scene, "--frames-every", "7", "--bus-log", log),
          "candump export --every 7: every 7th tick")
    text = open(dump).read()
    lines = text.splitlines(keepends=True)
    command_header_id = lines[-1].split()[2].split("#")[0]  # the last frame: the controller's header frame

    def whole_command_sets(t):
        return sum(1 for ln in t.splitlines(keepends=True)[:-1]
                   if ln.startswith("(") and ln.endswith("\n") and ln.split()[2].startswith(command_header_id + "#"))

    def frames_in(out):
        return out.split(" frames")[0].rsplit("; ", 1)[-1] if " frames" in out else ""

    def read_out(mcap, *extra):
        r = subprocess.run([node, readback, mcap, *extra], env=dict(os.environ, NODE_PATH=node_modules),
                           capture_output=True, text=True, timeout=300)
        print("     " + (r.stdout + r.stderr).strip())
        return r.returncode == 0, r.stdout

    # Cut inside a line: every whole tick before it, marked incomplete, exit 5.
    cut_at = len(text) // 2 + 37
    dcut = os.path.join(work, "cut.candump")
    with open(dcut, "w") as f:
        f.write(text[:cut_at])
    dcut_mcap = os.path.join(work, "cut-candump.mcap")
    r = run("export", dcut, "--mcap", dcut_mcap)
    check(r.returncode == 5 and "cut" in r.stderr and "incomplete" in r.stderr,
          f"a cut candump log: exit 5 with a message ({r.returncode}: {r.stderr.strip()[:200]})")
    want = whole_command_sets(text[:cut_at])
    ok, out = read_out(dcut_mcap, "--export", scene, "--incomplete", "--prefix", "--frames-every", "1", "--bus-log", log)
    check(ok and frames_in(out) == f"{want} + {want}",
          f"a cut candump log: its {want} whole ticks (counted here from the lines) are in the file, equal to the "
          f"bus log's, marked incomplete")
    # A line that is not a frame line: the ticks before it, exit 5.
    bad_line = len(lines) // 3
    dbad = os.path.join(work, "badline.candump")
    with open(dbad, "w") as f:
        f.write("".join(lines[:bad_line]) + "(0000000001.000000) vcan0 ZZZ##5\n" + "".join(lines[bad_line + 1:]))
    r = run("export", dbad, "--mcap", os.path.join(work, "badline.mcap"))
    check(r.returncode == 5 and f"line {bad_line + 1} is not a candump frame line" in r.stderr,
          f"a malformed line: exit 5 naming the line ({r.returncode}: {r.stderr.strip()[:200]})")
    want = whole_command_sets("".join(lines[:bad_line]) + "x")
    ok, out = read_out(os.path.join(work, "badline.mcap"), "--export", scene, "--incomplete", "--prefix",
                       "--frames-every", "1", "--bus-log", log)
    check(ok and frames_in(out) == f"{want} + {want}", f"a malformed line: the {want} ticks before it, incomplete")
    # A damaged frame (its CRC byte changed): the decoder rejects it; the ticks without both
    # sets are missing, the rest is exported and the file says incomplete.
    at = len(lines) // 2
    while not lines[at].startswith("(") or "##" not in lines[at]:
        at += 1
    ln = lines[at].rstrip("\n")
    i = ln.index("##") + 3  # the first data byte: the CRC-8
    damaged_line = ln[:i] + ("0" if ln[i] != "0" else "1") + ln[i + 1:] + "\n"
    ddmg = os.path.join(work, "damaged.candump")
    with open(ddmg, "w") as f:
        f.write("".join(lines[:at]) + damaged_line + "".join(lines[at + 1:]))
    r = run("export", ddmg, "--mcap", os.path.join(work, "damaged-candump.mcap"))
    check(r.returncode == 5 and "no complete sensor and command set" in r.stderr and "bad CRC" in r.stderr,
          f"a damaged frame: exit 5, the missing ticks and the decoder's reason ({r.returncode}: {r.stderr.strip()[:240]})")
    check(read(os.path.join(work, "damaged-candump.mcap"), "--export", scene, "--incomplete", "--prefix",
               "--frames-every", "1", "--bus-log", log),
          "a damaged frame: every other tick's frames in the file, equal to the bus log's, marked incomplete")
    # Another map: refused, nothing written.
    other = os.path.join(work, "othermap.candump")
    with open(other, "w") as f:
        f.write("".join(("# can-map " + ln.split()[2] + " 0123456789abcdef\n") if ln.startswith("# can-map ") else ln
                        for ln in lines))
    r = run("export", other, "--mcap", os.path.join(work, "othermap.mcap"))
    check(r.returncode == 5 and "CAN map" in r.stderr and not os.path.exists(os.path.join(work, "othermap.mcap")),
          f"a log of another CAN map: exit 5, nothing written ({r.returncode}: {r.stderr.strip()[:200]})")
    # A real CAN run's log (committed: tests/mcap/fixtures/ship-roll-damper-active-100.candump, recorded by
    #   hil/vcan-run -- gyrostab run sim/scenes/ship-roll-damper-active.toml --ticks 100 --transport can
    #                   --can-if vcan0 --can-log FILE
    # in the project's VM): its export equals the in-process run's bus log of the same ticks, bit for bit. A
    # change of the device's signal table changes its CAN map: then the export refuses the fixture (exit 5,
    # "recorded with the CAN map") and it is recorded again with that command.
    fixture = os.path.join(src, "tests/mcap/fixtures/ship-roll-damper-active-100.candump")
    flog = os.path.join(work, "run100.lcmlog")
    r = run("run", scene, "--no-progress", "--ticks", "100", "--out", os.path.join(work, "out100"), "--log", flog)
    fmcap = os.path.join(work, "real-can.mcap")
    r2 = run("export", fixture, "--mcap", fmcap)
    check(r.returncode == 0 and r2.returncode == 0,
          f"a real CAN run's candump log exports, exit 0 ({r.returncode}, {r2.returncode}: {r2.stderr.strip()[:240]})")
    check(r2.returncode == 0 and read(fmcap, "--export", scene, "--frames-every", "1", "--bus-log", flog),
          "a real CAN run's frames (lockstep over vcan in the VM) equal the in-process run's bus log, bit for bit")
    # candump's own log (no gyrostab header): refused, nothing written.
    plain = os.path.join(work, "bus.candump")
    with open(plain, "w") as f:
        f.write("(0.000000) vcan0 123#DEADBEEF\n")
    r = run("export", plain, "--mcap", os.path.join(work, "dump.mcap"))
    check(r.returncode == 2 and "candump" in r.stderr and not os.path.exists(os.path.join(work, "dump.mcap")),
          f"a candump log without gyrostab's header: refused with a message ({r.returncode})")
    check(not [n for n in os.listdir(work) if ".tmp-" in n], "no temporary file left beside any MCAP file")
    print(f"{'all checks passed' if not FAILS else str(len(FAILS)) + ' checks failed'} in {time.time() - t0:.1f} s")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
