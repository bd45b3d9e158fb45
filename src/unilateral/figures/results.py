"""The figures of a run, drawn from its ``results.nc`` alone: ``run`` and ``plot`` call :func:`draw_figures`.

Every figure reads only the Dataset (variables, coordinates and attributes written by
:func:`unilateral.analysis.write_outputs`), so ``unilateral plot results.nc`` redraws exactly the
files ``unilateral run`` wrote. Rules of the house: a unit on every axis; one length unit per
figure, millimetres when the values are below half a metre; openings and compressive forces on
one-sided axes (both start at zero: an element is either open or pressed, never both).

=======================  ======================================================================
file                     content
=======================  ======================================================================
``fig2``                 the main history (``output.figure``), every case
``constraints``          opening and compression of each unilateral element, or, with more than
                         :data:`MAX_PANELS` elements, a space-time map of the opening and the
                         envelopes along the foundation
``force_deformation``    force against deformation of the unilateral elements (the largest)
``gaps``                 relative displacement across each gap element with the gap line
``hysteresis``           force against deformation of the yield and friction elements, the
                         largest dissipated energy first (at most :data:`MAX_HYSTERESIS`)
``ground_motion``        the input record(s)
``base_forces``          base shear (or, with no horizontal force on the ground, the vertical
                         ground force) and overturning moment
``energy``               the energy balance and its relative error
``spectra``              the pseudo-acceleration spectrum of the ground motion and the floor
                         spectra of the chosen nodes, every case
``model``                the structure with the names of its parts and its first mode shapes
                         (:mod:`unilateral.figures.model`), from the attribute ``model_drawing``
=======================  ======================================================================

The contact figures (``constraints``, ``force_deformation``, ``gaps``) show the contacts only:
plastic multipliers and slips (``constraint_kind`` ``yield`` and ``friction``) are no openings and
their ``psi`` is no contact force; ``hysteresis`` shows them.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..io.summary import RATE_KINDS
from ..rules import EnergyPairing
from . import FigureDataError
from .plots import PAGE_WIDTH, _figure, _styled, envelope, math_unit, plain_text, save_figure

MAX_PANELS = 6
#: Most panels of the hysteresis figure.
MAX_HYSTERESIS = 12
FORMATS = ("png", "pdf")
#: Longest title, axis label or legend label drawn: a longer one is cut (laying out a megabyte of
#: text took minutes).
MAX_TEXT = 200
#: Longest ``case_labels`` attribute read (a JSON object of a few labels).
MAX_LABELS_JSON = 100_000


def main_case(ds) -> str | None:
    """The case the single-case figures show: ``unilateral`` if present (None without the dimension
    ``case``).

    Raises
    ------
    FigureDataError
        The dimension ``case`` has length 0.
    """
    if "case" not in ds.dims:
        return None
    cases = case_names(ds)
    return "unilateral" if "unilateral" in cases else cases[0]


def case_names(ds) -> list[str]:
    """The names of the cases of ``ds`` (its coordinate ``case``).

    Raises
    ------
    FigureDataError
        The dimension ``case`` has length 0: there is no case to draw.
    """
    cases = [str(c) for c in ds["case"].values]
    if not cases:
        raise FigureDataError("the dimension case has length 0: the file holds no case to draw (a results.nc "
                              "has 1 or more, e.g. unilateral and bilateral)")
    return cases


def _components(d, family: str) -> None:
    """Check that the dimension ``<family>_component`` of ``d`` (if any) is not empty."""
    dim = f"{family}_component"
    if d.sizes.get(dim, 1) == 0 and d.sizes.get(f"{family}_element", 0) > 0:
        raise FigureDataError(f"the dimension {dim} has length 0, yet the file has {d.sizes[f'{family}_element']} "
                              f"{family} element(s): their forces have no component to draw (1 or 2 expected)")


def _case(ds, name):
    return ds if name is None else ds.sel(case=name)


def length_scale(unit: str, peak: float) -> tuple[str, float]:
    """Display unit and factor for lengths: millimetres for metre values below 0.5 m."""
    if unit == "m" and 0.0 < peak < 0.5:
        return "mm", 1e3
    return unit, 1.0


def rotation_scale(peak: float) -> tuple[str, float]:
    """Display unit and factor for rotations [rad]: milliradians below 0.5 rad."""
    return ("mrad", 1e3) if 0.0 < peak < 0.5 else ("rad", 1.0)


def force_scale(unit: str, peak: float) -> tuple[str, float]:
    """Display unit and factor for forces: MN above 10^4 kN, kN above 10^4 N."""
    if unit == "kN" and peak >= 1e4:
        return "MN", 1e-3
    if unit == "N" and peak >= 1e4:
        return "kN", 1e-3
    return unit, 1.0


#: Variables whose ``units`` attribute gives a base unit, in order of preference.
_UNIT_SOURCES = {"time": ("time",), "length": ("v", "constraint_deformation", "storey_drift"),
                 "force": ("psi", "base_shear", "axial_force")}


def _unit(ds, key):
    """The base unit ``key`` (``time``, ``length``, ``force``) of the Dataset, or ``""``.

    From the attribute ``units_<key>`` if present, else from the ``units`` of a variable that has
    that unit (``time``; ``v``; ``psi``), as :func:`unilateral.io.to_dataset` writes them.
    """
    unit = ds.attrs.get(f"units_{key}")
    if unit:
        return _text(unit, 40)
    for name in _UNIT_SOURCES.get(key, ()):
        if name in ds.variables and ds[name].attrs.get("units"):
            return _text(ds[name].attrs["units"], 40)
    return ""


def _axis(text, unit):
    return f"{text} [{pretty_unit(unit)}]" if unit else text


def pretty_unit(unit: str) -> str:
    """A unit as drawn: powers as superscripts (``m/s^2`` -> ``m/s²``, ``s^-1`` -> ``s⁻¹``)."""
    import re

    return re.sub(r"\^\(?(-?\d+)\)?", lambda m: m.group(1).translate(_SUPERSCRIPT), str(unit))


_SUPERSCRIPT = str.maketrans("-0123456789", "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079")


def _power_of_ten(value, _position=None) -> str:
    """Tick label ``10⁻⁶`` of a logarithmic axis, in plain text (mathtext is slow to lay out)."""
    if value <= 0:
        return ""
    exponent = np.log10(value)
    if abs(exponent - round(exponent)) > 1e-9:
        return ""
    return "10" + str(int(round(exponent))).translate(_SUPERSCRIPT)


def _map_rows(n: int, max_rows: int = 1000):
    """Start indices of time buckets for a space-time map with more than ``max_rows`` rows.

    None when every row is drawn; otherwise bucket starts plus ``n``, for
    ``np.maximum.reduceat`` (the peak opening of each bucket is drawn, so no peak is lost).
    """
    if n <= max_rows:
        return None
    return np.append(np.linspace(0, n, max_rows, endpoint=False).astype(int), n)


def draw_figures(ds, out_dir, formats=("png",), *, skipped=None, only=None) -> list[Path]:
    """Draw every figure the Dataset supports into ``out_dir``; return the files written.

    Parameters
    ----------
    ds : xarray.Dataset or unilateral.io.dataset.Dataset
        A ``results.nc`` Dataset (:func:`unilateral.analysis.outputs.figure_view` of it), read by
        xarray (``unilateral plot``) or as written (:func:`unilateral.analysis.write_outputs`).
    out_dir : str or path-like
        Created if missing.
    formats : sequence of str
        matplotlib formats, e.g. ``("png",)`` (default) or ``("png", "pdf")``; empty: none.
    skipped : list, optional
        Receives ``"<figure>: <why>"`` for each figure the Dataset cannot give (a variable missing,
        an attribute that names nothing), and the others are drawn. Without it the first such
        figure raises :class:`~unilateral.figures.FigureDataError`.
    only : collection of str, optional
        The names of the figures to draw (of :data:`FIGURES`); default: all.
    """
    formats = tuple(formats)
    if not formats:
        return []
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for name, draw in FIGURES:
        if only is not None and name not in only:
            continue
        try:
            fig = _draw(draw, ds)
        except FigureDataError as exc:
            if skipped is None:
                raise
            skipped.append(f"{name}: {exc}")
            continue
        if fig is not None:
            written += save_figure(fig, out / name, formats)
    return written


def _draw(draw, ds):
    """``draw(ds)``; a variable or coordinate the file lacks is a :class:`FigureDataError`."""
    try:
        return draw(ds)
    except KeyError as exc:                     # xarray: "No variable named 'x'. Did you mean ..."
        raise FigureDataError(f"the figure needs what the file lacks: {exc.args[0] if exc.args else exc}") from None


def _text(value, limit: int = MAX_TEXT) -> str:
    """``value`` as text of at most ``limit`` characters (cut with an ellipsis)."""
    text = str(value)
    return plain_text(text if len(text) <= limit else text[:limit - 1] + "\u2026")


def _listing(names, limit: int = 10) -> str:
    names = [repr(str(n)) for n in names]
    return ", ".join(names[:limit]) + (f" and {len(names) - limit} more" if len(names) > limit else "")


def case_labels(ds) -> dict:
    """The legend label of each case: the attribute ``case_labels``, a JSON object (empty without it).

    Raises
    ------
    FigureDataError
        The attribute is not a JSON object of case names to labels (or is longer than
        :data:`MAX_LABELS_JSON` characters).
    """
    raw = ds.attrs.get("case_labels")
    if raw is None:
        return {}
    text = str(raw)
    try:
        labels = json.loads(text) if len(text) <= MAX_LABELS_JSON else None
    except (ValueError, RecursionError):        # RecursionError: nested thousands deep
        labels = None
    if not isinstance(labels, dict) or not all(isinstance(v, str) for v in labels.values()):
        raise FigureDataError(f"the attribute case_labels = {_text(text, 60)!r} ({len(text)} characters) is not a "
                              'JSON object of case names to labels, e.g. {"unilateral": "with uplift"}')
    return {str(key): _text(value) for key, value in labels.items()}


def _panel_grid(count, *, title):
    """A figure of ``count`` panels, three to a row, with ``title`` inches above them; the axes
    (rows, 3) with the unused ones removed."""
    ncols = min(3, count)
    nrows = -(-count // ncols)
    fig, axes = _figure((min(PAGE_WIDTH, 0.3 + 2.1 * ncols), 0.5 + title + 2.0 * nrows), nrows=nrows,
                        ncols=ncols, margins=(0.7, 0.4, 0.5, title), gaps=(0.75, 0.75), squeeze=False)
    for ax in axes.flat[count:]:
        ax.remove()
    return fig, axes


def _figure_location(ds):
    """The node and DOF of the main history: the attributes ``figure_node`` and ``figure_dof``, checked."""
    node, dof = str(ds.attrs["figure_node"]), str(ds.attrs.get("figure_dof"))
    nd = ds["node_displacement"]
    for attribute, value, dim in (("figure_node", node, "node"), ("figure_dof", dof, "component")):
        valid = [str(x) for x in nd[dim].values] if dim in nd.coords else []
        if value not in valid:
            raise FigureDataError(f"the attribute {attribute} = {_text(value, 60)!r} names no {dim} of "
                                  f"node_displacement; valid: {_listing(valid) or 'none'}")
    return node, dof


@_styled
def history_figure(ds):
    """The main history of every case (the paper's Fig. 2 for the example)."""
    if ds.attrs.get("figure_node") is None or "node_displacement" not in ds:
        return None
    node, dof = _figure_location(ds)
    nd = ds["node_displacement"].sel(node=node, component=dof)
    labels = case_labels(ds)
    t = ds["time"].values
    curves = ({labels.get(c, c): nd.sel(case=c).values for c in case_names(ds)}
              if "case" in nd.dims else {"": nd.values})
    peak = max(float(np.max(np.abs(y))) for y in curves.values())
    unit, factor = ("rad", 1.0) if dof == "rz" else length_scale(_unit(ds, "length"), peak)
    fig, ax = _figure((PAGE_WIDTH, 3.0), margins=(0.8, 0.2, 0.5, 0.35 if ds.attrs.get("title") else 0.15))
    for k, (label, y) in enumerate(curves.items()):
        ax.plot(*envelope(t, factor * y), ("-", "--", "-.", ":")[k % 4], color=f"C{k}", label=label or None)
    ax.margins(x=0)
    ax.set(xlabel=_axis("time t", _unit(ds, "time")),
           ylabel=_axis(_text(ds.attrs.get("figure_text") or f"{dof} of node {node}"), unit))
    if ds.attrs.get("title"):
        ax.set_title(_text(ds.attrs["title"]))
    if any(curves):
        ax.legend(loc="best")
    return fig


def _constraint_data(ds):
    """The main case with its contacts only (no plastic multipliers, no slips), or None without any."""
    d = _case(ds, main_case(ds))
    if "v" not in d or d.sizes.get("constraint", 0) == 0:
        return None
    if "constraint_kind" in d.coords:
        contact = np.flatnonzero(~np.isin(d["constraint_kind"].values.astype(str), RATE_KINDS))
        if contact.size < d.sizes["constraint"]:
            d = d.isel(constraint=contact) if contact.size else None
    return d


@_styled
def constraints_figure(ds):
    """Opening and compression of each unilateral element, or a map along x for many of them (the
    largest openings of a 3-D frame, whose elements a position along x does not tell apart)."""
    d = _constraint_data(ds)
    if d is None:
        return None
    m = d.sizes["constraint"]
    three_d = "component" in ds.coords and "uz" in [str(c) for c in ds["component"].values]
    if m > MAX_PANELS and "constraint_x" in d.coords and not three_d:
        return _contact_map(d)
    return _contact_panels(d)


def _contact_panels(d):
    t = d["time"].values
    v, psi = d["v"].values, d["psi"].values
    names = [str(c) for c in d["constraint"].values]
    shown = np.arange(len(names))
    if len(names) > MAX_PANELS:
        shown = np.sort(np.argsort(-v.max(axis=0), kind="stable")[:MAX_PANELS])
    lunit, lf = length_scale(_unit(d, "length"), float(np.max(v[:, shown], initial=0.0)))
    funit, ff = force_scale(_unit(d, "force"), float(np.max(-psi[:, shown], initial=0.0)))
    fig, axes = _figure((PAGE_WIDTH, 0.9 + 1.45 * len(shown)), margins=(0.8, 0.8, 0.5, 0.55), gaps=(0.0, 0.3),
                        nrows=len(shown), sharex=True, squeeze=False)
    for ax, i in zip(axes[:, 0], shown):
        ax.plot(*envelope(t, lf * v[:, i]), color="C0")
        twin = ax.twinx()
        twin.plot(*envelope(t, -ff * psi[:, i]), color="C3", linestyle="--")
        twin.grid(False)
        ax.set_ylim(0.0, 1.08 * lf * float(v[:, i].max()) or 1.0)
        twin.set_ylim(0.0, 1.08 * ff * float(-psi[:, i].min()) or 1.0)
        ax.margins(x=0)
        ax.set_title(names[i], loc="left")
        ax.set_ylabel(_axis("opening v", lunit), color="C0")
        twin.set_ylabel(_axis("compression −ψ", funit), color="C3")
        ax.tick_params(axis="y", colors="C0")
        twin.tick_params(axis="y", colors="C3")
    axes[-1, 0].set_xlabel(_axis("time t", _unit(d, "time")))
    fig.suptitle(f"{len(shown)} of {len(names)} unilateral elements, the largest openings" if len(shown) < len(names)
                 else "Unilateral elements: opening (solid) and compression (dashed)")
    return fig


def _contact_map(d):
    t = d["time"].values
    x = d["constraint_x"].values.astype(float)
    order = np.argsort(x, kind="stable")
    x = x[order]
    v, psi = d["v"].values[:, order], d["psi"].values[:, order]
    lunit, lf = length_scale(_unit(d, "length"), float(np.max(v, initial=0.0)))
    funit, ff = force_scale(_unit(d, "force"), float(np.max(-psi, initial=0.0)))
    xunit = _unit(d, "length")
    fig, (top, mid, low) = _figure((PAGE_WIDTH, 6.2), margins=(0.8, 0.2, 0.5, 0.35), gaps=(0.0, 0.6),
                                   nrows=3, height_ratios=(2.2, 1, 1))
    rows = _map_rows(len(t))
    tm = t[rows[:-1]] if rows is not None else t
    vm = np.maximum.reduceat(v, rows[:-1], axis=0) if rows is not None else v
    image = top.pcolormesh(x, tm, lf * vm, shading="nearest", cmap="viridis", vmin=0.0, rasterized=True)
    fig.colorbar(image, ax=top, label=_axis("opening v", lunit))
    top.set(xlabel=_axis("position x", xunit), ylabel=_axis("time t", _unit(d, "time")),
            title=f"Opening of {len(x)} unilateral elements over time")
    top.grid(False)
    mid.plot(x, lf * v.max(axis=0), "o-", color="C0", markersize=3)
    mid.set_ylim(0.0, 1.08 * lf * float(v.max()) or 1.0)
    mid.set(xlabel=_axis("position x", xunit), ylabel=_axis("peak opening", lunit))
    low.plot(x, -ff * psi.min(axis=0), "s-", color="C3", markersize=3)
    low.set_ylim(0.0, 1.08 * ff * float(-psi.min()) or 1.0)
    low.set(xlabel=_axis("position x", xunit), ylabel=_axis("peak compression", funit))
    return fig


@_styled
def force_deformation_figure(ds):
    """Force (compression positive) against deformation of the unilateral elements."""
    from matplotlib.ticker import MaxNLocator

    d = _constraint_data(ds)
    if d is None or "constraint_deformation" not in d:
        return None
    e, psi, v = d["constraint_deformation"].values, d["psi"].values, d["v"].values
    names = [str(c) for c in d["constraint"].values]
    shown = np.arange(len(names))
    if len(names) > MAX_PANELS:
        shown = np.sort(np.argsort(-v.max(axis=0), kind="stable")[:MAX_PANELS])
    lunit, lf = length_scale(_unit(d, "length"), float(np.max(np.abs(e[:, shown]), initial=0.0)))
    funit, ff = force_scale(_unit(d, "force"), float(np.max(-psi[:, shown], initial=0.0)))
    fig, axes = _panel_grid(len(shown), title=0.6 if len(shown) < len(names) else 0.35)
    for ax, i in zip(axes.flat, shown):
        ax.plot(*envelope(lf * e[:, i], lf * e[:, i], -ff * psi[:, i])[1:], color="C0", marker="o",
                markevery=[0], markersize=3)
        ax.set_ylim(0.0, 1.08 * ff * float(-psi[:, i].min()) or 1.0)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
        ax.set_title(names[i], loc="left")
        ax.set(xlabel=_axis("deformation", lunit), ylabel=_axis("compression", funit))
    if len(shown) < len(names):
        fig.suptitle(f"{len(shown)} of {len(names)} unilateral elements, the largest openings",
                     y=1.0 - 0.12 / fig.get_figheight(), va="top")
    return fig


@_styled
def gaps_figure(ds):
    """Relative displacement across each gap element, with the line where the gap closes."""
    d = _constraint_data(ds)
    if d is None or "constraint_kind" not in d.coords or "constraint_deformation" not in d:
        return None
    kinds = [str(k) for k in d["constraint_kind"].values]
    gaps = [i for i, k in enumerate(kinds) if k == "gap"][:MAX_PANELS]
    if not gaps:
        return None
    t = d["time"].values
    e = d["constraint_deformation"].values
    psi = impact_forces(d["psi"].values, _force_reference(_case(ds, main_case(ds))))
    gap = d["constraint_gap"].values.astype(float)
    names = [str(c) for c in d["constraint"].values]
    lunit, lf = length_scale(_unit(d, "length"), max(float(np.max(np.abs(e[:, gaps]))), float(np.max(gap[gaps]))))
    funit, ff = force_scale(_unit(d, "force"), float(np.max(-psi[:, gaps], initial=0.0)))
    fig, axes = _figure((PAGE_WIDTH, 0.6 + 2.6 * len(gaps)), margins=(0.8, 0.2, 0.5, 0.3), gaps=(0.0, 0.3),
                        nrows=2 * len(gaps), sharex=True, squeeze=False, height_ratios=[2, 1.2] * len(gaps))
    for k, i in enumerate(gaps):
        ax, low = axes[2 * k, 0], axes[2 * k + 1, 0]
        ax.plot(*envelope(t, lf * e[:, i]), color="C0", label="relative displacement (apart +)")
        ax.axhline(-lf * gap[i], color="C3", linestyle="--", linewidth=0.9,
                   label=f"closed: the gap of {lf * gap[i]:g} {lunit}")
        ax.margins(x=0)
        ax.set_title(names[i], loc="left")
        ax.set_ylabel(_axis("relative\ndisplacement", lunit))
        ax.legend(loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=2, frameon=False, borderaxespad=0.1)
        low.plot(*envelope(t, -ff * psi[:, i]), color="C3")
        low.set_ylim(0.0, 1.08 * ff * float(-psi[:, i].min()) or 1.0)
        if not np.any(psi[:, i] < 0.0):
            low.text(0.5, 0.5, "no impact (the gap never closes)", transform=low.transAxes, ha="center",
                     va="center", color="0.4")
        low.margins(x=0)
        low.set_ylabel(_axis("contact\nforce", funit))
    axes[-1, 0].set_xlabel(_axis("time t", _unit(d, "time")))
    return fig


#: Contact forces below this fraction of the run's force scale (:func:`_force_reference`) are round-off:
#: the gaps figure draws them as zero, not as impacts.
ROUND_OFF = 1e-9


def impact_forces(psi, reference: float):
    """``psi`` (N+1, m) with the values of magnitude at most ``ROUND_OFF * reference`` set to 0.

    Parameters
    ----------
    psi : (N+1, m) constraint reactions [force] (compression negative)
    reference : float, the force scale of the run [force] (:func:`_force_reference`)

    Returns
    -------
    (N+1, m) ndarray, a copy
    """
    psi = np.array(psi, dtype=float)
    psi[np.abs(psi) <= ROUND_OFF * reference] = 0.0
    return psi


def _force_reference(d) -> float:
    """The force scale of a case: the largest magnitude of its constraint reactions (every family),
    base forces and element axial forces [force]; 0 without any."""
    peaks = [float(np.nanmax(np.abs(d[name].values), initial=0.0))
             for name in ("psi", "base_vertical", "base_shear", "base_Fz", "axial_force") if name in d]
    return max(peaks, default=0.0)


@_styled
def hysteresis_figure(ds):
    """Force against deformation of the yield and friction elements, the most demanding first.

    One panel per element, at most :data:`MAX_HYSTERESIS`, ordered by the energy dissipated (the
    work of the force on the plastic deformation or the slip), then by the peak force over the
    yield force; dashed lines mark the yield forces.
    """
    from matplotlib.ticker import MaxNLocator

    d = _case(ds, main_case(ds))
    panels = _yield_panels(d) + _friction_panels(d)
    if not panels:
        return None
    panels.sort(key=lambda p: (-p["work"], -p["ratio"]))
    shown = panels[:MAX_HYSTERESIS]
    scales = _hysteresis_scales(d, shown)
    fig, axes = _panel_grid(len(shown), title=0.7 if len(shown) < len(panels) else 0.35)
    for ax, p in zip(axes.flat, shown):
        (xunit, xf), (yunit, yf) = scales[p["x"]], scales[p["y"]]
        ax.plot(*envelope(xf * p["deformation"], xf * p["deformation"], yf * p["force"])[1:], color="C0",
                linewidth=0.8, marker="o", markevery=[0], markersize=3)
        for limit in p["limits"]:
            ax.axhline(yf * limit, color="C3", linestyle="--", linewidth=0.7)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
        ax.set_title(p["name"], loc="left")
        ax.set_title(p["kind"], loc="right", color="0.4")
        ax.set(xlabel=_axis(p["xlabel"], xunit), ylabel=_axis(p["ylabel"], yunit))
    if len(shown) < len(panels):
        fig.suptitle(f"{len(shown)} of {len(panels)} yield and friction elements, the most dissipative first",
                     y=1.0 - 0.12 / fig.get_figheight(), va="top")
    return fig


def _yield_panels(d) -> list[dict]:
    """Hysteresis panels of the yield elements: deformation, force, yield lines, work, peak over yield
    (a 3-D hinge's: along the component of its larger peak, :func:`_along`)."""
    if "yield_force" not in d:
        return []
    _components(d, "yield")
    force, deformation = d["yield_force"].values, d["yield_element_deformation"].values
    plastic, pairing = d["plastic_deformation"].values, EnergyPairing.of_stats(str(d["stats"].values) if "stats" in d else "{}")
    positive, negative = d["yield_limit_positive"].values, d["yield_limit_negative"].values
    panels = []
    for k, name in enumerate(d["yield_element"].values):
        rotational = str(d["yield_deformation_unit"].values[k]) == "rad"
        work, label = _work_of(force, plastic, k, pairing), str(name)
        if force.ndim == 3:                     # components (a 3-D frame): the one of the larger peak
            j, label = _along(d, "yield", plastic, force, k)
            f, e, limits = force[:, k, j], deformation[:, k, j], (positive[k, j], -negative[k, j])
        else:
            f, e, limits = force[:, k], deformation[:, k], (positive[k], -negative[k])
        peak = max(float(np.max(f)) / limits[0], float(np.min(f)) / limits[1])
        panels.append({"name": label, "kind": str(d["yield_element_kind"].values[k]), "force": f,
                       "deformation": e, "limits": np.array(limits), "work": work,
                       "ratio": peak, "x": "rotation" if rotational else "length",
                       "y": "moment" if rotational else "force",
                       "xlabel": "end rotation" if rotational else "deformation",
                       "ylabel": "moment M" if rotational else "force F"})
    return panels


def _friction_panels(d) -> list[dict]:
    """Hysteresis panels of the friction elements: tangential motion against the friction force (a 3-D
    contact's along the component of its larger peak)."""
    if "friction_force" not in d:
        return []
    _components(d, "friction")
    force, motion, slip = d["friction_force"].values, d["tangential_deformation"].values, d["slip"].values
    panels, pairing = [], EnergyPairing.of_stats(str(d["stats"].values) if "stats" in d else "{}")
    for k, name in enumerate(d["friction_element"].values):
        label, j = str(name), None
        if force.ndim == 3:
            j, label = _along(d, "friction", slip, force, k)
        pick = (lambda a: a[:, k]) if j is None else (lambda a: a[:, k, j])
        panels.append({"name": label, "kind": str(d["friction_element_kind"].values[k]), "force": pick(force),
                       "deformation": pick(motion), "limits": (), "work": _work_of(force, slip, k, pairing), "ratio": 0.0,
                       "x": "length", "y": "force", "xlabel": "tangential motion", "ylabel": "friction force T"})
    return panels


def _along(d, family, plastic, force, k) -> tuple[int, str]:
    """``(j, "name (component)")``: the component of element ``k`` (values ``(time, element,
    component)``) with the larger peak plastic deformation, or force if it never yields; its name
    in the panel's title (none for an element with one component)."""
    names = [str(c) for c in d[f"{family}_component_name"].values[k]]
    count = sum(map(bool, names))
    if count == 0:
        raise FigureDataError(f"{family}_component_name names no component of the {family} element "
                              f"{_text(d[f'{family}_element'].values[k], 60)!r} (all {len(names)} names are empty)")
    peaks = np.nanmax(np.abs(plastic[:, k, :count]), axis=0, initial=0.0)
    if not peaks.any():
        peaks = np.nanmax(np.abs(force[:, k, :count]), axis=0, initial=0.0)
    j = int(np.argmax(peaks))
    name = str(d[f"{family}_element"].values[k])
    return j, (f"{name} ({names[j]})" if count > 1 else name)


def _work_of(force, deformation, k, pairing) -> float:
    """Work of element ``k``'s force on its deformation, summed over its components (if any)."""
    if force.ndim == 2:
        return pairing.series_work(force[:, k], deformation[:, k])
    return float(sum(pairing.series_work(force[:, k, j], deformation[:, k, j]) for j in range(force.shape[2])))


def _hysteresis_scales(d, panels) -> dict:
    """Display unit and factor of each axis quantity (``length``, ``rotation``, ``force``, ``moment``)
    over the panels: one unit per quantity in the figure."""
    def peak(axis, quantity):
        key = "deformation" if axis == "x" else "force"
        return max((float(np.nanmax(np.abs(p[key]), initial=0.0)) for p in panels if p[axis] == quantity), default=0.0)

    length, force = _unit(d, "length"), _unit(d, "force")
    funit, ff = force_scale(force, peak("y", "force"))
    munit, mf = force_scale(force, peak("y", "moment"))
    return {"length": length_scale(length, peak("x", "length")), "rotation": rotation_scale(peak("x", "rotation")),
            "force": (funit, ff), "moment": (f"{munit} {length}".strip(), mf)}


@_styled
def ground_motion_figure(ds):
    """The input ground acceleration(s)."""
    d = _case(ds, main_case(ds))
    if "ground_acceleration" not in d:
        return None
    t = d["time"].values
    a = d["ground_acceleration"].values
    unit = str(d["ground_acceleration"].attrs.get("units", ""))
    fig, ax = _figure((PAGE_WIDTH, 2.4))
    labels = [_excitation_label(str(label)) for label in d["excitation"].values]
    if len(set(labels)) < len(labels):          # two records in one direction: number them
        labels = [f"{label}, record {k + 1}" for k, label in enumerate(labels)]
    for k, label in enumerate(labels):
        ax.plot(*envelope(t, a[:, k]), color=f"C{k}", linewidth=0.8, label=label)
    ax.margins(x=0)
    what = labels[0] if len(labels) == 1 else "ground acceleration"
    ax.set(xlabel=_axis("time t", _unit(d, "time")), ylabel=_axis("$a_g$", unit),
           title=f"Input record: {what} $a_g$")
    if len(labels) > 1:
        ax.legend(loc="upper right")
    return fig


def _excitation_label(name: str) -> str:
    """``"0:ux"`` (index and direction of a ground motion) -> ``"horizontal ground acceleration"``."""
    direction = name.rpartition(":")[2]
    word = {"ux": "horizontal", "uy": "vertical"}.get(direction)
    return f"{word} ground acceleration" if word else _text(name, 40)


@_styled
def base_forces_figure(ds):
    """Base shear and overturning moment, every case."""
    if "base_shear" not in ds:
        return None
    t = ds["time"].values
    cases = [None] if "case" not in ds.dims else case_names(ds)
    labels = case_labels(ds)
    shear = [_case(ds, c)["base_shear"].values for c in cases]
    moment = [_case(ds, c)["overturning_moment"].values for c in cases]
    top_label = "base shear"
    peak = max(float(np.nanmax(np.abs(s), initial=0.0)) for s in shear)
    if "base_vertical" in ds:                   # vertical loads only: no base shear, show the vertical force
        vertical = [_case(ds, c)["base_vertical"].values for c in cases]
        peak_vertical = max(float(np.nanmax(np.abs(s), initial=0.0)) for s in vertical)
        if peak <= 1e-9 * peak_vertical:
            shear, peak, top_label = vertical, peak_vertical, "vertical ground force"
    funit, ff = force_scale(_unit(ds, "force"), peak)
    munit = f"{funit} {_unit(ds, 'length')}".strip()
    fig, (top, low) = _figure((PAGE_WIDTH, 4.4), margins=(0.8, 0.2, 0.5, 0.15 if top_label == "base shear" else 0.35),
                              gaps=(0.0, 0.3), nrows=2, sharex=True)
    for k, c in enumerate(cases):
        label = labels.get(c, c) if c else None
        top.plot(*envelope(t, ff * shear[k]), ("-", "--")[k % 2], color=f"C{k}", label=label)
        low.plot(*envelope(t, ff * moment[k]), ("-", "--")[k % 2], color=f"C{k}", label=label)
    point = ds.attrs.get("overturning_point")
    where = f" about ({point[0]:g}, {point[1]:g})" if point is not None and len(point) == 2 else ""
    top.set(ylabel=_axis(top_label, funit))
    if top_label != "base shear":
        top.set_title("no base shear (no horizontal force on the ground): vertical ground force",
                      loc="left")
    low.set(ylabel=_axis("moment", munit), xlabel=_axis("time t", _unit(ds, "time")))
    low.set_title(f"overturning moment{where}", loc="left")
    top.margins(x=0)
    if len(cases) > 1:
        top.legend(loc="best")
    return fig


@_styled
def energy_figure(ds):
    """Energies of the main case and the relative error of their balance."""
    from matplotlib.ticker import FuncFormatter, NullFormatter

    d = _case(ds, main_case(ds))
    if "energy_input_work" not in d:
        return None
    t = d["time"].values
    unit = str(d["energy_input_work"].attrs.get("units", ""))
    fig, (top, low) = _figure((PAGE_WIDTH, 4.2), margins=(0.8, 1.9, 0.5, 0.35), gaps=(0.0, 0.15), nrows=2,
                              sharex=True, height_ratios=(2.2, 1))
    for key, label in (("input_work", "input work"), ("support_work", "support work"), ("kinetic", "kinetic"),
                       ("elastic_structure", "elastic Δ (structure)"),
                       ("elastic_unilateral", "elastic Δ (unilateral)"),
                       ("damping_dissipated", "damping dissipated"), ("contact_dissipated", "contact dissipated"),
                       ("plastic_work", "plastic work"), ("friction_work", "friction work"),
                       ("geometric", "P-Delta Δ (geometric)"), ("numerical_dissipation", "numerical (the rule)")):
        if f"energy_{key}" not in d:
            continue
        y = d[f"energy_{key}"].values
        if key.startswith("elastic") or key == "geometric":
            y = y - y[0]
        if np.any(y):
            top.plot(*envelope(t, y), label=label)
    top.set(ylabel=_axis("energy", unit), title="Energy balance")
    if top.lines:
        top.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    top.margins(x=0)
    low.semilogy(*envelope(t, np.maximum(d["energy_relative_error"].values, 1e-17)), color="0.3")
    low.yaxis.set_major_formatter(FuncFormatter(_power_of_ten))
    low.yaxis.set_minor_formatter(NullFormatter())
    low.set(ylabel="relative error [1]", xlabel=_axis("time t", _unit(d, "time")))
    return fig


@_styled
def spectra_figure(ds):
    """Pseudo-acceleration spectra: the ground motion's, and the floors' of every case.

    The ground's in black; one colour per node, solid for the first case, dashed for the next.
    Axis units in mathtext (the ``units`` of ``ground_spectrum`` and of the coordinate ``period``).
    """
    if "ground_spectrum" not in ds:
        return None
    ground = ds["ground_spectrum"]
    periods = ds["period"].values
    attrs = ground.attrs
    unit, time = _text(attrs.get("units", ""), 40), _text(ds["period"].attrs.get("units") or _unit(ds, "time"), 40)
    fig, ax = _figure((PAGE_WIDTH, 3.2), margins=(0.8, 0.2, 0.5, 0.35))
    ax.plot(periods, ground.values, color="black", linewidth=1.4, label="ground (input)", zorder=3)
    if "floor_spectrum" in ds:
        labels = case_labels(ds)
        floors = ds["floor_spectrum"]
        cases = case_names(ds) if "case" in floors.dims else [None]
        for k, case in enumerate(cases):
            values = floors.sel(case=case).values if case is not None else floors.values
            for j, node in enumerate(floors["floor"].values):
                label = f"node {_text(node, 40)}" + (f", {labels.get(case, case)}" if len(cases) > 1 else "")
                ax.plot(periods, values[:, j], ("-", "--", "-.", ":")[k % 4], color=f"C{j % 10}", label=label)
    ax.margins(x=0)
    ax.set_ylim(bottom=0.0)
    direction = {"ux": "horizontal", "uy": "vertical"}.get(str(attrs.get("direction", "")), "")
    damping = _damping(attrs.get("damping"))
    ax.set(xlabel=f"period $T$ [{math_unit(time)}]" if time else "period $T$",
           ylabel=f"$S_a$ [{math_unit(unit)}]" if unit else "$S_a$",
           title=(f"Pseudo-acceleration response spectra, {direction} "
                  f"({100 * damping:g} % damping)" if damping is not None else
                  "Pseudo-acceleration response spectra").replace("  ", " "))
    ax.legend(loc="upper right", ncol=2 if len(ax.lines) > 6 else 1)
    return fig


def _damping(value) -> float | None:
    """The attribute ``damping`` of ``ground_spectrum`` as a number (None without it).

    Raises
    ------
    FigureDataError
        It is not one finite number.
    """
    if value is None:
        return None
    number = np.asarray(value)
    if number.ndim != 0 or number.dtype.kind not in "iuf" or not np.isfinite(number):
        raise FigureDataError(f"the attribute damping = {_text(value, 60)!r} of ground_spectrum is not a number; "
                              "a damping ratio such as 0.05 (5 %) is expected")
    return float(number)


def structure_figure(ds):
    """The model figure of the attribute ``model_drawing`` (a :class:`~unilateral.figures.model.ModelDrawing`
    as JSON), or None without it.

    Raises
    ------
    FigureDataError
        The attribute is not the JSON of a drawing.
    """
    from .model import ModelDrawing, model_figure

    if "model_drawing" not in ds.attrs:
        return None
    text = str(ds.attrs["model_drawing"])
    try:
        drawing = ModelDrawing.from_json(text)
    except (ValueError, TypeError, KeyError, RecursionError) as exc:
        raise FigureDataError(f"the attribute model_drawing = {_text(text, 60)!r} ({len(text)} characters) is not "
                              f"a model drawing (JSON of unilateral.figures.model.ModelDrawing): {_text(exc, 120)}") from None
    return model_figure(drawing)


#: Every figure, by file name, in the order drawn.
FIGURES = (("fig2", history_figure), ("constraints", constraints_figure),
           ("force_deformation", force_deformation_figure), ("gaps", gaps_figure),
           ("hysteresis", hysteresis_figure), ("ground_motion", ground_motion_figure),
           ("base_forces", base_forces_figure), ("energy", energy_figure), ("spectra", spectra_figure),
           ("model", structure_figure))
