"""Power gyro stabilizer figure: does the platform hold against the torque steps, and is the nutation the
predicted one?

Rows (whole run; beside it, when the CSV resolves the nutation, a zoom on the first disturbance step):
  α            the platform / outer-gimbal angle (and the elastic platform's angle), the book's steady value
               (14.21) dotted; the disturbance steps marked
  β            the inner-gimbal (precession) angle, its steady value M1/k1 (14.21); gimbal lock (90°) marked
               when β comes near it
  rates        α', β': the nutation; in the zoom the predicted decay e^(−σt) of (14.23) drawn on α', with the
               measured and predicted nutation frequency and decay rate from report.json figures
  torques      the motor torques against the command limit (and the dc drives' peak torque), the disturbance
               torques dashed
  currents     dc drives: winding currents against the current limit
  voltages     dc drives / back-EMF motor: voltages against the voltage limit
  status       event lanes of the status bits, only if one is ever set (a safe state held all run is also
               written on the first row)
The precession model's comparison with the full model (report.json "reduced_model") and the periodic-drift
monitor ("drift") are written on the α row. Limits (tools/plot/LIMITS.md): motor_torque_limit_Nm,
motor_voltage_limit_V, drive_current_limit_A, drive_voltage_limit_V; absent ones draw no line.
"""
import math

import numpy as np

import plot_lib as pl


def _steps(run):
    """(t, axis label, height) of the disturbance steps after t = 0 (a step at t = 0 is a load)."""
    out = []
    for name, label in (("M1_disturbance_Nm", "M1"), ("M2_disturbance_Nm", "M2")):
        v = run.col(name)
        if v is None:
            continue
        change = np.flatnonzero(np.diff(v) != 0)[:3]
        for i in change:
            out.append((float(run.t[i + 1]) - run.dt, label, float(v[i + 1] - v[i])))
    return sorted(out)


def _drift_shift(run):
    """(samples per forcing period, period s, start s) when report.json has a periodic-drift block and the CSV
    samples the period a whole number of times; else None."""
    dr = run.block("drift")
    tick = run.scene.get("tick_ns")
    if not dr or not isinstance(dr.get("period_ticks"), (int, float)) or not isinstance(tick, (int, float)):
        return None
    period = dr["period_ticks"] * tick * 1e-9
    n = period / run.dt
    if n < 1 or abs(n - round(n)) > 1e-6 * n or round(n) >= run.t.size:
        return None
    start = dr.get("reference_from_s") if isinstance(dr.get("reference_from_s"), (int, float)) else 0.0
    return int(round(n)), period, float(start)


def _zoom(run, steps):
    """The zoom window on the first step if the CSV samples resolve the nutation; else None."""
    drift = run.block("drift")
    tick_s = run.scene.get("tick_ns", 0) * 1e-9 if isinstance(run.scene.get("tick_ns"), (int, float)) else 0
    if drift and drift.get("period_ticks") and tick_s > 0:
        period = drift["period_ticks"] * tick_s
        length = min(6 * period, 0.25 * run.duration)
        return (run.t_end - length, run.t_end), "periodic steady state"
    if not steps:
        return None, None
    w = run.fig("nutation_frequency_rad_s") or run.fig("nutation_frequency_rad_s_predicted")
    sigma = run.fig("nutation_decay_rate_per_s") or run.fig("nutation_decay_rate_per_s_predicted")
    if not w or not sigma or sigma <= 0:
        return None, None
    period = 2 * math.pi / w
    if run.dt > period / 6:
        return None, None
    length = max(3.0 / sigma, 8 * period)
    if length > 0.4 * run.duration:
        return None, None
    t1 = steps[0][0]
    label = "zoom on the first step" + ("" if run.block("plant").get("fidelity") == "precession" else " (nutation)")
    return (max(0.0, t1 - 0.05 * length), min(run.t_end, t1 + length)), label


