"""Servo gyro (gyroscopic vibrator drive) figure: how much torque does the gyro put on the oscillator for the
motor torque it takes, and does the rate loop hold the drive rate?

Rows (whole run; beside it a zoom on four oscillator periods from figures.statistics_from_s):
  oscillator   the axis-1 oscillator angle α in degrees against ±α_A (the Fourier amplitude of the figures)
  gyro torque  the gyroscopic torque −H cos β β' on axis 1; the torque amplification M1max/M2max written on it
               beside the book's 1/α_A (14.44)
  motor        the axis-2 motor torque against the motor torque limit (the spin-up saturates it)
  drive rate   β' against the reference Ω; the zoom shows the tracking error β' − Ω
  status       event lanes of the status bits, only if one is ever set (rate-loop saturation in the spin-up)
Limit (tools/plot/LIMITS.md): motor_torque_limit_Nm; absent, no line.
"""
import math

import numpy as np

import plot_lib as pl

NAMES = {24: "rate loop saturated (spin-up)"}


def plot(run):
    alpha, m1, motor = run.col("alpha_rad"), run.col("M1_gyro_Nm"), run.col("motor_torque_Nm")
    rate = run.col("drive_rate_rad_s")
    if alpha is None and m1 is None and motor is None and rate is None:
        raise pl.NothingToPlot("servo_gyro: none of alpha_rad, M1_gyro_Nm, motor_torque_Nm, drive_rate_rad_s recorded")
    settle = run.fig("statistics_from_s", min(15.0, 0.5 * run.duration))
    omega = run.fig("drive_rate_reference_rad_s")
    zoom = None
    if omega:
        length = 4 * 2 * math.pi / abs(omega)
        if settle + length <= run.duration and length < 0.3 * run.duration:
            zoom = (settle, settle + length)
    bits = run.status()
    rows = [(k, h, True) for k, h, y in (("alpha", 1.1, alpha), ("m1", 1.0, m1), ("motor", 0.9, motor),
                                         ("rate", 0.9, rate)) if y is not None]
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="four periods after settling",
                  status_lanes=len(pl.active_bits(bits)))
    deg = pl.DEG
    for row in L.rows.values():
        if settle > 0:
            pl.shade_span(row.whole, run, 0.0, settle, label="settling" if row is L.top_row else None)

    if "alpha" in L.rows:
        r = L["alpha"]
        pl.plot_pair(r, run, alpha * deg, zoom, color=pl.C_MAIN, lw=0.9)
        a = run.fig("alpha_A_rad")
        for ax in r.axes:
            pl.limit_lines(ax, a, "α_A", deg, color=pl.C_BOOK, ls=":", unit="°")
        pl.ylabel(r.whole, "oscillator α [deg]")
        phase = run.fig("phase_rad")
        if a is not None:
            pl.note(r.whole, "amplitude α_A = %s° (%s revolutions after %s s), phase %s° (−90° at resonance)"
                    % (pl.num(a * deg), pl.num(run.fig("revolutions")), pl.num(settle),
                       pl.num(phase * deg) if phase is not None else "n/a"), loc="upper left", size=7.5)

    if "m1" in L.rows:
        r = L["m1"]
        pl.plot_pair(r, run, m1, zoom, color=pl.C_SECOND, lw=0.9)
        pl.ylabel(r.whole, "gyro torque M1\n−H cos β β' [N m]")
        g, gb, gh = run.fig("torque_gain"), run.fig("torque_gain_book"), run.fig("torque_gain_harmonic")
        if g is not None:
            pl.note(r.whole, "torque amplification M1max/M2max = %s   (book 1/α_A (14.44): %s; harmonic: %s)"
                    % (pl.num(g, 4), pl.num(gb, 4), pl.num(gh, 4)), loc="upper left", size=9.5, bold=True, color=pl.C_SECOND)
        m1max = run.fig("M1_max_Nm")
        if m1max is not None:
            pl.note(r.whole, "M1max %s N m" % pl.num(m1max), loc="lower left", size=7.5)

    if "motor" in L.rows:
        r = L["motor"]
        lim = run.limit("motor_torque_limit_Nm")
        peak = float(np.nanmax(np.abs(motor)))
        pl.plot_pair(r, run, motor, zoom, color=pl.C_MAIN, lw=0.8)
        pl.limit_lines(r.whole, lim, "torque limit", 1.0, peak, unit=" N m", below=True)  # the zoom: its own scale
        pl.ylabel(r.whole, "motor torque M2\n[N m]")
        m2, p, d = run.fig("M2_max_Nm"), run.fig("motor_power_W"), run.fig("dissipation_W")
        text = []
        if m2 is not None:
            text.append("M2max after settling %s N m" % pl.num(m2))
        if p is not None and d is not None:
            text.append("motor power %s W, dissipation %s W" % (pl.num(p, 4), pl.num(d, 4)))
        if text:
            pl.note(r.whole, "\n".join(text), loc="upper right", size=7.5)

    if "rate" in L.rows:
        r = L["rate"]
        pl.plot_t(r.whole, run, rate, color=pl.C_MAIN, lw=0.9, label="β'")
        if omega is not None:
            pl.hline(r.whole, omega, "reference Ω = %s rad/s" % pl.num(omega), va="top")
            if r.zoom is not None:
                pl.plot_t(r.zoom, run, (rate - omega) * 1e3, zoom=zoom, color=pl.C_MAIN, lw=0.8)
                r.zoom.set_ylabel("β' − Ω [mrad/s]", fontsize=8)
        elif r.zoom is not None:
            pl.plot_t(r.zoom, run, rate, zoom=zoom, color=pl.C_MAIN, lw=0.8)
        pl.ylabel(r.whole, "drive rate β'\n[rad/s]")
        mean, err = run.fig("drive_rate_mean_rad_s"), run.fig("drive_rate_error_max_rad_s")
        if mean is not None:
            pl.note(r.whole, "after settling: mean %s rad/s, max |β' − Ω| %s rad/s" % (pl.num(mean, 6), pl.num(err)),
                    loc="lower right", size=7.5)

    pl.status_banner(L, pl.status_strip(L, run, bits, NAMES, zoom), NAMES)
    pl.title(L.fig, run, "servo gyro (gyroscopic vibrator drive)", None)
    pl.limits_missing_note(L.fig, run, ["motor_torque_limit_Nm"])
    return L.finish()
