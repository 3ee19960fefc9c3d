#!/usr/bin/env python3
"""Every Cortex-M7 controller image boots on the emulated target and runs its controller (label pil).

For each image of tools/cross/build-firmware-arm (BUILD/arm/m7/*.elf): QEMU's mps2-an500 (a Cortex-M7 with the
double-precision FPU) runs it with deterministic instruction timing (-icount shift=0, sleep=off); the test
reads the image's memory through the QEMU monitor and requires that
  - SysTick paces the loop (g_systicks grows between two reads),
  - the real controller steps once per tick (g_actuator_tx.tick and .sequence grow with it),
  - the controller accepted its configuration (the device's defaults: no kConfigRefused bit), so its tasks
    are scheduled;
  - with no sensor frame ever delivered (there is no link yet), the firmware's fault monitor has put the
    command in its safe state, as on the host: the kSensorMissing, kAwaitingFirstFrame and kSafeState status
    bits, the precession brake on (1.0) and zero torque on both gimbal axes.
ActuatorFrame's layout is fixed by static_asserts in firmware/msg/actuator_frame.hpp (tick at 0, sequence at 24,
status at 28, gimbal_torque_Nm at 32, precession_brake at 64), the same on host and target.

Usage: pil_boot_test.py BUILD_DIR. Exit 0: every image passed; 1: a failure (printed); 77: no qemu-system-arm
(ctest reports the test as skipped).
"""
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time

# firmware/msg/fault_bits.hpp and firmware/control/law_status_bits.hpp
SENSOR_MISSING_BIT = 1 << 0  # FaultBit::kSensorMissing
SAFE_STATE_BIT = 1 << 9  # FaultBit::kSafeState
AWAITING_FIRST_FRAME_BIT = 1 << 10  # FaultBit::kAwaitingFirstFrame
CONFIG_REFUSED_BIT = 1 << 26  # LawStatusBit::kConfigRefused


def symbols(nm, elf):
    out = subprocess.run([nm, elf], check=True, capture_output=True, text=True).stdout
    table = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 3:
            table[parts[2]] = int(parts[0], 16)
    return table


class Monitor:
    """The QEMU human monitor over a unix socket: physical memory reads with `xp`."""

    def __init__(self, path, timeout_s=10.0):
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                self.sock = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
                self.sock.connect(path)
                break
            except OSError:
                self.sock.close()
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.02)
        self.sock.settimeout(timeout_s)
        self._read_until(b"(qemu) ")

    def _read_until(self, marker):
        data = b""
        while not data.endswith(marker):
            chunk = self.sock.recv(4096)
            if not chunk:
                raise RuntimeError("the QEMU monitor closed its socket")
            data += chunk
        return data

    def read(self, address, size):
        words = (size + 3) // 4
        self.sock.sendall(b"xp /%dwx 0x%x\n" % (words, address))
        text = self._read_until(b"(qemu) ").decode(errors="replace")
        values = []
        for line in text.splitlines():
            if ":" in line and line.strip().startswith(("0", "1", "2", "3", "4", "5", "6", "7", "8", "9")):
                values += [int(v, 16) for v in line.split(":", 1)[1].split()]
        if len(values) < words:
            raise RuntimeError("unexpected monitor answer: %r" % text)
        return struct.pack("<%dI" % words, *values[:words])[:size]


def check_image(qemu, nm, elf, workdir):
    name = os.path.basename(elf)[: -len(".elf")]
    sym = symbols(nm, elf)
    for s in ("g_systicks", "g_actuator_tx"):
        if s not in sym:
            return "%s: no symbol %s" % (name, s)
    mon_path = os.path.join(workdir, name + ".monitor")
    proc = subprocess.Popen(
        [qemu, "-M", "mps2-an500", "-display", "none", "-serial", "none", "-icount", "shift=0,sleep=off",
         "-monitor", "unix:%s,server=on,wait=off" % mon_path, "-kernel", elf],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        mon = Monitor(mon_path)
        time.sleep(0.3)
        first_ticks = struct.unpack("<I", mon.read(sym["g_systicks"], 4))[0]
        first = mon.read(sym["g_actuator_tx"], 72)
        time.sleep(0.3)
        ticks = struct.unpack("<I", mon.read(sym["g_systicks"], 4))[0]
        frame = mon.read(sym["g_actuator_tx"], 72)
    except Exception as e:  # noqa: BLE001 - any failure to talk to the emulator is this image's failure
        proc.kill()
        out = proc.communicate()[0].decode(errors="replace")
        return "%s: %s; qemu said: %s" % (name, e, out.strip()[-500:])
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    tick0 = struct.unpack_from("<Q", first, 0)[0]
    tick, = struct.unpack_from("<Q", frame, 0)
    sequence, status = struct.unpack_from("<II", frame, 24)
    torque = struct.unpack_from("<2d", frame, 32)
    brake, = struct.unpack_from("<d", frame, 64)
    print("  %-18s systicks %6d -> %6d, command tick %6d -> %6d, sequence %6d, status 0x%04x, brake %.1f, "
          "torque %s" % (name, first_ticks, ticks, tick0, tick, sequence, status, brake, torque))
    problems = []
    if not ticks > first_ticks > 0:
        problems.append("SysTick does not run (g_systicks %d then %d)" % (first_ticks, ticks))
    if not tick > tick0 > 0 or sequence < tick:
        problems.append("the controller does not step once per tick (tick %d then %d, sequence %d)"
                        % (tick0, tick, sequence))
    if status & CONFIG_REFUSED_BIT:
        problems.append("the controller refused its default configuration (status 0x%x)" % status)
    expected = SENSOR_MISSING_BIT | SAFE_STATE_BIT | AWAITING_FIRST_FRAME_BIT
    if status & expected != expected or brake != 1.0 or torque != (0.0, 0.0):
        problems.append("no safe state without sensor frames (status 0x%x, brake %r, torque %r)"
                        % (status, brake, torque))
    return "%s: %s" % (name, "; ".join(problems)) if problems else None


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    images_dir = os.path.join(sys.argv[1], "arm", "m7")
    qemu = shutil.which("qemu-system-arm")
    nm = shutil.which("arm-none-eabi-nm")
    if qemu is None or nm is None:
        print("pil_boot_test: qemu-system-arm or arm-none-eabi-nm not found (tools/setup installs both): skipped")
        return 77
    images = sorted(os.path.join(images_dir, f) for f in os.listdir(images_dir) if f.endswith(".elf")) \
        if os.path.isdir(images_dir) else []
    if not images:
        print("pil_boot_test: no image in %s (the build runs tools/cross/build-firmware-arm)" % images_dir)
        return 1
    failures = []
    with tempfile.TemporaryDirectory(prefix="gyrostab-pil-") as workdir:
        for elf in images:
            problem = check_image(qemu, nm, elf, workdir)
            if problem:
                failures.append(problem)
    for f in failures:
        print("FAIL " + f)
    print("pil_boot_test: %d of %d images boot and run their controller" % (len(images) - len(failures), len(images)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
