"""The CAN FD frames of a device's signal table: which frame each value rides in, and at which bit.

One function, layout(table), decides it; generate.py writes the result as the device's C++ map
(gyrostab_signals/<device>_can.hpp: hil/can/frame_map.hpp's MessageSpec and SignalSpec), and the interface
control document shows the same result. The wire rules (docs/can.md):

  * CAN FD, 11-bit identifiers, every frame's first 4 bytes the envelope: CRC-8 SAE J1850 (byte 0), alive
    counter (byte 1, bits 0-3), tick tag (bytes 2-3, the low 16 bits of the tick).
  * The two header frames, SENSOR_HUB (plant -> controller) and CONTROLLER_CMD (controller -> plant), are 64
    bytes: the frame header's fields at bytes 4-35 (status, tick, two times or time and sensor tick,
    sequence), room for the values of the header's node (sensor_hub, controller) at bytes 36-43, the link
    envelope at bytes 44-63 (sender, session, freshness, MAC). Each is sent last in its tick's set.
  * Every other value rides in a frame of its node (the table's `node`, per element for an array), the
    node's values in table order from byte 4, a new frame whenever the next value does not fit the 64
    bytes; the header node's values first fill the header's 8 bytes. A frame is as long as the smallest FD
    length that holds what it carries (unused bytes zero).
  * A value is its IEEE-754 double as it is (factor 1, offset 0: lockstep over CAN stays bit-identical to in
    process), unless the table says `can = "int32"` (or another integer type): then the integer, exact, and
    the encoder refuses a value that is not such an integer.
  * Identifiers: base + 16 * node code + k, k the node's frame number from 0; base 0x100 for commands, 0x200
    for sensors (commands win arbitration); node codes imu 1, drive1 2, drive2 3, cluster 4. The headers are
    0x1FF and 0x2FF, the last of their direction in priority too (a controller whose transmit mailboxes
    reorder frames still sends the header last); the header node's further frames base + 0xF0 + k - 1. A
    value added to a node moves no other node's identifiers.
  * Names: SENSOR_HUB and CONTROLLER_CMD; a node's first frame <NODE>_FB (sensors) or <NODE>_CMD (commands),
    its further frames <NODE>_FB_2, _3, ... (the header node's: SENSOR_HUB_2, CONTROLLER_CMD_2, ...); a
    value's signal is named after it, an array element with its number from 1 (gimbal_angle_rad_2).

The map lists the command frames, then the sensor frames, each direction's body frames by identifier and its
header last: the order frames are sent in.

For other generators (the interface control document): layout(table) returns the Message list — id, name,
sender, node, direction, length, header, comment and the signals, each a CanSignal with its start bit, length,
kind, byte offset in the generic frame, range, unit, comment and, for a table value, the table's signal name,
element and value index.

    python3 tools/signals/can_layout.py TABLE...    prints each table's frames and signals
"""

from __future__ import annotations

import dataclasses
import hashlib
import sys
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from signal_table import (  # noqa: E402
    CAN_DOUBLE, CAN_INTEGER_TYPES, COMMAND_NODES, SENSOR_NODES, Table, TableError, can_integer_range)

# msg::kFrameHeaderBytes: a frame's values start here, 8 bytes each (firmware/msg/signal_spec.hpp).
FRAME_HEADER_BYTES = 32
ENVELOPE_BYTES = 4
HEADER_LENGTH = 64
HEADER_VALUES_BYTE = 36   # the header node's values: bytes 36-43
LINK_ENVELOPE_BYTE = 44   # the link envelope: bytes 44-63
MAX_FD_LENGTH = 64
FD_LENGTHS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 20, 24, 32, 48, 64)
# The most frames of one direction (hil/can/frame_map.hpp kMaxMessagesPerDirection sizes the buffers).
MAX_MESSAGES_PER_DIRECTION = 12
MAX_FRAMES_PER_NODE = 16
ID_BASE = {"command": 0x100, "sensor": 0x200}
NODE_CODES = {"sensor_hub": 15, "controller": 15, "imu": 1, "drive1": 2, "drive2": 3, "cluster": 4}
HEADER_NODE = {"sensor": "sensor_hub", "command": "controller"}
HEADER_NAME = {"sensor": "SENSOR_HUB", "command": "CONTROLLER_CMD"}
SUFFIX = {"sensor": "FB", "command": "CMD"}
assert set(SENSOR_NODES) | set(COMMAND_NODES) == set(NODE_CODES)

