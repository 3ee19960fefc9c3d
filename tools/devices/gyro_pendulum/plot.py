"""Gyro pendulum figure: the instrument's deviation from the book — a Schuler-tuned gyro pendulum's vertical
error is the computable −Hw/(kR) of (12.65), and what is left (its free precession mode) is not disturbed by
the manoeuvres.

Rows (the whole flight):
  vertical error   the case's tilt α, β from the geocentric vertical (degrees) against the book's
                   −Hw/(kR) (dashed); the largest error beside the book's written on it
  deviation        d = z − (−Hw/(kR)) in arcseconds, and the size |p| of its precession mode (12.58): constant
                   for a tuned instrument (unperturbability); its start / min / max, the nutation ripple and the
                   measured period beside the book's (12.61)/(12.68) and Schuler's written on it
  vehicle          speed and heading: the manoeuvres
  status           event lanes of the status bits, only if one is ever set
The controller only monitors (zero torque): the device has no limits in report.json "limits".
"""
import numpy as np

import plot_lib as pl


def plot(run):
    a, b = run.col("alpha_rad"), run.col("beta_rad")
    ab, bb = run.col("alpha_book_rad"), run.col("beta_book_rad")
    p = run.col("precession_mode_rad")
    speed, hdg = run.nonzero("speed_m_s"), run.col("heading_deg")
    if a is None and b is None and p is None:
        raise pl.NothingToPlot("gyro_pendulum: none of alpha_rad, beta_rad, precession_mode_rad recorded")
    bits = run.status()
    rows = []
    if a is not None or b is not None:
        rows.append(("tilt", 1.3, False))
    dev_a = a - ab if a is not None and ab is not None else None
    dev_b = b - bb if b is not None and bb is not None else None
    if dev_a is not None or dev_b is not None or p is not None:
        rows.append(("dev", 1.2, False))
    if speed is not None or (hdg is not None and np.ptp(hdg) > 1e-6):
        rows.append(("veh", 0.7, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)),
                  right_in=0.7 if hdg is not None and np.ptp(hdg) > 1e-6 else 0.15)
    deg = pl.DEG

    if "tilt" in L.rows:
        ax = L["tilt"].whole
        for y, yb, name, c in ((a, ab, "α", pl.C_MAIN), (b, bb, "β", pl.C_SECOND)):
            if y is not None:
                pl.plot_t(ax, run, y * deg, color=c, lw=1.6, alpha=0.8, label=name)
            if yb is not None:
                pl.plot_t(ax, run, yb * deg, color=pl.C_BOOK, ls="--", lw=1.0,
                          label="book −Hw/(kR) (12.65)" if name == "α" else None)
        vm, bm = run.fig("vertical_error_max_rad"), run.fig("book_velocity_error_max_rad")
        if vm is not None:
            pl.note(ax, "largest vertical error %s° — the book's computable −Hw/(kR): %s°" % (
                pl.num(vm * deg), pl.num(bm * deg) if bm is not None else "n/a"), loc="upper left", size=9.5,
                bold=True, color=pl.C_MAIN)
        pl.ylabel(ax, "case tilt [deg]")
        pl.legend(ax, loc="lower right", ncol=3)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.2 * (hi - lo), hi + 0.2 * (hi - lo))

    if "dev" in L.rows:
        ax = L["dev"].whole
        u = pl.angle_unit(dev_a, dev_b, p, unit="arcsec")
        if dev_a is not None:
            pl.plot_t(ax, run, dev_a * u[0], color=pl.C_MAIN, lw=0.8, label="α − α_book")
        if dev_b is not None:
            pl.plot_t(ax, run, dev_b * u[0], color=pl.C_SECOND, lw=0.8, label="β − β_book")
        if p is not None:
            pl.plot_t(ax, run, p * u[0], color="black", lw=1.6, label="|p| precession mode")
        ax.axhline(0, color="0.4", lw=0.6)
        lines = []
        ps, pmin, pmax, pe = (run.fig(k) for k in ("precession_mode_start_rad", "precession_mode_min_rad",
                                                      "precession_mode_max_rad", "precession_mode_end_rad"))
        if ps is not None:
            lines.append("|p|: start %s%s, between %s and %s%s, end %s%s" % (
                pl.num(ps * u[0]), u[1], pl.num(pmin * u[0]), pl.num(pmax * u[0]), u[1], pl.num(pe * u[0]), u[1]))
        dm, rip = run.fig("deviation_from_book_max_rad"), run.fig("nutation_ripple_max_rad")
        if dm is not None:
            lines.append("largest deviation from the book %s%s, nutation ripple %s%s" % (
                pl.num(dm * u[0]), u[1], pl.num(rip * u[0]) if rip is not None else "n/a", u[1]))
        per, perb, sch = run.fig("period_measured_min"), run.fig("period_book_min"), run.fig("schuler_period_book_min")
        lines.append("period %s min measured, book %s min (Schuler %s min)" % (pl.num(per, 4), pl.num(perb, 4),
                                                                             pl.num(sch, 4)))
        wn = run.fig("nutation_frequency_rad_s")
        if wn is not None and wn * run.dt > 3.1416:
            lines.append("(the ripple at %s rad/s is aliased by the %s s samples of signals.csv)" % (
                pl.num(wn), pl.num(run.dt)))
        pl.note(ax, "\n".join(lines), loc="upper left", size=8)
        pl.ylabel(ax, "deviation from\nthe book [%s]" % u[2])
        pl.legend(ax, loc="lower right", ncol=3)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.15 * (hi - lo), hi + 0.45 * (hi - lo))

    if "veh" in L.rows:
        ax = L["veh"].whole
        if speed is not None:
            pl.plot_t(ax, run, speed, color="tab:brown", lw=1.0, label="speed")
            pl.ylabel(ax, "speed [m/s]")
        if hdg is not None and np.ptp(hdg) > 1e-6:
            ax2 = ax.twinx()
            pl.plot_t(ax2, run, hdg, color="0.4", ls="--", lw=0.9, label="heading")
            ax2.set_ylabel("heading [deg]", fontsize=8)
            ax2.tick_params(labelsize=7)
            h1, l1 = ax.get_legend_handles_labels()
            h2, l2 = ax2.get_legend_handles_labels()
            ax.legend(h1 + h2, l1 + l2, loc="upper right", fontsize=7.5, ncol=2)
        lat = run.col("latitude_deg")
        if lat is not None:
            pl.note(ax, "the manoeuvres; latitude %s° to %s°" % (pl.num(float(np.nanmin(lat))),
                                                                pl.num(float(np.nanmax(lat)))), loc="upper left",
                    size=7.5)

    pl.status_banner(L, pl.status_strip(L, run, bits))
    model = run.figures.get("model")
    pl.title(L.fig, run, "gyro pendulum" + (" (%s model)" % model if isinstance(model, str) else ""), None)
    return L.finish()
