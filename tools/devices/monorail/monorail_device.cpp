// The monorail in the registry (tools/devices/registry.cpp).
#include "tools/devices/monorail/monorail_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kMonorail{
    .name = "monorail",
    .summary =
        "The gyro-stabilized monorail car of Magnus §14.1, (14.1)-(14.7) (sim/plants/monorail_plant.hpp: "
        "sim/models/monorail.hpp with large-angle terms, docs/models/monorail.md): the car tilting by φ "
        "about the rail, the top-heavy gyro case at β on axis 2, held upright by the firmware motor law M2 = "
        "k φ − d β' (firmware/app/monorail_controller.hpp). The plant's analog law k is 0 (the firmware is "
        "the motor law); its damper `d_mechanical` is passive. The track runs straight, then through a curve "
        "(curve running (14.6): the path turns at Ω3(t)), with a side-wind gust. Shipped: "
        "`sim/scenes/monorail.toml`. Integrator: `rk4` (the only one).\n\nWhat the plant adds to the model "
        "(sim/plants/car_on_track.hpp): the centrifugal moments of the curve, a = v Ω3 the lateral "
        "acceleration, M1 += (a/g)(c cosφ − q cosφ (1 − cosβ)), M2 += −(a/g) q sinφ sinβ (the model neglects "
        "the tilt of the apparent vertical; to first order the moment c a/g on the car); the brake on axis 2 "
        "in the safe state; and the ground: a car that reaches |φ| = π/2 lies on its side (φ held, the model "
        "no longer applies).",
    .figures =
        "Figures: `tilt_rms_rad`, `tilt_max_rad` (after settle_s), `case_angle_max_rad`, "
        "`motor_torque_max_Nm`; the gain window `k_lo_Nm_per_rad`, `k_hi_Nm_per_rad` with the configured "
        "`k_Nm_per_rad`, `omega_P_rad_s`, `omega_N_rad_s`, `decay_rate_per_s_predicted` (−max Re λ of "
        "(14.3)) beside `decay_rate_per_s` (measured: the slowest root of a recurrence fitted to φ[k] from the "
        "release to the first load, the sensor errors as inputs; null in a curve from t = 0) and the "
        "`_predicted_sampled` figures of docs/sampled-data.md; in the curve `curve_Omega3_rad_s`, `curve_H_Omega3_Nm_per_rad`, `curve_radius_m`, "
        "`curve_condition_14_7_holds` ((c − HΩ3)(q − HΩ3) > 0), `curve_k_lo_Nm_per_rad`, "
        "`curve_k_hi_Nm_per_rad`, `curve_decay_rate_per_s_predicted` ((14.6)); the steady leans over the "
        "last second of the gust plateau and of the curve, measured and `_predicted` by the small-angle "
        "steady state of (14.6), φ = −M1/(c − HΩ3) (the car leans against the moment) and β = −k (φ + tilt "
        "bias)/(q − HΩ3): `gust_lean_rad`, `gust_case_angle_rad`, `curve_lean_rad`, `curve_case_angle_rad` "
        "(null without a plateau); `overturned`, `overturned_at_s`; `statistics_from_s`; `ticks`. CSV "
        "columns: `tilt_rad`, `case_angle_rad`, `tilt_rate_rad_s`, `case_rate_rad_s`, `Omega3_rad_s`, "
        "`gust_moment_Nm`, `centrifugal_moment_Nm`, `motor_torque_Nm`, `status_bits`. report.json "
        "`\"limits\"`: `motor_torque_limit_Nm`, `tilt_overturned_rad` (π/2: the car lies on the ground).",
    .read = read_monorail,
    .doc = monorail_doc,
};

}  // namespace gyrostab::tools
