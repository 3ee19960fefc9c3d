// Which part of the loop this process runs (DESIGN §2 modes) and how it reaches the other part.
//   kInProcess   plant + firmware in one program (the embedded default; tests and studies)
//   kPlant       the plant alone, exchanging frames with a controller process over a transport (LCM, CAN)
//   kController  the firmware controller alone, the other end of kPlant
//   kReplay      the controller alone, fed the sensor frames of a recorded bus log; checks every actuator frame
//   kResimulate  the plant alone, open loop, driven by the actuator frames of a recorded bus log
#pragma once

#include <cstdint>
#include <string>

namespace gyrostab::tools {

enum class Role { kInProcess, kPlant, kController, kReplay, kResimulate };

// Transport, pacing and log options (filled by the CLI; defaults = lockstep over the default LCM URL).
struct TransportOptions {
  std::string lcm_url{"udpm://239.255.76.67:7667?ttl=0"};
  std::string channel_suffix;  // appended to every channel name so that parallel runs don't mix
  bool real_time{false};       // pace by CLOCK_MONOTONIC deadlines instead of lockstep
  std::string log_path;        // record the bus as an LCM event log here (empty: no log)
  std::string replay_log;      // kReplay / kResimulate: the log to read
  bool replay_real_time{false};  // kReplay: feed frames at the scene's tick rate instead of as fast as possible
};

}  // namespace gyrostab::tools
