// Command-line options of the plant / controller processes (docs/transport.md) for `gyrostab run`,
// `gyrostab plant` and `gyrostab controller`. Header-only: only tools/gyrostab_main.cpp includes it.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>
#include <vector>

#include "tools/run/link_identity.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

enum class LinkSide { kRun, kPlant, kController };

// "TICK:COUNT" → FrameFault; "" if well formed, else the problem.
inline std::string parse_frame_fault(const std::string& text, FrameFault& f) {
  const auto colon = text.find(':');
  char* end = nullptr;
  const long long from = std::strtoll(text.c_str(), &end, 10);
  if (colon == std::string::npos || colon == 0 || end != text.c_str() + colon || from < 0) {
    return "expected TICK:COUNT, e.g. 500:3";
  }
  const long long count = std::strtoll(text.c_str() + colon + 1, &end, 10);
  if (*end != '\0' || count < 1) return "expected TICK:COUNT with COUNT >= 1";
  f.from = from;
  f.count = count;
  return "";
}

// "MAX_US" or "MAX_US@PROBABILITY" → jitter.
inline std::string parse_jitter(const std::string& text, TransportOptions& t) {
  const auto at = text.find('@');
  char* end = nullptr;
  const double max_us = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || max_us < 0 ||
      (at == std::string::npos ? *end != '\0' : end != text.c_str() + at)) {
    return "expected MAX_US or MAX_US@PROBABILITY, e.g. 300 or 2000@0.01";
  }
  double p = 1.0;
  if (at != std::string::npos) {
    p = std::strtod(text.c_str() + at + 1, &end);
    if (*end != '\0' || !(p > 0.0 && p <= 1.0)) return "the probability after @ must be in (0, 1]";
  }
  t.jitter_max_us = max_us;
  t.jitter_probability = p;
  return "";
}

// --target-fault KIND[:TICK[:COUNT]] (link_cli.hpp's help text lists the kinds).
inline std::string parse_target_fault(const std::string& text, hil::TargetFaults& f) {
  const std::size_t c1 = text.find(':');
  const std::string kind = text.substr(0, c1);
  if (kind == "config") {
    if (c1 != std::string::npos) return "config takes no tick";
    f.bad_config = true;
    return "";
  }
  if (c1 == std::string::npos) return "expected KIND:TICK[:COUNT] or config";
  const std::size_t c2 = text.find(':', c1 + 1);
  char* end = nullptr;
  const std::string tick_text = text.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
  const long long tick = std::strtoll(tick_text.c_str(), &end, 10);
  if (tick_text.empty() || *end != '\0' || tick < 0) return "TICK must be an integer >= 0";
  long long count = 1;
  if (c2 != std::string::npos) {
    const std::string count_text = text.substr(c2 + 1);
    count = std::strtoll(count_text.c_str(), &end, 10);
    if (count_text.empty() || *end != '\0' || count < 1) return "COUNT must be an integer >= 1";
  }
  if (kind == "corrupt") {
    f.corrupt_from = tick;
    f.corrupt_count = count;
  } else if (kind == "stale") {
    f.stale_from = tick;
    f.stale_count = count;
  } else if (kind == "skip") {
    f.skip_from = tick;
    f.skip_count = count;
  } else if (kind == "freeze" && c2 == std::string::npos) {
    f.freeze_at = tick;
  } else if (kind == "kill" && c2 == std::string::npos) {
    f.kill_at = tick;
  } else {
    return "unknown kind '" + kind + "' (corrupt, stale, skip take TICK:COUNT; freeze, kill take TICK; config)";
  }
  return "";
}