U32_MAX = float((1 << 32) - 1)
U64_MAX = float((1 << 64) - 1)
I64_MIN = -float(1 << 63)
I64_MAX = float((1 << 63) - 1)


@dataclass(frozen=True)
class CanSignal:
    """One signal of a frame: an envelope or header field, or one value of the table."""
    name: str          # DBC signal name, unique in its frame
    start_bit: int     # least significant bit (Intel byte order), bit 0 = byte 0 bit 0
    bit_length: int
    kind: str          # "unsigned", "signed", "double": what the raw bits are
    field_offset: int  # byte offset of the field it carries in the generic frame; -1: the envelope
    min: float
    max: float
    unit: str
    comment: str
    integer: bool = False   # a double frame field carried as an integer (the table's can = "int32", ...)
    value: int = -1          # the frame value it carries (index in the direction's values), -1: none
    factor: float = 1.0
    offset: float = 0.0
    table_name: str = ""     # the table's signal it carries ("" for envelope and header fields)
    element: int = 0         # its element (from 0) of that signal

    @property
    def start_byte(self) -> int:
        return self.start_bit // 8

    @property
    def end_byte(self) -> int:
        return (self.start_bit + self.bit_length + 7) // 8


@dataclass
class Message:
    id: int
    name: str
    sender: str       # the node that sends it (DBC BU_)
    node: str         # the node whose frame it is: sensors their sender, commands the node they act on
    direction: str    # "sensor" (plant -> controller) or "command" (controller -> plant)
    length: int       # CAN FD data length [bytes]
    header: bool      # the set's header: carries the frame header and the link envelope, sent last
    signals: list[CanSignal] = field(default_factory=list)
    comment: str = ""

    @property
    def used_bytes(self) -> int:
        return max(s.end_byte for s in self.signals)


def _u(name, start, bits, off, lo, hi, unit, comment, kind="unsigned") -> CanSignal:
    return CanSignal(name, start, bits, kind, off, lo, hi, unit, comment)


ENVELOPE = [
    _u("crc", 0, 8, -1, 0.0, 255.0, "",
       "CRC-8 SAE J1850 (poly 0x1D, init 0xFF, xorout 0xFF) over the identifier (low byte first) and bytes "
       "1..len-1"),
    _u("alive", 8, 4, -1, 0.0, 15.0, "", "alive counter: +1 mod 16 per frame on this identifier"),
    _u("tick_tag", 16, 16, -1, 0.0, 65535.0, "tick", "low 16 bits of the controller tick this frame belongs to"),
]
LINK_ENVELOPE = [
    _u("link_sender", 352, 32, -1, 1.0, U32_MAX, "", "sender id of this set (hil/link/link_guard.hpp)"),
    _u("link_session", 384, 32, -1, 1.0, U32_MAX, "", "session id drawn by the plant at start-up"),
    _u("link_freshness", 416, 32, -1, 0.0, U32_MAX, "", "low 32 bits of the sender's freshness counter (SecOC)"),
    _u("link_mac", 448, 64, -1, 0.0, U64_MAX, "", "SipHash-2-4 MAC over the set (keyed with --key-file, else unkeyed)"),
]
# The frame header's fields (msg::AnySensorFrame / AnyActuatorFrame: tick 0, time 8, third field 16,
# sequence 24, status 28) at bytes 4-35 of the header frame.
FRAME_HEADER = {
    "sensor": [
        _u("sensor_status", 32, 32, 28, 0.0, U32_MAX, "bits", "SensorStatusBit set (firmware/msg/fault_bits.hpp)"),
        _u("sensor_tick", 64, 64, 0, 0.0, U64_MAX, "tick", "controller tick this sensor frame belongs to"),
        _u("sensor_time", 128, 64, 8, I64_MIN, I64_MAX, "ns", "publish time on the plant's clock", "signed"),
        _u("sample_time", 192, 64, 16, I64_MIN, I64_MAX, "ns", "when the signals were sampled", "signed"),
        _u("sensor_sequence", 256, 32, 24, 0.0, U32_MAX, "", "publisher's frame counter, wraps at 2^32"),
    ],
    "command": [
        _u("controller_status", 32, 32, 28, 0.0, U32_MAX, "bits",
           "FaultBit set (firmware/msg/fault_bits.hpp); bit 9 = safe state: every drive to zero torque"),
        _u("command_tick", 64, 64, 0, 0.0, U64_MAX, "tick", "controller tick at which this command was computed"),
        _u("command_time", 128, 64, 8, I64_MIN, I64_MAX, "ns", "publish time on the controller's clock", "signed"),
        _u("command_sensor_tick", 192, 64, 16, 0.0, U64_MAX, "tick",
           "tick of the sensor frame the command was computed from"),
        _u("command_sequence", 256, 32, 24, 0.0, U32_MAX, "", "controller's frame counter, wraps at 2^32"),
    ],
}
FIXED_NAMES = {s.name for s in ENVELOPE + LINK_ENVELOPE + FRAME_HEADER["sensor"] + FRAME_HEADER["command"]}


