// The DBC file of a device's bus (hil/can/dbc_writer.hpp) says what its map says, for the bus of every shipped
// device, every map whole and the tests' own device:
//   1. parsed back here (a small reader of the DBC lines we write: BU_, BO_, SG_, SIG_VALTYPE_,
//      BA_ VFrameFormat), every message on the bus and each of its signals matches the map field by field,
//      doubles exactly (%.17g round-trips), and no other message is in the file;
//   2. an independent DBC reader, canmatrix (python3-canmatrix, installed by tools/setup), loads the file and
//      decodes a candump log of encoder output (tools/can/candump-decode) into exactly the values the frames
//      were encoded from — "common CAN tools decode the bus".
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

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hil/can/bus_nodes.hpp"
#include "hil/can/candump_log.hpp"
#include "hil/can/dbc_writer.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/frame_map.hpp"
#include "sim/random/seeded_rng.hpp"
#include "tests/unit/can_test_maps.hpp"
#include "tools/devices/registry.hpp"
#include "tools/run/can_link_setup.hpp"

extern char** environ;

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

std::map<std::uint32_t, DbcMessage> parse_dbc(const std::string& text, std::string* nodes = nullptr) {
  std::map<std::uint32_t, DbcMessage> msgs;
  std::istringstream in(text);
  std::string line;
  DbcMessage* current = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("BU_:", 0) == 0 && nodes != nullptr) {
      *nodes = line.substr(4);
    } else if (line.rfind("BO_ ", 0) == 0) {
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

// The buses a DBC file is written for: every map whole (every shipped device's, the tests' own devices); each
// distinct bus once.
std::vector<testing::TestBus> dbc_buses() {
  std::vector<testing::TestBus> out;
  const auto add = [&](const DeviceBus& b, const std::string& label) {
    for (const testing::TestBus& o : out)
      if (o.bus.map == b.map) return;
    out.push_back({b, label});
  };
  for (const CanMap* m : testing::test_can_maps()) add(whole_bus(*m), std::string(m->device));
  for (const tools::DeviceDescriptor* d : tools::devices()) add(tools::can_bus_of(d->name), std::string(d->name));
  return out;
}

TEST(CanDbc, ParsesBackToEveryBusMap) {
  for (const testing::TestBus& b : dbc_buses()) {
    SCOPED_TRACE(b.label);
    const std::string text = dbc_text(b.bus);
    EXPECT_NE(text.find("BA_ \"BusType\" \"CAN FD\";"), std::string::npos);
    std::string nodes;
    const auto msgs = parse_dbc(text, &nodes);
    std::string want_nodes;
    for (std::string_view n : bus_nodes(b.bus)) want_nodes += " " + std::string(n);
    EXPECT_EQ(nodes, want_nodes);
    ASSERT_EQ(msgs.size(), b.bus.frames(Direction::kSensor) + b.bus.frames(Direction::kActuator));
    std::string command_nodes;
    for (std::string_view n : command_receivers(b.bus)) command_nodes += (command_nodes.empty() ? "" : ",") + std::string(n);
    for (std::size_t i = 0; i < b.bus.messages().size(); ++i) {
      const MessageSpec& m = b.bus.messages()[i];
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
                                : m.node != "controller"          ? std::string(m.node)
                                : command_nodes.empty()           ? "Vector__XXX"
                                                                  : command_nodes)
            << s.name;
      }
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

// Runs argv with standard output and error into `out_path`; the exit status (-1 if it could not run).
int run_to_file(const std::vector<std::string>& argv, const std::string& out_path) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CanDbc, CanmatrixDecodesEncoderOutputExactlyOnEveryBus) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("gyrostab_can_dbc_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  random::SeededRng rng(2026, 3);
  for (const testing::TestBus& b : dbc_buses()) {
    SCOPED_TRACE(b.label);
    const fs::path dbc = dir / "bus.dbc";
    const fs::path log = dir / "bus.candump";
    const fs::path decoded = dir / "decoded.txt";
    std::ofstream(dbc) << dbc_text(b.bus);

    std::vector<CanFrame> frames(2 * kMaxMessagesPerDirection);
    FrameEncoder se(b.bus, Direction::kSensor), ae(b.bus, Direction::kActuator);
    std::size_t n = 0;
    for (std::uint64_t tick : {0x1'0000'0123ull, 77ull}) {
      n += se.encode(testing::random_sensor(b.bus, tick, rng),
                     std::span<CanFrame>(frames.data() + n, kMaxMessagesPerDirection));
      n += ae.encode(testing::random_actuator(b.bus, tick, rng),
                     std::span<CanFrame>(frames.data() + n, kMaxMessagesPerDirection));
      if (frames.size() < n + 2 * kMaxMessagesPerDirection) frames.resize(n + 2 * kMaxMessagesPerDirection);
    }
    frames.resize(n);
    ASSERT_EQ(n, 2 * (b.bus.frames(Direction::kSensor) + b.bus.frames(Direction::kActuator)));
    {
      CandumpWriter w;
      std::string error;
      ASSERT_TRUE(w.open(log.string(), "vcan0", {"gyrostab dbc test"}, error)) << error;
      for (const CanFrame& f : frames) ASSERT_TRUE(w.write(f, 1'000'000));
      ASSERT_TRUE(w.close(error)) << error;
    }
    const int rc = run_to_file({std::string(GYROSTAB_SOURCE_DIR) + "/tools/can/candump-decode", dbc.string(),
                                log.string()},
                               decoded.string());
    std::ifstream in(decoded);
    std::stringstream all_text;
    all_text << in.rdbuf();
    const std::string all = all_text.str();
    ASSERT_EQ(rc, 0) << "candump-decode failed:\n" << all;
    std::map<std::string, std::string> got;  // "LINE MESSAGE.SIGNAL" → value
    std::istringstream lines(all);
    std::string line_text;
    while (std::getline(lines, line_text)) {
      int line = 0;
      char message[64] = {}, signal[64] = {}, value[128] = {};
      if (std::sscanf(line_text.c_str(), "%d %63s %63s %127s", &line, message, signal, value) == 4)
        got[std::to_string(line) + " " + message + "." + signal] = value;
    }
    std::size_t checked = 0;
    for (std::size_t k = 0; k < frames.size(); ++k) {
      const CanFrame& f = frames[k];
      const MessageSpec& m = b.bus.messages()[static_cast<std::size_t>(b.bus.index_of(f.id))];
      for (const SignalSpec& sig : m.signals) {
        // The log's first line is the header comment: frame k is on line k + 2.
        const std::string key = std::to_string(k + 2) + " " + std::string(m.name) + "." + std::string(sig.name);
        const auto it = got.find(key);
        ASSERT_NE(it, got.end()) << key << " not decoded by canmatrix:\n" << all;
        EXPECT_TRUE(same_value(sig, expected_value(sig, f), it->second))
            << key << ": canmatrix " << it->second << ", map " << expected_value(sig, f);
        ++checked;
      }
    }
    EXPECT_EQ(checked, got.size());
  }
  fs::remove_all(dir);
}

}  // namespace can_dbc_test
}  // namespace gyrostab::can
