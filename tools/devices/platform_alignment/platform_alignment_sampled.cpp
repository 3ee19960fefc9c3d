// Docs: docs/sampled-data.md, docs/models/platform-alignment.md.
#include "tools/devices/platform_alignment/platform_alignment_sampled.hpp"

#include <cmath>
#include <limits>

#include "firmware/control/platform_alignment_loops.hpp"
#include "tools/devices/platform_alignment/platform_alignment_closed_forms.hpp"

namespace gyrostab::tools {

namespace {

using Model = models::PlatformAlignment;
using Vec3 = dynamics::Vec3;

Vec3 vec_of(const models::PlatformMisalignment& m) { return {m.tilt_east, m.tilt_north, m.heading_error}; }
models::PlatformMisalignment misalignment_of(const Vec3& x) { return {x[0], x[1], x[2]}; }

// The misalignment of a quaternion off the unit sphere (a probe): of its direction.
Vec3 misalignment_at(const Model::State& q) { return vec_of(Model::misalignment(Model::State(q.normalized()))); }

// ẋ of the misalignment at x with the rate command w: the model's quaternion rate through the Jacobian of the
// misalignment (central differences on q, step 1e-6: truncation O(1e-12), round-off O(1e-10) relative).
Vec3 misalignment_rate(Model& m, const Vec3& x, const Vec3& w) {
  m.inputs.rate_command = w;
  const Model::State q = Model::state_of(models::attitude_of(misalignment_of(x)));
  Model::State dq;
  m.derivative(0.0, q, dq);
  Eigen::Matrix<double, 3, 4> J;
  constexpr double h = 1e-6;
  for (int i = 0; i < 4; ++i) {
    Model::State qp = q, qm = q;
    qp[i] += h;
    qm[i] -= h;
    J.col(i) = (misalignment_at(qp) - misalignment_at(qm)) / (2.0 * h);
  }
  return J * dq;
}

// θ̂ = (a_N, −a_E)/g0 of the model's accelerometers at rest (specific force g up).
Eigen::Vector2d apparent_tilts(const Model& m, const Vec3& x, double g) {
  const Vec3 a = m.accelerometers(Model::state_of(models::attitude_of(misalignment_of(x))), Vec3(0.0, 0.0, g));
  return {a.y() / plants::kAlignmentGravityScale, -a.x() / plants::kAlignmentGravityScale};
}

}  // namespace

PlatformAlignmentSampled platform_alignment_sampled(const PlatformAlignmentScene& s, double continuous_slow_root) {
  // The plant: linearised at the steady misalignment of its biases and drifts under the equilibrium command
  // (ω_cmd = R_PG ω_IG − ε: the platform at rest in G, so the Jacobian's own variation has no rate to act on).
  Model m(s.plant.platform);
  const firmware::PlatformAlignmentGains g_site = oracles::gains_at(s.controller.law, s.plant.platform.latitude);
  const Vec3 x0 = vec_of(oracles::steady_misalignment(g_site, s.plant.platform, s.plant.gravity));
  const Model::State q0 = Model::state_of(models::attitude_of(misalignment_of(x0)));
  const Vec3 w0 = m.earth_rate_on_platform(q0) - s.plant.platform.drift;
  Eigen::MatrixXd A(3, 3), Bw(3, 3), C(2, 3);
  constexpr double hx = 1e-4;  // [rad]: the kinematics' curvature is O(1), truncation O(1e-8)
  for (int i = 0; i < 3; ++i) {
    Vec3 xp = x0, xm = x0;
    xp[i] += hx;
    xm[i] -= hx;
    A.col(i) = (misalignment_rate(m, xp, w0) - misalignment_rate(m, xm, w0)) / (2.0 * hx);
    C.col(i) = (apparent_tilts(m, xp, s.plant.gravity) - apparent_tilts(m, xm, s.plant.gravity)) / (2.0 * hx);
  }
  constexpr double hw = 1e-6;  // [rad/s]: ẋ is linear in the command
  for (int i = 0; i < 3; ++i) {
    Vec3 wp = w0, wm = w0;
    wp[i] += hw;
    wm[i] -= hw;
    Bw.col(i) = (misalignment_rate(m, x0, wp) - misalignment_rate(m, x0, wm)) / (2.0 * hw);
  }
  // The actuator frame's three commands (M_E, M_N, u_Z) to the rate command, through the plant's own actuate().
  plants::PlatformAlignmentPlant plant(s.plant, s.loop.plant_timing());
  const auto rate_of = [&](int slot, double v) {
    plants::PlatformAlignmentPlant::ActuatorFrame f{};
    if (slot == 0) f.east_torquer_Nm = v;
    if (slot == 1) f.north_torquer_Nm = v;
    if (slot == 2) f.zenith_torquer_V = v;
    plant.actuate(f);
    return Vec3(plant.inputs().rate_command);
  };
  Eigen::MatrixXd U(3, 3);
  for (int i = 0; i < 3; ++i) U.col(i) = rate_of(i, 1.0) - rate_of(i, 0.0);

  // The law, probed in its azimuth phase with its limits lifted: u = H x_c + D y + u0, x_c⁺ = x_c + G y
  // (the integrators I_E, I_N), read off the outputs of copies stepped from a common state.
  firmware::PlatformAlignmentLoopParams lp = s.controller.law;
  lp.levelling_min_s = 0.0;
  lp.settle_tilt_rad = 0.0;
  lp.torque_limit_Nm = lp.voltage_limit_V = std::numeric_limits<double>::max();
  const double T = s.controller.runtime.control_period_s();
  firmware::PlatformAlignmentLoops base(lp, T);
  base.step(0.0, 0.0);  // the phase switches after the first period
  const auto out = [](const firmware::PlatformAlignmentCommand& c) {
    return Eigen::Vector3d(c.M_east, c.M_north, c.u_zenith);
  };
  const auto integrators = [](const firmware::PlatformAlignmentLoops& l) {
    return Eigen::Vector2d(l.integrator_east(), l.integrator_north());
  };
  firmware::PlatformAlignmentLoops zero = base;
  const Eigen::Vector3d u0 = out(zero.step(0.0, 0.0));
  Eigen::MatrixXd D(3, 2), G(2, 2), H(3, 2);
  for (int j = 0; j < 2; ++j) {
    firmware::PlatformAlignmentLoops l = base;
    const Eigen::Vector3d u = out(l.step(j == 0 ? 1.0 : 0.0, j == 1 ? 1.0 : 0.0));
    D.col(j) = u - u0;
    G.col(j) = integrators(l) - integrators(base);
    // The state it left, stepped with y = 0: the output's change is H (G e_j).
    const Eigen::Vector3d u_next = out(l.step(0.0, 0.0));
    H.col(j) = u_next - u0;
  }
  // H was read on the states G e_j; G is diagonal (each channel integrates its own tilt).
  for (int j = 0; j < 2; ++j) H.col(j) /= G(j, j);
  analysis::LinearPlant p{A, Bw * U, C};
  analysis::DiscreteLaw law{Eigen::MatrixXd::Identity(2, 2), G, H, D};
  PlatformAlignmentSampled r;
  const double tick = s.loop.tick_s();
  r.roots = analysis::sampled_loop_roots(p, law, {T, tick * static_cast<double>(s.loop.latency_ticks)});
  r.slow_root = analysis::nearest_root(r.roots.s, {continuous_slow_root, 0.0});
  return r;
}

}  // namespace gyrostab::tools
