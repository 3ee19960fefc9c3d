// The precession power stabilizer's checks (power_stabilizer_checks_impl.hpp).
#include "tools/devices/power_stabilizer/power_stabilizer_checks_impl.hpp"

namespace gyrostab::tools {

bool check_power_stabilizer_precession(SceneReader& r, PowerStabilizerScene& s) {
  using namespace power_stabilizer_checks;
  return s.back_emf() ? check_reduced<models::BackEmfMotor>(r, s) : check_reduced<models::TorqueMotors>(r, s);
}

}  // namespace gyrostab::tools
