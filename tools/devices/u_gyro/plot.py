"""U-gyro (rate gyro with an asymmetric rotor): does the output carry the twice-spin component of relative
amplitude (A^R − B^R)/C^R that (15.29) predicts?

Rows (whole run; beside it a zoom on ten twice-spin periods at the end):
  output     the frame angle β in milliradians; the mean and ± the twice-spin amplitude measured (after
             figures.statistics_from_s) drawn over it, the book's and the measured asymmetry written on it
  torque     the gyroscopic torque on the frame against the book's held-frame torque H Ω [1 − a cos 2γ] (15.29)
  status     event lanes, only if a status bit is ever set
No limits.
"""
import numpy as np

import plot_lib as pl


def plot(run):
    beta, torque, book = run.col("beta_rad"), run.col("gyro_torque_Nm"), run.col("book_torque_Nm")
    if beta is None and torque is None:
        raise pl.NothingToPlot("u_gyro: none of beta_rad, gyro_torque_Nm recorded")
    settle = run.fig("statistics_from_s", 0.0)
    periods = run.fig("periods")  # whole twice-spin periods in the statistics window
    zoom = None
    if periods:
        length = 10 * (run.duration - settle) / periods
        if length < 0.3 * run.duration:
            zoom = (run.duration - length, run.duration)
    bits = run.status()
    rows = [(k, h, True) for k, h, y in (("beta", 1.2, beta), ("torque", 1.0, torque)) if y is not None]
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="ten twice-spin periods", status_lanes=len(pl.active_bits(bits)))
    for row in L.rows.values():
        if settle > 0:
            pl.shade_span(row.whole, run, 0.0, settle, label="settling" if row is L.top_row else None)

    if "beta" in L.rows:
        r = L["beta"]
        pl.plot_pair(r, run, beta * 1e3, zoom, color=pl.C_MAIN, lw=0.8)
        mean, twice = run.fig("mean_output_rad"), run.fig("twice_spin_amplitude_rad")
        if mean is not None and twice is not None:
            for ax in r.axes:
                for v in (mean - twice, mean + twice):
                    ax.axhline(v * 1e3, color=pl.C_BOOK, ls=":", lw=1.0)
            a_book, a_meas = run.fig("asymmetry_book"), run.fig("asymmetry_measured")
            pl.note(r.whole, "twice-spin amplitude %s mrad on a mean of %s mrad: asymmetry %s (book (A−B)/C = %s)"
                    % (pl.num(twice * 1e3, 5), pl.num(mean * 1e3, 5), pl.num(a_meas, 5), pl.num(a_book, 5)),
                    loc="upper left", size=9, bold=True, color=pl.C_MAIN)
            e1, e2 = run.fig("twice_spin_amplitude_rel_error"), run.fig("twice_spin_amplitude_coupled_rel_error")
            if e1 is not None and e2 is not None:
                pl.note(r.whole, "against (15.29) first order %s, with the inertia coupling %s (relative)"
                        % (pl.num(e1), pl.num(e2)), loc="lower right", size=7.5)
        pl.ylabel(r.whole, "frame angle β\n[mrad]")

    if "torque" in L.rows:
        r = L["torque"]
        pl.plot_pair(r, run, torque, zoom, color=pl.C_MAIN, lw=0.8, label="simulated")
        if book is not None:
            pl.plot_pair(r, run, book, zoom, color=pl.C_BOOK, lw=0.8, ls="--", label="book (15.29), frame held")
            pl.legend(r.whole, loc="lower right")
        pl.ylabel(r.whole, "gyroscopic torque\non the frame [N m]")

    pl.status_banner(L, pl.status_strip(L, run, bits, None, zoom), None)
    pl.title(L.fig, run, "U-gyro (asymmetric rotor)", None)
    return L.finish()