def fd_length(n: int) -> int:
    """The smallest CAN FD data length that holds n bytes."""
    for length in FD_LENGTHS:
        if length >= n:
            return length
    raise ValueError(f"{n} bytes do not fit a CAN FD frame")


@dataclass
class _Value:
    index: int   # position among the direction's values (frame value i at kFrameHeaderBytes + 8 i)
    node: str
    signal: CanSignal  # start_bit 0: placed later


def _values(t: Table, direction: str) -> list[_Value]:
    out = []
    signals = t.sensors if direction == "sensor" else t.commands
    for s in signals:
        for e in range(s.count):
            i = len(out)
            name = s.name if s.count == 1 else f"{s.name}_{e + 1}"
            if name in FIXED_NAMES:
                raise TableError(f"{t.path}: {direction} '{s.name}': its CAN signal '{name}' is a name of the "
                                 "envelope or the frame header")
            what = s.description.splitlines()[0]
            comment = f"{s.symbol}: {what}" + (f" (element {e + 1} of {s.count})" if s.count > 1 else "")
            if s.can == CAN_DOUBLE:
                sig = CanSignal(name, 0, 64, "double", FRAME_HEADER_BYTES + 8 * i, s.lo, s.hi, s.unit, comment,
                                False, i, table_name=s.name, element=e)
            else:
                bits, signed = CAN_INTEGER_TYPES[s.can]
                comment += f"; an integer, carried exactly as {s.can}"
                sig = CanSignal(name, 0, bits, "signed" if signed else "unsigned", FRAME_HEADER_BYTES + 8 * i,
                                s.lo, s.hi, s.unit, comment, True, i, table_name=s.name, element=e)
            out.append(_Value(i, s.nodes[e], sig))
    return out


def _place(sig: CanSignal, byte: int) -> CanSignal:
    return dataclasses.replace(sig, start_bit=8 * byte)


def frame_id(direction: str, node: str, k: int) -> int:
    """The identifier of frame k of a node (module docstring)."""
    base = ID_BASE[direction] + 16 * NODE_CODES[node]
    if node == HEADER_NODE[direction]:
        return base + 15 if k == 0 else base + k - 1
    return base + k


def _frame_name(direction: str, node: str, k: int) -> str:
    base = HEADER_NAME[direction] if node == HEADER_NODE[direction] else f"{node.upper()}_{SUFFIX[direction]}"
    return base if k == 0 else f"{base}_{k + 1}"


