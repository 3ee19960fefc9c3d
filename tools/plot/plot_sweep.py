#!/usr/bin/python3
"""Heat maps of a sizing study (gyrostab sweep merge, docs/sweep.md) over the sea-state table.

    plot_sweep.py RESULTS_DIR VARIANT...

For each variant, reads RESULTS_DIR/VARIANT/cells.csv and writes heatmap_roll_reduction.png and
heatmap_stop_contacts.png beside it: one square per (Hs, Tp) cell of the table, its colour and printed value
the cell's mean over replicates, averaged over headings with the headings' probabilities; a cell whose tasks
failed or are missing is left grey and marked. A figure the build does not report (stop_contacts before the
hull model reports it) gives a map that says so. Exit 3 without matplotlib (the tables are already written).
"""
import csv
import math
import os
import sys

try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError as e:  # the caller says the tables are complete
    print(f"plot_sweep.py: {e}", file=sys.stderr)
    sys.exit(3)

MAPS = [("roll_reduction", "roll reduction 1 − σ/σ₀", "viridis", "{:.2f}"),
        ("stop_contacts", "end-stop contacts per run", "magma_r", "{:.1f}")]


def num(text):
    return float(text) if text != "" else None


def cell_means(rows, figure):
    """(Hs, Tp) -> heading-weighted mean of `figure`, or None when a heading's row is excluded or null."""
    acc = {}
    for r in rows:
        key = (float(r["Hs_m"]), float(r["Tp_s"]))
        value = num(r[figure]) if r["included"] == "1" else None
        p = float(r["probability"])
        total, weight, ok = acc.get(key, (0.0, 0.0, True))
        if value is None:
            ok = False
        else:
            total += p * value
        acc[key] = (total, weight + p, ok)
    return {k: (t / w if ok and w > 0 else (None if not ok else math.nan)) for k, (t, w, ok) in acc.items()}


def draw(rows, figure, title, cmap, fmt, variant, path):
    means = cell_means(rows, figure)
    hs = sorted({k[0] for k in means})
    tp = sorted({k[1] for k in means})
    fig, ax = plt.subplots(figsize=(1.2 + 1.1 * len(tp), 1.0 + 0.8 * len(hs)), dpi=100)
    values = [v for v in means.values() if v is not None and not math.isnan(v)]
    lo, hi = (min(values), max(values)) if values else (0.0, 1.0)
    if hi == lo:
        hi = lo + 1.0
    colours = plt.get_cmap(cmap)
    for (h, t), v in sorted(means.items()):
        x, y = tp.index(t), hs.index(h)
        missing = v is None or math.isnan(v)
        face = "0.85" if missing else colours((v - lo) / (hi - lo))
        ax.add_patch(plt.Rectangle((x - 0.5, y - 0.5), 1, 1, facecolor=face, edgecolor="white"))
        label = "n/a" if missing else fmt.format(v)
        shade = 0.0 if missing else (v - lo) / (hi - lo)
        ax.text(x, y, label, ha="center", va="center", fontsize=9,
                color="white" if not missing and shade < 0.35 else "black")
    ax.set_xlim(-0.5, len(tp) - 0.5)
    ax.set_ylim(-0.5, len(hs) - 0.5)
    ax.set_xticks(range(len(tp)), [f"{t:g}" for t in tp])
    ax.set_yticks(range(len(hs)), [f"{h:g}" for h in hs])
    ax.set_xlabel("Tp [s]")
    ax.set_ylabel("Hs [m]")
    note = "" if values else " (not reported by this build)"
    ax.set_title(f"{variant}: {title}{note}", fontsize=10)
    if values:
        sm = plt.cm.ScalarMappable(cmap=colours, norm=plt.Normalize(lo, hi))
        fig.colorbar(sm, ax=ax)
    fig.tight_layout()
    fig.savefig(path, metadata={"Software": None})
    plt.close(fig)


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    out = argv[1]
    for variant in argv[2:]:
        with open(os.path.join(out, variant, "cells.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        for figure, title, cmap, fmt in MAPS:
            draw(rows, figure, title, cmap, fmt, variant, os.path.join(out, variant, f"heatmap_{figure}.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
