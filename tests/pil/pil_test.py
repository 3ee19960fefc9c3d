#!/usr/bin/env python3
"""Processor in the loop (label pil): every controller image on QEMU's Cortex-M7 against the plant (docs/pil.md).

Checks, each with `gyrostab run SCENE --transport target` (the image of BUILD/arm/m7, -icount shift=0):
  1. every image boots, takes its scene's configuration and steps in lockstep: a short run of every shipped
     scene of a device with a firmware controller gives a signals.csv identical byte for byte to the
     in-process run of the same scene and seed (the scenes come from sim/scenes/, the images from
     firmware/target/images/: no hand-kept list; 43 scenes and 18 images at the time of writing);
  2. two whole scenes on the target are bit-identical to in process: the monorail (60 000 ticks) and the power
     stabilizer with DC drives (100 000 ticks, current loops at 10 kHz);
  3. the board's UART carries the same frames (--target-link uart): identical for 300 ticks;
  4. replay: the in-process run's bus log fed to the image (`gyrostab replay LOG --target`): every actuator
     frame identical;
  5. faults on the link, counted by the image with their cause, and the safe state: two corrupted sensor
     frames in a row (the image steps both ticks without a frame: hold, then the latched safe state with
     kSensorMissing), a stale copy (alive counter repeated), a skipped alive counter;
  6. the emulator killed mid-run: exit 6 within the receive timeout, the message says so, report.json and
     the bus log are written, and the log replays identical up to the lost tick;
  7. the emulator hung (SIGSTOP): exit 6 within the receive timeout;
  8. an image that never boots (not an image: QEMU runs it as raw code and it never says Hello; a program that
     crashes the emulator; an emulator that exits at once): exit 6 with the reason, within the start timeout;
  9. a configuration the image's start-up check refuses: exit 2 with the check's reason; the wrong device's
     image: exit 2.

Usage: pil_test.py BUILD_DIR. Exit 0: passed; 1: a failure (printed); 77: no qemu-system-arm or no images
(ctest reports the test as skipped).
"""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib

SENSOR_MISSING_BIT = 1 << 0  # FaultBit::kSensorMissing (firmware/msg/fault_bits.hpp)
SAFE_STATE_BIT = 1 << 9  # FaultBit::kSafeState

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def image_devices():
    """The devices with a firmware controller image: firmware/target/images/<device>_image.cpp (the file that
    tools/cross/build-firmware-arm builds into BUILD/arm/m7/<device>.elf)."""
    folder = os.path.join(ROOT, "firmware", "target", "images")
    return sorted(f[:-len("_image.cpp")] for f in os.listdir(folder) if f.endswith("_image.cpp"))


def shipped_scenes():
    """Every shipped scene (sim/scenes/*.toml) and its [scene] device, by file name."""
    out = {}
    folder = os.path.join(ROOT, "sim", "scenes")
    for f in sorted(os.listdir(folder)):
        if f.endswith(".toml"):
            with open(os.path.join(folder, f), "rb") as fh:
                out[f[:-len(".toml")]] = tomllib.load(fh)["scene"]["device"]
    return out


# Every shipped scene whose device has a firmware image, and its image (= its device).
SCENES = {scene: device for scene, device in shipped_scenes().items() if device in image_devices()}

failures = []


def check(ok, what):
    print("  %s %s" % ("ok  " if ok else "FAIL", what))
    if not ok:
        failures.append(what)
    return ok


class Env:
    def __init__(self, build, work):
        self.bin = os.path.join(build, "bin", "gyrostab")
        self.images = os.path.join(build, "arm", "m7")
        self.root = ROOT
        self.work = work

    def scene(self, name):
        return os.path.join(self.root, "sim", "scenes", name + ".toml")

    def run(self, args, timeout=120):
        t0 = time.monotonic()
        p = subprocess.run([self.bin] + args, capture_output=True, text=True, timeout=timeout)
        return p.returncode, p.stderr, time.monotonic() - t0

    def out(self, name):
        return os.path.join(self.work, name)


