"""Monorail figure: does the gyro hold the car upright through the release, the gust and the curve?

Rows (whole run; beside it a zoom on the release from the stands, up to figures.statistics_from_s, when the car
starts tilted):
  car roll     the car's tilt φ in degrees, the gust and curve spans shaded, the book's steady leans
               φ = −M1/(c − HΩ3) of (14.6) dotted over their plateaus; tilt rms / max after settling, the gain
               window of (14.5) and an overturn (if any) written on it
  case         the gyro case angle β with its predicted steady angles
  torque       the motor torque against the motor torque limit
  moments      the disturbances: the side-wind gust and the centrifugal moment of the curve
  status       event lanes of the status bits, only if one is ever set
Limit (tools/plot/LIMITS.md): motor_torque_limit_Nm; absent, no line.
"""
import numpy as np

import plot_lib as pl


def _plateau(run, y):
    """(t0, t1) of the span where y is at its largest |value| (the gust's or the curve's plateau), or None."""
    if y is None:
        return None
    peak = np.nanmax(np.abs(y))
    if not peak > 0:
        return None
    on = np.abs(np.abs(y) - peak) <= 1e-9 * peak
    idx = np.flatnonzero(on)
    return float(run.t[idx[0]]), float(run.t[idx[-1]])


def _span(run, y):
    if y is None:
        return None
    idx = np.flatnonzero(np.abs(y) > 0)
    return (float(run.t[idx[0]]), float(run.t[idx[-1]])) if idx.size else None


