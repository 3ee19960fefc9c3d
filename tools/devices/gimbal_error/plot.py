"""Gimbal (kinematic) error of a free position gyro: how far do the gimbal angles stray from the vehicle's
Euler angles they are read as, and does the simulation hold the book's closed forms?

Rows (whole run):
  heading error  α − (the angle α is read as) in degrees; for the heading gyro "321" in a level turn the
                 extreme of (12.14) ±|α − ψ|max from figures.level_turn drawn as the book's line, the measured
                 extreme written on it
  second gimbal  β − (the angle β is read as) in degrees
  vehicle        yaw, pitch, roll in degrees (yaw wrapped to ±180°)
  status         event lanes, only if a status bit is ever set
The closed-form check (12.11), (12.16)-(12.20) is written in the title's subtitle. No limits.
"""
import numpy as np

import plot_lib as pl


def _wrap(a):
    return (a + np.pi) % (2.0 * np.pi) - np.pi


def plot(run):
    ea, eb = run.col("alpha_error_rad"), run.col("beta_error_rad")
    yaw, pitch, roll = run.col("yaw_rad"), run.col("pitch_rad"), run.col("roll_rad")
    if ea is None and eb is None and yaw is None:
        raise pl.NothingToPlot("gimbal_error: none of alpha_error_rad, beta_error_rad, yaw_rad recorded")
    bits = run.status()
    rows = [(k, h, True) for k, h, y in (("alpha", 1.2, ea), ("beta", 0.9, eb), ("vehicle", 0.9, yaw))
            if y is not None]
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    deg = pl.DEG
    mounting = run.figures.get("mounting", "?")

    if "alpha" in L.rows:
        r = L["alpha"]
        pl.plot_t(r.whole, run, ea * deg, color=pl.C_MAIN, lw=1.0)
        turn = run.block("figures", "level_turn")
        book = turn.get("book_extreme_abs_rad")
        if book is not None:
            pl.limit_lines(r.whole, book, "book (12.14) extreme", deg, color=pl.C_BOOK, ls=":", unit="°")
            pl.note(r.whole, "level turn at bank %s°: extreme |α − ψ| = %s° at heading %s° (book %s° at %s°)"
                    % (pl.num(turn.get("bank_rad", 0.0) * deg), pl.num(turn.get("measured_extreme_abs_rad", 0.0) * deg, 7),
                       pl.num(turn.get("measured_extreme_heading_rad", 0.0) * deg, 6), pl.num(book * deg, 7),
                       pl.num(turn.get("book_extreme_heading_rad", 0.0) * deg, 6)),
                    loc="upper left", size=9, bold=True, color=pl.C_MAIN)
        else:
            peak = run.block("figures", "alpha_error").get("max_abs_rad")
            if peak is not None:
                pl.note(r.whole, "max |error| %s°" % pl.num(peak * deg, 6), loc="upper left", size=9, bold=True)
        pl.ylabel(r.whole, "first gimbal\nerror [deg]")

    if "beta" in L.rows:
        r = L["beta"]
        pl.plot_t(r.whole, run, eb * deg, color=pl.C_SECOND, lw=1.0)
        peak = run.block("figures", "beta_error").get("max_abs_rad")
        if peak is not None:
            pl.note(r.whole, "max |error| %s°" % pl.num(peak * deg, 6), loc="upper left", size=8)
        pl.ylabel(r.whole, "second gimbal\nerror [deg]")

    if "vehicle" in L.rows:
        r = L["vehicle"]
        for y, name, c in ((yaw, "yaw", pl.C_MAIN), (pitch, "pitch", pl.C_SECOND), (roll, "roll", pl.C_BOOK)):
            if y is not None:
                pl.plot_t(r.whole, run, (_wrap(y) if name == "yaw" else y) * deg, color=c, lw=0.9, label=name)
        pl.legend(r.whole, loc="lower right")
        pl.ylabel(r.whole, "vehicle [deg]")

    da, db = run.fig("closed_form_alpha_max_diff_rad"), run.fig("closed_form_sin_beta_max_diff_rad")
    sub = "mounting %s" % mounting
    if da is not None and db is not None:
        sub += " · against the closed forms (12.11), (12.16)-(12.20): α %s rad, sin β %s" % (pl.num(da), pl.num(db))
    pl.status_banner(L, pl.status_strip(L, run, bits), None)
    pl.title(L.fig, run, "gimbal error of a position gyro", sub, L.top_row.whole)
    return L.finish()
