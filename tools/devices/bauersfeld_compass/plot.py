"""Spatial (two-rotor) compass of Bauersfeld: does the sphere keep the vertical and north while the vehicle
manoeuvres? Tuned (13.60) and started per (13.64) its axis a1 stays on the geocentric vertical and a3 on the
closed form of the speed deviation; mistuned or started off the vertical, the tilt swings (84.4 min, (13.63)).

Rows (the whole run):
  tilt      the tilt of a1 from the geocentric vertical toward east and north (auto unit); the largest tilt,
            the tuning ratio and the measured periods beside (13.63) written on it
  azimuth   the azimuth error of a3 from north (degrees) against the closed form atan2(−v_N, v_E + ω^E R cosφ)
            (dashed); the largest deviation written on it
  delta     the cases' swing δ against sin δ = H |ω_IG horizontal| / (2 f) (dashed)
  vehicle   speed and heading: the manoeuvres (only if the vehicle moves)
  status    event lanes, only if a status bit is ever set
No limits.
"""
import numpy as np

import plot_lib as pl


def plot(run):
    te, tn = run.col("tilt_east_rad"), run.col("tilt_north_rad")
    az, azb = run.col("azimuth_error_rad"), run.col("azimuth_book_rad")
    de, deb = run.col("delta_rad"), run.col("delta_book_rad")
    speed, hdg = run.nonzero("speed_m_s"), run.col("heading_deg")
    if te is None and tn is None and az is None:
        raise pl.NothingToPlot("bauersfeld_compass: none of tilt_east_rad, tilt_north_rad, azimuth_error_rad recorded")
    bits = run.status()
    rows = []
    if te is not None or tn is not None:
        rows.append(("tilt", 1.2, False))
    if az is not None:
        rows.append(("az", 1.0, False))
    if de is not None:
        rows.append(("delta", 0.8, False))
    moving_heading = hdg is not None and np.ptp(hdg) > 1e-6
    if speed is not None or moving_heading:
        rows.append(("veh", 0.7, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)), right_in=0.7 if moving_heading else 0.15)
    deg = pl.DEG

    if "tilt" in L.rows:
        ax = L["tilt"].whole
        u = pl.angle_unit(te, tn, unit="auto")
        m = pl._maxabs(te, tn)
        if 0.0 < m < 1e-7:  # the rounding-level tilt of a tuned compass: a power of ten of radians
            e = int(np.floor(np.log10(m)))
            u = (10.0 ** -e, "e%d rad" % e, "1e%d rad" % e)
        for y, name, c in ((te, "toward east", pl.C_MAIN), (tn, "toward north", pl.C_SECOND)):
            if y is not None:
                pl.plot_t(ax, run, y * u[0], color=c, lw=1.0, label=name)
        ax.axhline(0, color=pl.C_BOOK, ls="--", lw=1.0, label="tuned (13.60): 0")
        lines = []
        tm, q = run.fig("tilt_max_rad"), run.fig("tuning_ratio")
        if tm is not None:
            lines.append("largest tilt from the geocentric vertical %s rad (tuning ratio H²/(f m s |R^M|) = %s)"
                         % (pl.num(tm), pl.num(q, 6) if q is not None else "n/a"))
        pe, pn, pb = run.fig("period_east_min"), run.fig("period_north_min"), run.fig("schuler_period_book_min")
        if pe is not None or pn is not None:
            lines.append("periods (zero crossings): east %s min, north %s min — (13.63) %s min" % (
                pl.num(pe, 6) if pe is not None else "n/a", pl.num(pn, 6) if pn is not None else "n/a",
                pl.num(pb, 6)))
        if lines:
            pl.note(ax, "\n".join(lines), loc="upper left", size=8.5, bold=True, color=pl.C_MAIN)
        pl.ylabel(ax, "tilt of a1\n[%s]" % u[2])
        pl.legend(ax, loc="lower right", ncol=3)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.2 * (hi - lo), hi + 0.35 * (hi - lo))

    if "az" in L.rows:
        ax = L["az"].whole
        pl.plot_t(ax, run, az * deg, color=pl.C_MAIN, lw=1.4, label="a3 from north")
        if azb is not None:
            pl.plot_t(ax, run, azb * deg, color=pl.C_BOOK, ls="--", lw=1.0,
                      label="atan2(−v_N, v_E + ω^E R cosφ)")
        dv = run.fig("azimuth_deviation_from_book_max_rad")
        if dv is not None:
            pl.note(ax, "largest deviation from the closed form %s rad" % pl.num(dv), loc="upper left", size=8)
        pl.ylabel(ax, "azimuth error\n[deg]")
        pl.legend(ax, loc="lower right", ncol=2)

    if "delta" in L.rows:
        ax = L["delta"].whole
        pl.plot_t(ax, run, de * deg, color=pl.C_MAIN, lw=1.4, label="δ")
        if deb is not None:
            pl.plot_t(ax, run, deb * deg, color=pl.C_BOOK, ls="--", lw=1.0, label="sin δ = H |ω_IG,h| / (2 f)")
        pl.ylabel(ax, "case swing δ\n[deg]")
        pl.legend(ax, loc="lower right", ncol=2)

    if "veh" in L.rows:
        ax = L["veh"].whole
        if speed is not None:
            pl.plot_t(ax, run, speed, color="tab:brown", lw=1.0, label="speed")
            pl.ylabel(ax, "speed [m/s]")
        if moving_heading:
            ax2 = ax.twinx()
            pl.plot_t(ax2, run, hdg, color="0.4", ls="--", lw=0.9, label="heading")
            ax2.set_ylabel("heading [deg]", fontsize=8)
            ax2.tick_params(labelsize=7)
            h1, l1 = ax.get_legend_handles_labels()
            h2, l2 = ax2.get_legend_handles_labels()
            ax.legend(h1 + h2, l1 + l2, loc="upper right", fontsize=7.5, ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits))
    pl.title(L.fig, run, "spatial compass (Bauersfeld)", None)
    return L.finish()
