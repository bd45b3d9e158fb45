"""A pushover from a model file (``[analysis] type = "pushover"``) and its outputs.

:func:`run_file` runs the ``[pushover]`` of a model file read by
:func:`unilateral.modelfile.load_model_file` and writes, through an
:class:`~unilateral.io.folder.OutputFolder` (all files or none):

* ``pushover.csv``: one row per point of the path (the gravity state, every event, each target):
  the path parameter, the load factor, the control displacement, the roof drift (the control
  displacement over the control node's height above the lowest node, for ``ux``), the base shear
  and the events at the point;
* ``events.csv``: one row per event (load factor, control displacement, base shear, constraint, kind);
* ``summary.json``: the run (success, message, stats), the peak base shear, the first event, the
  end state, units;
* ``capacity_curve.<format>``: base shear against roof drift, the events marked.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np

from .api import pushover
from .patterns import vertical_axis

#: ``[pushover] p_delta`` -> the ``p_delta`` argument of :func:`pushover`.
_P_DELTA = {None: None, "none": False, "consistent": "consistent", "string": "string"}


def run_file(spec, out, *, figures=("png",), bilateral=False, **overrides) -> dict:
    """Run the ``[pushover]`` of a model file and write its outputs to ``out``.

    Parameters
    ----------
    spec : ModelSpec (:func:`unilateral.modelfile.load_model_file`) of a file with
        ``[analysis] type = "pushover"``
    out : the output folder
    figures : figure formats (``("png",)``, ``()``, ...)
    bilateral : refused (a pushover follows the constraints' laws)
    **overrides : ``lcp`` only (``dt``, ``t_end``, ``method``, ``rule``, ``initial`` are for transient runs)

    Returns
    -------
    dict : the summary (``summary.json``) with ``figures`` (the files drawn), ``report`` (the terminal
    text) and ``success_all``.

    Raises
    ------
    ModelFileError
        What the pushover refuses (a DOF that cannot move, a target of the wrong sign, 3-D frames, ...),
        under the key ``pushover``.
    ValueError
        Options of a transient run.
    """
    from ..io.folder import OutputFolder
    from ..modelfile.errors import ModelFileError

    given = sorted(key for key, value in overrides.items() if value is not None and key != "lcp")
    if given or bilateral:
        options = ", ".join("--" + key.replace("_", "-") for key in given) + (" --bilateral" if bilateral else "")
        raise ValueError(f"{options.strip(', ')}: not for a pushover ([analysis] type = \"pushover\" in "
                         f"{spec.source}); a pushover takes --lcp, --out and --figures")
    table = spec.document.pushover
    lcp = overrides.get("lcp") or spec.analysis.get("lcp") or "bpp"
    try:
        result = pushover(spec.structure, _pattern(spec.structure, table), node=table.node, dof=table.dof,
                          target=table.targets if table.cycles is not None else table.target,
                          gravity=_gravity(spec, table), control=table.control, p_delta=_P_DELTA[table.p_delta],
                          max_events=table.max_events, lcp=lcp)
    except (ValueError, TypeError) as exc:
        raise ModelFileError(spec.source, [f"pushover: {exc}"]) from None
    summary = summarise(result, spec, table)
    summary["not_applied"] = not_applied(spec.document)
    folder = OutputFolder(out)
    folder.prepare()
    try:
        write_tables(folder.staging, result, height_of(spec.structure, table))
        drawn = [draw_capacity_curve(folder.staging / f"capacity_curve.{fmt}", result, spec, table)
                 for fmt in figures]
        summary["figures"] = [str(Path(out) / path.name) for path in drawn]
        (folder.staging / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
        folder.commit()
    finally:
        folder.close()
    return {**summary, "report": report(result, summary), "success_all": bool(result.success)}


def _pattern(structure, table):
    """The pattern argument: a name, or the sum of the nodal forces of ``table.pattern``."""
    if isinstance(table.pattern, str):
        return table.pattern
    return sum(structure.nodal_load(f.node, **f.components) for f in table.pattern)


def _gravity(spec, table):
    """The gravity load of the pushover: the constant load of the file (``[loads.gravity]``), or None."""
    q = np.asarray(spec.load.constant, dtype=float)
    return q if table.gravity and np.any(q) else None


def height_of(structure, table) -> float:
    """The control node's height above the lowest node (0 but for a horizontal ``dof``: ``ux``; in 3-D
    also ``uy``)."""
    if table.dof not in ("ux", "uy") or (table.dof == "uy" and len(structure.dofs.dof_names) == 3):
        return 0.0
    up = vertical_axis(structure)
    return float(structure.coords[table.node][up]) - min(float(xy[up]) for xy in structure.coords.values())


def write_tables(folder: Path, result, height: float) -> None:
    """``pushover.csv`` and ``events.csv`` of ``result`` into ``folder``."""
    at = {}
    for e in result.events:
        at.setdefault(e.point, []).append(f"{e.kind} {e.name}")
    drift = result.displacement / height if height > 0 else np.full_like(result.displacement, np.nan)
    with open(folder / "pushover.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["point", "parameter", "load_factor", f"{result.control_dof}", "roof_drift", "base_shear",
                    "events"])
        for k, (t, lam, d, r, V) in enumerate(zip(result.parameter, result.load_factor, result.displacement, drift,
                                                  result.base_shear)):
            w.writerow([k, repr(float(t)), repr(float(lam)), repr(float(d)), repr(float(r)), repr(float(V)),
                        "; ".join(at.get(k, []))])
    per = result.base_shear[-1] / result.load_factor[-1] if result.load_factor[-1] else _per_unit(result)
    with open(folder / "events.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["load_factor", result.control_dof, "base_shear", "constraint", "kind"])
        for e in result.events:
            w.writerow([repr(float(e.load_factor)), repr(float(e.displacement)), repr(float(per * e.load_factor)),
                        e.name, e.kind])


def _per_unit(result) -> float:
    """Base shear per unit load factor (from any point with a nonzero load factor)."""
    k = int(np.argmax(np.abs(result.load_factor)))
    return float(result.base_shear[k] / result.load_factor[k]) if result.load_factor[k] else 0.0


def summarise(result, spec, table) -> dict:
    """The ``summary.json`` of a pushover."""
    k = int(np.argmax(np.abs(result.base_shear)))
    first = result.events[0] if result.events else None
    stats = {key: value for key, value in result.stats.items() if key != "time"}
    return {"analysis": "pushover", "model_file": str(spec.source), "units": spec.units,
            "success": bool(result.success), "message": result.message, "control_dof": result.control_dof, "control": table.control,
            "pattern": table.pattern if isinstance(table.pattern, str) else "nodal forces",
            "targets": table.targets, "stats": stats,
            "peak_base_shear": float(result.base_shear[k]), "peak_at": float(result.displacement[k]),
            "end": {"load_factor": float(result.load_factor[-1]), "displacement": float(result.displacement[-1]),
                    "base_shear": float(result.base_shear[-1])},
            "first_event": None if first is None else first._asdict(),
            "events": [e._asdict() for e in result.events]}


def not_applied(document) -> list[str]:
    """The loads of a model file a pushover does not apply (it applies ``[loads.gravity]`` only)."""
    loads = document.loads
    return ([f"loads.nodal[{k}]" for k in range(len(loads.nodal))]
            + [f"loads.distributed[{k}]" for k in range(len(loads.distributed))]
            + [f"loads.ground_motion[{k}]" for k in range(len(loads.ground_motion))])


def report(result, summary) -> str:
    """The terminal text of a pushover: the message, the capacity curve's table, the peak."""
    units = summary["units"]
    lines = [f"pushover of {summary['model_file']} ({summary['control']} control of {result.control_dof}, pattern "
             f"{summary['pattern']}): {'success' if result.success else 'STOPPED'}", result.message, "",
             result.table(), "",
             f"peak base shear {summary['peak_base_shear']:.6g} {units['force']} at {result.control_dof} = "
             f"{summary['peak_at']:.6g} {units['length']}; {len(result.events)} events, "
             f"max equilibrium error {result.stats['max_residual']:.1e}, max LCP error "
             f"{result.stats['max_lcp_error']:.1e}"]
    if summary.get("not_applied"):
        lines.append(f"note: a pushover applies [loads.gravity] and [pushover] pattern only; not applied: "
                     f"{', '.join(summary['not_applied'])}")
    return "\n".join(lines)


