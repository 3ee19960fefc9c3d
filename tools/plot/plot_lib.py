"""Shared helpers for the gyrostab run figures: tools/plot/plot_run.py and tools/devices/<device>/plot.py.

What is here:
  load_run(dir)         report.json + signals.csv -> Run (columns by name, figures, limits, scene);
                        a malformed CSV raises PlotError with a one-line message
  Run.col / has / fig / limit   a column, a figure or a limit, or None when absent (never a KeyError)
  time_unit, angle_unit, si_unit    unit choice and scale factors (rad -> deg / arcmin / arcsec, N m -> kN m ...)
  Layout                rows of axes, each a whole-run axis and, optionally, a zoomed window beside it
  envelope              min/max decimation of long series for the whole-run view (never used in a zoom)
  limit_lines           labelled +-limit lines (or a note when the limit is far off the data's scale)
  note, mark_peak, shade_span, vline    annotations
  status_strip          event lanes for the status bits that are set (nothing when all are zero)
  title, save           the title line (scene, device, seed, duration) and the PNG (110 dpi, 12 in wide)
  generic_figure        every column against time, grouped by unit suffix (the fallback figure)

Runs with Debian's /usr/bin/python3, python3-matplotlib and python3-numpy (no pip).
"""
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.transforms as mtransforms  # noqa: E402
import numpy as np  # noqa: E402

DPI = 110
MAX_TITLE_NAME = 80  # characters of the scene name in a figure's title
WIDTH_IN = 12.0
DEG = 180.0 / math.pi

# Colours used with one meaning on every figure.
C_MAIN = "tab:blue"      # the quantity the device exists for
C_REF = "0.55"           # its reference / the unstabilized or uncorrected case
C_BOOK = "tab:green"     # the book's (predicted) value
C_SOFT = "tab:orange"    # soft limits
C_HARD = "tab:red"       # hard limits: end stops, torque / current / voltage limits
C_SECOND = "tab:purple"  # a second axis of the same quantity


class PlotError(Exception):
    """The run cannot be plotted; the message is one line for stderr."""


class NothingToPlot(Exception):
    """A device module found none of its columns: plot_run.py falls back to the generic figure."""


# ---------------------------------------------------------------------------------------------- loading

def _finite(x):
    return isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x)


class Run:
    """One run's outputs. Columns are float arrays in SI units (as the CSV has them), ±inf read as NaN."""

    def __init__(self, out_dir, report, header, data):
        self.dir = out_dir
        self.report = report if isinstance(report, dict) else {}
        scene = self.report.get("scene")
        self.scene = scene if isinstance(scene, dict) else {}
        figures = self.report.get("figures")
        self.figures = figures if isinstance(figures, dict) else {}
        limits = self.report.get("limits")
        self.limits = limits if isinstance(limits, dict) else {}
        self.header = header
        self.cols = {}
        for i, name in enumerate(header):
            if name in self.cols or name == "t_s":
                continue
            v = data[:, i]
            if np.isnan(v).all():
                continue  # a column of NaN carries nothing: treat it as missing
            self.cols[name] = v
        self.t = data[:, header.index("t_s")]
        dev = self.scene.get("device")
        self.device = dev if isinstance(dev, str) else ""
        name = self.scene.get("name")
        self.name = name if isinstance(name, str) and name else os.path.basename(os.path.abspath(out_dir))
        # A title is one line: a scene may name itself with up to its file's size (1 MiB), and laying out that
        # much text costs matplotlib hundreds of MB.
        if len(self.name) > MAX_TITLE_NAME:
            self.name = self.name[:MAX_TITLE_NAME - 1] + "…"
        self.seed = self.scene.get("seed")
        d = self.scene.get("duration_s")
        self.duration = float(d) if _finite(d) and d > 0 else float(self.t[-1])
        self.t_end = max(self.duration, float(self.t[-1]))
        self.time = time_unit(self.t_end)

    # Columns -----------------------------------------------------------------------------------------
    def has(self, *names):
        return all(n in self.cols for n in names)

    def col(self, name):
        return self.cols.get(name)

    def nonzero(self, name, tol=0.0):
        """The column if present and not identically zero (a panel of zeros is not drawn)."""
        v = self.cols.get(name)
        if v is None:
            return None
        return v if np.nanmax(np.abs(v)) > tol else None

    def status(self):
        """status_bits as integers, or None when the column is absent or every bit is zero."""
        v = self.cols.get("status_bits")
        if v is None:
            return None
        b = np.nan_to_num(v, nan=0.0).astype(np.int64)
        return b if b.any() else None

    @property
    def dt(self):
        return float(np.median(np.diff(self.t))) if self.t.size > 1 else self.t_end

    # Report values -----------------------------------------------------------------------------------
    def fig(self, key, default=None):
        """A finite number from report.json "figures", else default."""
        v = self.figures.get(key)
        return float(v) if _finite(v) else default

    def limit(self, key):
        """A limit from report.json "limits" (SI units), or None if absent / not a finite positive number."""
        v = self.limits.get(key)
        return float(v) if _finite(v) and v > 0 else None

    def block(self, *path):
        """A nested dict of report.json (e.g. "reduced_model"), or {}."""
        node = self.report
        for k in path:
            node = node.get(k) if isinstance(node, dict) else None
        return node if isinstance(node, dict) else {}

    def window(self, t0, t1):
        """Boolean mask of the samples in [t0, t1] (seconds)."""
        return (self.t >= t0) & (self.t <= t1)


