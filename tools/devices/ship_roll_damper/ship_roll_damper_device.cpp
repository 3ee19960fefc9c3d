// The ship roll damper in the registry (tools/devices/registry.cpp).
#include "tools/devices/ship_roll_damper/ship_roll_damper_scene.hpp"
#include "tools/devices/ship_roll_damper/ship_roll_damper_study.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kShipRollDamper{
    .name = "ship_roll_damper",
    .summary =
        "The gyroscopic ship roll damper of Magnus §14.2, (14.8), with large-angle terms and precession end "
        "stops (sim/plants/ship_roll_damper_plant.hpp, docs/models/ship-roll-damper.md), in a regular or "
        "irregular beam sea, under the firmware's passive precession brake or active precession control. The "
        "same ship with the gyro locked runs in the same sea as the unstabilized reference. Shipped: "
        "`sim/scenes/ship-roll-damper-passive.toml`, `sim/scenes/ship-roll-damper-active.toml`, and a roll-decay "
        "trial in calm water, `sim/scenes/ship-roll-damper-roll-decay.toml`. Integrator: "
        "`rk4` (the only one).",
    .figures =
        "The passive keys are refused with `law = \"active\"` and the active keys with `law = \"passive\"`. "
        "A roll-decay trial (calm water: a regular sea of E0 = 0, `[ship] roll0_deg` ≠ 0) adds `decay_modes`: per "
        "root of the loop near the upright `decay_rate_per_s`, `frequency_rad_s` (measured: a recurrence fitted to "
        "φ every 50 ms; `decay_fit_samples`) beside `_predicted` (continuous) and `_predicted_sampled` (hold, "
        "latency, the firmware's law; `sampled_loop_max_abs_z`). "
        "Figures: `roll_rms_rad`, `roll_rms_unstabilized_rad`, `roll_rms_ratio` (their ratio σ/σ₀), `roll_reduction` (1 − σ/σ₀, what the field calls roll reduction), "
        "`roll_max_rad`, `roll_max_unstabilized_rad`, `precession_max_rad`, `precession_torque_max_Nm`, "
        "`wave_moment_rms_Nm`, `statistics_from_s`, `stop_penetration_max_rad` and "
        "`stop_penetration_bound_rad` (the end stops' largest penetration, and the bound the run's peaks "
        "allow: (H|φ'|max + |M2|max + |Q|φ'²max/2)/k_s + |β'|max/ω_s, /e for ζ_s ≥ 1), `stop_contacts` "
        "(contact onsets after settle_s) and the mount loads after settle_s "
        "(docs/models/ship-roll-damper.md#mount-loads): `roll_moment_max_Nm`, `yaw_moment_max_Nm` and "
        "`yaw_moment_rms_Nm` (net on the hull: a twin pair's cancel), `yaw_moment_unit_max_Nm` and "
        "`pitch_moment_max_Nm` (one unit). report.json `\"course\"`: speed, heading, turn rate, units, the "
        "regular wave's encounter frequency and the turning bound `turn_rate_bound_deg_s` = −(q + k_c)/H. "
        "report.json "
        "`\"plant\"`: the assembled model and its state size (4 + the locked reference's 4); `\"limits\"`: "
        "`precession_stop_rad`, `precession_torque_limit_Nm` and, active, `precession_soft_limit_rad`. No "
        "reduced model is offered for the ship: (14.8) keeps both inertias (roll A, case B) — nutation and "
        "precession — and a ship gyro has no scale separation between them (ω_N = H/sqrt(AB) ≈ 1.5 rad/s "
        "against the roll's 0.6 rad/s for the default ship, ε = O(1)), so the precession theory P0 does not "
        "hold (docs/models/gimbal-gyro.md).",
    .read = read_ship_roll_damper,
    .doc = ship_roll_damper_doc,
    .accuracy = ship_roll_damper_accuracy,
};

}  // namespace gyrostab::tools
