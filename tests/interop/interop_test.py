#!/usr/bin/env python3
"""ctest label `interop`: an outside controller closes the loop of `gyrostab plant` over LCM.

  interop_test.py GYROSTAB INTEROP_CONTROLLER SOURCE_DIR WORKDIR

INTEROP_CONTROLLER is tests/interop/interop_controller.c: C11 against the `lcm-gen -c` bindings of the device's
generated .lcm types, liblcm and libsodium, written from docs/protocol.md, docs/transport.md, docs/scenes.md and
the devices' docs pages only (no project header or library). Runs itself inside a private network namespace
(unshare -n; exit 77 where that is not permitted), ttl=0. First: the controller's sources include nothing but the
C library, liblcm, libsodium and lcm-gen's headers.

For the monorail (3000 ticks) and the active ship roll damper (5000 ticks), unkeyed and with --key-file (a key
file of mode 600 on both ends), `gyrostab plant SCENE --ticks N` runs against the C controller, which learns
neither N nor the session: it binds at the handshake, answers in lockstep and stops on the plant's end-of-run
frame. Checked each time: both exit 0, the controller acknowledged the end of run at tick N after N answers and
refused nothing, the plant's signals.csv is byte for byte the in-process run's (`gyrostab run SCENE --ticks N`)
and report.json's figures are equal. Two more runs (the monorail unkeyed, the ship keyed) lose every 500th
answer on purpose: the plant resends its sensor frame after 20 ms, the controller answers it again with a new
freshness (and MAC), and the results are still the in-process run's. Last, a controller built for another
scene (the monorail with another gain) refuses the plant's frames with both scene hashes and never binds: both
exit 6 after their start timeouts. About 3 s."""
import json
import os
import re
import shutil
import subprocess
import sys
import time

FAILS = []
KEY = "000102030405060708090a0b0c0d0e0f\n"
CASES = [
    # scene, ticks, keyed, lose_every
    ("monorail.toml", 3000, False, 0),
    ("monorail.toml", 3000, True, 0),
    ("ship-roll-damper-active.toml", 5000, False, 0),
    ("ship-roll-damper-active.toml", 5000, True, 0),
    ("monorail.toml", 3000, False, 500),
    ("ship-roll-damper-active.toml", 5000, True, 500),
]


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        FAILS.append(what)


def figures(out):
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)["figures"]


def read(path):
    with open(path, "rb") as f:
        return f.read()


ALLOWED_INCLUDE = re.compile(r'^(<(ctype|errno|math|stdint|stdio|stdlib|string|time|sys/stat)\.h>|<lcm/lcm\.h>|'
                             r'<sodium\.h>|"gyrostab_msg_\w+\.h"|"outside_cos\.h")$')


def outside_only(src):
    """The controller's own sources include the C library, liblcm, libsodium, lcm-gen's output and each other:
    nothing of the project (firmware/, hil/, sim/, tools/, generated gyrostab_signals/)."""
    includes, bad = 0, []
    for name in ("interop_controller.c", "outside_cos.h"):
        with open(os.path.join(src, "tests/interop", name)) as f:
            for n, line in enumerate(f, 1):
                m = re.match(r"\s*#\s*include\s+(\S+)", line)
                if m:
                    includes += 1
                    if not ALLOWED_INCLUDE.match(m.group(1)):
                        bad.append(f"{name}:{n} {m.group(1)}")
    check(includes > 0 and not bad, f"the controller's {includes} includes are the C library's, lcm's, sodium's or "
                                    f"lcm-gen's ({', '.join(bad) or 'none other'})")


