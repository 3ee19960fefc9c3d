// The CAN end of a plant ⇄ controller link: hil::FrameEndpoint (hil/link/frame_endpoint.hpp) specialised for
// the SocketCAN bus, so the plant and controller loops (tools/run/plant_process.hpp, controller_process.hpp)
// run over CAN unchanged: the same send / resend / receive / counters calls, the same lockstep and real-time
// rules, the same fault handling. What differs underneath (docs/can.md):
//   send(frame)      one generic frame → the CAN FD frames of its direction on the device's bus (its map,
//                    hil/can/frame_codec.hpp), header last, each written to the socket; a value the bus cannot
//                    carry exactly (not an integer where the map carries one, or a node the device does not
//                    have) is refused: the endpoint turns fatal (receive() then reports kError, the loop stops
//                    with "transport failed") and says which signal and why
//   resend()         the last frame again, re-encoded: new alive counters (a byte-identical CAN frame
//                    would be rejected by the receiver as a stale repeat); at most every resend_min_ns (250 ms):
//                    the bus delivers what was sent, a resend only serves a node that was not listening yet
//   receive(...)     CAN frames from the socket into the set assembler until a tick's set completes; every
//                    rejected frame (CRC, counter, length, id, ...) is counted in can_counters() and never
//                    reaches the loop; a timeout is the loop's business as over LCM
// Every set carries the link envelope in its header frame (link_seal.hpp: sender, session, 32-bit freshness,
// MAC over the whole set): the guard binds, counts and refuses exactly as over LCM, and a refused set never
// reaches the loop.
// With a candump log attached, every frame sent and received is written to it in bus order, stamped with the
// simulated time of its tick in lockstep (deterministic logs, canplayer replays them at the scene's rate) or
// with the kernel's receive time / the send time (CLOCK_REALTIME) in real time.
// LinkCounters stay at frame level (received = complete sets delivered); the CAN level is in
// can_counters() and report_extra() ("can" in report.json). No heap after construction.
#pragma once

#include <time.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "hil/can/bus_load.hpp"
#include "hil/can/bus_nodes.hpp"
#include "hil/can/candump_log.hpp"
#include "hil/can/frame_codec.hpp"
#include "hil/can/link_seal.hpp"
#include "hil/can/socketcan_link.hpp"
#include "hil/link/frame_endpoint.hpp"

namespace gyrostab::can {

// What a process needs to talk on the bus; opened by tools/run/can_link_setup.hpp.
struct CanBusTransport {
  SocketCan socket;
  std::string ifname;
  DeviceBus bus{};  // the device's map, and which of its frames are on the bus (can_link_setup.hpp)
  std::int64_t tick_ns{1'000'000};
  bool real_time{false};
  BusTiming timing{};
  BusLoad load{};
  CandumpWriter log;        // open when the run records the bus (--can-log)
  bool logging{false};
  std::int64_t send_timeout_ns{100'000'000};  // a frame that cannot be queued within this is a send error
  // A CAN frame on the bus reaches every listening node (the bus acknowledges and retransmits by itself): a
  // lockstep resend only matters for a node that was not listening yet. So resends of the same set are at
  // least this far apart (the loops ask every 20 ms, which on a slow host would only duplicate traffic).
  std::int64_t resend_min_ns{250'000'000};
};

}  // namespace gyrostab::can

namespace gyrostab::hil {

template <>
class FrameEndpoint<can::CanBusTransport> : public EndpointBook {
 public:
  // `signals` must be the frames of the bus's map (the same device's table): a mismatch turns the endpoint fatal.
  FrameEndpoint(can::CanBusTransport& bus, const GuardConfig& guard, const msg::DeviceSignals& signals)
      : EndpointBook(can::can_guard_config(guard)),
        bus_(bus),
        signals_(signals),
        sensor_tx_(bus.bus, can::Direction::kSensor),
        actuator_tx_(bus.bus, can::Direction::kActuator),
        sensor_rx_(bus.bus, can::Direction::kSensor),
        actuator_rx_(bus.bus, can::Direction::kActuator) {
    if (bus.bus.map == nullptr || bus.bus.map->signals->device != signals.device ||
        bus.bus.map->signals->sensors.size() != signals.sensors.size() ||
        bus.bus.map->signals->commands.size() != signals.commands.size()) {
      fatal_ = true;
      fatal_message_ = "the CAN map is not the one of the device's signal table";
      std::fprintf(stderr, "gyrostab: CAN: %s\n", fatal_message_.c_str());
    }
  }

