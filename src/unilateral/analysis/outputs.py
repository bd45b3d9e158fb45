"""A structural analysis from start to finish: solve with and without uplift, write every output.

Outputs in the output directory, each written atomically (a failed run leaves what was there):

=========================  ================================================================
``results.nc``             all cases (dims ``case x time x dof``, ``case x time x constraint``,
                           and node displacements ``case x time x node x component``)
``displacements.csv``      the unilateral case, one column per DOF (``bilateral_...`` likewise)
``constraints.csv``        uplift ``v`` and reaction ``psi`` per unilateral element
``summary.json``           the key figures (static state, peaks, LCP error, run time)
``fig2.png/.pdf``          the main history (the paper's Fig. 2: node 3, with and without uplift)
``constraints.png/.pdf``   uplift and contact force of each unilateral element
``force_deformation...``   the force-deformation path of each unilateral element
=========================  ================================================================
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from ..io import format_summary, save_csv, save_netcdf, summary, to_dataset, write_json_atomic
from ..figures import plot_constraints, plot_displacement, plot_force_deformation, save_figure
from ..solve import solve

COMPONENTS = ("ux", "uy", "rz")


def run_cases(model, load, *, dt, t_end, method="cq", rule="bdf2", lcp="bpp", initial="static",
              bilateral_reference=True, unilateral=True, progress=None) -> dict:
    """Solve the unilateral case and, optionally, the bilateral reference.

    Returns
    -------
    dict ``{"unilateral": Solution, "bilateral": Solution}`` (the cases asked for)
    """
    kw = dict(dt=dt, t_end=t_end, method=method, rule=rule, lcp=lcp, initial=initial)
    cases = {}
    if unilateral:
        cases["unilateral"] = solve(model, load, callback=progress, **kw)
    if bilateral_reference or not unilateral:
        cases["bilateral"] = solve(model, load, bilateral=True, **kw)
    return cases


def write_outputs(out_dir, cases: dict, *, structure=None, units=None, figure=None, title="",
                  meta=None, labels=None) -> dict:
    """Write results, tables, summary and figures of solved cases; return the summary dict.

    Parameters
    ----------
    out_dir : path, created if needed
    cases : dict of name -> Solution ("unilateral", "bilateral")
    structure : Structure, optional
        Gives node displacements (slave nodes included) and element deformations.
    units : dict ``{"length": ..., "force": ..., "time": ...}``
    figure : dict ``node``, ``dof``, ``label``, optional: the main history to plot
    title : str
    meta : dict, optional: attributes stored in ``results.nc`` and ``summary.json``
    labels : dict, optional: legend label of each case (default: the case names)
    """
    labels = labels or {}
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    meta = dict(meta or {})
    main = cases.get("unilateral") or cases["bilateral"]
    ds = to_dataset(cases, units=units, attrs=meta)
    if structure is not None:
        ds = _with_node_displacements(ds, cases, structure, units)
    save_netcdf(ds, out / "results.nc")
    for name, sol in cases.items():
        save_csv(sol, out, prefix="" if sol is main else f"{name}_")

    extra = dict(meta)
    if figure is not None and structure is not None:
        histories = {labels.get(name, name): (sol.t, structure.node_displacement(sol, figure["node"], figure["dof"]))
                     for name, sol in cases.items()}
        extra["figure"] = {
            "node": figure["node"], "dof": figure["dof"],
            "static": float(next(iter(histories.values()))[1][0]),
            "peak": {label: float(np.max(y)) for label, (_, y) in histories.items()},
            "minimum": {label: float(np.min(y)) for label, (_, y) in histories.items()},
        }
        ylabel = figure.get("label") or f"{figure['dof']} of node {figure['node']}"
        fig = plot_displacement(histories, ylabel=_with_unit(ylabel, units, figure["dof"]), title=title,
                                units=units)
        save_figure(fig, out / "fig2")
    if len(cases) > 1:
        extra["cases"] = {name: {"success": sol.success, "message": sol.message}
                          for name, sol in cases.items()}
    result = summary(main, units=units, extra=extra)
    write_json_atomic(out / "summary.json", result)
    if main.v.shape[1]:
        save_figure(plot_constraints(main, units=units), out / "constraints")
        if structure is not None:
            e, _ = structure.element_deformations(main.u, main.v)
            names = main.constraint_names
            fig = plot_force_deformation({k: e[:, i] for i, k in enumerate(names)},
                                         {k: main.psi[:, i] for i, k in enumerate(names)}, units=units)
            save_figure(fig, out / "force_deformation")
    return result


def report(result: dict) -> str:
    """The terminal summary of a run: :func:`format_summary` and the main history's extremes."""
    extra = result.get("extra", {})
    text = format_summary({**result, "extra": {k: v for k, v in extra.items()
                                               if k not in ("figure", "cases", "figure_node", "figure_dof")}})
    fig = extra.get("figure")
    if fig:
        unit = (result.get("units") or {}).get("length", "")
        lines = [f"{fig['dof']} of node {fig['node']} [{unit}]: static {fig['static']:.4g}"]
        for label, peak in fig["peak"].items():
            lines.append(f"  {label:>15}: max {peak:.4g}, min {fig['minimum'][label]:.4g}")
        text += "\n\n" + "\n".join(lines)
    for name, case in extra.get("cases", {}).items():
        if not case["success"]:
            text += f"\n{name} case FAILED: {case['message']}"
    return text


def _with_unit(label, units, dof):
    """Append the unit to an axis label that does not state one already."""
    unit = (units or {}).get("length", "") if dof != "rz" else "rad"
    return f"{label} [{unit}]" if unit and not any(c in label for c in "[(") else label


def _with_node_displacements(ds, cases, structure, units):
    nodes = list(structure.dofs.nodes)
    data = np.stack([structure.dofs.nodal(sol.u) for sol in cases.values()])
    if "case" not in ds.dims:
        data = data[0]
        dims = ("time", "node", "component")
    else:
        dims = ("case", "time", "node", "component")
    var = xr.DataArray(data, dims=dims, coords={"node": [str(n) for n in nodes],
                                                "component": list(COMPONENTS)})
    var.attrs["long_name"] = "displacements of every node (supported and rigidly linked included)"
    if units and "length" in units:
        var.attrs["units"] = f"{units['length']} (ux, uy); rad (rz)"
    return ds.assign(node_displacement=var)
