// The rigid power stabilizer with DC drives on both gimbal axes, under either integrator.
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_run.hpp"

namespace gyrostab::tools {

std::unique_ptr<PlantPort> make_power_stabilizer_dc(const PowerStabilizerScene& s) {
  using models::RigidStructure, models::TorqueMotors;
  if (s.loop.integrator == "rk4") {
    return make_plant_port<PowerStabilizerRun<TorqueMotors, RigidStructure, true, dynamics::Rk4>>(s);
  }
  return make_plant_port<PowerStabilizerRun<TorqueMotors, RigidStructure, true, dynamics::GyroscopicExponential>>(s);
}

}  // namespace gyrostab::tools
