// The power stabilizer's checks that need the plant built with the scene's options: physical validity, the
// plant step against the fastest mode (sim/dynamics/step_validation.hpp), the explicit drive coupling's
// stable step, the controller's start-up check with A, B as the plant has them, the loop at the inner
// gimbal's operating points (the gimbal-lock approach), and — for the precession model — where P0 holds and
// its expected error. Also the loop's predicted nutation root, which the checks and the figures share.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "firmware/control/power_stabilizer_loops.hpp"
#include "tools/devices/power_stabilizer/power_stabilizer_scene.hpp"
#include "tools/scene/scene_reader.hpp"

namespace gyrostab::tools {

// The checks of each variant group (power_stabilizer_check_{rigid,elastic,precession}.cpp).
bool check_power_stabilizer_rigid(SceneReader& r, PowerStabilizerScene& s);
bool check_power_stabilizer_elastic(SceneReader& r, PowerStabilizerScene& s);
bool check_power_stabilizer_precession(SceneReader& r, PowerStabilizerScene& s);

// Fills the derived parts of the scene (op_loops, controller.loops.A/B, full_loop, reduced_expected);
// problems go to the reader. false when refused.
bool check_power_stabilizer_plant(SceneReader& r, PowerStabilizerScene& s);
// The checks above in words, for docs/scenes.md.
std::vector<std::string> power_stabilizer_plant_rules();

// The loop's nutation root from what the controller's check assumes (A incl. reflected inertia and, when
// elastic, A^P — the quasi-static limit; total viscous damping = commanded + bearings):
//   torque mode (14.23): AB λ⁴ + (A d2 + B d1) λ³ + (H² + d1 d2) λ² + H (k1 + k2) λ + k1 k2 = 0
//   back-EMF (14.29) with bearings: AB λ³ + (A d2 + B D1) λ² + (H² + D1 d2) λ + H r s = 0, D1 = s d + d1
// The root with the largest |Im|; Im reported ≥ 0.
std::complex<double> predicted_nutation(const firmware::PowerStabilizerConfig& l);

// The first disturbance step that is one (a torque applied from t = 0 is a load the loop starts with, e.g.
// the hold of [initial] beta0_deg, not a step).
double first_step_s(const plants::PowerDisturbance& d);

// When the nutation is measured: after the inner-axis step (M2) if there is one — it moves α, which enters no
// equation, so the loop stays at one operating point — else after the first step. The window ends at the next
// step (a second input breaks the fitted recurrence) or after `window_s`.
struct NutationWindow {
  double step_s{0.0};  // the step that excites the nutation [s]
  double end_s{0.0};   // [s]
};
NutationWindow nutation_window(const plants::PowerDisturbance& d, double window_s);

}  // namespace gyrostab::tools
