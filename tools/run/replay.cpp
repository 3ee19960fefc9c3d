// Replay of a bus log into the firmware controller alone (Role::kReplay, `gyrostab replay LOG`): every
// recorded sensor frame, in order, goes to controller.step(tick, &frame, out), and `out` must equal the
// recorded actuator frame of the same tick byte for byte (memcmp of the whole ActuatorFrame). Nothing is
// excluded from the comparison: the controllers stamp time_ns = tick · tick_ns (controller_runtime.hpp),
// not a clock reading, so every field is deterministic; compute-time counters are not in the frame.
// The controller is the one the scene builds (the log's scene event, or --scene); no plant is built.
// As fast as possible, or paced at the scene's tick with --real-time.
// Exit codes: replay_session.hpp (0 identical, 4 mismatch, 5 truncated/corrupt log, 2 nothing replayed).
#include <cstdio>
#include <cstring>

#include "tools/log/frame_diff.hpp"
#include "tools/run/can_replay.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {

int replay_controller(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  std::unique_ptr<ControllerPort> ctl = scene.make_controller();
  ControllerPort& controller = *ctl;
  if (can::looks_like_candump_log(req.transport.replay_log)) return replay_controller_candump(controller, loop, req);
  ReplaySession session;
  int exit_code = 0;
  if (!session.open(loop, req, exit_code)) return exit_code;
  buslog::TickRecord t;
  msg::ActuatorFrame out{};
  std::int64_t ticks = 0;
  buslog::ReadStatus s;
  while ((s = session.next(t)) == buslog::ReadStatus::kOk) {
    controller.step(static_cast<std::uint64_t>(t.tick), &t.sensor, out);
    if (std::memcmp(&out, &t.actuator, sizeof out) != 0) {
      std::fprintf(stderr,
                   "gyrostab: %s: MISMATCH at tick %lld (actuator event at byte %lld; the %lld ticks before it are "
                   "identical): %s\n",
                   session.log_path().c_str(), static_cast<long long>(t.tick),
                   static_cast<long long>(t.actuator_offset), static_cast<long long>(ticks),
                   buslog::frame_differences(t.actuator, out).c_str());
      return kReplayExitMismatch;
    }
    ++ticks;
  }
  return session.finish(s, "actuator frame", ticks);
}

}  // namespace gyrostab::tools