def _node_frames(t: Table, direction: str, node: str, values: list[_Value]) -> list[Message]:
    """The frames of one node: its values in table order, a new frame when the next does not fit."""
    header_node = node == HEADER_NODE[direction]
    frames: list[list[CanSignal]] = [[]]
    byte = HEADER_VALUES_BYTE if header_node else ENVELOPE_BYTES
    limit = LINK_ENVELOPE_BYTE if header_node else MAX_FD_LENGTH
    for v in values:
        size = v.signal.bit_length // 8
        if byte + size > limit:
            frames.append([])
            byte, limit = ENVELOPE_BYTES, MAX_FD_LENGTH
        frames[-1].append(_place(v.signal, byte))
        byte += size
    most = MAX_FRAMES_PER_NODE - (1 if header_node else 0)
    if len(frames) > most:
        raise TableError(f"{t.path}: node {node} needs {len(frames)} {direction} frames, at most {most}")
    out = []
    who = "plant -> controller" if direction == "sensor" else "controller -> plant"
    for k, sigs in enumerate(frames):
        header = header_node and k == 0
        if not header and not sigs:
            continue
        names = ", ".join(s.name for s in sigs)
        if header:
            signals = ENVELOPE + FRAME_HEADER[direction] + sigs + LINK_ENVELOPE
            what = ("sensor frame header: tick, times, sequence, status" if direction == "sensor" else
                    "command header: tick, time, sensor tick, sequence, status (safe state)")
            comment = (f"{what}{'; ' + names if names else ''}; link envelope; completes the tick's "
                       f"{'sensor' if direction == 'sensor' else 'command'} set")
            length = HEADER_LENGTH
        else:
            signals = ENVELOPE + sigs
            comment = f"{node} ({who}): {names}"
            length = fd_length(max(s.end_byte for s in signals))
        sender = node if direction == "sensor" else "controller"
        out.append(Message(frame_id(direction, node, k), _frame_name(direction, node, k), sender, node,
                           direction, length, header, signals, comment))
    return out


def layout(t: Table) -> list[Message]:
    """The device's CAN FD frames: command frames then sensor frames, each direction's header last."""
    messages: list[Message] = []
    for direction in ("command", "sensor"):
        values = _values(t, direction)
        nodes = COMMAND_NODES if direction == "command" else SENSOR_NODES
        frames: list[Message] = []
        for node in nodes:
            frames += _node_frames(t, direction, node, [v for v in values if v.node == node])
        if len(frames) > MAX_MESSAGES_PER_DIRECTION:
            raise TableError(f"{t.path}: {len(frames)} {direction} frames, at most {MAX_MESSAGES_PER_DIRECTION} "
                             "(hil/can/frame_map.hpp kMaxMessagesPerDirection)")
        body = sorted((m for m in frames if not m.header), key=lambda m: m.id)
        messages += body + [m for m in frames if m.header]
    return messages


def fingerprint(messages: list[Message]) -> int:
    """64-bit fingerprint of a map: identifiers, names, lengths and every signal's position, type and field.
    A candump log records it; a replay refuses a log of another map."""
    h = hashlib.sha256()
    for m in messages:
        h.update(f"{m.id:x} {m.name} {m.direction} {m.length} {int(m.header)} {m.node}\n".encode())
        for s in m.signals:
            h.update(f" {s.name} {s.start_bit} {s.bit_length} {s.kind} {s.field_offset} {int(s.integer)}\n".encode())
    return int(h.hexdigest()[:16], 16)


def describe(t: Table) -> str:
    lines = [f"{t.device} ({t.path})"]
    for m in layout(t):
        lines.append(f"  0x{m.id:03X} {m.name:<18} {m.direction:<7} {m.sender:<10} {m.length:>2} B"
                     f"{'  header' if m.header else ''}")
        for s in m.signals:
            if s.field_offset < 0:
                continue
            lines.append(f"      bytes {s.start_byte:>2}-{s.end_byte - 1:<2} {s.kind:<8} {s.name}")
    return "\n".join(lines)


def main(argv: list[str]) -> int:
    from signal_table import load
    if not argv:
        print(__doc__.strip().splitlines()[-1].strip(), file=sys.stderr)
        return 2
    try:
        for p in argv:
            print(describe(load(Path(p))))
    except TableError as e:
        print(f"can_layout.py: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
