// The elastic power stabilizer's checks (power_stabilizer_checks_impl.hpp).
#include "tools/devices/power_stabilizer/power_stabilizer_checks_impl.hpp"

namespace gyrostab::tools {

bool check_power_stabilizer_elastic(SceneReader& r, PowerStabilizerScene& s) {
  using namespace power_stabilizer_checks;
  return s.back_emf() ? check_plant<models::BackEmfMotor, models::ElasticPlatform>(r, s)
                      : check_plant<models::TorqueMotors, models::ElasticPlatform>(r, s);
}

}  // namespace gyrostab::tools
