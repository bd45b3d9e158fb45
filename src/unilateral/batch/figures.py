"""Figures of a study: IDA curves and fragility curves (matplotlib on an Agg canvas, imported lazily).

* :func:`ida_figure`: intensity against a peak quantity, one line per record, with the median and
  the 16 % and 84 % fractiles over the records at each intensity level; one panel per model
  variant. A curve goes flat at a collapse; analyses that failed without one are marked apart.
* :func:`fragility_figure`: for each limit state, the fraction of analyses exceeding it at each
  level (with the number of analyses behind each point) and the lognormal fragility fitted by
  maximum likelihood (:func:`~unilateral.batch.fragility.fit_fragility`); one curve per variant.
  A collapse exceeds every limit state; a failure is left out (:mod:`unilateral.batch.collapse`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .fragility import fit_fragility


class _Plt:
    """The bits of pyplot used here, on a bare Agg canvas (no pyplot state, no GUI backend)."""

    @staticmethod
    def subplots(rows, cols, figsize, squeeze=False):
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        fig = Figure(figsize=figsize)
        FigureCanvasAgg(fig)
        return fig, fig.subplots(rows, cols, squeeze=squeeze)

    @staticmethod
    def get_cmap(name):
        import matplotlib

        return matplotlib.colormaps[name]

    @staticmethod
    def close(fig):
        pass


def _pyplot():
    return _Plt


def variant_labels(ds) -> dict:
    """``{variant: "model, key = value, ..."}``."""
    labels = {}
    params = [name for name in ds.data_vars if name.startswith("param.")]
    for v in np.unique(ds["variant"].values):
        rows = np.flatnonzero(ds["variant"].values == v)
        i = rows[0]
        parts = [str(ds["model"].values[i])]
        parts += [f"{name[6:]} = {_fmt(ds[name].values[i])}" for name in params]
        labels[int(v)] = ", ".join(parts)
    return labels


def _fmt(value) -> str:
    return f"{value:g}" if isinstance(value, (float, np.floating)) else str(value)


def _grid(plt, count):
    cols = min(count, 3)
    rows = math.ceil(count / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(max(5.2 * cols, 6.4), 4.4 * rows), squeeze=False)
    for ax in axes.ravel()[count:]:
        ax.set_visible(False)
    return fig, axes.ravel()


def _save(fig, path: Path, formats, dpi) -> list[Path]:
    from ..io.atomic import atomic_path

    written = []
    for fmt in formats:
        target = path.with_suffix(f".{fmt}")
        with atomic_path(target) as tmp:
            fig.savefig(tmp, dpi=dpi, format=fmt)
        written.append(target)
    return written


def _collapsed(ds) -> np.ndarray:
    """Boolean (analyses,): the rows whose structure collapsed (a table without the column: none)."""
    return ds["collapse"].values == 1 if "collapse" in ds else np.zeros(ds.sizes["analysis"], dtype=bool)


def ida_figure(ds, quantity: str, path, *, formats=("png",), dpi=150, title: str = "") -> list[Path]:
    """IDA curves of ``quantity`` (a column of the table) against the intensity; returns the files.

    A record's curve stops at its last level before a collapse and goes flat from there to the
    right edge (the collapse intensities marked ``>`` at the edge); analyses that failed without a
    collapse are red crosses at the edge, apart. The median and fractiles count a collapse as an
    infinite quantity (beyond the edge)."""
    plt = _pyplot()
    labels = variant_labels(ds)
    fig, axes = _grid(plt, len(labels))
    status, collapsed = ds["status"].values, _collapsed(ds)
    im_label = ds.attrs.get("intensity", "intensity")
    for ax, (v, label) in zip(axes, labels.items()):
        mine = ds["variant"].values == v
        _ida_panel(ax, ds, quantity, (mine, status, collapsed), plt)
        unit = ds[quantity].attrs.get("units", "")
        ax.set_xlabel(f"peak {quantity} [{pretty_unit(unit)}]" if unit else f"peak {quantity}")
        ax.set_ylabel(pretty_unit(im_label))
        ax.set_title(label, fontsize=9)
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6, ncol=2, loc="lower right")
    import textwrap

    fig.suptitle(textwrap.fill(title or f"IDA: {quantity}", 70), fontsize=10)
    fig.tight_layout()
    written = _save(fig, Path(path), formats, dpi)
    plt.close(fig)
    return written


def _ida_panel(ax, ds, quantity, rows_of, plt) -> None:
    """One variant's IDA curves (``rows_of = (mine, status, collapsed)``), median and fractiles."""
    mine, status, collapsed = rows_of
    values, intensity = ds[quantity].values, ds["intensity"].values
    good = mine & (status == "ok") & ~collapsed
    edge = float(np.nanmax(np.where(good, values, np.nan))) if np.any(good & np.isfinite(values)) else 1.0
    edge = 1.05 * (edge if edge > 0 else 1.0)                    # every peak 0 (nothing lifted): an edge at 1
    records = list(dict.fromkeys(ds["record"].values[mine]))
    cmap = plt.get_cmap("tab10" if len(records) <= 10 else "viridis")
    marks = {"collapse": False, "failed": False}
    for j, record in enumerate(records):
        rows = np.flatnonzero(mine & (ds["record"].values == record))
        rows = rows[np.argsort(intensity[rows])]
        gone = np.flatnonzero(collapsed[rows])
        curve = rows[: gone[0]] if gone.size else rows            # up to the first collapse
        curve = curve[good[curve]]
        color = cmap(j / max(len(records) - 1, 1)) if len(records) > 10 else cmap(j % 10)
        x, y = list(values[curve]), list(intensity[curve])
        if gone.size and x:                                       # the flatline at the last level standing
            x.append(edge)
            y.append(y[-1])
        ax.plot(x, y, "-o", color=color, lw=0.9, ms=2.5, alpha=0.75, label=record if len(records) <= 12 else None)
        if gone.size:
            ax.plot(np.full(gone.size, edge), intensity[rows[gone]], ">", color=color, ms=5,
                    label=None if marks["collapse"] else "collapse")
            marks["collapse"] = True
        bad = rows[(status[rows] != "ok") & (status[rows] != "pending") & ~collapsed[rows]]
        if bad.size:
            ax.plot(np.full(bad.size, edge * 1.04), intensity[bad], "x", color="red", ms=6,
                    label=None if marks["failed"] else "failed (not a collapse)")
            marks["failed"] = True
    ax.set_xlim(right=edge * 1.08)                               # the edge marks inside the panel
    levels = np.unique(intensity[mine])
    stats = []
    for level in levels:
        at = mine & (intensity == level)
        counted = np.concatenate([values[at & good], np.full(int(np.sum(at & collapsed)), np.inf)])
        counted = counted[~np.isnan(counted)]
        stats.append(np.percentile(counted, [16, 50, 84], method="inverted_cdf") if counted.size else [np.nan] * 3)
    stats = np.minimum(np.array(stats), edge)                     # a collapsed fractile at the edge
    if stats.size:
        ax.plot(stats[:, 1], levels, "-", color="black", lw=2.4, label="median")
        ax.plot(stats[:, 0], levels, "--", color="black", lw=1.4, label="16% / 84%")
        ax.plot(stats[:, 2], levels, "--", color="black", lw=1.4)


