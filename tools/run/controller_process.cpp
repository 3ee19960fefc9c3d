// The firmware controller as its own process (Role::kController, `gyrostab controller SCENE`): per tick k it
// takes the sensor frame of tick k from the link, runs controller.step(k, frame or nullptr, out) — the same
// call as in process — and publishes `out`. The process builds the controller from the same scene file as
// the plant; no plant exists in it.
//
// Sensor frames are screened in two places. Here: decodable (size, fingerprint), and for the expected tick
// with an advancing sequence (hil/link/actuator_frame_check.hpp's FrameOrder): older ticks are "stale", an
// exact repeat of the last one is "repeated" (lockstep: answered with the cached command, the plant's recovery
// of a lost datagram), a later tick (at most kMaxAheadTicks ahead) means the plant withheld the frames in
// between, which are stepped as missing. Content (NaN, ranges, sensor status) is the firmware fault monitor's
// job, as on the target: it holds the last good frame, then latches the safe state with the reason in every
// ActuatorFrame's status (firmware/fault/fault_monitor.hpp).
// Lockstep: a wait ends at the receive timeout ⇒ the plant is lost: the controller steps without frames until
// its fault monitor is in the safe state (hold_ticks + 1 ticks), publishing those safe commands for any drive
// still listening, then exits 6. Real time: see link_settings.hpp; a tick whose frame misses its deadline is
// stepped with nullptr; silence for the receive timeout ends the run (exit 6).
// Allocation-free after start-up (tests/alloc/lcm_loop_alloc_test.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/fault/fault_monitor.hpp"
#include "hil/lcm/lcm_transport.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/memory_bus.hpp"
#include "hil/link/end_of_run.hpp"
#include "hil/link/source_watch.hpp"
#include "hil/rt/deadline_pacer.hpp"
#include "hil/rt/rt_setup.hpp"
#include "tools/devices/registry.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/run/link_report.hpp"
#include "tools/run/link_settings.hpp"
#include "tools/run/link_stats.hpp"
#include "tools/run/output_dir.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/run/run_output.hpp"

namespace gyrostab::tools {
namespace {

struct ControllerLinkOutcome {
  std::int64_t ticks_run{0};
  bool peer_lost{false};
  std::int64_t lost_at_tick{-1};       // the tick whose sensor frame never came
  std::int64_t silent_ns{0};
  std::int64_t safe_state_tick{-1};    // first tick the fault monitor was in the safe state (any cause)
  std::int64_t missing_ticks{0};       // ticks stepped without a frame
  std::int64_t safe_ticks{0};          // ticks whose command was the safe one after the first good frame
  std::int64_t acknowledgements{0};    // link-loss trips acknowledged after kAcknowledgeAfterGoodFrames
  bool transport_error{false};
  int stop_signal{0};
  std::int64_t end_tick{-1};       // the plant's end-of-run frame (docs/protocol.md): its tick
  std::int64_t hijack_tick{-1};    // a second source speaking as the plant (hil/link/source_watch.hpp)
  bool hijack_by_stale_run{false};
  bool hijack_seen_by_plant{false};  // the plant's end-of-run frame says a second source sent as this controller
};

// The safe state was caused by the link alone: frames missing or stale, no bad sensor content.
bool tripped_by_link_only(std::uint32_t status) {
  const std::uint32_t causes = status & msg::kFaultCauseMask;
  const std::uint32_t link = msg::bit(msg::FaultBit::kSensorMissing) | msg::bit(msg::FaultBit::kSensorStale);
  return causes != 0 && (causes & ~link) == 0;
}

enum class SensorWait { kAccepted, kSkipped, kMissing, kLost, kStopped, kError, kEnd };

// Real time: where the controller believes the plant's clock is — the arrival of the sensor frame of
// `tick` (ns). The deadline for tick k follows from it.
struct PlantPhase {
  std::int64_t arrival_ns{0};
  std::int64_t tick{-1};  // < 0: not known yet (the tick-0 handshake runs in lockstep)