inline void add_link_options(CLI::App* cmd, RunRequest& req, LinkSide side) {
  TransportOptions& t = req.transport;
  if (side == LinkSide::kRun) {
    cmd->add_option(
           "--transport", t.transport,
           "inproc (default): plant and firmware in this process; lcm: plant and controller as two child "
           "processes over LCM, one report; can: the same over CAN FD (SocketCAN, --can-if); target: the "
           "device's firmware image on an emulated Cortex-M7 (QEMU), the plant here, in lockstep (docs/pil.md)")
        ->check(CLI::IsMember({"inproc", "lcm", "can", "target"}));
    cmd->add_option("--target-image", t.target_image,
                    "--transport target: run this controller image (default: the build's image of the scene's "
                    "device)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--target-link", t.target_link,
                    "--transport target: fifo (semihosting on two FIFOs, the fast lockstep channel; default) or "
                    "uart (the board's CMSDK UART0: a few hundred ticks per second in QEMU)")
        ->check(CLI::IsMember({"fifo", "uart"}));
    cmd->add_option("--target-core", t.target_core,
                    "--transport target: m7 (Cortex-M7 with the double-precision FPU, QEMU mps2-an500; default) "
                    "or m4f (the Cortex-M4F build, single-precision FPU, double in software; mps2-an386)")
        ->check(CLI::IsMember({"m7", "m4f"}));
    cmd->add_option("--qemu", t.qemu, "--transport target: the emulator (default qemu-system-arm)");
    cmd->add_option_function<std::vector<std::string>>(
        "--target-fault",
        [&t](const std::vector<std::string>& all) {
          for (const std::string& v : all) {
            if (const std::string e = parse_target_fault(v, t.target_faults); !e.empty()) {
              throw CLI::ValidationError("--target-fault", e);
            }
          }
        },
        "--transport target, fault injection (repeatable): corrupt:TICK:COUNT, stale:TICK:COUNT, "
        "skip:TICK:COUNT (a changed byte, a repeated frame, a skipped alive counter on the sensor frames of "
        "those ticks), freeze:TICK, kill:TICK (stop or kill the emulator), config (a configuration the "
        "controller must refuse)");
  }
  // CAN FD over SocketCAN (docs/can.md). For plant / controller, --can-if selects CAN instead of
  // LCM.
  cmd->add_option("--can-if", t.can_if,
                  side == LinkSide::kRun
                      ? "CAN interface for --transport can (default vcan0)"
                      : "talk CAN FD on this SocketCAN interface (vcan0, can0) instead of LCM");
  cmd->add_option(
      "--can-log", t.can_log,
      "record the CAN bus in candump's log format (canplayer replays it; gyrostab replay checks it)");
  cmd->add_option("--can-bitrate", t.can_bitrate,
                  "CAN arbitration bit rate for the bus-load check (default 1e6)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--can-data-bitrate", t.can_data_bitrate,
                  "CAN FD data-phase bit rate for the bus-load check (default 5e6)")
      ->check(CLI::PositiveNumber);
  cmd->add_flag(
      "!--can-no-filter", t.can_filter,
      "receive every frame on the interface (no kernel id filter): unknown ids are counted, not dropped");
  cmd->add_option("--key-file", t.key_file,
                  "authenticate every frame with this 128-bit key (32 hexadecimal digits, mode 600): frames "
                  "without its MAC are refused (docs/transport.md)")
      ->check(CLI::ExistingFile);
  if (side != LinkSide::kRun) {
    cmd->add_option_function<std::string>(
           "--session",
           [&t](const std::string& v) {
             if (!parse_link_id(v, t.session)) throw CLI::ValidationError("--session", "an id in [1, 2^32): " + v);
           },
           "the link's session id (0x... or decimal; default: the plant draws one, the controller binds to "
           "the plant of its first handshake)")
        ->group("Session");
    cmd->add_option_function<std::string>(
           "--controller-id",
           [&t](const std::string& v) {
             if (!parse_link_id(v, t.controller_id))
               throw CLI::ValidationError("--controller-id", "an id in [1, 2^32): " + v);
           },
           "the controller's sender id (0x... or decimal): the controller sends with it, the plant accepts no "
           "other (default: the controller draws one, the plant binds to it at the handshake)")
        ->group("Session");
  }
  cmd->add_option("--ticks", req.ticks,
                  "run exactly this many ticks instead of the scene's duration (a controller: stop after this many "
                  "ticks; by default it runs until the plant's end-of-run frame)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--lcm-url", t.lcm_url, "LCM provider URL (default udpm://239.255.76.67:7667?ttl=0)");
  cmd->add_option("--lcm-actuator-url", t.lcm_actuator_url,
                  "carry the actuator frames on this LCM URL instead (a bus per direction, e.g. "
                  "udpm://239.255.76.67:7668?ttl=0: no process receives its own datagrams; faster lockstep)");
  cmd->add_option(
      "--channel-suffix", t.channel_suffix,
      "appended to the channel names GYROSTAB_SENSOR / GYROSTAB_ACTUATOR so parallel runs don't mix "
      "(run --transport lcm picks _<pid> if not given)");
  cmd->add_flag(
      "--real-time", t.real_time,
      "pace by CLOCK_MONOTONIC deadlines at the scene's tick (SCHED_FIFO + mlockall when permitted) "
      "instead of lockstep");
  cmd->add_option("--spin-us", t.spin_us,
                  "real time: spin this long before each deadline instead of sleeping")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--rt-priority", t.rt_priority,
                  "real time: SCHED_FIFO priority, 0 = don't ask (default 50)")
      ->check(CLI::Range(0, 99));
  cmd->add_option("--timeout-ms", t.timeout_ms,
                  "receive timeout: the peer is declared lost after this long without a frame (default 1000)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--start-timeout-ms", t.start_timeout_ms,
                  "receive timeout for the first frame (default 10000)")
      ->check(CLI::PositiveNumber);
  const char* jitter_help =
      side == LinkSide::kRun
          ? "fault injection in the controller process: busy-wait up to MAX_US before each "
            "publish, on a PROBABILITY fraction of the ticks (MAX_US[@PROBABILITY])"
          : "fault injection: busy-wait up to MAX_US before each publish, on a PROBABILITY "
            "fraction of the ticks (MAX_US[@PROBABILITY])";
  cmd->add_option_function<std::string>(
      "--jitter",
      [&t](const std::string& v) {
        if (const std::string e = parse_jitter(v, t); !e.empty()) throw CLI::ValidationError("--jitter", e);
      },
      jitter_help);
  const auto fault_option = [cmd](const char* name, FrameFault& f, const char* help) {
    cmd->add_option_function<std::string>(
        name,
        [&f, name](const std::string& v) {
          if (const std::string e = parse_frame_fault(v, f); !e.empty()) throw CLI::ValidationError(name, e);
        },
        help);
  };
  cmd->add_option("--loss", t.loss,
                  "fault injection: each frame this side sends (with run: both sides) is lost on the way with "
                  "this probability, from a seeded stream")
      ->check(CLI::Range(0.0, 0.9));
  if (side != LinkSide::kController) {
    fault_option("--drop-sensor", t.sensor_drop,
                 "fault injection: the plant withholds the sensor frames of TICK:COUNT");
    fault_option("--corrupt-sensor", t.sensor_corrupt,
                 "fault injection: the plant sends the sensor frames of TICK:COUNT with a NaN carrier angle");
  }
  if (side != LinkSide::kPlant) {
    fault_option("--drop-actuator", t.actuator_drop,
                 "fault injection: the controller withholds the actuator frames of TICK:COUNT");
    fault_option("--corrupt-actuator", t.actuator_corrupt,
                 "fault injection: the controller sends the actuator frames of TICK:COUNT with a NaN torque");
  }
}