def fragility_fits(ds, limit_states) -> list[dict]:
    """Fits of every limit state and variant: dicts with theta, beta, levels, n, z, note.

    A collapse (column ``collapse``) exceeds every limit state, whatever its status; an analysis that
    failed without a collapse is left out (and counted in the note): it is evidence of neither."""
    fits = []
    status, collapsed = ds["status"].values, _collapsed(ds)
    for limit in limit_states:
        for v, label in variant_labels(ds).items():
            variant = ds["variant"].values == v
            mine = variant & ((status == "ok") | collapsed)
            levels = np.unique(ds["intensity"].values[variant])
            n, z = [], []
            for level in levels:
                rows = mine & (ds["intensity"].values == level)
                values = ds[limit.quantity].values[rows]
                known = np.isfinite(values) | collapsed[rows]
                n.append(int(np.sum(known)))
                z.append(int(np.sum(known & ((np.nan_to_num(values, nan=-np.inf) > limit.threshold)
                                             | collapsed[rows]))))
            failed = int(np.sum(variant & np.isin(status, ["failed", "error", "timeout"]) & ~collapsed))
            fit = fit_fragility(levels, n, z)
            note = fit.note
            if failed:
                note = (note + "; " if note else "") + f"{failed} failed analyses left out (not counted as collapse)"
            fits.append({"limit_state": limit.name, "quantity": limit.quantity, "threshold": limit.threshold,
                         "variant": v, "label": label, "theta": fit.theta, "beta": fit.beta,
                         "levels": fit.levels.tolist(), "n": fit.n.tolist(), "z": fit.z.tolist(), "note": note,
                         "fit": fit})
    return fits


