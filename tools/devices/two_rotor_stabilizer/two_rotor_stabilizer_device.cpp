// The two-rotor stabilizers in the registry (tools/devices/registry.cpp).
#include "tools/devices/two_rotor_stabilizer/two_rotor_stabilizer_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kTwoRotorStabilizer{
    .name = "two_rotor_stabilizer",
    .summary =
        "Two-rotor stabilizers of Magnus §14.3.4 (sim/plants/two_rotor_stabilizer_plant.hpp, "
        "docs/models/two-rotor-stabilizer.md): `kind = \"gyro_frame\"` — the gyro frame of Fig. 14.7, two "
        "counter-rotating gyros with mirrored linked cases in one frame, a stabilization motor on the frame "
        "driven by the case angle (sim/models/two_rotor_gyro_frame.hpp), on a base with constant and harmonic "
        "rotation rates: a base rotation about axis 2 does not turn the frame; `kind = \"two_axis\"` — the "
        "two-rotor two-axis stabilizer of Fig. 14.8, a platform in two frames with one gyro per axis "
        "(sim/models/two_rotor_two_axis.hpp). The firmware (firmware/app/two_rotor_stabilizer_controller.hpp) "
        "refuses gains outside the Hurwitz region of the closed loop. Shipped: "
        "`sim/scenes/two-rotor-gyro-frame.toml`, `sim/scenes/two-rotor-two-axis.toml`. Integrator: `rk4`.",
    .figures =
        "Figures: `alpha_peak_rad`, `alpha_final_rad` (frame 1), `beta1_final_rad` against "
        "`beta1_expected_rad` = M1/k1 (the steady case angle under the final disturbance), `gain_margin` (the "
        "largest stable scale of (k1, k2), from the law's Hurwitz test); gyro frame: `single_rotor_alpha_peak_rad`, "
        "`single_rotor_alpha_final_rad` (a single rotor of spin 2H and case inertia 2B under the same base "
        "motion, law and disturbance, integrated beside the plant), `link_torque_peak_Nm` (TR2); two-axis: "
        "`gamma_peak_rad`, `beta2_final_rad` against `beta2_expected_rad` = −σ M2/k2. CSV columns: "
        "`alpha_rad`, `gamma_rad`, `beta1_rad`, `beta2_rad`, `M1K_Nm`, `M2K_Nm`, `single_rotor_alpha_rad`, "
        "`link_torque_Nm`, `status_bits`.",
    .read = read_two_rotor_stabilizer,
    .doc = two_rotor_stabilizer_doc,
};

}  // namespace gyrostab::tools