// The options that only make sense with two processes: refused with --transport inproc.
inline std::string check_inproc_options(const RunRequest& req) {
  const TransportOptions& t = req.transport;
  if (t.transport != "inproc") return "";
  const TransportOptions d;
  if (t.real_time || t.jitter_max_us > 0 || t.loss > 0 || t.sensor_drop.from >= 0 || t.sensor_corrupt.from >= 0 ||
      t.actuator_drop.from >= 0 || t.actuator_corrupt.from >= 0 || t.lcm_url != d.lcm_url ||
      !t.lcm_actuator_url.empty() || !t.channel_suffix.empty() || t.spin_us != d.spin_us ||
      t.timeout_ms != d.timeout_ms || t.start_timeout_ms != d.start_timeout_ms ||
      t.rt_priority != d.rt_priority) {
    return "--real-time, --jitter, --lcm-url, --channel-suffix, --spin-us, --rt-priority, timeouts and the "
           "fault "
           "injections need --transport lcm";
  }
  if (!t.can_if.empty() || !t.can_log.empty() || t.can_bitrate != d.can_bitrate ||
      t.can_data_bitrate != d.can_data_bitrate || t.can_filter != d.can_filter) {
    return "--can-if, --can-log, --can-bitrate, --can-data-bitrate and --can-no-filter need --transport can";
  }
  return "";
}

}  // namespace gyrostab::tools
