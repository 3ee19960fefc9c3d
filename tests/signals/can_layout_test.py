#!/usr/bin/python3
"""tools/signals/can_layout.py and the CAN keys of a signal table (tools/signals/signal_table.py): the wire
rules of docs/can.md on the union fixture table and on small tables written here — values packed per node in table
order, a node with more than a frame holds gets more frames, the header node's values in bytes 36-43 of the
header, `node` per element, `can = "int32"` and its checks, stable identifiers, every byte of the frames
carried exactly once. Run by ctest (label unit, < 1 s)."""

import sys
import tempfile
import textwrap
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools" / "signals"))

import can_layout  # noqa: E402
from signal_table import TableError, load  # noqa: E402

HEAD = 'device = "{d}"\ntitle = "t"\nsummary = "s"\n'


def sensor(name, node, count=1, can=None, lo=-1.0, hi=1.0):
    extra = f'count = {count}\n' if count > 1 else ""
    extra += f'can = "{can}"\n' if can else ""
    node_text = node if node.startswith("[") else f'"{node}"'
    return (f'[[sensor]]\nname = "{name}"\nsymbol = "x"\nunit = "-"\nrange = [{lo}, {hi}]\nnode = {node_text}\n'
            f'description = "d"\n{extra}\n')


def command(name, node, count=1, can=None, safe=0.0, lo=-1.0, hi=1.0):
    return sensor(name, node, count, can, lo, hi).replace("[[sensor]]", "[[command]]") + f"safe = {safe}\n"


