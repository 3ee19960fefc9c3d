// Scene reading and start-up checks for an instrument that is a gyro in a rotating frame ((10.22),
// sim/models/gyro_in_rotating_frame.hpp: the gyro vertical, the gyrocompass): the scene's head (loop,
// vehicle motion, the [gyro] keys of the gyro itself), the nutation the precession theory does not see, and
// the plant sub-step against the fastest mode. Start-up only (Eigen solvers, strings).
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

#include <Eigen/Eigenvalues>

#include "sim/dynamics/step_validation.hpp"
#include "sim/models/gyro_in_rotating_frame.hpp"
#include "tools/devices/vehicle_motion_scene.hpp"
#include "tools/scene/loop_config.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// What the [gyro] keys of the gyro itself say in the device's terms.
struct GyroFrameKeys {
  double inertia;             // default of A and B [kg m²]
  const char* fidelity_what;  // the equations of the full and the precession form
  const char* A_what;
  const char* B_what;
};

// The head of the scene, in this order: [loop] (RK4 only), the vehicle's motion ([earth], [vehicle],
// [segmentN]; start latitude 50° by default), [gyro] fidelity, H, A, B. Scene: loop, motion, gyro.gyro
// (GyroFrameParams), gyro.fidelity. Problems go to the reader.
template <class Scene>
void read_gyro_frame_scene_head(SceneReader& r, const GyroFrameKeys& k, Scene& s) {
  s.loop = read_loop_config(r, "rk4", {"rk4"});
  s.motion = read_vehicle_motion(r, 50.0);
  s.gyro.fidelity = r.choice("gyro", "fidelity", "full", {"full", "precession"}, k.fidelity_what) == "precession"
                        ? models::InstrumentFidelity::kPrecession
                        : models::InstrumentFidelity::kFull;
  models::GyroFrameParams& gyro = s.gyro.gyro;
  gyro.H = r.required("gyro", "H", Range::positive(), "spin momentum [N m s]");
  gyro.A = r.number("gyro", "A", k.inertia, Range::positive(), k.A_what);
  gyro.B = r.number("gyro", "B", k.inertia, Range::positive(), k.B_what);
}

// Positional torques −K [α; β] of the closed loop linearized at rest [N m/rad].
struct GyroFrameStiffness {
  double k11, k12, k21, k22;
};

// Largest real part of the eigenvalues of (10.22) linearized at rest (Ω' = 0) with the torques
// −K [α; β] − diag(d1, d2) [α'; β'] (the frame-rate and pendulous terms folded into K) [1/s]. > 0: a mode
// grows — the nutation, when a circulatory (non-symmetric) K feeds it (model headers, digest §8).
inline double gyro_frame_growth_rate(const models::GyroFrameParams& p, const GyroFrameStiffness& K, double d1,
                                     double d2) {
  const double A = p.A, B = p.B, H = p.H;
  Eigen::Matrix4d J;
  J << 0, 0, 1, 0,  //
      0, 0, 0, 1,   //
      -K.k11 / A, -K.k12 / A, -d1 / A, -H / A,  //
      -K.k21 / B, -K.k22 / B, H / B, -d2 / B;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(J, false);
  double growth = -1e300;
  for (int i = 0; i < 4; ++i) growth = std::max(growth, es.eigenvalues()[i].real());
  return growth;
}

// "%.3g" of v (the checks' messages).
inline std::string format_3g(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Refuses ([gyro] d1) a closed loop whose nutation grows: "<cause> makes the nutation grow at <rate> /s (a
// circulatory force, model header): <remedy>".
inline void refuse_growing_nutation(SceneReader& r, const models::GyroFrameParams& p, const GyroFrameStiffness& K,
                                    double d1, double d2, const char* cause, const std::string& remedy) {
  const double growth = gyro_frame_growth_rate(p, K, d1, d2);
  if (growth > 0.0) {
    r.fail("gyro", "d1", std::string(cause) + " makes the nutation grow at " + format_3g(growth) +
                             " /s (a circulatory force, model header): " + remedy);
  }
}

// Refuses ([loop] plant_substeps) a plant sub-step too long for RK4 on the model's fastest mode at rest.
template <class Model>
void refuse_long_rk4_substep(SceneReader& r, const LoopConfig& loop, const Model& m) {
  const double h_sub = loop.tick_s() / loop.substeps;
  const dynamics::StepCheck step =
      dynamics::check_step(dynamics::Method::kRk4, dynamics::fastest_mode(m, 0.0, Model::make_state(0, 0)), h_sub);
  if (!step.ok) r.fail("loop", "plant_substeps", step.message);
}

}  // namespace gyrostab::tools