def _read_csv(path):
    try:
        with open(path, newline="") as f:
            first = f.readline()
            if not first.strip():
                raise PlotError("signals.csv is empty")
            header = [h.strip() for h in first.strip().split(",")]
            body = f.read()
    except OSError as e:
        raise PlotError("cannot read signals.csv: %s" % (e.strerror or e))
    except UnicodeDecodeError:
        raise PlotError("signals.csv is not text")
    if "t_s" not in header:
        raise PlotError("signals.csv has no t_s column (header: %s)" % first.strip()[:80])
    if any(not h for h in header):
        raise PlotError("signals.csv header has an empty column name")
    lines = [ln for ln in body.splitlines() if ln.strip()]
    if not lines:
        raise PlotError("signals.csv has a header but no data rows")
    n = len(header)
    # A fast path for the well-formed file; the slow path only to say where it is malformed.
    try:
        data = np.array([ln.split(",") for ln in lines], dtype=float)
        if data.ndim != 2 or data.shape[1] != n:
            raise ValueError
    except ValueError:
        for i, ln in enumerate(lines, start=2):
            fields = ln.split(",")
            if len(fields) != n:
                raise PlotError("signals.csv line %d: %d fields, the header has %d" % (i, len(fields), n))
            for j, x in enumerate(fields):
                try:
                    float(x)
                except ValueError:
                    raise PlotError("signals.csv line %d, column %s: not a number: %r" % (i, header[j], x[:20]))
        raise PlotError("signals.csv is malformed")
    data[~np.isfinite(data)] = np.nan
    t = data[:, header.index("t_s")]
    if not np.isfinite(t).all():
        raise PlotError("signals.csv: t_s has non-finite values")
    if t.size > 1 and (np.diff(t) < 0).any():
        raise PlotError("signals.csv: t_s is not increasing")
    return header, data


def load_run(out_dir):
    """Read OUT_DIR/signals.csv (required) and OUT_DIR/report.json (optional: without it, no device)."""
    if not os.path.isdir(out_dir):
        raise PlotError("%s is not a directory" % out_dir)
    csv_path = os.path.join(out_dir, "signals.csv")
    if not os.path.exists(csv_path):
        raise PlotError("no signals.csv in %s" % out_dir)
    header, data = _read_csv(csv_path)
    report, problem = {}, None
    try:
        with open(os.path.join(out_dir, "report.json")) as f:
            report = json.load(f)
        if not isinstance(report, dict):
            report, problem = {}, "report.json is not an object"
    except FileNotFoundError:
        problem = "no report.json"
    except (OSError, ValueError) as e:
        report, problem = {}, "report.json unreadable (%s)" % str(e).splitlines()[0][:80]
    run = Run(out_dir, report, header, data)
    run.report_problem = problem
    return run


# ------------------------------------------------------------------------------------------------ units

def time_unit(t_end):
    """(factor from s, label) for the time axis: s up to 20 min, min up to 5 h, then h."""
    if t_end <= 1200.0:
        return 1.0, "s"
    if t_end <= 5 * 3600.0:
        return 1.0 / 60.0, "min"
    return 1.0 / 3600.0, "h"


