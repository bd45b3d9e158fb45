"""Per-footing results of a frame on a soil medium: uplift, settlement, rotation, slip, bearing
pressure and contact length.

The soil acts on each patch ``j`` of a footing through a compressive contact force ``c_j >= 0``
and an opening ``v_j >= 0`` (uplift) with ``c_j v_j = 0``. For each footing and at every step:

- ``uplift``: the largest opening of its patches, ``max_j v_j`` (length);
- ``uy`` (2-D) or ``uz`` (3-D): the upward displacement of its base at the centroid of the patches,
  and ``rz`` (2-D) or ``rx``, ``ry`` (3-D): its rotation, from the plane ``z(x, y) = a + b (x - x_c)
  (+ b_y (y - y_c))`` fitted to the patches' upward motion ``z_j`` with weights their areas (exact
  for a rigid footing, whose patches move as a plane; for a flexible footing the best plane);
  a rotation is given only where the patches span the axis;
- ``slip`` (2-D) or ``slip_x``, ``slip_y`` (3-D), footings that slide: the area-weighted mean of
  the patches' net slip on the soil (length);
- ``peak_pressure``: the largest bearing pressure ``max_j c_j / A_j`` (force / length^2);
- ``contact_length`` (2-D: the length in contact, the patches' sizes along x where ``c_j`` is more
  than :data:`ROUND_OFF` of the run's largest contact force) or ``contact_area`` (3-D), and
  ``contact_ratio``, its share of the footing's base (1: full contact, 0: the footing is in the air);
- ``vertical_force``: the soil's total vertical force on the footing, ``sum_j c_j`` (force).
"""

from __future__ import annotations

import numpy as np

__all__ = ["ROUND_OFF", "footing_histories", "footing_variables", "footing_peaks"]

#: Contact forces at most this fraction of the run's largest contact force are no contact (round-off).
ROUND_OFF = 1e-9
#: Quantity -> (long name, unit key): the unit keys are resolved by :func:`_unit`.
QUANTITIES = {
    "uplift": ("largest opening between the footing and the soil (uplift) of its patches", "length"),
    "uy": ("upward displacement of the footing's base at the centroid of its patches", "length"),
    "uz": ("upward displacement of the footing's base at the centroid of its patches", "length"),
    "rz": ("rotation of the footing (counter-clockwise), the slope of the plane fitted to its patches' motion",
           "rad"),
    "rx": ("rotation of the footing about x, from the plane fitted to its patches' motion", "rad"),
    "ry": ("rotation of the footing about y, from the plane fitted to its patches' motion", "rad"),
    "slip": ("slip of the footing on the soil (+x), the area-weighted mean of its patches' net slip", "length"),
    "slip_x": ("slip of the footing on the soil along x, area-weighted mean of its patches", "length"),
    "slip_y": ("slip of the footing on the soil along y, area-weighted mean of its patches", "length"),
    "peak_pressure": ("largest bearing pressure of the footing's patches, contact force over patch area",
                      "pressure"),
    "contact_length": ("length of the footing's base in contact with the soil", "length"),
    "contact_area": ("area of the footing's base in contact with the soil", "area"),
    "contact_ratio": ("share of the footing's base in contact with the soil (1 full contact, 0 in the air)", "1"),
    "vertical_force": ("total compressive force of the soil on the footing", "force"),
}


def footing_histories(footings, structure, u, contact_sol, *, three_d=False) -> dict:
    """The results of every footing at every step.

    Parameters
    ----------
    footings : :class:`~unilateral.structure.foundation.Footings` (or ``Footings3D``)
    structure : the frame (its ``dofs`` and ``coords``)
    u : (N+1, n) displacements of the frame
    contact_sol : the solution whose ``psi`` and ``v`` hold the soil's constraints (after the
        frame's own, from ``footings.first``)
    three_d : bool, the footings are in plan (patch centres ``(x, y)``, vertical ``z``)

    Returns
    -------
    dict
        footing name -> {quantity: (N+1,) ndarray}, the quantities of the module docstring.
    """
    c = footings.contact_forces(contact_sol)
    opening = np.asarray(contact_sol.v, dtype=float)[:, footings.first:footings.first + footings.m]
    z = np.asarray(u, dtype=float) @ footings.T(structure.dofs, structure.coords)
    slips = footings.slips(contact_sol)
    in_contact = c > ROUND_OFF * max(float(np.max(np.abs(c), initial=0.0)), np.finfo(float).tiny)
    out, start = {}, 0
    for f in footings.footings:
        part = slice(start, start + f.m)
        start += f.m
        out[f.name] = _one_footing(f.patches, c[:, part], opening[:, part], z[:, part], in_contact[:, part],
                                   None if slips is None else slips[:, part], three_d)
    return out


