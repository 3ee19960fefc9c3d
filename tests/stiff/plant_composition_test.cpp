// Only what a scene names is in its loop (docs/architecture.md, scenes; docs/extreme.md): the power
// stabilizer's plant is composed at compile time from its options (sim/models/power_stabilizer.hpp,
// tools/devices/power_stabilizer_scene.cpp), an option that is off adds no state and no storage, and the
// runtime options that stay (sensor noise, the base's roll) cost nothing when zero. Deterministic facts only:
// state sizes (kStateSize of the composed types, the report's "plant" block of assembled scenes), empty
// types, storage; the per-tick cost itself is measured by tools/bench/plant_composition_bench.cpp, never
// asserted here.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

#include "sim/drives/gimbal_drive.hpp"
#include "sim/models/base_motion.hpp"
#include "sim/models/power_stabilizer.hpp"
#include "sim/random/seeded_rng.hpp"
#include "sim/sensors/rate_gyro.hpp"
#include "gyrostab_signals/power_stabilizer_outputs.hpp"
#include "tools/commands.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"

namespace gyrostab {
namespace plant_composition_test {

using models::BackEmfMotor, models::ElasticPlatform, models::FixedBase, models::FullGimbal,
    models::HarmonicBaseRotation, models::PrecessionOnly, models::RigidStructure, models::TorqueMotors;

// ---- the composed model types ----------------------------------------------------------------------------

// State: α, β, α', β', H — plus φ, φ' with the elastic platform — and α, β, H in the precession model.
static_assert(models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure>::kStateSize == 5);
static_assert(models::PowerStabilizer<FixedBase, BackEmfMotor, RigidStructure>::kStateSize == 5);
static_assert(models::PowerStabilizer<FixedBase, TorqueMotors, ElasticPlatform>::kStateSize == 7);
static_assert(models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure, PrecessionOnly>::kStateSize == 3);
static_assert(models::PowerStabilizer<FixedBase, BackEmfMotor, RigidStructure, PrecessionOnly>::kStateSize == 3);
// The "off" options are empty types, stored [[no_unique_address]]: no bytes in the plant.
static_assert(std::is_empty_v<TorqueMotors> && std::is_empty_v<RigidStructure> && std::is_empty_v<FullGimbal> &&
              std::is_empty_v<PrecessionOnly>);
static_assert(sizeof(models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure>) <
              sizeof(models::PowerStabilizer<FixedBase, BackEmfMotor, RigidStructure>));
static_assert(sizeof(models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure>) <
              sizeof(models::PowerStabilizer<FixedBase, TorqueMotors, ElasticPlatform>));
// The precession model drops the nutation's gyroscopic pair (no exact-flow integrator applies to it).
template <class P>
concept HasGyroscopicPair = requires(const P& p, const typename P::State& x) { p.gyroscopic_pair(x); };
static_assert(HasGyroscopicPair<models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure>>);
static_assert(!HasGyroscopicPair<models::PowerStabilizer<FixedBase, TorqueMotors, RigidStructure, PrecessionOnly>>);

// ---- assembled scenes: the report's "plant" block ------------------------------------------------------

const char* kBase = R"(
[scene]
name = "composition"
device = "power_stabilizer"
duration_s = 0.5
[loop]
tick_us = 1000
[gyro]
CR = 0.1
rpm = 19098.6
AR = 0.5
AJ = 0.5
BJ = 1.0
CJ = 0.3
AA = 1.0
EXTRA_GYRO
[disturbance]
M1_Nm = 20.0
[sensors]
EXTRA_SENSORS
[controller]
k1 = 200.0
k2 = 200.0
d1 = 5.0
d2 = 5.0
EXTRA_SECTIONS
[output]
plots = false
)";

std::string scene(const std::string& gyro, const std::string& sensors = "", const std::string& sections = "") {
  std::string s = kBase;
  s.replace(s.find("EXTRA_GYRO"), 10, gyro);
  s.replace(s.find("EXTRA_SENSORS"), 13, sensors.empty() ? "rate_noise_density = 0.0" : sensors);
  s.replace(s.find("EXTRA_SECTIONS"), 14, sections);
  return s;
}

nlohmann::json plant_of(const std::string& text) {
  tools::RunRequest req;
  req.scene_path = "composition.toml";
  req.scene_text = text;
  req.write_outputs = false;
  req.progress = false;
  nlohmann::json report;
  req.report_out = &report;
  EXPECT_EQ(tools::run_scene(req), 0) << text;
  return report["plant"];
}

bool lists(const nlohmann::json& plant, const std::string& part) {
  for (const auto& c : plant["components"]) {
    if (c.get<std::string>().find(part) != std::string::npos) return true;
  }
  return false;
}

const char* kDcDrive = R"(
[drive]
kind = "dc_motor"
R_ohm = 0.4
L_H = 0.8e-3
k_t_Nm_per_A = 0.12
J_m_kg_m2 = 6.0e-5
voltage_limit_V = 48.0
current_limit_A = 12.0
gear_ratio = 80.0
current_loop_bandwidth_rad_s = 250.0
)";

