// Bus-load arithmetic of hil/can/bus_load.hpp. Oracles: the worst-case length of a classic frame with an
// 11-bit id, C = 55 + 10 n bits (Davis, Burns, Bril, Lukkien, "Controller Area Network (CAN) schedulability
// analysis: refuted, revisited and revised", Real-Time Systems 35, 2007, eq. (1): g = 34, 8n + g + 13 +
// floor((g + 8n − 1)/4)), and the CAN FD frame layout of ISO 11898-1:2015 counted field by field below.
// Integer bit counts: exact. Loads: sums of those over exact bit rates, compared to 1e-9 (the hand sums are
// exact to 0.1 us; double rounding of a handful of additions is ~1e-16).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "gyrostab_signals/all_can_maps.hpp"
#include "hil/can/bus_load.hpp"
#include "tools/devices/registry.hpp"
#include "tools/run/can_link_setup.hpp"

namespace gyrostab::can {
namespace can_bus_load_test {

TEST(CanBusLoad, ClassicWorstCaseMatchesDavisEtAl) {
  for (std::size_t n = 0; n <= 8; ++n) {
    EXPECT_EQ(classic_frame_bits(n).nominal, 55 + 10 * static_cast<int>(n)) << n << " bytes";
  }
}

TEST(CanBusLoad, ClassicCanCarriesAbout7kFullFramesPerSecondAtOneMegabit) {
  const double frames_per_s = 1e6 / classic_frame_bits(8).nominal;  // worst case stuffing
  EXPECT_NEAR(frames_per_s, 7407.4, 0.1);
  // Without any stuff bits an 8-byte frame is 111 bits: the best case, 9009 frames/s.
  EXPECT_NEAR(1e6 / (classic_frame_bits(8).nominal - 24), 9009.0, 0.1);
}

TEST(CanBusLoad, FdFrameFieldByField) {
  // 64 bytes: arbitration 17 + 4 stuff + ACK/EOF/IFS 12 = 33 nominal bits; data phase: ESI + DLC 5, data 512,
  // dynamic stuff floor((21 + 512)/4) − 4 = 129, stuff count 4, CRC-21, 7 fixed stuff bits, CRC delimiter 1.
  EXPECT_EQ(fd_frame_bits(64).nominal, 33);
  EXPECT_EQ(fd_frame_bits(64).data, 5 + 512 + 129 + 4 + 21 + 7 + 1);
  // 16 bytes: CRC-17 with 6 fixed stuff bits; dynamic stuff floor((21 + 128)/4) − 4 = 33.
  EXPECT_EQ(fd_frame_bits(16).data, 5 + 128 + 33 + 4 + 17 + 6 + 1);
  // 20 bytes: CRC-21.
  EXPECT_EQ(fd_frame_bits(20).data, 5 + 160 + 41 + 4 + 21 + 7 + 1);
  // 12 bytes: dynamic stuff floor((21 + 96)/4) − 4 = 25, CRC-17.
  EXPECT_EQ(fd_frame_bits(12).data, 5 + 96 + 25 + 4 + 17 + 6 + 1);
}

// The buses of the legacy table's devices, by their descriptors' nodes (the transitional node filter).
DeviceBus legacy_bus(NodeSet nodes) { return device_bus(legacy::kCanMap, nodes); }

TEST(CanBusLoad, LegacyDeviceSetsAtOneKilohertz) {
  const BusTiming t{1e6, 5e6};
  auto us = [&](std::size_t n) { return 1e6 * frame_time_s(fd_frame_bits(n), t); };
  // Ship damper / monorail: IMU_FB 64, DRIVE2_FB 32 (angle, rate, current, encoder count as int32),
  // SENSOR_HUB 64, CONTROLLER_CMD 64, DRIVE2_CMD 20 (the header frames are 64 bytes: the link envelope).
  const BusLoad damper = bus_load(legacy_bus(kNodeImu | kNodeDrive2), 1000.0, t);
  EXPECT_EQ(damper.frames_per_tick, 5);
  EXPECT_NEAR(damper.busy_s_per_tick * 1e6, us(64) + us(32) + us(64) + us(64) + us(20), 1e-9);
  // Per frame [us] = 33 nominal bits / 1 Mbit/s + data bits / 5 Mbit/s: 64 B 168.8, 48 B 136.8, 32 B 104.8,
  // 20 B 80.8, 12 B 63.8. Damper: 168.8 + 104.8 + 168.8 + 168.8 + 80.8 = 692.0 us per 1 ms tick.
  EXPECT_NEAR(damper.load, 0.6920, 1e-9);
  EXPECT_TRUE(damper.acceptable());
  // Two-axis devices without IMU (power stabilizer, servo gyro): 2·104.8 + 2·168.8 + 2·80.8 = 708.8 us, over
  // the 70 % limit at 1 kHz on a 1/5 Mbit/s bus; with an 8 Mbit/s data phase 2·(33 + 359/8) + 2·(33 + 679/8) +
  // 2·(33 + 239/8) = 517.25 us.
  const BusLoad two_axis = bus_load(legacy_bus(kNodeDrive1 | kNodeDrive2), 1000.0, t);
  EXPECT_EQ(two_axis.frames_per_tick, 6);
  EXPECT_NEAR(two_axis.load, 0.7088, 1e-9);
  EXPECT_FALSE(two_axis.acceptable());
  EXPECT_NEAR(bus_load(legacy_bus(kNodeDrive1 | kNodeDrive2), 1000.0, BusTiming{1e6, 8e6}).load, 0.51725, 1e-9);
  // The CMG cluster: IMU_FB 64, the cluster's eight values in CLUSTER_FB (seven doubles, 64 B) and
  // CLUSTER_FB_2 (one, 12 B), its command frame of four doubles (48 B), and the two headers: 4·168.8 + 63.8 +
  // 136.8 = 875.8 us, refused at 1 kHz on a 1/5 Mbit/s bus; with an 8 Mbit/s data phase 4·(33 + 679/8) +
  // (33 + 154/8) + (33 + 519/8) = 621.625 us.
  const BusLoad cluster = bus_load(legacy_bus(kNodeImu | kNodeCluster), 1000.0, t);
  EXPECT_EQ(cluster.frames_per_tick, 6);
  EXPECT_NEAR(cluster.load, 0.8758, 1e-9);
  EXPECT_FALSE(cluster.acceptable());
  EXPECT_NEAR(bus_load(legacy_bus(kNodeImu | kNodeCluster), 1000.0, BusTiming{1e6, 8e6}).load, 0.621625, 1e-9);
  // Every node, 10 frames: 64 B ×4 (IMU_FB, CLUSTER_FB, the two headers) 675.2, 32 B ×2 209.6, 20 B ×2
  // 161.6, 48 B 136.8, 12 B 63.8 = 1247.0 us — refused at 1 kHz on a 1/5 Mbit/s bus.
  EXPECT_NEAR(bus_load(legacy_bus(kAllNodes), 1000.0, t).load, 1.2470, 1e-9);
  EXPECT_FALSE(bus_load(legacy_bus(kAllNodes), 1000.0, t).acceptable());
  // The 10 kHz current-loop scene: far beyond any CAN bus.
  EXPECT_GT(bus_load(legacy_bus(kNodeDrive1 | kNodeDrive2), 10000.0, t).load, 6.0);
}

// Every shipped device's bus at 1 kHz on the default 1/5 Mbit/s bus (the scenes' own rates: the closed-loop
// CAN test, tests/hil/can_closed_loop_test.cpp): printed, and each one's load the sum of its frames' times.
TEST(CanBusLoad, EveryShippedDeviceAtOneKilohertz) {
  const BusTiming t{1e6, 5e6};
  std::printf("[ bus load ] device                    map       frames/tick  load at 1 kHz (1/5 Mbit/s)\n");
  for (const tools::DeviceDescriptor* d : tools::devices()) {
    const DeviceBus bus = tools::can_bus_of(d->name);
    const BusLoad b = bus_load(bus, 1000.0, t);
    double busy = 0.0;
    int frames = 0;
    for (std::size_t i = 0; i < bus.messages().size(); ++i) {
      if (!bus.has(i)) continue;
      busy += frame_time_s(fd_frame_bits(bus.messages()[i].length), t);
      ++frames;
    }
    EXPECT_EQ(b.frames_per_tick, frames) << d->name;
    EXPECT_NEAR(b.load, busy * 1000.0, 1e-12) << d->name;
    EXPECT_GE(b.frames_per_tick, 2) << d->name << ": at least the two headers";
    std::printf("[ bus load ] %-25s %-9s %11d  %5.1f %%%s\n", std::string(d->name).c_str(),
                std::string(bus.map->device).c_str(), b.frames_per_tick, 100.0 * b.load,
                b.acceptable() ? "" : "  (over the 70 % limit at 1 kHz)");
  }
}

TEST(CanBusLoad, LoadScalesWithTickRateAndDataBitRate) {
  const BusLoad a = bus_load(legacy_bus(kAllNodes), 500.0, BusTiming{1e6, 5e6});
  const BusLoad b = bus_load(legacy_bus(kAllNodes), 1000.0, BusTiming{1e6, 5e6});
  EXPECT_NEAR(b.load, 2.0 * a.load, 1e-12);
  EXPECT_LT(bus_load(legacy_bus(kAllNodes), 1000.0, BusTiming{1e6, 8e6}).load, b.load);
}

}  // namespace can_bus_load_test
}  // namespace gyrostab::can
