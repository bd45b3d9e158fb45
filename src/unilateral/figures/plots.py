"""The house style of the figures, the Agg figure factory and atomic saving.

The figures are built on :class:`matplotlib.figure.Figure` with an Agg canvas, without pyplot:
no backend is switched, no window opens and nothing is registered globally. The house style
(font sizes for print, TrueType fonts in PDF, path simplification) applies only while a figure is
built or saved. Widths suit a journal page (6.3 in, about 16 cm).

Drawing is kept fast for long runs (10^5 steps and more):

* the axes are placed with fixed margins in inches (:func:`_figure`), not by constrained or tight
  layout, which measure every text twice per save;
* a line never gets more than about :data:`MAX_POINTS` points: :func:`envelope` keeps, in each of
  ``MAX_POINTS / 2`` time buckets, the samples where the curve is lowest and highest, so peaks and
  the envelope of oscillations drawn at the figure's resolution are kept exactly;
* the figure's dpi is the saving dpi, so text extents are measured once.
"""

from __future__ import annotations

import functools
import os
import sys
from pathlib import Path

import matplotlib as mpl
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..io.atomic import atomic_write

PAGE_WIDTH = 6.3            # inches
DPI = 150
MAX_POINTS = 2000
"""Most points drawn per line (2 per time bucket: the bucket's minimum and maximum)."""

_STYLE = {
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8, "ytick.labelsize": 8,
    "legend.fontsize": 8, "figure.titlesize": 10, "lines.linewidth": 1.2, "axes.linewidth": 0.6,
    "axes.grid": True, "grid.linewidth": 0.4, "grid.alpha": 0.6, "axes.formatter.use_mathtext": False,
    "legend.framealpha": 0.9, "pdf.fonttype": 42, "ps.fonttype": 42,
    "path.simplify": True, "path.simplify_threshold": 0.2, "agg.path.chunksize": 20000,
}


#: Options of ``savefig`` by format: a PNG compressed at zlib level 3, not 6 (the same pixels, a third
#: less time to encode, 3 % larger).
_SAVE = {"png": {"pil_kwargs": {"compress_level": 3}}}


def math_unit(unit: str) -> str:
    """A unit in mathtext: ``"m"`` -> ``$\\mathrm{m}$``, ``"m/s^2"`` -> ``$\\mathrm{m/s^{2}}$``, ``"kN m"``
    -> ``$\\mathrm{kN\\,m}$``. A unit of other characters than letters, digits, spaces and ``/^().*-``
    (read from a file) is returned as plain text, its ``$`` escaped."""
    import re

    text = str(unit)
    if not re.fullmatch(r"[A-Za-z0-9/^ ().*-]+", text):
        return text.replace("$", r"\$")
    body = re.sub(r"\^\(?(-?\d+)\)?", r"^{\1}", text).replace(" ", r"\,")
    return f"$\\mathrm{{{body}}}$"


def plain_text(text) -> str:
    """``text`` as matplotlib draws it without failing: as given if its ``$...$`` parts are valid
    mathtext (or it has none), else with every ``$`` escaped (drawn literally). A title or label
    read from a file (``title = "$\\frac{$"``) made the drawing raise, after the run was solved."""
    import re

    text = str(text)
    if len(re.findall(r"(?<!\\)\$", text)) < 2:
        return text
    from matplotlib.mathtext import MathTextParser

    try:
        MathTextParser("path").parse(text)
    except (ValueError, RuntimeError, IndexError, KeyError, TypeError):
        return re.sub(r"(?<!\\)\$", r"\\$", text)
    return text


def _styled(function):
    """Run ``function`` under the house style, restoring the caller's rcParams afterwards."""
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        with mpl.rc_context(_STYLE):
            return function(*args, **kwargs)
    return wrapper


