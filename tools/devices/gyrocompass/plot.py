"""Gyrocompass figure: the heading error — how the compass settles on its meridian, and how far it leaves its
equilibrium when the ship changes speed or latitude.

Rows (the whole run):
  heading      the compass's azimuth α (its heading error) in degrees against the book's equilibrium α_eq(t)
               ((13.11) at rest, the speed deviation (13.22)/(13.23) under way); the settling time into a band
               around α_eq and the measured period / decay / equilibrium beside the book's written on it
  deviation    α − α_eq: at rest on a log scale against the book's decay e^(−δt/2) of (13.12); under way in
               arcminutes, the ballistic deviation (zero for a Schuler-tuned undamped compass, (13.26))
  elevation    the rotor axis's elevation β in arcminutes (and the level sensor when it differs), the book's β0
  vehicle      latitude (and heading) when they change
  swing        the sphere's swing about its rotor axis (rolling error), only if it moves
  torques      the torquer commands against the torquer limit
  status       event lanes of the status bits, only if one is ever set
Limit (tools/plot/LIMITS.md): torquer_limit_Nm; absent, no line.
"""
import math

import numpy as np

import plot_lib as pl


def plot(run):
    a, aeq = run.col("alpha_rad"), run.col("alpha_eq_rad")
    b, level = run.col("beta_rad"), run.col("level_rad")
    lat, hdg = run.col("latitude_deg"), run.col("heading_deg")
    swing = run.nonzero("swing_rad")
    m1, m2 = run.nonzero("M1_Nm"), run.nonzero("M2_Nm")
    if a is None and b is None:
        raise pl.NothingToPlot("gyrocompass: neither alpha_rad nor beta_rad recorded")
    moving = (lat is not None and np.ptp(lat) > 1e-6) or (hdg is not None and np.ptp(hdg) > 1e-6)
    decay_book = run.fig("decay_rate_book_13_12_s")
    segs = run.figures.get("segments") if isinstance(run.figures.get("segments"), list) else []
    segs = [s for s in segs if isinstance(s, dict) and isinstance(s.get("t_start_s"), (int, float))
            and isinstance(s.get("t_end_s"), (int, float))]
    # Under way: a zoom on the first short manoeuvre (a stop, a speed change), which the whole run compresses
    # into a step.
    zoom = None
    if moving:
        short = sorted((s for s in segs if 0 < s["t_end_s"] - s["t_start_s"] < 0.05 * run.duration
                        and s["t_start_s"] > 0), key=lambda s: s["t_start_s"])
        if short:
            p = run.fig("period_book_13_12_s") or run.fig("schuler_period_s") or 5000.0
            s0 = short[0]
            zoom = (max(0.0, s0["t_start_s"] - 0.3 * p), min(run.t_end, s0["t_end_s"] + 0.8 * p))
    bits = run.status()
    rows = []
    if a is not None:
        rows.append(("heading", 1.4, True))
        if aeq is not None:
            rows.append(("dev", 1.0, True))
    if b is not None or level is not None:
        rows.append(("elev", 0.8, False))
    if moving:
        rows.append(("vehicle", 0.6, False))
    if swing is not None:
        rows.append(("swing", 0.6, False))
    if m1 is not None or m2 is not None:
        rows.append(("torque", 0.6, False))
    L = pl.Layout(run, rows, zoom=zoom, zoom_label="the first manoeuvre", status_lanes=len(pl.active_bits(bits)),
                  right_in=0.7 if moving and hdg is not None and np.ptp(hdg) > 1e-6 else 0.15)
    tf, tl = run.time
    deg = pl.DEG

    # Manoeuvre segments (under way): the ends as thin lines on every row.
    ends = sorted({s["t_end_s"] for s in segs if s["t_end_s"] < run.t_end * 0.999})
    if moving:
        for row in L.rows.values():
            for ax in row.axes:
                for t in ends:
                    pl.vline(ax, t * tf, color="0.6", lw=0.8)

    if "heading" in L.rows:
        r = L["heading"]
        ax = r.whole
        if aeq is not None:
            pl.plot_pair(r, run, aeq * deg, zoom, color=pl.C_BOOK, ls="--", lw=1.3, label="book equilibrium α_eq")
        pl.plot_pair(r, run, a * deg, zoom, color=pl.C_MAIN, lw=1.0, label="compass azimuth α (heading error)")
        lines = []
        pm, pb = run.fig("period_measured_s"), run.fig("period_book_13_12_s")
        if pm is not None or pb is not None:
            lines.append("period %s min measured, book (13.12) %s min" % (
                pl.num(pm / 60 if pm else None), pl.num(pb / 60 if pb else None)))
        dm, db = run.fig("decay_rate_measured_s"), decay_book
        if db is not None and db > 0:
            lines.append("decay %s /s measured, book δ/2 %s /s" % (pl.num(dm), pl.num(db)))
        elif db is not None:
            lines.append("undamped (δ = 0)")
        em, eb = run.fig("alpha_eq_measured_rad"), run.fig("alpha0_book_13_11_rad")
        if em is not None and not moving:
            lines.append("equilibrium α %s° measured, book (13.11) %s°" % (pl.num(em * deg), pl.num(eb * deg)
                                                                       if eb is not None else "n/a"))
        if lines:
            pl.note(ax, "\n".join(lines), loc="lower right", size=7.5)
        # Settling into a band around the equilibrium (when the run starts off it).
        if aeq is not None:
            dev = np.abs(a - aeq)
            d0 = float(dev[0])
            band = max(0.02 * d0, math.radians(0.05))
            if d0 > 5 * band and dev[-1] < band:
                out = np.flatnonzero(dev > band)
                t_settle = float(run.t[out[-1] + 1]) if out.size and out[-1] + 1 < run.t.size else float(run.t[0])
                ax.fill_between(run.t[[0, -1]] * tf, (aeq[[0, -1]] - band) * deg, (aeq[[0, -1]] + band) * deg,
                                color=pl.C_BOOK, alpha=0.12, lw=0) if np.ptp(aeq) == 0 else None
                pl.vline(ax, t_settle * tf, color=pl.C_BOOK, ls="-", lw=1.2)
                pl.note(ax, "settled within ±%s° of α_eq (2 %% of the initial %s°) after %s %s" % (
                    pl.num(band * deg), pl.num(d0 * deg), pl.num(t_settle * tf), tl), loc="upper left", size=10,
                    bold=True, color=pl.C_MAIN)
            elif moving:
                pl.note(ax, "largest |α − α_eq| %s′ (the ballistic deviation)" % pl.num(float(np.nanmax(dev)) * deg * 60),
                        loc="upper left", size=10, bold=True, color=pl.C_MAIN)
        pl.ylabel(ax, "azimuth α [deg]")
        pl.legend(ax, loc="lower left", ncol=2)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.3 * (hi - lo), hi + 0.2 * (hi - lo))

    if "dev" in L.rows:
        r = L["dev"]
        ax = r.whole
        dev = a - aeq
        if not moving and decay_book:
            pl.plot_t(ax, run, np.abs(dev) * deg, color=pl.C_MAIN, lw=0.8, label="|α − α_eq|")
            ax.set_yscale("log")
            m = np.abs(dev) > 0
            first_peak = float(np.nanmax(np.abs(dev[: max(3, dev.size // 20)])))
            tt = run.t
            ax.plot(tt * tf, first_peak * deg * np.exp(-decay_book * (tt - tt[0])), color=pl.C_BOOK, ls="--", lw=1.2,
                    label="book decay e^(−δt/2), δ/2 = %s /s" % pl.num(decay_book))
            floor = max(float(np.nanmin(np.abs(dev[m]))) if m.any() else 1e-12, first_peak * 1e-6)
            ax.set_ylim(floor * deg, first_peak * deg * 3)
            pl.ylabel(ax, "|α − α_eq| [deg]\n(log)")
        else:
            u = pl.angle_unit(dev)
            pl.plot_pair(r, run, dev * u[0], zoom, color=pl.C_MAIN, lw=0.9, label="α − α_eq")
            for x in r.axes:
                x.axhline(0, color="0.4", lw=0.6)
            pl.ylabel(ax, "α − α_eq [%s]" % u[2])
            pl.note(ax, "deviation from the book's equilibrium: the ballistic deviation, 0 when Schuler-tuned (13.26)"
                    if moving else "deviation from the book's equilibrium", loc="upper left", size=7.5)
        pl.legend(ax, loc="upper right")

    if "elev" in L.rows:
        ax = L["elev"].whole
        u = pl.angle_unit(b, level, unit="arcmin")
        if level is not None and (b is None or np.nanmax(np.abs(level - b)) > 1e-3 * pl._maxabs(b)):
            pl.plot_t(ax, run, level * u[0], color=pl.C_REF, lw=0.7, label="level sensor")
        if b is not None:
            pl.plot_t(ax, run, b * u[0], color=pl.C_SECOND, lw=0.9, label="elevation β")
        b0 = run.fig("beta0_book_13_11_rad")
        if b0 is not None and not moving:
            pl.hline(ax, b0 * u[0], "book (13.11) β0", va="top")
        pl.ylabel(ax, "β [%s]" % u[2])
        pl.legend(ax, loc="upper right", ncol=2)

    if "vehicle" in L.rows:
        ax = L["vehicle"].whole
        if lat is not None:
            pl.plot_t(ax, run, lat, color="tab:brown", lw=1.2, label="latitude")
            pl.ylabel(ax, "latitude [deg]")
        tune = run.fig("tune_latitude_deg")
        if tune is not None:
            pl.hline(ax, tune, "Schuler-tuned at %s°" % pl.num(tune), color=pl.C_BOOK, va="top")
        if hdg is not None:
            if np.ptp(hdg) > 1e-6:
                ax2 = ax.twinx()
                pl.plot_t(ax2, run, hdg, color="0.4", lw=0.8, ls="--", label="heading")
                ax2.set_ylabel("heading [deg]", fontsize=8)
                ax2.tick_params(labelsize=7)
            else:
                pl.note(ax, "heading %s° throughout" % pl.num(float(hdg[0])), loc="upper right", size=7.5)
        pl.legend(ax, loc="lower left")

    if "swing" in L.rows:
        ax = L["swing"].whole
        u = pl.angle_unit(swing)
        pl.plot_t(ax, run, swing * u[0], color="tab:olive", lw=0.7)
        pl.ylabel(ax, "swing [%s]" % u[2])
        rb = run.fig("rolling_error_book_13_38_rad")
        if rb is not None:
            pl.note(ax, "rolling error (13.38): %s′" % pl.num(rb * deg * 60), loc="upper left", size=7.5)

    if "torque" in L.rows:
        ax = L["torque"].whole
        lim = run.limit("torquer_limit_Nm")
        peak = pl._maxabs(m1, m2)
        f, unit = pl.si_unit("N m", maxabs=peak)
        if m1 is not None:
            pl.plot_t(ax, run, m1 * f, color=pl.C_MAIN, lw=0.8, label="M1 damping")
        if m2 is not None:
            pl.plot_t(ax, run, m2 * f, color=pl.C_SECOND, lw=0.8, label="M2 electrical pendulosity")
        pl.limit_lines(ax, lim, "torquer limit", f, peak, unit=" " + unit, base_unit="N m")
        pl.ylabel(ax, "torquer\n[%s]" % unit)
        pl.legend(ax, loc="upper right", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits))
    where = "under way" if moving else "fixed base"
    pl.title(L.fig, run, "gyrocompass (%s)" % where, None)
    pl.limits_missing_note(L.fig, run, ["torquer_limit_Nm"])
    return L.finish()
