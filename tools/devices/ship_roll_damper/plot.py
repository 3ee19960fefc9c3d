"""Ship roll damper figure: does the gyro take the roll out, and how close does the precession come to its limits?

Rows, the whole run on the left and a zoomed window (60 s from the start of the statistics) on the right:
  roll         the ship's roll with the gyro and with the gyro locked (the unstabilized reference in the same
               sea), in degrees; the roll reduction 1 − σ/σ₀ written on it, σ, σ₀ the rms rolls from
               figures.roll_rms_rad / roll_rms_unstabilized_rad (statistics from figures.statistics_from_s)
  precession   the case's precession angle against the soft limit (active law) and the end stops
  torque       the precession torque command against the torque limit
  sea          the wave roll moment (the excitation), on its own axis
  status       event lanes of the status bits, only if one is ever set
Limits from report.json "limits" (tools/plot/LIMITS.md): precession_soft_limit_rad, precession_stop_rad,
precession_torque_limit_Nm; a limit that is absent draws no line.
"""
import numpy as np

import plot_lib as pl

LIMIT_KEYS = ("precession_soft_limit_rad", "precession_stop_rad", "precession_torque_limit_Nm")
NAMES = {21: "precession torque at its limit", 22: "precession beyond the soft limit",
         23: "end-stop braking"}


