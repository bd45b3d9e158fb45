"""The example ``footings``: a two-bay frame on two footings on one layered soil.

:func:`run_footings_example` solves :func:`unilateral.structure.examples.two_bay_on_footings` (a soft
layer over stiffer ground, a synthetic earthquake) with uplift and yielding (the case
``unilateral``) and with every contact and hinge held (``bilateral``), a second time, with
uplift and yielding, on soils that do not interact (each footing on its own copy of the site: a
block-diagonal ``Phi``), and a third time on one soil with footings that also slide (horizontal
soil forces limited by friction, ``mu`` = :data:`MU`). It writes

* ``results_one_soil.nc`` (both cases), ``results_own_soils.nc`` and ``results_sliding.nc`` (the
  case ``unilateral``): each run's ``results.nc``, with the patch extents of the footings
  (:func:`unilateral.analysis.halfspace_example.run_dataset`);
* ``results.nc``, the CSV tables, ``summary.json`` and the figures of the footings on one soil
  (:func:`unilateral.analysis.write_outputs`); ``results.nc`` lists the run files in its attribute
  ``run_files``, ``summary.json`` under ``extra.run_files``, and the peaks of both runs under
  ``extra.comparison`` (run, then case);
* ``footings.png`` (:func:`draw_comparison`), drawn from the run files' Datasets: the two runs side
  by side, so the interaction through the ground shows as the difference: the motion of the outer
  edges (positive: up), the vertical force on each footing, its change caused by the other
  footing, the roof displacement, and the slip of each footing on the soil in the sliding run.
  ``unilateral plot results.nc`` redraws it from the run files next to it.
"""

from __future__ import annotations

import numpy as np

DEFAULTS = {"dt": 0.005, "t_end": 6.0}
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}
#: The two runs: their names (``soil`` attribute, keys of ``extra.comparison``), file stems and line styles.
ONE, OWN, SLIDE = "one soil", "each footing on its own soil", "one soil, sliding"
RUNS = {ONE: ("one_soil", "-"), OWN: ("own_soils", "--"), SLIDE: ("sliding", ":")}
#: The footings' friction coefficient on the soil in the sliding run.
MU = 0.4
COLOURS = ("tab:blue", "tab:red", "tab:green", "tab:purple")


def uncoupled(model, structure):
    """The same model with each footing on its own soil (no interaction through the ground)."""
    from ..soil.flexibility import SoilFlexibility
    from ..soil.foundation_model import FoundationModel

    soil = SoilFlexibility.block_diagonal([f.soil for f in structure.foundation.footings])
    return FoundationModel.on(model.structure, model.T, soil, gap=model.gap, contact_names=model.contact_names)


def outer_edges(ds, footings) -> dict:
    """The outer edge of each footing: ``(x, "left" or "right")``, on the side away from the centre
    of all the footings."""
    from .halfspace_example import footing_extent

    extents = {name: footing_extent(ds, name) for name in footings}
    centre = 0.5 * (min(lo for lo, _ in extents.values()) + max(hi for _, hi in extents.values()))
    return {name: (lo, "left") if lo + hi < 2 * centre else (hi, "right") for name, (lo, hi) in extents.items()}


