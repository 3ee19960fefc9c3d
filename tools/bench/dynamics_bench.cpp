// ns per step for every model × integrator (Google Benchmark). Reported, never asserted.
// Run: build/bin/gyrostab-bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <numbers>

#include "sim/dynamics/gyroscopic_exponential.hpp"
#include "sim/dynamics/implicit_midpoint.hpp"
#include "sim/dynamics/rk4.hpp"
#include "sim/dynamics/rotor_splitting.hpp"
#include "sim/models/free_rigid_body.hpp"
#include "sim/models/gimbal_gyro.hpp"
#include "sim/models/gimbal_gyro_precession.hpp"
#include "sim/models/heavy_symmetric_top.hpp"

namespace gyrostab {
namespace {

using dynamics::Quat;
using dynamics::Vec3;

// numerics.md case A1: I = (1, 2, 3), ω0 = (2, 0.5, 1) rad/s, h = 0.01.
models::FreeRigidBody free_body() { return models::FreeRigidBody({Vec3(1, 2, 3)}); }
models::RigidBodyState free_body_state() { return models::make_rigid_body_state({2, 0.5, 1}, Quat::Identity()); }

// numerics.md case B2 as a Lagrange top: A = 0.5, C = 1, 6000 rpm, Gs = 50 N m, 30° tilt, h = 1 ms.
models::HeavySymmetricTop top() { return models::HeavySymmetricTop({0.5, 1.0, 50.0}); }
models::RigidBodyState top_state() {
  return models::make_rigid_body_state({1.0, 0.0, 200.0 * std::numbers::pi},
                                       Quat(Eigen::AngleAxisd(std::numbers::pi / 6, Vec3::UnitX())));
}

// The foundation's gimbal gyro: C^R = 1, 6000 rpm, A = B = 0.5 plus gimbal masses, gravity, friction
// and a rolling base, so every term of the model is exercised. h = 1 ms (gyro-exponential) or 0.1 ms.
using Gyro = models::GimbalGyro<models::HarmonicBaseRotation>;
using GyroP0 = models::GimbalGyroPrecession<models::HarmonicBaseRotation>;
models::GimbalGyroParams gyro_params() {
  models::GimbalGyroParams p;
  p.AR = 0.4; p.CR = 1.0; p.AJ = 0.05; p.BJ = 0.1; p.CJ = 0.05; p.AA = 0.05;
  p.Gs = -5.0; p.d1 = 0.1; p.d2 = 0.1; p.r1 = 0.01; p.r2 = 0.01;
  return p;
}
models::HarmonicBaseRotation rolling_base() { return {Vec3::UnitX(), 0.2, 0.6, Vec3::UnitZ()}; }
Gyro gyro() { return Gyro(gyro_params(), rolling_base()); }
Gyro::State gyro_state() { return Gyro::make_state(0.1, 0.2, 0.5, -0.3, 200.0 * std::numbers::pi); }

template <class Integrator, class Model, class State>
void run(benchmark::State& st, const Model& model, State x, double h) {
  Integrator integrator(model);
  double t = 0.0;
  for (auto _ : st) {
    integrator.step(t, h, x);
    t += h;
    benchmark::DoNotOptimize(x);
  }
  st.SetItemsProcessed(st.iterations());
}

template <template <class> class I>
void BM_FreeBody(benchmark::State& st) {
  const auto m = free_body();
  run<I<models::FreeRigidBody>>(st, m, free_body_state(), 0.01);
}
template <template <class> class I>
void BM_LagrangeTop(benchmark::State& st) {
  const auto m = top();
  run<I<models::HeavySymmetricTop>>(st, m, top_state(), 1e-3);
}
template <template <class> class I>
void BM_GimbalGyro(benchmark::State& st) {
  const auto m = gyro();
  run<I<Gyro>>(st, m, gyro_state(), 1e-4);
}
void BM_GimbalGyroPrecession_Rk4(benchmark::State& st) {
  const GyroP0 m(gyro_params(), rolling_base());
  run<dynamics::Rk4<GyroP0>>(st, m, GyroP0::make_state(0.1, 0.2, 200.0 * std::numbers::pi), 1e-3);
}

BENCHMARK(BM_FreeBody<dynamics::Rk4>)->Name("free_body/rk4");
BENCHMARK(BM_FreeBody<dynamics::RotorStrang>)->Name("free_body/strang");
BENCHMARK(BM_FreeBody<dynamics::RotorYoshida4>)->Name("free_body/yoshida4");
BENCHMARK(BM_FreeBody<dynamics::ImplicitMidpoint>)->Name("free_body/implicit_midpoint");
BENCHMARK(BM_LagrangeTop<dynamics::Rk4>)->Name("lagrange_top/rk4");
BENCHMARK(BM_LagrangeTop<dynamics::RotorStrang>)->Name("lagrange_top/strang");
BENCHMARK(BM_LagrangeTop<dynamics::RotorYoshida4>)->Name("lagrange_top/yoshida4");
BENCHMARK(BM_LagrangeTop<dynamics::ImplicitMidpoint>)->Name("lagrange_top/implicit_midpoint");
BENCHMARK(BM_GimbalGyro<dynamics::Rk4>)->Name("gimbal_gyro/rk4");
BENCHMARK(BM_GimbalGyro<dynamics::GyroscopicExponential>)->Name("gimbal_gyro/gyro_exponential");
BENCHMARK(BM_GimbalGyro<dynamics::ImplicitMidpoint>)->Name("gimbal_gyro/implicit_midpoint");
BENCHMARK(BM_GimbalGyroPrecession_Rk4)->Name("gimbal_gyro_precession/rk4");

}  // namespace
}  // namespace gyrostab