def plot(run):
    roll, roll0 = run.col("roll_rad"), run.col("roll_unstabilized_rad")
    prec, torque, wave = run.col("precession_rad"), run.col("precession_torque_Nm"), run.col("wave_moment_Nm")
    if roll is None and roll0 is None and prec is None and torque is None:
        raise pl.NothingToPlot("ship_roll_damper: none of roll_rad, roll_unstabilized_rad, precession_rad, "
                               "precession_torque_Nm recorded")
    stats_from = run.fig("statistics_from_s", min(60.0, 0.2 * run.duration))
    zoom = None
    if run.duration > 90.0:
        z0 = min(stats_from, max(0.0, run.duration - 60.0))
        zoom = (z0, min(z0 + 60.0, run.duration))
    bits = run.status()
    rows = []
    if roll is not None or roll0 is not None:
        rows.append(("roll", 1.35, True))
    if prec is not None:
        rows.append(("prec", 1.1, True))
    if torque is not None:
        rows.append(("torque", 1.0, True))
    if wave is not None:
        rows.append(("sea", 0.6, True))
    lanes = len(pl.active_bits(bits))
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="zoom from the start of the statistics",
                  status_lanes=lanes, sharey_zoom=True)
    deg = pl.DEG

    if "roll" in L.rows:
        r = L["roll"]
        if roll0 is not None:
            pl.plot_pair(r, run, roll0 * deg, zoom, color=pl.C_REF, lw=0.8, label="gyro locked (unstabilized)")
        if roll is not None:
            pl.plot_pair(r, run, roll * deg, zoom, color=pl.C_MAIN, lw=0.9, label="with the gyro")
        pl.ylabel(r.whole, "roll φ [deg]")
        pl.symmetric_ylim(r.whole, 1.25)
        if stats_from > 0:
            pl.shade_span(r.whole, run, 0.0, stats_from, label="settling: not in σ, σ₀")
        sigma, sigma0 = run.fig("roll_rms_rad"), run.fig("roll_rms_unstabilized_rad")
        source = "report.json figures"
        if (sigma is None or sigma0 is None) and roll is not None and roll0 is not None:
            m = run.t >= stats_from
            if m.any():
                sigma = float(np.sqrt(np.nanmean(roll[m] ** 2)))
                sigma0 = float(np.sqrt(np.nanmean(roll0[m] ** 2)))
                source = "signals.csv samples (figures absent)"
        if sigma is not None and sigma0 is not None and sigma0 > 0:
            reduction = 1.0 - sigma / sigma0
            pl.note(r.whole, "roll reduction 1 − σ/σ₀ = %s %%" % ("%.1f" % (100.0 * reduction)).replace("-0.0", "0.0")
                    .replace("-", "−"), loc="upper left", size=11, bold=True, color=pl.C_MAIN)
            pl.note(r.whole, "σ = %s° with the gyro, σ₀ = %s° locked\n(rms roll from t = %s s; %s)"
                    % (pl.num(sigma * deg), pl.num(sigma0 * deg), pl.num(stats_from), source),
                    loc="lower left", size=7.5)
        peak, peak0 = run.fig("roll_max_rad"), run.fig("roll_max_unstabilized_rad")
        if peak is not None and peak0 is not None:
            pl.note(r.whole, "max |roll| %s° (locked %s°)" % (pl.num(peak * deg), pl.num(peak0 * deg)),
                    loc="lower right", size=7.5)
        pl.legend(r.whole, loc="upper right", ncol=2)

    if "prec" in L.rows:
        r = L["prec"]
        pl.plot_pair(r, run, prec * deg, zoom, color=pl.C_MAIN, lw=0.9)
        peak = run.fig("precession_max_rad", float(np.nanmax(np.abs(prec))))  # the figure: every tick
        soft, stop = run.limit("precession_soft_limit_rad"), run.limit("precession_stop_rad")
        for ax in r.axes:
            pl.limit_lines(ax, soft, "soft limit", deg, peak, color=pl.C_SOFT, max_ratio=6.0, unit="°",
                           below=True)
            pl.limit_lines(ax, stop, "end stop", deg, peak, color=pl.C_HARD, ls="-", max_ratio=6.0, unit="°")
        pl.ylabel(r.whole, "precession β [deg]")
        pl.symmetric_ylim(r.whole, 1.12)
        pl.mark_peak(r.whole, run, prec, deg, "max")
        text = "max |β| %s°" % pl.num(peak * deg)
        if stop:
            text += " = %s of the end stop" % pl.pct(peak / stop, 2)
        pen, bound = run.fig("stop_penetration_max_rad"), run.fig("stop_penetration_bound_rad")
        if pen is not None and pen > 0:
            pl.warn(r.whole, "end stops hit: penetration %s° (bound %s°)"
                    % (pl.num(pen * deg), pl.num(bound * deg) if bound is not None else "n/a"), loc="lower left")
        pl.note(r.whole, text, loc="upper left", size=8)

    if "torque" in L.rows:
        r = L["torque"]
        lim = run.limit("precession_torque_limit_Nm")
        peak = run.fig("precession_torque_max_Nm", float(np.nanmax(np.abs(torque))))
        f, unit = pl.si_unit("N m", maxabs=max(peak, lim) if lim and peak * 8 >= lim else peak)
        pl.plot_pair(r, run, torque * f, zoom, color=pl.C_MAIN, lw=0.8)
        for ax in r.axes:
            pl.limit_lines(ax, lim, "torque limit", f, peak, unit=" " + unit, max_ratio=8.0, base_unit="N m")
        pl.ylabel(r.whole, "precession torque M₂\n[%s]" % unit)
        pl.symmetric_ylim(r.whole, 1.12)
        text = "peak |M₂| %s %s" % (pl.num(peak * f), unit)
        if lim:
            text += " = %s of the limit" % pl.pct(peak / lim, 2)
        pl.note(r.whole, text, loc="upper left", size=8)

    if "sea" in L.rows:
        r = L["sea"]
        f, unit = pl.si_unit("N m", wave)
        pl.plot_pair(r, run, wave * f, zoom, color="tab:cyan", lw=0.7)
        pl.ylabel(r.whole, "wave moment\n[%s]" % unit)
        rms = run.fig("wave_moment_rms_Nm")
        if rms is not None:
            pl.note(r.whole, "excitation, rms %s %s" % (pl.num(rms * f), unit), loc="upper left", size=7.5)
        pl.symmetric_ylim(r.whole, 1.15)

    pl.status_banner(L, pl.status_strip(L, run, bits, NAMES, zoom), NAMES)

    comps = [c for c in run.block("plant").get("components") or [] if isinstance(c, str)]
    sea = next((c for c in comps if c.startswith(("regular sea", "irregular sea"))), None)
    pl.title(L.fig, run, "ship roll damper", sea, L.top)
    if any("H = 0" in c for c in comps):
        L.banner("rotor without spin (H = 0): no gyroscopic coupling, so no roll reduction")
    pl.limits_missing_note(L.fig, run, LIMIT_KEYS if "precession_soft_limit_rad" in run.limits or not run.limits
                           else LIMIT_KEYS[1:])
    return L.finish()
