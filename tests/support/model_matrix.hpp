// Every model × integrator of the foundation, as one list the allocation and determinism tests walk
// over. Each case integrates from a fixed initial state with all of the model's terms switched on.
#pragma once

#include <cstring>
#include <numbers>
#include <vector>

#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/implicit_midpoint.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/rotor_splitting.hpp"
#include "sim/dynamics/substepping.hpp"
#include "sim/models/free_rigid_body.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/models/gimbal_gyro_precession.hpp"
#include "sim/models/heavy_symmetric_top.hpp"

namespace gyrostab::testing {

using Gyro = models::GimbalGyro<models::HarmonicBaseRotation>;
using GyroP0 = models::GimbalGyroPrecession<models::HarmonicBaseRotation>;

inline models::GimbalGyroParams full_gyro_params() {
  models::GimbalGyroParams p;
  p.AR = 0.4; p.CR = 1.0; p.AJ = 0.05; p.BJ = 0.1; p.CJ = 0.05; p.AA = 0.05; p.BA = 0.02; p.CA = 0.03;
  p.Gs = -5.0; p.d1 = 0.1; p.d2 = 0.1; p.r1 = 0.01; p.r2 = 0.01;
  return p;
}
inline models::HarmonicBaseRotation rolling_base() {
  return {dynamics::Vec3(1.0, 0.2, 0.0).normalized(), 0.2, 0.6, dynamics::Vec3::UnitZ()};
}

// Runs `steps` steps of one model × integrator (1 kHz ticks, `substeps` each) and returns the final state's
// bytes. `between` is called once after construction and warm-up, before the measured steps.
template <template <class> class Integrator, class Model, class Between>
std::vector<unsigned char> integrate(const Model& model, typename Model::State x, long ticks, int substeps,
                                     Between&& between) {
  Integrator<Model> integ(model);
  dynamics::SubstepDriver<Integrator<Model>> driver(integ, 1'000'000, substeps);
  driver.advance_tick(0, x);  // warm-up: anything lazily sized happens here
  between();
  for (long k = 1; k <= ticks; ++k) driver.advance_tick(k, x);
  std::vector<unsigned char> bytes(sizeof(x));
  std::memcpy(bytes.data(), x.data(), sizeof(x));
  return bytes;
}

struct Case {
  const char* name;
  std::vector<unsigned char> (*run)(long ticks, void (*between)());
};

inline models::RigidBodyState tumbling() {
  return models::make_rigid_body_state({2.0, 0.5, 1.0}, dynamics::Quat(0.9, 0.1, 0.3, -0.2));
}
inline models::RigidBodyState spinning_top() {
  return models::make_rigid_body_state({1.0, 0.0, 200.0 * std::numbers::pi},
                                       dynamics::Quat(Eigen::AngleAxisd(0.5, dynamics::Vec3::UnitX())));
}

#define GYROSTAB_CASE(NAME, INTEGRATOR, MODEL_EXPR, STATE_EXPR, SUBSTEPS)                               \
  Case {                                                                                                \
    NAME, [](long ticks, void (*between)()) {                                                           \
      const auto model = MODEL_EXPR;                                                                    \
      return integrate<INTEGRATOR>(model, STATE_EXPR, ticks, SUBSTEPS, between);                       \
    }                                                                                                   \
  }

inline std::vector<Case> all_cases() {
  using namespace gyrostab::dynamics;
  using models::FreeRigidBody;
  using models::HeavySymmetricTop;
  const double H = 200.0 * std::numbers::pi;
  (void)H;
  return {
      GYROSTAB_CASE("free_body/rk4", Rk4, FreeRigidBody({dynamics::Vec3(1, 2, 3)}), tumbling(), 1),
      GYROSTAB_CASE("free_body/strang", RotorStrang, FreeRigidBody({dynamics::Vec3(1, 2, 3)}), tumbling(), 1),
      GYROSTAB_CASE("free_body/yoshida4", RotorYoshida4, FreeRigidBody({dynamics::Vec3(1, 2, 3)}), tumbling(), 1),
      GYROSTAB_CASE("free_body/implicit_midpoint", ImplicitMidpoint, FreeRigidBody({dynamics::Vec3(1, 2, 3)}),
                    tumbling(), 1),
      GYROSTAB_CASE("lagrange_top/rk4", Rk4, HeavySymmetricTop({0.5, 1.0, 50.0}), spinning_top(), 5),
      GYROSTAB_CASE("lagrange_top/strang", RotorStrang, HeavySymmetricTop({0.5, 1.0, 50.0}), spinning_top(), 1),
      GYROSTAB_CASE("lagrange_top/yoshida4", RotorYoshida4, HeavySymmetricTop({0.5, 1.0, 50.0}), spinning_top(), 1),
      GYROSTAB_CASE("lagrange_top/implicit_midpoint", ImplicitMidpoint, HeavySymmetricTop({0.5, 1.0, 50.0}),
                    spinning_top(), 1),
      GYROSTAB_CASE("gimbal_gyro/rk4", Rk4, Gyro(full_gyro_params(), rolling_base()),
                    Gyro::make_state(0.1, 0.2, 0.5, -0.3, 200.0 * std::numbers::pi), 13),
      GYROSTAB_CASE("gimbal_gyro/gyro_exponential", GyroscopicExponential, Gyro(full_gyro_params(), rolling_base()),
                    Gyro::make_state(0.1, 0.2, 0.5, -0.3, 200.0 * std::numbers::pi), 1),
      GYROSTAB_CASE("gimbal_gyro/implicit_midpoint", ImplicitMidpoint, Gyro(full_gyro_params(), rolling_base()),
                    Gyro::make_state(0.1, 0.2, 0.5, -0.3, 200.0 * std::numbers::pi), 1),
      GYROSTAB_CASE("gimbal_gyro_precession/rk4", Rk4, GyroP0(full_gyro_params(), rolling_base()),
                    GyroP0::make_state(0.1, 0.2, 200.0 * std::numbers::pi), 1),
      GYROSTAB_CASE("gimbal_gyro_precession/implicit_midpoint", ImplicitMidpoint,
                    GyroP0(full_gyro_params(), rolling_base()), GyroP0::make_state(0.1, 0.2, 200.0 * std::numbers::pi), 1),
  };
}

#undef GYROSTAB_CASE

}  // namespace gyrostab::testing
