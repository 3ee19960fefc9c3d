"""Inertial platform figure: the Schuler oscillation — the platform's tilt swings with the 84.4-min period at
the size its initial error sets, whatever the vehicle does, and so do the velocity and position errors.

Rows (the whole run; thin lines at whole Schuler periods of the loop):
  tilt         the level channels' tilt e (arcseconds) against the tuned bound sqrt(e0² + (Δω0/ω_S)²) of
               (16.46)/(16.49); the measured period beside the loop's 2π/ω (16.38)/(16.44) written on it
  velocity     channel 1's velocity error against the book's amplitude e0 sqrt(gR) (16.47)
  position     its integral (from signals.csv) against the book's 2 R e0 (16.47)
  vehicle      the apparent tilt θ the accelerometers see (the manoeuvres the platform ignores)
  status       event lanes of the status bits, only if one is ever set
The servo offset (gyro angle against M^S/k (16.2)) and the torquer peaks against the torquer limit are written
on the rows. Limit (tools/plot/LIMITS.md): torquer_limit_Nm; absent, not mentioned.
"""
import numpy as np

import plot_lib as pl


def _channel(run, i):
    chans = run.figures.get("channels")
    if isinstance(chans, list):
        for c in chans:
            if isinstance(c, dict) and c.get("channel") == i:
                return c
    return {}


def _f(d, k):
    v = d.get(k)
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) and np.isfinite(v) else None


