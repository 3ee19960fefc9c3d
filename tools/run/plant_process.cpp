// The plant as its own process (Role::kPlant, `gyrostab plant SCENE`): the loop of run_closed_loop
// (closed_loop.hpp) with the controller step replaced by an exchange over a link:
//   sense(k) → publish SensorFrame{k} → wait for the ActuatorFrame of tick k → latency pipe → actuate → advance
// The same plant code in the same order as in process (PlantTick), and the frames cross the link bit for bit
// (hil/lcm/frame_codec.hpp), so a lockstep run is bit-identical to the in-process run of the same scene and
// seed (tests/lcm/). The process builds the plant only: no controller exists in it.
//
// Every received actuator frame is checked before use (hil/link/actuator_frame_check.hpp): decodable, finite,
// within the scene's limits (DeviceScene::actuator_limits()), for the expected tick with an advancing
// sequence. A tick without an accepted command gets the drive watchdog's command (zero torque, brake released)
// in its latency-pipe slot, as real drives do.
// Lockstep: a frame rejected for its content (NaN, out of range) for the expected tick is followed by a grace
// of one resend interval for a good one, then the tick gets zero torque and the loop moves on (a faulty
// controller cannot stall the plant). Silence for the receive timeout ⇒ the controller is lost: the loop runs
// the `latency` ticks that the zero command needs to reach the plant, stops, writes its outputs and exits 6.
// Real time: see link_settings.hpp; silence for the receive timeout also ends the run with exit 6.
//
// Tick sink (closed_loop.hpp concept, e.g. the bus log of --log): record(k, published sensor frame, command
// used for tick k) right after the exchange, before actuation; stop_requested() is polled before each tick.
//
// Allocation-free after start-up: the endpoint's buffers, the statistics histograms and the recorder are
// allocated before tick 0 (tests/alloc/lcm_loop_alloc_test.cpp).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "hil/lcm/lcm_transport.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "hil/link/end_of_run.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/link/memory_bus.hpp"
#include "hil/rt/deadline_pacer.hpp"
#include "hil/rt/rt_setup.hpp"
#include "hil/target/target_endpoint.hpp"
#include "tools/devices/registry.hpp"
#include "tools/log/stop_signal.hpp"
#include "tools/run/bus_log_sink.hpp"
#include "tools/run/can_link_setup.hpp"
#include "tools/loop/closed_loop.hpp"
#include "tools/run/command_wait.hpp"
#include "tools/run/frame_table.hpp"
#include "tools/run/link_identity.hpp"
#include "tools/run/link_report.hpp"
#include "tools/run/link_settings.hpp"
#include "tools/run/link_stats.hpp"
#include "tools/run/run_modes.hpp"
#include "tools/run/run_mcap.hpp"
#include "tools/run/run_output.hpp"
#include "tools/run/target_link_setup.hpp"
#include "tools/view/run_view.hpp"

namespace gyrostab::tools {
namespace {

// report.json link.actuator_limits: what the plant's drives accept, per command of the device's table — its
// range and, where the scene sets one, the magnitude limit.
nlohmann::json actuator_limits_json(const hil::ActuatorLimits& limits, const msg::DeviceSignals& signals) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t i = 0; i < signals.commands.size(); ++i) {
    const msg::SignalSpec& c = signals.commands[i];
    std::string name(c.name);
    if (c.count > 1) name += "[" + std::to_string(c.element) + "]";
    nlohmann::json e{{"range", {c.min, c.max}}, {"unit", c.unit}};
    if (limits.from_scene && std::isfinite(limits.magnitude[i])) e["magnitude_limit"] = limits.magnitude[i];
    j[name] = e;
  }
  return j;
}

// What happened to the link during a plant run (report.json "peer" and "drive_watchdog").
struct PlantLinkOutcome {
  bool peer_lost{false};
  std::int64_t lost_at_tick{-1};            // the tick whose command never came
  std::int64_t silent_ns{0};                // how long the controller had been silent then
  std::int64_t zero_torque_from_tick{-1};   // first tick the plant integrated with the watchdog's zero command
                                            // after the loss
  std::int64_t watchdog_ticks{0};           // ticks whose slot got the watchdog's zero command (any cause)
  std::int64_t first_watchdog_tick{-1};
  bool transport_error{false};
  int stop_signal{0};
  // A second source speaking as the controller (hil/link/source_watch.hpp): the tick of the evidence.
  std::int64_t hijack_tick{-1};
  bool hijack_by_stale_run{false};
  // The end-of-run frame (docs/protocol.md): its tick, and whether the controller acknowledged it.
  std::int64_t end_tick{-1};
  bool end_acknowledged{false};
};

