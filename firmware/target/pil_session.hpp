// One device controller as a processor-in-the-loop image (firmware/target/images/<device>_image.cpp, built by
// tools/cross/build-firmware-arm for a Cortex-M7): the real controller of firmware/app/ — fault monitor,
// scheduler, the device's laws and drive loops — configured over the target link and stepped in lockstep with
// the plant on the host (docs/pil.md). The session, in frames of firmware/link/target_frame.hpp:
//   1. boot: the image sends Hello (its device name, sizeof(Config), the profile clock's resolution);
//   2. the host sends Config (the scene's controller configuration as the struct's bytes); a frame of another
//      size is answered with a refusal; otherwise the controller is built in static storage, the same
//      Config::check() as on the host runs in its constructor, and the verdict goes back (a refused controller
//      runs, but only ever commands the safe state with kConfigRefused, as on the host). The Config frame
//      binds the session: from then on frames of another session or sender are refused (counted);
//   3. per plant tick, one Sensor frame for tick k; the controller steps tick k on it and answers with the
//      Actuator frame of tick k. The rules mirror the controller process over LCM and CAN
//      (tools/run/controller_process.cpp):
//        - a frame for the next tick is stepped on;
//        - a frame for the tick just answered is a resend (the plant did not get the answer): the answer is
//          sent again, the controller is not stepped;
//        - a frame for a later tick (at most kMaxAheadTicks) means the plant withheld the ones between: those
//          ticks are stepped without a frame (their answers sent), then this one;
//        - a refused frame (CRC, framing, alive counter, session, ...) is the tick's frame lost: the next tick
//          is stepped without a frame and answered. The fault monitor then holds the last good frame for one
//          tick and latches the safe state on the second (kSensorMissing), exactly as when a CAN set is lost;
//        - anything older is late: counted, not answered;
//   4. ProfileRequest → the Profile frame (TargetProfile: the scheduler's per-task counters, the step, the
//      link's cost, the refusals); Stop → the Profile frame, then the emulation ends with exit status 0.
// Nothing here allocates or throws; the session's state is static. The controller is built once: a second
// Config frame is refused as out of sequence (kind).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#include "firmware/link/target_frame.hpp"
#include "firmware/msg/any_frame.hpp"
#include "firmware/scheduler/perf_counter.hpp"
#include "firmware/target/instruction_clock.hpp"
#include "firmware/target/target_channel.hpp"

namespace gyrostab::firmware::target {

inline constexpr std::uint32_t kTargetSenderId = 0x314C4950u;  // "PIL1": the image's id on the link
inline constexpr std::uint64_t kMaxAheadTicks = 1000;

template <class Controller>
class PilSession {
 public:
  using Config = typename Controller::Config;
  static_assert(sizeof(Config) <= link::kMaxConfigBytes, "the configuration does not fit one target frame");

  explicit PilSession(const char* image_name) : image_name_(image_name) {}

  [[noreturn]] void run() {
    InstructionClock::start();
    channel_.open();
    send_hello();
    for (;;) {
      std::span<const std::uint8_t> wire;
      if (!next_frame(wire)) semihosting::exit(3);  // the host closed the link
      link::TargetFrameView f;
      const auto t0 = clock_();
      const link::TargetRxVerdict v = decoder_.judge(wire, f);
      if (v != link::TargetRxVerdict::kOk) {
        if (controller_ != nullptr) step_and_answer(nullptr, t0);  // this tick's frame is lost
        continue;
      }
      switch (f.kind) {
        case link::TargetFrameKind::kConfig: on_config(f); break;
        case link::TargetFrameKind::kSensor: on_sensor(f, t0); break;
        case link::TargetFrameKind::kProfileRequest: send_profile(); break;
        case link::TargetFrameKind::kStop:
          send_profile();
          semihosting::exit(0);
        default: break;
      }
    }
  }

 private:
  bool next_frame(std::span<const std::uint8_t>& wire) {
    for (;;) {
      while (pos_ < have_) {
        if (decoder_.collect(buf_[pos_++], wire)) return true;
      }
      have_ = channel_.read_some(buf_, sizeof buf_);
      pos_ = 0;
      if (have_ == 0) return false;
    }
  }

  void send(std::span<const std::uint8_t> bytes) { channel_.write(bytes.data(), bytes.size()); }

  void send_hello() {
    link::TargetHello h{};
    for (std::size_t i = 0; i + 1 < sizeof h.image && image_name_[i] != '\0'; ++i) h.image[i] = image_name_[i];
    h.config_bytes = sizeof(Config);
    h.clock_ns_per_count = clock_.ns_per_count;
    h.sensor_signals = static_cast<std::uint16_t>(msg::signal_count_v<typename Controller::SensorFrame>);
    h.command_signals = static_cast<std::uint16_t>(msg::signal_count_v<typename Controller::ActuatorFrame>);
    send(encoder_.encode(link::TargetFrameKind::kHello, h));
  }

