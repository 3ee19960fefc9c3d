"""Single-axis platform with a position (2-DOF) gyro: does the platform hold the steady lag M1^SP/k and slew at
−M2^K/H (16.7), and does its transient decay as the dominant root of (16.8) says?

Rows (whole run; beside it a zoom on the transient after the disturbance step):
  lag        the pick-off δ − α in microradians against the book's lag M1^SP/k (16.7); the measured lag and
             the dominant root (measured against (16.8) and against the sampled loop) written on it
  platform   the platform angle δ and the gyro frame α in degrees; the slew rate measured against −M2^K/H,
             the gain and the unstable band of (16.9)
  torque     the platform torquer M1^KP and the disturbance M1^SP [N m]
  status     event lanes, only if a status bit is ever set
No limits.
"""
import numpy as np

import plot_lib as pl


def _root(run, key):
    r = run.figures.get(key)
    if not isinstance(r, dict) or not all(isinstance(r.get(c), (int, float)) for c in ("re", "im")):
        return "–"
    return "%s ± %si /s" % (pl.num(r["re"], 4), pl.num(abs(r["im"]), 4))


def plot(run):
    e, lag = run.col("pickoff_rad"), run.col("lag_book_rad")
    delta, alpha = run.col("platform_rad"), run.col("gyro_frame_rad")
    m1, dist = run.col("platform_torque_Nm"), run.col("disturbance_Nm")
    if e is None and delta is None:
        raise pl.NothingToPlot("position_gyro_platform: none of pickoff_rad, platform_rad recorded")
    zoom = None
    if dist is not None and np.any(dist != 0):
        t0 = run.t[np.argmax(dist != 0)]
        zoom = (max(0.0, t0 - 0.1), min(run.duration, t0 + 1.5))
    bits = run.status()
    rows = [(k, h, True) for k, h, y in (("lag", 1.3, e), ("platform", 1.0, delta), ("torque", 0.8, m1)) if y is not None]
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="after the disturbance step", status_lanes=len(pl.active_bits(bits)))

    if "lag" in L.rows:
        r = L["lag"]
        pl.plot_pair(r, run, e * 1e6, zoom, color=pl.C_MAIN, lw=0.8, label="δ − α simulated")
        if lag is not None:
            pl.plot_pair(r, run, lag * 1e6, zoom, color=pl.C_BOOK, lw=1.0, ls="--", label="book M1^SP/k (16.7)")
            pl.legend(r.whole, loc="lower right")
        meas, book = run.fig("lag_before_slew_rad"), run.fig("lag_book_16_7_rad")
        if meas is not None and book is not None:
            pl.note(r.whole, "lag %s µrad (book M1/k %s); slewing %s"
                    % (pl.num(meas * 1e6, 5), pl.num(book * 1e6, 5), pl.num((run.fig("lag_slewing_rad") or 0) * 1e6, 5)),
                    loc="lower center", size=9, bold=True, color=pl.C_MAIN)
        pl.note(r.whole, "dominant root (β's extrema after the step) %s;\nsampled loop %s; (16.8) %s"
                % (_root(run, "dominant_root_measured"), _root(run, "dominant_root_sampled"),
                   _root(run, "dominant_root_16_8")), loc="upper right", size=7.5)
        pl.ylabel(r.whole, "pick-off δ − α\n[µrad]")

    if "platform" in L.rows:
        r = L["platform"]
        pl.plot_pair(r, run, np.degrees(delta), zoom, color=pl.C_MAIN, lw=0.9, label="platform δ")
        if alpha is not None:
            pl.plot_pair(r, run, np.degrees(alpha), zoom, color=pl.C_BOOK, lw=0.9, ls="--", label="gyro frame α")
        pl.legend(r.whole, loc="lower right")
        rate, book = run.fig("slew_rate_platform_rad_s"), run.fig("slew_rate_book_16_7_rad_s")
        if rate is not None and book is not None:
            pl.note(r.whole, "slew %s °/s (book −M2/H = %s °/s)" % (pl.num(np.degrees(rate), 6), pl.num(np.degrees(book), 6)),
                    loc="upper left", size=9, bold=True, color=pl.C_MAIN)
        lo, hi = run.fig("band_lower_Nm_rad"), run.fig("band_upper_Nm_rad")
        if lo is not None and hi is not None:
            pl.note(r.whole, "k = %s N m/rad; unstable band (16.9) %s < k < %s"
                    % (pl.num(run.fig("gain_k_Nm_rad"), 5), pl.num(lo, 5), pl.num(hi, 5)), loc="lower left", size=7.5)
        pl.ylabel(r.whole, "angle [°]")

    if "torque" in L.rows:
        r = L["torque"]
        pl.plot_pair(r, run, m1, zoom, color=pl.C_MAIN, lw=0.8, label="torquer M1^KP")
        if dist is not None:
            pl.plot_pair(r, run, dist, zoom, color=pl.C_BOOK, lw=0.8, ls="--", label="disturbance M1^SP")
        pl.legend(r.whole, loc="lower right")
        pl.ylabel(r.whole, "platform torque\n[N m]")

    pl.status_banner(L, pl.status_strip(L, run, bits, None, zoom), None)
    pl.title(L.fig, run, "Platform with a position gyro", None)
    return L.finish()