// After the last tick: the end-of-run frame for the next tick (status kEndOfRun, signals zero), sent again every
// resend interval until the controller acknowledges it (an actuator frame of that tick with kEndOfRun) or the
// receive timeout passes. The controller stops on it; it never has to know the run's length.
template <class Transport>
void send_end_of_run(hil::FrameEndpoint<Transport>& ep, std::int64_t tick, std::int64_t last_sent_tick,
                     const LoopConfig& cfg, const LinkSettings& s, PlantLinkOutcome& link, bool second_source) {
  const msg::AnySensorFrame end = hil::end_of_run_frame(tick, cfg.tick_ns, second_source, last_sent_tick);
  link.end_tick = tick;
  if (!ep.send(end, tick * cfg.tick_ns / 1000)) return;
  const std::int64_t give_up = hil::monotonic_ns() + s.timeout_ns;
  std::int64_t next_resend = hil::monotonic_ns() + s.resend_ns;
  for (;;) {
    msg::AnyActuatorFrame a{};
    const hil::RxStatus r = ep.receive(std::min(give_up, next_resend), a);
    if (r == hil::RxStatus::kError) return;
    if (r == hil::RxStatus::kMessage) {
      if (a.tick == end.tick && (a.status & msg::bit(msg::FaultBit::kEndOfRun)) != 0u) {
        link.end_acknowledged = true;
        return;
      }
      continue;
    }
    const std::int64_t now = hil::monotonic_ns();
    if (now >= give_up) return;
    if (now >= next_resend) {
      ep.resend();
      next_resend = now + s.resend_ns;
    }
  }
}

