// The controller image on the emulated target behind the ControllerPort interface (controller_port.hpp), for
// `gyrostab replay LOG --target` (docs/pil.md): step(k, frame, out) sends the recorded sensor frame over the
// target link and waits for the image's actuator frame of tick k. The replay then compares it with the
// recorded one byte for byte, as it does for the host build of the controller.
// A link that fails (the emulator died or hung: no answer within the receive timeout) leaves `out` as the
// drive watchdog's command and marks the port lost; the replay stops at the next compare with the reason.
#pragma once

#include <cstring>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/msg/fault_bits.hpp"
#include "hil/link/actuator_frame_check.hpp"
#include "hil/target/target_endpoint.hpp"
#include "tools/loop/controller_port.hpp"
#include "tools/run/target_link_setup.hpp"

namespace gyrostab::tools {

class TargetControllerPort final : public ControllerPort {
 public:
  TargetControllerPort(hil::TargetBus& bus, std::int64_t timeout_ns, std::int64_t resend_ns)
      : bus_(bus), timeout_ns_(timeout_ns), resend_ns_(resend_ns) {}

  void step(std::uint64_t tick, const msg::AnySensorFrame* frame, msg::AnyActuatorFrame& out) override {
    out = hil::drive_watchdog_command(tick);
    if (lost_ || frame == nullptr) return;  // a replayed log always has the frame
    const std::int64_t lost_at = hil::monotonic_ns() + timeout_ns_;
    bool sent = bus_.write(bus_.encode_sensor(*frame));
    for (;;) {
      const std::int64_t now = hil::monotonic_ns();
      if (now >= lost_at || !sent) {
        lost_ = true;
        lost_tick_ = static_cast<std::int64_t>(tick);
        return;
      }
      firmware::link::TargetFrameView f;
      const hil::RxStatus s = bus_.next(std::min(lost_at, now + resend_ns_), f);
      if (s == hil::RxStatus::kError) {
        lost_ = true;
        lost_tick_ = static_cast<std::int64_t>(tick);
        return;
      }
      if (s == hil::RxStatus::kTimeout) {  // resend: the image answers a repeat with the same command
        sent = bus_.write(bus_.encode_sensor(*frame));
        continue;
      }
      if (f.kind != firmware::link::TargetFrameKind::kActuator) continue;
      const msg::AnyActuatorFrame a = hil::TargetBus::actuator_of(f);
      if (a.tick != tick) continue;  // an answer to an earlier tick
      out = a;
      last_status_ = a.status;
      return;
    }
  }
  bool in_safe_state() const override { return (last_status_ & msg::bit(msg::FaultBit::kSafeState)) != 0; }
  void acknowledge() override {}  // the image's monitor is its own; a replay never acknowledges
  firmware::MonitorState monitor_state() const override {
    return in_safe_state() ? firmware::MonitorState::kSafe : firmware::MonitorState::kNormal;
  }
  std::uint32_t monitor_status() const override { return last_status_; }
  nlohmann::json report() const override { return nlohmann::json::object(); }

  bool lost() const { return lost_; }
  std::int64_t lost_tick() const { return lost_tick_; }

 private:
  hil::TargetBus& bus_;
  std::int64_t timeout_ns_;
  std::int64_t resend_ns_;
  bool lost_{false};
  std::int64_t lost_tick_{-1};
  std::uint32_t last_status_{0};
};

}  // namespace gyrostab::tools
