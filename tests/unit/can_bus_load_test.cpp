// Bus-load arithmetic of hil/can/bus_load.hpp. Oracles: the worst-case length of a classic frame with an
// 11-bit id, C = 55 + 10 n bits (Davis, Burns, Bril, Lukkien, "Controller Area Network (CAN) schedulability
// analysis: refuted, revisited and revised", Real-Time Systems 35, 2007, eq. (1): g = 34, 8n + g + 13 +
// floor((g + 8n − 1)/4)), and the CAN FD frame layout of ISO 11898-1:2015 counted field by field below.
// Integer bit counts: exact. Loads: sums of those over exact bit rates, compared to 1e-9 (the hand sums are
// exact to 0.1 us; double rounding of a handful of additions is ~1e-16).
#include <gtest/gtest.h>

#include "hil/can/bus_load.hpp"

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
}

TEST(CanBusLoad, ShippedDeviceSetsAtOneKilohertz) {
  const BusTiming t{1e6, 5e6};
  auto us = [&](std::size_t n) { return 1e6 * frame_time_s(fd_frame_bits(n), t); };
  // Ship damper / monorail: IMU 64, DRIVE2_FB 32, SENSOR_HUB 64, CONTROLLER_CMD 64, DRIVE2_CMD 20 (the header
  // frames are 64 bytes since they carry the link envelope).
  const BusLoad damper = bus_load(kNodeImu | kNodeDrive2, 1000.0, t);
  EXPECT_EQ(damper.frames_per_tick, 5);
  EXPECT_NEAR(damper.busy_s_per_tick * 1e6, us(64) + us(32) + us(64) + us(64) + us(20), 1e-9);
  // Per frame [us] = 33 nominal bits / 1 Mbit/s + data bits / 5 Mbit/s: 64 B 168.8, 48 B 136.8, 32 B 104.8,
  // 20 B 80.8. Damper: 168.8 + 104.8 + 168.8 + 168.8 + 80.8 = 692.0 us per 1 ms tick.
  EXPECT_NEAR(damper.load, 0.6920, 1e-9);
  EXPECT_TRUE(damper.acceptable());
  // Two-axis devices without IMU (power stabilizer, servo gyro): 2·104.8 + 2·168.8 + 2·80.8 = 708.8 us, over
  // the 70 % limit at 1 kHz on a 1/5 Mbit/s bus; with an 8 Mbit/s data phase 2·(33 + 359/8) + 2·(33 + 679/8) +
  // 2·(33 + 239/8) = 517.25 us.
  const BusLoad two_axis = bus_load(kNodeDrive1 | kNodeDrive2, 1000.0, t);
  EXPECT_EQ(two_axis.frames_per_tick, 6);
  EXPECT_NEAR(two_axis.load, 0.7088, 1e-9);
  EXPECT_FALSE(two_axis.acceptable());
  EXPECT_NEAR(bus_load(kNodeDrive1 | kNodeDrive2, 1000.0, BusTiming{1e6, 8e6}).load, 0.51725, 1e-9);
  // The CMG cluster (IMU, the cluster's two feedback frames and its command frame of 48 B): 3·168.8 + 3·136.8 =
  // 916.8 us, refused at 1 kHz on a 1/5 Mbit/s bus; with an 8 Mbit/s data phase 3·(33 + 679/8) + 3·(33 + 519/8)
  // = 647.25 us.
  const BusLoad cluster = bus_load(kNodeImu | kNodeCluster, 1000.0, t);
  EXPECT_EQ(cluster.frames_per_tick, 6);
  EXPECT_NEAR(cluster.load, 0.9168, 1e-9);
  EXPECT_FALSE(cluster.acceptable());
  EXPECT_NEAR(bus_load(kNodeImu | kNodeCluster, 1000.0, BusTiming{1e6, 8e6}).load, 0.64725, 1e-9);
  // Every node: 877.6 us + the cluster's 3·136.8 = 1288.0 us — refused at 1 kHz on a 1/5 Mbit/s bus.
  EXPECT_NEAR(bus_load(kAllNodes, 1000.0, t).load, 1.2880, 1e-9);
  EXPECT_FALSE(bus_load(kAllNodes, 1000.0, t).acceptable());
  // The 10 kHz current-loop scene: far beyond any CAN bus.
  EXPECT_GT(bus_load(kNodeDrive1 | kNodeDrive2, 10000.0, t).load, 6.0);
}

TEST(CanBusLoad, LoadScalesWithTickRateAndDataBitRate) {
  const BusLoad a = bus_load(kAllNodes, 500.0, BusTiming{1e6, 5e6});
  const BusLoad b = bus_load(kAllNodes, 1000.0, BusTiming{1e6, 5e6});
  EXPECT_NEAR(b.load, 2.0 * a.load, 1e-12);
  EXPECT_LT(bus_load(kAllNodes, 1000.0, BusTiming{1e6, 8e6}).load, b.load);
}

}  // namespace can_bus_load_test
}  // namespace gyrostab::can
