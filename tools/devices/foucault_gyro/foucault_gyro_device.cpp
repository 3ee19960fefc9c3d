// The Foucault gyro in the registry (tools/devices/registry.cpp).
#include "tools/devices/foucault_gyro/foucault_gyro_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kFoucaultGyro{
    .name = "foucault_gyro",
    .summary =
        "Foucault's direction-finding gyros of Magnus §13.1, (13.1)-(13.4) (sim/plants/foucault_gyro_plant.hpp, "
        "sim/models/foucault_gyro.hpp, docs/models/foucault-gyro.md): a rotor of held spin momentum H in a frame "
        "with one degree of freedom on an Earth-fixed base at latitude φ, damped viscously on its free axis. "
        "`kind = \"declinometer\"` (Fig. 13.1): frame free about the vertical, rotor axis horizontal; the "
        "directive torque −H ω^E cosφ sinα (13.2) turns it into the meridian. `kind = \"inclinometer\"` "
        "(Fig. 13.2): frame free about the east-west axis, rotor in the meridian plane (ϑ: elevation of its north "
        "end, positive about the east axis); the torque −H ω^E sin(ϑ − φ) about the east axis ((13.4), whose "
        "axis 2 points west) turns it parallel to the Earth's axis, ϑ = φ, H like-directed to the Earth's "
        "rotation. The exact one-axis equation "
        "J x'' + d x' + H w sin x + (J_rotor_axis − J_cross) w² sin x cos x = 0 (w = ω^E cosφ or ω^E; the last "
        "term the frame's centrifugal torque). No torquers, no cage: the controller "
        "(firmware/app/free_instrument_controller.hpp) only runs the loop. Shipped: "
        "`sim/scenes/foucault-declinometer-settling.toml`, `sim/scenes/foucault-inclinometer-settling.toml`. "
        "Integrator: `rk4` (the only one).",
    .figures =
        "Figures (x = α or ϑ − φ, the offset from the equilibrium): `period_measured_s` (extrema below "
        "`small_amplitude_rad`) against `period_linear_s` (2π/ω_d of the linearised equation, centrifugal term "
        "and damping included) and `period_book_13_6_s` = 2π sqrt(J/(H w)); `decay_rate_measured_s` against "
        "`decay_rate_linear_s` = d/(2J); `equilibrium_measured_rad` (Aitken's Δ² on the last three extrema) and "
        "`angle_end_rad`, `offset_end_rad` against `equilibrium_book_rad` (0 or φ); `settled`, "
        "`settling_time_measured_s` (|x| last above `settle_tolerance_rad`) against `settling_time_envelope_s` "
        "(ln(|x0|/tol)/σ, the linear envelope of the extrema); `damping_ratio`, `directive_rate_rad_s` (w), "
        "`directive_torque_per_rad_Nm` (H w), `centrifugal_relative` ((J_rotor_axis − J_cross) w/H), `H_Nms`, "
        "`latitude_deg`, `kind`, `angle0_rad`, `extrema`, `extrema_small`, `ticks` (null where too few extrema). "
        "CSV columns: `angle_rad` (α or ϑ), `offset_rad`, `rate_rad_s`, `directive_torque_Nm` (the rotor's "
        "torque on the frame about the free axis), `envelope_rad` (|x0| e^(−σt)), `status_bits`.",
    .read = read_foucault_gyro,
    .doc = foucault_gyro_doc,
};

}  // namespace gyrostab::tools
