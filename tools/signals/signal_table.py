"""A device's signal table: every sensor, command and recorded signal, declared once.

The table is TOML (docs/adding-a-device.md, docs/signals.md):

    device = "monorail"                      # the registry's name: [scene] device
    title = "Monorail car"                   # for the interface control document
    summary = "..."                          # one paragraph for the ICD

    [[sensor]]                               # plant -> controller, in frame order
    name = "tilt_rad"                        # C++ field, LCM field and column name: snake_case + unit suffix
    symbol = "φ"                             # the book's symbol
    unit = "rad"                             # SI unit; "-" for a ratio, "counts", "bits"
    range = [-3.141592653589793, 3.141592653589793]   # plausible range (the fault monitor's default)
    node = "imu"                             # the CAN node that measures it; for an array, one node for all
                                             # elements or a list of one node per element: ["drive1", "drive2"]
    description = "..."
    count = 4                                # optional: an array of this many elements (unit i at index i-1)
    can = "int32"                            # optional: how the value rides on the CAN bus (can_layout.py):
                                             # "double" (default, the IEEE-754 bits as they are) or, for a
                                             # value that is always an integer (an encoder count), "int8",
                                             # "int16", "int32", "uint8", "uint16", "uint32": exact, and the
                                             # encoder refuses a value that is not an integer of that type

    [[command]]                              # controller -> plant, in frame order
    name = "motor_torque_Nm"
    ...                                      # as a sensor, plus
    safe = 0.0                               # the value in the safe state (required)

    [[column]]                               # signals.csv, in column order
    name = "tilt_rad"
    symbol = "φ"
    unit = "rad"
    description = "..."
    when = "dc_drive"                        # optional: recorded only when the scene has this option
    limits = ["motor_torque_limit_Nm"]       # optional: report.json "limits" keys drawn with it

    [[figure]]                               # report.json "figures"
    name = "tilt_rms_rad"
    unit = "rad"
    description = "..."

Everything that carries or shows a signal (typed frames, LCM types, CAN frames, the DBC, the target link's
payload, the CSV columns, the ICD) is generated from this table by generate.py; nothing else names a signal by
hand. Parsed with the standard library's tomllib (Python 3.11).
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

IDENT = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
DEVICE = re.compile(r"^[a-z][a-z0-9_]*$")
# The CAN nodes a signal can sit on (can_layout.py, docs/can.md): the sensor hub and the controller always exist.
SENSOR_NODES = ("sensor_hub", "imu", "drive1", "drive2", "cluster")
COMMAND_NODES = ("controller", "drive1", "drive2", "cluster")
# How a value can ride on the CAN bus: the double's bits (default), or an integer type for a value that is
# always an integer: bits and signedness.
CAN_DOUBLE = "double"
CAN_INTEGER_TYPES = {
    "int8": (8, True), "int16": (16, True), "int32": (32, True),
    "uint8": (8, False), "uint16": (16, False), "uint32": (32, False),
}


def can_integer_range(can: str) -> tuple[int, int]:
    """The values an integer CAN type holds: [min, max]."""
    bits, signed = CAN_INTEGER_TYPES[can]
    return (-(1 << (bits - 1)), (1 << (bits - 1)) - 1) if signed else (0, (1 << bits) - 1)
# Field names of the fixed headers and envelopes: a signal may not shadow them.
RESERVED = {
    "tick", "time_ns", "sample_time_ns", "sensor_tick", "sequence", "status", "sim_time_us", "sender",
    "session", "freshness", "mac", "scene", "t_s",
    "count",  # the generated SensorIndex/CommandIndex's number of values
}
MAX_SENSOR_VALUES = 32
MAX_COMMAND_VALUES = 16


class TableError(Exception):
    pass


@dataclass
class Signal:
    name: str
    symbol: str
    unit: str
    lo: float
    hi: float
    nodes: list[str]  # the CAN node of each element (count entries)
    description: str
    count: int = 1
    safe: float = 0.0
    can: str = CAN_DOUBLE  # how each element rides on the CAN bus: "double" or a CAN_INTEGER_TYPES key

    @property
    def node(self) -> str:
        """The node of every element, or the elements' nodes joined by ", " when they differ (for text)."""
        return self.nodes[0] if len(set(self.nodes)) == 1 else ", ".join(self.nodes)