TEST(PlantComposition, StateSizeAndStorageShrinkWithEveryComponentLeftOut) {
  const nlohmann::json minimal = plant_of(scene(""));
  EXPECT_EQ(minimal["state_size"].get<int>(), 5);  // the gimbal gyro alone
  EXPECT_EQ(minimal["electrical_states"].get<int>(), 0);
  EXPECT_EQ(minimal["sensor_filter_states"].get<int>(), 0);
  EXPECT_EQ(minimal["components"].size(), 1u) << minimal.dump();
  EXPECT_FALSE(lists(minimal, "noise"));
  EXPECT_FALSE(lists(minimal, "base motion"));

  // Motor electrics: two winding currents, and the two drives' storage.
  const nlohmann::json dc = plant_of(scene("", "", kDcDrive));
  EXPECT_EQ(dc["state_size"].get<int>(), 7);
  EXPECT_EQ(dc["electrical_states"].get<int>(), 2);
  EXPECT_TRUE(lists(dc, "motor electrics"));
  EXPECT_GE(dc["device_bytes"].get<std::size_t>(),
            minimal["device_bytes"].get<std::size_t>() + 2 * sizeof(drives::GimbalDrive));

  // Structural elasticity: the platform's φ, φ'.
  const nlohmann::json elastic = plant_of(scene("structure = \"elastic\"\nc = 2.0e4\nAP = 200.0"));
  EXPECT_EQ(elastic["state_size"].get<int>(), 7);
  EXPECT_TRUE(lists(elastic, "structural elasticity"));

  // Nutation itself: the precession model has α, β, H only.
  const nlohmann::json p0 = plant_of(scene("fidelity = \"precession\""));
  EXPECT_EQ(p0["state_size"].get<int>(), 3);
  EXPECT_EQ(p0["fidelity"].get<std::string>(), "precession");

  // Sensor bandwidth (a second-order filter per rate gyro) and noise, base motion, friction: listed only when
  // the scene names them.
  const nlohmann::json sensed = plant_of(scene("d1 = 0.05", "rate_noise_density = 1e-4\nrate_bandwidth_hz = 200.0",
                                               "[base]\nroll_amplitude_rad = 0.05"));
  EXPECT_EQ(sensed["state_size"].get<int>(), 9);
  EXPECT_TRUE(lists(sensed, "rate gyro noise"));
  EXPECT_TRUE(lists(sensed, "base motion"));
  EXPECT_TRUE(lists(sensed, "friction"));
}

// ---- the recorded columns: the signal table's, an option's only with it ------------------------------------

std::vector<std::string> columns_with(tools::PowerDrive drive, tools::PowerMotor motor, tools::PowerStructure structure) {
  tools::PowerStabilizerScene s;
  s.drive = drive;
  s.motor = motor;
  s.structure = structure;
  return tools::power_stabilizer_columns(s);
}

