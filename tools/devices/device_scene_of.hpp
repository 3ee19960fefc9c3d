// The DeviceScene of a device (device.hpp), from a traits struct: it owns the scene struct read by the
// device's schema and builds each side of the loop from it — the plant as PlantPortOf<Binding> (or the
// traits' own make_plant, for a plant with variants), the controller as ControllerPortOf<Controller> on the
// scene's `controller` configuration. The traits:
//   using Scene = ...;  using Binding = ...;  using Controller = ...;
//   the CSV columns: the binding's Record (its signal table's columns, gyrostab_signals/<device>_outputs.hpp),
//     with (optional) static bool column_option(const Scene&, std::string_view when) for columns that exist
//     only with an option;
//   (optional) static nlohmann::json limits(const Scene&);               // report.json "limits"
//   (optional) static hil::ActuatorLimits actuator_limits(const Scene&); // what a drive accepts
//   (optional) static std::unique_ptr<PlantPort> make_plant(const Scene&, const PlantOptions&);
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tools/devices/device.hpp"
#include "tools/signals/output_spec.hpp"

namespace gyrostab::tools {

template <class Traits>
class DeviceSceneOf final : public DeviceScene {
 public:
  using Scene = typename Traits::Scene;

  explicit DeviceSceneOf(std::unique_ptr<Scene> s) : s_(std::move(s)) {}

  const LoopConfig& loop() const override { return s_->loop; }
  std::vector<std::string> columns() const override {
    std::vector<std::string> c;
    for (const ColumnSpec& spec : table_columns()) {
      if (spec.when.empty() || column_option(spec.when)) c.emplace_back(spec.name);
    }
    return c;
  }
  std::vector<std::string> row_columns() const override {
    std::vector<std::string> c;
    for (const ColumnSpec& spec : table_columns()) c.emplace_back(spec.name);
    return c;
  }
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
  static constexpr std::span<const ColumnSpec> table_columns() {
    return device_outputs(static_cast<const typename Traits::Binding::Record*>(nullptr)).columns;
  }
  bool column_option(std::string_view when) const {
    if constexpr (requires(const Scene& s) { Traits::column_option(s, when); }) {
      return Traits::column_option(*s_, when);
    } else {
      return false;
    }
  }

  std::unique_ptr<Scene> s_;
};

}  // namespace gyrostab::tools