def draw_comparison(datasets, path_without_suffix, formats=("png",)) -> list:
    """The figure ``footings``: outer-edge uplift, footing forces, roof drift and slip, one soil against own
    soils and sliding.

    Parameters
    ----------
    datasets : iterable of Dataset
        The three runs' Datasets (:func:`~unilateral.analysis.halfspace_example.run_dataset`, or the
        run files read back), each with the attribute ``soil`` (:data:`ONE`, :data:`OWN`, :data:`SLIDE`).
    path_without_suffix : path
        ``out/footings`` gives ``out/footings.png``.
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
    from .halfspace_example import case_values, footing_names, footing_patches, node_history, runs_by

    runs = runs_by(datasets, "soil")
    missing = [label for label in RUNS if (label,) not in runs]
    if missing:
        raise FigureDataError(f"the run(s) {', '.join(missing)} are missing")
    fig, axes = _figure((9.0, 12.0), nrows=5, ncols=1, sharex="col", squeeze=False,
                        margins=(0.9, 0.2, 0.6, 0.6), gaps=(0.8, 0.3))
    first = runs[(ONE,)]
    footings = footing_names(first)
    edges = outer_edges(first, footings)
    forces = {}
    for label, (_, style) in RUNS.items():
        ds = runs[(label,)]
        t = np.asarray(ds["time"].values)
        psi = case_values(ds, "psi", "unilateral")
        for k, name in enumerate(footings):
            x, side = edges[name]
            colour = COLOURS[k % len(COLOURS)]
            axes[0, 0].plot(t, 1e3 * _edge_motion(ds, name, x), color=colour, ls=style, lw=1.0,
                            label=f"footing {name}, {side} edge, {label}")
            forces[label, name] = -psi[:, footing_patches(ds, name)].sum(axis=1)
            axes[1, 0].plot(t, forces[label, name], color=colour, ls=style, lw=1.0, label=f"footing {name}, {label}")
        axes[3, 0].plot(t, 1e3 * node_history(ds, "unilateral", *_roof(ds)), color="k", ls=style, lw=1.0,
                        label=label)
    sliding = runs[(SLIDE,)]
    for k, name in enumerate(footings):
        axes[4, 0].plot(sliding["time"].values, 1e3 * footing_slip(sliding, name), color=COLOURS[k % len(COLOURS)],
                        lw=1.0, label=f"footing {name}, {SLIDE} (mu = {sliding.attrs.get('mu', MU):g})")
    t = np.asarray(first["time"].values)
    for k, name in enumerate(footings):
        n = min(len(forces[ONE, name]), len(forces[OWN, name]))
        axes[2, 0].plot(t[:n], forces[ONE, name][:n] - forces[OWN, name][:n], color=COLOURS[k % len(COLOURS)],
                        lw=1.0, label=f"footing {name}")
    axes[0, 0].set_ylabel("uy of the outer edge [mm]")
    axes[1, 0].set_ylabel("vertical force on the footing [kN]")
    axes[2, 0].set_ylabel("force: one soil - own soils [kN]")
    axes[3, 0].set_ylabel("roof {1}, node {0} [mm]".format(*_roof(first)))
    axes[4, 0].set_ylabel("slip on the soil [mm]")
    axes[4, 0].set_xlabel("time [s]")
    for ax in axes[:, 0]:
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle("Two footings on a soft layer: on one soil (solid), each on its own soil (dashed),\n"
                 "on one soil and sliding (dotted)", fontsize=10)
    return save_figure(fig, path_without_suffix, formats)


def footing_slip(ds, footing: str) -> np.ndarray:
    """The mean net slip (N+1,) of a footing's patches on the soil (length, +x), case ``unilateral``:
    ``v`` of its shears (constraints ``<footing>.<j>.shear``)."""
    from ..figures import FigureDataError
    from .halfspace_example import case_values

    names = np.asarray(ds["constraint"].values).astype(str)
    cols = [i for i, n in enumerate(names) if n.startswith(f"{footing}.") and n.endswith(".shear")]
    if not cols:
        raise FigureDataError(f"the Dataset has no shears of footing {footing!r} (a run whose footings slide)")
    return case_values(ds, "v", "unilateral")[:, cols].mean(axis=1)


def _roof(ds) -> tuple[str, str]:
    """The node and DOF of the roof displacement: the attributes ``figure_node`` and ``figure_dof``."""
    from ..figures import FigureDataError

    if "figure_node" not in ds.attrs or "figure_dof" not in ds.attrs:
        raise FigureDataError("a run's Dataset lacks the attributes figure_node and figure_dof (the roof)")
    return str(ds.attrs["figure_node"]), str(ds.attrs["figure_dof"])


def _edge_motion(ds, footing: str, x: float) -> np.ndarray:
    """Upward motion (N+1,) of a rigid footing's point at abscissa ``x`` in the case ``unilateral``."""
    from .halfspace_example import rigid_motion

    x0, uy, rz = rigid_motion(ds, "unilateral", footing)
    return uy + (x - x0) * rz


