#!/usr/bin/env python3
"""ctest label `mcap`: one shipped scene run with --mcap, read back by an independent reader.

  mcap_scene_test.py GYROSTAB SCENE WORKDIR NODE_MODULES [--lcm]

Runs `gyrostab run SCENE --ticks N --mcap WORKDIR/run.mcap` (N = the scene's own ticks: its whole run; the
environment's GYROSTAB_MCAP_MAX_TICKS caps it), then tests/mcap/mcap_readback.cjs (Foxglove's @mcap/core under Debian's node) reads
every message back, through the indexes and record by record with every CRC checked, and compares each value
with signals.csv and the report message with report.json; the frame channels hold one sensor and one actuator
frame per recorded tick, every field typed and described (tests/mcap/mcap_frames_test.py compares frames with
the bus log). Exit 77 (skip) when node or @mcap/core is missing
(tools/setup installs both). With --lcm: plant and controller as two processes over LCM (at most 100 000 ticks), in a private network
namespace (unshare -n, loopback multicast; exit 77 where that is not permitted), with --view too: the file is
written from the plant's signals.csv and the merged report."""
import os
import shutil
import subprocess
import sys
import tomllib

# A scene's run takes at most a few seconds and its readback less: a step still going after this has hung.
STEP_TIMEOUT_S = 240


def run_step(what, cmd, **kw):
    """subprocess.run with STEP_TIMEOUT_S; a step that hangs is reported with its process state (R running,
    S sleeping and where, T stopped by a signal) and what it printed so far, then killed."""
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **kw)
    try:
        out, err = p.communicate(timeout=STEP_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        state = "?"
        try:
            with open(f"/proc/{p.pid}/stat") as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
            with open(f"/proc/{p.pid}/wchan") as f:
                state += " in " + (f.read() or "-")
        except OSError:
            pass
        p.kill()
        out, err = p.communicate()
        print(out, err)
        print(f"FAIL: {what} still running after {STEP_TIMEOUT_S} s (process state {state}): killed")
        return None
    return subprocess.CompletedProcess(cmd, p.returncode, out, err)

# GYROSTAB_MCAP_MAX_TICKS=N caps every scene at N ticks (0, the default: the scene's full duration).
MAX_TICKS = int(os.environ.get("GYROSTAB_MCAP_MAX_TICKS", "0"))


def main():
    gyrostab, scene, work, node_modules = sys.argv[1:5]
    lcm = "--lcm" in sys.argv[5:]
    node = shutil.which("node")
    if node is None or not os.path.isdir(os.path.join(node_modules, "@mcap", "core")):
        print("skip: node or @mcap/core missing (tools/setup installs them)")
        return 77
    with open(scene, "rb") as f:
        s = tomllib.load(f)
    tick_ns = int(round(float(s.get("loop", {}).get("tick_us", 1000)) * 1000))
    every = int(s.get("output", {}).get("record_every", 10))  # the frame channels' default: the recorded ticks
    ticks = int(round(float(s["scene"]["duration_s"]) * 1e9 / tick_ns))
    if MAX_TICKS > 0:
        ticks = min(ticks, MAX_TICKS)
    if lcm:
        ticks = min(ticks, 100_000)  # lockstep over LCM runs at a few 10 000 ticks/s: the first 100 s of the run
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out, mcap = os.path.join(work, "out"), os.path.join(work, "run.mcap")
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    cmd = [gyrostab, "run", scene, "--no-progress", "--ticks", str(ticks), "--out", out, "--mcap", mcap]
    if lcm:
        cmd = ["unshare", "-n", "--", "sh", "-c", "ip link set lo up && ip link set lo multicast on && "
               "ip route add 224.0.0.0/4 dev lo && exec \"$@\"", "sh", *cmd, "--transport", "lcm", "--view",
               "--view-linger", "0"]
        probe = subprocess.run(["unshare", "-n", "true"], capture_output=True)
        if probe.returncode != 0:
            print("skip: no private network namespace here (unshare -n)")
            return 77
    r = run_step("gyrostab run", cmd, env=env)
    if r is None:
        return 1
    if r.returncode not in (0, 3):  # 3: a scene that ends in its safe state or diverges still writes its outputs
        print(r.stdout, r.stderr)
        print(f"FAIL: gyrostab run exited {r.returncode}")
        return 1
    if not os.path.exists(mcap):
        print(r.stdout, r.stderr)
        print("FAIL: no MCAP file written")
        return 1
    leftovers = [n for n in os.listdir(work) if n.startswith("run.mcap.tmp")]
    if leftovers:
        print(f"FAIL: temporary files left beside the MCAP file: {leftovers}")
        return 1
    here = os.path.dirname(os.path.abspath(__file__))
    r = run_step("the readback (node)", [node, os.path.join(here, "mcap_readback.cjs"), mcap, "--csv",
                                          os.path.join(out, "signals.csv"), "--report", os.path.join(out, "report.json"),
                                          "--frames-every", str(every)],
                 env=dict(os.environ, NODE_PATH=node_modules))
    if r is None:
        return 1
    print(r.stdout, r.stderr, end="")
    return r.returncode


if __name__ == "__main__":
    sys.exit(main())
