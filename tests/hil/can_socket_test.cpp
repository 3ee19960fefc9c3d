// The SocketCAN link (hil/can/socketcan_link.hpp) on a real vcan interface, and can-utils as the independent
// other end: CAN FD and classic frames cross vcan intact with kernel timestamps; the kernel filter passes only
// our identifiers; candump records our frames exactly as our candump writer writes them; canplayer replays a
// log our writer wrote into frames identical to the originals. Also prints the frames/s through vcan (a
// measurement, not an assertion: timing is not asserted in tests).
#include <gtest/gtest.h>
#include <signal.h>
#include <time.h>

#include <chrono>
#include <cstring>
#include <thread>

#include "gyrostab_signals/union_fixture_can.hpp"
#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/socketcan_link.hpp"
#include "tests/hil/hil_test_support.hpp"
#include "tests/support/union_frames.hpp"

namespace gyrostab::testing {
namespace {

using can::CanFrame;
using can::CanRx;
using can::SocketCan;
using can::SocketCanConfig;

std::int64_t mono_ns(clockid_t c = CLOCK_MONOTONIC) {
  timespec ts{};
  clock_gettime(c, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

SocketCan open_socket(std::vector<std::uint32_t> ids = {}) {
  SocketCan s;
  SocketCanConfig c;
  c.ifname = can_if();
  c.receive_ids = std::move(ids);
  std::string error;
  EXPECT_TRUE(s.open(c, error)) << error;
  return s;
}

bool same_frame(const CanFrame& a, const CanFrame& b) {
  return a.id == b.id && a.len == b.len && a.flags == b.flags && std::memcmp(a.data, b.data, a.len) == 0;
}

CanFrame fd_frame(std::uint32_t id, std::uint8_t len, std::uint8_t seed) {
  CanFrame f{};
  f.id = id;
  f.len = len;
  f.flags = can::kFlagFd | can::kFlagBrs;
  for (int i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(seed + 7 * i);
  return f;
}

TEST(CanSocket, FdAndClassicFramesCrossVcanWithKernelTimestamps) {
  SocketCan tx = open_socket();
  SocketCan rx = open_socket();
  CanFrame classic{};
  classic.id = 0x123;
  classic.len = 4;
  std::memcpy(classic.data, "\xDE\xAD\xBE\xEF", 4);
  const CanFrame frames[] = {fd_frame(0x1A0, 48, 1), classic, fd_frame(0x7FF, 64, 9)};
  for (const CanFrame& f : frames) ASSERT_TRUE(tx.send(f, mono_ns() + 1'000'000'000));
  const std::int64_t wall = mono_ns(CLOCK_REALTIME);
  for (const CanFrame& want : frames) {
    CanFrame got;
    ASSERT_EQ(rx.receive(got, mono_ns() + 2'000'000'000), CanRx::kFrame);
    EXPECT_TRUE(same_frame(got, want)) << std::hex << got.id;
    // The kernel stamped it (CLOCK_REALTIME) when it was queued: within a minute of now, whatever the load.
    EXPECT_LT(std::llabs(got.time_ns - wall), 60'000'000'000LL);
  }
  EXPECT_EQ(tx.counters().sent, 3u);
  EXPECT_EQ(rx.counters().received, 3u);
  CanFrame none;
  EXPECT_EQ(rx.receive(none, mono_ns() + 50'000'000), CanRx::kTimeout);
}

TEST(CanSocket, KernelFilterPassesOnlyOurStandardIds) {
  SocketCan tx = open_socket();
  SocketCan rx = open_socket({0x1A0, 0x190});
  CanFrame other = fd_frame(0x123, 8, 3);
  CanFrame ext = fd_frame(0x1A0, 8, 4);
  ext.flags |= can::kFlagExtended;
  CanFrame classic_ours{};
  classic_ours.id = 0x190;
  classic_ours.len = 8;
  for (const CanFrame& f : {other, ext, fd_frame(0x1A0, 48, 5), classic_ours}) ASSERT_TRUE(tx.send(f, mono_ns() + 1'000'000'000));
  CanFrame got;
  ASSERT_EQ(rx.receive(got, mono_ns() + 2'000'000'000), CanRx::kFrame);
  EXPECT_EQ(got.id, 0x1A0u);
  EXPECT_EQ(got.len, 48);
  ASSERT_EQ(rx.receive(got, mono_ns() + 2'000'000'000), CanRx::kFrame);
  EXPECT_EQ(got.id, 0x190u) << "a classic frame on one of our ids passes the filter: the decoder counts it";
  EXPECT_FALSE(got.fd());
  EXPECT_EQ(rx.receive(got, mono_ns() + 50'000'000), CanRx::kTimeout);
}

// One tick of the bus: a sensor set and a command set of every node, as the processes send them.
std::vector<CanFrame> one_tick_of_frames() {
  const can::DeviceBus bus = can::whole_bus(can::union_fixture::kCanMap);
  can::FrameEncoder se(bus, can::Direction::kSensor), ae(bus, can::Direction::kActuator);
  msg::SensorFrame s{};
  s.tick = 42;
  s.carrier_angle_rad[0] = 0.25;
  s.rotor_speed_rad_s = 700.0;
  msg::ActuatorFrame a{};
  a.tick = 42;
  a.gimbal_torque_Nm[1] = -12.5;
  a.precession_brake = 1.0;
  std::array<CanFrame, can::kMaxMessagesPerDirection> buf{};
  std::vector<CanFrame> out;
  std::size_t n = se.encode(s, buf);
  out.insert(out.end(), buf.begin(), buf.begin() + static_cast<long>(n));
  n = ae.encode(a, buf);
  out.insert(out.end(), buf.begin(), buf.begin() + static_cast<long>(n));
  return out;
}

std::string strip_time(const std::string& line) {
  const auto p = line.find(") ");
  return p == std::string::npos ? line : line.substr(p + 2);
}

TEST(CanSocket, CandumpRecordsOurFramesAsOurWriterWritesThem) {
  TempDir d;
  const std::string log = d / "candump.log";
  const pid_t candump = spawn({"/bin/sh", "-c", "exec candump -L " + can_if() + " > " + log});
  ASSERT_TRUE(wait_for_can_listener(-1)) << "candump never opened its socket";
  SocketCan tx = open_socket();
  const std::vector<CanFrame> frames = one_tick_of_frames();
  for (const CanFrame& f : frames) ASSERT_TRUE(tx.send(f, mono_ns() + 1'000'000'000));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  kill(candump, SIGINT);
  wait_for(candump);
  std::istringstream in(read_file(log));
  std::string line;
  std::size_t i = 0;
  while (std::getline(in, line)) {
    ASSERT_LT(i, frames.size()) << "extra line from candump: " << line;
    char ours[can::kMaxCandumpLine];
    const std::size_t n = can::format_candump_line(frames[i], can_if(), 0, ours, sizeof ours);
    EXPECT_EQ(strip_time(line), strip_time(std::string(ours, n - 1))) << "frame " << i;
    ++i;
  }
  EXPECT_EQ(i, frames.size()) << "candump recorded " << i << " of " << frames.size() << " frames";
}

TEST(CanSocket, CanplayerReplaysALogOurWriterWrote) {
  TempDir d;
  const std::string log = d / "ours.log";
  const std::vector<CanFrame> frames = one_tick_of_frames();
  {
    can::CandumpWriter w;
    std::string error;
    ASSERT_TRUE(w.open(log, can_if(), {"gyrostab-candump 1", "canplayer skips comment lines"}, error)) << error;
    for (std::size_t i = 0; i < frames.size(); ++i) ASSERT_TRUE(w.write(frames[i], static_cast<std::int64_t>(i) * 1'000'000));
    ASSERT_TRUE(w.close(error)) << error;
  }
  SocketCan rx = open_socket();
  const Exit e = run({"/usr/bin/canplayer", "-I", log});
  ASSERT_EQ(e.code, 0);
  for (const CanFrame& want : frames) {
    CanFrame got;
    ASSERT_EQ(rx.receive(got, mono_ns() + 2'000'000'000), CanRx::kFrame);
    EXPECT_TRUE(same_frame(got, want)) << std::hex << want.id;
  }
}

TEST(CanSocket, FramesPerSecondThroughVcan) {
  SocketCan tx = open_socket();
  SocketCan rx = open_socket({0x190});
  constexpr int kFrames = 20000;
  std::uint64_t got = 0;
  std::thread reader([&] {
    CanFrame f;
    while (got < static_cast<std::uint64_t>(kFrames) && rx.receive(f, mono_ns() + 2'000'000'000) == CanRx::kFrame) ++got;
  });
  const CanFrame f = fd_frame(0x190, 64, 0);
  const auto start = std::chrono::steady_clock::now();
  int sent = 0;
  for (; sent < kFrames; ++sent)
    if (!tx.send(f, mono_ns() + 1'000'000'000)) break;
  reader.join();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(sent, kFrames);
  // Every frame sent was either received or dropped by the kernel for a full receive queue (counted): none
  // vanished unaccounted.
  EXPECT_EQ(got + rx.counters().kernel_drops, static_cast<std::uint64_t>(sent));
  std::printf("[ measured ] %s (%s): %d CAN FD 64-byte frames in %.3f s: %.0f frames/s sent, %.0f frames/s "
              "received, %llu dropped by the kernel\n",
              can_if().c_str(), std::getenv("GYROSTAB_VCAN_MODE"), sent, s, sent / s, static_cast<double>(got) / s,
              static_cast<unsigned long long>(rx.counters().kernel_drops));
}

}  // namespace
}  // namespace gyrostab::testing

GYROSTAB_HIL_TEST_MAIN()
