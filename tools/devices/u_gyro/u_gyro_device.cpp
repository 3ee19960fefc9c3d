// The U-gyro in the registry (tools/devices/registry.cpp).
#include "tools/devices/u_gyro/u_gyro_scene.hpp"

namespace gyrostab::tools {

extern const DeviceDescriptor kUGyro{
    .name = "u_gyro",
    .summary =
        "A rate gyro with an asymmetric rotor (U-gyro) of Magnus §15.4, (15.27)-(15.29) "
        "(sim/plants/u_gyro_plant.hpp, sim/models/u_gyro.hpp, docs/models/u-gyro.md): a single frame on the "
        "output axis 2, restrained by a spring c2 and a damper d2, carrying a rotor with A^R ≠ B^R spun at a "
        "held rate; the case turns at Ω about the input axis on a rate table. Lagrange's equation of the "
        "frame with the rotor's output-axis inertia varying at twice the spin angle; the output carries a "
        "twice-spin component of relative torque amplitude (A^R − B^R)/C^R. No torquers: the controller "
        "(firmware/app/free_instrument_controller.hpp) only runs the loop. Shipped: "
        "`sim/scenes/u-gyro-rate-table.toml` (the frame tuned to twice the spin, the book's read-out). "
        "Integrator: `rk4` (the only one).",
    .figures =
        "Figures, over the whole twice-spin periods after settle_s (a least-squares fit of a mean, a linear "
        "trend and the 2γ harmonic against the spin angle γ, `samples` of them: no leak of the mean into the "
        "harmonic whatever the window, sim/analysis/harmonic_fit.hpp): "
        "`mean_output_rad` against `mean_output_book_rad` = HΩ/c2 (15.4), `mean_output_rel_error`; "
        "`twice_spin_amplitude_rad` against `twice_spin_amplitude_book_rad` = |ε| HΩ |G(2γ')| — (15.29) "
        "through the frame's receptance at the mean inertia, `frame_receptance_at_twice_spin_rad_per_Nm` — "
        "and `twice_spin_amplitude_rel_error`; `twice_spin_amplitude_coupled_rad` (the same with the inertia's "
        "variation to second order, harmonic balance) and `twice_spin_amplitude_coupled_rel_error`, "
        "`inertia_coupling_rel` (the first-order form's expected relative error); `asymmetry_measured` (|ε| recovered from the output) beside "
        "`asymmetry_book` = (A^R − B^R)/C^R; `H_Nms`, `twice_spin_torque_amplitude_book_Nm`, `periods`, "
        "`statistics_from_s`, `ticks` (null measurements when no period completed after settle_s; a relative "
        "error, and `asymmetry_measured`, null when Ω = 0 leaves it no reference). CSV "
        "columns: `beta_rad`, `beta_rate_rad_s`, `gyro_torque_Nm` (the rotor's torque on the frame), "
        "`book_torque_Nm` ((15.29) at the same γ), `status_bits`.",
    .read = read_u_gyro,
    .doc = u_gyro_doc,
};

}  // namespace gyrostab::tools
