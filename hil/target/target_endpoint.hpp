// The plant's end of the target link (docs/pil.md): hil::FrameEndpoint (hil/link/frame_endpoint.hpp)
// specialised for a controller image on the emulated processor, so the plant loop
// (tools/run/plant_process.cpp) runs over it unchanged — the same send / resend / receive / counters calls,
// the same lockstep rules and fault handling as over LCM and CAN. Underneath:
//   send(frame)    the sensor frame as a Sensor frame of firmware/link/target_frame.hpp (COBS, CRC-32, alive
//                  counter, session), written to the image's FIFO (or UART); the link-level fault injections
//                  of --target-fault act here, on the first transmission of a tick only (a resend is clean)
//   resend()       the same sensor frame again, re-encoded (a byte-identical copy would be refused as stale)
//   receive(...)   bytes from the image until an Actuator frame is accepted; refused frames are counted per
//                  cause (report.json link.target.host_refused) and never reach the loop
// The session is bound in the handshake (open_target_session, before the loop): Hello from the image, the
// scene's controller configuration, the image's verdict. After the loop, finish() asks for the execution
// profile and ends the emulation.
// An emulator that has exited is a silent peer: receive() waits out its deadline (the loop then declares the
// controller lost at the receive timeout, exit 6) and peer_state() says what became of the emulator.
// No heap after open.
#pragma once

#include <time.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "firmware/link/target_frame.hpp"
#include "hil/link/frame_endpoint.hpp"
#include "hil/target/qemu_target.hpp"
#include "hil/target/target_faults.hpp"

namespace gyrostab::hil {

struct TargetInjected {
  std::uint64_t corrupted{0}, stale{0}, skipped{0};
  std::int64_t frozen_at{-1}, killed_at{-1};
};

// Everything the plant needs to talk to one image.
struct TargetBus {
  QemuTarget qemu;
  QemuLaunch launch;
  firmware::link::TargetFrameEncoder encoder{0, 0};
  firmware::link::TargetFrameDecoder decoder{/*from_host=*/false, {}};  // frame sizes: set_device()
  const msg::DeviceSignals* signals{nullptr};
  std::array<std::uint8_t, 4096> rx{};
  std::size_t rx_have{0}, rx_pos{0};
  std::int64_t write_timeout_ns{1'000'000'000};
  TargetFaults faults;
  TargetInjected injected;
  firmware::link::TargetHello hello{};
  std::uint32_t image_sender{0};  // the image's id on the link (from its Hello)
  firmware::link::TargetConfigVerdict verdict{};
  firmware::link::TargetProfile profile{};
  bool have_profile{false};

  // The scene's device: its frames' sizes on the link. Before open_target_session().
  void set_device(const msg::DeviceSignals& d) {
    signals = &d;
    decoder.set_frame_sizes(firmware::link::target_frame_sizes(d.sensors.size(), d.commands.size()));
  }
  // A sensor frame as the device's typed frame's bytes.
  std::span<const std::uint8_t> encode_sensor(const msg::AnySensorFrame& f) {
    return encoder.encode(firmware::link::TargetFrameKind::kSensor, &f, decoder.frame_sizes().sensor);
  }
  // An accepted actuator frame's payload as the device-independent frame (the signals past the device's zero).
  static msg::AnyActuatorFrame actuator_of(const firmware::link::TargetFrameView& f) {
    msg::AnyActuatorFrame a{};
    std::memcpy(&a, f.payload.data(), std::min(f.payload.size(), sizeof a));
    return a;
  }

  // Writes one encoded frame. false: the emulator is gone or does not read.
  bool write(std::span<const std::uint8_t> bytes) {
    return !bytes.empty() && qemu.write(bytes.data(), bytes.size(), monotonic_ns() + write_timeout_ns);
  }

  // Waits until deadline_ns for one accepted frame. When the emulator has exited: kTimeout after the deadline
  // (a dead peer is a silent one to the loop), or kError at once with `dead_is_error` (the handshake);
  // kError also when reading fails.
  RxStatus next(std::int64_t deadline_ns, firmware::link::TargetFrameView& f, bool dead_is_error = false) {
    for (;;) {
      while (rx_pos < rx_have) {
        std::span<const std::uint8_t> wire;
        if (!decoder.collect(rx[rx_pos++], wire)) continue;
        if (decoder.judge(wire, f) == firmware::link::TargetRxVerdict::kOk) return RxStatus::kMessage;
      }
      std::size_t got = 0;
      switch (qemu.read(rx.data(), rx.size(), deadline_ns, got)) {
        case ByteWait::kData:
          rx_have = got;
          rx_pos = 0;
          break;
        case ByteWait::kTimeout: return RxStatus::kTimeout;
        case ByteWait::kExited: {
          if (dead_is_error) return RxStatus::kError;
          if (deadline_ns != kNoDeadline) {
            const timespec ts = to_timespec(deadline_ns);
            while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
            }
          }
          return RxStatus::kTimeout;
        }
        case ByteWait::kError: return RxStatus::kError;
      }
    }
  }