  bool send(const msg::AnySensorFrame& f, std::int64_t sim_time_us) {
    last_sensor_ = f;
    last_kind_ = Last::kSensor;
    return send_set(sensor_tx_, f, sim_time_us);
  }
  bool send(const msg::AnyActuatorFrame& f, std::int64_t sim_time_us) {
    last_actuator_ = f;
    last_kind_ = Last::kActuator;
    return send_set(actuator_tx_, f, sim_time_us);
  }

  bool resend() {
    if (last_kind_ == Last::kNone) return false;
    if (monotonic_ns() - last_send_ns_ < bus_.resend_min_ns) return true;  // sent recently enough: on the bus
    ++counters_.resent;
    return last_kind_ == Last::kSensor ? send_set(sensor_tx_, last_sensor_, last_sim_us_)
                                       : send_set(actuator_tx_, last_actuator_, last_sim_us_);
  }

  RxStatus receive(std::int64_t deadline_ns, msg::AnySensorFrame& out, std::int64_t* sim_time_us = nullptr) {
    return receive_set(sensor_rx_, deadline_ns, out, sim_time_us);
  }
  RxStatus receive(std::int64_t deadline_ns, msg::AnyActuatorFrame& out, std::int64_t* sim_time_us = nullptr) {
    return receive_set(actuator_rx_, deadline_ns, out, sim_time_us);
  }

  // --loss (endpoint_book.hpp) draws once per set: a whole set is lost on the way.

  const msg::DeviceSignals& signals() const { return signals_; }

  // Binds to the peer of the set last returned by receive() (the handshake).
  void bind_to_last() { guard_.bind(last_rx_); }
  // The envelope of the set last returned by receive().
  const LinkEnvelope& last_envelope() const { return last_rx_; }
  const can::RxCounters& sensor_counters() const { return sensor_rx_.counters(); }
  const can::RxCounters& actuator_counters() const { return actuator_rx_.counters(); }
  bool fatal() const { return fatal_; }

  // report.json "link" → "can": the bus, its load and everything the CAN level counted (start-up and end only).
  nlohmann::json report_extra() const {
    nlohmann::json j;
    j["interface"] = bus_.ifname;
    if (bus_.bus.map != nullptr) {
      j["map"] = {{"table", bus_.bus.map->device}, {"fingerprint", fingerprint_text(bus_.bus.map->fingerprint)}};
      j["nodes"] = node_names(bus_.bus);
    }
    j["bitrate"] = {{"nominal", bus_.timing.nominal_bitrate}, {"data", bus_.timing.data_bitrate}};
    j["bus_load"] = {{"load", bus_.load.load},
                     {"frames_per_tick", bus_.load.frames_per_tick},
                     {"frames_per_s", bus_.load.frames_per_s},
                     {"limit", can::kMaxBusLoad}};
    const can::SocketCanCounters& s = bus_.socket.counters();
    j["socket"] = {{"sent", s.sent},          {"send_retries", s.send_retries}, {"send_failures", s.send_failures},
                   {"received", s.received},  {"error_frames", s.error_frames}, {"kernel_drops", s.kernel_drops},
                   {"odd_reads", s.odd_reads}};
    j["sensor_rx"] = rx_json(sensor_rx_.counters());
    j["actuator_rx"] = rx_json(actuator_rx_.counters());
    if (bus_.logging) j["candump_log_frames"] = bus_.log.frames_written();
    if (fatal_) j["fatal"] = fatal_message_;
    return j;
  }

  static nlohmann::json rx_json(const can::RxCounters& c) {
    nlohmann::json rejected = nlohmann::json::object();
    for (std::size_t i = 1; i < can::kFrameErrorCount; ++i) {
      if (c.rejected[i] != 0) rejected[std::string(can::frame_error_name(static_cast<can::FrameError>(i)))] = c.rejected[i];
    }
    return {{"frames", c.frames},
            {"accepted", c.accepted},
            {"rejected", rejected},
            {"sets_completed", c.sets_completed},
            {"sets_abandoned", c.sets_abandoned},
            {"non_finite_values", c.non_finite_values},
            {"out_of_range_values", c.out_of_range_values}};
  }

  static nlohmann::json node_names(const can::DeviceBus& b) {
    nlohmann::json a = nlohmann::json::array();
    for (std::string_view n : can::bus_nodes(b)) a.push_back(std::string(n));
    return a;
  }

