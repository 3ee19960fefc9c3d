// The platform alignment in the registry (tools/devices/registry.cpp).
#include "tools/devices/platform_alignment/platform_alignment_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kPlatformAlignment{
    .name = "platform_alignment",
    .summary =
        "Alignment of a local-level inertial platform from an unaligned start, Magnus §16.5, (16.52), Fig. "
        "16.13 (sim/plants/platform_alignment_plant.hpp, sim/models/platform_alignment.hpp, "
        "docs/models/platform-alignment.md): a three-axis platform whose servos follow its gyros (the platform "
        "turns at the torquing command plus the gyro's drift; attitude to the east-north-up frame as a "
        "quaternion, so large heading errors work) on a base at rest on the rotating Earth, optionally rocked "
        "by gusts (`[base]`: only its acceleration reaches the platform), with three biased accelerometers. The "
        "firmware (firmware/app/platform_alignment_controller.hpp, firmware/control/platform_alignment_loops.hpp) "
        "levels it — east accelerometer → north gyro (Earth rate ω^E cosφ compensated), north accelerometer → "
        "east gyro, second-order loops of bandwidth ω_L and damping ζ — and then gyrocompasses: the east "
        "gyro's steady torquing signal, −ω^E cosφ sinψ (16.52), drives the zenith gyro until it vanishes; "
        "time constant ≈ τ_A0/cosφ. The scene is refused beyond the latitude at which the alignment would "
        "outlast `[alignment] max_time_s` (the message gives the limit). Shipped: "
        "`sim/scenes/platform-alignment-aircraft.toml` (50°N, 12 min), "
        "`sim/scenes/platform-alignment-high-latitude.toml` (75°N: the slow azimuth). Integrator: `rk4`.",
    .figures =
        "Figures: `latitude_rad`, `latitude_limit_rad`, `max_time_s`; `east_gyro_signal_16_52_rad_s` "
        "(−ω^E cosφ sinψ0, the book's form at the initial heading error); `east_gyro_rate_at_azimuth_start_rad_s` "
        "(measured: the Earth's rate on the platform's east axis from the run's attitude when the azimuth phase "
        "begins, tilts and all) against `east_gyro_rate_at_azimuth_start_rad_s_predicted` ((16.52) at the heading "
        "error then) with `east_gyro_rate_at_azimuth_start_rel_error`; `azimuth_start_s` (measured: the zenith torquer leaves its Earth-rate "
        "compensation) beside `azimuth_start_predicted_s`, and the misalignment then "
        "(`tilt_east_at_azimuth_start_rad`, `tilt_north_at_azimuth_start_rad`, "
        "`heading_error_at_azimuth_start_rad`); `alignment_time_s` (within `[alignment]` tolerances from then "
        "to the end; null if not) beside `alignment_time_predicted_s` (the loop's slow root from the measured "
        "azimuth start) and `alignment_time_predicted_before_run_s` (the scene check's); "
        "`azimuth_time_constant_s` (measured: −1/Re of the slow root of a recurrence fitted to ψ at the law's "
        "rate with the apparent tilts' errors as inputs, from |ψ − ψ_ss| < 0.03 rad to the end; "
        "`azimuth_time_constant_fit_samples`) beside `azimuth_time_constant_predicted_sampled_s` (the sampled "
        "loop's: the model linearised at its steady misalignment, the firmware law, hold and latency; "
        "`sampled_loop_max_abs_z`), `azimuth_time_constant_predicted_s` (the cubic's slow root, level platform) "
        "and `azimuth_time_constant_cos_law_s` (τ_A0/cosφ); `azimuth_time_constant_tan_law_s` (tan(|ψ − ψ_ss|/2) "
        "over two e-folds from 5 levelling time constants after the switch); `tilt_east_end_rad`, `tilt_north_end_rad`, `heading_error_end_rad` beside the steady "
        "state `tilt_east_steady_rad` (−b_N/g), `tilt_north_steady_rad` (b_E/g), `heading_error_steady_rad` "
        "and its drift term `heading_error_drift_term_rad` (−ε_E/(ω^E cosφ)); `aligned_at_end`; `ticks`. "
        "Limits: `heading_tolerance_rad`, `tilt_tolerance_rad`, `max_time_s`. CSV columns: `tilt_east_rad`, "
        "`tilt_north_rad`, `heading_error_rad`, `accel_east_m_s2`, `accel_north_m_s2`, `accel_up_m_s2`, "
        "`rate_east_rad_s`, `rate_north_rad_s`, `rate_zenith_rad_s` (the commanded platform rates), "
        "`status_bits`.",
    .read = read_platform_alignment,
    .doc = platform_alignment_doc,
};

}  // namespace gyrostab::tools
