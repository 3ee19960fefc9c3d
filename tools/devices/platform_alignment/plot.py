"""Platform alignment figure: levelling, then gyrocompassing — the tilts fall within a minute, then the heading
error decays with the azimuth loop's time constant (≈ τ_A0/cosφ) into the tolerance band.

Rows (the whole run; a thin line at the start of the azimuth phase and one at the alignment time):
  heading      the heading error ψ (mrad, logarithmic outside the tolerance band: the decay is straight) against
               the tolerance band and the steady value of the drifts; the measured and predicted alignment
               time and time constant written on it
  tilts        θ_E, θ_N (mrad) against the tilt tolerance and the steady tilts −b_N/g, b_E/g
  rates        the commanded platform rates of the three gyros (deg/h), the east one carrying (16.52)
  status       event lanes of the status bits, only if one is ever set
Limits (tools/plot/LIMITS.md): heading_tolerance_rad, tilt_tolerance_rad, max_time_s; absent, no line.
"""
import numpy as np

import plot_lib as pl


def _f(run, k):
    v = run.fig(k)
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) else None


def plot(run):
    psi = run.col("heading_error_rad")
    te, tn = run.col("tilt_east_rad"), run.col("tilt_north_rad")
    we, wn, wz = run.col("rate_east_rad_s"), run.col("rate_north_rad_s"), run.col("rate_zenith_rad_s")
    if psi is None and te is None and tn is None:
        raise pl.NothingToPlot("platform_alignment: none of heading_error_rad, tilt_east_rad, tilt_north_rad recorded")
    bits = run.status()
    rows = []
    if psi is not None:
        rows.append(("psi", 1.3, False))
    if te is not None or tn is not None:
        rows.append(("tilt", 1.0, False))
    if we is not None or wn is not None or wz is not None:
        rows.append(("rate", 0.8, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    tf, tl = run.time
    t_az, t_al = _f(run, "azimuth_start_s"), _f(run, "alignment_time_s")
    for row in L.rows.values():
        if t_az is not None:
            pl.vline(row.whole, t_az * tf, "azimuth phase" if row is L.top_row else None, color="0.45", ls="--",
                     lw=0.8, rotation=0, y=0.03, ha="left", va="bottom", size=7.5)
        if t_al is not None:
            pl.vline(row.whole, t_al * tf, "aligned" if row is L.top_row else None, color=pl.C_MAIN, ls=":",
                     lw=0.9, rotation=0, y=0.03, ha="left", va="bottom", size=7.5)
    mrad = 1e3

    if "psi" in L.rows:
        ax = L["psi"].whole
        pl.plot_t(ax, run, psi * mrad, color=pl.C_MAIN, lw=1.0, label="heading error ψ")
        tol = run.limit("heading_tolerance_rad")
        pl.limit_lines(ax, tol, "tolerance", mrad, None, unit=" mrad")
        ss = _f(run, "heading_error_steady_rad")
        if ss is not None:
            pl.hline(ax, ss * mrad, "steady (drifts, biases)", color=pl.C_BOOK)
        lines = ["alignment %s s measured, %s s predicted (max %s s)" % (
            pl.num(t_al), pl.num(_f(run, "alignment_time_predicted_s")), pl.num(_f(run, "max_time_s")))]
        lines.append("azimuth time constant %s s measured, slow root %s s, τ_A0/cosφ %s s" % (
            pl.num(_f(run, "azimuth_time_constant_s")), pl.num(_f(run, "azimuth_time_constant_predicted_s")),
            pl.num(_f(run, "azimuth_time_constant_cos_law_s"))))
        lat, lim = _f(run, "latitude_rad"), _f(run, "latitude_limit_rad")
        if lat is not None:
            lines.append("latitude %s° (limit %s°)" % (pl.num(lat * pl.DEG), pl.num(lim * pl.DEG if lim else None)))
        pl.note(ax, "\n".join(lines), loc="upper right", size=8.5, bold=True, color=pl.C_MAIN)
        pl.ylabel(ax, "heading error\n[mrad]")
        hi = np.nanmax(np.abs(psi)) * mrad
        lo = min(np.nanmin(psi) * mrad * 1.5, -3.0 * (tol or 0.0) * mrad)
        ax.set_ylim(lo, hi * 8.0)
        if tol:  # linear inside the band, logarithmic outside: the exponential decay is a straight line
            ax.set_yscale("symlog", linthresh=tol * mrad)

    if "tilt" in L.rows:
        ax = L["tilt"].whole
        if te is not None:
            pl.plot_t(ax, run, te * mrad, color=pl.C_MAIN, lw=0.9, label="θ_E (about east)")
        if tn is not None:
            pl.plot_t(ax, run, tn * mrad, color=pl.C_SECOND, lw=0.9, label="θ_N (about north)")
        pl.limit_lines(ax, run.limit("tilt_tolerance_rad"), "tolerance", mrad, None, unit=" mrad")
        pl.note(ax, "steady: θ_E = −b_N/g = %s mrad, θ_N = b_E/g = %s mrad" % (
            pl.num((_f(run, "tilt_east_steady_rad") or 0.0) * mrad),
            pl.num((_f(run, "tilt_north_steady_rad") or 0.0) * mrad)), loc="lower right", size=7.5)
        pl.ylabel(ax, "tilt\n[mrad]")
        pl.legend(ax, loc="upper right", ncol=2)
        ax.set_yscale("symlog", linthresh=1e-2)

    if "rate" in L.rows:
        ax = L["rate"].whole
        degh = pl.DEG * 3600.0
        for y, c, name in ((we, pl.C_MAIN, "east"), (wn, pl.C_SECOND, "north"), (wz, "tab:green", "zenith")):
            if y is not None:
                pl.plot_t(ax, run, y * degh, color=c, lw=0.8, label=name)
        s = _f(run, "east_gyro_signal_16_52_rad_s")
        if s is not None:
            pl.note(ax, "(16.52) at ψ0: −ω^E cosφ sinψ0 = %s deg/h on the east gyro" % pl.num(s * degh),
                    loc="lower right", size=7.5)
        pl.ylabel(ax, "commanded rate\n[deg/h]")
        pl.legend(ax, loc="upper right", ncol=3)

    pl.status_banner(L, pl.status_strip(L, run, bits))
    pl.title(L.fig, run, "platform alignment", None)
    return L.finish()