  void on_config(const link::TargetFrameView& f) {
    link::TargetConfigVerdict v{};
    if (controller_ != nullptr) {
      ++decoder_.counters().kind;  // configured once; the counters say a second one came
      return;
    }
    encoder_.set_session(f.session);
    if (f.payload.size() != sizeof(Config)) {
      copy_text(v.reason, "configuration frame of the wrong size for this image's Config");
      v.value = static_cast<double>(f.payload.size());
      v.lower = v.upper = static_cast<double>(sizeof(Config));
      send(encoder_.encode(link::TargetFrameKind::kConfigVerdict, v));
      return;
    }
    decoder_.bind(f.session, f.sender);
    std::memcpy(&config_, f.payload.data(), sizeof(Config));
    controller_ = ::new (storage_) Controller(config_, clock_);
    const auto& check = controller_->config_check();
    v.accepted = check.ok ? 1u : 0u;
    v.value = check.value;
    v.lower = check.lower;
    v.upper = check.upper;
    copy_text(v.reason, check.reason);
    send(encoder_.encode(link::TargetFrameKind::kConfigVerdict, v));
  }

  void on_sensor(const link::TargetFrameView& f, std::int64_t t0) {
    if (controller_ == nullptr) {
      ++decoder_.counters().kind;  // no configuration yet: nothing to step
      return;
    }
    std::memcpy(&sensor_, f.payload.data(), sizeof sensor_);
    const std::uint64_t k = sensor_.tick;
    if (k == next_tick_) {
      step_and_answer(&sensor_, t0);
    } else if (answered_ && k + 1 == next_tick_) {
      ++profile_.republished;
      send(encoder_.encode(link::TargetFrameKind::kActuator, command_));
    } else if (k > next_tick_ && k - next_tick_ <= kMaxAheadTicks) {
      while (next_tick_ < k) step_and_answer(nullptr, clock_());
      step_and_answer(&sensor_, clock_());
    } else {
      ++late_;  // a tick already stepped past: nothing to do
    }
  }

  // Steps next_tick_ and sends its command. t0: when the frame's handling began (link cost = everything in
  // this tick but the step).
  void step_and_answer(const typename Controller::SensorFrame* frame, std::int64_t t0) {
    const std::int64_t t1 = clock_();
    controller_->step(next_tick_, frame, command_);
    const std::int64_t t2 = clock_();
    profile_.step.record(t1, t2 - t1, 0);
    if (frame == nullptr) ++profile_.missing;
    ++next_tick_;
    answered_ = true;
    const std::span<const std::uint8_t> bytes = encoder_.encode(link::TargetFrameKind::kActuator, command_);
    const std::int64_t t3 = clock_();
    profile_.link.record(t0, (t1 - t0) + (t3 - t2), 0);
    send(bytes);
  }

  void send_profile() {
    profile_.ticks = next_tick_;
    profile_.clock_ns_per_count = clock_.ns_per_count;
    if (controller_ != nullptr) {
      profile_.control = controller_->control_counters();
      profile_.drive = controller_->drive_counters();
      profile_.monitor_status = controller_->monitor_status();
    }
    profile_.rx = decoder_.counters();
    profile_.late = late_;
    send(encoder_.encode(link::TargetFrameKind::kProfile, profile_));
  }

  template <std::size_t N>
  static void copy_text(char (&out)[N], const char* text) {
    std::size_t i = 0;
    for (; text != nullptr && i + 1 < N && text[i] != '\0'; ++i) out[i] = text[i];
    out[i] = '\0';
  }

  const char* image_name_;
  InstructionClock clock_{};
  TargetChannel channel_{};
  link::TargetFrameEncoder encoder_{kTargetSenderId, 0};
  link::TargetFrameDecoder decoder_{/*from_host=*/true,
                                   link::target_frame_sizes(msg::signal_count_v<typename Controller::SensorFrame>,
                                                            msg::signal_count_v<typename Controller::ActuatorFrame>)};
  std::uint8_t buf_[256]{};
  std::size_t have_{0};
  std::size_t pos_{0};
  Config config_{};
  alignas(Controller) unsigned char storage_[sizeof(Controller)]{};
  Controller* controller_{nullptr};
  typename Controller::SensorFrame sensor_{};
  typename Controller::ActuatorFrame command_{};
  std::uint64_t next_tick_{0};
  bool answered_{false};
  std::uint64_t late_{0};
  link::TargetProfile profile_{};
};

// The image's entry: the session in static storage (no heap), for ever.
template <class Controller>
[[noreturn]] void run_pil_image(const char* image_name) {
  static PilSession<Controller> session(image_name);
  session.run();
}

}  // namespace gyrostab::firmware::target