ANGLE_UNITS = {"deg": (DEG, "°", "deg"), "arcmin": (DEG * 60.0, "′", "arcmin"),
               "arcsec": (DEG * 3600.0, "″", "arcsec"), "mrad": (1e3, " mrad", "mrad"),
               "urad": (1e6, " µrad", "µrad"), "rad": (1.0, " rad", "rad")}


def angle_unit(*arrays, unit="auto"):
    """(factor from rad, suffix for numbers, axis label): degrees, or arcmin / arcsec for small angles."""
    if unit == "auto":
        m = _maxabs(*arrays)
        unit = "deg" if m * DEG >= 1.0 or m == 0.0 else ("arcmin" if m * DEG * 60.0 >= 1.0 else "arcsec")
    return ANGLE_UNITS[unit]


def fmt_angle(x_rad, unit):
    f, suffix, _ = unit
    return "%s%s" % (num(x_rad * f), suffix)


_PREFIX = [(1e9, "G"), (1e6, "M"), (1e3, "k"), (1.0, ""), (1e-3, "m"), (1e-6, "µ"), (1e-9, "n")]


def si_unit(unit, *arrays, maxabs=None):
    """(factor, label) putting the largest magnitude between 1 and 1000 of a prefixed SI unit ("N m" -> "kN m")."""
    m = _maxabs(*arrays) if maxabs is None else maxabs
    if m == 0.0 or not math.isfinite(m):
        return 1.0, unit
    for scale, p in _PREFIX:
        if m >= scale * 0.999:
            return 1.0 / scale, p + unit
    return 1e9, "n" + unit


def _maxabs(*arrays):
    m = 0.0
    for a in arrays:
        if a is None:
            continue
        a = np.asarray(a, dtype=float)
        if a.size and np.isfinite(a).any():
            m = max(m, float(np.nanmax(np.abs(a))))
    return m


def num(x, digits=3):
    """A number with `digits` significant digits, without a trailing '.0' or '-0'."""
    if x is None or not math.isfinite(x):
        return "n/a"
    if x == 0:
        return "0"
    a = abs(x)
    if 1e-3 <= a < 1e5:
        decimals = max(0, digits - 1 - int(math.floor(math.log10(a))))
        s = "%.*f" % (decimals, x)
        if "." in s:
            s = s.rstrip("0").rstrip(".")
        return "0" if s in ("-0", "") else s.replace("-", "−")
    s = "%.*e" % (digits - 1, x)
    mant, exp = s.split("e")
    if "." in mant:
        mant = mant.rstrip("0").rstrip(".")
    return ("%se%d" % (mant, int(exp))).replace("-", "−")


def pct(x, digits=3):
    return "%s %%" % num(100.0 * x, digits) if x is not None and math.isfinite(x) else "n/a"


# ----------------------------------------------------------------------------------------------- layout

class Row:
    """One row of the figure: the whole-run axis `whole` and the zoom axis `zoom` (None without zoom)."""

    def __init__(self, whole, zoom):
        self.whole, self.zoom = whole, zoom

    @property
    def axes(self):
        return [a for a in (self.whole, self.zoom) if a is not None]


def fixed_margins(height_in, nrows, ncols, right_in=0.15, left_in=0.95, top_in=0.62, bottom_in=0.5,
                  row_gap_in=0.14, col_gap_in=0.8):
    """Gridspec margins and gaps from fixed sizes in inches (a constrained layout would cost a second draw:
    ~40 % of the render time). The left margin holds two-line axis labels and 6-character tick labels; the
    gap between the columns the zoom's tick labels (and a zoom axis label); the top the title and a row title."""
    w, h = WIDTH_IN, height_in
    axes_h = h - top_in - bottom_in - row_gap_in * (nrows - 1)
    axes_w = w - left_in - right_in - col_gap_in * (ncols - 1)
    return dict(left=left_in / w, right=1 - right_in / w, top=1 - top_in / h, bottom=bottom_in / h,
                hspace=row_gap_in / (axes_h / nrows), wspace=col_gap_in / (axes_w / ncols) if ncols > 1 else 0.0)


