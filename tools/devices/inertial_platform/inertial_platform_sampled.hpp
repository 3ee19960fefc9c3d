// The inertial platform's Schuler loops as the closed loop runs them (docs/sampled-data.md): the platform model
// (servos, gyros and their cross-coupling, sim/models/inertial_platform*.hpp) linearised at rest at the scene's
// starting point — the vehicle frame held at t = 0, no tilt — by central differences of its own derivative
// (the models are linear in the state, so the differences are exact to round-off); the torquers through the
// plant's own `set_torquers`; the accelerometers through the model's apparent tilts, reported as the plant does
// as the trapezoid mean over the previous tick, ½(θ[k−1] + θ[k]) (a state of the sampled loop); and the
// firmware's `SchulerLoop` probed for its exact discrete law (ω ← ω − (g0/R) T θ, M = −H ω). Sampled with the
// zero-order hold at the law's period and the latency (sim/analysis/sampled_loop_roots.hpp). The Schuler mode
// of channel i is the sampled root nearest the book's i ω, ω² = (g/R_loop)(H_loop/H_i) ((16.38)/(16.44)).
// The loop the trapezoid describes is the tick's: with a control divisor above 1 the law reads only the last
// tick's mean, which these matrices do not model (nullopt then).
#pragma once

#include <cmath>
#include <complex>
#include <optional>
#include <vector>

#include "firmware/control/schuler_loop.hpp"
#include "sim/analysis/sampled_loop_roots.hpp"
#include "sim/plants/inertial_platform_plant.hpp"
#include "tools/devices/inertial_platform/inertial_platform_scene.hpp"

namespace gyrostab::tools {

struct InertialPlatformSampled {
  std::complex<double> schuler[2]{};  // channel i's sampled Schuler root (Im > 0) [1/s]
  analysis::SampledLoopRoots roots;
};

template <class Model>
std::optional<InertialPlatformSampled> inertial_platform_sampled(const InertialPlatformScene& s) {
  using Plant = plants::InertialPlatformPlant<Model>;
  using Axes = plants::PlatformAxes<Model>;
  constexpr int kN = Model::kStateSize, kCh = Plant::kChannels;
  if (s.controller.runtime.control_divisor != 1) return std::nullopt;
  plants::InertialPlatformPlantParams pp = s.plant;
  for (auto& a : pp.axis) a.tilt0 = 0.0;
  pp.accel_noise_density = 0.0;
  const Plant plant(pp, s.loop.plant_timing());
  Model m = plant.model();
  const typename Model::State x0 = plant.state();
  const double t0 = m.inputs.frame.t0;
  const auto f = [&](const typename Model::State& x, const double (&u)[2]) {
    typename Plant::ActuatorFrame cmd{};
    cmd.torquer1_Nm = u[0];
    cmd.torquer2_Nm = u[1];
    Axes::set_torquers(m, cmd);
    typename Model::State dx;
    m.derivative(t0, x, dx);
    return dx;
  };
  const auto theta = [&](const typename Model::State& x) {
    double th[2];
    Axes::apparent(m, t0, x, th);
    return Eigen::Vector2d(th[0], th[1]);
  };
  // The plant, with the trapezoid's previous sample kept in the law: ẋ = A x + B M, y = C x (θ at the sample).
  Eigen::MatrixXd A(kN, kN), B = Eigen::MatrixXd::Zero(kN, kCh), C(kCh, kN);
  const double u0[2] = {0.0, 0.0};
  constexpr double h = 1e-6;
  for (int i = 0; i < kN; ++i) {
    typename Model::State xp = x0, xm = x0;
    xp[i] += h;
    xm[i] -= h;
    A.col(i) = (f(xp, u0) - f(xm, u0)) / (2.0 * h);
    C.col(i) = ((theta(xp) - theta(xm)) / (2.0 * h)).head(kCh);
  }
  for (int j = 0; j < kCh; ++j) {
    const double up[2] = {j == 0 ? 1.0 : 0.0, j == 1 ? 1.0 : 0.0};
    B.col(j) = f(x0, up) - f(x0, u0);  // the torquers enter linearly: a unit step is exact
  }
  // The law, probed with its limit lifted: ω⁺ = ω + G_s θ̂, M = H_s ω + D_s θ̂ (ω before the step).
  firmware::SchulerLoopParams lp = s.controller.law;
  lp.torque_limit_Nm = 1e300;
  const double T = s.controller.runtime.control_period_s();
  const firmware::SchulerLoop base(lp, T);
  const auto run = [&](firmware::SchulerLoop& l, double a, double b) {
    const double th[firmware::kSchulerChannels] = {a, b};
    const firmware::SchulerTorques t = l.step(th);
    return Eigen::Vector2d(t.M[0], t.M[1]);
  };
  const auto rates = [](const firmware::SchulerLoop& l) {
    return Eigen::Vector2d(l.commanded_rate(0), l.commanded_rate(1));
  };
  Eigen::Matrix2d Gs, Hs, Ds;
  firmware::SchulerLoop zero = base;
  const Eigen::Vector2d M0 = run(zero, 0.0, 0.0);
  for (int j = 0; j < 2; ++j) {
    firmware::SchulerLoop l = base;
    Ds.col(j) = run(l, j == 0 ? 1.0 : 0.0, j == 1 ? 1.0 : 0.0) - M0;
    Gs.col(j) = rates(l) - rates(base);
    Hs.col(j) = (run(l, 0.0, 0.0) - M0) / Gs(j, j);  // from the state G e_j (each channel integrates its own)
  }
  // The loop's law on y = θ[k] with the state [ω (kCh), θ[k−1] (kCh)]: θ̂ = ½(y + θ[k−1]).
  const Eigen::MatrixXd G = Gs.topLeftCorner(kCh, kCh), H = Hs.topLeftCorner(kCh, kCh), D = Ds.topLeftCorner(kCh, kCh);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(kCh, kCh);
  analysis::DiscreteLaw law;
  law.F = Eigen::MatrixXd::Zero(2 * kCh, 2 * kCh);
  law.F.topLeftCorner(kCh, kCh) = I;
  law.F.topRightCorner(kCh, kCh) = 0.5 * G;
  law.G = Eigen::MatrixXd::Zero(2 * kCh, kCh);
  law.G.topRows(kCh) = 0.5 * G;
  law.G.bottomRows(kCh) = I;
  law.H = Eigen::MatrixXd::Zero(kCh, 2 * kCh);
  law.H.leftCols(kCh) = H;
  law.H.rightCols(kCh) = 0.5 * D;
  law.D = 0.5 * D;
  InertialPlatformSampled r;
  r.roots = analysis::sampled_loop_roots({A, B, C}, law,
                                         {T, s.loop.tick_s() * static_cast<double>(s.loop.latency_ticks)});
  const double g = s.plant.vehicle.earth.gravity;
  for (int i = 0; i < kCh; ++i) {
    const double w = std::sqrt(g / lp.radius * lp.H / s.plant.axis[i].params.H);
    r.schuler[i] = analysis::nearest_root(r.roots.s, {0.0, w});
  }
  return r;
}

}  // namespace gyrostab::tools
