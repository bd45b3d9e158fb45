"""The example ``halfspace``: the paper's tower on three soils, with and without uplift, two loads.

:func:`run_halfspace_example` solves :func:`unilateral.structure.examples.halfspace_tower` on the
paper's Winkler-Kelvin soil, on Wolf's cones and on the rigorous half-space, each with uplift
(the case ``unilateral``) and with the contacts held (``bilateral``), under the paper's pulse and
under a synthetic earthquake: six runs of two cases. It writes

* ``results_<soil>_<load>.nc`` for each run (``results_cones_pulse.nc``, ...): its ``results.nc``,
  both cases, with the patch extents of the footing (:func:`run_dataset`);
* ``results.nc``, the CSV tables, ``summary.json`` and the figures of the half-space under the
  earthquake (:func:`unilateral.analysis.write_outputs`); ``results.nc`` lists the run files in
  its attribute ``run_files``, ``summary.json`` under ``extra.run_files``, and the peaks of every
  run under ``extra.comparison`` (run, then case);
* ``halfspace.png`` (:func:`draw_comparison`), drawn from the run files' Datasets: uplift of the
  footing's left edge, rocking and the contact pressure under the left strip, side by side for
  the two loads. ``unilateral plot results.nc`` redraws it from the run files next to it.

The helpers that read a run's Dataset (:func:`case_values`, :func:`rigid_motion`, ...) take an
:class:`xarray.Dataset` (a file read back) or a :class:`unilateral.io.dataset.Dataset` (as
written); :mod:`unilateral.analysis.footings_example` uses them too.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

#: Time step and end time of each load (s): the whole example runs in seconds.
DEFAULTS = {"pulse": {"dt": 2e-3, "t_end": 1.5}, "earthquake": {"dt": 2e-3, "t_end": 8.0}}
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}
SOIL_LABELS = {"winkler-kelvin": "paper's Winkler-Kelvin", "cones": "cones", "halfspace": "half-space"}
COLOURS = {"winkler-kelvin": "tab:blue", "cones": "tab:green", "halfspace": "tab:red"}
LOADS = ("pulse", "earthquake")
TITLES = {"pulse": "the paper's pulse (200 kN, 0.1 s)", "earthquake": "synthetic earthquake (PGA 5 m/s$^2$)"}
#: The run whose outputs are ``results.nc``, the CSV tables and the standard figures.
MAIN = ("halfspace", "earthquake")
#: Line style of each case in the comparison figures.
STYLES = {"unilateral": ("-", 1.0), "bilateral": ("--", 0.8)}


def run_file(name: str) -> str:
    """The file of the run ``name``: ``results_<name>.nc``."""
    return f"results_{name}.nc"


def solve_all(*, dt=None, t_end=None, method="cq", rule="bdf2", lcp="bpp", progress=None) -> dict:
    """Solve the six runs of two cases each.

    One model per soil is shared by both loads and both cases, so the soil's weights are computed
    once per time step (:meth:`unilateral.soil.SoilFlexibility.cq_weights`).

    Returns
    -------
    dict
        ``{(soil, load): (structure, load, info, {"unilateral": sol, "bilateral": sol}, model)}``
    """
    from ..solve import solve
    from ..structure.examples import HALFSPACE_SOILS, halfspace_tower

    out, done, total = {}, 0, 4 * len(HALFSPACE_SOILS)
    for soil in HALFSPACE_SOILS:
        model = None
        for load_name in LOADS:
            structure, load, info = halfspace_tower(soil, load=load_name)
            if model is None:
                model = structure.to_model()
            step = dt or DEFAULTS[load_name]["dt"]
            end = t_end or DEFAULTS[load_name]["t_end"]
            cases = {}
            for case in ("unilateral", "bilateral"):
                cases[case] = solve(model, load, dt=step, t_end=end, method=method, rule=rule, lcp=lcp,
                                    bilateral=case == "bilateral")
                done += 1
                if progress is not None:
                    progress(done, total + 1)
            out[(soil, load_name)] = (structure, load, info, cases, model)
    return out


# ---------------------------------------------------------------------- the runs' Datasets
def run_dataset(cases: dict, *, structure, model, load, figure: dict, meta: dict, rule="bdf2",
                units=UNITS_KN):
    """The ``results.nc`` Dataset of one run, as :func:`unilateral.analysis.write_outputs` builds it.

    Parameters
    ----------
    cases : dict
        ``{"unilateral": Solution, "bilateral": Solution}`` (the cases solved; one is enough).
    structure, model, load
        The frame, the model solved and its load (for the structure's results).
    figure : dict
        ``node``, ``dof``, ``label``: the history of ``fig2``.
    meta : dict
        Attributes of the Dataset (the run's ``soil``, ``figure_prefix``, ...).
    rule : str
        The time rule of the runs (for the energy balance).
    units : dict
        The base units.

    Returns
    -------
    unilateral.io.dataset.Dataset
        Every case, the node displacements, the constraints' coordinates (the footings' patch
        extents included), the structure's results and the legend labels ``case_labels``
        (:func:`unilateral.analysis.run.case_labels` of the constraints' kinds).
    """
    from ..io.dataset import cases_dataset
    from .constraint_units import with_constraint_units
    from .outputs import (_on_common_axis, _strip_unit, _structure_results, _with_constraint_coords,
                          _with_node_displacements, _with_results)

    padded = _on_common_axis(cases)
    attrs = {**meta, "figure_node": str(figure["node"]), "figure_dof": figure["dof"],
             "figure_text": _strip_unit(figure.get("label") or f"{figure['dof']} of node {figure['node']}")}
    ds = cases_dataset(padded, units=units, attrs=attrs, footings=structure.foundation)
    ds = _with_node_displacements(ds, padded, structure, units)
    ds = _with_constraint_coords(ds, structure)
    results = _structure_results(structure, model, cases, load=load, units=units, rule=rule, point=None,
                                 storeys=None)
    ds = _with_results(ds, results, True, list(padded))
    ds = with_constraint_units(ds, structure, units)
    labels = example_labels(ds)
    ds.attrs["case_labels"] = json.dumps({name: labels.get(name, name) for name in padded})
    return ds


def example_labels(ds) -> dict:
    """The legend label of each case from the kinds of the constraints (``constraint_kind``) of a
    run's Dataset: :func:`unilateral.analysis.run.case_labels` (empty: the case names)."""
    from .run import case_labels

    return case_labels([str(kind) for kind in ds["constraint_kind"].values]) or {}


def write_runs(datasets: dict, folder: Path) -> list[str]:
    """Write each run's Dataset to ``folder / results_<name>.nc``; return the file names."""
    from ..io.dataset import save_netcdf

    names = []
    for name, ds in datasets.items():
        save_netcdf(ds, folder / run_file(name))
        names.append(run_file(name))
    return names


def case_values(ds, name: str, case: str) -> np.ndarray:
    """The values of the variable ``name`` of a run's Dataset in the case ``case`` (that dimension dropped).

    Raises
    ------
    unilateral.figures.FigureDataError
        The Dataset has no such variable or case.
    """
    from ..figures import FigureDataError

    if name not in ds:
        raise FigureDataError(f"the Dataset has no variable {name}")
    var = ds[name]
    if "case" not in var.dims:
        return np.asarray(var.values)
    cases = [str(c) for c in ds["case"].values]
    if case not in cases:
        raise FigureDataError(f"the Dataset has no case {case!r} (it has {', '.join(cases)})")
    return np.take(np.asarray(var.values), cases.index(case), axis=var.dims.index("case"))


def cases_of(ds) -> list[str]:
    """The cases of a run's Dataset, ``unilateral`` first."""
    return sorted((str(c) for c in ds["case"].values), key=lambda c: c != "unilateral")


def footing_names(ds) -> list[str]:
    """The footings of a run's Dataset (its coordinate ``footing``), in the order of their patches."""
    from ..figures import FigureDataError

    if "footing" not in ds.coords:
        raise FigureDataError("the Dataset has no coordinate footing (the patch extents of its footings)")
    return list(dict.fromkeys(str(f) for f in ds["footing"].values if str(f)))


def footing_patches(ds, footing: str) -> np.ndarray:
    """The positions along ``constraint`` of the patches of ``footing``, left to right."""
    from ..figures import FigureDataError

    cols = np.flatnonzero(np.asarray(ds["footing"].values).astype(str) == footing)
    if not cols.size:
        raise FigureDataError(f"the Dataset has no footing {footing!r}")
    return cols[np.argsort(np.asarray(ds["patch_x"].values)[cols], kind="stable")]


def footing_extent(ds, footing: str) -> tuple[float, float]:
    """``(x_left, x_right)``: the edges of the footing, from its patch extents."""
    cols = footing_patches(ds, footing)
    x, width = np.asarray(ds["patch_x"].values)[cols], np.asarray(ds["patch_width"].values)[cols]
    return float(np.min(x - 0.5 * width)), float(np.max(x + 0.5 * width))


def rigid_motion(ds, case: str, footing: str) -> tuple[float, np.ndarray, np.ndarray]:
    """``(x0, uy, rz)``: a rigid footing's point at abscissa ``x`` moves up by ``uy + (x - x0) rz``.

    ``uy`` and ``rz`` (N+1,) are the displacements of the footing's node (``patch_node``, the same
    for all its patches) in ``case``, ``x0`` the centre of its patches, on which a rigid footing's
    strips are centred.

    Raises
    ------
    unilateral.figures.FigureDataError
        The footing is flexible (its patches act on several nodes), or a variable is missing.
    """
    from ..figures import FigureDataError

    cols = footing_patches(ds, footing)
    nodes = sorted({str(n) for n in np.asarray(ds["patch_node"].values)[cols]})
    if len(nodes) != 1:
        raise FigureDataError(f"footing {footing!r} is flexible (its patches act on the nodes {', '.join(nodes)}); "
                              "the figure shows rigid footings")
    lo, hi = footing_extent(ds, footing)
    return 0.5 * (lo + hi), node_history(ds, case, nodes[0], "uy"), node_history(ds, case, nodes[0], "rz")


def node_history(ds, case: str, node: str, dof: str) -> np.ndarray:
    """The displacement ``dof`` of ``node`` in ``case`` (``node_displacement``)."""
    from ..figures import FigureDataError

    values = case_values(ds, "node_displacement", case)
    nodes, components = ([str(x) for x in ds[dim].values] for dim in ("node", "component"))
    if node not in nodes or dof not in components:
        raise FigureDataError(f"node_displacement has no node {node!r} with {dof!r}")
    return values[:, nodes.index(node), components.index(dof)]


def runs_by(datasets, *keys: str) -> dict:
    """The runs' Datasets keyed by their attributes ``keys`` (e.g. ``soil``, ``load``)."""
    from ..figures import FigureDataError

    out = {}
    for ds in datasets:
        missing = [key for key in keys if key not in ds.attrs]
        if missing:
            raise FigureDataError(f"a run's Dataset lacks the attribute(s) {', '.join(missing)}")
        out[tuple(str(ds.attrs[key]) for key in keys)] = ds
    return out


# ---------------------------------------------------------------------- the figure
def draw_comparison(datasets, path_without_suffix, formats=("png",)) -> list:
    """The figure ``halfspace``: 3 rows (edge uplift, rocking, left-strip pressure) x 2 loads.

    Parameters
    ----------
    datasets : iterable of Dataset
        The six runs' Datasets (:func:`run_dataset`, or the run files read back), each with the
        attributes ``soil`` and ``load``.
    path_without_suffix : path
        ``out/halfspace`` gives ``out/halfspace.png``.
    formats : sequence of str

    Returns
    -------
    list of pathlib.Path

    Raises
    ------
    unilateral.figures.FigureDataError
        A run missing, or a Dataset without what the figure shows.
    """
    from ..figures import FigureDataError
    from ..figures.plots import _figure, save_figure

    runs = runs_by(datasets, "soil", "load")
    missing = [f"{soil}/{load}" for load in LOADS for soil in SOIL_LABELS if (soil, load) not in runs]
    if missing:
        raise FigureDataError(f"the run(s) {', '.join(missing)} are missing")
    fig, axes = _figure((11.0, 8.0), nrows=3, ncols=2, sharex="col", squeeze=False,
                        margins=(0.9, 0.2, 0.6, 0.6), gaps=(0.8, 0.3))
    for col, load in enumerate(LOADS):
        for soil in SOIL_LABELS:
            _draw_run(axes[:, col], runs[(soil, load)], soil)
        axes[0, col].set_title(TITLES[load], fontsize=10)
        axes[2, col].set_xlabel("time [s]")
        for row in range(3):
            axes[row, col].axhline(0.0, color="0.6", lw=0.5)
    axes[0, 0].set_ylabel("uy of the left edge [mm]")
    axes[1, 0].set_ylabel("rocking rz [mrad]")
    axes[2, 0].set_ylabel("pressure, left strip [kPa]")
    axes[0, 0].legend(fontsize=7, loc="upper right")
    fig.suptitle("Tower on a rigid footing: Winkler-Kelvin soil, cones and the elastic half-space", fontsize=11)
    return save_figure(fig, path_without_suffix, formats)


def _draw_run(axes, ds, soil: str) -> None:
    """Edge uplift, rocking and left-strip pressure of both cases of one run into the three ``axes``.

    The left edge is that of the tower's 10 m footing (:data:`~unilateral.structure.examples.FOOTING_WIDTH`),
    at the centre of the paper's left Winkler-Kelvin spring, whose strip reaches 2.5 m beyond it.
    """
    from ..figures.results import case_labels
    from ..structure.examples import FOOTING_WIDTH

    (footing,) = footing_names(ds)
    left = footing_patches(ds, footing)[0]
    area = float(ds["patch_width"].values[left] * ds["patch_length"].values[left])
    labels, t = case_labels(ds), np.asarray(ds["time"].values)
    for case in cases_of(ds):
        _, uy, rz = rigid_motion(ds, case, footing)
        pressure = -case_values(ds, "psi", case)[:, left] / area
        style, width = STYLES.get(case, ("-.", 0.8))
        kw = dict(color=COLOURS[soil], ls=style, lw=width, label=f"{SOIL_LABELS[soil]}, {labels.get(case, case)}")
        axes[0].plot(t, 1e3 * (uy - 0.5 * FOOTING_WIDTH * rz), **kw)
        axes[1].plot(t, 1e3 * rz, **kw)
        axes[2].plot(t, pressure, **kw)


# ---------------------------------------------------------------------- the example
def run_halfspace_example(out, *, figures=("png",), progress=None, figure_process=None, dt=None, t_end=None,
                          method=None, rule=None, lcp=None, initial=None) -> dict:
    """Run the example and write its outputs to ``out``; return the summary dict (as ``run_example``).

    The output folder and the estimated time (:func:`~unilateral.analysis.example_cost.check_example_cost`:
    at most an hour) are checked before anything is solved. The run files are written into its
    staging folder first, then the outputs of the half-space under the earthquake by
    :func:`unilateral.analysis.outputs.write_outputs`, which lists them all in ``manifest.json``.
    """
    from ..io.folder import OutputFolder
    from ..structure.examples import HALFSPACE_SOILS
    from .example_cost import check_example_cost
    from .outputs import write_outputs

    if initial not in (None, "static"):
        raise ValueError(f"initial={initial!r}: the halfspace example starts from the static state only")
    steps = [round((t_end or DEFAULTS[name]["t_end"]) / (dt or DEFAULTS[name]["dt"])) for name in LOADS]
    check_example_cost("halfspace", steps * 2 * len(HALFSPACE_SOILS), dt, t_end)     # before anything is solved
    rule = rule or "bdf2"
    folder = OutputFolder(out)
    staging = folder.prepare()
    try:
        runs = solve_all(dt=dt, t_end=t_end, method=method or "cq", rule=rule, lcp=lcp or "bpp", progress=progress)
        datasets = {f"{soil}_{load_name}": run_dataset(
            cases, structure=structure, model=model, load=load, figure=info["figure"], rule=rule,
            meta={"example": "halfspace", "soil": soil, "load": load_name, "figure_prefix": f"{soil}_{load_name}_",
                  "title": f"Tower on a rigid footing, {SOIL_LABELS[soil]} soil: {TITLES[load_name]}"})
            for (soil, load_name), (structure, load, info, cases, model) in runs.items()}
        files = write_runs(datasets, staging)
        comparison = {f"{soil}/{load_name}": {case: _peaks(sol) for case, sol in run[3].items()}
                      for (soil, load_name), run in runs.items()}
        structure, load, info, cases, model = runs[MAIN]
        result = write_outputs(
            folder, cases, structure=structure, units=UNITS_KN, figure=info["figure"],
            title="Tower on a rigid footing on the elastic half-space, synthetic earthquake",
            meta={"example": "halfspace", "soil": MAIN[0], "load": MAIN[1], "run_files": files,
                  "model": "docs/theory.md section 12; unilateral.structure.examples.halfspace_tower"},
            labels=example_labels(datasets["_".join(MAIN)]), model=model, load=load, rule=rule, formats=figures,
            figure_process=figure_process, summary_extra={"comparison": comparison},
            extra_figures=lambda where, formats: draw_comparison(datasets.values(), where / "halfspace", formats))
    finally:
        folder.close()
    result["comparison"] = comparison
    result["success_all"] = all(sol.success for run in runs.values() for sol in run[3].values())
    if progress is not None:
        progress(1, 1)
    return result


def _peaks(sol) -> dict:
    """The peaks of one case of a run for ``summary.json`` (``extra.comparison``)."""
    return {"max_uplift": float(np.max(sol.v)), "success": bool(sol.success),
            "max_contact_force": float(np.max(-sol.psi)), "contact_changes": int(sol.stats.get("contact_changes", 0))}