def _one_footing(patches, c, opening, z, in_contact, slips, three_d) -> dict:
    """The quantities of one footing from its patches' forces, openings, motion and slips (N+1, m)."""
    areas = np.asarray(patches.areas, dtype=float)
    plan = np.asarray(patches.centres, dtype=float)[:, :2 if three_d else 1]
    out = {"uplift": opening.max(axis=1)} | _plane(z, plan, areas, three_d)
    if slips is not None:
        mean = np.tensordot(slips, areas / areas.sum(), axes=([1], [0]))
        out |= {"slip_x": mean[:, 0], "slip_y": mean[:, 1]} if three_d else {"slip": mean}
    out["peak_pressure"] = (c / areas).max(axis=1)
    if three_d:
        out["contact_area"] = in_contact @ areas
        out["contact_ratio"] = out["contact_area"] / areas.sum()
    else:
        lengths = np.asarray(patches.sizes, dtype=float)[:, 0]
        out["contact_length"] = in_contact @ lengths
        out["contact_ratio"] = out["contact_length"] / lengths.sum()
    out["vertical_force"] = c.sum(axis=1)
    return out


def _plane(z, plan, areas, three_d) -> dict:
    """The centroid's upward motion and the rotations of the plane fitted to ``z`` (N+1, m) with
    weights ``areas`` over the patch centres ``plan`` (m, 1 or 2); only the axes the patches span."""
    centroid = areas @ plan / areas.sum()
    spans = [k for k in range(plan.shape[1]) if np.ptp(plan[:, k]) > 1e-12 * max(1.0, np.abs(plan[:, k]).max())]
    X = np.column_stack([np.ones(len(areas))] + [plan[:, k] - centroid[k] for k in spans])
    w = np.sqrt(areas)
    coef = np.linalg.lstsq(X * w[:, None], (z * w).T, rcond=None)[0]       # (1 + len(spans), N+1)
    out = {"uz" if three_d else "uy": coef[0]}
    for row, k in enumerate(spans, start=1):
        if not three_d:
            out["rz"] = coef[row]                  # z = uy + (x - xc) rz
        elif k == 0:
            out["ry"] = -coef[row]                 # z = uz + (y - yc) rx - (x - xc) ry
        else:
            out["rx"] = coef[row]
    return out


def footing_variables(histories: dict, units: dict) -> dict:
    """The variables of ``results.nc``: ``footing_<quantity>`` -> ``(values (N+1, footings), long name,
    unit)``, one column per footing (a quantity missing for a footing, a rotation about an axis
    its patches do not span, is NaN there)."""
    names = list(histories)
    quantities = [q for q in QUANTITIES if any(q in h for h in histories.values())]
    steps = len(next(iter(histories.values()))["uplift"])
    out = {}
    for q in quantities:
        values = np.column_stack([histories[name].get(q, np.full(steps, np.nan)) for name in names])
        long_name, unit = QUANTITIES[q]
        out[f"footing_{q}"] = (values, long_name, _unit(unit, units))
    return out


def footing_peaks(t, histories: dict) -> dict:
    """For ``summary.json``: footing name -> {quantity: {max, t_max, min, t_min, final}}."""
    t = np.asarray(t, dtype=float)
    out = {}
    for name, h in histories.items():
        out[name] = {}
        for q, y in h.items():
            i, j = int(np.argmax(y)), int(np.argmin(y))
            out[name][q] = {"max": float(y[i]), "t_max": float(t[i]), "min": float(y[j]), "t_min": float(t[j]),
                            "final": float(y[-1])}
    return out


def _unit(key: str, units: dict) -> str:
    """The unit of ``key`` (length, area, pressure, force, rad, 1) in the run's ``units``."""
    L, Fu = units.get("length", ""), units.get("force", "")
    return {"length": L, "area": f"{L}^2" if L else "", "pressure": f"{Fu}/{L}^2" if L and Fu else "",
            "force": Fu}.get(key, key)