@_styled
def save_figure(fig: Figure, path_without_suffix: str | os.PathLike, formats=("png", "pdf"), *,
                dpi: int = DPI) -> list[Path]:
    """Write ``fig`` once per format, each file atomically, then close the figure.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    path_without_suffix : str or path-like
        ``"out/fig2"`` gives ``out/fig2.png`` and ``out/fig2.pdf``.
    formats : sequence of str
        matplotlib output formats.
    dpi : int
        Resolution of raster formats.

    Returns
    -------
    list of pathlib.Path
        The files written. On an error the figure stays open (nothing partial is left behind).
    """
    base = os.fspath(path_without_suffix)
    paths = [atomic_write(f"{base}.{fmt}", functools.partial(fig.savefig, format=fmt, dpi=dpi, **_SAVE.get(fmt, {})))
             for fmt in formats]
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:          # only pyplot keeps figures; ours are not registered there
        pyplot.close(fig)
    return paths


def _figure(size, *, margins=(0.8, 0.2, 0.5, 0.35), gaps=(0.8, 0.35), **subplots):
    """A Figure on an Agg canvas with fixed margins, and its subplots.

    Parameters
    ----------
    size : (width, height)
        Figure size, inches.
    margins : (left, right, bottom, top)
        Space around the grid of axes, inches: room for tick labels and axis labels (left,
        bottom), a right-hand twin axis (right) and a title (top).
    gaps : (horizontal, vertical)
        Space between neighbouring axes, inches.
    **subplots
        Passed to :meth:`matplotlib.figure.Figure.subplots` (``nrows``, ``ncols``, ``sharex``,
        ``squeeze``, ``height_ratios``, ...).

    Returns
    -------
    fig : matplotlib.figure.Figure
    axes : Axes or array of Axes
    """
    width, height = size
    left, right, bottom, top = margins
    nrows, ncols = subplots.get("nrows", 1), subplots.get("ncols", 1)
    grid_w = max(width - left - right, 0.1 * width)
    grid_h = max(height - bottom - top, 0.1 * height)
    axes_w = max(grid_w - (ncols - 1) * gaps[0], 0.1) / ncols
    axes_h = max(grid_h - (nrows - 1) * gaps[1], 0.1) / nrows
    fig = Figure(figsize=size, dpi=DPI)
    FigureCanvasAgg(fig)
    fig.subplots_adjust(left=left / width, right=1.0 - right / width, bottom=bottom / height,
                        top=1.0 - top / height, wspace=gaps[0] / axes_w, hspace=gaps[1] / axes_h)
    return fig, fig.subplots(**subplots)


def envelope(x, *ys, max_points: int = MAX_POINTS):
    """Samples of a curve to draw: every sample, or per bucket the extreme ones.

    With ``n = len(x) <= max_points`` the inputs are returned as they are. Otherwise the samples
    are cut into ``max_points // (2 * len(ys))`` buckets of consecutive samples and, in each
    bucket, the samples where each ``y`` is lowest and highest are kept (with the first and the
    last sample), in their order. The global extremes of every ``y`` are therefore kept exactly,
    and the drawn line covers the same band as the full one at the figure's resolution.

    Parameters
    ----------
    x : (n,) array
        Abscissae (times; or the first coordinate of a parametric curve, then also pass it in ``ys``).
    *ys : (n,) arrays
        Ordinates sharing ``x``; the extremes of each are kept.
    max_points : int
        Most samples returned (>= 4 per series).

    Returns
    -------
    tuple of arrays
        ``(x_kept, *ys_kept)``, each ``(k,)`` with ``k <= max_points + 2``.
    """
    x = np.asarray(x)
    ys = tuple(np.asarray(y) for y in ys)
    n = len(x)
    per_bucket = 2 * max(len(ys), 1)
    if n <= max_points or max_points < 2 * per_bucket:
        return (x, *ys)
    buckets = max_points // per_bucket
    size = -(-n // buckets)
    keep = [np.array([0, n - 1])]
    offsets = np.arange(buckets) * size
    for y in ys:
        padded = np.concatenate([y, np.full(buckets * size - n, y[-1])]).reshape(buckets, size)
        finite = np.where(np.isnan(padded), 0.0, padded)
        keep += [offsets + np.argmin(finite, axis=1), offsets + np.argmax(finite, axis=1)]
    index = np.unique(np.minimum(np.concatenate(keep), n - 1))
    return (x[index], *(y[index] for y in ys))
