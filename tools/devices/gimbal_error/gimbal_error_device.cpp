// The gimbal error of a position gyro in the registry (tools/devices/registry.cpp).
#include "tools/devices/gimbal_error/gimbal_error_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kGimbalError{
    .name = "gimbal_error",
    .summary =
        "The kinematic (gimbal) error of a free two-gimbal position gyro of Magnus §12.1, (12.2)-(12.20) "
        "(sim/plants/gimbal_error_plant.hpp, sim/models/position_gyro_gimbal_error.hpp, "
        "docs/models/gimbal-error.md): the rotor axis fixed in inertial space, the vehicle yawing, pitching "
        "and rolling as prescribed (ψ, ϑ, φ each a constant, a rate and a harmonic), the attitude integrated "
        "from the body rates and the gimbal angles α, β read from it for one of the six mountings \"321\", "
        "\"312\", \"213\", \"231\", \"123\", \"132\". No torquers: the controller "
        "(firmware/app/free_instrument_controller.hpp) only runs the loop. Shipped: "
        "`sim/scenes/gimbal-error-heading-gyro-turn.toml` (the heading gyro in a 30° banked level turn: "
        "book 4.117°), `sim/scenes/gimbal-error-recorded-motion.toml` (the same turn from a recorded motion: "
        "[base motion](#base-motion); `[motion] kind = \"harmonic_roll\"`, the default, is the [yaw], [pitch], "
        "[roll] generator; with `prescribed` or `recorded` the body rates and the attitude, and the Euler angles "
        "read from it, are the motion's, and the [yaw], [pitch], [roll] keys stay the nominal motion of the step "
        "rule and the level-turn figure). Integrator: `rk4` (the only one).",
    .figures =
        "Figures: `mounting`; `alpha_error` and `beta_error`, each the gimbal angle against the vehicle angle "
        "it nominally reads (`measures`: roll, pitch or yaw), with `max_abs_rad`, the signed `at_max_rad`, "
        "and where it first occurred: `time_s`, `yaw_rad`, `pitch_rad`, `roll_rad`; "
        "`closed_form_alpha_max_diff_rad` and `closed_form_sin_beta_max_diff_rad`, the simulated angles "
        "against the book's closed form of the mounting at the prescribed Euler angles (α skipped where "
        "cosβ < 1e-3, counted in `closed_form_skipped_near_gimbal_lock`); `attitude_error_max_rad`, the "
        "integrated attitude against the analytic one; `level_turn` (null unless the heading gyro \"321\" "
        "turns level at constant bank): `bank_rad`, `book_extreme_abs_rad` and `book_extreme_heading_rad` "
        "(the extreme of (12.14) at tan²ψ = 1/cosφ), `measured_extreme_abs_rad`, "
        "`measured_extreme_heading_rad` (the heading of the measured extreme from the nearest multiple of "
        "180°: (12.14) has period π and is odd about it), `formula_12_14_max_diff_rad`; `ticks`. CSV columns: `alpha_rad`, "
        "`beta_rad`, `alpha_error_rad`, `beta_error_rad`, `yaw_rad`, `pitch_rad`, `roll_rad`, `status_bits`.",
    .read = read_gimbal_error,
    .doc = gimbal_error_doc,
};

}  // namespace gyrostab::tools
