// How the plant and controller processes (plant_process.hpp, controller_process.hpp) use their link, derived
// from the scene's loop and the request's transport options (run_role.hpp). Times in CLOCK_MONOTONIC ns.
//
// Lockstep (default): no clock; the plant waits for the actuator frame of tick k before it integrates tick k,
// the controller waits for the sensor frame of tick k. A wait ends at the receive timeout (the peer is lost),
// except the plant's wait for a command withheld by a controller that answered the tick before: after
// kMissingCommandFraction of the timeout that tick's drives get zero torque and the loop goes on;
// while waiting, the plant publishes the sensor frame again every kResendNs (a datagram lost on the way, or a
// controller that subscribed after the first publish), and the controller answers a repeated sensor frame
// with its cached actuator frame (at most once per kResendNs).
// Real time (--real-time): the plant is the clock master: tick k starts at epoch + k·T (clock_nanosleep,
// TIMER_ABSTIME), its command must arrive by epoch + k·T + kPlantWindow·T, else the drives get zero torque
// for that tick. The controller's deadline for the sensor frame of tick k is anchored on the plant's phase:
// t_anchor + (k − k_anchor)·T + kControllerWindow·T, with the anchor at the last frame it accepted (at the
// handshake: when its first command left, since that arrival is the plant's epoch); past it, it steps without
// a frame (the fault monitor holds, then trips). A frame that arrives after its tick was stepped as missing,
// at most kMaxResyncTicks late and newer than the anchor, moves the anchor to its arrival: the plant is the
// clock master, and a phase error beyond the window would otherwise make every later frame late as well.
// Tick 0 is a lockstep handshake in both modes (the epoch starts after it).
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

#include "hil/link/frame_transport.hpp"
#include "sim/random/seeded_rng.hpp"
#include "tools/run/run_role.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

inline constexpr std::int64_t kResendNs = 20'000'000;
inline constexpr double kPlantWindow = 0.75;
inline constexpr double kControllerWindow = 0.5;
// Lockstep: the share of the receive timeout the plant waits for a command that its controller, heard on the
// previous tick, withholds; then that tick's drives get zero torque and the loop goes on.
inline constexpr double kMissingCommandFraction = 0.5;
// Lockstep: a sensor frame may skip at most this many ticks ahead (the plant withheld frames); a frame
// further ahead is rejected as "ahead" (a forged or corrupted tick must not make the controller step a
// billion times).
inline constexpr std::int64_t kMaxAheadTicks = 1000;
// Real time: the controller follows a late frame's phase only this many ticks back (a forged old tick must
// not stall it for long).
inline constexpr std::int64_t kMaxResyncTicks = 10;
// The controller process as supervisor: a safe state tripped by the link alone (frames missing or stale) is
// acknowledged once this many frames in a row have been accepted again (10 ms at 1 kHz); the fault monitor
// then leaves it on the next good frame. A sensor fault (NaN, out of range, reported) stays latched.
inline constexpr std::int64_t kAcknowledgeAfterGoodFrames = 10;
// A link run whose controller spent more than this share of its ticks in the safe state, or that ended with the
// safe state latched (whatever the share), did not do its job: its verdict is "degraded", not "completed", and
// it exits kExitDegraded.
inline constexpr double kMaxSafeShare = 0.05;
inline constexpr int kExitDegraded = 8;
// Exit code of a process whose peer fell silent for the receive timeout (and of `run --transport lcm` when a
// process of the pair was lost).
inline constexpr int kExitPeerLost = 6;
// The run completed, but the link carried frames of another session, recorded frames or frames that failed
// authentication: none was acted on; the bus was shared, replayed onto or attacked (link.session.refused).
inline constexpr int kExitForeignFrames = 7;

struct LinkSettings {
  bool real_time{false};
  std::int64_t period_ns{1'000'000};
  std::int64_t timeout_ns{1'000'000'000};
  std::int64_t start_timeout_ns{10'000'000'000};
  std::int64_t spin_ns{0};
  std::int64_t resend_ns{kResendNs};
  std::int64_t jitter_max_ns{0};
  double jitter_probability{1.0};
};

inline LinkSettings link_settings(const LoopConfig& loop, const TransportOptions& t) {
  LinkSettings s;
  s.real_time = t.real_time;
  s.period_ns = loop.tick_ns;
  s.timeout_ns = std::max<std::int64_t>(1, t.timeout_ms) * 1'000'000;
  s.start_timeout_ns = std::max<std::int64_t>(1, t.start_timeout_ms) * 1'000'000;
  s.spin_ns = std::max<std::int64_t>(0, t.spin_us) * 1000;
  s.resend_ns = std::min(kResendNs, std::max<std::int64_t>(1'000'000, s.timeout_ns / 4));
  s.jitter_max_ns = static_cast<std::int64_t>(std::max(0.0, t.jitter_max_us) * 1000.0);
  s.jitter_probability = std::clamp(t.jitter_probability, 0.0, 1.0);
  return s;
}

// The LCM URLs of the two directions: sensor frames on --lcm-url, actuator frames on --lcm-actuator-url if
// given (a bus per direction), else on the same URL.
inline const std::string& sensor_url(const TransportOptions& t) {
  return t.lcm_url;
}
inline const std::string& actuator_url(const TransportOptions& t) {
  return t.lcm_actuator_url.empty() ? t.lcm_url : t.lcm_actuator_url;
}

// The channel names of a run: GYROSTAB_SENSOR<suffix>, GYROSTAB_ACTUATOR<suffix>.
inline std::string sensor_channel(const TransportOptions& t) {
  return std::string("GYROSTAB_SENSOR") + t.channel_suffix;
}
inline std::string actuator_channel(const TransportOptions& t) {
  return std::string("GYROSTAB_ACTUATOR") + t.channel_suffix;
}

// --jitter: before publishing, busy-wait a uniformly random 0..max on a `probability` fraction of the ticks
// (a compute overrun). Its own random stream of the scene seed, so a rerun injects the same delays.
class JitterInjector {
 public:
  static constexpr std::uint64_t kStream = 63;
  JitterInjector(const LinkSettings& s, std::uint64_t seed)
      : max_ns_(s.jitter_max_ns),
        probability_(s.jitter_probability),
        rng_(seed, s.jitter_max_ns > 0 ? kStream : 0) {}
  // The delay to inject this tick [ns] (0 most ticks when probability < 1).
  std::int64_t next() {
    if (max_ns_ <= 0) return 0;
    if (rng_.uniform() >= probability_) return 0;
    return static_cast<std::int64_t>(rng_.uniform() * static_cast<double>(max_ns_));
  }

 private:
  std::int64_t max_ns_;
  double probability_;
  random::SeededRng rng_;
};

}  // namespace gyrostab::tools
