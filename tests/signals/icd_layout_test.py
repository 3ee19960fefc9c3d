#!/usr/bin/env python3
"""The byte offsets the interface control documents give (tools/signals/icd.py) are where lcm-gen's own encoder
puts each field.

For every device table: the two .lcm types generate.py writes, compiled by `lcm-gen -p` into Python, one message
with a distinct value in every field (each array element its own), encoded by lcm-gen's code; then every row of
icd.lcm_fields() must find its value at its offset and size, big-endian, the fingerprint in the first 8 bytes,
and the rows must tile the message exactly. An independent check of the documents' layout: it shares only the
member list with the generator.

Usage: icd_layout_test.py LCM_GEN TABLE...   Under 5 s.
"""

import importlib
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "signals"))

import generate  # noqa: E402
import icd  # noqa: E402
from signal_table import load  # noqa: E402

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print("FAIL", what)


def fill(msg, t, direction):
    """Distinct values in every field; returns {field name: [expected bytes of each element]}."""
    header = generate.SENSOR_HEADER if direction == "sensor" else generate.ACTUATOR_HEADER
    signals = t.sensors if direction == "sensor" else t.commands
    expected = {}
    k = 1
    for name, _, lt, _, _ in header:
        v = 0x0102030405060700 + k if lt == "int64_t" else 0x01020300 + k
        setattr(msg, name, v)
        expected[name] = struct.pack(">q" if lt == "int64_t" else ">i", v)
        k += 1
    for s in signals:
        vals = [1000.0 * k + 0.25 * e for e in range(s.count)]
        k += 1
        setattr(msg, s.name, vals if s.count > 1 else vals[0])
        expected[s.name] = b"".join(struct.pack(">d", v) for v in vals)
    for name, _ in generate.TRAILER:
        v = -0x0A0B0C0D0E0F0000 - k
        setattr(msg, name, v)
        expected[name] = struct.pack(">q", v)
        k += 1
    return expected


def main(argv):
    if len(argv) < 2:
        print(__doc__)
        return 2
    lcm_gen, tables = argv[0], [load(Path(p)) for p in argv[1:]]
    with tempfile.TemporaryDirectory(prefix="gyrostab-icd-layout-") as tmp:
        tmp = Path(tmp)
        lcm_files = []
        for t in tables:
            for d in ("sensor", "actuator"):
                p = tmp / "lcm" / f"{generate.lcm_type(t, d)}.lcm"
                p.parent.mkdir(exist_ok=True)
                p.write_text(generate.lcm_file(t, d))
                lcm_files.append(str(p))
        subprocess.run([lcm_gen, "-p", "--ppath", str(tmp / "py")] + lcm_files, check=True)
        sys.path.insert(0, str(tmp / "py"))
        checked = 0
        for t in tables:
            for d in ("sensor", "actuator"):
                name = generate.lcm_type(t, d)
                cls = getattr(importlib.import_module(f"gyrostab_msg.{name}"), name)
                msg = cls()
                expected = fill(msg, t, d)
                wire = msg.encode()
                fields = icd.lcm_fields(t, d)
                where = f"{t.device} {d}"
                check(len(wire) == generate.encoded_size(t, d) == fields[-1][0] + fields[-1][1],
                      f"{where}: lcm-gen encodes {len(wire)} bytes, the ICD says {generate.encoded_size(t, d)}")
                check(wire[:8] == struct.pack(">Q", generate.fingerprint(t, d)),
                      f"{where}: fingerprint {wire[:8].hex()} != {generate.fingerprint(t, d):016x}")
                at = 0
                for offset, size, field, _, _ in fields:
                    check(offset == at, f"{where}: {field} at {offset}, the previous field ends at {at}")
                    at = offset + size
                    if field.startswith("("):
                        continue
                    check(wire[offset:offset + size] == expected[field],
                          f"{where}: {field}: bytes {offset}..{offset + size - 1} are "
                          f"{wire[offset:offset + size].hex()}, lcm-gen wrote {expected[field].hex()} elsewhere")
                    checked += 1
                check(set(expected) == {f[2] for f in fields if not f[2].startswith("(")},
                      f"{where}: the ICD's fields are not the type's fields")
        print(f"{checked} fields of {2 * len(tables)} LCM types at the offsets their ICDs give")
    return 1 if failures or not checked else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