def fragility_figure(ds, limit_states, path, *, formats=("png",), dpi=150, title: str = "") -> tuple[list, list]:
    """Fragility curves of the limit states; returns ``(files, fits)``."""
    plt = _pyplot()
    fits = fragility_fits(ds, limit_states)
    fig, axes = _grid(plt, len(limit_states))
    im_label = ds.attrs.get("intensity", "intensity")
    top = float(np.nanmax(ds["intensity"].values)) if ds.sizes["analysis"] else 1.0
    x = np.linspace(top / 400, top * 1.1, 400)
    for ax, limit in zip(axes, limit_states):
        mine = [f for f in fits if f["limit_state"] == limit.name]
        for j, f in enumerate(mine):
            color = plt.get_cmap("tab10")(j % 10)
            fit = f["fit"]
            frac = np.divide(fit.z, fit.n, out=np.full(fit.n.shape, np.nan), where=fit.n > 0)
            ax.plot(fit.levels, frac, "o", color=color, ms=5)
            for xj, fj, nj in zip(fit.levels, frac, fit.n):
                ax.annotate(f"{nj}", (xj, fj), textcoords="offset points", xytext=(0, 6), ha="center",
                            fontsize=6, color=color)
            if math.isfinite(f["theta"]):
                text = f"{f['label']}: θ = {f['theta']:.3g}{_im_unit(im_label)}, β = {f['beta']:.2f}"
                ax.plot(x, fit(x), "-", color=color, lw=1.6, label=text)
            else:
                ax.plot([], [], "-", color=color, label=f"{f['label']}: {f['note']}")
        ax.set_ylim(-0.03, 1.08)
        ax.set_xlim(0, top * 1.1)
        ax.set_xlabel(pretty_unit(im_label))
        ax.set_ylabel("P(exceedance)")
        ax.set_title(f"{limit.name} ({limit.quantity} > {limit.threshold:g})", fontsize=9)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle(title or "Fragility (lognormal, maximum likelihood; numbers: analyses per point)", fontsize=10)
    fig.tight_layout()
    written = _save(fig, Path(path), formats, dpi)
    plt.close(fig)
    return written, fits


def _im_unit(label: str) -> str:
    """`` g`` of an intensity label ``"PGA [g]"`` (the unit of the fragility's median θ), or ``""``."""
    label = str(label)
    if label.endswith("]") and "[" in label:
        return " " + pretty_unit(label[label.rindex("[") + 1:-1])
    return ""


def pretty_unit(unit: str) -> str:
    """A unit as drawn (``m/s^2`` -> ``m/s²``): :func:`unilateral.figures.results.pretty_unit`."""
    from ..figures.results import pretty_unit as pretty

    return pretty(unit)