def inside(gyrostab, controller, src, work):
    outside_only(src)
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    subprocess.run(["ip", "link", "set", "lo", "up"], check=True)
    subprocess.run(["ip", "link", "set", "lo", "multicast", "on"], check=True)
    subprocess.run(["ip", "route", "add", "224.0.0.0/4", "dev", "lo"], check=True)
    key = os.path.join(work, "link.key")
    with open(key, "w") as f:
        f.write(KEY)
    os.chmod(key, 0o600)
    refs = {}
    for n, (scene_file, ticks, keyed, lose_every) in enumerate(CASES):
        scene = os.path.join(src, "sim/scenes", scene_file)
        name = f"{scene_file[:-5]} {'keyed' if keyed else 'unkeyed'}" + (f", every {lose_every}th answer lost"
                                                                        if lose_every else "")
        if (scene_file, ticks) not in refs:
            ref = os.path.join(work, f"inproc-{scene_file[:-5]}")
            r = subprocess.run([gyrostab, "run", scene, "--no-progress", "--ticks", str(ticks), "--out", ref],
                               env=env, capture_output=True, text=True, timeout=300)
            check(r.returncode == 0, f"{scene_file}: the in-process run exits 0 ({r.returncode} {r.stderr[-300:]})")
            refs[(scene_file, ticks)] = ref
        ref = refs[(scene_file, ticks)]
        out = os.path.join(work, f"plant-{n}")
        key_args = ["--key-file", key] if keyed else []
        t0 = time.time()
        plant = subprocess.Popen([gyrostab, "plant", scene, "--ticks", str(ticks), "--out", out] + key_args,
                                 env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        ctl_args = [controller, scene] + key_args + (["--lose-every", str(lose_every)] if lose_every else [])
        try:
            ctl = subprocess.run(ctl_args, capture_output=True, text=True, timeout=120)
        finally:
            plant_out, _ = plant.communicate(timeout=120)
        wall = time.time() - t0
        check(ctl.returncode == 0, f"{name}: the C controller exits 0 on the end-of-run frame ({ctl.returncode}: "
                                   f"{ctl.stdout.strip()} {ctl.stderr.strip()[-300:]})")
        check(plant.returncode == 0, f"{name}: the plant exits 0 ({plant.returncode}: {plant_out.strip()[-400:]})")
        m = re.search(r"end of run at tick (\d+) acknowledged; (\d+) answers \((\d+) lost on purpose\), (\d+) resends"
                      r", (\d+) end-of-run acknowledgements; refused: (\d+) foreign, (\d+) other scene, (\d+) MAC "
                      r"or freshness, (\d+) out of order", ctl.stdout)
        check(m is not None, f"{name}: the controller's summary")
        if m:
            tick, answers, lost, resends, acks, foreign, other, bad, stale = map(int, m.groups())
            check(tick == ticks and answers == ticks and acks >= 1,
                  f"{name}: end of run acknowledged at tick {tick} (plant --ticks {ticks}) after {answers} answers")
            check(lost == (ticks // lose_every if lose_every else 0) and resends == lost,
                  f"{name}: {lost} answers lost, {resends} answered again on the plant's resend")
            check(foreign == 0 and other == 0 and bad == 0,
                  f"{name}: nothing refused ({foreign} foreign, {other} other scene, {bad} MAC or freshness)")
        same_csv = os.path.exists(os.path.join(out, "signals.csv")) and \
            read(os.path.join(ref, "signals.csv")) == read(os.path.join(out, "signals.csv"))
        check(same_csv, f"{name}: signals.csv byte-identical to the in-process run ({wall:.1f} s)")
        same_fig = os.path.exists(os.path.join(out, "report.json")) and figures(ref) == figures(out)
        check(same_fig, f"{name}: report.json figures equal to the in-process run's")
    # A controller built for another scene (the monorail with k = 5600): it refuses the plant's frames, naming both
    # hashes, and never binds; both ends give up after their start timeout (exit 6).
    scene = os.path.join(src, "sim/scenes/monorail.toml")
    with open(scene) as f:
        text = f.read()
    other = os.path.join(work, "monorail-other-gain.toml")
    with open(other, "w") as f:
        f.write(re.sub(r"(?m)^k = 5500", "k = 5600", text))
    plant = subprocess.Popen([gyrostab, "plant", scene, "--ticks", "100", "--start-timeout-ms", "1500", "--out",
                              os.path.join(work, "plant-other")], env=env, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, text=True)
    try:
        ctl = subprocess.run([controller, other, "--start-timeout-ms", "1000"], capture_output=True, text=True,
                             timeout=60)
    finally:
        plant_out, _ = plant.communicate(timeout=60)
    check(ctl.returncode == 6 and re.search(r"refusing frames of scene [0-9a-f]{16} \(ours [0-9a-f]{16}\)",
                                            ctl.stderr) is not None,
          f"a controller of another scene refuses the plant's frames with both hashes and exits 6 ({ctl.returncode}: "
          f"{ctl.stderr.strip()[-300:]})")
    check(plant.returncode == 6, f"its plant gets no answer and exits 6 ({plant.returncode}: {plant_out.strip()[-200:]})")
    return 1 if FAILS else 0


def main():
    gyrostab, controller, src, work = sys.argv[1:5]
    if "--inside" in sys.argv:
        t0 = time.time()
        rc = inside(gyrostab, controller, src, work)
        print(f"{'all checks passed' if rc == 0 else str(len(FAILS)) + ' checks failed'} in {time.time() - t0:.1f} s")
        return rc
    if subprocess.run(["unshare", "-n", "true"], capture_output=True).returncode != 0:
        print("skip: no private network namespace here (unshare -n)")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    return subprocess.run(["unshare", "-n", sys.executable, os.path.abspath(__file__), gyrostab, controller, src,
                           work, "--inside"]).returncode


if __name__ == "__main__":
    sys.exit(main())
