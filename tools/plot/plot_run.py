#!/usr/bin/python3
"""Plot a gyrostab run: every column of signals.csv against time, grouped by unit suffix, into PNGs.

Usage: plot_run.py OUT_DIR   (reads OUT_DIR/signals.csv and OUT_DIR/report.json, writes OUT_DIR/*.png)
Runs with Debian's system interpreter and python3-matplotlib (no pip).
"""
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(out_dir):
    with open(os.path.join(out_dir, "signals.csv"), newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    cols = {name: [float(r[i]) for r in data] for i, name in enumerate(header)}
    t = cols.pop("t_s")
    title = ""
    try:
        with open(os.path.join(out_dir, "report.json")) as f:
            title = json.load(f)["scene"]["name"]
    except (OSError, KeyError, ValueError):
        pass
    units = [("_rad_s", "rad/s"), ("_rad", "rad"), ("_Nm", "N m"), ("_A", "A"), ("_V", "V"), ("_bits", "bits"),
             ("_m", "m")]
    groups = {}
    for name in cols:
        unit = next((label for suffix, label in units if name.endswith(suffix)), "")
        groups.setdefault(unit, []).append(name)
    fig, axes = plt.subplots(len(groups), 1, figsize=(10, 2.6 * len(groups)), sharex=True, squeeze=False)
    for ax, (unit, names) in zip(axes[:, 0], groups.items()):
        for n in names:
            ax.plot(t, cols[n], label=n, linewidth=0.8)
        ax.set_ylabel(unit)
        ax.grid(True, alpha=0.3)
        ax.legend(loc="upper right", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]")
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "signals.png"), dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
