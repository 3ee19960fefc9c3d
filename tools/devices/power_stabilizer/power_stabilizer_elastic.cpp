// The power stabilizer on an elastic platform (14.31): torque motors, back-EMF motor or DC drives; RK4 only
// (no exact gyroscopic flow for the shaft mode).
#include "sim/dynamics/rk4.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_run.hpp"

namespace gyrostab::tools {

std::unique_ptr<PlantPort> make_power_stabilizer_elastic(const PowerStabilizerScene& s) {
  using models::BackEmfMotor, models::ElasticPlatform, models::TorqueMotors;
  if (s.back_emf()) return make_plant_port<PowerStabilizerRun<BackEmfMotor, ElasticPlatform, false, dynamics::Rk4>>(s);
  if (s.dc_drive()) return make_plant_port<PowerStabilizerRun<TorqueMotors, ElasticPlatform, true, dynamics::Rk4>>(s);
  return make_plant_port<PowerStabilizerRun<TorqueMotors, ElasticPlatform, false, dynamics::Rk4>>(s);
}

}  // namespace gyrostab::tools