  static std::string fingerprint_text(std::uint64_t f) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(f));
    return buf;
  }

 private:
  enum class Last { kNone, kSensor, kActuator };

  static std::string violation_text(const can::FieldViolation& v) {
    const std::string where = std::string(v.message) + "." + std::string(v.signal);
    char value[40];
    std::snprintf(value, sizeof value, "%.17g", v.value);
    const bool is_signed = v.spec != nullptr && v.spec->kind == can::SignalKind::kSigned;
    const int bits = v.spec != nullptr ? v.spec->bit_length : 0;
    return "the device set " + where + " to " + value + ", which its CAN signal carries as " +
           (is_signed ? "int" : "uint") + std::to_string(bits) +
           " (the signal table's can key): only an integer of that type travels exactly, so the frame is refused";
  }

  static std::int64_t now_ns(clockid_t clock) {
    timespec ts{};
    clock_gettime(clock, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
  }

  void log_frame(const can::CanFrame& f, std::int64_t tick) {
    if (!bus_.logging) return;
    const std::int64_t t = bus_.real_time ? (f.time_ns != 0 ? f.time_ns : now_ns(CLOCK_REALTIME)) : tick * bus_.tick_ns;
    bus_.log.write(f, t);
  }

  template <class Frame>
  bool send_set(can::FrameEncoder& enc, const Frame& f, std::int64_t sim_time_us) {
    if (fatal_) return false;
    last_sim_us_ = sim_time_us;
    can::FieldViolation v;
    const std::size_t n = enc.encode(f, tx_, &v);
    if (n == 0) {
      fatal_ = true;
      fatal_message_ = violation_text(v);
      std::fprintf(stderr, "gyrostab: CAN: %s\n", fatal_message_.c_str());
      ++counters_.send_errors;
      return false;
    }
    can::seal(std::span<can::CanFrame>(tx_.data(), n), guard_);
    last_send_ns_ = monotonic_ns();
    if (lost_on_the_way()) return true;  // the whole set gone on the way (fault injection)
    const std::int64_t deadline = last_send_ns_ + bus_.send_timeout_ns;
    bool ok = true;
    for (std::size_t i = 0; i < n; ++i) {
      if (bus_.socket.send(tx_[i], deadline)) {
        log_frame(tx_[i], static_cast<std::int64_t>(f.tick));
      } else {
        ok = false;
      }
    }
    if (ok) {
      ++counters_.sent;
    } else {
      ++counters_.send_errors;
    }
    return ok;
  }

  template <class Frame>
  RxStatus receive_set(can::SetAssembler& rx, std::int64_t deadline_ns, Frame& out, std::int64_t* sim_time_us) {
    if (fatal_) return RxStatus::kError;
    for (;;) {
      can::CanFrame f;
      const can::CanRx r = bus_.socket.receive(f, deadline_ns);
      if (r == can::CanRx::kTimeout) {
        ++counters_.timeouts;
        return RxStatus::kTimeout;
      }
      if (r == can::CanRx::kInterrupted) return RxStatus::kInterrupted;
      if (r == can::CanRx::kError) return RxStatus::kError;
      // The frame's tick from its 16-bit tag, next to the tick the assembler expects (log stamps only).
      const auto tag = static_cast<std::uint16_t>(f.data[can::kTickTagByte] | (f.data[can::kTickTagByte + 1] << 8));
      const std::uint64_t e = rx.expected_tick();
      const auto delta = static_cast<std::int16_t>(static_cast<std::uint16_t>(tag - static_cast<std::uint16_t>(e)));
      const std::int64_t tick = static_cast<std::int64_t>(e) + delta;
      log_frame(f, tick < 0 ? 0 : tick);
      if (rx.accept(f) != can::FrameError::kNone || !rx.ready()) continue;
      const std::size_t n = rx.ready_frames(rx_set_);
      LinkEnvelope env;
      if (can::open(std::span<const can::CanFrame>(rx_set_.data(), n), guard_, env) != GuardVerdict::kOk) {
        rx.drop_ready();  // counted by the guard; the tick is still expected
        continue;
      }
      rx.take(out);
      ++counters_.received;
      last_rx_ = env;
      if (sim_time_us != nullptr) *sim_time_us = static_cast<std::int64_t>(out.tick) * bus_.tick_ns / 1000;
      return RxStatus::kMessage;
    }
  }

  can::CanBusTransport& bus_;
  const msg::DeviceSignals& signals_;
  LinkEnvelope last_rx_{};
  can::FrameEncoder sensor_tx_, actuator_tx_;
  can::SetAssembler sensor_rx_, actuator_rx_;
  std::array<can::CanFrame, can::kMaxMessagesPerDirection> tx_{};
  std::array<can::CanFrame, can::kMaxMessagesPerDirection> rx_set_{};
  msg::AnySensorFrame last_sensor_{};
  msg::AnyActuatorFrame last_actuator_{};
  Last last_kind_{Last::kNone};
  std::int64_t last_sim_us_{0};
  std::int64_t last_send_ns_{0};
  bool fatal_{false};
  std::string fatal_message_;
};

}  // namespace gyrostab::hil
