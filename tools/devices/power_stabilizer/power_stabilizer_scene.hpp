// A power stabilizer scene (Magnus §14.3, (14.19)-(14.40)), as read and checked: the plant's options, the
// loop, the gyro as entered, the composed plant's parameters (sim/plants/power_stabilizer_plant.hpp: the gyro
// as integrated), the firmware controller's configuration (firmware/app/power_stabilizer_controller.hpp), the
// report's settings, and what the checks derived (the loop at the operating point, the reduced model's
// expected error and the full model's loop for the comparison). Member initializers are the scene's
// defaults; the keys: power_stabilizer_schema.cpp, docs/scenes.md.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/app/power_stabilizer_controller.hpp"
#include "sim/plants/power_stabilizer_plant.hpp"
#include "tools/devices/device.hpp"
#include "tools/scene/loop_config.hpp"

namespace gyrostab::tools {

enum class PowerStructure : std::uint8_t { kRigid, kElastic };
enum class PowerMotor : std::uint8_t { kTorque, kBackEmf };
enum class PowerFidelity : std::uint8_t { kFull, kPrecession };
enum class PowerDrive : std::uint8_t { kTorque, kDcMotor };

// The controller's configuration a scene starts from: the firmware's, without commanded rate damping.
inline firmware::PowerStabilizerControllerConfig power_stabilizer_controller_defaults() {
  firmware::PowerStabilizerControllerConfig c;
  c.loops.d1 = 0.0;
  c.loops.d2 = 0.0;
  return c;
}

struct PowerStabilizerScene {
  PowerStructure structure{PowerStructure::kRigid};
  PowerMotor motor{PowerMotor::kTorque};
  PowerFidelity fidelity{PowerFidelity::kFull};
  PowerDrive drive{PowerDrive::kTorque};
  LoopConfig loop;
  models::GimbalGyroParams gyro{};  // as entered in [gyro]
  double rpm{0.0};                  // [gyro] rpm; H = C^R rpm 2π/60 goes to plant.H
  plants::PowerStabilizerPlantParams plant;
  models::ElasticPlatform platform{};  // as entered
  int base_roll_axis{1};               // [base] roll_axis: 1 or 2
  double rate_bandwidth_hz{0.0};       // [sensors]: 0 = no low-pass
  int rate_filter_order{2};
  double rate_damping{std::numbers::sqrt2 / 2};
  double current_loop_bandwidth_rad_s{2000.0};  // [drive]
  double torque_limit_Nm{100.0};                // [controller], both axes
  firmware::PowerStabilizerControllerConfig controller{power_stabilizer_controller_defaults()};
  double measure_window_s{1.5};  // [report] nutation_window_s
  double drift_period_s{0.0};    // [report]: periodic drift monitor (0: off)
  double drift_from_s{0.0};

  // Derived by the checks.
  // The loop linearised at the inner gimbal's initial angle β0 (= controller.loops when β0 = 0): A → I(β0),
  // H → H cos β0. The `_predicted` nutation figures use it.
  firmware::PowerStabilizerConfig op_loops;
  // The loop linearised where the nutation is measured (nutation_window): at β0, or at the platform load's
  // steady deflection (14.21) when that load acts from before the window. The nutation `_predicted` figures
  // use it.
  firmware::PowerStabilizerConfig measure_loops;
  double measure_beta_rad{0.0};
  // fidelity = precession: the full model's loop for the comparison (its integrator and the sub-steps its
  // own step validation needs) and the expected error.
  LoopConfig full_loop;
  nlohmann::json reduced_expected;

  bool elastic() const { return structure == PowerStructure::kElastic; }
  bool back_emf() const { return motor == PowerMotor::kBackEmf; }
  bool precession() const { return fidelity == PowerFidelity::kPrecession; }
  bool dc_drive() const { return drive == PowerDrive::kDcMotor; }
};

// Reads and checks the scene (the problems in the reader); false when refused.
bool read_power_stabilizer_scene(SceneReader& r, PowerStabilizerScene& s);
std::unique_ptr<DeviceScene> read_power_stabilizer(SceneReader& r);
SceneDoc power_stabilizer_doc();

// The CSV columns of the scene's variant: the signal table's columns (power_stabilizer_signals.toml) without
// those `when` an option the scene does not take (they depend on the drive, the motor and the structure only).
std::vector<std::string> power_stabilizer_columns(const PowerStabilizerScene& s);
// Whether the scene takes a column's `when` option: "dc_motor" ([drive] kind = "dc_motor"), "voltage_driven"
// (the axis-1 motor takes a voltage: dc_motor drives or [gyro] motor = "back_emf"), "elastic"; false for any
// other.
bool power_stabilizer_column_option(const PowerStabilizerScene& s, std::string_view when);

// The plant of each variant group, one translation unit each (power_stabilizer_<group>.cpp).
std::unique_ptr<PlantPort> make_power_stabilizer_rigid(const PowerStabilizerScene& s);
std::unique_ptr<PlantPort> make_power_stabilizer_dc(const PowerStabilizerScene& s);
std::unique_ptr<PlantPort> make_power_stabilizer_elastic(const PowerStabilizerScene& s);
std::unique_ptr<PlantPort> make_power_stabilizer_precession(const PowerStabilizerScene& s, const PlantOptions& o);

}  // namespace gyrostab::tools
