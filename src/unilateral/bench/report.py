"""Benchmark output: the results table and the scaling figure."""

from __future__ import annotations

import math
import os

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ..figures.plots import PAGE_WIDTH, _figure, _styled, save_figure
from .suite import METHODS

COLUMNS = (("problem", 12), ("method", 10), ("N", 7), ("n", 5), ("m", 5), ("us/step", 9),
           ("all us/step", 11), ("total s", 8), ("peak MiB", 9), ("error", 8), ("changes", 7))
"""Table columns and their widths; a notes column follows."""

NOTES_WIDTH = 110
"""Notes longer than this are cut in the table (the JSON keeps them whole)."""

_COLORS = {method: f"C{k}" for k, method in enumerate(METHODS)}
_PLAIN = FuncFormatter(lambda x, _: f"{x:g}")
_N_SLOPES = (("N", lambda N: N, "--"), ("N log$^2$N", lambda N: N * np.log2(N) ** 2, ":"),
             ("N$^2$", lambda N: N**2, "-."))
_M_SLOPES = (("m", lambda m: m, "--"), ("m$^2$", lambda m: m**2, "-."))


def format_table(records) -> str:
    """The records of :func:`~unilateral.bench.suite.run_suite` as a text table.

    ``us/step`` is the ``"steps"`` phase of ``sol.stats["time"]`` (the march) divided by N;
    ``all us/step`` and ``total s`` are the whole solve (bilateral response, weights or poles,
    recovery of u included) per step and in all; ``error`` is the relative maximum error of the key output
    against the reference.
    """
    header = " ".join(f"{name:>{width}}" if k > 1 else f"{name:<{width}}"
                      for k, (name, width) in enumerate(COLUMNS)) + "  notes"
    lines = [header, "-" * len(header)]
    for r in records:
        ok = r.get("status") == "ok"
        cells = [r["problem"], r["method"], r["N"], r["n"], r["m"],
                 _number(1e6 * r["steps_s"] / r["N"], ".4g") if ok else "-",
                 _number(1e6 * r["total_s"] / r["N"], ".4g") if ok else "-",
                 _number(r.get("total_s"), ".4g"), _number(r.get("peak_mib"), ".0f"),
                 _number(r.get("error"), ".2e"), r.get("contact_changes", "-") if ok else "-"]
        row = " ".join(f"{cell!s:>{width}}" if k > 1 else f"{cell!s:<{width}}"
                       for k, (cell, (_, width)) in enumerate(zip(cells, COLUMNS)))
        lines.append(f"{row}  {_notes(r)}")
    return "\n".join(lines)


def _number(value, spec) -> str:
    return "-" if value is None or not math.isfinite(value) else format(value, spec)


def _notes(record) -> str:
    """Skip or failure reason, else the engine, history and LCP space (and retried attempts)."""
    status = record.get("status")
    if status != "ok":
        text = f"{'skipped' if status == 'skipped' else 'FAILED'}: {record.get('reason', '')}"
    else:
        keys = ("engine", "history", "lcp_space")
        text = ", ".join(f"{key} {record[key]}" for key in keys if record.get(key))
        if record.get("reason"):
            text += f"; lcp {record['lcp_solver']} after {record['reason']}"
    return text if len(text) <= NOTES_WIDTH else text[: NOTES_WIDTH - 3] + "..."


@_styled
def scaling_figure(records) -> Figure:
    """Log-log run times: the paper problem against N and the Winkler beams against m.

    Parameters
    ----------
    records : list of dict
        Records of :func:`~unilateral.bench.suite.run_scaling` (``sweep`` ``"N"`` or ``"m"``);
        only successful runs are drawn, at their total solve time.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels, with dashed reference slopes ``N, N log^2 N, N^2`` and ``m, m^2``.
    """
    fig, (ax_n, ax_m) = _figure((PAGE_WIDTH, 2.8), ncols=2)
    for ax, sweep, slopes, xlabel, title in (
            (ax_n, "N", _N_SLOPES, "number of steps N", "Liolios (1990) example, m = 3"),
            (ax_m, "m", _M_SLOPES, "unilateral unknowns m", "beam on Winkler springs")):
        ok = [r for r in records if r.get("sweep") == sweep and r.get("status") == "ok"]
        for method in dict.fromkeys(r["method"] for r in ok):
            points = sorted((r[sweep], r["total_s"]) for r in ok if r["method"] == method)
            x, y = np.array(points).T
            ax.loglog(x, y, "o-", color=_COLORS.get(method, "k"), label=method, markersize=3)
        if ok:
            x = np.array([r[sweep] for r in ok], dtype=float)
            _reference_slopes(ax, x, np.array([r["total_s"] for r in ok]), sweep, slopes)
            ax.set_xticks(np.unique(x))
            ax.legend(loc="upper left")
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_major_formatter(_PLAIN)
            axis.set_minor_formatter(NullFormatter())
        ax.yaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
        ax.set_xlabel(xlabel)
        ax.set_ylabel("solve time [s]")
        ax.set_title(title)
    return fig


def _reference_slopes(ax, x, y, sweep, slopes) -> None:
    """Dashed lines ``c f(x)`` through the median time at the smallest ``x``."""
    x0 = x.min()
    y0 = float(np.median(y[x == x0]))
    grid = np.geomspace(x0, x.max(), 50) if x.max() > x0 else np.array([x0, 2 * x0])
    for label, f, linestyle in slopes:
        line = y0 * f(grid) / f(x0)
        ax.loglog(grid, line, color="0.5", linestyle=linestyle, linewidth=0.8)
        ax.annotate(label, (grid[-1], line[-1]), textcoords="offset points", xytext=(2, 0),
                    fontsize=7, color="0.35", va="center")
    ax.set_xlim(right=grid[-1] * (1.6 if sweep == "N" else 1.4))


def save_scaling_figure(records, path_without_suffix: str | os.PathLike) -> list:
    """Draw :func:`scaling_figure` and save it as PNG and PDF (atomically).

    Returns
    -------
    list of pathlib.Path
    """
    return save_figure(scaling_figure(records), path_without_suffix)
