// The inertial platform in the registry (tools/devices/registry.cpp).
#include "tools/devices/inertial_platform/inertial_platform_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kInertialPlatform{
    .name = "inertial_platform",
    .summary =
        "Schuler-tuned inertial platforms of Magnus ch. 16, (16.1)-(16.50) "
        "(sim/plants/inertial_platform_plant.hpp, sim/models/inertial_platform.hpp, "
        "docs/models/inertial-platform.md): `axes = 1`, the single-axis platform of Fig. 16.9 on the book's "
        "great circle over a non-rotating Earth (no turns; track frame, platform axis = left); `axes = 3`, a "
        "three-axis local-level platform in the azimuth-free frame of the [vehicle motion](#vehicle-motion) "
        "over the rotating Earth (default latitude 45°). Each axis: a rate-integrating gyro (H, B, d, c) "
        "whose pick-off drives the axis's stabilization motor (an analog servo of gain k, part of the "
        "plant); three axes: with the gyros' cross-coupling (16.11)-(16.13) (`coupling = \"full\"`, default; "
        "`\"decoupled\"`: the large-H/d limit), or held by two position gyros (16.19)-(16.21) (`gyros = "
        "\"two_position\"`); the servo's stability is checked on the coupled roots (9th/11th order). The firmware (firmware/app/inertial_platform_controller.hpp) runs the Schuler loops of the "
        "level channels: accelerometer (as the apparent tilt θ = specific force/g0 in carrier_angle) → "
        "integrator → gyro torquer, M = −H ω_cmd. The loops start on the level frame's rate at t = 0 (ideal "
        "alignment) plus the scene's velocity error. Shipped: `sim/scenes/inertial-platform-schuler.toml` "
        "(three-axis), `sim/scenes/inertial-platform-two-position-gyros.toml`, "
        "`sim/scenes/inertial-platform-single-axis.toml`. Integrator: `rk4`; the step is "
        "checked against the servo modes.",
    .figures =
        "Figures: `axes`, `schuler_period_s` (2π sqrt(R/g)), `ticks`; three axes: `gyros`, `coupling`, "
        "`servo_root_worst_re_per_s` and `servo_root_worst_im_rad_s` (the coupled servo root with the largest "
        "real part); and per level channel (`channels`): "
        "`period_s` (the Schuler root of a recurrence fitted to the tilt every `extrema_sample_s`; null when "
        "the channel does not swing) and `period_measured_s` (extrema of the tilt, null with fewer than 2) "
        "beside `period_s_predicted_sampled`, `decay_rate_per_s_predicted_sampled` (the sampled loop at rest: "
        "the model linearised, the trapezoid accelerometer mean, the firmware law, hold and latency; "
        "`sampled_loop_max_abs_z` at the top level) and `period_loop_book_s` "
        "(2π/ω, ω² = (g/R_loop)(H_loop/H): 84.4 min tuned, (16.38)/(16.44)); `fit_samples`; `tilt_max_rad` beside "
        "`tilt_bound_tuned_rad` (sqrt(e0² + (Δω0/ω_S)²): the tuned swing, whatever the vehicle does (16.34), "
        "(16.46), (16.49)); `tilt_end_rad`; `velocity_error_max_m_s` (R_loop ω_cmd − R Ω, ω_cmd from the "
        "torquer command) beside `velocity_error_amplitude_book_16_47_m_s` (e0 sqrt(gR)); "
        "`position_error_max_m` (∫ velocity error) beside `position_error_max_book_16_47_m` (2 R e0; book: "
        "2.2 km for 0.01°); `servo_offset_book_16_2_rad` (M^S/k; position gyros −M^S/k, (16.22)) and "
        "`gyro_angle_end_rad` (the channel's pick-off); "
        "`servo_gain_limit_16_5` (the single-axis bound; null for position gyros); `drift_position_rate_book_16_50_m_s` (−ε R); `extrema`. Limits: "
        "`torquer_limit_Nm`. CSV columns: `tilt1_rad`, `tilt2_rad`, `theta1_rad`, `theta2_rad`, "
        "`torquer1_Nm`, `torquer2_Nm`, `gyro1_rad`, `velocity_error1_m_s`, `status_bits`.",
    .read = read_inertial_platform,
    .doc = inertial_platform_doc,
};

}  // namespace gyrostab::tools
