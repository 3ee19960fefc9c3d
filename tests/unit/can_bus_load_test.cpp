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
#include "gyrostab_signals/union_fixture_can.hpp"
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

// The union fixture's bus (tests/signals/union_fixture_signals.toml): every shipped device's signal shapes at once.
DeviceBus union_bus() { return whole_bus(union_fixture::kCanMap); }

TEST(CanBusLoad, UnionFixtureSetAtOneKilohertz) {
  const BusTiming t{1e6, 5e6};
  auto us = [&](std::size_t n) { return 1e6 * frame_time_s(fd_frame_bits(n), t); };
  // Per frame [us] = 33 nominal bits / 1 Mbit/s + data bits / 5 Mbit/s: 64 B 168.8, 48 B 136.8, 32 B 104.8,
  // 20 B 80.8, 12 B 63.8. Every node, 10 frames: 64 B ×4 (IMU_FB, CLUSTER_FB, the two headers) 675.2, 32 B ×2
  // (DRIVE1_FB, DRIVE2_FB: angle, rate, current, encoder count as int32) 209.6, 20 B ×2 (DRIVE1_CMD,
  // DRIVE2_CMD) 161.6, 48 B (CLUSTER_CMD) 136.8, 12 B (CLUSTER_FB_2) 63.8 = 1247.0 us — refused at 1 kHz on a
  // 1/5 Mbit/s bus.
  const BusLoad all = bus_load(union_bus(), 1000.0, t);
  EXPECT_EQ(all.frames_per_tick, 10);
  EXPECT_NEAR(all.busy_s_per_tick * 1e6, 4 * us(64) + 2 * us(32) + 2 * us(20) + us(48) + us(12), 1e-9);
  EXPECT_NEAR(all.load, 1.2470, 1e-9);
  EXPECT_FALSE(all.acceptable());
  // The 10 kHz current-loop rate: far beyond any CAN bus.
  EXPECT_GT(bus_load(union_bus(), 10000.0, t).load, 12.0);
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
    for (const MessageSpec& m : bus.messages()) {
      busy += frame_time_s(fd_frame_bits(m.length), t);
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
  const BusLoad a = bus_load(union_bus(), 500.0, BusTiming{1e6, 5e6});
  const BusLoad b = bus_load(union_bus(), 1000.0, BusTiming{1e6, 5e6});
  EXPECT_NEAR(b.load, 2.0 * a.load, 1e-12);
  EXPECT_LT(bus_load(union_bus(), 1000.0, BusTiming{1e6, 8e6}).load, b.load);
}

}  // namespace can_bus_load_test
}  // namespace gyrostab::can