@dataclass
class Column:
    name: str
    symbol: str
    unit: str
    description: str
    when: str = ""
    limits: list[str] = field(default_factory=list)


@dataclass
class Figure:
    name: str
    unit: str
    description: str


@dataclass
class Table:
    path: Path
    device: str
    title: str
    summary: str
    namespace: str
    sensors: list[Signal]
    commands: list[Signal]
    columns: list[Column]
    figures: list[Figure]

    @property
    def sensor_values(self) -> int:
        return sum(s.count for s in self.sensors)

    @property
    def command_values(self) -> int:
        return sum(s.count for s in self.commands)


def _need(d: dict, key: str, kind, where: str):
    if key not in d:
        raise TableError(f"{where}: missing key '{key}'")
    v = d[key]
    if kind is float and isinstance(v, int) and not isinstance(v, bool):
        v = float(v)
    if not isinstance(v, kind) or isinstance(v, bool) and kind is not bool:
        raise TableError(f"{where}: '{key}' must be a {kind.__name__}, not {type(v).__name__}")
    return v


def _no_unknown(d: dict, allowed: set[str], where: str) -> None:
    unknown = sorted(set(d) - allowed)
    if unknown:
        raise TableError(f"{where}: unknown key(s) {', '.join(unknown)} (allowed: {', '.join(sorted(allowed))})")


def _text(d: dict, key: str, where: str, allow_empty: bool = False) -> str:
    v = _need(d, key, str, where)
    if not allow_empty and not v.strip():
        raise TableError(f"{where}: '{key}' is empty")
    if "\n" in v and key != "description":
        raise TableError(f"{where}: '{key}' must be one line")
    return v


def _ident(name: str, where: str) -> str:
    if not IDENT.match(name) or len(name) > 48:
        raise TableError(f"{where}: name '{name}' is not a snake_case identifier of at most 48 characters "
                         "(letters, digits, '_'; a unit suffix such as _rad, _Nm, _rad_s may use capitals)")
    if name in RESERVED:
        raise TableError(f"{where}: name '{name}' is a header or envelope field, or a generated name")
    return name


def _nodes(d: dict, where: str, nodes: tuple[str, ...], count: int) -> list[str]:
    if "node" not in d:
        raise TableError(f"{where}: missing key 'node'")
    v = d["node"]
    if isinstance(v, str):
        v = [v] * count
    elif isinstance(v, list) and all(isinstance(x, str) for x in v):
        if len(v) != count:
            raise TableError(f"{where}: 'node' lists {len(v)} nodes for {count} element(s): one node, or one per "
                             "element")
    else:
        raise TableError(f"{where}: 'node' must be a node name or a list of one per element")
    for n in v:
        if n not in nodes:
            raise TableError(f"{where}: node '{n}' is not one of {', '.join(nodes)}")
    return list(v)


def _can(d: dict, where: str, lo: float, hi: float) -> str:
    can = d.get("can", CAN_DOUBLE)
    if not isinstance(can, str) or (can != CAN_DOUBLE and can not in CAN_INTEGER_TYPES):
        raise TableError(f"{where}: 'can' must be one of {CAN_DOUBLE}, {', '.join(CAN_INTEGER_TYPES)}")
    if can != CAN_DOUBLE:
        tmin, tmax = can_integer_range(can)
        if lo < tmin or hi > tmax:
            raise TableError(f"{where}: the range [{lo}, {hi}] does not fit '{can}' ([{tmin}, {tmax}]): a "
                             "plausible value must travel exactly")
    return can


