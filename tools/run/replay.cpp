// Replay of a bus log into the firmware controller alone (Role::kReplay, `gyrostab replay LOG`): every
// recorded sensor frame, in order, goes to controller.step(tick, &frame, out), and `out` must equal the
// recorded actuator frame of the same tick byte for byte (memcmp of the whole ActuatorFrame). Nothing is
// excluded from the comparison: the controllers stamp time_ns = tick · tick_ns (controller_runtime.hpp),
// not a clock reading, so every field is deterministic; compute-time counters are not in the frame.
// The controller is the one the scene builds (the log's scene event, or --scene); no plant is built.
// As fast as possible, or paced at the scene's tick with --real-time.
// With --target the controller is the device's firmware image on the emulated Cortex-M7
// (target_controller_port.hpp, docs/pil.md): the same frames, the same byte-for-byte comparison; exit 6 when
// the emulator is lost.
// Exit codes: replay_session.hpp (0 identical, 4 mismatch, 5 truncated/corrupt log, 2 nothing replayed).
#include <cstdio>
#include <cstring>
#include <memory>

#include "tools/devices/registry.hpp"
#include "tools/log/frame_diff.hpp"
#include "tools/run/can_replay.hpp"
#include "tools/run/replay_session.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/run/run_output.hpp"
#include "tools/run/target_controller_port.hpp"

namespace gyrostab::tools {

int replay_controller(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  std::unique_ptr<hil::TargetBus> bus;
  TargetControllerPort* target = nullptr;
  std::unique_ptr<ControllerPort> ctl;
  if (req.transport.transport == "target") {
    bus = std::make_unique<hil::TargetBus>();
    RunRequest target_req = req;
    nlohmann::json info;
    if (const int rc = open_target_link(scene, target_req, *bus, info); rc != 0) return rc;
    const LinkSettings s = link_settings(loop, target_req.transport);
    auto port = std::make_unique<TargetControllerPort>(*bus, s.timeout_ns, s.resend_ns);
    target = port.get();
    ctl = std::move(port);
  } else {
    ctl = scene.make_controller();
  }
  ControllerPort& controller = *ctl;
  if (can::looks_like_candump_log(req.transport.replay_log)) return replay_controller_candump(controller, loop, signals_of(scene), req);
  ReplaySession session;
  int exit_code = 0;
  if (!session.open(loop, req, exit_code)) return exit_code;
  buslog::TickRecord t;
  msg::AnyActuatorFrame out{};
  std::int64_t ticks = 0;
  buslog::ReadStatus s;
  while ((s = session.next(t)) == buslog::ReadStatus::kOk) {
    controller.step(static_cast<std::uint64_t>(t.tick), &t.sensor, out);
    if (target != nullptr && target->lost()) {
      std::fprintf(stderr, "gyrostab: %s: the target was lost at tick %lld (%s); the %lld ticks before it are identical\n",
                   session.log_path().c_str(), static_cast<long long>(t.tick), bus->peer_state().c_str(),
                   static_cast<long long>(ticks));
      bus->qemu.close();
      return kExitPeerLost;
    }
    if (std::memcmp(&out, &t.actuator, sizeof out) != 0) {
      std::fprintf(stderr,
                   "gyrostab: %s: MISMATCH at tick %lld (actuator event at byte %lld; the %lld ticks before it are "
                   "identical): %s\n",
                   session.log_path().c_str(), static_cast<long long>(t.tick),
                   static_cast<long long>(t.actuator_offset), static_cast<long long>(ticks),
                   buslog::frame_differences(t.actuator, out, signals_of(scene)).c_str());
      return kReplayExitMismatch;
    }
    ++ticks;
  }
  if (bus != nullptr) {
    hil::finish_target_session(*bus, hil::monotonic_ns() + link_settings(loop, req.transport).timeout_ns);
    if (bus->have_profile) {
      const firmware::PerfCounter& st = bus->profile.step;
      std::fprintf(stderr, "gyrostab: target %s: %llu ticks; controller step %lld-%lld instructions (mean %lld)\n",
                   bus->launch.device.c_str(), static_cast<unsigned long long>(bus->profile.ticks),
                   static_cast<long long>(st.min_ns), static_cast<long long>(st.max_ns),
                   static_cast<long long>(st.mean_ns()));
    }
  }
  return session.finish(s, "actuator frame", ticks);
}

}  // namespace gyrostab::tools
