// A test's controller as a ControllerPort: any class with step(tick, frame or nullptr, out) on typed frames
// (the union fixture's, tests/support/union_frames.hpp), without the firmware
// runtime's fault monitor (never in its safe state, nothing to acknowledge, no counters).
#pragma once

#include <nlohmann/json.hpp>
#include <utility>

#include "tests/support/union_frames.hpp"
#include "tools/loop/controller_port.hpp"

namespace gyrostab::testing {

template <class Law>
class LawPort final : public tools::ControllerPort {
 public:
  template <class... Args>
  explicit LawPort(Args&&... args) : law_(std::forward<Args>(args)...) {}
  void step(std::uint64_t tick, const msg::AnySensorFrame* frame, msg::AnyActuatorFrame& out) override {
    msg::SensorFrame in{};
    msg::ActuatorFrame command{};
    if (frame != nullptr) msg::from_any(*frame, in);
    law_.step(tick, frame != nullptr ? &in : nullptr, command);
    msg::to_any(command, out);
  }
  bool in_safe_state() const override { return false; }
  void acknowledge() override {}
  firmware::MonitorState monitor_state() const override { return firmware::MonitorState::kNormal; }
  std::uint32_t monitor_status() const override { return 0; }
  nlohmann::json report() const override { return nlohmann::json::object(); }
  Law& law() { return law_; }

 private:
  Law law_;
};

}  // namespace gyrostab::testing