class Layout:
    """Rows of axes sharing the time axis; with `zoom=(t0, t1)` (s) each row marked zoomed gets a second
    axis on the right showing only that window, the window shaded on the whole-run axis.

    rows: list of (key, height, zoomed). The status strip (if any bit is set) is added below by status_strip.
    """

    def __init__(self, run, rows, zoom=None, zoom_label="zoom", status_lanes=0, width_ratios=(2.3, 1.0),
                 row_height=2.0, sharey_zoom=False, right_in=0.15):
        self.run = run
        self.zoom = zoom if zoom is not None and zoom[1] > zoom[0] else None
        any_zoom = self.zoom is not None and any(z for _, _, z in rows)
        heights = [h for _, h, _ in rows]
        if status_lanes:
            heights.append(0.2 + 0.16 * status_lanes)
        total = sum(heights) * row_height + 1.1
        height_in = min(max(total, 4.0), 15.0)
        self.fig = plt.figure(figsize=(WIDTH_IN, height_in), dpi=DPI)
        ncol = 2 if any_zoom else 1
        self.margins = fixed_margins(height_in, len(heights), ncol, right_in)
        self.gs = gs = self.fig.add_gridspec(len(heights), ncol, height_ratios=heights,
                                             width_ratios=list(width_ratios) if ncol == 2 else None, **self.margins)
        self.banners = []
        self.rows = {}
        self.zoom_label = zoom_label
        first_whole = first_zoom = None
        tf, tl = run.time
        for i, (key, _, zoomed) in enumerate(rows):
            w = self.fig.add_subplot(gs[i, 0], sharex=first_whole)
            first_whole = first_whole or w
            z = None
            if any_zoom and zoomed:
                z = self.fig.add_subplot(gs[i, 1], sharex=first_zoom, sharey=w if sharey_zoom else None)
                first_zoom = first_zoom or z
            self.rows[key] = Row(w, z)
        self.status_row = None
        if status_lanes:
            w = self.fig.add_subplot(gs[len(rows), 0], sharex=first_whole)
            z = self.fig.add_subplot(gs[len(rows), 1], sharex=first_zoom) if any_zoom and first_zoom else None
            self.status_row = Row(w, z)
        self.first_whole, self.first_zoom = first_whole, first_zoom
        self.top = first_whole  # the first row's whole-run axis: warnings and the variant line go there
        self.top_row = self.rows[rows[0][0]]
        for r in self.all_rows():
            for ax in r.axes:
                ax.grid(True, alpha=0.3)
                ax.tick_params(labelsize=8)
        first_whole.set_xlim(0.0, run.t_end * tf)
        if first_zoom is not None:
            first_zoom.set_xlim(self.zoom[0] * tf, self.zoom[1] * tf)
        self._bottom_labels()

    def __getitem__(self, key):
        return self.rows[key]

    def all_rows(self):
        rows = list(self.rows.values())
        if self.status_row is not None:
            rows.append(self.status_row)
        return rows

    def _bottom_labels(self):
        """Time tick labels and the time label on the lowest visible axis of each column only."""
        tl = self.run.time[1]
        wholes = [r.whole for r in self.all_rows() if r.whole.get_visible()]
        zooms = [r.zoom for r in self.all_rows() if r.zoom is not None and r.zoom.get_visible()]
        for group in (wholes, zooms):
            for ax in group[:-1]:
                ax.tick_params(labelbottom=False)
                ax.set_xlabel("")
            if group:
                group[-1].tick_params(labelbottom=True)
                group[-1].set_xlabel("time [%s]" % tl, fontsize=9)

    def banner(self, text):
        """A red warning line under the title (the run did something no reader may miss); finish() makes room."""
        self.banners.append(text)

    def finish(self):
        """Place the banners, shade the zoom window on the whole-run axes and title the zoom column."""
        if self.banners:
            h = self.fig.get_figheight()
            lines = sum(b.count("\n") + 1 for b in self.banners)
            self.fig.text(0.01, 1 - 0.36 / h, "\n".join(self.banners), ha="left", va="top", fontsize=9.5,
                          color="darkred", fontweight="bold", linespacing=1.25)
            top = self.margins["top"] - 0.2 * lines / h
            hspace = self.margins["hspace"] * (self.margins["top"] - self.margins["bottom"]) / (top - self.margins["bottom"])
            self.gs.update(top=top, hspace=hspace)
        if self.zoom is None or self.first_zoom is None:
            return self.fig
        tf = self.run.time[0]
        for r in self.rows.values():
            if r.zoom is not None:
                r.whole.axvspan(self.zoom[0] * tf, self.zoom[1] * tf, color="gold", alpha=0.18, lw=0, zorder=0)
        top = next(r for r in self.rows.values() if r.zoom is not None)
        top.zoom.set_title("%s: %s–%s %s" % (self.zoom_label, num(self.zoom[0] * tf), num(self.zoom[1] * tf),
                                             self.run.time[1]), fontsize=9, loc="left")
        return self.fig


