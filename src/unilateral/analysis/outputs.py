"""A structural analysis from start to finish: solve with and without uplift, write every output.

Outputs in the output directory, replaced as a set (:class:`unilateral.io.folder.OutputFolder`):
every file is written into a staging folder next to it, which is then swapped in, so the folder
holds the complete files of one run at every instant and a failed or killed run leaves what was
there. A case that stopped early (``success=False``) is written up to where it stopped: its CSV
tables end there, and in ``results.nc`` its values after that are NaN.

=========================  ================================================================
``results.nc``             all cases (dims ``case x time x dof``, ``case x time x constraint``,
                           node displacements ``case x time x node x component``) and, for a
                           frame, the structure's results of :mod:`unilateral.analysis.results`
                           (end forces, reactions, base shear, overturning moment, drifts,
                           accelerations, energies, modes), each with ``long_name`` and ``units``;
                           a 3-D frame's: :data:`NOT_IN_3D` (its note in ``summary.json``); the
                           unit of each constraint's ``v`` and ``psi`` (rad and kN m for a hinge)
                           in the coordinates ``v_unit`` and ``psi_unit``
                           (:mod:`unilateral.analysis.constraint_units`)
``displacements.csv``      the unilateral case, one column per DOF (``bilateral_...`` likewise)
``constraints.csv``        ``v`` (uplift, plastic multiplier, slip) and ``psi`` per constraint unknown
                           (every CSV header states its unit: ``time [s]``, ``3.ux [m]``,
                           ``psi:soil2 [kN]``; ``[1]``: dimensionless)
``element_forces.csv``     end forces ``name:N_i [kN]`` ... ``name:M_j [kN m]`` per element (frames;
                           3-D: ``name:N_i`` ... ``name:Mz_j``, :func:`unilateral.structure.forces3d.end_forces`)
``base.csv``               base shear, base vertical force, overturning moment, drifts, energies
``spectra.csv``            with a ground motion and spectra asked for (``spectra=``): the
                           pseudo-acceleration spectrum of the ground motion and the floor
                           spectra of the chosen nodes per case (:mod:`unilateral.analysis.spectra`)
``yield_and_slip.csv``     plastic deformation and force of each yield element, slip, tangential
                           and normal force of each friction element (frames that have them;
                           a 3-D hinge or friction cone: one column per component,
                           ``plastic_deformation:H:roty [rad]``, ``slip:s1:t2 [m]``, and its
                           ``yield_ratio:H [1]``); these three, like the displacements, for every
                           case (``bilateral_element_forces.csv``, ...)
``summary.json``           the key figures (static state, peaks with their times, periods,
                           energy balance, LCP error, run time)
figures                    :mod:`unilateral.figures.results`, drawn from the Dataset written
                           to ``results.nc`` (``unilateral plot`` draws the same files); with
                           ``model_figure``, ``model.png`` of the structure and its modes
                           (:mod:`unilateral.figures.model`; ``results.nc`` holds the drawing;
                           a 3-D frame's is drawn in perspective, without modes, by
                           :mod:`unilateral.figures.model3d`, and not held in ``results.nc``)
=========================  ================================================================

The Dataset is a :class:`unilateral.io.dataset.Dataset`, written by h5netcdf without xarray, and
the figures are drawn from it (the command line's ``run`` and ``example`` import neither xarray
nor pandas; ``unilateral plot`` draws the same figures from the file read by xarray).
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..io.atomic import WriteError, to_jsonable, write_json_atomic, write_text_atomic
from ..io.dataset import Variable, cases_dataset, save_netcdf
from ..io.folder import OutputFolder
from ..io.recorders import Recorders, select, solution_view
from ..io.results import csv_text, save_csv
from ..io.summary import summary
from ..result import Solution
from ..solve import solve
from .constraint_units import with_constraint_units
from .terminal import (DISSIPATED, ENERGY_WARNING, FAILURE_HINT, _result_lines, case_name,  # noqa: F401 (re-exported)
                     energy_warnings, report)
from .results import load_samples_of, results_of_load

#: :func:`unilateral.analysis.results.results_of_load`, 2-D and 3-D, by its former names here.
_structure_results = _structure_results_3d = results_of_load
#: :func:`unilateral.analysis.results.load_samples_of` by its former name here.
_load_samples = load_samples_of

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
                  meta=None, labels=None, model=None, load=None, rule=None, formats=("png",),
                  point=None, storeys=None, figure_process=None, extra_figures=None, summary_extra=None,
                  spectra=None, model_figure=False, recorders=None) -> dict:
    """Write results, tables, summary and figures of solved cases; return the summary dict.

    The files replace those of the previous run in ``out_dir`` as a set (see the module's doc).

    Parameters
    ----------
    out_dir : path, created if needed, or a prepared :class:`unilateral.io.folder.OutputFolder`
    cases : dict of name -> Solution ("unilateral", "bilateral")
    structure : Structure, optional
        Gives node displacements (slave nodes included) and, with ``model``, the structure's
        results (:func:`unilateral.analysis.results.structure_results`).
    units : dict ``{"length": ..., "force": ..., "time": ...}``
    figure : dict ``node``, ``dof``, ``label``, optional: the main history to plot
    title : str
    meta : dict, optional: attributes stored in ``results.nc`` and ``summary.json``
    labels : dict, optional: legend label of each case (default: the case names)
    model : Model, optional: the model solved (modes of the bilateral structure)
    load : LoadHistory, array or callable, optional: the applied load (energy input, ground motions)
    rule : the time rule of the runs (default: the ``rule`` statistic of the main case)
    formats : figure formats, e.g. ``("png",)`` (default), ``("png", "pdf")`` or ``()`` (none)
    point : (x0, y0) of the overturning moment (default: the centre of the base, :func:`unilateral.structure.forces.base_point`)
    storeys : ``[(lower_node, upper_node)]`` storeys for drifts (default: levels by elevation)
    figure_process : :class:`unilateral.figures.background.BackgroundFigures`, optional
        A forked process that draws the figures while this one writes the other files (the same
        files as in process); closed here if the writing fails.
    summary_extra : dict, optional
        Entries added to ``summary.json`` only (e.g. the peaks of an example's other runs).
    extra_figures : callable, optional
        ``extra_figures(folder, formats)`` draws figures of its own (not redrawn by ``unilateral
        plot``) into the staging folder and returns their paths: they join the set of files (and
        ``manifest.json``). Called only with ``formats``.
    spectra : unilateral.analysis.spectra.SpectraSettings, optional
        With a frame under a ground motion: the response spectra (``ground_spectrum`` and
        ``floor_spectrum`` in ``results.nc``, ``spectra.csv``, ``spectra`` in ``summary.json``, the
        figure ``spectra``). None, or no ground motion: none.
    model_figure : bool
        With a frame: the figure ``model`` (:mod:`unilateral.figures.model`), the structure with its
        names and its first modes; ``results.nc`` keeps it in its attribute ``model_drawing``.
    recorders : unilateral.io.recorders.Recorders or dict, optional
        What of the results is written to ``results.nc`` and the CSV tables (default: every history
        of a small run, the key histories of a large one); the summary and the figures are of every
        result. ``summary.json``'s ``output`` says what was written.
    """
    folder = out_dir if isinstance(out_dir, OutputFolder) else OutputFolder(out_dir)
    try:
        staging = folder.prepare()
        try:
            result = _write_all(staging, cases, structure=structure, units=units, figure=figure, title=title,
                                meta=meta, labels=labels, model=model, load=load, rule=rule, formats=formats,
                                point=point, storeys=storeys, figure_process=figure_process,
                                summary_extra=summary_extra, spectra=spectra, model_figure=model_figure,
                                recorders=recorders)
            if formats and extra_figures is not None:
                result["figures"] += [str(p) for p in extra_figures(staging, formats)]
        except BaseException:
            if figure_process is not None:      # it draws into the staging folder, removed below
                figure_process.close()
            raise
        final = folder.commit()
    except WriteError as exc:                   # name the output folder, not the staging folder
        raise WriteError(folder.path / exc.path.name, exc) from exc
    except OSError as exc:                      # the swap (a rename)
        raise WriteError(folder.path, exc) from exc
    finally:
        folder.close()
    result["figures"] = [str(final / Path(p).name) for p in result["figures"]]
    return result


def _write_all(out, cases: dict, *, structure, units, figure, title, meta, labels, model, load, rule, formats,
               point, storeys, figure_process, summary_extra=None, spectra=None, model_figure=False,
               recorders=None) -> dict:
    """:func:`write_outputs` into the folder ``out`` (the staging folder)."""
    done = compute_results(cases, structure=structure, units=units, figure=figure, title=title, meta=meta,
                           labels=labels, model=model, load=load, rule=rule, point=point, storeys=storeys,
                           summary_extra=summary_extra, spectra=spectra, model_figure=model_figure)
    return write_results(done, out, formats=formats, figure_process=figure_process, recorders=recorders)


@dataclass
class ComputedResults:
    """Every result of solved cases, in memory (:func:`compute_results`), before anything is written.

    Attributes
    ----------
    ds : unilateral.io.dataset.Dataset
        Every history and static result (what ``histories = "full"`` writes to ``results.nc``).
    solutions : dict of str to Solution
        The cases as solved (a case that stopped early: up to where it stopped).
    summary : dict
        ``summary.json`` but its ``output`` (what is written) and ``figures``.
    responses : list of dict
        The response spectra (:func:`unilateral.analysis.spectra.run_spectra`), none without.
    """

    ds: object
    solutions: dict
    summary: dict
    responses: list
    structure: object = None
    units: dict | None = None
    figure: dict | None = None
    title: str = ""
    main_name: str = "unilateral"
    tables: bool = False
    model_figure: bool = False


def compute_results(cases: dict, *, structure=None, units=None, figure=None, title="", meta=None, labels=None,
                    model=None, load=None, rule=None, point=None, storeys=None, summary_extra=None, spectra=None,
                    model_figure=False) -> ComputedResults:
    """The Dataset, spectra and summary of solved ``cases`` (see :func:`write_outputs` for the parameters)."""
    labels = labels or {}
    computed = cases
    cases = _on_common_axis(cases)
    meta = dict(meta or {})
    main_name = "unilateral" if "unilateral" in cases else "bilateral"
    main = cases[main_name]
    if figure is not None:
        meta.update(figure_node=str(figure["node"]), figure_dof=figure["dof"],
                    figure_text=_strip_unit(figure.get("label") or f"{figure['dof']} of node {figure['node']}"))
    if title:
        meta["title"] = title
    ds = cases_dataset(cases, units=units, attrs=meta, footings=getattr(structure, "foundation", None))
    ds.attrs["case_labels"] = json.dumps({name: labels.get(name, name) for name in cases})
    extra_results = None
    if structure is None and model is not None:
        ds = _with_model_kinds(ds, model)
    three_d = is_3d(structure)
    rule = rule or main.stats.get("rule", "bdf2")
    if structure is not None:
        ds = _with_node_displacements(ds, cases, structure, units)
        ds = _with_constraint_coords(ds, structure)
        if model is not None:
            results_of = results_of_load
            if three_d and getattr(structure, "rigid", None) is not None:    # rigid contacts: analysis/rigid3d.py
                from .rigid3d import structure_results_rigid_3d as results_of
            extra_results = results_of(structure, model, computed, load=load, units=units, rule=rule, point=point,
                                       storeys=storeys)
            ds = _with_results(ds, extra_results, "case" in ds.dims, list(cases))
        ds = with_constraint_units(ds, structure, units)
    ds, responses = _with_spectra(ds, structure, extra_results, spectra, dt=_time_step(main), units=units,
                                  names=list(cases), three_d=three_d)
    if model_figure and structure is not None and not three_d:
        ds.attrs["model_drawing"] = _model_drawing(structure, extra_results, units, title).to_json()
    extra = {key: value for key, value in meta.items() if key not in ("figure_node", "figure_dof", "figure_text")}
    result = _summary_of(ds, computed, main_name, extra | (summary_extra or {}), structure=structure, units=units,
                         figure=figure, labels=labels, extra_results=extra_results, rule=rule, responses=responses)
    return ComputedResults(ds, computed, result, responses, structure=structure, units=units, figure=figure,
                           title=title, main_name=main_name, tables=extra_results is not None,
                           model_figure=model_figure)


def _summary_of(ds, computed, main_name, extra, *, structure, units, figure, labels, extra_results, rule,
                responses) -> dict:
    """``summary.json`` of the cases (:func:`compute_results`), without ``output`` and ``figures``."""
    main = computed[main_name]
    if figure is not None and structure is not None:
        histories = {name: structure.node_displacement(sol, figure["node"], figure["dof"])
                     for name, sol in computed.items()}
        extra["figure"] = {
            "node": figure["node"], "dof": figure["dof"],
            "static": float(next(iter(histories.values()))[0]),
            "peak": {label: float(np.max(y)) for label, y in histories.items()},
            "minimum": {label: float(np.min(y)) for label, y in histories.items()},
        }
    if len(computed) > 1 or not main.success:
        extra["cases"] = {name: {"success": sol.success, "message": sol.message,
                                 "steps_computed": len(sol.t) - 1, "t_reached": float(sol.t[-1])}
                          for name, sol in computed.items()}
    kinds = ds["constraint_kind"].values.tolist() if "constraint_kind" in ds.coords else None
    result = summary(main, units=units, extra=extra, kinds=kinds)
    if any(labels.get(name, name) != name for name in computed):
        result["case_labels"] = {name: labels.get(name, name) for name in computed}
    if extra_results is not None:
        result["results"] = to_jsonable(extra_results["peaks"])
        warnings = energy_warnings({case_name(name, labels): p for name, p in result["results"].items()},
                                   rule=rule, dt=main.stats.get("dt"))
        if warnings:
            result["warnings"] = warnings
    if responses:
        from .spectra import spectra_summary

        result["spectra"] = spectra_summary(responses[0])
        if is_3d(structure):
            result["spectra"]["by_direction"] = {each["direction"]: spectra_summary(each) for each in responses}
    if is_3d(structure):
        result["notes"] = [NOT_IN_3D]
    return result


def write_results(done: ComputedResults, out, *, formats=("png",), figure_process=None, recorders=None) -> dict:
    """Write ``results.nc``, the CSV tables, ``summary.json`` and the figures of ``done`` into the folder ``out``
    (a staging folder: :func:`write_outputs` swaps it in); return the summary with ``output`` and ``figures``."""
    ds, structure = done.ds, done.structure
    if formats and figure_process is not None:
        figure_process.submit(figure_view(ds), out, formats)
    output_info = _write_files(ds, out, done.solutions, done.responses, main_name=done.main_name,
                               structure=structure, units=done.units, recorders=recorders, figure=done.figure,
                               tables=done.tables)
    result = dict(done.summary) | {"output": output_info}
    write_json_atomic(out / "summary.json", result)
    result["figures"] = []
    if formats and figure_process is not None:
        result["figures"] = [str(p) for p in figure_process.result()]
    elif formats:                               # matplotlib is imported only to draw
        from ..figures.results import draw_figures

        result["figures"] = [str(p) for p in draw_figures(figure_view(ds), out, formats)]
    if formats and done.model_figure and is_3d(structure):    # drawn here: results.nc holds no 3-D drawing
        from ..figures.model import draw_model
        from ..figures.model3d import model_drawing_3d

        drawing = model_drawing_3d(structure, units=done.units, title=done.title)
        result["figures"] += [str(p) for p in draw_model(drawing, out, formats)]
    return result


def _write_files(ds, out, computed, responses, *, main_name, structure, units, recorders, figure, tables) -> dict:
    """``results.nc`` and the CSV tables of what ``recorders`` write (:func:`unilateral.io.recorders.select`) of
    the Dataset ``ds`` of every result; returns the choice made (``summary.json``'s ``output``)."""
    recorders = Recorders.of(recorders)
    written, info = select(ds, recorders, figure_node=None if figure is None else figure["node"])
    save_netcdf(written, out / "results.nc")
    if not recorders.csv:
        return info
    digits = recorders.precision
    for name, sol in computed.items():
        view = solution_view(written.sel(case=name) if "case" in written.dims else written, sol)
        save_csv(view, out, prefix="" if name == main_name else f"{name}_", precision=digits,
                 column_units=csv_units(view, units, structure))
    if tables:
        every = info["every"]
        _save_result_tables(written, out, main_name=main_name, units=units, precision=digits,
                            rows={name: -(-len(sol.t) // every) for name, sol in computed.items()})
    if responses:
        from .spectra import spectra_columns

        columns = {}
        for each in responses:              # a 3-D frame: every column names its direction
            columns |= _with_direction(spectra_columns(each, {}), each["direction"], units) \
                if is_3d(structure) else spectra_columns(each, units)
        write_text_atomic(out / "spectra.csv", csv_text(columns))
    return info


def _with_direction(columns: dict, direction: str, units) -> dict:
    """The columns of ``spectra.csv`` (:func:`unilateral.analysis.spectra.spectra_columns` without units)
    of a 3-D frame: ``Sa:ground:ux [m/s^2]``, ``Sa:<case>:<node>:ux [m/s^2]`` (the period's column as is)."""
    time, length = ((units or {}).get(k, "") for k in ("time", "length"))
    unit = f" [{length}/{time}^2]" if length and time else ""
    out = {}
    for k, (name, values) in enumerate(columns.items()):
        out[(f"period [{time}]" if time else "period") if k == 0 else f"{name}:{direction}{unit}"] = values
    return out


def _time_step(sol) -> float:
    """The time step of a solution: its ``dt`` statistic, else its first step."""
    dt = sol.stats.get("dt")
    return float(dt) if dt else float(sol.t[1] - sol.t[0])


def _with_spectra(ds, structure, extra_results, spectra, *, dt, units, names, three_d=False):
    """``(ds, responses)``: the Dataset with the response spectra of :func:`unilateral.analysis.spectra.run_spectra`
    and those spectra (a list: one direction for a 2-D frame; for a 3-D frame one per horizontal
    direction of its ground motions, :func:`unilateral.analysis.spectra.directions`, the first as
    ``ground_spectrum`` and ``floor_spectrum``, the next as ``ground_spectrum_uy`` and ``floor_spectrum_uy``);
    ``(ds, [])`` without ``spectra`` settings, structure results or a ground motion."""
    if spectra is None or extra_results is None:
        return ds, []
    from .spectra import directions, run_spectra

    responses = [run_spectra(structure, extra_results, spectra, dt, direction)
                 for direction in (directions(extra_results) if three_d else [None])]
    responses = [response for response in responses if response is not None]
    for k, response in enumerate(responses):
        res = _spectra_results(response, units)
        if k:
            suffix = f"_{response['direction']}"
            res["static"] = {f"{name}{suffix}": value for name, value in res["static"].items()}
            res["variables"] = {f"{name}{suffix}": value for name, value in res["variables"].items()}
        ds = _with_results(ds, res, "case" in ds.dims, names)
    return ds, responses


def _spectra_results(response: dict, units) -> dict:
    """The spectra of :func:`unilateral.analysis.spectra.run_spectra` as results for :func:`_with_results`:
    ``ground_spectrum`` (period) and, with floor nodes, ``floor_spectrum`` (period, floor) per case."""
    length, time = ((units or {}).get(k, "") for k in ("length", "time"))
    unit = {"units": f"{length}/{time}^2"} if length and time else {}
    attrs = {"damping": float(response["damping"]), "direction": response["direction"], **unit}
    period = {"long_name": "period of the oscillators of the response spectra", **({"units": time} if time else {})}
    out = {"coords": {"period": (("period",), response["periods"], period)}, "attrs": {},
           "static": {"ground_spectrum": (("period",), response["ground"], {
               "long_name": f"pseudo-acceleration response spectrum of the ground motion along {response['direction']}",
               **attrs})},
           "variables": {}}
    if response["floors"]:
        out["coords"]["floor"] = (("floor",), [str(node) for node in response["nodes"]],
                                  {"long_name": "the node of each floor spectrum"})
        out["variables"]["floor_spectrum"] = (("period", "floor"), response["floors"], {
            "long_name": f"pseudo-acceleration response spectrum of the absolute acceleration of the node along "
                         f"{response['direction']}", **attrs})
    return out


def _model_drawing(structure, extra_results, units, title):
    """The :class:`~unilateral.figures.model.ModelDrawing` of a frame, with the modes of its results."""
    from ..figures.model import model_drawing

    static = (extra_results or {}).get("static", {})
    shapes, periods = static.get("mode_shape"), static.get("mode_period")
    return model_drawing(structure, shapes=None if shapes is None else shapes[1],
                         periods=None if periods is None else periods[1], units=units, title=title)


def figure_view(ds):
    """The part of a ``results.nc`` Dataset the figures show: every case where all have values.

    ``ds``: an :class:`xarray.Dataset` (``unilateral plot``) or a :class:`unilateral.io.dataset.Dataset`
    (:func:`write_outputs`); the view is of the same type.

    A case that stopped early is NaN after its last step (:func:`write_outputs`); the figures
    then show all cases up to that time (``u`` and ``v`` finite). A Dataset without NaN or
    infinite values is returned as it is.

    Raises
    ------
    unilateral.figures.FigureDataError
        No time step, or ``u`` or ``v`` not finite at t = 0: nothing to draw.
    """
    from ..figures import FigureDataError

    if ds.sizes.get("time", 0) == 0:
        raise FigureDataError("the dimension time has length 0: there is no time step to draw")
    finite = np.ones(ds.sizes["time"], dtype=bool)
    for name in ("v", "u"):
        if name in ds.data_vars and "time" in ds[name].dims:
            values = ds[name].transpose("time", ...).values
            ok = np.isfinite(values.reshape(values.shape[0], -1)).all(axis=1)
            if not ok[0]:
                raise FigureDataError(f"the variable {name} is not finite (inf or NaN) at t = 0: there is "
                                      "nothing to draw")
            finite &= ok
    if finite.all():
        return ds
    return ds.isel(time=slice(0, int(np.argmin(finite))))


def _on_common_axis(cases: dict) -> dict:
    """The cases on the longest time axis: one that stopped early is padded with NaN.

    A failed case (``success=False``) ends where its march stopped; ``results.nc`` holds all cases
    on one time axis, so its values after that are NaN, and every case gets the statistic
    ``steps_computed`` (a variable along ``case`` in ``results.nc``).
    """
    longest = max(cases.values(), key=lambda sol: len(sol.t))
    t = np.asarray(longest.t)
    if all(len(sol.t) == len(t) for sol in cases.values()):
        return cases
    out = {}
    for name, sol in cases.items():
        k = len(sol.t)
        if not np.array_equal(np.asarray(sol.t), t[:k]):
            out[name] = sol                     # another grid: to_dataset says so
            continue
        padded = {key: _pad(getattr(sol, key), len(t)) for key in ("v", "psi", "psiL", "u", "udot")}
        out[name] = Solution(t=t, **padded, success=sol.success, message=sol.message,
                             stats={**sol.stats, "steps_computed": k - 1}, dof_names=sol.dof_names,
                             constraint_names=sol.constraint_names)
    return out


def _pad(values, rows: int):
    if values is None:
        return None
    values = np.asarray(values, dtype=float)
    padded = np.full((rows, *values.shape[1:]), np.nan)
    padded[: len(values)] = values
    return padded


def _stacked(arrays: list, rows: int | None) -> np.ndarray:
    """``np.stack`` of ``arrays`` each padded with NaN to ``rows`` rows (None: as they are), written
    into the result at once (no padded copy of each)."""
    if rows is None:
        return np.stack(arrays)
    arrays = [np.asarray(a, dtype=float) for a in arrays]
    out = np.empty((len(arrays), rows, *arrays[0].shape[1:]))
    for k, a in enumerate(arrays):
        out[k, :len(a)] = a
        out[k, len(a):] = np.nan
    return out


def _strip_unit(label: str) -> str:
    """``"ux of node 7 (m)"`` -> ``"ux of node 7"``: figures state their own (scaled) unit."""
    for opening in (" (", " ["):
        if label.endswith((")", "]")) and opening in label:
            return label[: label.rindex(opening)]
    return label


def is_3d(structure) -> bool:
    """Whether ``structure`` is a 3-D frame (six DOFs per node, :class:`~unilateral.structure.Frame3D`)."""
    return structure is not None and len(getattr(structure.dofs, "dof_names", ())) == 6


#: The note in ``summary.json`` of a 3-D frame: what its run writes, and the outputs that exist only for 2-D frames.
NOT_IN_3D = ("3-D frame: results.nc holds the displacements of every node (ux, uy, uz, rx, ry, rz), the "
             "constraints, the accelerations (relative to the ground and, under ground motions, absolute, of every "
             "free DOF), the element end forces in local axes (N, Vy, Vz, T, My, Mz at each end; element_forces.csv), "
             "the base forces Fx, Fy, Fz, Mx, My, Mz, the support and ground reactions, the interstorey drift ratios "
             "along x and y (the largest over the plan's corners), the energy balance (base.csv), the response "
             "spectra along x and y (spectra.csv), the modes of the bilateral structure and the yield and slip "
             "histories of hinges, yield links, friction contacts and sliders (results.nc, yield_and_slip.csv, "
             "summary.json; a hinge's plastic rotations and end moments about y' and z', a friction cone's slip and "
             "tangential force along t1 and t2, with the component dimension yield_component or "
             "friction_component; the hysteresis figure along the component of the larger peak); model.png is "
             "drawn without modes, and unilateral plot does not redraw it. Not written (2-D frames only): the "
             "constraints' deformations, the interstorey drifts themselves and the residual drift, the base shear "
             "of each separate frame and its periods, and the base forces figure; a 3-D model file cannot ask for "
             "floor_spectra yet (the model file's check refuses them)")


def _with_results(ds, res, multi, names):
    """Add the structure's results to the Dataset (a ``case`` dim if ``multi``)."""
    coords = {}
    for key, value in res["coords"].items():
        coords[key] = value
    ds = ds.assign_coords(coords)
    new = {}
    for name, (dims, per_case, attrs) in res["variables"].items():
        if not all(case in per_case for case in names):
            continue
        if multi:
            rows = ds.sizes["time"] if dims[0] == "time" else None    # a case that stopped early: NaN after
            new[name] = Variable(("case", *dims), _stacked([per_case[case] for case in names], rows), attrs)
        else:
            new[name] = Variable(dims, per_case[names[0]], attrs)
    for name, (dims, data, attrs) in res["static"].items():
        new[name] = Variable(dims, data, attrs)
    ds = ds.assign(new)
    for key, value in res["attrs"].items():
        ds.attrs[key] = value
    return ds


def _with_constraint_coords(ds, structure):
    """Position, kind and gap of each constraint unknown, as coordinates along ``constraint``.

    The kind of a contact is its element's (``soil``, ``gap``, ``cable``), that of a plastic
    multiplier ``yield`` and of a slip ``friction``.
    """
    footings = getattr(structure, "foundation", None)
    if footings is not None and "constraint" in ds.dims:
        own = _own_constraint_coords(structure) if structure.m else None
        patches = footings.constraint_coords()                     # the footings' patches follow
        if own is not None:
            patches = {key: ("constraint", list(own[key][1]) + list(value[1])) for key, value in patches.items()}
        return ds.assign_coords(patches)
    if not structure.m:
        return ds
    return ds.assign_coords(_own_constraint_coords(structure))


def _own_constraint_coords(structure) -> dict:
    """x, y, kind and gap of the frame's own constraint unknowns (see :func:`_with_constraint_coords`)."""
    x, y, kind, gap = [], [], [], []
    for e, u in structure.constraints:
        nodes = [u.node] if u.node is not None else [node for node, _ in e.dofs]
        xy = np.mean([structure.coords[node] for node in nodes], axis=0) if structure.coords else (np.nan, np.nan)
        x.append(float(xy[0]))
        y.append(float(xy[1]))
        contact = u.kind == "contact"
        kind.append(e.kind if contact else u.kind)
        gap.append(float(-e.theta[u.row]) if contact and e.kind != "cable" else 0.0)
    return {"constraint_x": ("constraint", x), "constraint_y": ("constraint", y),
            "constraint_kind": ("constraint", kind), "constraint_gap": ("constraint", gap)}


def _with_model_kinds(ds, model):
    """The family of each unknown of a model without a structure as ``constraint_kind`` (``contact``,
    ``yield``, ``friction``), if it has other unknowns than contacts."""
    kinds = getattr(getattr(model, "law", None), "kinds", ())
    if "constraint" not in ds.dims or not set(kinds) - {"contact"}:
        return ds
    return ds.assign_coords(constraint_kind=("constraint", list(kinds)))


#: Columns of ``yield_and_slip.csv``: the variables of :mod:`unilateral.analysis.inelastic`.
INELASTIC_COLUMNS = {"yield_element": ("plastic_deformation", "yield_force", "yield_ratio"),
                     "friction_element": ("slip", "friction_force", "normal_force")}


def _save_result_tables(ds, out, *, main_name, rows=None, units=None, precision="float64"):
    """``element_forces.csv``, ``base.csv`` and ``yield_and_slip.csv`` of every case: the main case's
    without prefix, the others' as ``<case>_<file>`` (``bilateral_base.csv``), as the displacements.
    ``rows``: case -> the number of time steps it computed (a case that stopped early ends there)."""
    names = [str(c) for c in ds["case"].values] if "case" in ds.dims else [main_name]
    for name in names:
        d = ds.sel(case=name) if "case" in ds.dims else ds
        if rows and name in rows:
            d = d.isel(time=slice(0, rows[name]))
        _save_case_tables(d, out, prefix="" if name == main_name else f"{name}_", units=units or {},
                          precision=precision)


def _save_case_tables(d, out, *, prefix, units, precision="float64"):
    force, length, time = (units.get(k, "") for k in ("force", "length", "time"))
    moment = f"{force} {length}".strip()
    t = d["time"].values
    if "end_force" in d:
        end = d["end_force"].values
        columns = {_head("time", time): t}
        for k, name in enumerate(d["element"].values):
            for c, comp in enumerate(d["end_component"].values):
                columns[_head(f"{name}:{comp}", moment if str(comp).startswith(("M", "T")) else force)] = end[:, k, c]
        write_text_atomic(out / f"{prefix}element_forces.csv", csv_text(columns, precision))
    columns = {_head("time", time): t}
    for name, unit in (("base_shear", force), ("base_vertical", force), ("overturning_moment", moment)):
        if name in d:
            columns[_head(name, unit)] = d[name].values
    for key in ("Fx", "Fy", "Fz", "Mx", "My", "Mz"):            # a 3-D frame
        if f"base_{key}" in d:
            columns[_head(f"base_{key}", force if key.startswith("F") else moment)] = d[f"base_{key}"].values
    if "support_reaction" in d:
        for k, label in enumerate(d["support"].values):
            unit = moment if str(label).rsplit(".", 1)[-1].startswith("r") else force
            columns[_head(f"reaction:{label}", unit)] = d["support_reaction"].values[:, k]
    if "drift_ratio" in d:
        for k, label in enumerate(d["storey"].values):
            columns[_head(f"drift_ratio:{label}", "1")] = d["drift_ratio"].values[:, k]
    for name in d.data_vars:
        if str(name).startswith("energy_"):
            columns[_head(str(name), "1" if str(name) == "energy_relative_error" else moment)] = d[name].values
    for axis in "xy":                                           # a 3-D frame: its drift ratios last
        if f"drift_ratio_{axis}" in d:
            for k, label in enumerate(d["storey"].values):
                columns[_head(f"drift_ratio_{axis}:{label}", "1")] = d[f"drift_ratio_{axis}"].values[:, k]
    write_text_atomic(out / f"{prefix}base.csv", csv_text(columns, precision))
    columns = {_head("time", time): t}
    for dim, names in INELASTIC_COLUMNS.items():
        for name in (name for name in names if name in d):
            values = d[name].values
            for k, label in enumerate(d[dim].values):
                unit = _inelastic_unit(d, name, k, units)
                if values.ndim == 2:
                    columns[_head(f"{name}:{label}", unit)] = values[:, k]
                    continue
                parts = [str(c) for c in d[dim.replace("element", "component_name")].values[k]]
                for j, part in enumerate(parts):       # a 3-D frame: each component (one: as in 2-D)
                    if part:
                        head = f"{name}:{label}:{part}" if sum(map(bool, parts)) > 1 else f"{name}:{label}"
                        columns[_head(head, unit)] = values[:, k, j]
    if len(columns) > 1:
        write_text_atomic(out / f"{prefix}yield_and_slip.csv", csv_text(columns, precision))


def _head(name: str, unit: str) -> str:
    """A CSV column header with its unit: ``base_shear [kN]`` (``[1]``: dimensionless)."""
    return f"{name} [{unit}]" if unit else name


def _inelastic_unit(d, name, k, units) -> str:
    """The unit of column ``k`` of ``name`` in ``yield_and_slip.csv``: rotations of hinges in rad."""
    force, length = units.get("force", ""), units.get("length", "")
    if name == "yield_ratio":
        return "1"
    rotational = name in ("plastic_deformation", "yield_force") and "yield_deformation_unit" in d and \
        str(d["yield_deformation_unit"].values[k]) == "rad"
    if name in ("plastic_deformation", "slip"):
        return "rad" if rotational else length
    return f"{force} {length}".strip() if rotational else force


def csv_units(sol, units, structure=None) -> dict:
    """Units of the columns of ``displacements.csv`` and ``constraints.csv`` (:func:`unilateral.io.save_csv`):
    ``time``, DOFs (``.rz``: rad), ``v``, ``psi``, ``psiL`` (the multipliers of a hinge or of a
    link along a rotation of ``structure``: rad, their moments in force x length)."""
    from .inelastic import rotational_unknowns

    units = units or {}
    force, length, time = (units.get(k, "") for k in ("force", "length", "time"))
    out = {"time": time}
    for name in sol.dof_names or ():
        out[name] = "rad" if str(name).endswith(("rx", "ry", "rz")) else length
    rotational = rotational_unknowns(structure) if structure is not None else set()
    for c in sol.constraint_names or ():
        hinge = c in rotational
        out[f"v:{c}"] = "rad" if hinge else length
        for key in ("psi", "psiL"):
            out[f"{key}:{c}"] = f"{force} {length}".strip() if hinge else force
    return out


def _with_unit(label, units, dof):
    """Append the unit to an axis label that does not state one already."""
    unit = (units or {}).get("length", "") if dof != "rz" else "rad"
    return f"{label} [{unit}]" if unit and not any(c in label for c in "[(") else label


def _with_node_displacements(ds, cases, structure, units):
    nodes = list(structure.dofs.nodes)
    names = list(getattr(structure.dofs, "dof_names", COMPONENTS))
    data = np.stack([structure.dofs.nodal(sol.u) for sol in cases.values()])
    if "case" not in ds.dims:
        data = data[0]
        dims = ("time", "node", "component")
    else:
        dims = ("case", "time", "node", "component")
    var = Variable(dims, data, {"long_name": "displacements of every node (supported and rigidly linked included)"})
    if units and "length" in units:
        translations = ", ".join(name for name in names if name.startswith("u"))
        rotations = ", ".join(name for name in names if name.startswith("r"))
        var.attrs["units"] = f"{units['length']} ({translations}); rad ({rotations})"
    return ds.assign_coords(node=[str(n) for n in nodes], component=names).assign(node_displacement=var)
