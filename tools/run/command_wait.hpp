// The plant process's wait for the actuator frame of tick k (tools/run/plant_process.cpp): every frame that
// arrives is checked — decodable (the endpoint), finite and within the scene's limits
// (hil/link/actuator_frame_check.hpp), for the expected tick with an advancing sequence (FrameOrder) — and
// counted when rejected. Lockstep: the sensor frame is published again every resend interval while waiting;
// a frame for this tick rejected for its content is followed by a grace of one resend interval for a good one.
// Returns kAccepted (`cmd` holds it), kMissing (deadline or grace over), kLost (receive timeout), kStopped
// (SIGINT/SIGTERM) or kError (the transport failed).
#pragma once

#include <algorithm>
#include <cstdint>

#include "hil/link/actuator_frame_check.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/source_watch.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/link_settings.hpp"

namespace gyrostab::tools {

enum class CommandWait { kAccepted, kMissing, kLost, kStopped, kError };

// Waits for the actuator frame of tick k (see the header for the rules). `cmd` receives it on kAccepted.
// `watch` sees every frame of the bound controller (a second source speaking as it: source_watch.hpp).
template <class Transport>
CommandWait wait_for_command(hil::FrameEndpoint<Transport>& ep, hil::FrameOrder& order,
                             const hil::ActuatorLimits& limits, const msg::DeviceSignals& signals, std::int64_t k,
                             std::int64_t deadline_ns, bool lockstep, std::int64_t lost_at_ns, const LinkSettings& s,
                             msg::AnyActuatorFrame& cmd, hil::SourceWatch& watch) {
  hil::LinkCounters& c = ep.counters();
  std::int64_t next_resend = lockstep ? hil::monotonic_ns() + s.resend_ns : hil::kNoDeadline;
  std::int64_t grace_until = hil::kNoDeadline;
  const auto tick = static_cast<std::uint64_t>(k);
  for (;;) {
    const std::int64_t until = std::min({deadline_ns, lost_at_ns, next_resend, grace_until});
    msg::AnyActuatorFrame f{};
    const hil::RxStatus r = ep.receive(until, f);
    if (r == hil::RxStatus::kError) return CommandWait::kError;
    if (stop_signal_received() != 0) return CommandWait::kStopped;
    if (r != hil::RxStatus::kMessage) {
      const std::int64_t now = hil::monotonic_ns();
      if (now >= lost_at_ns) return CommandWait::kLost;
      if (now >= deadline_ns || now >= grace_until) return CommandWait::kMissing;
      if (now >= next_resend) {
        ep.resend();
        next_resend = now + s.resend_ns;
      }
      continue;
    }
    const bool from_peer = ep.guard().bound();
    const std::uint64_t content = from_peer ? hil::frame_content_hash(f, signals.commands.size()) : 0;
    const hil::ActuatorVerdict v = hil::check_actuator_values(f, signals, limits);
    if (v != hil::ActuatorVerdict::kOk) {
      if (from_peer) watch.refused(f.tick, content, f.tick < tick);
      if (v == hil::ActuatorVerdict::kNonFinite) ++c.rejected_non_finite;
      else ++c.rejected_out_of_range;
      // The controller answered this tick with a command no drive may apply: no resend will change that.
      if (lockstep && f.tick == tick && grace_until == hil::kNoDeadline) {
        grace_until = hil::monotonic_ns() + s.resend_ns;
        next_resend = hil::kNoDeadline;
      }
      continue;
    }
    const hil::OrderVerdict o = order.classify(f.tick, f.sequence, tick);
    if (o != hil::OrderVerdict::kExpected) {
      hil::count_order_rejection(o, c);
      if (from_peer) watch.refused(f.tick, content, o == hil::OrderVerdict::kStale && f.tick < tick);
      continue;
    }
    order.accept(f.tick, f.sequence);
    watch.accepted(f.tick, from_peer ? content : hil::frame_content_hash(f, signals.commands.size()));
    ++c.accepted;
    cmd = f;
    return CommandWait::kAccepted;
  }
}

}  // namespace gyrostab::tools
