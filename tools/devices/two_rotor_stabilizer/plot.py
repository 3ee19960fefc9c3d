"""Two-rotor stabilizers: does the frame stay put where a single rotor under the same base motion turns away?

Rows (whole run):
  frame      the stabilized frame's angle α (and γ of the second frame, two-axis kind) in degrees; for the gyro
             frame, the single rotor integrated beside it under the same base motion, law and disturbance, with
             the final values written on it
  cases      the case angles β1 (and β2) in degrees against the expected steady case angle
  motors     the motor torques M1^K (and M2^K) against the motor torque limit
  link       the torque the link carries between the two cases (gyro frame only)
  status     event lanes, only if a status bit is ever set
Limit (tools/plot/LIMITS.md): motor_torque_limit_Nm.
"""
import numpy as np

import plot_lib as pl


def _live(y):
    return y is not None and bool(np.any(y != 0.0))


def plot(run):
    alpha, gamma = run.col("alpha_rad"), run.col("gamma_rad")
    b1, b2 = run.col("beta1_rad"), run.col("beta2_rad")
    m1, m2 = run.col("M1K_Nm"), run.col("M2K_Nm")
    single, link = run.col("single_rotor_alpha_rad"), run.col("link_torque_Nm")
    if alpha is None and b1 is None:
        raise pl.NothingToPlot("two_rotor_stabilizer: none of alpha_rad, beta1_rad recorded")
    bits = run.status()
    rows = [(k, h, False) for k, h, y in (("frame", 1.2, alpha), ("cases", 0.9, b1), ("motors", 0.9, m1),
                                          ("link", 0.8, link if _live(link) else None)) if y is not None]
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    deg = pl.DEG

    if "frame" in L.rows:
        ax = L["frame"].whole
        pl.plot_t(ax, run, alpha * deg, color=pl.C_MAIN, lw=1.0, label="α (two rotors)")
        if _live(gamma):
            pl.plot_t(ax, run, gamma * deg, color=pl.C_SECOND, lw=1.0, label="γ (frame 2)")
        if _live(single):
            pl.plot_t(ax, run, single * deg, color=pl.C_HARD, lw=0.9, ls="--", label="α of a single rotor")
            a, s = run.fig("alpha_final_rad"), run.fig("single_rotor_alpha_final_rad")
            if a is not None and s is not None:
                pl.note(ax, "final α: two counter-rotating rotors %s°, a single rotor %s°"
                        % (pl.num(a * deg, 4), pl.num(s * deg, 4)), loc="upper left", size=9, bold=True,
                        color=pl.C_MAIN)
        pl.legend(ax, loc="lower right")
        pl.ylabel(ax, "frame angle [deg]")

    if "cases" in L.rows:
        ax = L["cases"].whole
        pl.plot_t(ax, run, b1 * deg, color=pl.C_MAIN, lw=1.0, label="β1")
        if _live(b2):
            pl.plot_t(ax, run, b2 * deg, color=pl.C_SECOND, lw=1.0, label="β2")
        e = run.fig("beta1_expected_rad")
        if e is not None:
            pl.hline(ax, e * deg, "expected β1 = %s°" % pl.num(e * deg, 4))
        pl.legend(ax, loc="lower right")
        pl.ylabel(ax, "case angles [deg]")

    if "motors" in L.rows:
        ax = L["motors"].whole
        pl.plot_t(ax, run, m1, color=pl.C_MAIN, lw=0.9, label="M1^K")
        if _live(m2):
            pl.plot_t(ax, run, m2, color=pl.C_SECOND, lw=0.9, label="M2^K")
        peak = float(np.nanmax(np.abs(m1)))
        pl.limit_lines(ax, run.limit("motor_torque_limit_Nm"), "torque limit", 1.0, peak, unit=" N m", below=True)
        g = run.fig("gain_margin")
        if g is not None:
            pl.note(ax, "gain margin %s (largest stable gain over the scene's)" % pl.num(g, 4), loc="upper left",
                    size=7.5)
        pl.legend(ax, loc="center right")
        pl.ylabel(ax, "motor torque [N m]")

    if "link" in L.rows:
        ax = L["link"].whole
        pl.plot_t(ax, run, link, color=pl.C_MAIN, lw=0.9)
        p = run.fig("link_torque_peak_Nm")
        if p is not None:
            pl.note(ax, "peak %s N m" % pl.num(p), loc="upper left", size=7.5)
        pl.ylabel(ax, "link torque\n[N m]")

    pl.status_banner(L, pl.status_strip(L, run, bits), None)
    pl.title(L.fig, run, "two-rotor stabilizer", None)
    pl.limits_missing_note(L.fig, run, ["motor_torque_limit_Nm"])
    return L.finish()
