// The rigid power stabilizer's checks (power_stabilizer_checks_impl.hpp).
#include "tools/devices/power_stabilizer/power_stabilizer_checks_impl.hpp"

namespace gyrostab::tools {

bool check_power_stabilizer_rigid(SceneReader& r, PowerStabilizerScene& s) {
  using namespace power_stabilizer_checks;
  return s.back_emf() ? check_plant<models::BackEmfMotor, models::RigidStructure>(r, s)
                      : check_plant<models::TorqueMotors, models::RigidStructure>(r, s);
}

}  // namespace gyrostab::tools
