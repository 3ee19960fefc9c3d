"""Gyro vertical figure: how far does the indicated vertical wander in the aircraft's turns, against the book?

Rows (the whole flight; the manoeuvre segments of figures.segments shaded, turns labelled):
  tilt error   the instrument's tilt α (roll axis: the indicated-bank error) and β (pitch axis) in degrees,
               the apparent vertical α_L the erection pulls towards (dashed), the book's tilt at each segment's
               end ((12.45)/(12.39), crosses) and its steady turn error z_G (12.47) over the turns (dotted);
               the largest indicated-bank error and the turn-end errors against the book written on it
  turn rate    the true turn rate and the turn indicator's reading (≈ cos(bank) of it, (15.6)), with the
               correction cut-out threshold
  dead zone    with bearing Coulomb friction (figures.dead_zone): α and β near the band of Fig. 12.12 in which
               the correction cannot move the gimbals (shaded per axis), the residual tilt at the end, whether
               the gimbals are held, and the largest gimbal rate over the last tenth of the run (the creep)
  torques      the erection torques M1, M2 against the torquer limit
  status       event lanes of the status bits, only if one is ever set (cut-out, torquer limited)
Limits (tools/plot/LIMITS.md): torquer_limit_Nm, turn_cutout_rad_s; absent, no line.
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
    a, b = run.col("alpha_rad"), run.col("beta_rad")
    aL, bL = run.nonzero("alpha_L_rad", 1e-12), run.nonzero("beta_L_rad", 1e-12)
    turn, ind = run.col("turn_rate_rad_s"), run.col("turn_indicator_rad_s")
    m1, m2 = run.nonzero("M1_Nm"), run.nonzero("M2_Nm")
    if a is None and b is None and turn is None and ind is None:
        raise pl.NothingToPlot("gyro_vertical: none of alpha_rad, beta_rad, turn_rate_rad_s recorded")
    bits = run.status()
    rows = []
    if a is not None or b is not None:
        rows.append(("tilt", 1.6, False))
    dz = run.figures.get("dead_zone")
    dz = dz if isinstance(dz, dict) else None
    if dz is not None and (a is not None or b is not None):
        rows.append(("deadzone", 1.1, False))
    if (turn is not None or ind is not None) and dz is None:
        rows.append(("turn", 0.8, False))
    if m1 is not None or m2 is not None:
        rows.append(("torque", 0.8, False))
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    tf = run.time[0]
    deg = pl.DEG
    segs = _segments(run)
    for s in segs:
        w = s.get("turn_rate_rad_s") or 0.0
        if abs(w) > 1e-3:
            for row in L.rows.values():
                label = None
                if row is L.top_row:
                    label = "%s turn %s°/s" % ("right" if w > 0 else "left", pl.num(abs(w) * deg, 2))
                pl.shade_span(row.whole, run, s["t_start_s"], s["t_end_s"], color="tab:orange", alpha=0.10,
                              label=label, y=0.90)

    if "tilt" in L.rows:
        ax = L["tilt"].whole
        if aL is not None:
            pl.plot_t(ax, run, aL * deg, color=pl.C_REF, ls="--", lw=1.0, label="apparent vertical α_L")
        if bL is not None:
            pl.plot_t(ax, run, bL * deg, color=pl.C_REF, ls=":", lw=1.0, label="apparent vertical β_L")
        if a is not None:
            pl.plot_t(ax, run, a * deg, color=pl.C_MAIN, lw=1.1, label="α (bank error)")
        if b is not None:
            pl.plot_t(ax, run, b * deg, color=pl.C_SECOND, lw=1.1, label="β (pitch error)")
        first = True
        lines = []
        for s in segs:
            t1 = s["t_end_s"]
            for key, c in (("alpha_book_end_rad", pl.C_MAIN), ("beta_book_end_rad", pl.C_SECOND)):
                v = s.get(key)
                if isinstance(v, (int, float)):
                    ax.plot([t1 * tf], [v * deg], "x", color=pl.C_BOOK, ms=7, mew=2, zorder=8,
                            label="book (12.45) at the segment's end" if first else None)
                    first = False
            w = s.get("turn_rate_rad_s") or 0.0
            if abs(w) > 1e-3:
                for key in ("alpha_G_rad", "beta_G_rad"):
                    v = s.get(key)
                    if isinstance(v, (int, float)):
                        ax.hlines(v * deg, s["t_start_s"] * tf, t1 * tf, color=pl.C_BOOK, ls=":", lw=1.6, zorder=4)
                ae, ab, be, bb = (s.get(k) for k in ("alpha_end_rad", "alpha_book_end_rad", "beta_end_rad",
                                                     "beta_book_end_rad"))
                if all(isinstance(v, (int, float)) for v in (ae, ab, be, bb)):
                    lines.append("%s turn at %s s: α %s° (book %s°), β %s° (book %s°)%s" % (
                        "right" if w > 0 else "left", pl.num(t1), pl.num(ae * deg), pl.num(ab * deg),
                        pl.num(be * deg), pl.num(bb * deg), ", cut out" if s.get("correction_cut_out") else ""))
        mx = run.fig("indicated_bank_error_max_rad")
        if mx is not None:
            pl.note(ax, "largest indicated-bank error |α| = %s°" % pl.num(mx * deg), loc="upper left", size=10,
                    bold=True, color=pl.C_MAIN)
        if lines:
            pl.note(ax, "tilt error at the end of each turn:\n" + "\n".join(lines), loc="lower left", size=7.5)
        d, wp = run.fig("delta_s"), run.fig("omega_P_rad_s")
        if d is not None:
            text = "erection δ = f/H = %s /s (time constant %s s), $\\omega^P$ = %s rad/s" % (
                pl.num(d), pl.num(1 / d) if d > 0 else "∞", pl.num(wp))
            if run.figures.get("prediction_applies") is False:
                text += "\nthe law is not the linear one: the book's prediction does not apply"
            pl.note(ax, text, loc="lower right", size=7.5)
        pl.ylabel(ax, "tilt [deg]")
        pl.legend(ax, loc="lower center", ncol=2)
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo - 0.45 * (hi - lo), hi + 0.25 * (hi - lo))  # room for the notes

    if "deadzone" in L.rows:
        _dead_zone(L["deadzone"].whole, run, dz, a, b)

    if "turn" in L.rows:
        ax = L["turn"].whole
        if turn is not None:
            pl.plot_t(ax, run, turn * deg, color=pl.C_REF, lw=1.6, label="true turn rate")
        if ind is not None:
            pl.plot_t(ax, run, ind * deg, color=pl.C_MAIN, lw=0.9, label="turn indicator")
        pl.limit_lines(ax, run.limit("turn_cutout_rad_s"), "cut-out", pl.DEG, None, color=pl.C_SOFT, unit="°/s")
        ratios = [s.get("turn_indicator_over_true") for s in segs if abs(s.get("turn_rate_rad_s") or 0.0) > 1e-3]
        ratios = [r for r in ratios if isinstance(r, (int, float))]
        if ratios:
            pl.note(ax, "indicator / true in the turns: %s (≈ cos bank, (15.6))" % ", ".join(pl.num(r) for r in ratios),
                    loc="lower left", size=7.5)
        pl.ylabel(ax, "turn rate\n[deg/s]")
        pl.legend(ax, loc="upper right", ncol=2)

    if "torque" in L.rows:
        ax = L["torque"].whole
        lim = run.limit("torquer_limit_Nm")
        peak = pl._maxabs(m1, m2)
        f, unit = pl.si_unit("N m", maxabs=max(peak, lim) if lim and peak * 4 >= lim else peak)
        if m1 is not None:
            pl.plot_t(ax, run, m1 * f, color=pl.C_MAIN, lw=0.8, label="M1")
        if m2 is not None:
            pl.plot_t(ax, run, m2 * f, color=pl.C_SECOND, lw=0.8, label="M2")
        pl.limit_lines(ax, lim, "torquer limit", f, peak, unit=" " + unit, base_unit="N m")
        pl.ylabel(ax, "erection torque\n[%s]" % unit)
        pl.legend(ax, loc="lower left", ncol=2)

    pl.status_banner(L, pl.status_strip(L, run, bits, NAMES), NAMES)
    pl.title(L.fig, run, "gyro vertical (aircraft)", None)
    pl.limits_missing_note(L.fig, run, ["torquer_limit_Nm"])
    return L.finish()


def _pair(v):
    if isinstance(v, list) and len(v) == 2 and all(isinstance(x, (int, float)) for x in v):
        return v
    return None


def _dead_zone(ax, run, dz, a, b):
    deg = pl.DEG
    band = dz.get("band") if isinstance(dz.get("band"), dict) else None
    widths = []
    if band is not None:
        for key, color, name in (("e1_rad", pl.C_MAIN, "α"), ("e2_rad", pl.C_SECOND, "β")):
            lo_hi = _pair(band.get(key))
            if lo_hi is not None:
                ax.axhspan(lo_hi[0] * deg, lo_hi[1] * deg, color=color, alpha=0.10,
                           label="dead zone of %s (Fig. 12.12)" % name)
                widths.append(abs(lo_hi[1] - lo_hi[0]) / 2)
    if a is not None:
        pl.plot_t(ax, run, a * deg, color=pl.C_MAIN, lw=1.1, label="α")
    if b is not None:
        pl.plot_t(ax, run, b * deg, color=pl.C_SECOND, lw=1.1, label="β")
    res = _pair(dz.get("residual_tilt_rad"))
    lines = ["bearing friction: %s, r = %s / %s N m" % (dz.get("friction_model"), pl.num(dz.get("r1_Nm")),
                                                        pl.num(dz.get("r2_Nm")))]
    if res is not None:
        t_end = run.t_end * run.time[0]
        ax.plot([t_end, t_end], [res[0] * deg, res[1] * deg], "o", color=pl.C_BOOK, ms=5, zorder=8,
                label="residual tilt")
        lines.append("residual tilt e = (%s°, %s°)" % (pl.num(res[0] * deg, 4), pl.num(res[1] * deg, 4)))
    if band is not None:
        hw = _pair(band.get("half_width_rad"))
        if hw is not None:
            lines.append("band half-widths r2/f2, r1/f1 = %s°, %s°" % (pl.num(hw[0] * deg), pl.num(hw[1] * deg)))
        out = dz.get("outside_band_rad")
        if isinstance(out, (int, float)):
            lines.append("outside the band by %s rad" % pl.num(out))
    elif isinstance(dz.get("band_why_not"), str):
        lines.append(dz["band_why_not"])
    held = dz.get("held")
    if isinstance(held, list):
        lines.append("gimbals held at the end: %s" % ", ".join("yes" if h else "no" for h in held))
    creep = dz.get("late_rate_max_rad_s")
    if isinstance(creep, (int, float)):
        lines.append("largest gimbal rate over the last tenth: %s rad/s" % pl.num(creep))
    pl.note(ax, "\n".join(lines), loc="upper right", size=7.5)
    if widths:
        w = max(widths) * deg
        ax.set_ylim(-2.6 * w, 5.2 * w)  # room for the note above the band
    pl.ylabel(ax, "tilt near the\ndead zone [deg]")
    pl.legend(ax, loc="lower right", ncol=3)
