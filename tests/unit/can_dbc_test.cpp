// The DBC file of the bus (hil/can/dbc_writer.hpp) says what the frame map says:
//   1. parsed back here (a small reader of the DBC lines we write: BO_, SG_, SIG_VALTYPE_, BA_ VFrameFormat),
//      every message and signal matches the map field by field, doubles exactly (%.17g round-trips);
//   2. an independent DBC reader, canmatrix (python3-canmatrix, installed by tools/setup), loads the file and
//      decodes a candump log of encoder output (tools/can/candump-decode) into exactly the contract values
//      the frames were encoded from — "common CAN tools decode the bus".
#include <gtest/gtest.h>

#include <bit>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "hil/can/candump_log.hpp"
#include "hil/can/dbc_writer.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/frame_map.hpp"

namespace gyrostab::can {
namespace can_dbc_test {

struct DbcSignal {
  int start{-1}, length{-1};
  char order{'?'}, sign{'?'};
  double factor{0}, offset{0}, min{0}, max{0};
  std::string unit, receivers;
  int valtype{0};
};
struct DbcMessage {
  std::string name, sender;
  int length{-1};
  int frame_format{-1};
  std::map<std::string, DbcSignal> signals;
};

std::map<std::uint32_t, DbcMessage> parse_dbc(const std::string& text) {
  std::map<std::uint32_t, DbcMessage> msgs;
  std::istringstream in(text);
  std::string line;
  DbcMessage* current = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("BO_ ", 0) == 0) {
      unsigned id = 0;
      char name[64] = {}, sender[64] = {};
      int len = -1;
      EXPECT_EQ(std::sscanf(line.c_str(), "BO_ %u %63[^:]: %d %63s", &id, name, &len, sender), 4) << line;
      DbcMessage& m = msgs[id];
      m.name = name;
      m.sender = sender;
      m.length = len;
      current = &m;
    } else if (line.rfind(" SG_ ", 0) == 0) {
      EXPECT_NE(current, nullptr) << line;
      if (current == nullptr) continue;
      char name[64] = {}, unit[64] = {}, receivers[128] = {};
      DbcSignal s;
      const int got = std::sscanf(line.c_str(), " SG_ %63s : %d|%d@%c%c (%lf,%lf) [%lf|%lf] \"%63[^\"]\" %127s", name,
                                  &s.start, &s.length, &s.order, &s.sign, &s.factor, &s.offset, &s.min, &s.max, unit,
                                  receivers);
      if (got == 9) {  // empty unit: %[ matches nothing
        std::sscanf(line.c_str() + line.find("\"\"") + 2, " %127s", receivers);
      } else {
        EXPECT_EQ(got, 11) << line;
      }
      s.unit = unit;
      s.receivers = receivers;
      current->signals[name] = s;
    } else if (line.rfind("SIG_VALTYPE_ ", 0) == 0) {
      unsigned id = 0;
      char name[64] = {};
      int type = 0;
      EXPECT_EQ(std::sscanf(line.c_str(), "SIG_VALTYPE_ %u %63s : %d;", &id, name, &type), 3) << line;
      msgs[id].signals[name].valtype = type;
    } else if (line.rfind("BA_ \"VFrameFormat\" BO_ ", 0) == 0) {
      unsigned id = 0;
      int format = -1;
      EXPECT_EQ(std::sscanf(line.c_str(), "BA_ \"VFrameFormat\" BO_ %u %d;", &id, &format), 2) << line;
      msgs[id].frame_format = format;
    }
  }
  return msgs;
}

TEST(CanDbc, ParsesBackToTheFrameMap) {
  const std::string text = dbc_text();
  EXPECT_NE(text.find("BA_ \"BusType\" \"CAN FD\";"), std::string::npos);
  const auto msgs = parse_dbc(text);
  ASSERT_EQ(msgs.size(), kMessageCount);
  for (const MessageSpec& m : kMessages) {
    const auto it = msgs.find(m.id);
    ASSERT_NE(it, msgs.end()) << m.name;
    const DbcMessage& d = it->second;
    EXPECT_EQ(d.name, m.name);
    EXPECT_EQ(d.sender, m.sender);
    EXPECT_EQ(d.length, m.length) << m.name;
    EXPECT_EQ(d.frame_format, 14) << m.name << ": StandardCAN_FD";
    EXPECT_EQ(d.signals.size(), m.signals.size()) << m.name;
    for (const SignalSpec& s : m.signals) {
      const auto sit = d.signals.find(std::string(s.name));
      ASSERT_NE(sit, d.signals.end()) << m.name << "." << s.name;
      const DbcSignal& ds = sit->second;
      EXPECT_EQ(ds.start, s.start_bit) << s.name;
      EXPECT_EQ(ds.length, s.bit_length) << s.name;
      EXPECT_EQ(ds.order, '1') << s.name << ": Intel byte order";
      EXPECT_EQ(ds.sign, s.kind == SignalKind::kUnsigned ? '+' : '-') << s.name;
      EXPECT_EQ(ds.factor, s.factor) << s.name;
      EXPECT_EQ(ds.offset, s.offset) << s.name;
      EXPECT_EQ(ds.min, s.min) << s.name;
      EXPECT_EQ(ds.max, s.max) << s.name;
      EXPECT_EQ(ds.unit, s.unit) << s.name;
      EXPECT_EQ(ds.valtype, s.kind == SignalKind::kDouble ? 2 : 0) << s.name;
      EXPECT_EQ(ds.receivers, m.direction == Direction::kSensor ? "controller"
                              : m.requires_node == kNodeDrive1  ? "drive1"
                              : m.requires_node == kNodeDrive2  ? "drive2"
                              : m.requires_node == kNodeCluster ? "cluster"
                                                                : "drive1,drive2,cluster")
          << s.name;
    }
  }
}

