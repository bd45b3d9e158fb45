"""The study quantity of footings on a soil medium: ``[[quantities]] type = "footing"``.

``measure`` names what is taken of each footing's histories
(:func:`unilateral.analysis.footing_results.footing_histories`, the same numbers as ``unilateral
run`` writes), ``elements`` the footings (default: all), ``over`` whether the column is the largest
over them (``"max"``) or one column per footing (``"each"``, ``<name>.<footing>``):

- ``uplift``: the peak uplift (length);
- ``rotation``, ``residual_rotation``: the peak and the last-step rotation, absolute (rad; in 3-D the
  magnitude of ``(rx, ry)``);
- ``settlement``, ``residual_settlement``: the peak and the last-step downward motion of the base
  from the static state at ``t = 0`` (length; negative: the footing ended above it);
- ``slip``, ``residual_slip``: the peak and the last-step slip on the soil, absolute (length; 3-D:
  the magnitude in plan), footings that slide only;
- ``peak_pressure``: the largest bearing pressure (force / length^2);
- ``contact_ratio``: the least share of the base in contact (1: never lifted).

A measure a footing does not have (a slip of a footing that does not slide, a rotation of a
footing whose patches span no axis) is NaN with a note saying why, never 0.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["FOOTING_MEASURES", "footing_names", "footing_problems", "collect_footing", "measure_unit"]

#: ``measure`` -> the unit key of its value (see :func:`measure_unit`).
FOOTING_MEASURES = {"uplift": "length", "rotation": "rad", "residual_rotation": "rad", "settlement": "length",
                    "residual_settlement": "length", "slip": "length", "residual_slip": "length",
                    "peak_pressure": "pressure", "contact_ratio": "1"}


def footing_names(structure) -> list[str]:
    """The names of the footings of a frame on a soil medium (none: no footings)."""
    foundation = getattr(structure, "foundation", None)
    return [] if foundation is None else [f.name for f in foundation.footings]


def measure_unit(measure: str, units: dict) -> str:
    """The unit of ``measure`` in the model's ``units``."""
    key = FOOTING_MEASURES[measure]
    length, force = units.get("length", ""), units.get("force", "")
    return {"length": length, "pressure": f"{force}/{length}^2"}.get(key, key)


def footing_problems(k: int, elements, structure, where: str) -> list[str]:
    """What is wrong with footing quantity ``quantities[k]`` of footings ``elements`` (None: all) on a
    model variant's ``structure`` (``where``: which variant)."""
    from ..modelfile.errors import did_you_mean, toml_value, value_problem

    names = footing_names(structure)
    if not names:
        return [value_problem(("quantities", k, "type"), "footing", f"{where} has no footings on a soil medium "
                              "([[foundations]]); footing quantities need them")]
    return [value_problem(("quantities", k, "elements", j), name, f"no footing {toml_value(name)} {where} "
                          f"(footings: {', '.join(names)})") + did_you_mean(name, names)
            for j, name in enumerate(elements or []) if name not in names]


def collect_footing(quantity: dict, sol, structure) -> tuple[dict, list]:
    """``({column: value}, notes)`` of a footing quantity for the solution ``sol`` of ``structure``."""
    from ..analysis.footing_results import footing_histories

    name, measure = quantity["name"], quantity["measure"]
    foundation = structure.foundation
    three_d = len(structure.dofs.dof_names) == 6
    histories = footing_histories(foundation, structure, sol.u, sol, three_d=three_d)
    names = quantity.get("elements") or list(histories)
    values, notes = {}, []
    for footing in names:
        value, why = _measure(histories[footing], measure, three_d)
        values[footing] = value
        if why:
            notes.append(f"{name}: {measure} of footing {footing!r} not available: {why}")
    if quantity.get("over") == "each":
        return {f"{name}.{footing}": value for footing, value in values.items()}, notes
    known = [v for v in values.values() if not math.isnan(v)]
    return {name: max(known) if known else math.nan}, notes


def _measure(h: dict, measure: str, three_d: bool) -> tuple[float, str]:
    """``(value, why NaN or "")`` of ``measure`` from one footing's histories ``h``."""
    if measure == "uplift":
        return float(h["uplift"].max()), ""
    if measure == "peak_pressure":
        return float(h["peak_pressure"].max()), ""
    if measure == "contact_ratio":
        return float(h["contact_ratio"].min()), ""
    if measure in ("settlement", "residual_settlement"):
        down = -(h["uz" if three_d else "uy"] - h["uz" if three_d else "uy"][0])
        return float(down.max() if measure == "settlement" else down[-1]), ""
    keys = (("rx", "ry") if three_d else ("rz",)) if "rotation" in measure else \
        (("slip_x", "slip_y") if three_d else ("slip",))
    parts = [h[key] for key in keys if key in h]
    if not parts:
        return math.nan, ("the footing does not slide (horizontal = \"soil\" slides)" if "slip" in measure
                          else "its patches span no axis (one patch, or a row in 3-D about the other axis)")
    size = np.sqrt(sum(p * p for p in parts))
    return float(size.max() if not measure.startswith("residual") else size[-1]), ""
