"""The house style of the figures, the Agg figure factory and atomic saving.

The figures are built on :class:`matplotlib.figure.Figure` with an Agg canvas, without pyplot:
no backend is switched, no window opens and nothing is registered globally. The house style
(font sizes for print, constrained layout, TrueType fonts in PDF) applies only while a figure is
built or saved. Widths suit a journal page (6.3 in, about 16 cm).
"""

from __future__ import annotations

import functools
import os
import sys
from pathlib import Path

import matplotlib as mpl
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from ..io.atomic import atomic_write

PAGE_WIDTH = 6.3            # inches
DPI = 150

_STYLE = {
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8, "ytick.labelsize": 8,
    "legend.fontsize": 8, "figure.titlesize": 10, "lines.linewidth": 1.2, "axes.linewidth": 0.6,
    "axes.grid": True, "grid.linewidth": 0.4, "grid.alpha": 0.6, "axes.formatter.use_mathtext": False,
    "legend.framealpha": 0.9, "pdf.fonttype": 42, "ps.fonttype": 42,
}


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
    paths = [atomic_write(f"{base}.{fmt}", functools.partial(fig.savefig, format=fmt, dpi=dpi))
             for fmt in formats]
    pyplot = sys.modules.get("matplotlib.pyplot")
    if pyplot is not None:          # only pyplot keeps figures; ours are not registered there
        pyplot.close(fig)
    return paths


def _figure(size, **subplots):
    """A constrained-layout Figure on an Agg canvas, and its subplots."""
    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig, fig.subplots(**subplots)
