"""The unit of each constraint unknown in ``results.nc``: a hinge's ``v`` is a rotation, its ``psi`` a moment.

A constraint unknown ``v`` is a deformation and ``psi`` its force, in the units of the strain it acts
on. Which strain that is comes from the element the unknown belongs to
(:attr:`Structure.constraints <unilateral.structure.Structure.constraints>`, the
``(element, Unknown)`` of every unknown in the model's order, contacts, yield and friction
families alike; :func:`unilateral.analysis.inelastic.rotational_unknowns`), not from its name:

==============================================  ==============  ==================
unknown                                         ``v``           ``psi``, ``psiL``
==============================================  ==============  ==================
hinge (2-D, 3-D facets), link along a rotation  rad             force x length
any other contact, yield link, friction, slip   length          force
footing patch, its shear and slip pair          length          force
==============================================  ==============  ==================

:func:`with_constraint_units` writes the coordinates ``v_unit`` and ``psi_unit`` along ``constraint``
and sets the ``units`` attribute of ``v``, ``psi``, ``psiL`` and ``constraint_deformation``: one
unit if all unknowns share it, else both, with a pointer to the coordinate (the CSV headers of
:func:`unilateral.analysis.outputs.csv_units` say the same per column). The model's base units are
then the Dataset's attributes ``units_length``, ``units_force``, ``units_time`` (the figures read
them there, :func:`unilateral.figures.results._unit`).
"""

from __future__ import annotations

from ..io.dataset import Variable

#: The variables along ``constraint`` whose unit is that of ``v`` (deformation) or of ``psi`` (force).
DEFORMATIONS = ("v", "constraint_deformation")
FORCES = ("psi", "psiL")


def constraint_units(structure, m: int, units=None) -> tuple[list[str], list[str]]:
    """The units of ``v`` and of ``psi`` of each of the ``m`` constraint unknowns of a run.

    Parameters
    ----------
    structure : Structure (2-D or 3-D), or None (a model of matrices: every unknown a contact)
    m : int, the number of unknowns of the run (a frame's own first, then its footings' patches,
        :class:`~unilateral.structure.foundation.Footings`: contacts, shears and slips)
    units : dict ``{"length": ..., "force": ...}`` of the model

    Returns
    -------
    (v_units, psi_units) : two lists of ``m`` str, e.g. ``["m", "rad"]``, ``["kN", "kN m"]``
    """
    from .inelastic import _rotational

    units = units or {}
    length, force = units.get("length", ""), units.get("force", "")
    moment = f"{force} {length}".strip()
    own = [_rotational(element) for element, _ in getattr(structure, "constraints", ())][:m]
    rotational = own + [False] * (m - len(own))         # the footings' unknowns: lengths and forces
    return ([("rad" if r else length) for r in rotational], [(moment if r else force) for r in rotational])


def with_constraint_units(ds, structure, units=None):
    """``ds`` with the coordinates ``v_unit`` and ``psi_unit`` (constraint) of :func:`constraint_units`
    and the ``units`` attribute of :data:`DEFORMATIONS` and :data:`FORCES` set from them.

    Parameters
    ----------
    ds : :class:`unilateral.io.dataset.Dataset` with the dimension ``constraint``
    structure, units : as :func:`constraint_units`

    Returns
    -------
    Dataset (``ds`` itself without constraints or without a length unit)
    """
    units = units or {}
    m = ds.sizes.get("constraint", 0)
    if not m or not units.get("length"):
        return ds
    v_units, psi_units = constraint_units(structure, m, units)
    ds = ds.assign_coords(
        v_unit=Variable(("constraint",), v_units, {"long_name": "unit of the constraint's v and deformation"}),
        psi_unit=Variable(("constraint",), psi_units, {"long_name": "unit of the constraint's psi and psiL"}))
    changed = {}
    for names, each in ((DEFORMATIONS, v_units), (FORCES, psi_units)):
        text = _unit_text(each, "v_unit" if names is DEFORMATIONS else "psi_unit")
        for name in names:
            if name in ds.data_vars:
                var = ds.variables[name]
                changed[name] = Variable(var.dims, var.values, {**var.attrs, "units": text})
    ds = ds.assign(changed)
    for key in ("length", "force", "time"):
        if units.get(key):
            ds.attrs[f"units_{key}"] = units[key]
    return ds


def _unit_text(each: list, coordinate: str) -> str:
    """``"m"`` if every unknown has it, else ``"m or rad (per constraint: v_unit)"``."""
    distinct = list(dict.fromkeys(u for u in each if u))
    if len(distinct) <= 1:
        return distinct[0] if distinct else ""
    return f"{' or '.join(distinct)} (per constraint: {coordinate})"