def _signal(d: dict, where: str, nodes: tuple[str, ...], command: bool) -> Signal:
    allowed = {"name", "symbol", "unit", "range", "node", "description", "count", "can"} | (
        {"safe"} if command else set())
    _no_unknown(d, allowed, where)
    name = _ident(_text(d, "name", where), where)
    where = f"{where} ({name})"
    rng = _need(d, "range", list, where)
    if len(rng) != 2 or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in rng):
        raise TableError(f"{where}: 'range' must be [min, max]")
    lo, hi = float(rng[0]), float(rng[1])
    if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
        raise TableError(f"{where}: 'range' must be finite with min < max, not [{lo}, {hi}]")
    count = d.get("count", 1)
    if not isinstance(count, int) or isinstance(count, bool) or not 1 <= count <= 8:
        raise TableError(f"{where}: 'count' must be an integer in [1, 8]")
    node_list = _nodes(d, where, nodes, count)
    can = _can(d, where, lo, hi)
    safe = 0.0
    if command:
        safe = _need(d, "safe", float, where)
        if not lo <= safe <= hi:
            raise TableError(f"{where}: the safe value {safe} is outside its range [{lo}, {hi}]")
        if can != CAN_DOUBLE and (safe != int(safe) or math.copysign(1.0, safe) < 0.0 and safe == 0.0):
            raise TableError(f"{where}: the safe value {safe} is not an integer that 'can = \"{can}\"' carries "
                             "exactly")
    return Signal(name, _text(d, "symbol", where), _text(d, "unit", where), lo, hi, node_list,
                  _text(d, "description", where), count, safe, can)


def _column(d: dict, where: str) -> Column:
    _no_unknown(d, {"name", "symbol", "unit", "description", "when", "limits"}, where)
    name = _ident(_text(d, "name", where), where)
    where = f"{where} ({name})"
    limits = d.get("limits", [])
    if not isinstance(limits, list) or not all(isinstance(x, str) and IDENT.match(x) for x in limits):
        raise TableError(f"{where}: 'limits' must be a list of report.json limit keys")
    when = d.get("when", "")
    if not isinstance(when, str) or (when and not DEVICE.match(when)):
        raise TableError(f"{where}: 'when' must name one scene option (snake_case)")
    return Column(name, _text(d, "symbol", where), _text(d, "unit", where), _text(d, "description", where),
                  when, limits)


def _figure(d: dict, where: str) -> Figure:
    _no_unknown(d, {"name", "unit", "description"}, where)
    name = _text(d, "name", where)
    if not IDENT.match(name):
        raise TableError(f"{where}: figure name '{name}' is not snake_case")
    return Figure(name, _text(d, "unit", f"{where} ({name})"), _text(d, "description", f"{where} ({name})"))


def _unique(items, what: str, path: Path) -> None:
    seen = set()
    for it in items:
        if it.name in seen:
            raise TableError(f"{path}: {what} '{it.name}' is declared twice")
        seen.add(it.name)


def load(path: Path) -> Table:
    path = Path(path)
    try:
        with path.open("rb") as f:
            d = tomllib.load(f)
    except tomllib.TOMLDecodeError as e:
        raise TableError(f"{path}: {e}") from None
    _no_unknown(d, {"device", "title", "summary", "namespace", "sensor", "command", "column", "figure"}, str(path))
    device = _text(d, "device", str(path))
    if not DEVICE.match(device):
        raise TableError(f"{path}: device '{device}' is not snake_case")
    if path.name != f"{device}_signals.toml":
        raise TableError(f"{path}: the table of device '{device}' is named {device}_signals.toml")
    namespace = d.get("namespace", f"gyrostab::msg::{device}")
    sensors = [_signal(s, f"{path}: sensor #{i + 1}", SENSOR_NODES, False) for i, s in enumerate(d.get("sensor", []))]
    commands = [_signal(s, f"{path}: command #{i + 1}", COMMAND_NODES, True)
                for i, s in enumerate(d.get("command", []))]
    columns = [_column(c, f"{path}: column #{i + 1}") for i, c in enumerate(d.get("column", []))]
    figures = [_figure(c, f"{path}: figure #{i + 1}") for i, c in enumerate(d.get("figure", []))]
    _unique(sensors, "sensor", path)
    _unique(commands, "command", path)
    _unique(columns, "column", path)
    _unique(figures, "figure", path)
    t = Table(path, device, _text(d, "title", str(path)), _text(d, "summary", str(path)), namespace, sensors,
              commands, columns, figures)
    if t.sensor_values > MAX_SENSOR_VALUES:
        raise TableError(f"{path}: {t.sensor_values} sensor values, at most {MAX_SENSOR_VALUES} (msg::kMaxSensorSignals)")
    if t.command_values > MAX_COMMAND_VALUES:
        raise TableError(f"{path}: {t.command_values} command values, at most {MAX_COMMAND_VALUES} (msg::kMaxCommandSignals)")
    return t
