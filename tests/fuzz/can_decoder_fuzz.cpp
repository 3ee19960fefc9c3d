// libFuzzer target for the CAN decoders (hil/can/): arbitrary bytes as
//   1. a stream of received frames, into the set assemblers of both directions of the bus named by the first
//      byte: its high bits pick a map of the build (gyrostab_signals/all_can_maps.hpp) (record: flags, id low,
//      id high, len, then len data bytes — len is taken modulo 65 and may disagree with the frame kind, as a
//      hostile bus could make it);
//   2. candump log text, line by line, through parse_candump_line, and every parsed frame into the assemblers.
// Invariants beyond "no crash, no sanitizer report": every frame is either accepted or rejected with one
// cause (frames = accepted + rejections), a completed set can be taken exactly once, and its tick agrees with
// the tick tag of the frames that completed it. A completed set is also judged by the link envelope
// (hil/can/link_seal.hpp): under a key the input does not know it never passes (it would be a forgery), and
// without one a set that passes names a live session and sender (never 0). Built with -DGYROSTAB_FUZZ=ON (clang);
// run with tools/fuzz/run-can-fuzz.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <span>
#include <string_view>

#include "gyrostab_signals/all_can_maps.hpp"
#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/link_seal.hpp"

namespace {

using gyrostab::can::CanFrame;
using gyrostab::can::DeviceBus;
using gyrostab::can::Direction;
using gyrostab::can::FrameError;
using gyrostab::can::SetAssembler;

void judge_envelope(const SetAssembler& rx) {
  std::array<CanFrame, gyrostab::can::kMaxMessagesPerDirection> set{};
  const std::size_t n = rx.ready_frames(set);
  if (n == 0) __builtin_trap();
  const std::span<const CanFrame> frames(set.data(), n);
  gyrostab::firmware::link::Key128 secret;
  for (std::size_t i = 0; i < secret.bytes.size(); ++i) secret.bytes[i] = static_cast<std::uint8_t>(0x6b ^ (i * 53));
  gyrostab::hil::LinkGuard keyed(gyrostab::can::can_guard_config(gyrostab::hil::GuardConfig{7, 0, 0, 0, secret, 1, 2}));
  gyrostab::hil::LinkEnvelope e;
  if (gyrostab::can::open(frames, keyed, e) == gyrostab::hil::GuardVerdict::kOk) __builtin_trap();
  gyrostab::hil::LinkGuard plain(gyrostab::can::can_guard_config(gyrostab::hil::GuardConfig{7, 0, 0, 0, std::nullopt, 1, 2}));
  if (gyrostab::can::open(frames, plain, e) == gyrostab::hil::GuardVerdict::kOk && (e.session == 0 || e.sender == 0))
    __builtin_trap();
}

void check(SetAssembler& rx, const CanFrame& f) {
  const FrameError e = rx.accept(f);
  const auto& c = rx.counters();
  if (c.frames != c.accepted + c.rejected_total()) __builtin_trap();
  if (e != FrameError::kNone && c.last_error != e) __builtin_trap();
  if (rx.ready()) {
    judge_envelope(rx);
    const std::uint64_t tick = rx.ready_tick();
    if (e == FrameError::kNone) {
      const auto tag = static_cast<std::uint16_t>(f.data[2] | (f.data[3] << 8));
      if (static_cast<std::uint16_t>(tick & 0xFFFFu) != tag) __builtin_trap();
    }
    bool taken = false;
    if (rx.direction() == Direction::kSensor) {
      gyrostab::msg::AnySensorFrame s{};
      taken = rx.take(s);
      if (taken && s.tick != tick) __builtin_trap();
    } else {
      gyrostab::msg::AnyActuatorFrame a{};
      taken = rx.take(a);
      if (taken && a.tick != tick) __builtin_trap();
    }
    if (!taken || rx.ready()) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  constexpr std::size_t kMaps = std::size(gyrostab::can::kAllCanMaps);
  const gyrostab::can::CanMap& map = *gyrostab::can::kAllCanMaps[(data[0] >> 4) % kMaps];
  const DeviceBus bus = gyrostab::can::whole_bus(map);
  SetAssembler sensor(bus, Direction::kSensor);
  SetAssembler actuator(bus, Direction::kActuator);

  // 1. Binary frame stream.
  std::size_t i = 1;
  while (i + 4 <= size) {
    CanFrame f{};
    f.flags = data[i];
    f.id = static_cast<std::uint32_t>(data[i + 1] | (data[i + 2] << 8)) & 0x7FFu;
    f.len = static_cast<std::uint8_t>(data[i + 3] % 65);
    i += 4;
    const std::size_t n = f.len < size - i ? f.len : size - i;
    std::memcpy(f.data, data + i, n);
    i += n;
    check(sensor, f);
    check(actuator, f);
  }

  // 2. The same bytes as candump text.
  SetAssembler sensor2(bus, Direction::kSensor);
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    CanFrame f{};
    std::string_view ifname;
    const auto r = gyrostab::can::parse_candump_line(text.substr(start, end - start), f, ifname);
    if (r == gyrostab::can::CandumpParse::kFrame) {
      if (ifname.empty() || ifname.size() > 15) __builtin_trap();
      if (f.len > (f.fd() ? 64 : 8)) __builtin_trap();
      check(sensor2, f);
      // What parses must format and parse back to the same frame.
      char buf[gyrostab::can::kMaxCandumpLine];
      const std::size_t n = gyrostab::can::format_candump_line(f, ifname, f.time_ns, buf, sizeof buf);
      if (n == 0) __builtin_trap();
      CanFrame g{};
      std::string_view ifname2;
      if (gyrostab::can::parse_candump_line(std::string_view(buf, n), g, ifname2) != gyrostab::can::CandumpParse::kFrame)
        __builtin_trap();
      if (g.id != f.id || g.len != f.len || g.flags != f.flags || std::memcmp(g.data, f.data, f.len) != 0 ||
          g.time_ns != f.time_ns || ifname2 != ifname)
        __builtin_trap();
    }
    start = end + 1;
  }
  return 0;
}