def plot_t(ax, run, y, zoom=None, max_points=4000, **kw):
    """Plot column y against time on ax: the whole run decimated to an envelope, or (zoom=(t0, t1)) every
    sample in the window, unchanged."""
    tf = run.time[0]
    if zoom is not None:
        m = run.window(zoom[0] - run.dt, zoom[1] + run.dt)
        return ax.plot(run.t[m] * tf, y[m], **kw)
    t, v = envelope(run.t, y, max_points)
    return ax.plot(t * tf, v, **kw)


def plot_pair(row, run, y, zoom, **kw):
    """The same line on the whole-run axis and (if the row has one) the zoom axis; returns the whole's line."""
    line = plot_t(row.whole, run, y, **kw)
    if row.zoom is not None:
        kw.pop("label", None)
        plot_t(row.zoom, run, y, zoom=zoom, **kw)
    return line


def envelope(t, y, max_points=4000):
    """Min/max decimation: for more than max_points samples, each bin keeps its minimum and maximum in time
    order, so peaks survive (for the whole-run view only)."""
    n = t.size
    if n <= max_points or np.isnan(y).any():
        return t, y
    bins = max_points // 2
    per = n // bins
    m = bins * per
    tb = t[:m].reshape(bins, per)
    yb = y[:m].reshape(bins, per)
    imin = yb.argmin(axis=1)
    imax = yb.argmax(axis=1)
    first = np.minimum(imin, imax)
    second = np.maximum(imin, imax)
    rows = np.arange(bins)
    tt = np.column_stack([tb[rows, first], tb[rows, second]]).ravel()
    yy = np.column_stack([yb[rows, first], yb[rows, second]]).ravel()
    if m < n:
        tt = np.concatenate([tt, t[m:]])
        yy = np.concatenate([yy, y[m:]])
    return tt, yy


# ---------------------------------------------------------------------------------------------- annotate

def limit_lines(ax, value, label, scale=1.0, data_maxabs=None, symmetric=True, color=C_HARD, ls="--",
                max_ratio=4.0, lw=1.1, unit="", below=False, base_unit=None):
    """Lines at +-value (value in SI, times scale for the axis) labelled at the right end. If the data's peak
    is less than 1/max_ratio of the limit the lines would flatten the data: a note states the limit (in the
    prefixed base_unit that suits it, if given) and the peak's share of it instead. Returns True if lines were
    drawn. value None: nothing (limit not reported)."""
    if value is None:
        return False
    v = value * scale
    if data_maxabs is not None and data_maxabs * scale * max_ratio < v:
        share = data_maxabs / value if value > 0 else float("nan")
        shown, shown_unit = v, unit
        if base_unit:
            f, u = si_unit(base_unit, maxabs=value)
            shown, shown_unit = value * f, " " + u
        text = "%s %s%s%s off scale (peak %s of it)" % (label, "±" if symmetric else "", num(shown), shown_unit,
                                                      pct(share, 2))
        prev = getattr(ax, "_pl_offscale", None)
        if prev is None:
            ax._pl_offscale = note(ax, text, loc="lower right", size=7.5, color=color)
        else:
            prev.set_text(prev.get_text() + "\n" + text)
        return False
    ax.set_ymargin(max(ax.margins()[1], 0.1))  # room for the label above the upper line
    trans = mtransforms.blended_transform_factory(ax.transAxes, ax.transData)
    for s in ((1, -1) if symmetric else (1,)):
        ax.axhline(s * v, color=color, ls=ls, lw=lw, zorder=3)
    ax.text(0.995, v, "%s %s%s%s" % (label, "±" if symmetric else "", num(v), unit), transform=trans, ha="right",
            va="top" if below else "bottom", fontsize=7.5, color=color, zorder=6, clip_on=True,
            bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.7))
    return True


