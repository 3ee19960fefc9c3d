// The coning platform in the registry (tools/devices/registry.cpp).
#include "tools/devices/coning/coning_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kConing{
    .name = "coning",
    .summary =
        "Vibration effects on rate gyros, the coning error of Magnus §15.5, (15.36)-(15.42) "
        "(sim/plants/coning_plant.hpp, sim/models/coning_platform.hpp, the gyro "
        "sim/sensors/single_axis_gyro_coning.hpp, docs/models/coning.md): a platform turning about its axis 3 "
        "on a base with angular vibration of amplitude Φ at ν about an axis at δ from axis 3 towards axis 1 "
        "(planar, or conical with the spin-axis component lagging by ε), driven by a geared servo and carrying "
        "a single-axis P-gyro (c2 > 0) or I-gyro (c2 = 0) with its input axis on the platform's axis 3 and its "
        "spin axis on axis 1; the gyro's gimbal kinematics are exact, so its effective input axis tilts by β. "
        "The firmware (firmware/app/coning_controller.hpp, firmware/control/coning_null_law.hpp) slaves the "
        "platform so that the gyro reads zero: the platform then turns relative to the base at minus the "
        "gyro's coning error. Shipped: `sim/scenes/coning-p-gyro-planar-vibration.toml` (the constructed case "
        "of (15.41): −3.08e-3 rad/s), `sim/scenes/coning-i-gyro-conical-vibration.toml` (an I-gyro under "
        "conical vibration; planar would give none, (15.42)), `sim/scenes/coning-recorded-motion.toml` (the base "
        "driven by a recorded motion, [base motion](#base-motion): `[motion] kind = \"harmonic_roll\"` — the "
        "default — is the [vibration] generator; with `prescribed` or `recorded` the [vibration] keys stay the "
        "nominal vibration of the step rules and the figures), `sim/scenes/coning-goodman-robinson-sidereal-day.toml` "
        "(no vibration: the base at 50°N turning with the Earth, `[motion] prescribed` with `pitch_deg` and "
        "`yaw_rate_deg_s`; the slaved platform turns by −2π sin λ in a sidereal day, (15.35)). Integrator: `rk4` "
        "(the only one).",
    .figures =
        "Figures, after settle_s over whole vibration periods (rounded to ticks): `drift_rate_rad_s` (the "
        "platform's turn relative to the base: the slope between its azimuth averaged over the first and the "
        "last period) against `coning_rate_book_rad_s` (the open-loop error: P −H Ω10 Ω30 cos ε/(2 c2) "
        "(15.39)-(15.41), I −H Ω10 Ω30 sin ε/(2 d2 ν)) with `drift_rel_error_vs_book` (drift = −error), and "
        "`drift_predicted_rad_s` (first order through the gyro's response G(iν), the loop's sensitivity at ν "
        "and the mean cos φ of the drifting platform) with `drift_rel_error_vs_prediction`, and the same through the "
        "sensitivity of the loop as it runs (sum, PI, hold, latency at z = e^{iνT}): "
        "`drift_predicted_sampled_rad_s`, `drift_rel_error_vs_prediction_sampled`, `loop_sensitivity_sampled_abs`; "
        "`coning_rate_first_order_rad_s` (open loop, through G(iν)); `platform_mean_rate_rad_s` (its absolute "
        "rate about axis 3, = the drift), `gyro_mean_reading_rad_s` (nulled by the loop), `mean_cos_phi`, "
        "`max_abs_beta_rad`, `loop_sensitivity_abs`, `gyro_kind`, `Omega10_input_rad_s`, "
        "`Omega30_spin_rad_s`, `vibration_period_s`, `periods`, `statistics_from_s`, `ticks` (null measurements when fewer than two "
        "periods completed after settle_s; a relative error whose reference is 0 — no vibration — is null). When "
        "the base's axis 3 runs round a cone (`[motion] kind = \"prescribed\"` with a constant `pitch_deg` ϑ, a "
        "`yaw_rate_deg_s` ψ' and no harmonic): `goodman_robinson` — the Goodman–Robinson theorem (15.30)-(15.35): "
        "`turn_rad`, the platform's turn relative to the base over one circuit T = 2π/|ψ'| (the nearest whole "
        "ticks, `span_s`) from settle_s (`from_s`), against `turn_rad_predicted` = (A − 2πn) span/T, "
        "`turn_rel_error`, `turn_error_rad`, with `turn_per_circuit_book_rad` = −sgn(ψ') 2π cos ϑ, "
        "`enclosed_area_sr` A, `cone_half_angle_rad`, `latitude_rad` = 90° − ϑ, `circuit_s` (null measurements "
        "when the run ends before the circuit). CSV columns: `phi_rad` (platform azimuth relative to the base), "
        "`phi_rate_rad_s`, `platform_rate_rad_s` (absolute, about axis 3), `beta_rad`, `reading` (P (c2/H) β "
        "[rad/s], I (d2/H) β [rad]), `drive_voltage_V`, `status_bits`. report.json `\"limits\"`: "
        "`drive_voltage_limit_V`.",
    .read = read_coning,
    .doc = coning_doc,
};

}  // namespace gyrostab::tools
