// The DeviceScene of a device (device.hpp), from a traits struct: it owns the scene struct read by the
// device's schema and builds each side of the loop from it — the plant as PlantPortOf<Binding> (or the
// traits' own make_plant, for a plant with variants), the controller as ControllerPortOf<Controller> on the
// scene's `controller` configuration. The traits:
//   using Scene = ...;  using Binding = ...;  using Controller = ...;
//   static std::vector<std::string> columns(const Scene&);               // the CSV columns
//   (optional) static nlohmann::json limits(const Scene&);               // report.json "limits"
//   (optional) static hil::ActuatorLimits actuator_limits(const Scene&); // what a drive accepts
//   (optional) static std::unique_ptr<PlantPort> make_plant(const Scene&, const PlantOptions&);
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tools/devices/device.hpp"

namespace gyrostab::tools {

template <class Traits>
class DeviceSceneOf final : public DeviceScene {
 public:
  using Scene = typename Traits::Scene;

  explicit DeviceSceneOf(std::unique_ptr<Scene> s) : s_(std::move(s)) {}

  const LoopConfig& loop() const override { return s_->loop; }
  std::vector<std::string> columns() const override { return Traits::columns(*s_); }
  hil::ActuatorLimits actuator_limits() const override {
    if constexpr (requires(const Scene& s) { Traits::actuator_limits(s); }) {
      return Traits::actuator_limits(*s_);
    } else {
      return hil::ActuatorLimits{};
    }
  }
  nlohmann::json limits() const override {
    if constexpr (requires(const Scene& s) { Traits::limits(s); }) {
      return Traits::limits(*s_);
    } else {
      return nlohmann::json::object();
    }
  }
  std::unique_ptr<PlantPort> make_plant(const PlantOptions& options) const override {
    if constexpr (requires(const Scene& s) { Traits::make_plant(s, options); }) {
      return Traits::make_plant(*s_, options);
    } else {
      return make_plant_port<typename Traits::Binding>(*s_);
    }
  }
  std::unique_ptr<ControllerPort> make_controller() const override {
    return make_controller_port<typename Traits::Controller>(s_->controller);
  }
  std::vector<std::uint8_t> controller_config() const override { return config_bytes(s_->controller); }
  const motion::SceneBaseMotion* base_motion() const override {
    if constexpr (requires(const Scene& s) { Traits::base_motion(s); }) {
      return Traits::base_motion(*s_);
    } else {
      return nullptr;
    }
  }

 private:
  std::unique_ptr<Scene> s_;
};

}  // namespace gyrostab::tools
