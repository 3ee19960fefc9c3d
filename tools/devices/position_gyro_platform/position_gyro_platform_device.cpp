// The position-gyro platform in the registry (tools/devices/registry.cpp).
#include "tools/devices/position_gyro_platform/position_gyro_platform_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kPositionGyroPlatform{
    .name = "position_gyro_platform",
    .summary =
        "A single-axis platform stabilized by a position (two-degree-of-freedom) gyro, Magnus §16.2.2, "
        "(16.6)-(16.10) (sim/plants/position_gyro_platform_plant.hpp, sim/models/position_gyro_platform.hpp, "
        "docs/models/position-gyro-platform.md): the gyro's outer gimbal axis is the platform axis; the "
        "firmware (firmware/app/position_gyro_platform_controller.hpp) reads the pick-off δ − α and drives the "
        "platform's torquer M1^KP = −k(δ − α), and slews the platform through the gyro's torquer, "
        "M2^K = −H ω_cmd. A disturbance torque stepped on, an optional base roll through the bearing's "
        "friction. The check refuses a gain inside the unstable band of (16.9) (Hübner) with the band's edges, "
        "an undamped gyro, and a sampled loop whose discrete closed loop is unstable. Shipped: "
        "`sim/scenes/position-gyro-platform.toml`. Integrator: `rk4` (the only one); the step is checked "
        "against the analog loop's fastest mode.",
    .figures =
        "Figures: `gain_k_Nm_rad`, `band_exists`, `band_lower_Nm_rad`, `band_upper_Nm_rad` (the unstable band "
        "of (16.9), null without one); `sampled_spectral_radius` and `sampled_slowest_decay_1_s` (−ln ρ/Tc); "
        "`lag_before_slew_rad` and `lag_slewing_rad` (means over lag_window_s before the slew's start and end) "
        "beside `lag_book_16_7_rad` = M1^SP/k; `slew_rate_platform_rad_s`, `slew_rate_gyro_frame_rad_s` "
        "(over lag_window_s before the slew's end) beside `slew_rate_book_16_7_rad_s` = −M2^K/H; "
        "`dominant_root_measured` (the root of a recurrence fitted to the inner gimbal angle β at the law's rate "
        "from 20 ms after the step to the slew, the pick-off noise as an input; docs/sampled-data.md) and "
        "`dominant_root_extrema` (from β's extrema, fit_delay_s to the slew; null with fewer than 4) beside "
        "`dominant_root_16_8` (the quartic of (16.8)) and `dominant_root_sampled` (ln z/Tc of the discrete closed "
        "loop), each {re, im} [1/s]; the same as `decay_rate_per_s`, `frequency_rad_s` (measured) beside "
        "`…_predicted` (16.8) and `…_predicted_sampled`; "
        "`extrema`, `pickoff_max_rad`, `ticks`. CSV columns: `pickoff_rad`, `lag_book_rad`, `platform_rad`, "
        "`platform_rate_rad_s`, `gyro_frame_rad`, `beta_rad`, `platform_torque_Nm`, `gyro_torque_Nm`, "
        "`disturbance_Nm`, `base_rad`, `status_bits`.",
    .read = read_position_gyro_platform,
    .doc = position_gyro_platform_doc,
};

}  // namespace gyrostab::tools