// Each option adds its columns after the always-recorded ones, in the table's order (the order signals.csv had
// before the table existed); every option-only column of the table belongs to some variant.
TEST(PlantComposition, EveryOptionAddsItsColumnsOnly) {
  using tools::PowerDrive, tools::PowerMotor, tools::PowerStructure;
  const std::vector<std::string> base{"alpha_rad",         "beta_rad",          "alpha_rate_rad_s",
                                      "beta_rate_rad_s",   "M1_motor_Nm",       "M2_motor_Nm",
                                      "M1_disturbance_Nm", "M2_disturbance_Nm", "status_bits"};
  const std::vector<std::string> dc{"motor1_current_A", "motor2_current_A", "motor1_voltage_V", "motor2_voltage_V"};
  auto plus = [&](std::vector<std::string> extra) {
    std::vector<std::string> c = base;
    c.insert(c.end(), extra.begin(), extra.end());
    return c;
  };
  EXPECT_EQ(columns_with(PowerDrive::kTorque, PowerMotor::kTorque, PowerStructure::kRigid), base);
  EXPECT_EQ(columns_with(PowerDrive::kDcMotor, PowerMotor::kTorque, PowerStructure::kRigid), plus(dc));
  EXPECT_EQ(columns_with(PowerDrive::kTorque, PowerMotor::kBackEmf, PowerStructure::kRigid),
            plus({"motor1_voltage_V"}));
  EXPECT_EQ(columns_with(PowerDrive::kTorque, PowerMotor::kTorque, PowerStructure::kElastic), plus({"platform_rad"}));
  std::vector<std::string> dc_elastic = dc;
  dc_elastic.emplace_back("platform_rad");
  EXPECT_EQ(columns_with(PowerDrive::kDcMotor, PowerMotor::kTorque, PowerStructure::kElastic), plus(dc_elastic));
  EXPECT_EQ(columns_with(PowerDrive::kTorque, PowerMotor::kBackEmf, PowerStructure::kElastic),
            plus({"motor1_voltage_V", "platform_rad"}));
  for (const tools::ColumnSpec& c : msg::power_stabilizer::kColumns) {
    if (c.when.empty()) continue;
    bool taken = false;
    for (const PowerDrive d : {PowerDrive::kTorque, PowerDrive::kDcMotor}) {
      for (const PowerMotor m : {PowerMotor::kTorque, PowerMotor::kBackEmf}) {
        for (const PowerStructure st : {PowerStructure::kRigid, PowerStructure::kElastic}) {
          tools::PowerStabilizerScene s;
          s.drive = d;
          s.motor = m;
          s.structure = st;
          taken = taken || tools::power_stabilizer_column_option(s, c.when);
        }
      }
    }
    EXPECT_TRUE(taken) << c.name << ": no scene takes its option \"" << c.when << "\"";
  }
}

// ---- runtime options that stay: zero costs nothing -------------------------------------------------------

// A noise-free rate gyro draws no random numbers (sensor_noise.hpp: a zero density draws nothing): the
// generator is untouched, so no Gaussian is computed per tick.
TEST(PlantComposition, NoiseFreeRateGyroDrawsNothing) {
  sensors::RateGyro quiet{};
  random::SeededRng rng(7, 1), twin(7, 1);
  for (int k = 0; k < 1000; ++k) EXPECT_EQ(quiet.measure(0.25, rng), 0.25);
  EXPECT_EQ(rng.gaussian(), twin.gaussian());  // the stream is where it started
  sensors::RateGyroParams p;
  p.noise.white_density = 1e-4;
  sensors::RateGyro noisy(p);
  noisy.measure(0.25, rng);
  EXPECT_NE(rng.gaussian(), twin.gaussian());  // (the check can fail: a draw does move the stream)
}

// A base that does not roll takes the at-rest path: the same sample as a FixedBase, without its sin/cos.
TEST(PlantComposition, BaseWithoutRollIsTheBaseAtRest) {
  const HarmonicBaseRotation still{dynamics::Vec3::UnitX(), 0.0, 0.8, dynamics::Vec3::UnitZ()};
  const FixedBase fixed{};
  for (const double t : {0.0, 0.3, 1e3}) {
    const models::BaseSample a = still(t), b = fixed(t);
    EXPECT_EQ(a.w_B, b.w_B);
    EXPECT_EQ(a.dw_B, b.dw_B);
    EXPECT_EQ(a.up_B, b.up_B);
  }
}

}  // namespace plant_composition_test
}  // namespace gyrostab