def plot(run):
    e1, e2 = run.nonzero("tilt1_rad"), run.nonzero("tilt2_rad")
    th1, th2 = run.nonzero("theta1_rad"), run.nonzero("theta2_rad")
    v1 = run.col("velocity_error1_m_s")
    g1 = run.col("gyro1_rad")
    q1, q2 = run.nonzero("torquer1_Nm"), run.nonzero("torquer2_Nm")
    if e1 is None and e2 is None and v1 is None:
        raise pl.NothingToPlot("inertial_platform: none of tilt1_rad, tilt2_rad, velocity_error1_m_s recorded")
    c1, c2 = _channel(run, 1), _channel(run, 2)
    bits = run.status()
    rows = []
    if e1 is not None or e2 is not None:
        rows.append(("tilt", 1.4, False))
    if v1 is not None:
        rows.append(("vel", 0.9, False))
        rows.append(("pos", 0.9, False))
    if th1 is not None or th2 is not None:
        rows.append(("veh", 0.6, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    tf, tl = run.time
    period = _f(c1, "period_loop_book_s") or run.fig("schuler_period_s")
    if period:
        for row in L.rows.values():
            k = 1
            while k * period < run.t_end:
                pl.vline(row.whole, k * period * tf, "%d T" % k if row is L.top_row else None, color="0.45", ls="--",
                         lw=0.8, rotation=0, y=0.03, ha="left", va="bottom", size=7.5)
                k += 1

    if "tilt" in L.rows:
        ax = L["tilt"].whole
        u = pl.angle_unit(e1, e2, unit="arcsec")
        if e2 is not None:
            pl.plot_t(ax, run, e2 * u[0], color=pl.C_SECOND, lw=0.9, label="tilt e2 (channel 2)")
        if e1 is not None:
            pl.plot_t(ax, run, e1 * u[0], color=pl.C_MAIN, lw=1.1, label="tilt e1 (channel 1)")
        bound = _f(c1, "tilt_bound_tuned_rad")
        pl.limit_lines(ax, bound if bound and bound > 0 else None, "tuned bound (16.46)", u[0], None, color=pl.C_BOOK,
                       ls=":", unit=u[1])
        pm, pb = _f(c1, "period_measured_s"), _f(c1, "period_loop_book_s")
        lines = ["Schuler period %s min measured, loop (16.38) %s min" % (pl.num(pm / 60 if pm else None, 4),
                                                                       pl.num(pb / 60 if pb else None, 4))]
        tm = _f(c1, "tilt_max_rad")
        if tm is not None:
            lines.append("max |e1| %s%s (tuned bound %s%s)" % (pl.num(tm * u[0]), u[1], pl.num(bound * u[0]) if bound
                                                               else "n/a", u[1] if bound else ""))
        if c2:
            tm2 = _f(c2, "tilt_max_rad")
            lines.append("channel 2: max |e2| %s%s" % (pl.num(tm2 * u[0]), u[1]))
        pl.note(ax, "\n".join(lines), loc="upper left", size=9, bold=True, color=pl.C_MAIN)
        if g1 is not None:
            so = _f(c1, "servo_offset_book_16_2_rad")
            pl.note(ax, "gyro 1 angle at the end %s rad (servo offset M^S/k (16.2): %s rad)" % (
                pl.num(float(g1[-1])), pl.num(so)), loc="lower left", size=7.5)
        pl.ylabel(ax, "platform tilt [%s]" % u[2])
        pl.legend(ax, loc="upper right", ncol=2)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.25 * (hi - lo), hi + 0.3 * (hi - lo))

    if "vel" in L.rows:
        ax = L["vel"].whole
        pl.plot_t(ax, run, v1, color=pl.C_MAIN, lw=1.0)
        amp = _f(c1, "velocity_error_amplitude_book_16_47_m_s")
        pl.limit_lines(ax, amp if amp else None, "book e0·sqrt(gR) (16.47)", 1.0, None, color=pl.C_BOOK, ls=":",
                       unit=" m/s")
        vm = _f(c1, "velocity_error_max_m_s")
        text = "max |v err| %s m/s" % pl.num(vm) if vm is not None else ""
        lim = run.limit("torquer_limit_Nm")
        qpeak = pl._maxabs(q1, q2)
        if lim and qpeak:
            f, unit = pl.si_unit("N m", maxabs=qpeak)
            fl, ul = pl.si_unit("N m", maxabs=lim)
            text += "\ntorquer peak %s %s = %s of the %s %s limit" % (pl.num(qpeak * f), unit, pl.pct(qpeak / lim, 2),
                                                                     pl.num(lim * fl), ul)
        if text:
            pl.note(ax, text.strip(), loc="lower left", size=7.5)
        pl.ylabel(ax, "velocity error 1\n[m/s]")

    if "pos" in L.rows:
        ax = L["pos"].whole
        dt = np.diff(run.t, prepend=0.0)
        pos = np.cumsum(np.nan_to_num(v1) * dt)
        f, unit = pl.si_unit("m", pos)
        pl.plot_t(ax, run, pos * f, color=pl.C_MAIN, lw=1.0)
        pb = _f(c1, "position_error_max_book_16_47_m")
        pl.limit_lines(ax, pb if pb else None, "book 2R·e0 (16.47)", f, None, color=pl.C_BOOK, ls=":",
                       unit=" " + unit)
        pm = _f(c1, "position_error_max_m")
        if pm is not None:
            pl.note(ax, "max |position error| %s %s (report.json), the curve integrated from signals.csv"
                    % (pl.num(pm * f), unit), loc="lower left", size=7.5)
        pl.ylabel(ax, "position error 1\n[%s]" % unit)

    if "veh" in L.rows:
        ax = L["veh"].whole
        deg = pl.DEG
        if th1 is not None:
            pl.plot_t(ax, run, th1 * deg, color="tab:brown", lw=0.8, label="θ1")
        if th2 is not None:
            pl.plot_t(ax, run, th2 * deg, color="tab:olive", lw=0.8, label="θ2")
        pl.ylabel(ax, "apparent tilt θ\n[deg]")
        pl.note(ax, "what the accelerometers see: the vehicle's manoeuvres", loc="upper left", size=7.5)
        pl.legend(ax, loc="upper right", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits))
    axes = run.fig("axes")
    what = "inertial platform" + (" (%d-axis)" % axes if axes else "")
    pl.title(L.fig, run, what, None)
    return L.finish()
