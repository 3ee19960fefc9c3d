#!/usr/bin/python3
"""Plot a gyrostab accuracy study: error against run time (log-log), one panel per error quantity.

Usage: plot_work_precision.py OUT_DIR   (reads OUT_DIR/report.json, writes OUT_DIR/work_precision.png)
Runs with Debian's system interpreter and python3-matplotlib (no pip).

Each method is one line through its step (fixed-step) or tolerance (adaptive) sweep: ours solid with filled
markers, the peers dashed with open markers. Lower-left is better: less error for less time. The star is the
scene's own integrator and step; hollow grey markers lie below the reference floor (not resolved: not used
in the speed-up unless the reference is at round-off, when they sit at the floor); the grey band is that floor
(10x the difference of the two reference runs).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "gyro-exponential": ("tab:red", "o"),
    "rk4": ("tab:blue", "s"),
    "implicit-midpoint": ("tab:purple", "D"),
    "odeint-rk4": ("tab:cyan", "s"),
    "odeint-dopri5": ("tab:green", "^"),
    "cvode-bdf": ("tab:orange", "v"),
    "cvode-adams": ("tab:brown", "<"),
}


def main(out_dir):
    with open(os.path.join(out_dir, "report.json")) as f:
        rep = json.load(f)
    quantities = rep["quantities"]
    runs = rep["runs"]
    ref = rep["reference"]
    fig, axes = plt.subplots(1, len(quantities), figsize=(6.2 * len(quantities), 5.2), squeeze=False)
    for ax, q in zip(axes[0], quantities):
        name = q["name"]
        methods = []
        for r in runs:
            if r["method"] not in methods:
                methods.append(r["method"])
        for m in methods:
            pts = [r for r in runs if r["method"] == m and r["ok"] and r["errors"].get(name)]
            pts.sort(key=lambda r: r["s_per_simulated_s"])
            if not pts:
                continue
            color, marker = STYLE.get(m, ("k", "x"))
            ours = pts[0]["family"] == "ours"
            # The line runs through the errors the comparison uses (a run below the reference floor sits at
            # the floor when the reference is at round-off); a run below the floor is drawn hollow.
            used = [r for r in pts if r["comparison_error"].get(name)]
            xs = [1e3 * r["s_per_simulated_s"] for r in used]
            ys = [r["comparison_error"][name] for r in used]
            ax.plot(xs, ys, linestyle="-" if ours else "--", marker=marker, color=color,
                    markerfacecolor=color if ours else "none", label=("ours: " if ours else "peer: ") + m)
            floor = [r for r in pts if r["below_reference_floor"][name]]
            ax.plot([1e3 * r["s_per_simulated_s"] for r in floor],
                    [r["comparison_error"][name] or r["errors"][name] for r in floor],
                    linestyle="none", marker=marker, color="0.5", markerfacecolor="white")
            for r in pts:
                e = r["comparison_error"].get(name) or r["errors"][name]
                if r.get("scene_configuration") and e > 0:
                    ax.plot([1e3 * r["s_per_simulated_s"]], [e], marker="*", markersize=16,
                            color="gold", markeredgecolor="k", linestyle="none", label="the scene's own setting")
        if ref.get("kind") == "converged reference":
            d = ref["difference"][name]
            if d and d > 0:
                ax.axhspan(1e-300, 10 * d, color="0.85", zorder=0)
                ax.axhline(10 * d, color="0.5", linewidth=0.8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ys = [r["comparison_error"][name] or r["errors"][name] for r in runs
              if r["ok"] and (r["comparison_error"].get(name) or r["errors"].get(name))]
        if ys:
            ax.set_ylim(min(ys) / 3, max(ys) * 3)
        ax.set_xlabel("run time (thread CPU) per simulated second [ms/s]")
        ax.set_ylabel("error: %s [%s]" % (name, q["unit"]))
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, loc="best")
    su = rep.get("speed_up", {}).get("at_scene_error")
    title = "%s: work-precision (window %.3g s)" % (rep["scene"]["name"], rep["scene"]["window_s"])
    if su and su.get("ratio"):
        title += " | speed-up at the scene's error %.2g: %.3gx (%s over %s)" % (
            su["error"], su["ratio"], su["ours_method"], su["peer_method"])
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "work_precision.png"), dpi=110)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1]))