  // What became of the emulator, for the "controller lost" message.
  std::string peer_state() {
    if (injected.killed_at >= 0) return "the emulator was killed before tick " + std::to_string(injected.killed_at) +
                                        " (fault injection); it " + (qemu.exited() ? qemu.exit_text() : "still runs");
    if (injected.frozen_at >= 0) return "the emulator was stopped before tick " + std::to_string(injected.frozen_at) +
                                        " (fault injection): it hung";
    const std::string said = qemu.last_words();
    const std::string quote = said.empty() ? "" : " (it said: " + said + ")";
    if (qemu.exited()) return "the emulator " + qemu.exit_text() + quote;
    return "the emulator still runs but sent no accepted frame" + quote;
  }
};

// Starts the emulator on the image and binds the session: waits for Hello (until start_deadline_ns), checks it
// names `device` and a Config of `config.size()` bytes, sends the configuration, waits for the verdict.
// Returns "" on success (bus.verdict says whether the controller accepted it), else what went wrong.
std::string open_target_session(TargetBus& bus, std::uint32_t session, std::uint32_t sender,
                                std::span<const std::uint8_t> config, std::int64_t start_deadline_ns);

// After the loop: asks for the profile (Stop), waits for it until deadline_ns and for the emulator to exit.
// false: no profile came (the emulator is gone or hung); the emulator is ended either way.
bool finish_target_session(TargetBus& bus, std::int64_t deadline_ns);

// report.json timing.target: the image's execution profile at the stated core clocks.
nlohmann::json target_timing_json(const TargetBus& bus, std::int64_t tick_ns);
// report.json link.target: what each end refused, what was injected, the emulator.
nlohmann::json target_link_json(TargetBus& bus);

template <>
class FrameEndpoint<TargetBus> : public EndpointBook {
 public:
  FrameEndpoint(TargetBus& bus, const GuardConfig& guard, const msg::DeviceSignals& /*signals: TargetBus::set_device*/)
      : EndpointBook(guard), bus_(bus) {
    guard_.bind(LinkEnvelope{bus.image_sender, guard.session, 0, 0});
  }

  bool send(const msg::AnySensorFrame& f, std::int64_t /*sim_time_us*/) {
    last_ = f;
    have_last_ = true;
    return transmit(true);
  }
  bool send(const msg::AnyActuatorFrame&, std::int64_t) { return false; }  // the plant sends sensor frames only

  bool resend() {
    if (!have_last_) return false;
    ++counters_.resent;
    return transmit(false);
  }

  template <class Frame>
  RxStatus receive(std::int64_t deadline_ns, Frame& out, std::int64_t* sim_time_us = nullptr) {
    for (;;) {
      firmware::link::TargetFrameView f;
      const std::uint64_t foreign_before = bus_.decoder.counters().foreign;
      const RxStatus s = bus_.next(deadline_ns, f);
      if (const std::uint64_t d = bus_.decoder.counters().foreign - foreign_before; d > 0) {
        for (std::uint64_t i = 0; i < d; ++i) guard_.count(GuardVerdict::kForeign);
      }
      if (s != RxStatus::kMessage) {
        if (s == RxStatus::kTimeout) ++counters_.timeouts;
        return s;
      }
      ++counters_.received;
      if constexpr (std::is_same_v<Frame, msg::AnyActuatorFrame>) {
        if (f.kind == firmware::link::TargetFrameKind::kActuator) {
          out = TargetBus::actuator_of(f);
          if (sim_time_us != nullptr) *sim_time_us = 0;
          return RxStatus::kMessage;
        }
      }
      if (f.kind == firmware::link::TargetFrameKind::kProfile) {
        std::memcpy(&bus_.profile, f.payload.data(), sizeof bus_.profile);
        bus_.have_profile = true;
        continue;
      }
      ++counters_.rejected_malformed;  // a kind the loop has no use for now
    }
  }

  void bind_to_last() {}  // bound in the handshake (open_target_session)

  std::string peer_state() { return bus_.peer_state(); }

 private:
  bool transmit(bool first) {
    const auto k = static_cast<std::int64_t>(last_.tick);
    TargetFaults& fl = bus_.faults;
    if (first && k == fl.kill_at) {
      bus_.qemu.kill_now();
      bus_.injected.killed_at = k;
    }
    if (first && k == fl.freeze_at) {
      bus_.qemu.freeze();
      bus_.injected.frozen_at = k;
    }
    if (first && TargetFaults::covers(fl.skip_from, fl.skip_count, k)) {
      (void)bus_.encode_sensor(last_);  // a counter value unsent
      ++bus_.injected.skipped;
    }
    std::span<const std::uint8_t> bytes;
    if (first && TargetFaults::covers(fl.stale_from, fl.stale_count, k) && last_wire_size_ > 0) {
      bytes = std::span<const std::uint8_t>(last_wire_.data(), last_wire_size_);  // the previous bytes again
      ++bus_.injected.stale;
    } else {
      bytes = bus_.encode_sensor(last_);
      std::memcpy(last_wire_.data(), bytes.data(), bytes.size());
      last_wire_size_ = bytes.size();
    }
    std::array<std::uint8_t, firmware::link::kMaxTargetWire> corrupted{};
    if (first && TargetFaults::covers(fl.corrupt_from, fl.corrupt_count, k)) {
      std::memcpy(corrupted.data(), bytes.data(), bytes.size());
      std::uint8_t& b = corrupted[bytes.size() / 2];
      b = b == 0xFF ? 0xFE : static_cast<std::uint8_t>(b + 1);  // never 0: the frame stays one frame
      bytes = std::span<const std::uint8_t>(corrupted.data(), bytes.size());
      ++bus_.injected.corrupted;
      ++counters_.corrupted_by_fault;
    }
    if (lost_on_the_way()) return true;  // --loss: the lockstep resend recovers it
    if (!bus_.write(bytes)) {
      ++counters_.send_errors;
      return false;
    }
    ++counters_.sent;
    return true;
  }

  TargetBus& bus_;
  msg::AnySensorFrame last_{};
  bool have_last_{false};
  std::array<std::uint8_t, firmware::link::kMaxTargetWire> last_wire_{};
  std::size_t last_wire_size_{0};
};

}  // namespace gyrostab::hil