// Expected value of a signal in a frame, as text comparable with Python's repr.
std::string expected_value(const SignalSpec& s, const CanFrame& f) {
  std::uint64_t raw = 0;
  const int first = s.start_bit / 8;
  const int bytes = (s.start_bit % 8 + s.bit_length + 7) / 8;
  for (int i = 0; i < bytes; ++i) raw |= static_cast<std::uint64_t>(f.data[first + i]) << (8 * i);
  raw >>= s.start_bit % 8;
  if (s.bit_length < 64) raw &= (std::uint64_t{1} << s.bit_length) - 1;
  char buf[64];
  switch (s.kind) {
    case SignalKind::kDouble: std::snprintf(buf, sizeof buf, "%.17g", std::bit_cast<double>(raw)); break;
    case SignalKind::kUnsigned: std::snprintf(buf, sizeof buf, "%llu", static_cast<unsigned long long>(raw)); break;
    case SignalKind::kSigned: {
      const unsigned shift = static_cast<unsigned>(64 - s.bit_length);
      std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(static_cast<std::int64_t>(raw << shift) >> shift));
      break;
    }
  }
  return buf;
}

bool same_value(const SignalSpec& s, const std::string& want, const std::string& got) {
  if (s.kind != SignalKind::kDouble) return want == got;
  return std::bit_cast<std::uint64_t>(std::strtod(want.c_str(), nullptr)) ==
         std::bit_cast<std::uint64_t>(std::strtod(got.c_str(), nullptr));
}

TEST(CanDbc, CanmatrixDecodesEncoderOutputExactly) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("gyrostab_can_dbc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path dbc = dir / "bus.dbc";
  const fs::path log = dir / "bus.candump";
  std::ofstream(dbc) << dbc_text();

  msg::SensorFrame s{};
  s.tick = 0x1'0000'0123ull;
  s.time_ns = -5;
  s.sample_time_ns = 1234567890123;
  s.sequence = 0xFFFFFFFFu;
  s.status = 0x8000000Bu;
  s.carrier_angle_rad[0] = 0.1;
  s.carrier_angle_rad[2] = -3.0e-300;
  s.carrier_rate_rad_s[1] = 1.0 / 3.0;
  s.gimbal_angle_rad[1] = -2.5;
  s.gimbal_rate_rad_s[0] = 123.456;
  s.motor_current_A[1] = -0.0;
  s.rotor_speed_rad_s = 6283.185307179586;
  s.encoder_count[0] = -2147483647 - 1;
  s.encoder_count[1] = 2147483647;
  s.cluster_gimbal_angle_rad[2] = -3.0;
  s.cluster_gimbal_rate_rad_s[3] = 0.5;
  msg::ActuatorFrame a{};
  a.tick = 77;
  a.time_ns = 77'000'000;
  a.sensor_tick = 76;
  a.sequence = 3;
  a.status = 0x200u;
  a.gimbal_torque_Nm[0] = 1.5e6;
  a.gimbal_torque_Nm[1] = -2.0;
  a.motor_voltage_V[0] = 24.0;
  a.precession_brake = 1.0;
  a.cluster_rate_command_rad_s[1] = -0.75;

  std::vector<CanFrame> frames(2 * kMaxMessagesPerDirection);
  FrameEncoder se(Direction::kSensor, kAllNodes), ae(Direction::kActuator, kAllNodes);
  std::size_t n = se.encode(s, std::span<CanFrame>(frames.data(), kMaxMessagesPerDirection));
  n += ae.encode(a, std::span<CanFrame>(frames.data() + n, kMaxMessagesPerDirection));
  frames.resize(n);
  ASSERT_EQ(n, 10u);
  {
    CandumpWriter w;
    std::string error;
    ASSERT_TRUE(w.open(log.string(), "vcan0", {"gyrostab dbc test"}, error)) << error;
    for (const CanFrame& f : frames) ASSERT_TRUE(w.write(f, 1'000'000));
    ASSERT_TRUE(w.close(error)) << error;
  }

  const std::string cmd = std::string(GYROSTAB_SOURCE_DIR) + "/tools/can/candump-decode " + dbc.string() + " " +
                          log.string() + " 2>&1";
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::map<std::string, std::string> got;  // "MESSAGE.SIGNAL" → value
  char buf[512];
  std::string all;
  while (std::fgets(buf, sizeof buf, p) != nullptr) {
    all += buf;
    int line = 0;
    char message[64] = {}, signal[64] = {}, value[128] = {};
    if (std::sscanf(buf, "%d %63s %63s %127s", &line, message, signal, value) == 4)
      got[std::string(message) + "." + signal] = value;
  }
  ASSERT_EQ(::pclose(p), 0) << "candump-decode failed:\n" << all;

  std::size_t checked = 0;
  for (const CanFrame& f : frames) {
    const MessageSpec& m = kMessages[static_cast<std::size_t>(message_index(f.id))];
    for (const SignalSpec& sig : m.signals) {
      const std::string key = std::string(m.name) + "." + std::string(sig.name);
      const auto it = got.find(key);
      ASSERT_NE(it, got.end()) << key << " not decoded by canmatrix:\n" << all;
      EXPECT_TRUE(same_value(sig, expected_value(sig, f), it->second))
          << key << ": canmatrix " << it->second << ", map " << expected_value(sig, f);
      ++checked;
    }
  }
  EXPECT_EQ(checked, got.size());
  fs::remove_all(dir);
}

}  // namespace can_dbc_test
}  // namespace gyrostab::can