class Tables(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.dir.cleanup()

    def table(self, body, device="fixture"):
        p = Path(self.dir.name) / f"{device}_signals.toml"
        p.write_text(HEAD.format(d=device) + textwrap.dedent(body))
        return load(p)

    def refused(self, body, words):
        with self.assertRaises(TableError) as e:
            can_layout.layout(self.table(body))
        self.assertIn(words, str(e.exception))


def covered_once(test, t, messages):
    """Every byte of both frames (header + 8 bytes per value) is carried by exactly one signal."""
    for direction, values in (("sensor", t.sensor_values), ("command", t.command_values)):
        size = can_layout.FRAME_HEADER_BYTES + 8 * values
        cover = [0] * size
        for m in messages:
            if m.direction != direction:
                continue
            bits = [False] * (8 * m.length)
            for s in m.signals:
                test.assertLessEqual(s.start_bit + s.bit_length, 8 * m.length, f"{m.name}.{s.name}")
                for b in range(s.start_bit, s.start_bit + s.bit_length):
                    test.assertFalse(bits[b], f"{m.name}.{s.name} overlaps at bit {b}")
                    bits[b] = True
                if s.field_offset < 0:
                    continue
                n = 8 if s.integer else s.bit_length // 8
                for i in range(s.field_offset, s.field_offset + n):
                    cover[i] += 1
            test.assertEqual(m.length, 64 if m.header else can_layout.fd_length(m.used_bytes), m.name)
        test.assertEqual(cover, [1] * size, f"{direction} bytes not covered exactly once")


class UnionFixtureTable(Tables):
    def test_the_union_fixture_keeps_its_frames_and_the_drive_frames_their_32_bytes(self):
        t = load(ROOT / "tests/signals/union_fixture_signals.toml")
        m = can_layout.layout(t)
        self.assertEqual([(x.name, hex(x.id), x.length) for x in m], [
            ("DRIVE1_CMD", "0x120", 20), ("DRIVE2_CMD", "0x130", 20), ("CLUSTER_CMD", "0x140", 48),
            ("CONTROLLER_CMD", "0x1ff", 64),
            ("IMU_FB", "0x210", 64), ("DRIVE1_FB", "0x220", 32), ("DRIVE2_FB", "0x230", 32),
            ("CLUSTER_FB", "0x240", 64), ("CLUSTER_FB_2", "0x241", 12), ("SENSOR_HUB", "0x2ff", 64)])
        drive2 = next(x for x in m if x.name == "DRIVE2_FB")
        self.assertEqual([(s.name, s.start_bit, s.bit_length, s.kind) for s in drive2.signals[3:]], [
            ("gimbal_angle_rad_2", 32, 64, "double"), ("gimbal_rate_rad_s_2", 96, 64, "double"),
            ("motor_current_A_2", 160, 64, "double"), ("encoder_count_2", 224, 32, "signed")])
        self.assertTrue(drive2.signals[-1].integer)
        hub = m[-1]
        self.assertEqual([s.name for s in hub.signals if 36 * 8 <= s.start_bit < 44 * 8], ["rotor_speed_rad_s"])
        covered_once(self, t, m)


class Packing(Tables):
    def test_values_ride_in_their_node_frame_in_table_order_element_by_element(self):
        t = self.table(sensor("a", "imu") + sensor("b", '["drive1", "drive2"]', 2) + sensor("c", "imu")
                       + command("u", '["drive2", "drive1"]', 2))
        m = {x.name: x for x in can_layout.layout(t)}
        self.assertEqual([s.name for s in m["IMU_FB"].signals[3:]], ["a", "c"])
        self.assertEqual([s.name for s in m["DRIVE1_FB"].signals[3:]], ["b_1"])
        self.assertEqual([s.name for s in m["DRIVE2_FB"].signals[3:]], ["b_2"])
        self.assertEqual([s.name for s in m["DRIVE2_CMD"].signals[3:]], ["u_1"])
        self.assertEqual([s.name for s in m["DRIVE1_CMD"].signals[3:]], ["u_2"])
        # Value i of the frame at kFrameHeaderBytes + 8 i: a 0, b_1 1, b_2 2, c 3.
        self.assertEqual(m["IMU_FB"].signals[4].field_offset, 32 + 8 * 3)
        self.assertEqual(m["DRIVE2_FB"].signals[3].field_offset, 32 + 8 * 2)
        self.assertEqual(m["DRIVE1_CMD"].signals[3].field_offset, 32 + 8 * 1)
        self.assertEqual(m["IMU_FB"].length, 20)
        b2 = m["DRIVE2_FB"].signals[3]
        self.assertEqual((b2.table_name, b2.element, b2.value), ("b", 1, 2))
        covered_once(self, t, can_layout.layout(t))

    def test_a_node_with_more_than_a_frame_holds_gets_more_frames(self):
        t = self.table(sensor("w", "cluster", 8) + sensor("z", "cluster", 2))
        m = [x for x in can_layout.layout(t) if x.node == "cluster"]
        self.assertEqual([(x.name, hex(x.id), x.length, len(x.signals) - 3) for x in m],
                         [("CLUSTER_FB", "0x240", 64, 7), ("CLUSTER_FB_2", "0x241", 32, 3)])
        covered_once(self, t, can_layout.layout(t))

    def test_the_header_node_fills_bytes_36_to_43_then_frames_of_its_own(self):
        t = self.table(sensor("s", "sensor_hub", 3) + sensor("n", "sensor_hub", 2, "int32", -10, 10)
                       + command("b", "controller", 1))
        m = {x.name: x for x in can_layout.layout(t)}
        hub = m["SENSOR_HUB"]
        self.assertEqual(hub.id, 0x2FF)
        self.assertEqual([(s.name, s.start_bit // 8) for s in hub.signals if s.value >= 0], [("s_1", 36)])
        self.assertEqual(hub.signals[-4].name, "link_sender")
        self.assertEqual(m["SENSOR_HUB_2"].id, 0x2F0)
        self.assertEqual([(s.name, s.start_bit // 8, s.bit_length) for s in m["SENSOR_HUB_2"].signals[3:]],
                         [("s_2", 4, 64), ("s_3", 12, 64), ("n_1", 20, 32), ("n_2", 24, 32)])
        self.assertEqual(m["SENSOR_HUB_2"].length, 32)
        self.assertEqual([s.name for s in m["CONTROLLER_CMD"].signals if s.value >= 0], ["b"])
        layout = can_layout.layout(t)
        self.assertEqual(layout[-1].name, "SENSOR_HUB", "the header is sent last")
        covered_once(self, t, layout)

    def test_two_integers_share_the_header_room(self):
        t = self.table(sensor("k", "sensor_hub", 3, "int32", -5, 5))
        m = {x.name: x for x in can_layout.layout(t)}
        self.assertEqual([(s.name, s.start_bit // 8) for s in m["SENSOR_HUB"].signals if s.value >= 0],
                         [("k_1", 36), ("k_2", 40)])
        self.assertEqual([s.name for s in m["SENSOR_HUB_2"].signals[3:]], ["k_3"])
        self.assertEqual(m["SENSOR_HUB_2"].length, 8)

    def test_a_device_without_values_still_has_both_headers(self):
        t = self.table("")
        self.assertEqual([x.name for x in can_layout.layout(t)], ["CONTROLLER_CMD", "SENSOR_HUB"])

    def test_identifiers_of_a_node_do_not_move_when_another_node_grows(self):
        small = can_layout.layout(self.table(sensor("a", "imu") + sensor("d", "drive2")))
        big = can_layout.layout(self.table(sensor("a", "imu", 8) + sensor("c", "imu", 8) + sensor("d", "drive2")))
        ident = lambda ms, n: next(x.id for x in ms if x.name == n)  # noqa: E731
        self.assertEqual(ident(small, "DRIVE2_FB"), ident(big, "DRIVE2_FB"))
        self.assertEqual(sorted(x.name for x in big if x.node == "imu"), ["IMU_FB", "IMU_FB_2", "IMU_FB_3"])
        self.assertNotEqual(can_layout.fingerprint(small), can_layout.fingerprint(big))

    def test_ids_are_unique_eleven_bit_and_within_each_direction_the_header_is_the_highest(self):
        t = self.table(sensor("a", "imu", 8) + sensor("b", "sensor_hub", 8) + sensor("c", "cluster", 8)
                       + command("u", "controller", 8) + command("v", "drive1", 8))
        m = can_layout.layout(t)
        self.assertEqual(len({x.id for x in m}), len(m))
        for d in ("sensor", "command"):
            ids = [x.id for x in m if x.direction == d]
            self.assertTrue(all(i <= 0x7FF for i in ids))
            self.assertEqual(max(ids), [x.id for x in m if x.direction == d and x.header][0])
        covered_once(self, t, m)


class TableKeys(Tables):
    def test_node_lists_have_one_node_per_element(self):
        self.refused(sensor("g", '["drive1"]', 2), "lists 1 nodes for 2 element(s)")
        self.refused(sensor("g", '["drive1", "ship"]', 2), "node 'ship' is not one of")
        self.refused(command("g", '["drive1", "imu"]', 2), "node 'imu' is not one of")
        self.refused(sensor("g", "[1, 2]", 2), "'node' must be a node name or a list")
        t = self.table(sensor("g", '["drive2", "drive1"]', 2))
        self.assertEqual(t.sensors[0].nodes, ["drive2", "drive1"])
        self.assertEqual(t.sensors[0].node, "drive2, drive1")

    def test_can_integer_types_are_checked(self):
        self.refused(sensor("n", "drive1", 1, "int64"), "'can' must be one of")
        self.refused(sensor("n", "drive1", 1, "int16", -40000, 10), "does not fit 'int16'")
        self.refused(sensor("n", "drive1", 1, "uint8", -1, 10), "does not fit 'uint8'")
        self.refused(command("n", "drive1", 1, "int32", 0.5), "is not an integer")
        self.refused(command("n", "drive1", 1, "int32", "-0.0"), "is not an integer")
        t = self.table(sensor("n", "drive1", 1, "uint16", 0, 65535))
        s = can_layout.layout(t)[-2].signals[3]
        self.assertEqual((s.name, s.bit_length, s.kind, s.integer), ("n", 16, "unsigned", True))

    def test_a_value_may_not_take_an_envelope_name(self):
        self.refused(sensor("link_mac", "imu"), "is a name of the envelope or the frame header")
        self.refused(sensor("sample_time", "imu"), "is a name of the envelope or the frame header")


if __name__ == "__main__":
    unittest.main()
