"""CMG cluster: does the slew reach its attitude, and how close do the gimbals come to a singular configuration?

Rows (whole run):
  error      the attitude error against the commanded attitude, log scale, with the settle band; the final
             error and the settling time written on it
  momentum   the cluster's momentum h Σ s_i in body axes (x, y, z) with the envelope along the slew axis and
             the internal singular level 2h cosβ along x (the pyramid's, drawn when figures name it)
  measure    the singularity measure det(AAᵀ)/h⁶, log scale, its minimum along the run and the near-singular level
  status     event lanes (rate-limited gimbal commands, singular pseudo-inverse), only if a bit is ever set
Limits: settle_band_deg, near_singular_measure.
"""
import numpy as np

import plot_lib as pl


def plot(run):
    err, m = run.col("attitude_error_deg"), run.col("singularity_measure")
    if err is None and m is None:
        raise pl.NothingToPlot("cmg_cluster: none of attitude_error_deg, singularity_measure recorded")
    H = [run.col("H_cmg_%s_Nms" % a) for a in "xyz"]
    bits = run.status()
    rows = [(k, h, True) for k, h, y in (("error", 1.2, err), ("momentum", 1.0, H[0]), ("measure", 1.0, m))
            if y is not None]
    L = pl.Layout(run, rows, status_lanes=len(pl.active_bits(bits)))
    steering = run.figures.get("steering") or "?"

    if "error" in L.rows:
        r = L["error"]
        pl.plot_t(r.whole, run, np.maximum(err, 1e-9), color=pl.C_MAIN, lw=0.9)
        r.whole.set_yscale("log")
        band = run.limit("settle_band_deg")
        if band is not None:
            pl.hline(r.whole, band, "settle band %s°" % pl.num(band))
        ts = run.fig("settling_time_s")
        pl.note(r.whole, "%s: final error %s°, settled %s" % (
            steering, pl.num(run.fig("final_attitude_error_deg")), "at %s s" % pl.num(ts) if ts is not None else "never"),
            loc="upper right", size=9, bold=True, color=pl.C_MAIN)
        pl.ylabel(r.whole, "attitude error\n[deg]")

    if "momentum" in L.rows:
        r = L["momentum"]
        for y, name, c in zip(H, "xyz", ("C0", "C1", "C2")):
            if y is not None:
                pl.plot_t(r.whole, run, y, color=c, lw=0.9, label="H_" + name)
        internal = run.fig("pyramid_internal_singularity_Nms")
        if internal is not None:
            pl.hline(r.whole, -internal, "−2h cosβ: the internal singularity along x", va="top")
            pl.hline(r.whole, internal, None)
        env = run.fig("envelope_along_slew_axis_Nms")
        if env is not None:
            pl.hline(r.whole, env, "envelope along the slew axis")
            pl.hline(r.whole, -env, None)
        pl.note(r.whole, "peak |H| %s N m s" % pl.num(run.fig("peak_cmg_momentum_Nms")), loc="lower right", size=8)
        pl.legend(r.whole, loc="upper right", ncol=3)
        pl.ylabel(r.whole, "cluster momentum\n[N m s]")

    if "measure" in L.rows:
        r = L["measure"]
        pl.plot_t(r.whole, run, np.maximum(m, 1e-16), color=pl.C_MAIN, lw=0.9)
        r.whole.set_yscale("log")
        near = run.limit("near_singular_measure")
        if near is not None:
            pl.hline(r.whole, near, "near-singular")
        pl.note(r.whole, "min det(AAᵀ)/h⁶ %s at %s s; near-singular for %s s" % (
            pl.num(run.fig("min_singularity_measure")), pl.num(run.fig("min_singularity_measure_at_s")),
            pl.num(run.fig("near_singular_time_s"))), loc="lower right", size=8)
        pl.ylabel(r.whole, "singularity measure\ndet(AAᵀ)/h⁶")

    pl.status_banner(L, pl.status_strip(L, run, bits, None, None), None)
    pl.title(L.fig, run, "CMG cluster (%s steering)" % steering, None)
    return L.finish()