template <class Transport>
LoopOutcome run_plant_loop(PlantPort& plant_port, const hil::ActuatorLimits& limits,
                           const msg::DeviceSignals& signals, const LoopConfig& cfg,
                           const RunRequest& req, const LinkSettings& s, hil::FrameEndpoint<Transport>& ep,
                           LinkStats& stats, PlantLinkOutcome& link, Recorder* recorder, TickSink* sink,
                           RowSink* rows) {
  LoopOutcome out;
  const std::int64_t ticks = cfg.ticks();
  const int latency = cfg.latency_ticks;
  const TransportOptions& t = req.transport;
  hil::FrameOrder order;
  hil::SourceWatch watch;
  JitterInjector jitter(s, cfg.seed);
  PlantTick plant(plant_port, cfg, recorder, rows);
  msg::AnySensorFrame sensor{};
  msg::AnySensorFrame published{};
  msg::AnyActuatorFrame command{};
  std::int64_t epoch = 0;
  std::int64_t last_heard = hil::monotonic_ns();
  std::int64_t missing_in_a_row = 0;
  std::int64_t stop_after = std::numeric_limits<std::int64_t>::max();
  std::int64_t last_sent_tick = -1;
  const auto start = std::chrono::steady_clock::now();
  for (std::int64_t k = 0; k < ticks && k <= stop_after; ++k) {
    if (sink != nullptr && sink->stop_requested()) {
      out.interrupted = true;
      break;
    }
    if (stop_signal_received() != 0) {
      out.interrupted = true;
      link.stop_signal = stop_signal_received();
      break;
    }
    const bool handshake = k == 0;
    std::int64_t tick_deadline = 0;
    if (s.real_time && !handshake) {
      tick_deadline = epoch + k * s.period_ns;
      stats.lateness.add(hil::sleep_until(tick_deadline, s.spin_ns));
    }
    const std::int64_t t_start = hil::monotonic_ns();
    stats.tick_started(t_start, s.period_ns);

    plant_port.sense(k, sensor);
    published = sensor;
    const bool dropped = t.sensor_drop.covers(k);
    if (t.sensor_corrupt.covers(k)) {
      // The first signal becomes NaN: the controller's fault monitor must catch it (every signal is screened).
      published.signal[0] = std::numeric_limits<double>::quiet_NaN();
      ++ep.counters().corrupted_by_fault;
    }
    if (const std::int64_t d = jitter.next(); d > 0) hil::spin_for(d);
    const std::int64_t sim_us = k * cfg.tick_ns / 1000;
    if (dropped) {
      ++ep.counters().dropped_by_fault;
    } else {
      ep.send(published, sim_us);
      last_sent_tick = k;
    }

    // The exchange: the command of tick k, or the watchdog's.
    const std::int64_t t_sent = hil::monotonic_ns();
    CommandWait w = CommandWait::kMissing;
    if (link.peer_lost || (dropped && !s.real_time)) {
      w = CommandWait::kMissing;  // lost: nobody answers; lockstep + withheld frame: nobody was asked
    } else {
      const bool lockstep = handshake || !s.real_time;
      const auto window = static_cast<std::int64_t>(kPlantWindow * static_cast<double>(s.period_ns));
      // Lockstep: a controller that answered the previous tick but withholds this tick's command gets
      // kMissingCommandFraction of the receive timeout, then the drives get zero torque for this tick and the
      // loop goes on; a second silent tick in a row waits for the receive timeout (the controller is lost).
      std::int64_t deadline = epoch + k * s.period_ns + window;
      if (lockstep) {
        deadline = handshake || missing_in_a_row > 0
                       ? hil::kNoDeadline
                       : t_sent + static_cast<std::int64_t>(kMissingCommandFraction * static_cast<double>(s.timeout_ns));
      }
      const std::int64_t lost_at = (handshake ? t_sent : last_heard) + (handshake ? s.start_timeout_ns : s.timeout_ns);
      w = wait_for_command(ep, order, limits, signals, k, deadline, lockstep, lost_at, s, command, watch);
      watch.end_tick(k, lockstep);
    }
    const std::int64_t t_got = hil::monotonic_ns();
    if (w == CommandWait::kStopped) {
      out.interrupted = true;
      link.stop_signal = stop_signal_received();
      break;
    }
    if (w == CommandWait::kError) {
      link.transport_error = true;
      break;
    }
    if (watch.hijacked()) {
      // Two sources speak as the controller: no command of this run can be trusted from here on. Stop before
      // this tick is integrated.
      link.hijack_by_stale_run = watch.conflict_tick() < 0;
      link.hijack_tick = link.hijack_by_stale_run ? watch.stale_streak_tick() : watch.conflict_tick();
      break;
    }
    if (!dropped || s.real_time) missing_in_a_row = w == CommandWait::kAccepted ? 0 : missing_in_a_row + 1;
    if (w == CommandWait::kAccepted) {
      last_heard = t_got;
      stats.round_trip.add(t_got - t_sent);
      // The handshake's command names the controller this session is with; any other sender is foreign.
      if (!ep.guard().bound()) ep.bind_to_last();
    } else {
      ++ep.counters().missed_frames;
      if (w == CommandWait::kLost && !link.peer_lost) {
        link.peer_lost = true;
        link.lost_at_tick = k;
        link.silent_ns = t_got - last_heard;
        // Lockstep: run until the zero command has reached the plant through the latency pipe. Real time: the
        // drives have been at zero since the first missed tick; stop now.
        stop_after = s.real_time ? k : k + latency;
        link.zero_torque_from_tick = k + latency;
      }
      command = hil::drive_watchdog_command(static_cast<std::uint64_t>(k));
      ++link.watchdog_ticks;
      if (link.first_watchdog_tick < 0) link.first_watchdog_tick = k;
    }
    if (handshake && s.real_time) epoch = t_got;  // tick 1 starts one period after the handshake

    if (sink != nullptr && !sink->record(k, published, command)) {
      out.interrupted = true;
      break;
    }
    if (!plant.step(k, command, out)) break;
    const std::int64_t t_end = hil::monotonic_ns();
    stats.compute.add((t_end - t_start) - (t_got - t_sent));
    if (s.real_time && !handshake && t_end > epoch + (k + 1) * s.period_ns) ++stats.overruns;
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The target link ends its session with its own Stop frame (hil/target/target_session.cpp).
  if constexpr (!std::is_same_v<Transport, hil::TargetBus>) {
    // After a hijack too: the genuine controller learns why its run ends (it may not see the second source).
    if (!link.peer_lost && !link.transport_error && ep.guard().bound()) {
      send_end_of_run(ep, out.ticks_run, last_sent_tick, cfg, s, link, link.hijack_tick >= 0);
    }
  }
  return out;
}

// Opens the transport the request names (LCM, or the test's in-memory bus), runs the loop, writes the
// outputs. Exit code: 0 ok; 2 bad options; 3 diverged / outputs or log not written / transport failed;
// 6 the controller was lost (receive timeout); 128 + N stopped by signal N.
template <class Transport>
int run_plant_over(const DeviceScene& scene, const RunRequest& req, Transport& transport,
                   const nlohmann::json& link_info, const hil::RtSetup* rt) {
  LinkIdentity guard;
  if (std::string error; !link_identity(req.transport, /*plant_side=*/true, guard, error)) {
    std::fprintf(stderr, "gyrostab plant: %s\n", error.c_str());
    return 2;
  }
  // As in process: --ticks sets the loop's length only; the recorder, the report's scene block and the
  // outputs keep the scene's own configuration.
  const LoopConfig& loop = scene.loop();
  LoopConfig run_loop = loop;
  if (req.ticks >= 0) run_loop.duration_s = static_cast<double>(req.ticks) * run_loop.tick_s();
  if (!signals_ok(scene, req)) return 2;
  std::unique_ptr<PlantPort> plant = scene.make_plant(PlantOptions{false, req.ticks});
  const hil::ActuatorLimits limits = scene.actuator_limits();
  Recorder rec = scene_recorder(scene, req.ticks >= 0 ? req.ticks : loop.ticks());
  const LinkSettings s = link_settings(run_loop, req.transport);
  hil::FrameEndpoint<Transport> ep(transport, hil::plant_guard(guard.session, guard.key, loop.scene_hash, guard.peer),
                                   signals_of(scene));
  if (req.transport.loss > 0) ep.inject_loss(req.transport.loss, loop.seed, 1);
  auto stats = std::make_unique<LinkStats>();
  PlantLinkOutcome link;
  LoopOutcome outcome;
  // --log FILE: the bus log as the loop's tick sink: it records the sensor frame the plant published and the
  // command it used, per tick, as `gyrostab run --log` does in process.
  const bool logging = !req.transport.log_path.empty();
  std::unique_ptr<BusLog> log;
  LoggedRun logged;
  if (logging) {
    log = std::make_unique<BusLog>();
    if (!log->open(loop, req, logged.error)) {
      std::fprintf(stderr, "gyrostab plant: %s\n", logged.error.c_str());
      return 3;
    }
  }
  // --mcap (or, in the plant process of a pair, the parent's --mcap): the frames the plant published and used.
  std::string frames_error;
  std::unique_ptr<FrameTable> frames = make_frame_table(signals_of(scene), req, loop, run_loop.ticks(), frames_error);
  if (!frames_error.empty()) {
    std::fprintf(stderr, "gyrostab plant: --mcap: %s\n", frames_error.c_str());
    return 2;
  }
  TickFanOut sinks(log.get(), frames.get());
  // Installed for the rest of the run: a stop request that comes while the outputs are written only sets the
  // flag (the run is ending anyway), so it cannot kill the process half way through report.json.
  StopSignalGuard stop_guard;
  // --view: the live view of the plant's rows (no controller here: its status comes with the frames, later).
  std::unique_ptr<view::RunView> live;
  if (req.view.enabled) {
    std::string why;
    live = view::RunView::start(scene, req, rec, nullptr, run_loop.ticks(), why);
    if (!live) {
      std::fprintf(stderr, "gyrostab plant: %s\n", why.c_str());
      return 2;
    }
  }
  {
    if (req.before_loop) req.before_loop();
    outcome = run_plant_loop(*plant, limits, signals_of(scene), run_loop, req, s, ep, *stats, link, &rec, sinks.sink(),
                             live ? live->sink() : nullptr);
    if (logging && outcome.interrupted && link.stop_signal == 0) link.stop_signal = stop_signal_received();
    if (req.after_loop) req.after_loop();
  }
  // The target's execution profile, then the emulator is ended (a lost one is not waited for).
  if constexpr (std::is_same_v<Transport, hil::TargetBus>) {
    hil::finish_target_session(transport, hil::monotonic_ns() + (link.peer_lost ? 0 : s.timeout_ns));
  }
  if (logging) {
    logged.stop_signal = link.stop_signal;
    log->close(outcome, logged,
               link.peer_lost ? "controller lost after tick " + std::to_string(link.lost_at_tick) : std::string());
  }
  const std::string& log_error = logged.error;
  nlohmann::json report = plant_report(scene, *plant, req, outcome);
  report["timing"].update(link_timing_json(*stats, s));
  nlohmann::json l = link_info;
  l["role"] = "plant";
  l["counters"] = counters_json(ep.counters());
  l["session"] = session_json(ep);
  if constexpr (std::is_same_v<Transport, hil::TargetBus>) {
    l["target"] = hil::target_link_json(transport);
    report["timing"]["target"] = hil::target_timing_json(transport, loop.tick_ns);
  } else if constexpr (requires { ep.report_extra(); }) {
    l["can"] = ep.report_extra();  // CAN level
  }
  l["actuator_limits"] = actuator_limits_json(limits, signals_of(scene));
  l["drive_watchdog"] = {{"zero_torque_ticks", link.watchdog_ticks}, {"first_tick", link.first_watchdog_tick}};
  if (link.end_tick >= 0) {
    l["end_of_run"] = {{"tick", link.end_tick}, {"acknowledged", link.end_acknowledged}};
  }
  std::string happened = "completed";
  if (link.hijack_tick >= 0) {
    happened = hijack_message("controller", ep.guard().peer(), link.hijack_by_stale_run, link.hijack_tick,
                              "commands", "the run was stopped there: its results are not the loop's");
    l["hijacked"] = {{"tick", link.hijack_tick},
                     {"evidence", link.hijack_by_stale_run ? "stale frames of other contents on 8 ticks in a row" : "two commands for one tick"}};
  } else if (link.peer_lost) {
    happened = "controller lost: no actuator frame for tick " + std::to_string(link.lost_at_tick) + " within " +
               std::to_string(link.silent_ns / 1'000'000) + " ms; drives at zero torque from tick " +
               std::to_string(link.zero_torque_from_tick) + refused_hint(ep);
    if constexpr (requires { ep.peer_state(); }) happened += "; " + ep.peer_state();
    l["peer"] = {{"lost", true},
                 {"lost_at_tick", link.lost_at_tick},
                 {"silent_ms", static_cast<double>(link.silent_ns) * 1e-6},
                 {"zero_torque_from_tick", link.zero_torque_from_tick},
                 {"reaction_ticks", link.zero_torque_from_tick - link.lost_at_tick}};
  } else if (link.transport_error) {
    happened = "transport error";
  } else if (link.stop_signal != 0) {
    happened = std::string("stopped by ") + signal_name(link.stop_signal) + " after tick " +
               std::to_string(outcome.ticks_run - 1);
  } else if (outcome.diverged) {
    happened = "the plant state became non-finite at tick " + std::to_string(outcome.diverged_tick);
  }
  if (link.end_tick >= 0 && !link.end_acknowledged)
    happened += "; the controller did not acknowledge the end of the run within the receive timeout";
  l["what_happened"] = happened;
  if (rt != nullptr) l["real_time_setup"] = {{"sched_fifo", rt->fifo}, {"priority", rt->priority},
                                             {"mlockall", rt->memory_locked}, {"message", rt->message}};
  report["link"] = l;
  if (logging) report["log"] = logged.summary;
  std::string error;
  const bool written = write_run_outputs(req, loop, rec, report, error, frames.get());
  if (live) live->finish(report);
  if (!written) {
    std::fprintf(stderr, "gyrostab plant: %s\n", error.c_str());
    return 3;
  }
  if (logging && !log_error.empty()) {
    std::fprintf(stderr, "gyrostab plant: %s\n", log_error.c_str());
    return 3;
  }
  if (link.hijack_tick >= 0) {
    std::fprintf(stderr, "gyrostab plant: %s: %s\n", loop.name.c_str(), happened.c_str());
    return kExitForeignFrames;
  }
  if (link.peer_lost) {
    std::fprintf(stderr, "gyrostab plant: %s: %s (receive timeout %lld ms); outputs up to it are written\n",
                 loop.name.c_str(), happened.c_str(), static_cast<long long>(req.transport.timeout_ms));
    return kExitPeerLost;
  }
  if (link.transport_error) {
    std::fprintf(stderr, "gyrostab plant: %s: the transport failed after tick %lld\n", loop.name.c_str(),
                 static_cast<long long>(outcome.ticks_run - 1));
    return 3;
  }
  if (link.stop_signal != 0) {
    std::fprintf(stderr, "gyrostab plant: %s: %s; outputs up to it are written\n", loop.name.c_str(), happened.c_str());
    return 128 + link.stop_signal;
  }
  if (outcome.diverged) {
    std::fprintf(stderr, "gyrostab plant: %s; outputs up to it are written\n",
                 describe_non_finite(loop.name, outcome.diverged_tick, outcome.diverged_state).c_str());
    return 3;
  }
  std::uint64_t image_refused = 0;
  if constexpr (std::is_same_v<Transport, hil::TargetBus>) {
    if (transport.have_profile) image_refused = transport.profile.rx.foreign;
  }
  return completed_exit_code("plant", loop.name, ep.guard(), image_refused);
}

}  // namespace

