"""Publication figures of unilateral analyses (matplotlib, Agg canvas).

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
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter

from ..io.atomic import atomic_write
from ..result import Solution

PAGE_WIDTH = 6.3            # inches
MAX_PANELS = 6
DPI = 150

_STYLE = {
    "font.size": 9, "axes.titlesize": 9, "axes.labelsize": 9, "xtick.labelsize": 8, "ytick.labelsize": 8,
    "legend.fontsize": 8, "figure.titlesize": 10, "lines.linewidth": 1.2, "axes.linewidth": 0.6,
    "axes.grid": True, "grid.linewidth": 0.4, "grid.alpha": 0.6, "axes.formatter.use_mathtext": False,
    "legend.framealpha": 0.9, "pdf.fonttype": 42, "ps.fonttype": 42,
}
_LINESTYLES = ("-", "--", "-.", ":")
_V_COLOR, _PSI_COLOR = "C0", "C3"


def _styled(function):
    """Run ``function`` under the house style, restoring the caller's rcParams afterwards."""
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        with mpl.rc_context(_STYLE):
            return function(*args, **kwargs)
    return wrapper


@_styled
def plot_displacement(solutions: dict[str, tuple[np.ndarray, np.ndarray]], *, ylabel: str,
                      title: str | None = None, static: float | None = None,
                      units: dict | None = None) -> Figure:
    """Displacement histories of several analyses on one axes (the paper's Fig. 2).

    Parameters
    ----------
    solutions : dict of str to (t, y)
        Curve label to times and values, e.g. ``{"with uplift": (sol.t, y3), "without uplift":
        (bil.t, y3b)}``. Curves differ in colour and line style (readable in greyscale).
    ylabel : str
        The quantity with its unit, e.g. ``"vertical displacement of node 3 [mm]"``.
    title : str, optional
    static : float, optional
        Draw a thin horizontal line at this (static) value.
    units : dict, optional
        ``units["time"]`` labels the time axis.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = _figure((PAGE_WIDTH, 3.0))
    for k, (label, (t, y)) in enumerate(solutions.items()):
        ax.plot(t, y, _LINESTYLES[k % len(_LINESTYLES)], color=f"C{k}", label=label)
    if static is not None:
        ax.axhline(static, color="0.4", linewidth=0.6, linestyle=":", label="static value")
    ax.margins(x=0)
    ax.set(xlabel=_label("time $t$", units, "time"), ylabel=ylabel)
    if title:
        ax.set_title(title)
    ax.legend(loc="best")
    return fig


@_styled
def plot_constraints(sol: Solution, *, units: dict | None = None, max_panels: int = MAX_PANELS) -> Figure:
    """Uplift ``v`` and reaction ``psi`` of each constraint against time, one panel each.

    The deformation (left axis) and the reaction (right axis) share a zero line in the middle
    of each panel: uplift rises above it, compression hangs below it. With more than
    ``max_panels`` constraints, those with the largest peak uplift are shown and the title says so.

    Parameters
    ----------
    sol : Solution
    units : dict, optional
        ``{"length": ..., "force": ..., "time": ...}`` for the axis labels.
    max_panels : int

    Returns
    -------
    matplotlib.figure.Figure
        ``2 k`` axes for ``k`` panels: the panels' ``v`` axes top to bottom, then their ``psi``
        twins in the same order.
    """
    v, psi = np.asarray(sol.v), np.asarray(sol.psi)
    m = v.shape[1]
    shown = np.arange(m)
    if m > max_panels:              # the largest peak uplifts, in the model's order
        shown = np.sort(np.argsort(-v.max(axis=0), kind="stable")[:max_panels])
    fig, axes = _figure((PAGE_WIDTH, 0.6 + 1.45 * len(shown)), nrows=len(shown), sharex=True, squeeze=False)
    for ax, i in zip(axes[:, 0], shown):
        ax.plot(sol.t, v[:, i], color=_V_COLOR)
        twin = ax.twinx()
        twin.plot(sol.t, psi[:, i], color=_PSI_COLOR, linestyle="--")
        twin.grid(False)
        _symmetric(ax, v[:, i])
        _symmetric(twin, psi[:, i])
        ax.axhline(0.0, color="0.3", linewidth=0.5)
        ax.margins(x=0)
        ax.set_title(sol.constraint_names[i], loc="left")
        ax.set_ylabel(_scaled(ax.yaxis, v[:, i], "opening $v$", units, "length"), color=_V_COLOR)
        twin.set_ylabel(_scaled(twin.yaxis, psi[:, i], r"reaction $\psi$", units, "force"), color=_PSI_COLOR)
        ax.tick_params(axis="y", colors=_V_COLOR)
        twin.tick_params(axis="y", colors=_PSI_COLOR)
    axes[-1, 0].set_xlabel(_label("time $t$", units, "time"))
    fig.suptitle(f"{len(shown)} of {m} constraints, those with the largest peak opening" if m > max_panels
                 else "Unilateral constraints: opening (uplift, gap, slack) and reaction")
    return fig


@_styled
def plot_force_deformation(deformation: dict[str, np.ndarray], force: dict[str, np.ndarray], *,
                           units: dict | None = None, title: str | None = None) -> Figure:
    """Force-deformation path of each unilateral element, one panel each (three per row).

    Parameters
    ----------
    deformation, force : dict of str to (N+1,) arrays
        Element name to its deformation and force histories; the same names in both.
    units : dict, optional
        ``{"length": ..., "force": ...}`` for the axis labels.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure
        One axes per element with one line (a dot marks the start of the path).
    """
    if deformation.keys() != force.keys():
        raise ValueError(f"deformation and force must name the same elements, got {sorted(deformation)} "
                         f"and {sorted(force)}")
    names = list(deformation)
    ncols = min(3, len(names))
    nrows = -(-len(names) // ncols)
    fig, axes = _figure((min(PAGE_WIDTH, 0.3 + 2.1 * ncols), 0.4 + 2.0 * nrows), nrows=nrows, ncols=ncols,
                        squeeze=False)
    for ax in axes.flat[len(names):]:
        ax.remove()
    for ax, name in zip(axes.flat, names):
        ax.plot(deformation[name], force[name], color="C0", marker="o", markevery=[0], markersize=3)
        ax.set_title(name, loc="left")
        ax.set(xlabel=_scaled(ax.xaxis, deformation[name], "deformation", units, "length"),
               ylabel=_scaled(ax.yaxis, force[name], "force", units, "force"))
    if title:
        fig.suptitle(title)
    return fig


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


def _label(text: str, units: dict | None, quantity: str) -> str:
    unit = (units or {}).get(quantity)
    return f"{text} [{unit}]" if unit else text


def _scaled(axis, values: np.ndarray, text: str, units: dict | None, quantity: str) -> str:
    """Show tiny or huge values in a power of ten; return the label, e.g. ``v [$10^{-3}$ m]``.

    Unlike matplotlib's offset text, the power goes into the label, so it cannot collide with
    labels or titles.
    """
    peak = float(np.max(np.abs(values), initial=0.0))
    if not 0.0 < peak < 1e-2 and peak < 1e4:
        return _label(text, units, quantity)
    power = 3 * int(np.floor(np.log10(peak) / 3))
    axis.set_major_formatter(FuncFormatter(
        lambda x, _: f"{x / 10.0 ** power:g}".replace("-", "\N{MINUS SIGN}")))
    unit = (units or {}).get(quantity)
    return f"{text} [$10^{{{power}}}$ {unit}]" if unit else f"{text} [$10^{{{power}}}$]"


def _symmetric(ax, values: np.ndarray) -> None:
    """Limits symmetric about zero, so twin axes share their zero line."""
    bound = 1.08 * float(np.max(np.abs(values))) or 1.0
    ax.set_ylim(-bound, bound)