def same_file(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def report(out):
    with open(os.path.join(out, "report.json")) as f:
        return json.load(f)


def pair(env, scene, extra, tag, target_extra=()):
    """In process and on the target, same scene and options; True when signals.csv is identical."""
    a, b = env.out(tag + "-in"), env.out(tag + "-target")
    rc_a, err_a, _ = env.run(["run", env.scene(scene), "--out", a] + extra)
    rc_b, err_b, secs = env.run(["run", env.scene(scene), "--transport", "target", "--out", b] + extra
                                + list(target_extra))
    if rc_a != 0 or rc_b != 0:
        check(False, "%s: exit codes in process %d, target %d: %s %s" % (tag, rc_a, rc_b, err_a[-300:], err_b[-300:]))
        return False
    same = same_file(os.path.join(a, "signals.csv"), os.path.join(b, "signals.csv"))
    r = report(b)
    ticks = r["timing"]["target"]["ticks"]
    check(same, "%s: signals.csv identical in process and on the target (%d ticks, %.1f s)" % (tag, ticks, secs))
    return same


def status_at(csv_path, tick_column, tick):
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        if round(float(row[tick_column])) >= tick:
            return int(float(row["status_bits"]))
    return None


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    build = os.path.abspath(sys.argv[1])
    if shutil.which("qemu-system-arm") is None:
        print("SKIP: qemu-system-arm not installed (apt-get install qemu-system-arm)")
        return 77
    work = tempfile.mkdtemp(prefix="gyrostab-pil-test-")
    env = Env(build, work)
    if not all(os.path.exists(os.path.join(env.images, i + ".elf")) for i in set(SCENES.values())):
        print("SKIP: no controller images in %s (tools/cross/build-firmware-arm: arm-none-eabi-g++ missing?)" % env.images)
        return 77
    try:
        print("1. every image, every scene of its device: 3000 ticks, in process vs target")
        no_image = sorted(set(shipped_scenes().values()) - set(image_devices()))
        check(len(SCENES) > 0, "%d shipped scenes of %d devices with an image%s" % (
            len(SCENES), len(set(SCENES.values())), "; no image: " + ", ".join(no_image) if no_image else ""))
        for scene in SCENES:
            pair(env, scene, ["--ticks", "3000"], scene)

        print("2. two whole scenes")
        pair(env, "monorail", [], "monorail-whole")
        pair(env, "power-stabilizer-drive", [], "power-stabilizer-drive-whole")

        print("3. the board's UART")
        # The emulated UART moves about 130 ticks/s; on a machine loaded by the other tests a tick can take longer
        # than the default 1 s receive timeout, and what is checked here is the bytes, not the time.
        pair(env, "ship-roll-damper-active", ["--ticks", "300"], "uart", ["--target-link", "uart", "--timeout-ms", "10000"])

        print("4. replay of a bus log into the image")
        log = env.out("monorail.lcmlog")
        rc, err, _ = env.run(["run", env.scene("monorail"), "--ticks", "5000", "--log", log, "--out", env.out("log-run")])
        check(rc == 0, "in-process run with --log (exit %d)" % rc)
        rc, err, secs = env.run(["replay", log, "--target"])
        check(rc == 0 and "5000 ticks" in err,
              "replay --target: every actuator frame identical (exit %d, %.1f s): %s" % (rc, secs, err.strip()[-200:]))

        print("5. faults on the target link")
        out = env.out("faults")
        rc, err, _ = env.run(["run", env.scene("ship-roll-damper-active"), "--transport", "target", "--ticks", "2000",
                              "--target-fault", "corrupt:1000:2", "--target-fault", "stale:1500:1",
                              "--target-fault", "skip:1700:1", "--out", out])
        check(rc == 0, "the run completes (exit %d) %s" % (rc, err.strip()[-300:]))
        if rc == 0:
            t = report(out)["link"]["target"]
            refused = t["image_refused"]
            check(refused["crc"] + refused["framing"] == 2, "two corrupted frames refused (CRC %d, framing %d)"
                  % (refused["crc"], refused["framing"]))
            check(refused["repeated"] == 1, "the stale copy refused: alive counter repeated (%d)" % refused["repeated"])
            # As on CAN, a frame lost to its CRC leaves the alive counter behind: the next frame is refused as
            # skipped and resynchronises the counter (one after the corrupted pair, one injected).
            check(refused["skipped"] == 2, "skipped alive counters refused (%d, expected 2)" % refused["skipped"])
            check(t["image_ticks"]["without_frame"] == 5, "five ticks stepped without a frame (%d)"
                  % t["image_ticks"]["without_frame"])
            before = status_at(os.path.join(out, "signals.csv"), "t_s", 0.95)
            after = status_at(os.path.join(out, "signals.csv"), "t_s", 1.05)
            check(before is not None and before & SAFE_STATE_BIT == 0, "no safe state before the faults (0x%x)" % (before or 0))
            want = SAFE_STATE_BIT | SENSOR_MISSING_BIT
            check(after is not None and after & want == want,
                  "the safe state with kSensorMissing after two lost frames (status 0x%x)" % (after or 0))

        print("6. the emulator dies")
        out, log = env.out("killed"), env.out("killed.lcmlog")
        rc, err, secs = env.run(["run", env.scene("ship-roll-damper-active"), "--transport", "target", "--ticks", "5000",
                                 "--target-fault", "kill:1000", "--timeout-ms", "500", "--log", log, "--out", out])
        check(rc == 6 and "killed" in err, "exit 6, the message names the kill (exit %d, %.1f s): %s"
              % (rc, secs, err.strip()[-300:]))
        check(secs < 5.0, "ended within the receive timeout plus start-up (%.1f s)" % secs)
        check(os.path.exists(os.path.join(out, "report.json")) and report(out)["link"]["peer"]["lost"],
              "report.json written, link.peer.lost")
        rc, err, _ = env.run(["replay", log])
        check(rc == 4 and "the 1000 ticks before it are identical" in err,
              "the log is valid and replays identical up to the lost tick (exit %d): %s" % (rc, err.strip()[-200:]))

        print("7. the emulator hangs")
        out = env.out("frozen")
        rc, err, secs = env.run(["run", env.scene("ship-roll-damper-active"), "--transport", "target", "--ticks", "5000",
                                 "--target-fault", "freeze:1000", "--timeout-ms", "500", "--out", out])
        check(rc == 6 and "hung" in err, "exit 6, the message says it hung (exit %d, %.1f s): %s"
              % (rc, secs, err.strip()[-300:]))
        check(secs < 5.0, "ended within the receive timeout plus start-up (%.1f s)" % secs)

        print("8. images that never boot")
        bogus = env.out("not-an-image.elf")
        with open(bogus, "w") as f:
            f.write("not an ELF file\n")
        rc, err, secs = env.run(["run", env.scene("monorail"), "--transport", "target", "--target-image", bogus,
                                 "--start-timeout-ms", "3000", "--out", env.out("bogus")])
        check(rc == 6 and "did not boot" in err,
              "not an image (QEMU runs it as raw code): exit 6 at the start timeout (exit %d, %.1f s): %s"
              % (rc, secs, err.strip()[-300:]))
        rc, err, secs = env.run(["run", env.scene("monorail"), "--transport", "target", "--qemu", "/bin/false",
                                 "--out", env.out("no-emulator")])
        check(rc == 6 and "exited with status 1" in err and secs < 2.0,
              "an emulator that exits at once: exit 6 at once, its exit named (exit %d, %.1f s): %s"
              % (rc, secs, err.strip()[-300:]))
        # The Cortex-M4F proof program locks up on this board; QEMU aborts.
        crashing = os.path.join(build, "arm", "firmware.elf")
        rc, err, secs = env.run(["run", env.scene("monorail"), "--transport", "target", "--target-image", crashing,
                                 "--out", env.out("crashing")])
        check(rc == 6 and "did not boot" in err and "killed by SIG" in err and secs < 2.0,
              "a program that crashes the emulator: exit 6 at once, the signal named (exit %d, %.1f s): %s"
              % (rc, secs, err.strip()[-300:]))

        print("9. refusals")
        rc, err, _ = env.run(["run", env.scene("monorail"), "--transport", "target", "--target-fault", "config",
                              "--out", env.out("refused")])
        check(rc == 2 and "start-up check on the target" in err and "tick_period_ns" in err,
              "a configuration the image refuses: exit 2 with its reason: %s" % err.strip()[-300:])
        rc, err, _ = env.run(["run", env.scene("monorail"), "--transport", "target", "--target-image",
                              os.path.join(env.images, "servo_gyro.elf"), "--out", env.out("wrong")])
        check(rc == 2 and "servo_gyro" in err, "another device's image: exit 2: %s" % err.strip()[-300:])
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
