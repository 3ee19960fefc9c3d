// The CMG cluster in the registry (tools/devices/registry.cpp).
#include "tools/devices/cmg_cluster/cmg_cluster_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kCmgCluster{
    .name = "cmg_cluster",
    .summary =
        "A rigid spacecraft steered by a cluster of single-gimbal control moment gyros: the three-axis servo gyro "
        "of Magnus §14.4, (14.45), on the gyrostat of §4.1 (sim/models/cmg_cluster_spacecraft.hpp, geometry "
        "sim/models/cmg_geometry.hpp: the four-unit pyramid at skew β or explicit axes; docs/models/cmg-cluster.md). "
        "The gimbal rate servos (PI, motor torque limit, poles at −ω_s) are in the plant, as in a CMG's own "
        "electronics; the firmware (firmware/app/cmg_cluster_controller.hpp) closes the attitude loop by "
        "quaternion error feedback u = −K_p q_e,vec sign(q_e,0) − K_d ω + ω × H and steers the gimbals by ν = "
        "−A⁺u with the pseudo-inverse, the singularity-robust inverse or the generalized singularity-robust "
        "inverse (Wie's deterministic off-diagonal dither, timed by the tick). The four units' gimbal angles, rates "
        "and rate commands travel in the contract's cluster fields (CAN: the `cluster` node). "
        "Shipped: `sim/scenes/cmg-cluster-slew.toml` (30° rest-to-rest about x), "
        "`sim/scenes/cmg-cluster-singularity-pseudo-inverse.toml` and "
        "`sim/scenes/cmg-cluster-singularity-robust.toml` (a 60° slew about x whose momentum demand crosses the "
        "pyramid's internal singularity at 2h cosβ: the pseudo-inverse stalls there, the robust inverse passes), "
        "`sim/scenes/cmg-cluster-singularity-generalized.toml` (the same with the gyro noise off: only the "
        "generalized inverse passes), `sim/scenes/cmg-cluster-envelope-x.toml` (a 180° slew about x that asks for "
        "more momentum than the cluster holds: it saturates at the envelope 2h(1 + cosβ) along −x and the slew "
        "completes). "
        "Integrator: `rk4` (the only one).",
    .figures =
        "Figures: the attitude pair about the slew axis (a principal axis; docs/sampled-data.md) as natural "
        "frequency and damping ratio, `attitude_natural_frequency_rad_s`, `attitude_damping_ratio` (measured: "
        "the body-rate noise's response `attitude_noise_response_max` taken off (q, ω), the modal filter "
        "y = W (q, ω) that nulls the other two attitude pairs' output directions, the planar recurrence of y fitted "
        "to means over 1/(50 ω_a) from `attitude_window_from_s`, when the error falls below 0.1°; "
        "`attitude_fit_samples`) beside `_predicted_sampled` (the 19-state model linearised where the run ends, "
        "the firmware's law probed through the frame, hold and latency; `sampled_loop_max_abs_z`, whose neutral "
        "null-motion mode sits at 1 ± 1e-8) and `_predicted` (the design J s² + K_d s + K_p/2); "
        "`attitude_pair_share` (the pair's share of the slew axis's motion; below 0.95 `attitude_loop` says the "
        "configuration couples the axes); else `attitude_loop` (why not). `final_attitude_error_deg`, `settling_time_s` (the last time the error was outside "
        "`settle_band_deg`; null if it never settled), `min_singularity_measure` = min det(AAᵀ)/h⁶ along the run "
        "and `min_singularity_measure_at_s`, beside `singularity_measure_at_zero_momentum`; "
        "`near_singular_time_s` (measure below `near_singular_measure`); `rate_limited_ticks` (gimbal rates scaled "
        "to max_gimbal_rate) and `singular_ticks` (the pseudo-inverse refused to invert); "
        "`peak_cmg_momentum_Nms` against `envelope_along_slew_axis_Nms` and `envelope_x/y/z_Nms` (h Σ sqrt(1 − "
        "(e·g_i)²)) and `pyramid_internal_singularity_Nms` = 2h cosβ (the pyramid's; null for explicit axes); "
        "`peak_cmg_momentum_along_slew_axis_Nms` (max |H_cmg·e|) against `envelope_along_slew_axis_closed_form_Nms` "
        "(the pyramid along a principal axis: 2h(1 + cosβ) along x or y, 4h sinβ along z; null otherwise) with "
        "`envelope_reached_rel_error`; `peak_body_rate_rad_s`, `peak_gimbal_rate_rad_s`, `peak_gimbal_motor_torque_Nm`; "
        "`momentum_drift_Nms` = max |L_W(t) − L_W(0)| (the inertial angular momentum, conserved); `steering`, "
        "`slew_deg`, `ticks`. CSV columns: `attitude_error_deg`, `omega_x/y/z_rad_s`, `H_cmg_x/y/z_Nms`, "
        "`delta_1..4_rad`, `singularity_measure`, `status_bits`. report.json `\"limits\"`: "
        "`max_gimbal_rate_rad_s`, `settle_band_deg`, `near_singular_measure`.",
    .read = read_cmg_cluster,
    .doc = cmg_cluster_doc,
};

}  // namespace gyrostab::tools