def run_footings_example(out, *, figures=("png",), progress=None, figure_process=None, dt=None, t_end=None,
                         method=None, rule=None, lcp=None, initial=None) -> dict:
    """Run the example and write its outputs to ``out``; return the summary dict (as ``run_example``).

    The output folder is checked before anything is solved; the run files are written into its
    staging folder first, then the outputs of the footings on one soil
    (:func:`unilateral.analysis.outputs.write_outputs`, which lists them all in ``manifest.json``).
    """
    from ..io.folder import OutputFolder
    from ..structure.examples import two_bay_on_footings
    from .halfspace_example import example_labels, run_dataset, write_runs
    from .outputs import write_outputs

    if initial not in (None, "static"):
        raise ValueError(f"initial={initial!r}: the footings example starts from the static state only")
    settings = dict(dt=dt or DEFAULTS["dt"], t_end=t_end or DEFAULTS["t_end"], method=method or "cq",
                    rule=rule or "bdf2", lcp=lcp or "bpp")
    folder = OutputFolder(out)
    staging = folder.prepare()
    try:
        structure, load, info = two_bay_on_footings()
        sliding, sliding_load, _ = two_bay_on_footings(mu=MU)     # the footings' ux are free: other DOFs
        structures = {ONE: structure, OWN: structure, SLIDE: sliding}
        loads = {ONE: load, OWN: load, SLIDE: sliding_load}
        models = {ONE: structure.to_model(), SLIDE: sliding.to_model()}
        models[OWN] = uncoupled(models[ONE], structure)
        solved = _solve_runs(models, loads, settings, progress)
        datasets = {RUNS[label][0]: run_dataset(
            cases, structure=structures[label], model=models[label], load=loads[label], figure=info["figure"],
            rule=settings["rule"], meta={"example": "footings", "soil": label, "figure_prefix": f"{RUNS[label][0]}_",
                                         "title": f"Two-bay frame on two footings, {label}"}
            | ({"mu": MU} if label == SLIDE else {}))
            for label, cases in solved.items()}
        files = write_runs(datasets, staging)
        comparison = {label: {case: _peaks(structures[label], sol, info["figure"]) for case, sol in cases.items()}
                      for label, cases in solved.items()}
        result = write_outputs(
            folder, solved[ONE], structure=structure, units=UNITS_KN, figure=info["figure"],
            title="Two-bay frame on two footings on a soft layer over stiffer ground, synthetic earthquake",
            meta={"example": "footings", "soil": ONE, "run_files": files,
                  "model": "unilateral.structure.examples.two_bay_on_footings"},
            labels=example_labels(datasets[RUNS[ONE][0]]), model=models[ONE], load=load, rule=settings["rule"],
            formats=figures, figure_process=figure_process, summary_extra={"comparison": comparison},
            extra_figures=lambda where, formats: draw_comparison(datasets.values(), where / "footings", formats))
    finally:
        folder.close()
    result["comparison"] = comparison
    result["success_all"] = all(sol.success for cases in solved.values() for sol in cases.values())
    if progress is not None:
        progress(1, 1)
    return result


def _solve_runs(models: dict, loads: dict, settings: dict, progress) -> dict:
    """``{ONE: {"unilateral": sol, "bilateral": sol}, OWN: {"unilateral": sol}, SLIDE: {...}}``, reporting
    progress."""
    from ..solve import solve

    wanted = {ONE: ("unilateral", "bilateral"), OWN: ("unilateral",), SLIDE: ("unilateral",)}
    total = sum(map(len, wanted.values())) + 1
    solved, done = {}, 0
    for label, cases in wanted.items():
        solved[label] = {}
        for case in cases:
            solved[label][case] = solve(models[label], loads[label], bilateral=case == "bilateral", **settings)
            done += 1
            if progress is not None:
                progress(done, total)
    return solved


def _peaks(structure, sol, roof: dict) -> dict:
    """The peaks of one case of a run for ``summary.json`` (``extra.comparison``); ``roof``: the node
    and DOF of the roof displacement (the example's ``figure``)."""
    footings = structure.foundation
    out = {"max_uplift": float(np.max(sol.v[:, footings.first:footings.first + footings.m])),
           "success": bool(sol.success),
           "max_roof_ux": float(np.abs(structure.node_displacement(sol, roof["node"], roof["dof"])).max()),
           "contact_changes": int(sol.stats.get("contact_changes", 0))}
    if footings.sliding:
        out["max_slip"] = float(np.abs(footings.slips(sol)).max())
    return out
