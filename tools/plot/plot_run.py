#!/usr/bin/python3
"""Plot a gyrostab run into OUT_DIR/signals.png.

Usage: plot_run.py OUT_DIR   (reads OUT_DIR/signals.csv and OUT_DIR/report.json, writes OUT_DIR/signals.png)

The device (report.json "scene"."device") draws its own figure: tools/devices/<device>/plot.py, a module with
plot(run) -> matplotlib Figure (helpers: tools/plot/plot_lib.py). Without such a module (or without a
report.json) the generic figure is drawn: every column against time, grouped by unit suffix.
Exit status 0 when signals.png was written; 1 with a one-line message on stderr when the run cannot be
plotted (no or malformed signals.csv, ...). A device module that fails is reported on stderr (one line) and
the generic figure is drawn instead; with GYROSTAB_PLOT_STRICT=1 (the tests) that failure exits 1, and a
device figure that finds none of its columns says so on stderr.
Runs with Debian's system interpreter, python3-matplotlib and python3-numpy (no pip).
"""
import importlib.util
import os
import re
import sys
import traceback

sys.dont_write_bytecode = True  # the source tree may be read-only; nothing to cache for a one-shot script
HERE = os.path.dirname(os.path.abspath(__file__))
DEVICES = os.path.normpath(os.path.join(HERE, "..", "devices"))
PROG = "plot_run.py"


def device_module(device):
    """The device's plot module, or None if it has none."""
    if not re.fullmatch(r"[a-z][a-z0-9_]*", device or ""):
        return None
    path = os.path.join(DEVICES, device, "plot.py")
    if not os.path.isfile(path):
        return None
    spec = importlib.util.spec_from_file_location("gyrostab_plot_" + device, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def one_line(e):
    text = str(e).strip().splitlines()
    return "%s: %s" % (type(e).__name__, text[0] if text else "")


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        sys.stderr.write("usage: %s OUT_DIR (writes OUT_DIR/signals.png from signals.csv and report.json)\n" % PROG)
        return 2
    out_dir = argv[1]
    sys.path.insert(0, HERE)
    try:
        import plot_lib
    except ImportError as e:  # matplotlib or numpy missing
        sys.stderr.write("%s: cannot import the plot libraries (%s)\n" % (PROG, one_line(e)))
        return 1
    try:
        run = plot_lib.load_run(out_dir)
    except plot_lib.PlotError as e:
        sys.stderr.write("%s: %s: %s\n" % (PROG, out_dir, e))
        return 1
    fig = None
    why = None
    if run.report_problem:
        why = run.report_problem + ": generic figure"
    else:
        try:
            module = device_module(run.device)
            if module is None:
                why = "no plot module for device %r: generic figure" % run.device
            else:
                fig = module.plot(run)
        except plot_lib.NothingToPlot as e:
            why = "%s: generic figure" % e
            if os.environ.get("GYROSTAB_PLOT_STRICT") == "1":  # the tests: say that the device figure was not drawn
                sys.stderr.write("%s: %s\n" % (PROG, why))
        except Exception as e:  # a bug in a device module must not cost the user the figure
            where = traceback.extract_tb(e.__traceback__)[-1]
            what = "%s (%s:%d)" % (one_line(e), os.path.relpath(where.filename, HERE), where.lineno)
            if os.environ.get("GYROSTAB_PLOT_STRICT") == "1":
                sys.stderr.write("%s: the %s figure failed: %s\n" % (PROG, run.device, what))
                return 1
            sys.stderr.write("%s: the %s figure failed (%s); drew the generic figure\n" % (PROG, run.device, what))
            why = "the device figure failed: generic figure"
            plot_lib.plt.close("all")
    try:
        if fig is None:
            fig = plot_lib.generic_figure(run, why)
        plot_lib.save(fig, run)
    except Exception as e:
        sys.stderr.write("%s: cannot write %s/signals.png (%s)\n" % (PROG, out_dir, one_line(e)))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
