"""The example ``footings``: a two-bay frame on two footings on one layered soil.

:func:`run_footings_example` solves :func:`unilateral.structure.examples.two_bay_on_footings` (a soft
layer over stiffer ground, a synthetic earthquake) with uplift and yielding, and with every
contact and hinge held (the linear case), and writes their outputs
(:func:`unilateral.analysis.write_outputs`). A third run takes the same footings on soils that do
not interact (each footing on its own copy of the site: a block-diagonal ``Phi``): the figure
``footings.png`` sets the two side by side, so the interaction through the ground shows as the
difference: the motion of the outer edges (positive: up), the vertical force on each footing, its
change caused by the other footing, and the roof displacement. The peaks of both runs are in
``summary.json`` under ``extra.comparison``. ``unilateral plot`` redraws the figures of
``results.nc`` (the coupled soil), not ``footings.png``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

DEFAULTS = {"dt": 0.005, "t_end": 6.0}
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}


def uncoupled(model, structure):
    """The same model with each footing on its own soil (no interaction through the ground)."""
    from ..soil.foundation_model import FoundationModel, SoilFlexibility

    soil = SoilFlexibility.block_diagonal([f.soil for f in structure.foundation.footings])
    return FoundationModel.on(model.structure, model.T, soil, gap=model.gap, contact_names=model.contact_names)


def edge_uplift(structure, sol, footing, x):
    """Upward displacement (N+1,) of a rigid footing's point at abscissa ``x``."""
    node = footing.node
    x0 = structure.coords[node][0]
    return structure.node_displacement(sol, node, "uy") + (x - x0) * structure.node_displacement(sol, node, "rz")


def draw_comparison(structure, runs: dict, edges: dict, path_without_suffix, formats=("png",)) -> list:
    """The figure ``footings``: outer-edge uplift, footing forces and roof drift, coupled vs not."""
    from ..figures.plots import _figure, save_figure

    fig, axes = _figure((9.0, 10.0), nrows=4, ncols=1, sharex="col", squeeze=False,
                        margins=(0.9, 0.2, 0.6, 0.6), gaps=(0.8, 0.3))
    footings = structure.foundation.footings
    colours = {"A": "tab:blue", "B": "tab:red"}
    first = structure.foundation.first
    forces = {}
    for label, (sol, style) in runs.items():
        start = first
        for f in footings:
            x = edges[f.name][0] if f.name == "A" else edges[f.name][1]
            axes[0, 0].plot(sol.t, 1e3 * edge_uplift(structure, sol, f, x), color=colours[f.name], ls=style, lw=1.0,
                            label=f"footing {f.name}, {'left' if f.name == 'A' else 'right'} edge, {label}")
            forces[label, f.name] = -sol.psi[:, start:start + f.m].sum(axis=1)
            axes[1, 0].plot(sol.t, forces[label, f.name], color=colours[f.name], ls=style, lw=1.0,
                            label=f"footing {f.name}, {label}")
            start += f.m
        axes[3, 0].plot(sol.t, 1e3 * structure.node_displacement(sol, 21, "ux"), color="k", ls=style, lw=1.0,
                        label=label)
    together, apart = list(runs)
    for f in footings:
        n = min(len(forces[together, f.name]), len(forces[apart, f.name]))
        axes[2, 0].plot(runs[together][0].t[:n], forces[together, f.name][:n] - forces[apart, f.name][:n],
                        color=colours[f.name], lw=1.0, label=f"footing {f.name}")
    axes[0, 0].set_ylabel("uy of the outer edge [mm]")
    axes[1, 0].set_ylabel("vertical force on the footing [kN]")
    axes[2, 0].set_ylabel("force: one soil - own soils [kN]")
    axes[3, 0].set_ylabel("roof ux, node 21 [mm]")
    axes[3, 0].set_xlabel("time [s]")
    for ax in axes[:, 0]:
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.legend(fontsize=7, loc="upper right")
    fig.suptitle("Two-bay frame on two footings on a soft layer: the footings interact through the ground "
                 "(solid) or not (dashed)", fontsize=10)
    return save_figure(fig, path_without_suffix, formats)


def run_footings_example(out, *, figures=("png",), progress=None, figure_process=None, dt=None, t_end=None,
                         method=None, rule=None, lcp=None, initial=None) -> dict:
    """Run the example and write its outputs to ``out``; return the summary dict (as ``run_example``)."""
    from ..solve import solve
    from ..structure.examples import two_bay_on_footings
    from .outputs import write_outputs

    if initial not in (None, "static"):
        raise ValueError(f"initial={initial!r}: the footings example starts from the static state only")
    structure, load, info = two_bay_on_footings()
    model = structure.to_model()
    settings = dict(dt=dt or DEFAULTS["dt"], t_end=t_end or DEFAULTS["t_end"], method=method or "cq",
                    rule=rule or "bdf2", lcp=lcp or "bpp")
    cases, done = {}, 0

    def step(sol):
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, 4)
        return sol

    for case in ("unilateral", "bilateral"):
        cases[case] = step(solve(model, load, bilateral=case == "bilateral", **settings))
    apart = step(solve(uncoupled(model, structure), load, **settings))
    runs = {"one soil": (cases["unilateral"], "-"), "each footing on its own soil": (apart, "--")}
    first = structure.foundation.first
    comparison = {label: {"max_uplift": float(np.max(sol.v[:, first:])), "success": bool(sol.success),
                          "max_roof_ux": float(np.abs(structure.node_displacement(sol, 21, "ux")).max()),
                          "contact_changes": int(sol.stats.get("contact_changes", 0))}
                  for label, (sol, _) in runs.items()}
    result = write_outputs(Path(out), cases, structure=structure, units=UNITS_KN, figure=info["figure"],
                           title="Two-bay frame on two footings on a soft layer over stiffer ground, synthetic "
                                 "earthquake",
                           meta={"example": "footings", "model": "unilateral.structure.examples.two_bay_on_footings"},
                           labels={"unilateral": "with yield and uplift", "bilateral": "linear (constraints held)"},
                           model=model, load=load, rule=settings["rule"], formats=figures,
                           figure_process=figure_process,
                           extra_figures=lambda folder, formats: draw_comparison(structure, runs, info["edges"],
                                                                                 folder / "footings", formats),
                           summary_extra={"comparison": comparison})
    result["comparison"] = comparison
    result["success_all"] = all(sol.success for sol in (*cases.values(), apart))
    if progress is not None:
        progress(1, 1)
    return result
