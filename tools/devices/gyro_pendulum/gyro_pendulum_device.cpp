// The gyro pendulum in the registry (tools/devices/registry.cpp).
#include "tools/devices/gyro_pendulum/gyro_pendulum_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kGyroPendulum{
    .name = "gyro_pendulum",
    .summary =
        "A Schuler-tuned gyro pendulum (H > 0) or physical pendulum (H = 0) whose pivot rides on a vehicle "
        "over the rotating spherical Earth: Magnus §12.3.3, (12.52)-(12.68), and Chelnokov §2 "
        "(sim/plants/gyro_pendulum_plant.hpp, docs/models/gyro-pendulum.md). The pivot's motion is the "
        "[vehicle motion](#vehicle-motion) (default latitude 50°), sampled once per tick at each end (the "
        "end's left limit, so accelerations that jump at a manoeuvre corner on a tick boundary are exact) "
        "and interpolated linearly in between. The reference frame is the azimuth-free trihedron (F3 up, no "
        "absolute rotation about the vertical: Magnus (12.52), Chelnokov (2.5)). The angles α, β are the "
        "case's small rotations about F1, F2 (rotor axis ≈ (β, −α, 1) in F). The firmware controller "
        "(firmware/app/gyro_pendulum_controller.hpp) only monitors: zero torque, since any correction would "
        "spoil the tuning. Or, `[vehicle] kind = \"kepler_orbit\"`, the pivot flies a Kepler ellipse (Chelnokov "
        "§4, sim/motion/kepler_orbit.hpp, the [orbit] keys) in the orbital trihedron (O3 radial up, O2 the orbit "
        "normal): the specific force at the pivot is 0, so only `model = \"rigid-body\"` with `start = "
        "\"vertical\"` applies. Shipped: `sim/scenes/schuler-gyro-pendulum.toml` (a tuned instrument, 3 h of "
        "flight), `sim/scenes/gyro-pendulum-kepler-orbit.toml` (one orbit, e = 0.3: the body's quaternion "
        "against the harmonic oscillator z'' + ¼Ω²z = 0).\n\nIntegrators (`[loop] integrator`): with `model = \"magnus\"`: `gyro-exponential` "
        "(default; carries the nutation ω^N ≈ H/A exactly, so the step is bounded only by h ω^N ≤ 0.8·2π) or "
        "`rk4`; with `model = \"rigid-body\"`: `strang` (default), `yoshida4` (exact free-body flow, kicks "
        "of the pendulous and gravity-gradient torques) or `rk4`. The step is checked against the nutation "
        "(H > 0) or the pendulum's own frequency (H = 0).",
    .figures =
        "Figures: `vertical_error_max_rad` (largest tilt |z| of the instrument axis from the geocentric "
        "vertical) beside `book_velocity_error_max_rad` (largest |−Hw/(kR)|, (12.65): the computable error a "
        "tuned gyro pendulum is meant to show; 0 for H = 0); `deviation_from_book_max_rad` (largest |d|, d = "
        "z − (−Hw/(kR))), split into the precession mode p = (ω^N d + i d')/(ω^N − ω^P) of (12.58) — "
        "`precession_mode_start_rad`, `_min_rad`, `_max_rad`, `_end_rad`: the free Schuler swing, which a "
        "tuned instrument keeps at its initial size whatever the manoeuvres (unperturbability) — and "
        "`nutation_ripple_max_rad` (largest |d − p|, excited at every manoeuvre corner); "
        "`period_measured_min` (upward zero crossings of Re p, null with fewer than 2) beside "
        "`period_book_min` (2π/|ω^P| of (12.61)/(12.68) for H > 0; 2π sqrt(A/k) of (12.60) for H = 0, null "
        "if k ≤ 0) and `schuler_period_book_min` (2π sqrt(R/g)); `period_crossings`; `s_m`, `s_tuned_m`, "
        "`k_Nm_per_rad` (12.57); for H > 0 `nutation_frequency_rad_s`, `precession_rate_rad_s` and "
        "`nutation_over_precession`; `model`, `step_s`, `ticks`. The reference −Hw/(kR) is the book's linear "
        "theory: with `model = \"rigid-body\"` and the Earth's transport velocity (tilts of 2°–4°) d also "
        "holds the 3-D body's O(tilt²) and |v|²/(gR) departures from it (~3e-4 rad over the shipped flight), "
        "so p and the period are meaningful for the magnus model or small tilts. No limits (the monitor "
        "commands no torque). CSV columns: `alpha_rad`, `beta_rad`, `tilt_rad`, `alpha_book_rad`, "
        "`beta_book_rad` (−Hw/(kR)), `precession_mode_rad` (|p|), `speed_m_s`, `heading_deg`, "
        "`latitude_deg`, `status_bits`. With `kind = \"kepler_orbit\"` also `kepler_oscillator_gap_max` (largest "
        "|z − z_oracle| over the components of z = q_IB ∘ μ(t) against z(0) cos(Ωt/2) + (2/Ω) z'(0) sin(Ωt/2)), "
        "`kepler_Omega_rad_s` (Ω = 2|z'(0)| = |L|/A), `orbit_period_s`; the Earth figures (the book's "
        "velocity error, the Schuler period) do not apply there, and `speed_m_s`, `latitude_deg` are the "
        "orbital speed and the pivot's declination.",
    .read = read_gyro_pendulum,
    .doc = gyro_pendulum_doc,
};

}  // namespace gyrostab::tools
