// The gyrocompass in the registry (tools/devices/registry.cpp).
#include "tools/devices/gyrocompass/gyrocompass_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kGyrocompass{
    .name = "gyrocompass",
    .summary =
        "The pendulous gyrocompass of Magnus ch. 13, (13.7)-(13.39) (sim/plants/gyrocompass_plant.hpp, "
        "sim/models/gyrocompass.hpp on the master equation (10.22), docs/models/gyrocompass.md) in the "
        "geographic frame (up, east, north) of the [vehicle motion](#vehicle-motion) (default latitude 50°): "
        "at rest for the fixed-base compass, or a ship. The sphere's mechanical pendulosity c acts on the "
        "tilt from the apparent horizon; the firmware (firmware/app/gyrocompass_controller.hpp) adds the "
        "damping torque about the vertical M1 = −f β_lvl (13.8) and the electrical pendulosity M2 = −c_e "
        "β_lvl, both from the level sensor; c_e may be Schuler-tuned (13.26) for a latitude and f set by a "
        "damping ratio of (13.12). Rolling error: with `swing_inertia` > 0 the sphere swings about its rotor "
        "axis under the ship's roll (13.29)-(13.36). Shipped: "
        "`sim/scenes/gyrocompass-fixed-base-settling.toml`, "
        "`sim/scenes/gyrocompass-ship-crossing-latitudes.toml`. Integrator: `rk4`; the step is checked "
        "against the nutation (full form) and the swing.",
    .figures =
        "Figures: `omega_c_s` ((c + c_e)/H), `omega_c_schuler_tuned_here_s` ((13.26) at the final latitude), "
        "`delta_s`, `latitude_end_deg`, `alpha_end_rad`, `beta_end_rad`, `alpha0_book_13_11_rad`, "
        "`beta0_book_13_11_rad`; `period_measured_s` (from the extrema of α) beside `period_book_13_12_s` "
        "(2π/ω^K, null if aperiodic) and, full form, `period_book_13_16_s`, `nutation_frequency_rad_s`; "
        "`decay_rate_measured_s` (last three extrema), `decay_rate_measured_first_s` (first three) beside "
        "`decay_rate_book_13_12_s` (δ/2); on a base at rest the compass mode of the model linearised at its "
        "equilibrium, `decay_rate_per_s_predicted`, `period_s_predicted`, and of the loop sampled with the hold "
        "and the latency, `…_predicted_sampled`, `sampled_loop_max_abs_z`, beside the measured `decay_rate_per_s`, "
        "`period_s` (a recurrence fitted to α every extrema_sample_s from 600 s; docs/sampled-data.md) — null "
        "with `linear_prediction` saying why when the vehicle moves; `alpha_eq_measured_rad`, `beta_eq_measured_rad` (Aitken's Δ² on "
        "the last three extrema); `alpha_extrema`, `schuler_period_s`, `tune_latitude_deg`, `ticks`; "
        "`segments`: per manoeuvre segment (0 = the final cruise) `t_start_s`, `t_end_s`, "
        "`latitude_end_deg`, `heading_end_deg`, `v_north_end_m_s`, `v_east_end_m_s`, `alpha_end_rad` beside "
        "`alpha_eq_book_end_rad` (the steady state of (13.22) with damping: −(Ω2 + δβ0)/Ω3, β0 = Ω1/(ω^c + "
        "Ω3)) and `speed_deviation_book_13_23_rad`, `deviation_from_equilibrium_max_rad` (max |α − α_eq(t)|: "
        "the ballistic deviation, 0 when tuned (13.26)), `alpha_mean_minus_eq_rad`; with the swing "
        "`rolling_error_book_13_38_rad`, `swing_frequency_rad_s`, `roll_acceleration_amplitude_m_s2`. "
        "Limits: `torquer_limit_Nm`. CSV columns: `alpha_rad`, `beta_rad`, `alpha_eq_rad`, `level_rad`, "
        "`M1_Nm`, `M2_Nm`, `latitude_deg`, `heading_deg`, `swing_rad`, `status_bits`.",
    .read = read_gyrocompass,
    .doc = gyrocompass_doc,
};

}  // namespace gyrostab::tools