def hline(ax, value, label, color=C_BOOK, ls=":", lw=1.2, va="bottom", x=0.995, ha="right", near=None):
    """A labelled horizontal reference line (e.g. the book's steady value). With near=array, only if value
    lies within the array's range widened by half of it (a zoom axis keeps its own scale)."""
    if value is None or not math.isfinite(value):
        return
    if near is not None and np.isfinite(near).any():
        lo, hi = float(np.nanmin(near)), float(np.nanmax(near))
        pad = 0.5 * max(hi - lo, 1e-300)
        if not lo - pad <= value <= hi + pad:
            return
    ax.axhline(value, color=color, ls=ls, lw=lw, zorder=3)
    trans = mtransforms.blended_transform_factory(ax.transAxes, ax.transData)
    ax.text(x, value, label, transform=trans, ha=ha, va=va, fontsize=7.5, color=color, zorder=6, clip_on=True,
            bbox=dict(boxstyle="square,pad=0.1", fc="white", ec="none", alpha=0.7))


def vline(ax, x, label=None, color="0.35", ls=":", lw=1.0, y=0.98, rotation=90, size=7, ha="right", va="top"):
    ax.axvline(x, color=color, ls=ls, lw=lw, zorder=2)
    if label:
        trans = mtransforms.blended_transform_factory(ax.transData, ax.transAxes)
        ax.text(x, y, " " + label, transform=trans, rotation=rotation, ha=ha, va=va, fontsize=size,
                color=color, zorder=6, clip_on=True)


_LOC = {"upper left": (0.008, 0.97, "left", "top"), "upper right": (0.992, 0.97, "right", "top"),
        "lower left": (0.008, 0.03, "left", "bottom"), "lower right": (0.992, 0.03, "right", "bottom"),
        "upper center": (0.5, 0.97, "center", "top"), "lower center": (0.5, 0.03, "center", "bottom")}


def note(ax, text, loc="upper left", size=8, color="black", bold=False, alpha=0.85):
    """A boxed text in a corner of ax (axes coordinates)."""
    x, y, ha, va = _LOC[loc]
    return ax.text(x, y, text, transform=ax.transAxes, ha=ha, va=va, fontsize=size, color=color, zorder=10,
                   fontweight="bold" if bold else "normal", linespacing=1.3,
                   bbox=dict(boxstyle="round,pad=0.3", fc="white", ec="0.7", alpha=alpha))


def free_corner(ax, run, arrays, candidates=("upper left", "lower right", "lower left", "upper right")):
    """The corner of ax (among candidates, in order of preference) where the fewest samples of arrays (in the
    axis' units, against run.t) fall: a box there hides the least data. Call after the y limits are final."""
    lo, hi = ax.get_ylim()
    x0, x1 = (v / run.time[0] for v in ax.get_xlim())
    span_y, span_x = (hi - lo) or 1.0, (x1 - x0) or 1.0
    best, score = candidates[0], None
    for loc in candidates:
        top, left = loc.startswith("upper"), loc.endswith("left")
        n = 0
        for y in arrays:
            if y is None:
                continue
            fx = (run.t - x0) / span_x
            fy = (y - lo) / span_y
            inx = fx <= 0.45 if left else fx >= 0.55
            iny = fy >= 0.7 if top else fy <= 0.3
            n += int(np.count_nonzero(inx & iny))
        if score is None or n < score:
            best, score = loc, n
    return best


def warn(ax, text, loc="upper center"):
    """A red warning box (the run did something the figure must not let the reader miss)."""
    return note(ax, text, loc=loc, size=9, color="darkred", bold=True, alpha=0.92)


def mark_peak(ax, run, y, scale, label_fmt, zoom=None, color="black"):
    """Mark the largest |y| (in the whole run, or in zoom) with a dot and a label."""
    m = run.window(*zoom) if zoom else np.ones(run.t.size, bool)
    if not m.any():
        return
    idx = np.flatnonzero(m)
    i = idx[np.nanargmax(np.abs(y[m]))]
    tf = run.time[0]
    ax.plot([run.t[i] * tf], [y[i] * scale], "o", ms=4, color=color, zorder=7)
    ax.annotate(label_fmt, (run.t[i] * tf, y[i] * scale), xytext=(4, 4 if y[i] >= 0 else -10),
                textcoords="offset points", fontsize=7.5, color=color, zorder=7)


