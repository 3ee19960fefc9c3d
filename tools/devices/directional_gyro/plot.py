"""Directional gyro figure: how far does the heading indication wander from the true heading, against the book?

Rows (the whole flight; turns shaded and labelled):
  heading error  the indication minus the true heading (the gyro's drift, its gimbal error in banked turns and
                 the turn error), with the compass's error against the truth when it is noisy; the drift figures
                 (measured, the free gyro's, the book's (12.22) and the law's compensation) written on it
  rotor          β (inner gimbal) and the bank, and per turn the book's β at the turn's end ((12.25) + (12.29),
                 crosses) with the rotor's azimuth drift δ beside (12.32)
  torques        M1 (inter-gimbal), M2 (compensation + heading correction) against the torquer limit
  status         event lanes of the status bits, only if one is ever set (cut-out, torquer limited)
Limits (tools/plot/LIMITS.md): torquer_limit_Nm, turn_cutout_rad_s (noted); absent, no line.
"""

import plot_lib as pl

NAMES = {29: "correction cut out (turn)", 30: "torquer at its limit"}


def _segments(run):
    segs = run.figures.get("segments")
    out = []
    if isinstance(segs, list):
        for s in segs:
            if isinstance(s, dict) and all(isinstance(s.get(k), (int, float)) for k in ("t_start_s", "t_end_s")):
                out.append(s)
    return sorted(out, key=lambda s: s["t_start_s"])


def plot(run):
    err, beta, bank = run.col("heading_error_rad"), run.col("beta_rad"), run.col("bank_rad")
    comp, true = run.col("compass_rad"), run.col("true_heading_rad")
    m1, m2 = run.nonzero("M1_Nm"), run.nonzero("M2_Nm")
    if err is None and beta is None:
        raise pl.NothingToPlot("directional_gyro: neither heading_error_rad nor beta_rad recorded")
    bits = run.status()
    rows = []
    if err is not None:
        rows.append(("heading", 1.4, False))
    if beta is not None or bank is not None:
        rows.append(("rotor", 1.0, False))
    if m1 is not None or m2 is not None:
        rows.append(("torque", 0.8, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    tf = run.time[0]
    deg = pl.DEG
    segs = _segments(run)
    for s in segs:
        w = s.get("turn_rate_rad_s") or 0.0
        if abs(w) > 1e-6:
            for row in L.rows.values():
                label = None
                if row is L.top_row:
                    label = "%s turn %s°/s" % ("right" if w > 0 else "left", pl.num(abs(w) * deg, 2))
                pl.shade_span(row.whole, run, s["t_start_s"], s["t_end_s"], color="tab:orange", alpha=0.10,
                              label=label, y=0.90)

    if "heading" in L.rows:
        ax = L["heading"].whole
        if comp is not None and true is not None:
            ce = (comp - true + pl.np.pi) % (2 * pl.np.pi) - pl.np.pi
            if pl.np.nanmax(pl.np.abs(ce)) > 0:
                pl.plot_t(ax, run, ce * deg, color=pl.C_REF, lw=0.5, alpha=0.5, label="compass − true")
        pl.plot_t(ax, run, err * deg, color=pl.C_MAIN, lw=1.2, label="indication − true heading")
        d = run.figures.get("drift")
        if isinstance(d, dict) and all(isinstance(d.get(k), (int, float)) for k in (
                "measured_deg_h", "free_gyro_deg_h", "book_12_22_deg_h", "compensation_deg_h")):
            pl.note(ax, "drift over the run: measured %s °/h; free gyro %s °/h vs book (12.22) %s °/h\n"
                        "(Earth %s, transport %s); compensation %s °/h" % (
                        pl.num(d["measured_deg_h"]), pl.num(d["free_gyro_deg_h"]), pl.num(d["book_12_22_deg_h"]),
                        pl.num(d.get("earth_rate_term_deg_h")), pl.num(d.get("transport_term_deg_h")),
                        pl.num(d["compensation_deg_h"])), loc="lower left", size=7.5)
        pl.ylabel(ax, "heading error\n[deg]")
        pl.legend(ax, loc="upper right", ncol=2)

    if "rotor" in L.rows:
        ax = L["rotor"].whole
        if bank is not None:
            pl.plot_t(ax, run, bank * deg, color=pl.C_REF, ls="--", lw=1.0, label="bank")
        if beta is not None:
            pl.plot_t(ax, run, beta * deg, color=pl.C_SECOND, lw=1.1, label="β (inner gimbal)")
        lines, first = [], True
        for s in segs:
            v = s.get("beta_book_end_rad")
            if isinstance(v, (int, float)):
                ax.plot([s["t_end_s"] * tf], [v * deg], "x", color=pl.C_BOOK, ms=7, mew=2, zorder=8,
                        label="book (12.25)+(12.29) at the turn's end" if first else None)
                first = False
                be, dl, db, c = (s.get(k) for k in ("beta_end_rad", "rotor_azimuth_change_rad", "delta_book_rad",
                                                    "c"))
                if all(isinstance(x, (int, float)) for x in (be, dl, db, c)):
                    lines.append("turn to %s s, c = %s: β %s° (book %s°), δ %s° (book (12.32) %s°)" % (
                        pl.num(s["t_end_s"]), pl.num(c), pl.num(be * deg), pl.num(v * deg), pl.num(dl * deg),
                        pl.num(db * deg)))
        if lines:
            pl.note(ax, "\n".join(lines), loc="lower left", size=7.5)
        pl.ylabel(ax, "angle [deg]")
        pl.legend(ax, loc="upper right", ncol=3)

    if "torque" in L.rows:
        ax = L["torque"].whole
        lim = run.limit("torquer_limit_Nm")
        peak = pl._maxabs(m1, m2)
        f, unit = pl.si_unit("N m", maxabs=max(peak, lim) if lim and peak * 4 >= lim else peak)
        if m1 is not None:
            pl.plot_t(ax, run, m1 * f, color=pl.C_MAIN, lw=0.8, label="M1 (inter-gimbal)")
        if m2 is not None:
            pl.plot_t(ax, run, m2 * f, color=pl.C_SECOND, lw=0.8, label="M2 (compensation + heading)")
        pl.limit_lines(ax, lim, "torquer limit", f, peak, unit=" " + unit, base_unit="N m")
        pl.ylabel(ax, "torquer\n[%s]" % unit)
        pl.legend(ax, loc="lower left", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits, NAMES), NAMES)
    pl.title(L.fig, run, "directional gyro (aircraft)", None)
    pl.limits_missing_note(L.fig, run, ["torquer_limit_Nm"])
    return L.finish()