// Opens the link of the request and runs the plant over it.
int run_plant_process(const DeviceScene& scene, const RunRequest& req) {
  const LoopConfig& loop = scene.loop();
  const TransportOptions& t = req.transport;
  hil::RtSetup rt;
  if (t.real_time) {
    rt = hil::setup_real_time(t.rt_priority);
    std::fprintf(stderr, "gyrostab plant: %s\n", rt.message.c_str());
  }
  if (t.transport == "target") {  // the firmware image on the emulated Cortex-M7 (target_link_setup.hpp)
    auto bus = std::make_unique<hil::TargetBus>();
    RunRequest target_req = req;
    nlohmann::json info;
    if (const int rc = open_target_link(scene, target_req, *bus, info); rc != 0) return rc;
    return run_plant_over(scene, target_req, *bus, info, nullptr);
  }
  if (!t.can_if.empty()) {  // CAN FD over SocketCAN (tools/run/can_link_setup.hpp, docs/can.md)
    auto bus = std::make_unique<can::CanBusTransport>();
    nlohmann::json info;
    if (const int rc = open_can_link(*bus, loop, req, /*plant_side=*/true, info); rc != 0) return rc;
    return run_plant_over(scene, req, *bus, info, t.real_time ? &rt : nullptr);
  }
  if (t.memory_bus != nullptr) {
    hil::MemoryTransport transport(t.memory_bus->to_controller, t.memory_bus->to_plant);
    return run_plant_over(scene, req, transport, nlohmann::json{{"transport", "memory"}},
                          t.real_time ? &rt : nullptr);
  }
  if (!hil::valid_channel_suffix(t.channel_suffix)) {
    std::fprintf(stderr, "gyrostab plant: --channel-suffix '%s': only letters, digits, '_' and '-' (at most 40)\n",
                 t.channel_suffix.c_str());
    return 2;
  }
  auto transport = std::make_unique<hil::LcmTransport>();
  std::string error;
  if (!transport->open(actuator_url(t), sensor_channel(t), actuator_channel(t), hil::kLcmQueueCapacity, error,
                       sensor_url(t))) {
    std::fprintf(stderr, "gyrostab plant: %s\n", error.c_str());
    return 3;
  }
  const nlohmann::json info{{"transport", "lcm"},
                            {"url", t.lcm_url},
                            {"publishes_on", sensor_url(t)},
                            {"subscribes_on", actuator_url(t)},
                            {"publishes", sensor_channel(t)},
                            {"subscribes", actuator_channel(t)},
                            {"queue_capacity", hil::kLcmQueueCapacity},
                            {"timeout_ms", t.timeout_ms},
                            {"start_timeout_ms", t.start_timeout_ms}};
  return run_plant_over(scene, req, *transport, info, t.real_time ? &rt : nullptr);
}

}  // namespace gyrostab::tools
