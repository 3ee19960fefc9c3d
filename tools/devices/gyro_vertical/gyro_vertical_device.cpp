// The gyro vertical in the registry (tools/devices/registry.cpp).
#include "tools/devices/gyro_vertical/gyro_vertical_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kGyroVertical{
    .name = "gyro_vertical",
    .summary =
        "The gyro vertical (gyro horizon) of Magnus §12.3, (12.35)-(12.51), on an aircraft "
        "(sim/plants/gyro_vertical_plant.hpp, sim/models/gyro_vertical.hpp on the master equation (10.22), "
        "docs/models/gyro-vertical.md) in the track frame (forward, right, down) of the [vehicle "
        "motion](#vehicle-motion) (default latitude 50°), erected by the firmware's correction law "
        "(firmware/app/gyro_vertical_controller.hpp: the five rows of (12.35), the turn cut-out, a torque "
        "limit). Sensors: the erection sensor (tilt from the apparent vertical), gimbal-rate pick-offs, and "
        "a turn indicator — a P rate gyro with its own dynamics (sim/sensors/rate_integrating_gyro.hpp, "
        "(15.1)-(15.6)) on the aircraft's normal axis (coordinated flight: bank = the apparent vertical's "
        "roll angle) — whose reading drives the cut-out. Shipped: "
        "`sim/scenes/gyro-vertical-aircraft-turn.toml`, `sim/scenes/gyro-vertical-dead-zone.toml` (bearing "
        "Coulomb friction: the dead zone of Fig. 12.12). Integrator: `rk4`; the step is checked against the "
        "nutation H/sqrt(AB) (full form).",
    .figures =
        "Figures: `delta_s` (f1/H), `omega_P_rad_s` ((c + c1)/H), `resonance_turn_rate_rad_s` (−ω^P), "
        "`indicated_bank_error_max_rad` (max |α|), `alpha_end_rad`, `beta_end_rad`, `H_Nms`, `ticks`, "
        "`nutation_frequency_rad_s` (full form), `prediction_applies` (the law is the linear one: rows 1 and 4, "
        "equal on both axes, no friction); when the first segment flies straight with the linear law: "
        "`erection_decay_rate_per_s`, `erection_frequency_rad_s` (measured: the planar recurrence fitted to 1 s "
        "means of (α, β) between `erection_window_from_s` and `erection_window_to_s`, the sensor errors' response "
        "through the sampled loop taken off, `erection_noise_response_max_rad`, `erection_fit_samples`) beside "
        "`erection_decay_rate_per_s_predicted_sampled`, `erection_frequency_rad_s_predicted_sampled` (the "
        "sampled loop: the model linearised on the starting frame, the firmware law, hold and latency; "
        "`sampled_loop_max_abs_z`) and the continuous loop's `_predicted`; else `erection_root` (why not); and `segments`: per manoeuvre segment (0 = the final cruise) "
        "`t_start_s`, `t_end_s`, `turn_rate_rad_s` (Ω3), `alpha_L_rad`, `beta_L_rad`, `correction_cut_out`, "
        "`alpha_end_rad`, `beta_end_rad` beside the book's `alpha_book_end_rad`, `beta_book_end_rad` (z = z_eq + "
        "(z0 − z_eq) e^(−[δ + i(ω + ω^P)]t) from the segment's start, (12.45)/(12.39)) and the steady "
        "`alpha_G_rad`, `beta_G_rad` (z_G of (12.47) in a steady turn); the book neglects the Earth and transport"
        " rates, whose steady error is ≈ |Ω_h| H/f. `turn_indicator_over_true` (≈ cos(bank), (15.6)). With "
        "bearing friction (r1 or r2 > 0), `dead_zone`: `friction_model`, `r1_Nm`, `r2_Nm`, `residual_tilt_rad` "
        "(e1, e2 at the end), `held` (stick_slip: each gimbal held in the last step), `late_rate_max_rad_s` "
        "(largest |α'|, |β'| over the run's last tenth: the creep) and, for the linear correction alone, `band` "
        "(`e1_rad`, `e2_rad`: the stuck set |f2 e1 + T2| ≤ r2, |−f1 e2 + T1| ≤ r1 at the end, T the frame's "
        "torques of (10.22) at rest; `half_width_rad` r2/f2, r1/f1) and `outside_band_rad`; with stick-slip "
        "friction error_estimate covers the run's first second (the breakaway and the nutation's reversals) and "
        "assumes order 1 (its events fall on step boundaries). Limits: `torquer_limit_Nm`, `turn_cutout_rad_s` "
        "(when the cut-out is on). CSV columns: `alpha_rad`, `beta_rad`, `alpha_L_rad`, `beta_L_rad`, `M1_Nm`, "
        "`M2_Nm`, `turn_rate_rad_s`, `turn_indicator_rad_s`, `status_bits`.",
    .read = read_gyro_vertical,
    .doc = gyro_vertical_doc,
};

}  // namespace gyrostab::tools
