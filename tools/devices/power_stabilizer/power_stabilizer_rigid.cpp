// The rigid power stabilizer's plants: torque motors or the back-EMF motor, under either integrator.
#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/rk4.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_run.hpp"

namespace gyrostab::tools {
namespace {

template <class Motor>
std::unique_ptr<PlantPort> make(const PowerStabilizerScene& s) {
  if (s.loop.integrator == "rk4") {
    return make_plant_port<PowerStabilizerRun<Motor, models::RigidStructure, false, dynamics::Rk4>>(s);
  }
  return make_plant_port<PowerStabilizerRun<Motor, models::RigidStructure, false, dynamics::GyroscopicExponential>>(s);
}

}  // namespace

std::unique_ptr<PlantPort> make_power_stabilizer_rigid(const PowerStabilizerScene& s) {
  return s.back_emf() ? make<models::BackEmfMotor>(s) : make<models::TorqueMotors>(s);
}

}  // namespace gyrostab::tools
