#!/usr/bin/env python3
"""Generates everything that carries a device's signals from its signal table (signal_table.py).

  generate.py --out GEN_DIR TABLE...     the C++ headers and LCM types the build compiles:
      GEN_DIR/gyrostab_signals/<device>_frames.hpp    typed frames + signal specs (firmware: no heap, no I/O)
      GEN_DIR/gyrostab_signals/<device>_outputs.hpp   the CSV row (Record) and the columns' and figures' specs
      GEN_DIR/gyrostab_signals/<device>_can.hpp       the CAN FD map (can_layout.py; host side)
      GEN_DIR/gyrostab_signals/all_can_maps.hpp       every map, found by device name
      GEN_DIR/lcm/<device>_sensor_t.lcm, <device>_actuator_t.lcm   the LCM types (lcm-gen runs on them)
  generate.py --fixture --out GEN_DIR TABLE...   only the typed frames and CAN maps of test tables (no index)
      GEN_DIR/gyrostab_signals/all_devices.hpp, all_outputs.hpp   every table's signals / columns, by device
  generate.py --icd DOCS_DIR TABLE...    docs/icd/<device>.md, the interface control documents (icd.py), and
      docs/icd/README.md, their index with each device's bytes and frames per tick
  generate.py --check-icd DOCS_DIR TABLE...   exit 1 if a committed document differs from the generated one

A file is rewritten only when its text changes, so a build that regenerates recompiles nothing it need not.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import can_layout  # noqa: E402
import lcm_fingerprint  # noqa: E402
from signal_table import Signal, Table, TableError, load  # noqa: E402

SENSOR_HEADER = [("tick", "std::uint64_t", "int64_t", "controller tick this frame belongs to", "tick"),
                 ("time_ns", "std::int64_t", "int64_t", "publish time on the plant's clock", "ns"),
                 ("sample_time_ns", "std::int64_t", "int64_t", "when the signals were sampled", "ns"),
                 ("sequence", "std::uint32_t", "int32_t", "publisher's frame counter, +1 per frame, wraps at 2^32",
                  "-"),
                 ("status", "std::uint32_t", "int32_t", "SensorStatusBit set (firmware/msg/fault_bits.hpp)",
                  "bits")]
ACTUATOR_HEADER = [("tick", "std::uint64_t", "int64_t", "controller tick at which this command was computed",
                    "tick"),
                   ("time_ns", "std::int64_t", "int64_t", "the tick's time: tick x tick_ns", "ns"),
                   ("sensor_tick", "std::uint64_t", "int64_t",
                    "tick of the sensor frame the command was computed from", "tick"),
                   ("sequence", "std::uint32_t", "int32_t", "controller's frame counter, wraps at 2^32", "-"),
                   ("status", "std::uint32_t", "int32_t", "FaultBit set (firmware/msg/fault_bits.hpp)", "bits")]
TRAILER = [("sim_time_us", "simulated time of the tick [us]"),
           ("scene", "the sender's scene hash: FNV-1a 64 of its scene file (docs/protocol.md)"),
           ("sender", "the sending end's id (docs/protocol.md)"),
           ("session", "the plant's session id; 0 in a bus log"),
           ("freshness", "the sender's frame counter on this channel"),
           ("mac", "SipHash-2-4 MAC (docs/protocol.md); 0 without a key")]


def write_if_changed(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    if path.exists() and path.read_text() == text:
        return
    tmp = path.with_suffix(path.suffix + ".tmp")
    tmp.write_text(text)
    tmp.replace(path)


def cstr(s: str) -> str:
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", " ") + '"'


def num(x: float) -> str:
    r = repr(float(x))
    return r if ("e" in r or "." in r or "inf" in r) else r + ".0"


def lcm_type(t: Table, direction: str) -> str:
    return f"{t.device}_{direction}_t"


def lcm_members(t: Table, direction: str) -> list[tuple[str, str, list[int]]]:
    header = SENSOR_HEADER if direction == "sensor" else ACTUATOR_HEADER
    signals = t.sensors if direction == "sensor" else t.commands
    m = [(n, lt, []) for n, _, lt, _, _ in header]
    m += [(s.name, "double", [s.count] if s.count > 1 else []) for s in signals]
    m += [(n, "int64_t", []) for n, _ in TRAILER]
    return m


def fingerprint(t: Table, direction: str) -> int:
    return lcm_fingerprint.fingerprint(lcm_members(t, direction))


def encoded_size(t: Table, direction: str) -> int:
    values = t.sensor_values if direction == "sensor" else t.command_values
    return 8 + 32 + 8 * values + 8 * len(TRAILER)


# --- C++ ---------------------------------------------------------------------------------------------------

def _frame_struct(name: str, header, signals: list[Signal], what: str, extra: list[str]) -> list[str]:
    out = [f"// {what}", f"struct {name} {{"] + extra
    for field, ctype, _, doc, unit in header:
        out.append(f"  {ctype} {field}{{0}};  // {doc} [{unit}]")
    for s in signals:
        dims = f"[{s.count}]" if s.count > 1 else ""
        out.append(f"  double {s.name}{dims}{{}};  // {s.symbol}: {s.description.splitlines()[0]} [{s.unit}]")
    out.append("};")
    return out


def _ranges_struct(signals: list[Signal]) -> list[str]:
    out = ["// The fault monitor's plausible range of every sensor value, the table's ranges by default (a scene",
           "// narrows them; firmware/fault/fault_monitor.hpp walks them as one Range per value, in frame order).",
           "struct SensorRanges {"]
    for s in signals:
        r = f"{{{num(s.lo)}, {num(s.hi)}}}"
        if s.count > 1:
            out.append(f"  Range {s.name}[{s.count}]{{{', '.join([r] * s.count)}}};  // [{s.unit}]")
        else:
            out.append(f"  Range {s.name}{r};  // [{s.unit}]")
    if not signals:
        out.append("  Range none_[1]{};  // no sensor values")
    out.append("};")
    return out


def _index_struct(name: str, signals: list[Signal], what: str) -> list[str]:
    out = [f"// {what}: the index of each value in frame order (an array's first element), for code that walks",
           "// the values (signal_value, set_signal_value: firmware/msg/any_frame.hpp).", f"struct {name} {{"]
    i = 0
    for s in signals:
        out.append(f"  static constexpr std::size_t {s.name} = {i};")
        i += s.count
    out.append(f"  static constexpr std::size_t count = {i};")
    out.append("};")
    return out


def _specs(name: str, signals: list[Signal]) -> list[str]:
    if not signals:
        return [f"inline constexpr std::span<const SignalSpec> {name}{{}};"]
    out = [f"inline constexpr SignalSpec {name}[] = {{"]
    for s in signals:
        for e in range(s.count):
            out.append(f"    {{{cstr(s.name)}, {cstr(s.symbol)}, {cstr(s.unit)}, {num(s.lo)}, {num(s.hi)}, "
                       f"{num(s.safe)}, {cstr(s.nodes[e])}, {e}, {s.count}, {cstr(s.description)}}},")
    out.append("};")
    return out


def frames_header(t: Table) -> str:
    ns = t.namespace
    n_s, n_c = t.sensor_values, t.command_values
    lines = [
        f"// Generated by tools/signals/generate.py from {rel(t.path)}: do not edit.",
        f"// {t.title}: the typed frames of the device's interface (docs/icd/{t.device}.md).",
        "#pragma once",
        "",
        "#include <cstddef>",
        "#include <cstdint>",
        "#include <span>",
        "#include <type_traits>",
        "",
        '#include "firmware/msg/signal_spec.hpp"',
        "",
        f"namespace {ns} {{",
        "",
        f"inline constexpr std::string_view kDevice = {cstr(t.device)};",
        "",
    ]
    lines += _ranges_struct(t.sensors)
    lines.append("")
    lines += _index_struct("SensorIndex", t.sensors, "Sensor values")
    lines += _index_struct("CommandIndex", t.commands, "Command values")
    lines.append("")
    lines += _frame_struct("SensorFrame", SENSOR_HEADER, t.sensors,
                           "Plant -> controller, once per controller tick: the fixed header, then the signals.",
                           ["  using Ranges = SensorRanges;", "  using Index = SensorIndex;"])
    lines.append("")
    lines += _frame_struct("ActuatorFrame", ACTUATOR_HEADER, t.commands,
                           "Controller -> plant, once per controller tick: the fixed header, then the commands.",
                           ["  using Index = CommandIndex;"])
    lines.append("")
    lines += _specs("kSensorSignals", t.sensors)
    lines += _specs("kCommandSignals", t.commands)
    lines += [
        "",
        "inline constexpr DeviceSignals kSignals{",
        f"    kDevice, kSensorSignals, kCommandSignals,",
        f"    {cstr('gyrostab_msg.' + lcm_type(t, 'sensor'))}, {cstr('gyrostab_msg.' + lcm_type(t, 'actuator'))},",
        f"    0x{fingerprint(t, 'sensor'):016x}ull, 0x{fingerprint(t, 'actuator'):016x}ull}};",
        "",
        "// ADL hooks: the specs and the device of a typed frame (firmware/msg/any_frame.hpp).",
        "constexpr std::span<const SignalSpec> signal_specs(const SensorFrame*) { return kSensorSignals; }",
        "constexpr std::span<const SignalSpec> signal_specs(const ActuatorFrame*) { return kCommandSignals; }",
        "constexpr const DeviceSignals& device_signals(const SensorFrame*) { return kSignals; }",
        "constexpr const DeviceSignals& device_signals(const ActuatorFrame*) { return kSignals; }",
        "",
        "static_assert(std::is_trivially_copyable_v<SensorFrame> && std::is_standard_layout_v<SensorFrame>);",
        "static_assert(std::is_trivially_copyable_v<ActuatorFrame> && std::is_standard_layout_v<ActuatorFrame>);",
        f"static_assert(sizeof(SensorFrame) == kFrameHeaderBytes + {n_s} * sizeof(double), \"no padding\");",
        f"static_assert(sizeof(ActuatorFrame) == kFrameHeaderBytes + {n_c} * sizeof(double), \"no padding\");",
        f"static_assert({n_s} <= kMaxSensorSignals && {n_c} <= kMaxCommandSignals);",
        f"static_assert(sizeof(SensorRanges) == {max(n_s, 1)} * sizeof(Range), \"one Range per sensor value\");",
        "",
        f"}}  // namespace {ns}",
        "",
    ]
    return "\n".join(lines)


def outputs_header(t: Table) -> str:
    ns = t.namespace
    lines = [
        f"// Generated by tools/signals/generate.py from {rel(t.path)}: do not edit.",
        f"// {t.title}: the recorded signals (signals.csv) and the report's figures (docs/icd/{t.device}.md).",
        "#pragma once",
        "",
        '#include "tools/signals/output_spec.hpp"',
        "",
        f"namespace {ns} {{",
        "",
        "// One row of signals.csv after t_s, every column the device can record, in column order.",
        "struct Record {",
    ]
    for c in t.columns:
        lines.append(f"  double {c.name}{{0.0}};  // {c.symbol}: {c.description.splitlines()[0]} [{c.unit}]")
    lines += ["};", ""]
    if t.columns:
        lines.append("inline constexpr tools::ColumnSpec kColumns[] = {")
        for c in t.columns:
            lim = ", ".join(c.limits)
            lines.append(f"    {{{cstr(c.name)}, {cstr(c.symbol)}, {cstr(c.unit)}, {cstr(c.when)}, {cstr(lim)}, "
                         f"{cstr(c.description)}}},")
        lines.append("};")
    else:
        lines.append("inline constexpr std::span<const tools::ColumnSpec> kColumns{};")
    if t.figures:
        lines.append("inline constexpr tools::FigureSpec kFigures[] = {")
        for f in t.figures:
            lines.append(f"    {{{cstr(f.name)}, {cstr(f.unit)}, {cstr(f.description)}}},")
        lines.append("};")
    else:
        lines.append("inline constexpr std::span<const tools::FigureSpec> kFigures{};")
    lines += [
        "inline constexpr tools::DeviceOutputs kOutputs{kColumns, kFigures};",
        "// ADL hook: the outputs of a Record (tools/devices/device_scene_of.hpp).",
        "constexpr const tools::DeviceOutputs& device_outputs(const Record*) { return kOutputs; }",
        (f"static_assert(sizeof(Record) == {len(t.columns)} * sizeof(double));" if t.columns else
         "// No columns declared: the device's CSV columns are not in its table yet (Record is empty)."),
        "",
        f"}}  // namespace {ns}",
        "",
    ]
    return "\n".join(lines)


def lcm_file(t: Table, direction: str) -> str:
    header = SENSOR_HEADER if direction == "sensor" else ACTUATOR_HEADER
    signals = t.sensors if direction == "sensor" else t.commands
    who = "plant -> controller" if direction == "sensor" else "controller -> plant"
    lines = [
        f"// Generated by tools/signals/generate.py from {rel(t.path)}: do not edit.",
        f"// {t.title}, {who}: the header, the device's signals, the tick's simulated time and the link's",
        f"// envelope. {encoded_size(t, direction)} bytes encoded with the fingerprint (docs/icd/{t.device}.md,",
        "// docs/protocol.md). Unsigned header fields travel as the signed type of the same width, bit for bit.",
        "package gyrostab_msg;",
        "",
        f"struct {lcm_type(t, direction)}",
        "{",
    ]
    for field, _, lt, doc, unit in header:
        lines.append(f"  {lt} {field};  // {doc} [{unit}]")
    for s in signals:
        dims = f"[{s.count}]" if s.count > 1 else ""
        lines.append(f"  double {s.name}{dims};  // {s.symbol} [{s.unit}]")
    for field, doc in TRAILER:
        lines.append(f"  int64_t {field};  // {doc}")
    lines += ["}", ""]
    return "\n".join(lines)


KIND = {"unsigned": "SignalKind::kUnsigned", "signed": "SignalKind::kSigned", "double": "SignalKind::kDouble"}
DIRECTION = {"sensor": "Direction::kSensor", "command": "Direction::kActuator"}


def can_namespace(t: Table) -> str:
    return f"gyrostab::can::{t.device}"


def can_header(t: Table) -> str:
    messages = can_layout.layout(t)
    lines = [
        f"// Generated by tools/signals/generate.py from {rel(t.path)}: do not edit.",
        f"// {t.title}: the CAN FD frames of the device (tools/signals/can_layout.py; docs/can.md,",
        f"// docs/icd/{t.device}.md). Host side: the codec, the DBC writer and the bus-load check walk it.",
        "#pragma once",
        "",
        f'#include "gyrostab_signals/{t.device}_frames.hpp"',
        '#include "hil/can/frame_map.hpp"',
        "",
        f"namespace {can_namespace(t)} {{",
        "",
    ]
    for m in messages:
        lines.append(f"inline constexpr SignalSpec kSignals_{m.name}[] = {{")
        for sig in m.signals:
            lines.append(f"    {{{cstr(sig.name)}, {sig.start_bit}, {sig.bit_length}, {KIND[sig.kind]}, "
                         f"{sig.field_offset}, {'true' if sig.integer else 'false'}, {num(sig.factor)}, "
                         f"{num(sig.offset)}, {num(sig.min)}, {num(sig.max)}, {cstr(sig.unit)}, {cstr(sig.comment)}}},")
        lines.append("};")
    lines.append("")
    lines.append("inline constexpr MessageSpec kMessages[] = {")
    for m in messages:
        lines.append(f"    {{0x{m.id:03X}, {cstr(m.name)}, {cstr(m.sender)}, {cstr(m.node)}, {DIRECTION[m.direction]}, "
                     f"{m.length}, {'true' if m.header else 'false'}, kSignals_{m.name}, {cstr(m.comment)}}},")
    lines.append("};")
    n_cmd = sum(1 for m in messages if m.direction == "command")
    lines += [
        "",
        f"inline constexpr CanMap kCanMap{{{cstr(t.device)}, &{t.namespace}::kSignals, kMessages, "
        f"0x{can_layout.fingerprint(messages):016x}ull}};",
        "",
        f"static_assert(msg::kFrameHeaderBytes == {can_layout.FRAME_HEADER_BYTES});",
        f"static_assert({n_cmd} <= kMaxMessagesPerDirection && {len(messages) - n_cmd} <= kMaxMessagesPerDirection);",
        "",
        f"}}  // namespace {can_namespace(t)}",
        "",
    ]
    return "\n".join(lines)


def all_can_maps_header(tables: list[Table]) -> str:
    lines = ["// Generated by tools/signals/generate.py: the CAN FD map of every signal table of the build, in file",
             "// order. Do not edit.", "#pragma once", "", "#include <string_view>", ""]
    lines += [f'#include "gyrostab_signals/{t.device}_can.hpp"' for t in tables]
    lines += ["", "namespace gyrostab::can {", "", "inline constexpr const CanMap* kAllCanMaps[] = {"]
    lines += [f"    &{can_namespace(t)}::kCanMap," for t in tables]
    lines += ["};", "",
              "// The map generated from the table of this device, or nullptr (no table declares that device).",
              "constexpr const CanMap* find_can_map(std::string_view device) {",
              "  for (const CanMap* m : kAllCanMaps)",
              "    if (m->device == device) return m;",
              "  return nullptr;",
              "}", "", "}  // namespace gyrostab::can", ""]
    return "\n".join(lines)


ROOT = Path(__file__).resolve().parents[2]


def rel(p: Path) -> str:
    try:
        return str(Path(p).resolve().relative_to(ROOT))
    except ValueError:
        return str(p)


def all_devices_header(tables: list[Table]) -> str:
    lines = ["// Generated by tools/signals/generate.py: every signal table of the build, in file order. Do not edit.",
             "#pragma once", "", "#include <span>", ""]
    lines += [f'#include "gyrostab_signals/{t.device}_frames.hpp"' for t in tables]
    lines += ["", "namespace gyrostab::msg {", "",
              "inline constexpr const DeviceSignals* kAllDeviceSignals[] = {"]
    lines += [f"    &{t.namespace}::kSignals," for t in tables]
    lines += ["};", "", "}  // namespace gyrostab::msg", ""]
    return "\n".join(lines)


def all_outputs_header(tables: list[Table]) -> str:
    lines = ["// Generated by tools/signals/generate.py: every signal table's recorded columns and figures, by device,",
             "// in file order. Do not edit.",
             "#pragma once", "", "#include <string_view>", "", '#include "tools/signals/output_spec.hpp"']
    lines += [f'#include "gyrostab_signals/{t.device}_outputs.hpp"' for t in tables]
    lines += ["", "namespace gyrostab::tools {", "",
              "struct NamedDeviceOutputs {", "  std::string_view device;", "  const DeviceOutputs* outputs;", "};",
              "",
              "inline constexpr NamedDeviceOutputs kAllDeviceOutputs[] = {"]
    lines += [f"    {{{cstr(t.device)}, &{t.namespace}::kOutputs}}," for t in tables]
    lines += ["};", "", "}  // namespace gyrostab::tools", ""]
    return "\n".join(lines)


def all_lcm_types_header(tables: list[Table]) -> str:
    lines = ["// Generated by tools/signals/generate.py: each table's signals with lcm-gen's classes of its two LCM",
             "// types, for the tests that hold the codec to lcm-gen's own encoder. Do not edit.",
             "#pragma once", ""]
    for t in tables:
        lines.append(f'#include "gyrostab_signals/{t.device}_frames.hpp"')
        lines.append(f'#include "gyrostab_msg/{lcm_type(t, "sensor")}.hpp"')
        lines.append(f'#include "gyrostab_msg/{lcm_type(t, "actuator")}.hpp"')
    lines += ["", "namespace gyrostab::msg {", "",
              "// fn(const DeviceSignals&, sensor type tag, actuator type tag) for every table.",
              "template <class Sensor, class Actuator>", "struct LcmTypes {};", "",
              "template <class Fn>", "void for_each_lcm_type(Fn&& fn) {"]
    for t in tables:
        lines.append(f"  fn({t.namespace}::kSignals, LcmTypes<gyrostab_msg::{lcm_type(t, 'sensor')}, "
                     f"gyrostab_msg::{lcm_type(t, 'actuator')}>{{}});")
    lines += ["}", "", "}  // namespace gyrostab::msg", ""]
    return "\n".join(lines)


def generate(tables: list[Table], out: Path, fixture: bool = False) -> None:
    if fixture:
        for t in tables:
            write_if_changed(out / "gyrostab_signals" / f"{t.device}_frames.hpp", frames_header(t))
            write_if_changed(out / "gyrostab_signals" / f"{t.device}_can.hpp", can_header(t))
        return
    write_if_changed(out / "gyrostab_signals" / "all_devices.hpp", all_devices_header(tables))
    write_if_changed(out / "gyrostab_signals" / "all_lcm_types.hpp", all_lcm_types_header(tables))
    write_if_changed(out / "gyrostab_signals" / "all_can_maps.hpp", all_can_maps_header(tables))
    write_if_changed(out / "gyrostab_signals" / "all_outputs.hpp", all_outputs_header(tables))
    for t in tables:
        write_if_changed(out / "gyrostab_signals" / f"{t.device}_frames.hpp", frames_header(t))
        write_if_changed(out / "gyrostab_signals" / f"{t.device}_can.hpp", can_header(t))
        write_if_changed(out / "gyrostab_signals" / f"{t.device}_outputs.hpp", outputs_header(t))
        for d in ("sensor", "actuator"):
            write_if_changed(out / "lcm" / f"{lcm_type(t, d)}.lcm", lcm_file(t, d))


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, help="generated sources into this directory")
    ap.add_argument("--icd", type=Path, help="write docs/icd/<device>.md into this directory")
    ap.add_argument("--check-icd", type=Path, help="compare docs/icd/<device>.md in this directory")
    ap.add_argument("--list", action="store_true", help="print each table's device and file")
    ap.add_argument("--fixture", action="store_true",
                    help="with --out: only the frames and CAN map headers (test tables, no index headers)")
    ap.add_argument("tables", nargs="+", type=Path)
    a = ap.parse_args(argv)
    try:
        tables = [load(p) for p in a.tables]
        for t in tables:
            can_layout.layout(t)  # a table whose frames do not fit the bus is refused here, with the reason
    except TableError as e:
        print(f"generate.py: {e}", file=sys.stderr)
        return 2
    names = [t.device for t in tables]
    if len(set(names)) != len(names):
        print("generate.py: two tables declare the same device", file=sys.stderr)
        return 2
    if a.out:
        generate(tables, a.out, a.fixture)
    if a.icd or a.check_icd:
        import icd  # noqa: E402

        stale = 0
        docs = [(f"{t.device}.md", icd.document(t)) for t in tables] + [("README.md", icd.index(tables))]
        for name, text in docs:
            if a.icd:
                write_if_changed(a.icd / name, text)
            else:
                p = a.check_icd / name
                if not p.exists() or p.read_text() != text:
                    print(f"{p} is stale: regenerate it with `{icd.REGENERATE}` "
                          f"(tools/signals/generate.py --icd docs/icd tools/devices/*/*_signals.toml)",
                          file=sys.stderr)
                    stale += 1
        if a.check_icd and a.check_icd.is_dir():
            extra = sorted(p.name for p in a.check_icd.glob("*.md") if p.name not in {n for n, _ in docs})
            for name in extra:
                print(f"{a.check_icd / name} is no device's document: remove it", file=sys.stderr)
                stale += 1
        if stale:
            return 1
    if a.list:
        for t in tables:
            print(t.device, rel(t.path))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