def plot(run):
    tilt, case = run.col("tilt_rad"), run.col("case_angle_rad")
    torque = run.col("motor_torque_Nm")
    gust, cent, om = run.nonzero("gust_moment_Nm"), run.nonzero("centrifugal_moment_Nm"), run.nonzero("Omega3_rad_s")
    if tilt is None and case is None and torque is None:
        raise pl.NothingToPlot("monorail: none of tilt_rad, case_angle_rad, motor_torque_Nm recorded")
    settle = run.fig("statistics_from_s", min(10.0, 0.2 * run.duration))
    zoom = None
    if tilt is not None and abs(tilt[0]) > 1e-3 and 0 < settle < 0.5 * run.duration:
        zoom = (0.0, settle)
    bits = run.status()
    rows = []
    if tilt is not None:
        rows.append(("tilt", 1.3, True))
    if case is not None:
        rows.append(("case", 1.0, True))
    if torque is not None:
        rows.append(("torque", 0.9, True))
    if gust is not None or cent is not None:
        rows.append(("moments", 0.7, False))
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="release from the stands", status_lanes=len(pl.active_bits(bits)))
    tf = run.time[0]
    deg = pl.DEG
    gust_span, curve_span = _span(run, gust), _span(run, om if om is not None else cent)
    gust_plateau, curve_plateau = _plateau(run, gust), _plateau(run, om if om is not None else cent)
    label_row = L.rows.get("moments") or L.rows[rows[0][0]]
    for row in L.rows.values():
        if gust_span:
            pl.shade_span(row.whole, run, *gust_span, color="tab:cyan", alpha=0.12,
                          label="gust" if row is label_row else None, y=0.45)
        if curve_span:
            pl.shade_span(row.whole, run, *curve_span, color="tab:green", alpha=0.10,
                          label="curve" if row is label_row else None, y=0.45)

    def steady(ax, plateau, value, label):
        if plateau is None or value is None:
            return
        ax.hlines(value * deg, plateau[0] * tf, plateau[1] * tf, color=pl.C_BOOK, ls=":", lw=2.0, zorder=5,
                  label=label)

    gain_note = None
    k, lo, hi = run.fig("k_Nm_per_rad"), run.fig("k_lo_Nm_per_rad"), run.fig("k_hi_Nm_per_rad")
    if k is not None and lo is not None and hi is not None:
        gain_note = "gain k = %s N m/rad in the window %s < k < %s of (14.5)" % (pl.num(k, 4), pl.num(lo, 4),
                                                                                   pl.num(hi, 4))
        clo, chi = run.fig("curve_k_lo_Nm_per_rad"), run.fig("curve_k_hi_Nm_per_rad")
        if clo is not None and chi is not None:
            gain_note += "\nin the curve %s < k < %s" % (pl.num(clo, 4), pl.num(chi, 4))
        d = run.fig("decay_rate_per_s_predicted")
        if d is not None:
            gain_note += "; decay %s /s predicted" % pl.num(d)

    if "tilt" in L.rows:
        r = L["tilt"]
        if gain_note:
            pl.note(r.whole, gain_note, loc="upper left", size=7.5)
        pl.plot_pair(r, run, tilt * deg, zoom, color=pl.C_MAIN, lw=0.9)
        steady(r.whole, gust_plateau, run.fig("gust_lean_rad_predicted"), "book steady lean (14.6)")
        steady(r.whole, curve_plateau, run.fig("curve_lean_rad_predicted"), None)
        pl.ylabel(r.whole, "car roll φ [deg]")
        if settle > 0:
            pl.shade_span(r.whole, run, 0.0, settle, label="settling", y=0.04)
        lines = []
        rms, mx = run.fig("tilt_rms_rad"), run.fig("tilt_max_rad")
        if rms is not None:
            lines.append("after %s s: rms %s°, max |φ| %s°" % (pl.num(settle), pl.num(rms * deg), pl.num(mx * deg)))
        for what, key in (("gust", "gust_lean_rad"), ("curve", "curve_lean_rad")):
            m, p = run.fig(key), run.fig(key + "_predicted")
            if m is not None:
                lines.append("%s lean %s° (book %s°)" % (what, pl.num(m * deg), pl.num(p * deg) if p is not None else "n/a"))
        if lines:
            pl.note(r.whole, "\n".join(lines), loc="lower right", size=7.5)
        if run.figures.get("overturned"):
            at = run.fig("overturned_at_s")
            L.banner("the car OVERTURNED at t = %s s" % pl.num(at) if at is not None else "the car OVERTURNED")
            if at is not None:
                for row in L.rows.values():
                    pl.vline(row.whole, at * tf, color=pl.C_HARD, ls="-", lw=1.5)
        elif run.figures.get("curve_condition_14_7_holds") is False:
            L.banner("(14.7) does not hold in the curve: c > HΩ3 > q, the car overturns for every gain")
        pl.legend(r.whole, loc="upper right")

    if "case" in L.rows:
        r = L["case"]
        pl.plot_pair(r, run, case * deg, zoom, color=pl.C_SECOND, lw=0.9)
        steady(r.whole, gust_plateau, run.fig("gust_case_angle_rad_predicted"), "book steady β")
        steady(r.whole, curve_plateau, run.fig("curve_case_angle_rad_predicted"), None)
        pl.ylabel(r.whole, "gyro case β [deg]")
        mx = run.fig("case_angle_max_rad")
        if mx is not None:
            pl.note(r.whole, "max |β| %s°" % pl.num(mx * deg), loc="upper left", size=7.5)
        pl.legend(r.whole, loc="lower right")

    if "torque" in L.rows:
        r = L["torque"]
        lim = run.limit("motor_torque_limit_Nm")
        peak = run.fig("motor_torque_max_Nm", float(np.nanmax(np.abs(torque))))
        f, unit = pl.si_unit("N m", maxabs=peak)
        pl.plot_pair(r, run, torque * f, zoom, color=pl.C_MAIN, lw=0.8)
        for ax in r.axes:
            pl.limit_lines(ax, lim, "torque limit", f, peak, unit=" " + unit, base_unit="N m")
        pl.ylabel(r.whole, "motor torque [%s]" % unit)
        text = "peak %s %s" % (pl.num(peak * f), unit)
        if lim:
            text += " = %s of the limit" % pl.pct(peak / lim, 2)
        pl.note(r.whole, text, loc="upper left", size=7.5)

    if "moments" in L.rows:
        r = L["moments"]
        f, unit = pl.si_unit("N m", gust, cent)
        if gust is not None:
            pl.plot_t(r.whole, run, gust * f, color="tab:cyan", lw=1.0, label="side-wind gust")
        if cent is not None:
            pl.plot_t(r.whole, run, cent * f, color="tab:green", lw=1.0, label="centrifugal (curve)")
        pl.ylabel(r.whole, "disturbance\n[%s]" % unit)
        radius = run.fig("curve_radius_m")
        if radius is not None:
            pl.note(r.whole, "curve radius %s m, Ω3 = %s rad/s" % (pl.num(radius), pl.num(run.fig("curve_Omega3_rad_s"))),
                    loc="upper left", size=7.5)
        pl.legend(r.whole, loc="upper right", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits, None, zoom))
    pl.title(L.fig, run, "gyro monorail car", None)
    pl.limits_missing_note(L.fig, run, ["motor_torque_limit_Nm"])
    return L.finish()
