// The servo gyro in the registry (tools/devices/registry.cpp).
#include "tools/devices/servo_gyro/servo_gyro_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kServoGyro{
    .name = "servo_gyro",
    .summary =
        "The servo gyro as a gyroscopic vibrator drive of Magnus §14.4, (14.41)-(14.44), Fig. 14.9 "
        "(sim/plants/servo_gyro_plant.hpp: sim/models/servo_gyro.hpp in its torque-driven mode, "
        "docs/models/servo-gyro.md): the firmware rate loop (firmware/app/servo_gyro_controller.hpp: PI + "
        "the feed-forward −H cosβ α' of (14.43)) turns axis 2 at Ω, and the gyroscopic torque M1 = −H cosβ "
        "β' (14.42) drives the oscillator (c1, d1) on axis 1. Axis 2 turns without end: its encoder is "
        "absolute, single turn (β read in [−π, π)). Shipped: `sim/scenes/servo-gyro.toml` (the book's 5.7° "
        "example: gain ×10). Integrator: `rk4` (the only one).",
    .figures =
        "Figures: the rate loop's pair (docs/sampled-data.md) as natural frequency and damping ratio, "
        "`rate_loop_natural_frequency_rad_s`, `rate_loop_damping_ratio` (measured: a recurrence fitted to β' from "
        "settle_s, with the sensor errors and the torque the PI did not command as inputs; "
        "`rate_loop_fit_samples`) beside `_predicted_sampled` (the axis-2 inertia, the firmware's PI, hold and "
        "latency; `sampled_loop_max_abs_z`) and `_predicted` (the continuous design, ω_n = sqrt(k_i/B)); with a "
        "law below the tick rate `rate_loop` (why not). "
        "Over the whole drive revolutions after settle_s (least-squares fits of a mean and the β or 2β harmonic against the drive angle β, sim/analysis/servo_drive_sums.hpp): "
        "`alpha_A_rad` and `phase_rad` (α = α_A cos(β − φ); −π/2 at resonance), `M1_max_Nm` (peak of the "
        "gyroscopic torque −H cosβ β' on axis 1), `M2_max_Nm` (peak of the applied motor torque, sensor "
        "noise included), `torque_gain` = M1_max/M2_max — the measured torque amplification — beside "
        "`torque_gain_book` = 1/α_A (14.44) and `torque_gain_general` = 2/(α_A(1 + |sin φ|)) "
        "(sim/models/servo_gyro.hpp; equal at resonance); `M1_amplitude_harmonic_Nm`, `M2_max_harmonic_Nm` "
        "(mean + 2β harmonic of M2) and `torque_gain_harmonic`, their noise-free estimate; "
        "`drive_rate_mean_rad_s`, `drive_rate_error_max_rad_s`, `drive_rate_reference_rad_s` (the rate "
        "loop's tracking); `motor_power_W` against `dissipation_W` (d1 α'² + d2 β'²); `revolutions`, "
        "`statistics_from_s`, `ticks` (null measurements when no revolution completed after settle_s). CSV "
        "columns: `alpha_rad`, `alpha_rate_rad_s`, `drive_rate_rad_s`, `M1_gyro_Nm`, `motor_torque_Nm`, "
        "`status_bits`. report.json `\"limits\"`: `motor_torque_limit_Nm`.",
    .read = read_servo_gyro,
    .doc = servo_gyro_doc,
};

}  // namespace gyrostab::tools
