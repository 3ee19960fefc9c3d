// The spatial (two-rotor) compass of Bauersfeld in the registry (tools/devices/registry.cpp).
#include "tools/devices/bauersfeld_compass/bauersfeld_compass_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kBauersfeldCompass{
    .name = "bauersfeld_compass",
    .summary =
        "The spatial two-rotor compass of Bauersfeld, Magnus §13.4, (13.40)-(13.64) "
        "(sim/plants/bauersfeld_compass_plant.hpp, sim/models/bauersfeld_compass.hpp, "
        "docs/models/bauersfeld-compass.md): a float sphere, centre of mass s below its support point, with "
        "two rotors of momentum H in cases swinging by ±δ about its axis a1, held by springs M^F = f sin 2δ. "
        "Its axis obeys (13.57) a1 × [(H²/f) a1'' + m s (R^M'' + g R^M/|R^M|)] = 0 (R^M'' the centre of "
        "mass's acceleration, kept exactly), integrated in inertial axes with the support point on a vehicle "
        "over the rotating Earth sampled exactly at every RK4 stage; the azimuth follows a1' (a2 = "
        "a1'/|a1'|, "
        "sin δ = H |a1'|/(2 f)). Tuned (13.60), H² = f m s |R^M|, and started per (13.64), a1 stays on the "
        "geocentric vertical for any manoeuvre and a3 points north but for the speed deviation; perturbed, "
        "the tilt swings with 84.4 min (13.63). The spring is given or set by the tuning (or a mistuning "
        "ratio); the report gives H²/(f m s |R^M|). No torquers: the controller "
        "(firmware/app/free_instrument_controller.hpp) only runs the loop. Shipped: "
        "`sim/scenes/bauersfeld-compass-ship.toml` (tuned, a ship manoeuvring), "
        "`sim/scenes/bauersfeld-compass-mistuned.toml` (the same ship, spring 5 % off) and "
        "`sim/scenes/bauersfeld-compass-tilt.toml` (an initial tilt on the Equator: the 84.4-min swing). "
        "Integrator: `rk4` (the only one).",
    .figures =
        "Figures: `tuning_ratio` = H²/(f m s |R^M|), `f_Nm` beside `f_tuned_Nm` (13.60), `radius_M_m` = R − "
        "s, "
        "`effective_inertia_kg_m2` = H²/f + m s², `schuler_period_book_min` (13.63), `step_s`, `ticks`; the "
        "tilt of a1 from the geocentric vertical: `tilt_max_rad` (at `tilt_max_time_s`), `tilt_end_rad`; the "
        "azimuth error of a3: `azimuth_error_max_abs_rad` and `azimuth_deviation_from_book_max_rad` against "
        "atan2(−v_N, v_E + ω^E R cosφ); the cases' swing: `delta_min_rad`, `delta_max_rad`, "
        "`delta_deviation_from_book_max_rad` against sin δ = H |ω_IG horizontal|/(2 f), `sin_delta_max`, "
        "`delta_real` (sin δ stayed below 1), the start-up check's bound `rate_bound_rad_s` and "
        "`sin_delta_bound`; the tilt components' periods from their zero crossings, `period_east_min`, "
        "`period_north_min` (null with fewer than two crossings), `period_crossings_east`, "
        "`period_crossings_north`. CSV columns: `tilt_east_rad`, `tilt_north_rad`, `tilt_rad`, "
        "`azimuth_error_rad`, `azimuth_book_rad`, `delta_rad`, `delta_book_rad`, `speed_m_s`, `heading_deg`, "
        "`latitude_deg`, `status_bits`.",
    .read = read_bauersfeld_compass,
    .doc = bauersfeld_compass_doc,
};

}  // namespace gyrostab::tools