def draw_capacity_curve(path: Path, result, spec, table) -> Path:
    """The capacity curve (base shear against roof drift, the events marked) into ``path``."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    height = height_of(spec.structure, table)
    scale, label = (1.0 / height, f"roof drift {result.control_dof} / {height:g} {spec.units['length']}") \
        if height > 0 else (1.0, f"{result.control_dof} [{spec.units['length']}]")
    fig = Figure(figsize=(6.4, 4.2))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.plot(scale * result.displacement, result.base_shear, color="C0", lw=1.4)
    per = _per_unit(result)
    marks = {"yield": ("o", "C3"), "unload": ("s", "C2"), "uplift": ("^", "C1"), "contact": ("v", "C4"),
             "slip": ("D", "C5")}
    for kind, (marker, color) in marks.items():
        chosen = result.events_of(kind)
        if chosen:
            ax.plot([scale * e.displacement for e in chosen], [per * e.load_factor for e in chosen], marker,
                    color=color, ms=4.5, ls="none", label=f"{kind} ({len(chosen)})")
    ax.axhline(0.0, color="0.7", lw=0.6)
    ax.set_xlabel(label)
    ax.set_ylabel(f"base shear [{spec.units['force']}]")
    ax.set_title(spec.analysis.get("title") or f"capacity curve: {spec.source.stem}")
    if result.events:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path
