// The power stabilizer in the registry (tools/devices/registry.cpp), and its scene for the run modes.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/platform/posix/monotonic_clock.hpp"
#include "gyrostab_signals/power_stabilizer_outputs.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_study.hpp"

namespace gyrostab::tools {
namespace {

using Controller = firmware::BasicPowerStabilizerController<firmware::posix::MonotonicClock>;

class PowerStabilizerDeviceScene final : public DeviceScene {
 public:
  explicit PowerStabilizerDeviceScene(std::unique_ptr<PowerStabilizerScene> s) : s_(std::move(s)) {}

  const LoopConfig& loop() const override { return s_->loop; }
  std::vector<std::string> columns() const override { return power_stabilizer_columns(*s_); }
  std::vector<std::string> row_columns() const override {
    std::vector<std::string> c;
    for (const ColumnSpec& spec : msg::power_stabilizer::kColumns) c.emplace_back(spec.name);
    return c;
  }
  nlohmann::json limits() const override {
    const auto& l = s_->controller.loops;
    if (s_->back_emf()) return {{"motor_voltage_limit_V", l.voltage_limit_V}};
    nlohmann::json j{{"motor_torque_limit_Nm", l.torque_limit_Nm[0]}};
    if (s_->dc_drive()) {
      j["drive_current_limit_A"] = s_->plant.drive.motor.current_limit;
      j["drive_voltage_limit_V"] = s_->plant.drive.motor.voltage_limit;
    }
    return j;
  }
  std::unique_ptr<PlantPort> make_plant(const PlantOptions& o) const override {
    if (s_->precession()) return make_power_stabilizer_precession(*s_, o);
    if (s_->elastic()) return make_power_stabilizer_elastic(*s_);
    if (s_->dc_drive()) return make_power_stabilizer_dc(*s_);
    return make_power_stabilizer_rigid(*s_);
  }
  std::unique_ptr<ControllerPort> make_controller() const override {
    return make_controller_port<Controller>(s_->controller);
  }
  std::vector<std::uint8_t> controller_config() const override { return config_bytes(s_->controller); }
  const motion::SceneBaseMotion* base_motion() const override { return &s_->plant.base; }

 private:
  std::unique_ptr<PowerStabilizerScene> s_;
};

}  // namespace

bool power_stabilizer_column_option(const PowerStabilizerScene& s, std::string_view when) {
  if (when == "dc_motor") return s.dc_drive();
  if (when == "voltage_driven") return s.dc_drive() || s.back_emf();
  if (when == "elastic") return s.elastic();
  return false;
}

std::vector<std::string> power_stabilizer_columns(const PowerStabilizerScene& s) {
  std::vector<std::string> c;
  for (const ColumnSpec& spec : msg::power_stabilizer::kColumns) {
    if (spec.when.empty() || power_stabilizer_column_option(s, spec.when)) c.emplace_back(spec.name);
  }
  return c;
}

std::unique_ptr<DeviceScene> read_power_stabilizer(SceneReader& r) {
  auto s = std::make_unique<PowerStabilizerScene>();
  if (!read_power_stabilizer_scene(r, *s)) return nullptr;
  return std::make_unique<PowerStabilizerDeviceScene>(std::move(s));
}

extern const DeviceDescriptor kPowerStabilizer{
    .name = "power_stabilizer",
    .summary =
        "The two-axis power gyro stabilizer of Magnus §14.3, (14.19)-(14.40) "
        "(sim/plants/power_stabilizer_plant.hpp, docs/models/power-stabilizer.md): the full nonlinear gimbal "
        "gyro (10.4) on a rolling base with disturbance torque steps, encoders and rate gyros, under the "
        "firmware's stabilization loops (gains checked against (14.25) / (14.30) at start-up). The option "
        "keys (`structure`, `motor`, `fidelity`, `[drive] kind`) pick the plant's variant once at start-up; "
        "an option that is off costs nothing. Shipped: `sim/scenes/power-stabilizer.toml` (ideal torque "
        "motors), `sim/scenes/power-stabilizer-precession.toml` (the same in the precession model P0, "
        "compared with the full model), `sim/scenes/power-stabilizer-drive.toml` (DC motors, gears, current "
        "loops at 10 kHz). Integrators: `gyro-exponential` (default) or `rk4` for the rigid gyro; `rk4` only "
        "when elastic or in the precession model.",
    .figures =
        "Figures: `nutation_frequency_rad_s`, `nutation_decay_rate_per_s` (measured: the root of a recurrence "
        "fitted to α at the law's rate after the inner-axis step, else the first step, with the sensor errors "
        "as inputs; `_extrema`: from the extrema of α') and `_predicted` ((14.23), or (14.29) with back_emf; A with "
        "reflected inertia and, elastic, A^P) and `_predicted_sampled` (the loop sampled with the hold and the "
        "latency, docs/sampled-data.md), linearised at `nutation_operating_point_beta_rad` (β0, or M1/k1 when "
        "the platform load acts from before the window `nutation_window_from_s`-`nutation_window_to_s`), "
        "`sampled_loop_max_abs_z`, "
        "`steady_*` and `_predicted` (14.21), `gain_margin`, motor torque peaks; dc_motor: "
        "`motor{1,2}_current_peak_A`, `motor{1,2}_voltage_peak_V`, `reflected_inertia_kg_m2`, "
        "`drive_peak_torque_Nm`; back_emf: `r_max_V_per_rad`, `motor1_voltage_peak_V`; elastic: "
        "`platform_frequency_rad_s_predicted` (14.37), `effective_stiffness_Nm_per_rad_predicted` (14.35), "
        "`alpha_over_phi_predicted` (14.33), `steady_platform_rad`; with `beta0_deg` ≠ 0: "
        "`operating_point_beta_rad`; precession: the "
        "measured nutation is null. report.json `\"plant\"`: model, fidelity, the components in the loop, "
        "`state_size`, integrator. `\"reduced_model\"` (precession): `epsilon` = ω_P/ω_N, the a-priori "
        "bounds `alpha_rad_bound`, `beta_rad_bound` (docs/models/gimbal-gyro.md#precession-model-p0), "
        "`measured_error` (largest and RMS |P0 − full| of α, β), `within_bounds`, `full_model`; "
        "`timing.reduced_model`: both loops' wall times. `\"drift\"` (drift_period_s > 0): `max_departure` "
        "per signal, `max_departure_so_far` at 10³ … 10⁷ ticks, `bound_rad` (two encoder counts), "
        "`within_bound`. docs/extreme.md has the stiff and extreme cases.",
    .read = read_power_stabilizer,
    .doc = power_stabilizer_doc,
    .accuracy = power_stabilizer_accuracy,
};

}  // namespace gyrostab::tools