  std::int64_t deadline(std::int64_t k, const LinkSettings& s) const {
    return arrival_ns + (k - tick) * s.period_ns +
           static_cast<std::int64_t>(kControllerWindow * static_cast<double>(s.period_ns));
  }
};

// kEnd: `frame` is the plant's end-of-run frame (its tick is the first the run did not have). `watch` sees
// every frame of the bound plant.
template <class Transport>
SensorWait wait_for_sensor(hil::FrameEndpoint<Transport>& ep, hil::FrameOrder& order, std::int64_t k,
                           PlantPhase& phase, std::int64_t lost_at_ns, bool lockstep, const LinkSettings& s,
                           std::int64_t last_sent_tick, std::int64_t& last_republish_ns, msg::AnySensorFrame& frame,
                           msg::AnySensorFrame& early, hil::SourceWatch& watch, std::size_t signals) {
  hil::LinkCounters& c = ep.counters();
  const auto tick = static_cast<std::uint64_t>(k);
  for (;;) {
    const std::int64_t deadline_ns = lockstep ? hil::kNoDeadline : phase.deadline(k, s);
    const std::int64_t until = std::min(deadline_ns, lost_at_ns);
    msg::AnySensorFrame f{};
    const hil::RxStatus r = ep.receive(until, f);
    if (r == hil::RxStatus::kError) return SensorWait::kError;
    if (stop_signal_received() != 0) return SensorWait::kStopped;
    if (r != hil::RxStatus::kMessage) {
      const std::int64_t now = hil::monotonic_ns();
      if (now >= lost_at_ns) return SensorWait::kLost;
      if (now >= deadline_ns) return SensorWait::kMissing;
      continue;
    }
    // Before the handshake only a tick-0 frame can start a session (a plant already running belongs to
    // another controller).
    if (!ep.guard().bound() && f.tick != 0) {
      ++c.rejected_before_handshake;
      continue;
    }
    const bool from_peer = ep.guard().bound();
    const std::uint64_t content = hil::frame_content_hash(f, signals);
    // The end of the run: the plant's next frame, whatever tick this end expected (in real time it may have
    // stepped further, or not yet so far).
    if ((f.status & msg::bit(msg::SensorStatusBit::kEndOfRun)) != 0u && from_peer &&
        order.sequence_advances(f.sequence)) {
      order.accept(f.tick, f.sequence);  // not counted as accepted: that counts the run's sensor frames
      frame = f;
      return SensorWait::kEnd;
    }
    const hil::OrderVerdict o = order.classify(f.tick, f.sequence, tick);
    if (o == hil::OrderVerdict::kExpected) {
      order.accept(f.tick, f.sequence);
      watch.accepted(f.tick, content);
      ++c.accepted;
      frame = f;
      if (!ep.guard().bound()) ep.bind_to_last();
      return SensorWait::kAccepted;
    }
    if (from_peer) watch.refused(f.tick, content, o == hil::OrderVerdict::kStale && f.tick < tick);
    if (o == hil::OrderVerdict::kAhead && f.tick - tick <= static_cast<std::uint64_t>(kMaxAheadTicks)) {
      early = f;  // the plant withheld ticks k .. f.tick - 1: they are stepped as missing, then this one
      return SensorWait::kSkipped;
    }
    hil::count_order_rejection(o, c);
    if (!lockstep && o == hil::OrderVerdict::kStale && f.tick < tick &&
        tick - f.tick <= static_cast<std::uint64_t>(kMaxResyncTicks) &&
        static_cast<std::int64_t>(f.tick) > phase.tick && order.sequence_advances(f.sequence)) {
      // A frame we had already stepped as missing: the plant's clock runs behind our estimate of it (a slow
      // first tick, a stall of either process). Follow the plant, the clock master, from this arrival on;
      // otherwise a phase error beyond the window would make every later frame stale as well.
      phase.arrival_ns = hil::monotonic_ns();
      phase.tick = static_cast<std::int64_t>(f.tick);
      ++c.resynced;
    }
    if (o == hil::OrderVerdict::kRepeated && lockstep && last_sent_tick >= 0 &&
        f.tick == static_cast<std::uint64_t>(last_sent_tick)) {
      // The plant did not get our answer (or its copy of the frame crossed ours): answer again, at most once
      // per resend interval so that a burst of copies is not answered by a burst.
      const std::int64_t now = hil::monotonic_ns();
      if (now - last_republish_ns >= s.resend_ns) {
        ep.resend();
        last_republish_ns = now;
      }
    }
  }
}

// The number of sensor values of the device whose frames this endpoint carries.
template <class Endpoint>
std::size_t signals_of_controller(const Endpoint& ep) {
  if constexpr (requires { ep.signals(); }) {
    return ep.signals().sensors.size();
  } else {
    return msg::kMaxSensorSignals;
  }
}

// Answers the plant's end-of-run frame: an actuator frame of its tick with kEndOfRun, every command at its safe
// value; answered again for every copy of it that comes within the resend interval (the plant resends until it
// has the answer).
template <class Transport>
void acknowledge_end(hil::FrameEndpoint<Transport>& ep, const msg::AnySensorFrame& end, const msg::AnyActuatorFrame& last,
                     std::uint32_t monitor_status, const LoopConfig& cfg, const LinkSettings& s) {
  msg::AnyActuatorFrame ack{};
  if constexpr (requires { ep.signals(); }) {
    ack = hil::end_of_run_ack(end, last, monitor_status, cfg.tick_ns, ep.signals());
  } else {
    ack = hil::end_of_run_ack(end, last, monitor_status, cfg.tick_ns, msg::DeviceSignals{});
  }
  ep.send(ack, static_cast<std::int64_t>(end.tick) * cfg.tick_ns / 1000);
  const std::int64_t until = hil::monotonic_ns() + 2 * s.resend_ns;
  for (;;) {
    msg::AnySensorFrame f{};
    if (ep.receive(until, f) != hil::RxStatus::kMessage) return;
    if (f.tick == end.tick && (f.status & msg::bit(msg::SensorStatusBit::kEndOfRun)) != 0u) ep.resend();
  }
}

template <class Transport>
void run_controller_loop(ControllerPort& ctl, const LoopConfig& cfg, const RunRequest& req, const LinkSettings& s,
                         hil::FrameEndpoint<Transport>& ep, LinkStats& stats, ControllerLinkOutcome& link) {
  const TransportOptions& t = req.transport;
  const std::size_t signals = signals_of_controller(ep);
  hil::FrameOrder order;
  hil::SourceWatch watch;
  JitterInjector jitter(s, cfg.seed);
  msg::AnySensorFrame frame{}, early{};
  bool have_early = false;
  msg::AnyActuatorFrame out{}, published{};
  std::int64_t last_sent_tick = -1;
  std::int64_t last_republish = 0;
  PlantPhase phase;  // real time: the plant's clock, from the arrivals of its frames
  std::int64_t good_in_a_row = 0;
  std::int64_t last_heard = hil::monotonic_ns();
  bool heard_any = false;
  // Until the plant's end-of-run frame (the plant decides how long a run is), the plant is lost, a stop request
  // comes, or a second source speaks as the plant; `--ticks` given to the controller stops it there instead.
  for (std::int64_t k = 0; req.ticks < 0 || k < req.ticks; ++k) {
    if (stop_signal_received() != 0) {
      link.stop_signal = stop_signal_received();
      break;
    }
    const bool lockstep = !s.real_time || phase.tick < 0;
    const std::int64_t lost_at =
        (lockstep ? hil::monotonic_ns() : last_heard) + (heard_any ? s.timeout_ns : s.start_timeout_ns);
    SensorWait w = SensorWait::kMissing;
    if (have_early && early.tick == static_cast<std::uint64_t>(k)) {
      frame = early;
      have_early = false;
      order.accept(frame.tick, frame.sequence);
      ++ep.counters().accepted;
      w = SensorWait::kAccepted;
    } else if (have_early) {
      w = SensorWait::kMissing;  // a withheld tick before the early frame
    } else {
      w = wait_for_sensor(ep, order, k, phase, lost_at, lockstep, s, last_sent_tick, last_republish, frame,
                          early, watch, signals);
      watch.end_tick(k, lockstep);
      if (watch.hijacked()) {
        link.hijack_by_stale_run = watch.conflict_tick() < 0;
        link.hijack_tick = link.hijack_by_stale_run ? watch.stale_streak_tick() : watch.conflict_tick();
        break;
      }
      if (w == SensorWait::kEnd) {
        link.end_tick = static_cast<std::int64_t>(frame.tick);
        if ((frame.status & msg::bit(msg::SensorStatusBit::kSecondSource)) != 0u) {
          link.hijack_seen_by_plant = true;
          link.hijack_tick = link.end_tick;
        }
        acknowledge_end(ep, frame, out, ctl.monitor_status(), cfg, s);
        break;
      }
      if (w == SensorWait::kSkipped) {
        have_early = true;
        w = SensorWait::kMissing;
      }
    }
    const std::int64_t t_start = hil::monotonic_ns();
    if (w == SensorWait::kStopped) {
      link.stop_signal = stop_signal_received();
      break;
    }
    if (w == SensorWait::kError) {
      link.transport_error = true;
      break;
    }
    if (w == SensorWait::kLost) {
      link.peer_lost = true;
      link.lost_at_tick = k;
      link.silent_ns = t_start - last_heard;
      // Lockstep: time stood still while waiting; take the fault monitor to its safe state now, tick by tick,
      // and publish those commands. Real time: it has got there already, tick by tick.
      for (std::int64_t j = k; j < k + kMaxAheadTicks && link.safe_state_tick < 0; ++j) {
        ctl.step(static_cast<std::uint64_t>(j), nullptr, out);
        ++link.missing_ticks;
        ++ep.counters().missed_frames;
        ep.send(out, j * cfg.tick_ns / 1000);
        link.ticks_run = j + 1;
        if (ctl.in_safe_state()) link.safe_state_tick = j;
      }
      break;
    }
    stats.tick_started(t_start, s.period_ns);
    const bool got = w == SensorWait::kAccepted;
    if (got) {
      last_heard = t_start;
      heard_any = true;
      if (s.real_time && !lockstep) {
        phase.arrival_ns = t_start;
        phase.tick = k;
      }
    } else {
      ++link.missing_ticks;
      ++ep.counters().missed_frames;
    }
    ctl.step(static_cast<std::uint64_t>(k), got ? &frame : nullptr, out);
    if (link.safe_state_tick < 0 && ctl.in_safe_state()) link.safe_state_tick = k;
    good_in_a_row = got ? good_in_a_row + 1 : 0;
    if (ctl.monitor_state() == firmware::MonitorState::kSafe) {
      ++link.safe_ticks;
      // The supervisor's rule for a link dropout (docs/transport.md): the firmware latches, the host
      // acknowledges once the frames have come back; a sensor fault stays latched.
      if (good_in_a_row >= kAcknowledgeAfterGoodFrames && tripped_by_link_only(ctl.monitor_status())) {
        ctl.acknowledge();
        ++link.acknowledgements;
        good_in_a_row = 0;
      }
    }
    const std::int64_t t_stepped = hil::monotonic_ns();
    if (const std::int64_t d = jitter.next(); d > 0) hil::spin_for(d);
    if (t.actuator_drop.covers(k)) {
      ++ep.counters().dropped_by_fault;
    } else {
      published = out;
      if (t.actuator_corrupt.covers(k)) {
        // The first command (every device that commands anything has one) becomes NaN: a plant must refuse it.
        published.signal[0] = std::numeric_limits<double>::quiet_NaN();
        ++ep.counters().corrupted_by_fault;
      }
      ep.send(published, k * cfg.tick_ns / 1000);
      last_sent_tick = k;
    }
    const std::int64_t t_end = hil::monotonic_ns();
    // The handshake: the plant's epoch is the arrival of this first command, not of its sensor frame (which
    // came a whole first step earlier — a first step may be slow: page faults, a sanitizer's start-up).
    if (s.real_time && lockstep) {
      phase.arrival_ns = t_end;
      phase.tick = k;
    }
    const std::int64_t deadline = lockstep ? hil::kNoDeadline : phase.deadline(k, s);
    stats.compute.add(t_stepped - t_start);
    // Real time: the command is late if it leaves after the plant's window for it closes (approximately: the
    // plant's clock is not ours).
    const auto plant_margin =
        static_cast<std::int64_t>((kPlantWindow - kControllerWindow) * static_cast<double>(s.period_ns));
    if (s.real_time && deadline != hil::kNoDeadline && t_end > deadline + plant_margin) {
      ++stats.overruns;
    }
    link.ticks_run = k + 1;
  }
}

template <class Transport>
int run_controller_over(const DeviceScene& scene, const RunRequest& req, Transport& transport,
                        const nlohmann::json& link_info, const hil::RtSetup* rt) {
  const LoopConfig& loop = scene.loop();  // the scene's, for the report; run_loop: --ticks sets the loop's length
  LoopConfig run_loop = loop;
  std::unique_ptr<ControllerPort> ctl = scene.make_controller();
  if (req.ticks >= 0) run_loop.duration_s = static_cast<double>(req.ticks) * run_loop.tick_s();
  const LinkSettings s = link_settings(run_loop, req.transport);
  LinkIdentity guard;
  if (std::string error; !link_identity(req.transport, /*plant_side=*/false, guard, error)) {
    std::fprintf(stderr, "gyrostab controller: %s\n", error.c_str());
    return 2;
  }
  hil::FrameEndpoint<Transport> ep(transport,
                                   hil::controller_guard(guard.own_id, guard.session, guard.key, loop.scene_hash),
                                   signals_of(scene));
  if (req.transport.loss > 0) ep.inject_loss(req.transport.loss, loop.seed, 2);
  auto stats = std::make_unique<LinkStats>();
  ControllerLinkOutcome link;
  const auto start = std::chrono::steady_clock::now();
  // Installed for the rest of the run: a stop request that comes while the outputs are written only sets the
  // flag (the run is ending anyway), so it cannot kill the process half way through report.json.
  StopSignalGuard stop_guard;
  {
    if (req.before_loop) req.before_loop();
    run_controller_loop(*ctl, run_loop, req, s, ep, *stats, link);
    if (req.after_loop) req.after_loop();
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json timing{{"ticks", link.ticks_run},
                        {"wall_s", wall_s},
                        {"ticks_per_second", wall_s > 0 ? static_cast<double>(link.ticks_run) / wall_s : 0.0}};
  timing.update(link_timing_json(*stats, s));
  timing["controller"] = ctl->report();
  nlohmann::json l = link_info;
  l["role"] = "controller";
  l["counters"] = counters_json(ep.counters());
  l["session"] = session_json(ep);
  if constexpr (requires { ep.report_extra(); }) l["can"] = ep.report_extra();  // CAN level
  l["missing_ticks"] = link.missing_ticks;
  l["safe_state_tick"] = link.safe_state_tick >= 0 ? nlohmann::json(link.safe_state_tick) : nlohmann::json();
  if (link.end_tick >= 0) l["end_of_run"] = {{"tick", link.end_tick}};
  std::string happened = "completed";
  if (link.hijack_tick >= 0) {
    happened = link.hijack_seen_by_plant
        ? "hijacked: the plant saw a second source send as this controller and ended the run at tick " +
              std::to_string(link.hijack_tick) +
              " (without a link key anyone who reads the bus can copy the ids: use --key-file)"
        : hijack_message("plant", ep.guard().peer(), link.hijack_by_stale_run, link.hijack_tick, "sensor frames",
                         "the controller stopped there");
    l["hijacked"] = {{"tick", link.hijack_tick},
                     {"evidence", link.hijack_seen_by_plant ? "the plant's end-of-run frame"
                                  : link.hijack_by_stale_run ? "stale frames of other contents on 8 ticks in a row"
                                                             : "two frames for one tick"}};
  } else if (link.peer_lost) {
    happened = "plant lost: no sensor frame for tick " + std::to_string(link.lost_at_tick) + " within " +
               std::to_string(link.silent_ns / 1'000'000) + " ms; " +
               (link.safe_state_tick >= 0 ? "safe state from tick " + std::to_string(link.safe_state_tick)
                                          : std::string("safe state NOT reached")) +
               refused_hint(ep);
    l["peer"] = {{"lost", true},
                 {"lost_at_tick", link.lost_at_tick},
                 {"silent_ms", static_cast<double>(link.silent_ns) * 1e-6},
                 {"safe_state_tick", link.safe_state_tick},
                 {"reaction_ticks", link.safe_state_tick >= 0 ? link.safe_state_tick - link.lost_at_tick + 1 : -1}};
  } else if (link.transport_error) {
    happened = "transport error";
  } else if (link.stop_signal != 0) {
    happened = std::string("stopped by ") + signal_name(link.stop_signal) + " after tick " +
               std::to_string(link.ticks_run - 1);
  }
  const double safe_share =
      link.ticks_run > 0 ? static_cast<double>(link.safe_ticks) / static_cast<double>(link.ticks_run) : 0.0;
  l["safe_state"] = {{"ticks", link.safe_ticks},
                     {"share", safe_share},
                     {"max_share", kMaxSafeShare},
                     {"first_tick", link.safe_state_tick >= 0 ? nlohmann::json(link.safe_state_tick) : nlohmann::json()},
                     {"ticks_without_frame", link.missing_ticks},
                     {"link_loss_acknowledged", link.acknowledgements},
                     {"acknowledge_after_good_frames", kAcknowledgeAfterGoodFrames}};
  // A run that ends with the safe command out did not finish its job, however short the latched stretch.
  const bool ended_safe = link.ticks_run > 0 && ctl->in_safe_state();
  l["safe_state"]["at_end"] = ended_safe;
  const bool degraded = happened == "completed" && (ended_safe || safe_share > kMaxSafeShare);
  if (degraded) {
    char buf[240];
    if (ended_safe) {
      std::snprintf(buf, sizeof buf,
                    "degraded: the run ended in the safe state (held %lld of %lld ticks, %.1f %%)",
                    static_cast<long long>(link.safe_ticks), static_cast<long long>(link.ticks_run),
                    100.0 * safe_share);
    } else {
      std::snprintf(buf, sizeof buf, "degraded: the safe state held %lld of %lld ticks (%.1f %%, more than %.0f %%)",
                    static_cast<long long>(link.safe_ticks), static_cast<long long>(link.ticks_run),
                    100.0 * safe_share, 100.0 * kMaxSafeShare);
    }
    happened = buf;
  }
  l["what_happened"] = happened;
  if (rt != nullptr) l["real_time_setup"] = {{"sched_fifo", rt->fifo}, {"priority", rt->priority},
                                             {"mlockall", rt->memory_locked}, {"message", rt->message}};
  nlohmann::json report{{"scene", scene_summary(loop, req.scene_path)}, {"timing", timing}, {"link", l}};
  if (req.report_out) *req.report_out = report;
  if (req.write_outputs) {
    std::string error;
    if (!check_output_dir(req.out_dir, error) ||
        !write_file_atomic(req.out_dir + "/report.json", report.dump(2) + "\n", error)) {
      std::fprintf(stderr, "gyrostab controller: %s\n", error.c_str());
      return 3;
    }
  }
  if (link.hijack_tick >= 0) {
    std::fprintf(stderr, "gyrostab controller: %s: %s\n", loop.name.c_str(), happened.c_str());
    return kExitForeignFrames;
  }
  if (link.peer_lost) {
    std::fprintf(stderr, "gyrostab controller: %s: %s (receive timeout %lld ms)\n", loop.name.c_str(),
                 happened.c_str(), static_cast<long long>(req.transport.timeout_ms));
    return kExitPeerLost;
  }
  if (link.transport_error) {
    std::fprintf(stderr, "gyrostab controller: %s: the transport failed after tick %lld\n", loop.name.c_str(),
                 static_cast<long long>(link.ticks_run - 1));
    return 3;
  }
  if (link.stop_signal != 0) {
    std::fprintf(stderr, "gyrostab controller: %s: %s\n", loop.name.c_str(), happened.c_str());
    return 128 + link.stop_signal;
  }
  if (degraded) {
    std::fprintf(stderr, "gyrostab controller: %s: %s\n", loop.name.c_str(), happened.c_str());
    return kExitDegraded;
  }
  return completed_exit_code("controller", loop.name, ep.guard());
}

}  // namespace

// Opens the link of the request and runs the controller over it.
int run_controller_process(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  const TransportOptions& t = req.transport;
  hil::RtSetup rt;
  if (t.real_time) {
    rt = hil::setup_real_time(t.rt_priority);
    std::fprintf(stderr, "gyrostab controller: %s\n", rt.message.c_str());
  }
  if (!t.can_if.empty()) {  // CAN FD over SocketCAN (tools/run/can_link_setup.hpp, docs/can.md)
    auto bus = std::make_unique<can::CanBusTransport>();
    nlohmann::json info;
    if (const int rc = open_can_link(*bus, loop, req, /*plant_side=*/false, info); rc != 0) return rc;
    return run_controller_over(scene, req, *bus, info, t.real_time ? &rt : nullptr);
  }
  if (t.memory_bus != nullptr) {
    hil::MemoryTransport transport(t.memory_bus->to_plant, t.memory_bus->to_controller);
    return run_controller_over(scene, req, transport, nlohmann::json{{"transport", "memory"}},
                               t.real_time ? &rt : nullptr);
  }
  if (!hil::valid_channel_suffix(t.channel_suffix)) {
    std::fprintf(stderr, "gyrostab controller: --channel-suffix '%s': only letters, digits, '_' and '-' (at most 40)\n",
                 t.channel_suffix.c_str());
    return 2;
  }
  auto transport = std::make_unique<hil::LcmTransport>();
  std::string error;
  if (!transport->open(sensor_url(t), actuator_channel(t), sensor_channel(t), hil::kLcmQueueCapacity, error,
                       actuator_url(t))) {
    std::fprintf(stderr, "gyrostab controller: %s\n", error.c_str());
    return 3;
  }
  const nlohmann::json info{{"transport", "lcm"},
                            {"url", t.lcm_url},
                            {"publishes_on", actuator_url(t)},
                            {"subscribes_on", sensor_url(t)},
                            {"publishes", actuator_channel(t)},
                            {"subscribes", sensor_channel(t)},
                            {"queue_capacity", hil::kLcmQueueCapacity},
                            {"timeout_ms", t.timeout_ms},
                            {"start_timeout_ms", t.start_timeout_ms}};
  return run_controller_over(scene, req, *transport, info, t.real_time ? &rt : nullptr);
}

}  // namespace gyrostab::tools
