"""The example ``halfspace``: the paper's tower on three soils, with and without uplift, two loads.

:func:`run_halfspace_example` solves :func:`unilateral.structure.examples.halfspace_tower` on the
paper's Winkler-Kelvin soil, on Wolf's cones and on the rigorous half-space, each with uplift
(unilateral contact) and without (contacts held), under the paper's pulse and under a synthetic
earthquake: 12 runs. It writes the outputs of the half-space under the earthquake (``results.nc``,
CSV tables, ``summary.json``, figures; :func:`unilateral.analysis.write_outputs`) and the
comparison figure ``halfspace.png``: uplift of the footing's left edge, rocking and the contact
pressure under the left strip, side by side for the two loads.

``results.nc`` (and so ``unilateral plot``, which redraws the figures of ``results.nc``) holds the
half-space under the earthquake only; ``halfspace.png`` is listed in ``manifest.json`` but drawn
from all 12 runs, so ``unilateral plot`` does not redraw it: run the example again. The peaks of
every run are in ``summary.json`` under ``extra.comparison``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

#: Time step and end time of each load (s): the whole example runs in seconds.
DEFAULTS = {"pulse": {"dt": 2e-3, "t_end": 1.5}, "earthquake": {"dt": 2e-3, "t_end": 8.0}}
UNITS_KN = {"length": "m", "force": "kN", "time": "s"}
SOIL_LABELS = {"winkler-kelvin": "paper's Winkler-Kelvin", "cones": "cones", "halfspace": "half-space"}
COLOURS = {"winkler-kelvin": "tab:blue", "cones": "tab:green", "halfspace": "tab:red"}


def solve_all(*, dt=None, t_end=None, method="cq", rule="bdf2", lcp="bpp", progress=None) -> dict:
    """Solve the 12 runs: ``{(soil, load): (structure, load, info, {"unilateral": sol, "bilateral": sol})}``.

    One model per soil is shared by both loads and both cases, so the soil's weights are computed
    once per time step (:meth:`unilateral.soil.SoilFlexibility.cq_weights`).
    """
    from ..solve import solve
    from ..structure.examples import HALFSPACE_SOILS, halfspace_tower

    out, done, total = {}, 0, 4 * len(HALFSPACE_SOILS)
    for soil in HALFSPACE_SOILS:
        model = None
        for load_name in ("pulse", "earthquake"):
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


def draw_comparison(runs: dict, path_without_suffix, formats=("png",)) -> list:
    """The figure ``halfspace``: 3 rows (edge uplift, rocking, left-strip pressure) x 2 loads."""
    from ..figures.plots import _figure, save_figure

    fig, axes = _figure((11.0, 8.0), nrows=3, ncols=2, sharex="col", squeeze=False,
                        margins=(0.9, 0.2, 0.6, 0.6), gaps=(0.8, 0.3))
    titles = {"pulse": "the paper's pulse (200 kN, 0.1 s)", "earthquake": "synthetic earthquake (PGA 5 m/s$^2$)"}
    for col, load_name in enumerate(("pulse", "earthquake")):
        for soil in SOIL_LABELS:
            structure, _, info, cases, _ = runs[(soil, load_name)]
            fnd = structure.foundation
            area = float(fnd.patches.areas[0])
            for case, style in (("unilateral", "-"), ("bilateral", "--")):
                sol = cases[case]
                uy = structure.node_displacement(sol, 2, "uy")
                rz = structure.node_displacement(sol, 2, "rz")
                edge = uy + info["edge"] * rz
                pressure = -sol.psi[:, 0] / area
                label = f"{SOIL_LABELS[soil]}, {'with' if case == 'unilateral' else 'without'} uplift"
                kw = dict(color=COLOURS[soil], ls=style, lw=1.0 if case == "unilateral" else 0.8, label=label)
                axes[0, col].plot(sol.t, 1e3 * edge, **kw)
                axes[1, col].plot(sol.t, 1e3 * rz, **kw)
                axes[2, col].plot(sol.t, pressure, **kw)
        axes[0, col].set_title(titles[load_name], fontsize=10)
        axes[2, col].set_xlabel("time [s]")
        for row in range(3):
            axes[row, col].axhline(0.0, color="0.6", lw=0.5)
    axes[0, 0].set_ylabel("uy of the left edge [mm]")
    axes[1, 0].set_ylabel("rocking rz [mrad]")
    axes[2, 0].set_ylabel("pressure, left strip [kPa]")
    axes[0, 0].legend(fontsize=7, loc="upper right")
    fig.suptitle("Tower on a rigid footing: Winkler-Kelvin soil, cones and the elastic half-space", fontsize=11)
    return save_figure(fig, path_without_suffix, formats)


def run_halfspace_example(out, *, figures=("png",), progress=None, figure_process=None, dt=None, t_end=None,
                          method=None, rule=None, lcp=None, initial=None) -> dict:
    """Run the example and write its outputs to ``out``; return the summary dict (as ``run_example``).

    The outputs of the half-space under the earthquake (with and without uplift) are written by
    :func:`unilateral.analysis.outputs.write_outputs`; ``halfspace.png`` (and the other formats
    of ``figures``) is the comparison of the three soils and two loads.
    """
    from .outputs import write_outputs

    if initial not in (None, "static"):
        raise ValueError(f"initial={initial!r}: the halfspace example starts from the static state only")
    runs = solve_all(dt=dt, t_end=t_end, method=method or "cq", rule=rule or "bdf2", lcp=lcp or "bpp",
                     progress=progress)
    structure, load, info, cases, model = runs[("halfspace", "earthquake")]
    comparison = {
        f"{soil}/{load_name}": {case: {"max_uplift": float(np.max(sol.v)), "success": bool(sol.success),
                                       "max_contact_force": float(np.max(-sol.psi)),
                                       "contact_changes": int(sol.stats.get("contact_changes", 0))}
                                for case, sol in runs[(soil, load_name)][3].items()}
        for soil, load_name in runs}
    out = Path(out)
    result = write_outputs(out, cases, structure=structure, units=UNITS_KN, figure=info["figure"],
                           title="Tower on a rigid footing on the elastic half-space, synthetic earthquake",
                           meta={"example": "halfspace", "model": "docs/theory.md section 12; "
                                 "unilateral.structure.examples.halfspace_tower"},
                           labels={"unilateral": "with uplift", "bilateral": "without uplift"}, model=model,
                           load=load, rule=rule or "bdf2", formats=figures, figure_process=figure_process,
                           extra_figures=lambda folder, formats: draw_comparison(runs, folder / "halfspace", formats),
                           summary_extra={"comparison": comparison})
    result["comparison"] = comparison
    result["success_all"] = all(sol.success for run in runs.values() for sol in run[3].values())
    if progress is not None:
        progress(1, 1)
    return result