def shade_span(ax, run, t0, t1, color="0.85", alpha=0.5, label=None, y=0.04):
    tf = run.time[0]
    ax.axvspan(t0 * tf, t1 * tf, color=color, alpha=alpha, lw=0, zorder=0)
    if label:
        trans = mtransforms.blended_transform_factory(ax.transData, ax.transAxes)
        ax.text(0.5 * (t0 + t1) * tf, y, label, transform=trans, ha="center", va="bottom", fontsize=7,
                color="0.3", zorder=6)


def ylabel(ax, text):
    ax.set_ylabel(text, fontsize=9)


def legend(ax, loc="upper right", ncol=1, size=7.5):
    h, labels = ax.get_legend_handles_labels()
    if h:
        ax.legend(loc=loc, fontsize=size, ncol=ncol, framealpha=0.85, handlelength=1.8)


def symmetric_ylim(ax, margin=1.08):
    lo, hi = ax.get_ylim()
    m = max(abs(lo), abs(hi)) * margin
    ax.set_ylim(-m, m)


# ----------------------------------------------------------------------------------------- status bits

# ActuatorFrame::status: firmware/msg/fault_bits.hpp (0-15), firmware/control/power_stabilizer_loops.hpp
# (16-20) and firmware/control/law_status_bits.hpp (21-30).
STATUS_BITS = {
    0: "sensor frame missing", 1: "sensor frame stale", 2: "sensor non-finite", 3: "sensor out of range",
    4: "sensor-reported fault", 8: "holding last good frame", 9: "SAFE STATE (drives off, brake on)",
    10: "awaiting first good frame",
    16: "M1 torque saturated", 17: "M2 torque saturated", 18: "voltage saturated", 19: "gains refused",
    20: "non-finite sensor (zero command)",
    21: "axis-2 torque saturated", 22: "beyond soft limit", 23: "end-stop braking", 24: "rate loop saturated",
    25: "gimbal-lock guard", 26: "config refused", 27: "non-finite command", 28: "drive voltage saturated",
    29: "correction cut out", 30: "torquer limited",
}


def active_bits(bits):
    """The bit numbers set at least once."""
    if bits is None:
        return []
    acc = int(np.bitwise_or.reduce(bits))
    return [b for b in range(32) if acc >> b & 1]


def status_summary(run, bits, names=None):
    """One line per active bit: its name and the share of the run it was set."""
    names = {**STATUS_BITS, **(names or {})}
    out = []
    for b in active_bits(bits):
        on = (bits >> b & 1).astype(bool)
        out.append("%s: %s of samples" % (names.get(b, "bit %d" % b), pct(on.mean(), 2)))
    return out


def status_strip(layout, run, bits, names=None, zoom=None):
    """Event lanes (one per bit that is ever set) on layout.status_row: a bar where the bit is set. Returns the
    bits that persist through the whole run (worth a warning on the main axes)."""
    row = layout.status_row
    if row is None or bits is None:
        return []
    names = {**STATUS_BITS, **(names or {})}
    lanes = active_bits(bits)
    tf = run.time[0]
    dt = run.dt
    always = []
    for ax, win in ((row.whole, None), (row.zoom, zoom)):
        if ax is None:
            continue
        if win is not None and not (bits[run.window(*win)] != 0).any():
            ax.set_visible(False)  # nothing set in the zoom window: no empty lanes
            layout._bottom_labels()
            continue
        min_w = (run.t_end if win is None else (win[1] - win[0])) * 0.002
        for k, b in enumerate(lanes):
            on = (bits >> b & 1).astype(np.int8)
            if win is None and on.all():
                always.append(b)
            edges = np.diff(np.concatenate([[0], on, [0]]))
            starts = np.flatnonzero(edges == 1)
            ends = np.flatnonzero(edges == -1)
            t0 = run.t[starts] - dt  # the sample at t covers (t - dt, t]
            t1 = run.t[ends - 1]
            spans = [(a * tf, max(bb - a, min_w) * tf) for a, bb in zip(t0, t1)]
            ax.broken_barh(spans, (k - 0.35, 0.7), color=_lane_color(b), lw=0)
        ax.set_ylim(len(lanes) - 0.45, -0.55)
        ax.set_yticks([])
        ax.grid(False)
        if win is None:
            for k, b in enumerate(lanes):
                share = (bits >> b & 1).mean()
                ax.text(0.003, k, "%s (%s)" % (names.get(b, "bit %d" % b), pct(share, 2)), transform=
                        mtransforms.blended_transform_factory(ax.transAxes, ax.transData), ha="left",
                        va="center", fontsize=7, zorder=6,
                        bbox=dict(boxstyle="square,pad=0.15", fc="white", ec="none", alpha=0.8))
    ylabel(row.whole, "status")
    return always


