"""The interface control document of a device, generated from its signal table (generate.py --icd).

document(table) is docs/icd/<device>.md: the device and its scenes; every sensor, command, recorded column and
report figure with its symbol, unit, range, safe value and meaning; the two LCM types with their fingerprints
and every field's byte offset and size in the encoded message (the layout hil/lcm/frame_codec.hpp encodes,
from the same member list generate.py writes the .lcm files from); the CAN FD frames of can_layout.layout().
index(tables) is docs/icd/README.md: the devices with their bytes and frames per tick.

What every device shares (handshake, scene hash, lockstep, resends, end of run, MAC) is docs/protocol.md; the
documents link to it and do not repeat it.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import can_layout
import generate
from signal_table import CAN_DOUBLE, Signal, Table

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "sim" / "scenes"
REGENERATE = "ninja -C build icd"


def _cell(s: str) -> str:
    return " ".join(str(s).split()).replace("|", "\\|")


_POWERS = {float((1 << 64) - 1): "2^64 - 1", float((1 << 63) - 1): "2^63 - 1", -float(1 << 63): "-2^63"}


def _num(x: float) -> str:
    if float(x) in _POWERS:
        return _POWERS[float(x)]
    if x == int(x) and abs(x) < 1e16:
        return str(int(x))
    return repr(float(x))


def _range(lo: float, hi: float) -> str:
    return f"[{_num(lo)}, {_num(hi)}]"


def _hex(v: int, digits: int = 16) -> str:
    return f"0x{v:0{digits}x}"


def scenes_of(device: str) -> list[str]:
    """The shipped scene files (sim/scenes/, sub-folders included) whose [scene] device is this device."""
    out = []
    if not SCENES.is_dir():
        return out
    for p in sorted(SCENES.rglob("*.toml")):
        try:
            with p.open("rb") as f:
                d = tomllib.load(f)
        except (OSError, tomllib.TOMLDecodeError):
            continue
        scene = d.get("scene")
        if isinstance(scene, dict) and scene.get("device") == device:
            out.append(str(p.relative_to(ROOT)))
    return out


# --- LCM -----------------------------------------------------------------------------------------------------

def lcm_fields(t: Table, direction: str) -> list[tuple[int, int, str, str, str]]:
    """Every field of the encoded message in wire order: (offset, size, name, LCM type, meaning)."""
    header = generate.SENSOR_HEADER if direction == "sensor" else generate.ACTUATOR_HEADER
    signals = t.sensors if direction == "sensor" else t.commands
    out = [(0, 8, "(fingerprint)", "8 bytes", "the type's fingerprint (lcm-gen's getHash()): "
            f"{_hex(generate.fingerprint(t, direction))}")]
    at = 8
    for name, _, lt, doc, unit in header:
        size = 8 if lt == "int64_t" else 4
        out.append((at, size, name, lt, f"{doc} [{unit}]"))
        at += size
    for s in signals:
        size = 8 * s.count
        lt = f"double[{s.count}]" if s.count > 1 else "double"
        out.append((at, size, s.name, lt, f"{s.symbol} [{s.unit}]"))
        at += size
    for name, doc in generate.TRAILER:
        out.append((at, 8, name, "int64_t", doc))
        at += 8
    assert at == generate.encoded_size(t, direction), (t.device, direction, at)
    return out


def _lcm_section(t: Table, direction: str) -> list[str]:
    name = generate.lcm_type(t, direction)
    who = "plant → controller" if direction == "sensor" else "controller → plant"
    channel = "GYROSTAB_SENSOR" if direction == "sensor" else "GYROSTAB_ACTUATOR"
    size = generate.encoded_size(t, direction)
    fields = lcm_fields(t, direction)
    session_at = next(f[0] for f in fields if f[2] == "session")
    data_id = "0x53454E53 (\"SENS\")" if direction == "sensor" else "0x41435455 (\"ACTU\")"
    lines = [
        f"### `gyrostab_msg.{name}` ({who}, channel `{channel}<suffix>`)",
        "",
        f"Fingerprint `{_hex(generate.fingerprint(t, direction))}` (the message's first 8 bytes, big-endian); "
        f"{size} bytes encoded. The MAC (data id {data_id}) covers bytes 0 to {session_at - 1}.",
        "",
        "| offset | size | field | LCM type | meaning |",
        "|---:|---:|---|---|---|",
    ]
    for at, sz, field, lt, doc in fields:
        lines.append(f"| {at} | {sz} | `{field}` | {lt} | {_cell(doc)} |" if not field.startswith("(") else
                     f"| {at} | {sz} | {field} | {lt} | {_cell(doc)} |")
    lines.append("")
    return lines


# --- signals -------------------------------------------------------------------------------------------------

def _signal_rows(signals: list[Signal], command: bool) -> list[str]:
    head = "| name | symbol | unit | range | " + ("safe | " if command else "") + "count | node | CAN | description |"
    rule = "|---|---|---|---|" + ("---|" if command else "") + "---:|---|---|---|"
    rows = [head, rule]
    for s in signals:
        safe = f"{_num(s.safe)} | " if command else ""
        rows.append(f"| `{s.name}` | {_cell(s.symbol)} | {_cell(s.unit)} | {_range(s.lo, s.hi)} | {safe}{s.count} | "
                    f"{_cell(s.node)} | {s.can if s.can != CAN_DOUBLE else 'double'} | {_cell(s.description)} |")
    return rows


def _signals_section(t: Table) -> list[str]:
    lines = ["## Sensors (plant → controller)", ""]
    if t.sensors:
        lines += ["In frame order; an array's elements follow each other (element 1 first). The range is the "
                  "plausible range the controller's fault monitor holds a value to by default (a scene may "
                  "narrow it).", ""]
        lines += _signal_rows(t.sensors, False)
    else:
        lines.append("None: the sensor frame carries only its header and trailer.")
    lines += ["", "## Commands (controller → plant)", ""]
    if t.commands:
        lines += ["In frame order. The plant refuses a command outside its range; `safe` is the value the "
                  "controller sends in the safe state and in its answer to the end-of-run frame.", ""]
        lines += _signal_rows(t.commands, True)
    else:
        lines.append("None: the device is an open-loop instrument; the actuator frame carries only its header and "
                     "trailer, and the controller still answers every sensor frame with it (lockstep).")
    lines.append("")
    return lines


def _outputs_section(t: Table) -> list[str]:
    lines = ["## Recorded signals (`signals.csv`)", ""]
    if t.columns:
        lines += ["After `t_s`, in column order. `when`: recorded only when the scene has that option. `limits`: "
                  "the `report.json` limits drawn with the column.", "",
                  "| column | symbol | unit | when | limits | description |", "|---|---|---|---|---|---|"]
        for c in t.columns:
            lim = ", ".join(f"`{x}`" for x in c.limits)
            lines.append(f"| `{c.name}` | {_cell(c.symbol)} | {_cell(c.unit)} | {c.when} | {lim} | "
                         f"{_cell(c.description)} |")
    else:
        lines.append("None declared in the table.")
    lines += ["", "## Figures (`report.json` `figures`)", ""]
    if t.figures:
        lines += ["What a run of the device reports after it ends. A scene reports a subset (a figure that needs "
                  "an option the scene lacks is left out); tests/unit/figure_keys_test.cpp checks that every "
                  "figure a shipped scene reports is declared here.", "",
                  "| figure | unit | meaning |", "|---|---|---|"]
        for f in t.figures:
            lines.append(f"| `{f.name}` | {_cell(f.unit)} | {_cell(f.description)} |")
    else:
        lines.append("None declared in the table.")
    lines.append("")
    return lines


# --- CAN -----------------------------------------------------------------------------------------------------

def _can_type(s: can_layout.CanSignal) -> str:
    if s.kind == "double":
        return "IEEE-754 double"
    if s.bit_length % 8:
        return f"{s.kind}, {s.bit_length} bits"
    return f"{'int' if s.kind == 'signed' else 'uint'}{s.bit_length}"


def _can_carries(s: can_layout.CanSignal) -> str:
    if s.field_offset < 0:
        return "envelope"
    if s.table_name:
        element = f" element {s.element + 1}" if s.name != s.table_name else ""
        return f"value {s.value}: `{s.table_name}`{element}"
    return "frame header"


def can_frames_per_tick(t: Table) -> tuple[int, int, int, int]:
    """(sensor frames, command frames, sensor data bytes, command data bytes) of one tick."""
    ms = can_layout.layout(t)
    sens = [m for m in ms if m.direction == "sensor"]
    cmd = [m for m in ms if m.direction == "command"]
    return len(sens), len(cmd), sum(m.length for m in sens), sum(m.length for m in cmd)


def _can_section(t: Table) -> list[str]:
    messages = can_layout.layout(t)
    lines = [
        "## CAN FD frames",
        "",
        "11-bit identifiers, CAN FD with bit-rate switch. Every signal is Intel byte order (little-endian): its "
        "least significant bit is the start bit, bit 0 being bit 0 of byte 0. A table value rides as its "
        "IEEE-754 double unchanged (factor 1, offset 0, so a run over CAN is bit-identical to one in process) or, "
        "where the table says `can = \"int32\"` or another integer type, as that integer, exact. The frames of a "
        "tick's set are sent in the order listed, each direction's header last; the rules (identifiers, packing, "
        "the CRC, the alive counter and the link envelope's MAC) are [docs/can.md](../can.md). "
        f"Map fingerprint `{_hex(can_layout.fingerprint(messages))}` (a CAN log records it).",
        "",
        "| id | frame | direction | sender | length [bytes] | carries |",
        "|---|---|---|---|---:|---|",
    ]
    for m in messages:
        lines.append(f"| 0x{m.id:03X} | `{m.name}` | {m.direction} | {m.sender} | {m.length} | {_cell(m.comment)} |")
    lines.append("")
    for m in messages:
        lines += [f"### 0x{m.id:03X} `{m.name}` ({m.length} bytes)", "",
                  "| start bit | bytes | bits | type | factor | offset | range | unit | signal | carries |",
                  "|---:|---|---:|---|---:|---:|---|---|---|---|"]
        for s in m.signals:
            last = s.end_byte - 1
            where = f"{s.start_byte}" if last == s.start_byte else f"{s.start_byte}-{last}"
            lines.append(f"| {s.start_bit} | {where} | {s.bit_length} | {_can_type(s)} | {_num(s.factor)} | "
                         f"{_num(s.offset)} | {_range(s.min, s.max)} | {_cell(s.unit)} | `{s.name}` | "
                         f"{_can_carries(s)} |")
        lines.append("")
    return lines


# --- the documents -------------------------------------------------------------------------------------------

def _generated_note(what: str) -> str:
    return (f"<!-- Generated by tools/signals/generate.py --icd from {what}: do not edit. Regenerate with "
            f"`{REGENERATE}`; the ctest icd_docs_test fails when this file differs. -->")


def document(t: Table) -> str:
    scenes = scenes_of(t.device)
    n_s, n_c = t.sensor_values, t.command_values
    s_bytes, a_bytes = generate.encoded_size(t, "sensor"), generate.encoded_size(t, "actuator")
    fs, fc, bs, bc = can_frames_per_tick(t)
    lines = [
        _generated_note(generate.rel(t.path)),
        "",
        f"# {t.title} (`{t.device}`): interface control document",
        "",
        _cell(t.summary),
        "",
        f"- Device name (`[scene] device`): `{t.device}`; signal table: `{generate.rel(t.path)}`.",
        "- Scenes: " + (", ".join(f"`{s}`" for s in scenes) if scenes else "none shipped") + ".",
        f"- Per tick: {n_s} sensor value(s), {n_c} command value(s); over LCM {s_bytes} + {a_bytes} = "
        f"{s_bytes + a_bytes} bytes; over CAN FD {fs} + {fc} frames ({bs} + {bc} data bytes).",
        "- The protocol every device shares — channels, handshake with the scene hash, lockstep, resends with and "
        "without a key, end of run, timeouts, the envelope's fields and the MAC's exact input with a worked "
        "example — is [docs/protocol.md](../protocol.md). This page is what is particular to this device.",
        "",
    ]
    lines += _signals_section(t)
    lines += [
        "## LCM",
        "",
        "Two LCM types, generated from the table into `build/generated/lcm/` (run `lcm-gen` on them for your "
        "language). LCM marshals every field big-endian (network order) after the 8-byte fingerprint, doubles as "
        "their IEEE-754 bits, an array element by element; it has no unsigned types, so `tick`, `sensor_tick`, "
        "`sequence` and `status` travel as the signed type of the same width with the same bits, and the 32-bit "
        "ids `sender` and `session` are zero-extended into their int64 fields. Offsets are from the start of the "
        "encoded message, fingerprint included.",
        "",
    ]
    lines += _lcm_section(t, "sensor")
    lines += _lcm_section(t, "actuator")
    lines += _can_section(t)
    lines += _outputs_section(t)
    return "\n".join(lines).rstrip("\n") + "\n"


def index(tables: list[Table]) -> str:
    lines = [
        _generated_note("every device's signal table (tools/devices/*/*_signals.toml)"),
        "",
        "# Interface control documents",
        "",
        "One document per device, generated from its signal table: its sensors, commands, recorded signals and "
        "figures, its two LCM types with every field's byte offset, and its CAN FD frames with every signal's "
        "bit position. What every device shares — the handshake, the scene hash, lockstep, the end of run, the "
        "envelope and the MAC — is [docs/protocol.md](../protocol.md); how a table is written is "
        "[docs/signals.md](../signals.md).",
        "",
        "Bytes per tick over LCM are the two encoded messages, 88 + 8 × values bytes each (fingerprint, header, "
        "values, trailer); CAN FD frames per tick are the sensor set and the command set (their data bytes in "
        "brackets).",
        "",
        "| device | document | scenes | sensor values | command values | LCM sensor + actuator [bytes] | "
        "LCM bytes per tick | CAN FD frames per tick (data bytes) |",
        "|---|---|---:|---:|---:|---|---:|---|",
    ]
    for t in sorted(tables, key=lambda t: t.device):
        s_bytes, a_bytes = generate.encoded_size(t, "sensor"), generate.encoded_size(t, "actuator")
        fs, fc, bs, bc = can_frames_per_tick(t)
        lines.append(f"| {_cell(t.title)} | [`{t.device}`]({t.device}.md) | {len(scenes_of(t.device))} | "
                     f"{t.sensor_values} | {t.command_values} | {s_bytes} + {a_bytes} | {s_bytes + a_bytes} | "
                     f"{fs} + {fc} ({bs} + {bc}) |")
    lines += ["", f"Regenerate after changing a table or adding a scene: `{REGENERATE}` (or "
              "`python3 tools/signals/generate.py --icd docs/icd tools/devices/*/*_signals.toml`).", ""]
    return "\n".join(lines)
