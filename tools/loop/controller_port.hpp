// The firmware controller as every run mode sees it: one virtual call per tick, the same
// step(tick, frame or nullptr, out) the target runs (firmware/app/controller_runtime.hpp). The run modes (in
// process, controller process, replay) are compiled once against this port; ControllerPortOf<C> holds the
// device's controller in place (controllers are neither copyable nor movable: the scheduler holds `this`).
// Docs: docs/architecture.md.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <utility>

#include "firmware/fault/fault_monitor.hpp"
#include "firmware/msg/any_frame.hpp"
#include "tools/loop/controller_report.hpp"

namespace gyrostab::tools {

class ControllerPort {
 public:
  virtual ~ControllerPort() = default;

  virtual void step(std::uint64_t tick, const msg::AnySensorFrame* frame, msg::AnyActuatorFrame& out) = 0;
  // The safe command is out: latched safe state, or still awaiting the first good frame.
  virtual bool in_safe_state() const = 0;
  // The fault monitor's recovery request (firmware/fault/fault_monitor.hpp): the safe state is left on the
  // next good frame.
  virtual void acknowledge() = 0;
  virtual firmware::MonitorState monitor_state() const = 0;
  // The fault monitor's status bits (kSafeState, kHoldingLastGood and the causes, msg/fault_bits.hpp).
  virtual std::uint32_t monitor_status() const = 0;
  // report.json timing.controller: the scheduler's per-task counters and the fault monitor's.
  virtual nlohmann::json report() const = 0;
};

// Holds the controller in place and converts between the run modes' device-independent frames and the
// controller's typed ones (one copy of each frame per tick).
template <class Controller>
class ControllerPortOf final : public ControllerPort {
 public:
  using SensorFrame = typename Controller::SensorFrame;
  using ActuatorFrame = typename Controller::ActuatorFrame;

  template <class... Args>
  explicit ControllerPortOf(Args&&... args) : c_(std::forward<Args>(args)...) {}

  void step(std::uint64_t tick, const msg::AnySensorFrame* frame, msg::AnyActuatorFrame& out) override {
    ActuatorFrame command{};
    if (frame != nullptr) {
      SensorFrame in{};
      msg::from_any(*frame, in);
      c_.step(tick, &in, command);
    } else {
      c_.step(tick, nullptr, command);
    }
    msg::to_any(command, out);
  }
  bool in_safe_state() const override {
    const firmware::MonitorState s = c_.monitor_state();
    return s == firmware::MonitorState::kSafe || s == firmware::MonitorState::kAwaitingFirstFrame;
  }
  void acknowledge() override { c_.acknowledge(); }
  firmware::MonitorState monitor_state() const override { return c_.monitor_state(); }
  std::uint32_t monitor_status() const override { return c_.monitor_status(); }
  nlohmann::json report() const override { return controller_report(c_); }

  Controller& controller() { return c_; }

 private:
  Controller c_;
};

template <class Controller, class... Args>
std::unique_ptr<ControllerPort> make_controller_port(Args&&... args) {
  return std::make_unique<ControllerPortOf<Controller>>(std::forward<Args>(args)...);
}

}  // namespace gyrostab::tools
