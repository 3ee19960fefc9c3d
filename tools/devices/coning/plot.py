"""Coning platform figure: does the platform, slaved so that its rate gyro reads zero, turn at minus the gyro's
coning error (Magnus §15.5, (15.39)-(15.42))?

Rows (whole run; beside it a zoom on two vibration periods at the end):
  azimuth   the platform's azimuth φ relative to the base in degrees; from statistics_from_s the lines of the
            book's rate (minus the open-loop coning error) and of the closed-loop first-order prediction; the
            measured drift written on it
  reading   the gyro's reading (P: (c2/H) β in rad/s; I: (d2/H) β in rad) — it follows the vibration, its mean
            is nulled by the loop
  beta      the gyro's output angle β (the tilt of its effective input axis) in degrees
  drive     the drive voltage against its limit
  status    event lanes of the status bits, only if one is ever set
Limit (tools/plot/LIMITS.md): drive_voltage_limit_V; absent, no line.
"""
import numpy as np

import plot_lib as pl

NAMES = {28: "drive voltage saturated"}


def plot(run):
    phi, reading, beta, volt = run.col("phi_rad"), run.col("reading"), run.col("beta_rad"), run.col("drive_voltage_V")
    if phi is None and reading is None and beta is None:
        raise pl.NothingToPlot("coning: none of phi_rad, reading, beta_rad recorded")
    settle = run.fig("statistics_from_s", 0.5 * run.duration)
    zoom = None
    period = run.fig("vibration_period_s")
    if period is not None and 0 < 2 * period < 0.3 * run.duration:
        zoom = (run.duration - 2 * period, run.duration)
    bits = run.status()
    rows = [(k, h, z) for k, h, z, y in (("azimuth", 1.2, False, phi), ("reading", 0.9, True, reading),
                                         ("beta", 0.8, True, beta), ("drive", 0.8, True, volt)) if y is not None]
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="two vibration periods", status_lanes=len(pl.active_bits(bits)))
    deg = pl.DEG
    tf = run.time[0]
    for row in L.rows.values():
        if settle > 0:
            pl.shade_span(row.whole, run, 0.0, settle, label="settling" if row is L.top_row else None)

    if "azimuth" in L.rows:
        r = L["azimuth"]
        pl.plot_t(r.whole, run, phi * deg, color=pl.C_MAIN, lw=1.0, label="platform φ")
        book, pred, drift = run.fig("coning_rate_book_rad_s"), run.fig("drift_predicted_rad_s"), run.fig("drift_rate_rad_s")
        phi0 = float(np.interp(settle, run.t, phi))
        t = np.array([settle, run.t_end])
        if book is not None:
            r.whole.plot(t * tf, (phi0 - book * (t - settle)) * deg, color=pl.C_BOOK, ls=":", lw=1.4,
                         label="− book coning error")
        if pred is not None:
            r.whole.plot(t * tf, (phi0 + pred * (t - settle)) * deg, color=pl.C_SECOND, ls="--", lw=1.0,
                         label="closed-loop prediction")
        pl.ylabel(r.whole, "platform azimuth φ\n[deg]")
        pl.legend(r.whole, loc="lower right")
        if drift is not None:
            pl.note(r.whole, "drift %s rad/s (%s°/s); book %s, prediction %s (rel. %s)"
                    % (pl.num(drift, 4), pl.num(drift * deg, 3), pl.num(-book, 4) if book is not None else "n/a",
                       pl.num(pred, 4) if pred is not None else "n/a",
                       pl.pct(run.fig("drift_rel_error_vs_prediction", float("nan")))),
                    loc="upper left", size=9, bold=True, color=pl.C_MAIN)

    if "reading" in L.rows:
        r = L["reading"]
        pl.plot_pair(r, run, reading, zoom, color=pl.C_MAIN, lw=0.7)
        kind = run.figures.get("gyro_kind")
        pl.ylabel(r.whole, "gyro reading\n[rad/s]" if kind != "I" else "gyro reading\n[rad]")
        m = run.fig("gyro_mean_reading_rad_s")
        if m is not None:
            pl.note(r.whole, "mean reading rate after settling %s rad/s (nulled)" % pl.num(m), loc="upper left", size=7.5)

    if "beta" in L.rows:
        r = L["beta"]
        pl.plot_pair(r, run, beta * deg, zoom, color=pl.C_SECOND, lw=0.7)
        pl.ylabel(r.whole, "output angle β\n[deg]")

    if "drive" in L.rows:
        r = L["drive"]
        pl.plot_pair(r, run, volt, zoom, color=pl.C_MAIN, lw=0.7)
        lim = run.limit("drive_voltage_limit_V")
        pl.limit_lines(r.whole, lim, "voltage limit", 1.0, float(np.nanmax(np.abs(volt))), unit=" V")
        pl.ylabel(r.whole, "drive voltage\n[V]")

    pl.status_banner(L, pl.status_strip(L, run, bits, NAMES, zoom), NAMES)
    pl.title(L.fig, run, "coning platform (rate gyro under angular vibration)", None)
    pl.limits_missing_note(L.fig, run, ["drive_voltage_limit_V"])
    return L.finish()