def status_banner(layout, always, names=None):
    """A banner for the status bits held through the whole run (status_strip's return): the safe state said
    in words (the drives are off, the loop is open), else the bits' names."""
    if not always:
        return
    names = {**STATUS_BITS, **(names or {})}
    others = [names.get(b, "bit %d" % b) for b in always if b != 9]
    if 9 in always:
        layout.banner("controller in the SAFE STATE for the whole run%s: drives off, the loop is open"
                      % (" (" + ", ".join(others) + ")" if others else ""))
    else:
        layout.banner("set for the whole run: " + ", ".join(others))


def _lane_color(b):
    if b in (9, 19, 26, 27, 20, 0, 1, 2, 3, 4):
        return C_HARD
    if b in (8, 10):
        return "tab:brown"
    return C_SOFT


# ------------------------------------------------------------------------------------------ title, save

def title(fig, run, what, subtitle=None, ax=None):
    """Title: scene name, what the device is, seed and duration; the variant (subtitle) in small print over
    the first axis ax (or at the top right of the figure without ax)."""
    parts = [run.name, what]
    if run.seed is not None:
        parts.append("seed %s" % run.seed)
    tf, tl = run.time
    parts.append("%s %s" % (num(run.duration * tf), tl))
    fig.suptitle("  ·  ".join(parts), fontsize=12, fontweight="bold", x=0.01, ha="left", va="top",
                 y=1 - 0.08 / fig.get_figheight())
    if subtitle and ax is not None:
        ax.set_title(subtitle, fontsize=8, loc="left", color="0.3")
    elif subtitle:
        fig.text(0.99, 0.995, subtitle, ha="right", va="top", fontsize=8, color="0.3")


def limits_missing_note(fig, run, keys):
    """Say (small, top right) which limits the figure would draw but report.json does not have."""
    missing = [k for k in keys if run.limit(k) is None]
    if missing:
        fig.text(0.995, 0.998, "not in report.json \"limits\", no line: " + ", ".join(missing), fontsize=6.5,
                 color="0.45", ha="right", va="top")


def save(fig, run, name="signals.png"):
    path = os.path.join(run.dir, name)
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    return path


# --------------------------------------------------------------------------------------- generic figure

_UNITS = [("_rad_s", "rad/s"), ("_m_s", "m/s"), ("_rad", "rad"), ("_Nm", "N m"), ("_A", "A"), ("_V", "V"),
          ("_deg", "deg"), ("_bits", "bits"), ("_m", "m")]


def generic_figure(run, why=None):
    """Every column against time, one panel per unit suffix (the figure for a device without a plot module).
    Columns that are identically zero are listed, not drawn."""
    groups, zeros = {}, []
    for name, v in run.cols.items():
        if not np.nanmax(np.abs(v)) > 0:
            zeros.append(name)
            continue
        unit = next((label for suffix, label in _UNITS if name.endswith(suffix)), "")
        groups.setdefault(unit, []).append(name)
    if not groups:
        groups[""] = []
    height_in = min(max(2.4 * len(groups) + 1.0, 4.0), 15.0)
    fig, axes = plt.subplots(len(groups), 1, figsize=(WIDTH_IN, height_in), sharex=True, squeeze=False, dpi=DPI,
                             gridspec_kw=fixed_margins(height_in, len(groups), 1))
    tf, tl = run.time
    for ax, (unit, names) in zip(axes[:, 0], groups.items()):
        for n in names:
            t, v = envelope(run.t, run.cols[n])
            ax.plot(t * tf, v, label=n, linewidth=0.8)
        ax.set_ylabel(unit, fontsize=9)
        ax.grid(True, alpha=0.3)
        ax.tick_params(labelsize=8)
        legend(ax)
    axes[-1, 0].set_xlim(0.0, run.t_end * tf)
    axes[-1, 0].set_xlabel("time [%s]" % tl, fontsize=9)
    if zeros:
        note(axes[-1, 0], "identically zero: " + ", ".join(zeros), loc="lower left", size=7)
    title(fig, run, run.device or "device unknown", why, axes[0, 0])
    return fig
