// Which part of the loop this process runs (docs/architecture.md: the run modes) and how it reaches the other part.
//   kInProcess   plant + firmware in one program (the embedded default; tests and studies)
//   kPlant       the plant alone, exchanging frames with a controller process over a transport (LCM, CAN)
//   kController  the firmware controller alone, the other end of kPlant
//   kReplay      the controller alone, fed the sensor frames of a recorded bus log; checks every actuator frame
//   kResimulate  the plant alone, open loop, driven by the actuator frames of a recorded bus log
#pragma once

#include <cstdint>
#include <string>

#include "hil/target/target_faults.hpp"

namespace gyrostab::hil {
struct MemoryBus;
}

namespace gyrostab::tools {

enum class Role { kInProcess, kPlant, kController, kReplay, kResimulate };

// Fault injection on one side's published frames: ticks [from, from + count) (from < 0: none).
struct FrameFault {
  std::int64_t from{-1};
  std::int64_t count{0};
  bool covers(std::int64_t tick) const { return from >= 0 && tick >= from && tick < from + count; }
};

// Transport, pacing and log options (filled by the CLI; defaults = lockstep over the default LCM URL).
struct TransportOptions {
  std::string lcm_url{"udpm://239.255.76.67:7667?ttl=0"};
  std::string lcm_actuator_url;  // actuator frames on their own LCM URL (empty: lcm_url, one bus for both)
  std::string channel_suffix;  // appended to every channel name so that parallel runs don't mix
  bool real_time{false};       // pace by CLOCK_MONOTONIC deadlines instead of lockstep
  std::string log_path;        // record the bus as an LCM event log here (empty: no log)
  std::string replay_log;      // kReplay / kResimulate: the log to read
  bool replay_real_time{false};  // kReplay: feed frames at the scene's tick rate instead of as fast as possible
  bool replay_scene_override{false};  // kReplay / kResimulate: the scene came from --scene, not from the log
  // Plant / controller processes over LCM (tools/run/link_settings.hpp, docs/transport.md):
  std::string transport{"inproc"};    // `run`: inproc, or lcm (plant and controller as two child processes)
  std::int64_t timeout_ms{1000};      // receive timeout: the peer is declared lost after this long silent
  std::int64_t start_timeout_ms{10000};  // the same for the first frame (the peer may still be starting)
  std::int64_t spin_us{0};            // real time: spin this long before each deadline instead of sleeping
  int rt_priority{50};                // real time: SCHED_FIFO priority (0: do not ask)
  double jitter_max_us{0.0};          // --jitter: busy-wait up to this long before publishing (fault injection)
  double jitter_probability{1.0};     //   ... on this fraction of the ticks
  FrameFault sensor_drop, sensor_corrupt;      // plant: withhold / NaN-corrupt the sensor frames of these ticks
  FrameFault actuator_drop, actuator_corrupt;  // controller: the same for its actuator frames
  hil::MemoryBus* memory_bus{nullptr};  // tests: an in-process bus instead of LCM (hil/link/memory_bus.hpp)
  // CAN FD over SocketCAN (tools/run/can_link_setup.hpp, docs/can.md). `run --transport can` sets
  // can_if (default vcan0); for `plant` / `controller` a non-empty can_if selects CAN instead of LCM.
  std::string can_if;                 // interface (vcan0, can0); empty: not CAN
  std::string can_log;                // record the bus in candump's log format here (empty: no log)
  double can_bitrate{1e6};            // arbitration bit rate for the bus-load check [bit/s]
  double can_data_bitrate{5e6};       // CAN FD data-phase bit rate (bit-rate switch) [bit/s]
  bool can_filter{true};              // kernel filter on the ids this side receives (false: every frame, counted)
  double loss{0.0};                   // fault injection: each frame sent is lost with this probability [-]
  // Sessions and authentication (tools/run/link_identity.hpp, docs/transport.md):
  std::string key_file;               // the link key: every frame carries a MAC (empty: session binding only)
  std::uint64_t session{0};           // the session both ends use (0: the plant draws one, the controller binds)
  std::uint64_t controller_id{0};     // the controller's sender id, known to both ends (0: the controller draws
                                      // one, the plant binds to it at the handshake)
  // Processor in the loop (`run --transport target`, tools/run/target_link_setup.hpp, docs/pil.md):
  std::string target_image;           // the controller image (empty: the build's image of the scene's device)
  std::string target_link{"fifo"};    // fifo (semihosting, fast) or uart (the board's UART0)
  std::string target_core{"m7"};      // m7 (Cortex-M7, FPv5-D16) or m4f (Cortex-M4F: double in software)
  std::string qemu{"qemu-system-arm"};  // the emulator
  hil::TargetFaults target_faults;    // --target-fault
};

}  // namespace gyrostab::tools
