// `gyrostab replay LOG` for a candump log of the CAN bus (`--can-log`, or candump itself): the controller the
// scene builds is fed the recorded sensor frames and every CAN frame it would send is compared with the
// recorded one, bit for bit — identifier, length, FD flags and all data bytes, CRC and alive counter
// included. The replay runs the same decoder as the controller process (hil/can/frame_codec.hpp) and mirrors
// the lockstep protocol: a sensor set repeated for the tick just stepped (a plant resend) is not stepped
// again, and a recorded command set repeated for a tick (the controller's resend) is matched by encoding the
// last command again, with the next alive counters, as the controller did.
// Frames the decoder rejects (a flood, bad frames of a fault test) are counted and skipped, as the controller
// skipped them; a rejected frame where the controller's own frame is due is a mismatch.
// The scene: --scene, or the one in the log's header (`# scene-toml-base64` lines, written by --can-log).
// The frames are decoded with the CAN map of the scene's device (tools/signals/device_can_map.hpp); a log whose
// header names another map (`# can-map TABLE FINGERPRINT`) or log version is refused, since its identifiers
// and positions would mean something else.
// Exit codes as for LCM logs (replay_session.hpp): 0 identical, 4 mismatch (line and fields printed),
// 5 the log is unreadable past a line, or ends before the controller's answer to its last sensor set, or its
// header disagrees with the scene or names another map, 2 nothing replayed.
#pragma once

#include <time.h>

#include <array>
#include <cstdio>
#include <cstring>
#include <deque>
#include <string>

#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "tools/log/frame_diff.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

// The value of a "# key value" header line of a candump log ("" if absent).
inline std::string candump_header(const can::CandumpFile& f, const std::string& key) {
  for (const std::string& c : f.comments)
    if (c.size() > key.size() && c.compare(0, key.size(), key) == 0 && c[key.size()] == ' ') return c.substr(key.size() + 1);
  return "";
}

inline std::string base64_decode(const std::string& in) {
  std::string out;
  unsigned v = 0;
  int bits = 0;
  for (char c : in) {
    int d = -1;
    if (c >= 'A' && c <= 'Z') d = c - 'A';
    else if (c >= 'a' && c <= 'z') d = c - 'a' + 26;
    else if (c >= '0' && c <= '9') d = c - '0' + 52;
    else if (c == '+') d = 62;
    else if (c == '/') d = 63;
    else continue;  // '=' padding, whitespace
    v = (v << 6) | static_cast<unsigned>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((v >> bits) & 0xFFu);
    }
  }
  return out;
}

// The scene text carried by a gyrostab candump log ("" if it has none).
inline std::string candump_scene_text(const can::CandumpFile& f) {
  std::string b64;
  const std::string key = "scene-toml-base64 ";
  for (const std::string& c : f.comments)
    if (c.compare(0, key.size(), key) == 0) b64 += c.substr(key.size());
  return base64_decode(b64);
}

inline std::string describe_can_frame(const can::CanFrame& f) {
  char line[can::kMaxCandumpLine];
  const std::size_t n = can::format_candump_line(f, "-", 0, line, sizeof line);
  // Drop "(0000000000.000000) - " and the newline.
  const std::string s(line, n);
  const std::size_t at = s.find(") - ");
  return at == std::string::npos ? s : s.substr(at + 4, s.size() - at - 5);
}

// Exit codes as for LCM logs (replay_session.hpp).
int replay_controller_candump(ControllerPort& controller, const LoopConfig& loop, const msg::DeviceSignals& signals,
                              const RunRequest& req);

}  // namespace gyrostab::tools