def plot(run):
    alpha, beta = run.col("alpha_rad"), run.col("beta_rad")
    platform = run.col("platform_rad")
    ar, br = run.col("alpha_rate_rad_s"), run.col("beta_rate_rad_s")
    m1, m2 = run.nonzero("M1_motor_Nm"), run.nonzero("M2_motor_Nm")
    d1, d2 = run.nonzero("M1_disturbance_Nm"), run.nonzero("M2_disturbance_Nm")
    currents = [c for c in (run.col("motor1_current_A"), run.col("motor2_current_A")) if c is not None]
    volts = [(n, run.col(n)) for n in ("motor1_voltage_V", "motor2_voltage_V") if run.has(n)]
    if all(x is None for x in (alpha, beta, ar, br, m1, m2, platform)) and not currents and not volts:
        raise pl.NothingToPlot("power_stabilizer: no angle, rate or torque column recorded")
    steps = _steps(run)
    zoom, zoom_label = _zoom(run, steps)
    bits = run.status()
    rows = []
    if alpha is not None or platform is not None:
        rows.append(("alpha", 1.0, True))
    if beta is not None:
        rows.append(("beta", 1.0, True))
    if ar is not None or br is not None:
        rows.append(("rate", 0.9, True))
    drift_shift = _drift_shift(run)
    if drift_shift and (alpha is not None or beta is not None):
        rows.append(("drift", 0.9, False))
    if any(x is not None for x in (m1, m2, d1, d2)):
        rows.append(("torque", 1.0, True))
    if currents:
        rows.append(("current", 0.8, True))
    if volts:
        rows.append(("volt", 0.8, True))
    L = pl.Layout(run, rows, zoom=zoom, zoom_label=zoom_label or "zoom", status_lanes=len(pl.active_bits(bits)))

    # Disturbance steps on every axis (described on the torque row).
    tf = run.time[0]
    for row in L.rows.values():
        for ax in row.axes:
            for t, _, _ in steps:
                pl.vline(ax, t * tf)

    if "alpha" in L.rows:
        r = L["alpha"]
        u = pl.angle_unit(alpha, platform)
        f = u[0]
        if alpha is not None:
            pl.plot_pair(r, run, alpha * f, zoom, color=pl.C_MAIN, lw=0.9, label="α outer gimbal")
        if platform is not None:
            pl.plot_pair(r, run, platform * f, zoom, color=pl.C_SECOND, lw=0.9, label="platform")
        pred = run.fig("steady_alpha_rad_predicted")
        meas = run.fig("steady_alpha_rad")
        pl.hline(r.whole, pred * f if pred is not None else None, "book (14.21)",
                 near=alpha * f if alpha is not None else None)
        if r.zoom is not None and alpha is not None and pred is not None:
            pl.hline(r.zoom, pred * f, "book (14.21)", near=alpha[run.window(*zoom)] * f)
        lines = []
        if meas is not None:
            lines.append("α at the end %s · book steady (14.21) %s" % (pl.fmt_angle(meas, u), pl.fmt_angle(pred, u)
                                                           if pred is not None else "n/a"))
        sp = run.fig("steady_platform_rad")
        if sp is not None:
            lines.append("steady platform %s, platform frequency (14.37) %s rad/s"
                         % (pl.fmt_angle(sp, u), pl.num(run.fig("platform_frequency_rad_s_predicted"))))
        rm = run.block("reduced_model")
        if rm:
            err = rm.get("measured_error", {})
            lines.append("precession model P0 against the full model (ε = %s):\nmax |Δα| %s rad (bound %s), "
                         "max |Δβ| %s rad (bound %s): %s" % (pl.num(rm.get("epsilon")),
                             pl.num(err.get("alpha_rad_max")), pl.num(rm.get("alpha_rad_bound")),
                             pl.num(err.get("beta_rad_max")), pl.num(rm.get("beta_rad_bound")),
                             "within the bounds" if rm.get("within_bounds") else "OUTSIDE the bounds"))
        dr = run.block("drift")
        if dr:
            md = dr.get("max_departure", {})
            worst = max((v for v in md.values() if isinstance(v, (int, float))), default=None)
            lines.append("periodic drift over %s ticks: max departure %s (bound %s rad): %s" % (
                pl.num(dr.get("compared_ticks")), pl.num(worst), pl.num(dr.get("bound_rad")),
                "within" if dr.get("within_bound") else "OUTSIDE"))
        pl.ylabel(r.whole, "α platform [%s]" % u[2])
        if lines:
            pl.note(r.whole, "\n".join(lines), size=7.5, loc=pl.free_corner(
                r.whole, run, [y * f for y in (alpha, platform) if y is not None]))
        if alpha is not None and platform is not None:
            pl.legend(r.whole, loc="center right")

    if "beta" in L.rows:
        r = L["beta"]
        u = pl.angle_unit(beta)
        f = u[0]
        pl.plot_pair(r, run, beta * f, zoom, color=pl.C_MAIN, lw=0.9, label="β inner gimbal")
        pred = run.fig("steady_beta_rad_predicted")
        meas = run.fig("steady_beta_rad")
        pl.hline(r.whole, pred * f if pred is not None else None, "book (14.21) M1/k1", near=beta * f)
        if r.zoom is not None and pred is not None:
            pl.hline(r.zoom, pred * f, "book (14.21)", near=beta[run.window(*zoom)] * f)
        # Gimbal lock (β = ±90°, the coupling H cos β vanishes): a line if β comes within a few of its own
        # swings of it, else a note with the distance.
        if np.nanmax(np.abs(beta)) > math.radians(45):
            side = 1.0 if np.nanmean(beta) > 0 else -1.0
            gap = math.pi / 2 - float(np.nanmax(side * beta))
            swing = float(np.nanmax(beta) - np.nanmin(beta))
            if gap < 3 * swing:
                for ax in r.axes:
                    pl.hline(ax, side * math.pi / 2 * f, "gimbal lock", color=pl.C_HARD, ls="-", va="top")
            else:
                pl.note(r.whole, "%s from gimbal lock (β = %s90°)" % (pl.fmt_angle(gap, pl.angle_unit(np.array([gap]))),
                                                                    "" if side > 0 else "−"),
                        loc="upper right", size=8, color=pl.C_HARD)
        if meas is not None:
            pl.note(r.whole, "β at the end %s · book steady (14.21) %s" % (
                pl.fmt_angle(meas, u), pl.fmt_angle(pred, u) if pred is not None else "n/a"),
                loc=pl.free_corner(r.whole, run, [beta * f], ("lower right", "upper left", "lower left")), size=7.5)
        op = run.fig("operating_point_beta_rad")
        if op is not None:
            pl.note(r.whole, "operating point β₀ = %s: coupling H cos β₀" % pl.fmt_angle(op, u), loc="upper left",
                    size=7.5)
        pl.ylabel(r.whole, "β inner gimbal [%s]" % u[2])

    if "rate" in L.rows:
        r = L["rate"]
        if br is not None:
            pl.plot_pair(r, run, br, zoom, color=pl.C_SECOND, lw=0.7, alpha=0.8, label="β'")
        if ar is not None:
            pl.plot_pair(r, run, ar, zoom, color=pl.C_MAIN, lw=0.8, label="α'")
        pl.ylabel(r.whole, "rate [rad/s]")
        pl.legend(r.whole, loc="upper right", ncol=2)
        w, wp = run.fig("nutation_frequency_rad_s"), run.fig("nutation_frequency_rad_s_predicted")
        s, sp = run.fig("nutation_decay_rate_per_s"), run.fig("nutation_decay_rate_per_s_predicted")
        if w is not None:
            text = ("nutation: %s rad/s, decay %s /s measured\n(14.23) predicts %s rad/s, %s /s"
                    % (pl.num(w, 4), pl.num(s), pl.num(wp, 4), pl.num(sp)))
        else:
            why = run.figures.get("nutation_measurement") or "not measured"
            text = "nutation %s\n(14.23) predicts %s rad/s, decay %s /s" % (why, pl.num(wp, 4), pl.num(sp))
        has_nutation = run.block("plant").get("fidelity") != "precession"
        if has_nutation and wp and run.dt > math.pi / wp / 2:
            text += "\n(%s Hz: faster than the CSV's %s Hz samples, not resolved here)" % (
                pl.num(wp / 2 / math.pi), pl.num(1 / run.dt))
        pl.note(r.whole, text, loc="upper left", size=7.5)
        if r.zoom is not None and ar is not None and sp and steps and has_nutation:
            t1 = steps[0][0]
            m = run.window(t1, t1 + 2 * math.pi / (wp or w))
            if m.any():
                a0 = float(np.nanmax(np.abs(ar[m])))
                tt = np.linspace(t1, zoom[1], 200)
                env = a0 * np.exp(-sp * (tt - t1))
                r.zoom.plot(tt * tf, env, color=pl.C_BOOK, ls="--", lw=1.0, label="predicted decay e^(−σt)")
                r.zoom.plot(tt * tf, -env, color=pl.C_BOOK, ls="--", lw=1.0)
                pl.legend(r.zoom, loc="upper right")

    if "drift" in L.rows:
        r = L["drift"]
        n, period, start = drift_shift
        m = run.t[n:] >= start
        tt = run.t[n:][m]
        dev = [(y[n:] - y[:-n])[m] for y in (alpha, beta) if y is not None]
        f, unit = pl.si_unit("rad", *dev)
        for y, label, c in ((alpha, "α(t) − α(t − T)", pl.C_MAIN), (beta, "β(t) − β(t − T)", pl.C_SECOND)):
            if y is not None:
                r.whole.plot(tt * tf, (y[n:] - y[:-n])[m] * f, color=c, lw=0.8, label=label)
        bound = run.block("drift").get("bound_rad")
        if isinstance(bound, (int, float)):
            pl.limit_lines(r.whole, bound, "bound (two encoder counts)", f, pl._maxabs(*dev), unit=" " + unit,
                           max_ratio=50.0, base_unit="rad")
        pl.ylabel(r.whole, "departure over\none period [%s]" % unit)
        lo, hi = r.whole.get_ylim()
        r.whole.set_ylim(lo, hi + 0.5 * (hi - lo))
        pl.note(r.whole, "each sample against the one a forcing period T = %s s earlier (from %s s)"
                % (pl.num(period), pl.num(start)), loc="upper left", size=7.5)
        pl.legend(r.whole, loc="upper right", ncol=2)

    if "torque" in L.rows:
        r = L["torque"]
        lim = run.limit("motor_torque_limit_Nm")
        drive_peak = run.fig("drive_peak_torque_Nm")
        peak = pl._maxabs(m1, m2, d1, d2)
        f, unit = pl.si_unit("N m", maxabs=peak)
        for y, label, c, ls in ((d1, "M1 disturbance", pl.C_MAIN, "--"), (d2, "M2 disturbance", pl.C_SECOND, "--"),
                                (m1, "M1 motor", pl.C_MAIN, "-"), (m2, "M2 motor", pl.C_SECOND, "-")):
            if y is not None:
                pl.plot_pair(r, run, y * f, zoom, color=c, ls=ls, lw=0.9 if ls == "-" else 0.8, label=label)
        mpeak = max(pl._maxabs(m1, m2), run.fig("motor1_torque_peak_Nm", 0.0), run.fig("motor2_torque_peak_Nm", 0.0))
        for ax in r.axes:  # lines only if the torques use at least 40 % of the limit, else a note
            pl.limit_lines(ax, lim, "command limit", f, mpeak, unit=" " + unit, below=True, base_unit="N m",
                           max_ratio=2.5)
            pl.limit_lines(ax, drive_peak, "drive peak", f, mpeak, unit=" " + unit, color="tab:brown", ls=":",
                           base_unit="N m", max_ratio=2.5)
        pl.ylabel(r.whole, "torque [%s]" % unit)
        pl.legend(r.whole, loc="upper right", ncol=2)
        tp = [run.fig("motor1_torque_peak_Nm"), run.fig("motor2_torque_peak_Nm")]
        text = []
        if steps:
            text.append("steps: " + ", ".join("%s %s%s N m at %s %s" % (a, "+" if h > 0 else "", pl.num(h), pl.num(t * tf), run.time[1])
                                               for t, a, h in steps))
        if any(v is not None for v in tp):
            text.append("motor torque peaks " + ", ".join(
                "M%d %s %s" % (i + 1, pl.num(v * f), unit) for i, v in enumerate(tp) if v is not None))
        if text:
            pl.note(r.whole, "\n".join(text), loc="upper left", size=7.5)

    if "current" in L.rows:
        r = L["current"]
        for i, c in enumerate(currents):
            pl.plot_pair(r, run, c, zoom, color=(pl.C_MAIN, pl.C_SECOND)[i], lw=0.8, label="motor %d" % (i + 1))
        lim = run.limit("drive_current_limit_A")
        for ax in r.axes:
            pl.limit_lines(ax, lim, "current limit", 1.0, pl._maxabs(*currents), unit=" A")
        pl.ylabel(r.whole, "current [A]")
        pl.legend(r.whole, loc="upper right", ncol=2)

    if "volt" in L.rows:
        r = L["volt"]
        for i, (n, v) in enumerate(volts):
            pl.plot_pair(r, run, v, zoom, color=(pl.C_MAIN, pl.C_SECOND)[i], lw=0.8, label="motor %s" % n[5])
        lim = run.limit("drive_voltage_limit_V") or run.limit("motor_voltage_limit_V")
        for ax in r.axes:
            pl.limit_lines(ax, lim, "voltage limit", 1.0, pl._maxabs(*[v for _, v in volts]), unit=" V")
        pl.ylabel(r.whole, "voltage [V]")
        pl.legend(r.whole, loc="upper right", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits, None, zoom))

    comps = run.block("plant").get("components") or []
    sub = "; ".join(c for c in comps[1:] if isinstance(c, str))
    fid = run.block("plant").get("fidelity")
    what = "power gyro stabilizer" + (" (precession model P0)" if fid == "precession" else "")
    pl.title(L.fig, run, what, sub or None, L.top)
    keys = ["motor_voltage_limit_V"] if run.has("motor1_voltage_V") and not run.has("motor2_voltage_V") \
        else ["motor_torque_limit_Nm"]
    if currents:
        keys += ["drive_current_limit_A", "drive_voltage_limit_V"]
    pl.limits_missing_note(L.fig, run, keys)
    return L.finish()
