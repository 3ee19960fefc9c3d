"""Foucault gyro (declinometer or inclinometer, Magnus §13.1): does the rotor axis settle where the book says —
in the meridian (α = 0) or parallel to the Earth's axis (ϑ = φ) — with the period and decay of its linearised
equation?

Rows (the whole run):
  angle      α or ϑ in degrees with the book's equilibrium (0 or φ) and the linear envelope of the extrema
             (equilibrium ± |x0| e^(−σt)); the measured period, decay and equilibrium beside the predictions
  offset     |offset from the equilibrium| in arcseconds on a log scale against the envelope and the settling
             tolerance; the settling time measured and from the envelope
  torque     the rotor's directive torque on the frame about the free axis ((13.2) M1, (13.4))
  status     event lanes, only if a status bit is ever set
No limits.
"""
import math

import numpy as np

import plot_lib as pl

ARCSEC = 180.0 / math.pi * 3600.0


def plot(run):
    angle, offset = run.col("angle_rad"), run.col("offset_rad")
    envelope, torque = run.col("envelope_rad"), run.col("directive_torque_Nm")
    if angle is None and offset is None:
        raise pl.NothingToPlot("foucault_gyro: neither angle_rad nor offset_rad recorded")
    incl = run.figures.get("kind") == "inclinometer"
    name, sym = ("inclinometer", "ϑ") if incl else ("declinometer", "α")
    bits = run.status()
    rows = [(k, h, False) for k, h, y in (("angle", 1.4, angle), ("offset", 1.1, offset), ("torque", 0.7, torque))
            if y is not None]
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    tf, tl = run.time
    deg = pl.DEG
    eq = run.fig("equilibrium_book_rad")

    if "angle" in L.rows:
        ax = L["angle"].whole
        if eq is not None:
            ax.axhline(eq * deg, color=pl.C_BOOK, ls="--", lw=1.2,
                       label="book equilibrium %s" % ("ϑ = φ (Earth's axis)" if incl else "α = 0 (north)"))
            if envelope is not None:
                for s in (-1.0, 1.0):
                    pl.plot_t(ax, run, (eq + s * envelope) * deg, color=pl.C_REF, lw=0.8, ls=":",
                              label="linear envelope |x0| e^(−σt)" if s > 0 else None)
        y = angle if angle is not None else offset
        pl.plot_t(ax, run, y * deg, color=pl.C_MAIN, lw=1.0, label="%s %s" % (name, sym))
        lines = []
        pm, pl_, pb = run.fig("period_measured_s"), run.fig("period_linear_s"), run.fig("period_book_13_6_s")
        if pm is not None or pl_ is not None:
            lines.append("period %s s measured, linearised %s s (book (13.6), undamped: %s s)"
                         % (pl.num(pm, 7), pl.num(pl_, 7), pl.num(pb, 5)))
        dm, dl = run.fig("decay_rate_measured_s"), run.fig("decay_rate_linear_s")
        if dl is not None:
            lines.append("decay %s /s measured, d/(2J) %s /s" % (pl.num(dm, 8), pl.num(dl, 8)))
        em = run.fig("equilibrium_measured_rad")
        if em is not None and eq is not None:
            lines.append("equilibrium %s° measured (%s″ from the book's %s°)"
                         % (pl.num(em * deg, 9), pl.num((em - eq) * ARCSEC), pl.num(eq * deg, 6)))
        if lines:
            pl.note(ax, "\n".join(lines), loc="lower right", size=7.5)
        pl.ylabel(ax, "%s [deg]" % sym)
        pl.legend(ax, loc="upper right")

    if "offset" in L.rows:
        ax = L["offset"].whole
        mag = np.abs(offset) * ARCSEC
        pl.plot_t(ax, run, mag, color=pl.C_MAIN, lw=0.8, label="|%s − equilibrium|" % sym)
        if envelope is not None:
            pl.plot_t(ax, run, envelope * ARCSEC, color=pl.C_BOOK, ls="--", lw=1.1, label="envelope |x0| e^(−σt)")
        ax.set_yscale("log")
        positive = mag[mag > 0]
        top = float(np.nanmax(mag)) if mag.size else 1.0
        floor = max(float(np.nanmin(positive)) if positive.size else top * 1e-9, top * 1e-9)
        ax.set_ylim(floor, top * 3)
        tol = run.fig("settle_tolerance_rad")
        if tol is not None:
            pl.hline(ax, tol * ARCSEC, "tolerance %s″" % pl.num(tol * ARCSEC), va="top")
        ts, te = run.fig("settling_time_measured_s"), run.fig("settling_time_envelope_s")
        if ts is not None:
            pl.vline(ax, ts * tf, color=pl.C_MAIN, ls="-", lw=1.0)
            pl.note(ax, "settled within %s″ after %s %s (envelope: %s %s)"
                    % (pl.num(tol * ARCSEC if tol else None), pl.num(ts * tf), tl,
                       pl.num(te * tf if te is not None else None), tl),
                    loc="lower left", size=9, bold=True, color=pl.C_MAIN)
        elif run.figures.get("settled") is False:
            pl.note(ax, "not settled within the run", loc="lower left", size=9, bold=True, color=pl.C_MAIN)
        pl.ylabel(ax, "|offset| [″]\n(log)")
        pl.legend(ax, loc="upper right")

    if "torque" in L.rows:
        ax = L["torque"].whole
        f, unit = pl.si_unit("N m", torque)
        pl.plot_t(ax, run, torque * f, color=pl.C_SECOND, lw=0.8,
                  label="directive torque on the frame, (13.4)" if incl else "directive torque M1 (13.2)")
        ax.axhline(0, color="0.4", lw=0.6)
        pl.ylabel(ax, "torque\n[%s]" % unit)
        pl.legend(ax, loc="upper right")

    pl.status_banner(L, pl.status_strip(L, run, bits))
    lat = run.fig("latitude_deg")
    pl.title(L.fig, run, "Foucault %s gyro%s" % (name, " at %s°" % pl.num(lat) if lat is not None else ""), None)
    return L.finish()
