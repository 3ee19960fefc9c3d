// The directional (heading) gyro in the registry (tools/devices/registry.cpp).
#include "tools/devices/directional_gyro/directional_gyro_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kDirectionalGyro{
    .name = "directional_gyro",
    .summary =
        "The directional (heading) gyro of Magnus §12.2, (12.21)-(12.34), on an aircraft "
        "(sim/plants/directional_gyro_plant.hpp, sim/models/directional_gyro.hpp, docs/models/directional-gyro.md): "
        "rotor axis horizontal, outer gimbal axis along the aircraft's normal axis (the outer-gimbal angle is the "
        "heading indication), precession theory with the gimbal kinematics exact (the bank goes through the "
        "gimbals: coordinated flight, bank = the apparent vertical's roll angle), on the [vehicle "
        "motion](#vehicle-motion) (default latitude 50°). The firmware (firmware/app/directional_gyro_controller.hpp) "
        "applies the drift compensation (12.22) set for a latitude and speed, the heading correction (12.23) toward "
        "the compass and the inter-gimbal correction (12.24), with a turn cut-out and a torque limit. Sensors: the "
        "heading and inner-gimbal pick-offs, the compass (true heading + white noise), the turn rate. Shipped: "
        "`sim/scenes/directional-gyro-earth-rate.toml` (50°, east at 250 m/s: 11.52 + 9.65 °/h without "
        "compensation, ≈ 0 with it), `sim/scenes/directional-gyro-turn-error.toml` (two level turns at 9° bank with "
        "the inter-gimbal correction c = 1: the turn error (12.29), (12.32)). Integrator: `rk4`.",
    .figures =
        "Figures: `H_Nms`, `ticks`, `drift`: over the run, `measured_deg_h` (the indicated-minus-true heading's "
        "mean rate), `free_gyro_deg_h` (the same less the torquers' precession −M2/(H cos β): what the gyro "
        "drifts without torques), the book's (12.22) along the flown path `book_12_22_deg_h` = "
        "`earth_rate_term_deg_h` + `transport_term_deg_h`, `compensation_deg_h` (the law's (12.22) rate at its "
        "latitude, speed and the indicated heading) and `book_residual_deg_h` (their sum); `bank_term_deg_h` (what "
        "(12.22) leaves out: the case's normal axis, banked by φ_b — the Coriolis bank of a great circle — picks "
        "up the level frame's rate across the track, ∫Ω_left sin φ_b dt), `book_12_22_with_bank_deg_h`, "
        "`book_residual_with_bank_deg_h`, and the free gyro's drift against (12.22) "
        "`free_gyro_rel_error_vs_book_12_22` and with the bank term `free_gyro_rel_error_vs_book_with_bank` (null "
        "without a reference); `final_heading_error_deg`. "
        "When the last segment flies straight and level with the inter-gimbal correction on: "
        "`inner_gimbal_decay_rate_per_s` (measured: the real root of a recurrence fitted to β between "
        "`inner_gimbal_window_from_s` and `inner_gimbal_window_to_s`, `inner_gimbal_fit_samples`) beside "
        "`inner_gimbal_decay_rate_per_s_predicted_sampled` (the sampled loop linearised where the run ends: hold, "
        "latency, the firmware's corrections; `sampled_loop_max_abs_z`, whose neutral heading mode the "
        "compensation's heading dependence moves by ±1e-7), `inner_gimbal_decay_rate_per_s_predicted` (the "
        "continuous loop's) and `inner_gimbal_decay_rate_book_12_24_per_s` (k/H); else `inner_gimbal_root` (why not). "
        "`segments`: per manoeuvre segment (0 = the final cruise) `t_start_s`, `t_end_s`, `turn_rate_rad_s`, "
        "`bank_rad` (mean), `heading_turned_rad`, `beta_start_rad`, `beta_end_rad`, `rotor_azimuth_change_rad` "
        "(δ: the rotor axis's azimuth in the level frame), `correction_cut_out`, and in a turn `c` = k/(H|ψ'0|) "
        "(12.27); where the book's turn-error setting holds (a turn, the correction on, the rotor along the flight "
        "direction and β ≈ 0 at the segment's start) `book_applies` with `beta_book_end_rad` ((12.25) + (12.29)) "
        "and `delta_book_rad` ((12.32) as corrected; its sign follows the turn's). CSV columns: "
        "`indicated_heading_rad`, `true_heading_rad`, `heading_error_rad`, `compass_rad`, `alpha_rad`, `beta_rad`, "
        "`bank_rad`, `rotor_azimuth_rad`, `M1_Nm`, `M2_Nm`, `status_bits`.",
    .read = read_directional_gyro,
    .doc = directional_gyro_doc,
};

}  // namespace gyrostab::tools
