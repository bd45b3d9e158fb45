"""The steps of one case's structure results, 2-D and 3-D (:func:`unilateral.analysis.results.structure_results`).

:func:`case_results` runs the steps a :class:`~unilateral.analysis.dimension.Dimension` lists, in its
order, on a :class:`Case` (the case's solution, histories and what the steps computed); each step
adds its variables (name -> (dims, {case: array}, attrs)) with the dims and attributes of the
Dimension's :class:`~unilateral.analysis.dimension.Spec` of each, and its coordinates. Most steps
are those of both dimensions, their components from the Dimension; the reactions, the base forces
and the drifts have one step per dimension (:mod:`unilateral.structure.forces` and
:mod:`unilateral.structure.forces3d` differ in what they return: the footings' forces among the
ground elements' or apart; base shear, vertical force and overturning moment of a plane frame, the
six resultants of a 3-D one; the drift of each storey pair, the largest drift ratio over a plan's
corners), and so does the summary of a case (:data:`PEAKS`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..structure import forces as F
from ..structure import forces3d as F3
from .footing_results import footing_histories, footing_peaks, footing_variables
from .residual import residual_peaks
from .result_parts import (_abs_peak, _extreme, _frame_part, _linear_drift_note, _peaks, _put, acceleration_peaks,
                      acceleration_results, element_end_forces, energy_peaks, energy_results, motions_at,
                      pairing_rule, step_means)
from .rigid import rigid_ground_reactions, rigid_summary


@dataclass
class Settings:
    """What every case of a :func:`~unilateral.analysis.results.structure_results` call shares."""

    structure: object
    dim: object                 # Dimension
    units: object               # Units
    unit_dict: dict
    rule: object
    point: tuple
    inelastic: object
    energy_keys: tuple
    load_samples: object = None
    ground_motions: list = field(default_factory=list)
    storey_pairs: object = None
    static_load: object = None
    variables: dict = field(default_factory=dict)
    coords: dict = field(default_factory=dict)


@dataclass
class Case:
    """One case: ``solved`` (the solution as solved), ``sol`` (the frame's part), ``contact`` (the load
    (N+1, n) of the footings' or rigid contacts' forces on the frame, or None), ``h`` (the frame's
    histories), ``motions`` (the ground motions as its accelerations read them), and what the steps
    computed."""

    name: str
    solved: object
    sol: object
    contact: object
    h: object
    motions: list
    ends: dict = None
    reaction: dict = None
    base: dict = None
    per_frame: dict = None
    drifts: dict = None
    footings: dict = None
    histories: dict = field(default_factory=dict)
    energy: dict = None


def case_results(s: Settings, name, solved) -> dict:
    """The variables of case ``name`` (Solution ``solved``) added to ``s.variables``; returns its peaks."""
    structure, dim = s.structure, s.dim
    foundation = getattr(structure, "foundation", None)
    contact, solved, sol = _frame_part(structure, foundation, solved, rigid=dim.rigid_contacts)
    q0 = None if s.load_samples is None else s.load_samples[0]
    if contact is not None and (q0 is not None or dim.contact_at_start):
        q0 = contact[0] if q0 is None else q0 + contact[0]
    h = F.Histories.from_solution(structure, sol, s.rule, load0=q0)
    c = Case(name, solved, sol, contact, h, step_means(s.ground_motions, sol))
    for step in dim.steps:
        STEPS[step](s, c)
    return PEAKS[dim.name](s, c)


def _put_spec(s: Settings, name, case, array, **fields):
    """:func:`~unilateral.analysis.result_parts._put` of the variable ``name`` of ``case`` with the dims
    and attributes of the Dimension's :class:`~unilateral.analysis.dimension.Spec` (its long name's
    ``fields`` filled in)."""
    spec = s.dim.spec(name)
    _put(s.variables, name, spec.dims, case, array, *spec.attributes(s.units, **fields))


def _accelerations(s: Settings, c: Case):
    acceleration_results(s.variables, s.coords, s.structure, c.h, c.motions, case=c.name, unit=s.units.acc)


def _node_accelerations(s: Settings, c: Case):
    """``node_acceleration`` (time, node, component): the accelerations of the rule of every node's DOFs
    relative to the ground (supported DOFs 0, rigidly linked nodes following their masters) and, under
    ground motions, ``node_absolute_acceleration``: plus the ground's translation ``sum a_g,k d_k`` on
    the translations of every node (a supported node moves with the ground)."""
    relative = s.structure.dofs.nodal(c.h.uddot)                # (N+1, nodes, DOFs per node)
    _put_spec(s, "node_acceleration", c.name, relative)
    if c.motions:
        absolute = relative.copy()
        for direction, a_g in motions_at(c.motions, c.h.t):
            d = np.zeros(relative.shape[2])
            d[list(s.structure.dofs.dof_names).index(direction)] = 1.0
            absolute += a_g[:, None, None] * d
        _put_spec(s, "node_absolute_acceleration", c.name, absolute)


def _end_forces(s: Settings, c: Case):
    """``end_force`` (time, element, end_component) in the elements' local axes and ``axial_force``
    (time, element); keeps :func:`~unilateral.structure.forces.end_forces` (or the 3-D one) for the peaks."""
    c.ends = s.dim.forces.end_forces(s.structure, c.h)
    end = element_end_forces(s.coords, s.structure, c.ends, s.dim.end_components, steps=len(c.h.t))
    _put_spec(s, "end_force", c.name, end)
    first, other = s.dim.axial_columns
    _put_spec(s, "axial_force", c.name,
              np.where(np.any(end[:, :, first] != 0, axis=0), end[:, :, first], end[:, :, other]))


def _footings(s: Settings, c: Case):
    """The footings' histories on a soil medium (time, foundation), kept for the peaks."""
    foundation = getattr(s.structure, "foundation", None)
    if foundation is None:
        return
    c.footings = footing_histories(foundation, s.structure, c.h.u, c.solved, **s.dim.footing_options)
    s.coords["foundation"] = list(c.footings)
    for name, (values, long_name, unit) in footing_variables(c.footings, s.unit_dict).items():
        _put(s.variables, name, ("time", "foundation"), c.name, values, long_name, unit)


def _reactions_2d(s: Settings, c: Case):
    """The reactions of a plane frame (:func:`unilateral.structure.forces.reactions`), the rigid contacts'
    and blocks' (:func:`~unilateral.analysis.rigid.rigid_ground_reactions`) and the footings' patches'
    on a soil medium joining the ground elements' (:func:`_put_reactions`)."""
    structure = s.structure
    c.reaction = F.reactions(structure, c.h)
    if s.dim.rigid_contacts and getattr(structure, "rigid", None) is not None:
        motions = motions_at(c.motions, c.h.t) if c.motions else []
        forces, at = rigid_ground_reactions(structure, c.h, c.solved, motions)
        c.reaction["ground_elements"].update(forces)
        c.reaction["at"].update(at)
    if getattr(structure, "foundation", None) is not None:
        forces, at = structure.foundation.ground_reactions(structure, c.solved)
        c.reaction["ground_elements"].update(forces)
        c.reaction["at"].update(at)
    _put_reactions(s, c, c.reaction["ground_elements"])


def _reactions_3d(s: Settings, c: Case):
    """The reactions of a 3-D frame (:func:`unilateral.structure.forces3d.reactions`), the footings'
    patches on a soil medium after the ground elements (:func:`_put_reactions`)."""
    c.reaction = F3.reactions(s.structure, c.h, c.solved)
    _put_reactions(s, c, {**c.reaction["ground_elements"], **c.reaction.get("footings", {})})


def _put_reactions(s: Settings, c: Case, grounded: dict):
    """``support_reaction`` (time, support) and ``ground_reaction`` (time, ground_element,
    force_component): the ground's forces through the supports and through each of ``grounded``
    (name -> (N+1, components))."""
    if c.reaction["support"]:
        s.coords["support"] = list(c.reaction["support"])
        _put_spec(s, "support_reaction", c.name, np.column_stack(list(c.reaction["support"].values())))
    if grounded:
        s.coords["ground_element"] = list(grounded)
        s.coords["force_component"] = list(s.dim.force_components)
        _put_spec(s, "ground_reaction", c.name, np.stack(list(grounded.values()), axis=1))


def _base_2d(s: Settings, c: Case):
    """Base shear, vertical force and overturning moment about the point (time,) and, with several
    frames (pounding buildings), each frame's base shear (time, frame)."""
    point = s.point
    c.base = F.base_forces(s.structure, c.reaction, point)
    c.per_frame = F.base_forces_per_frame(s.structure, c.reaction, point)
    if c.per_frame:
        s.coords["frame"] = list(c.per_frame)
        _put_spec(s, "frame_base_shear", c.name, np.column_stack([b["base_shear"] for b in c.per_frame.values()]))
    for name in ("base_shear", "base_vertical"):
        _put_spec(s, name, c.name, c.base[name])
    _put_spec(s, "overturning_moment", c.name, c.base["overturning_moment"], x0=point[0], y0=point[1])
    s.variables["overturning_moment"][2]["overturning_point"] = list(point)


def _base_3d(s: Settings, c: Case):
    """The resultants ``base_Fx`` ... ``base_Mz`` (time,) of the ground's forces about the base point."""
    c.base = F3.base_forces(s.structure, c.reaction, s.point)
    for key, values in c.base.items():
        _put_spec(s, f"base_{key}", c.name, values)


def _drifts_2d(s: Settings, c: Case):
    """The interstorey drifts ``ux(upper) - ux(lower)`` and drift ratios (time, storey)."""
    c.drifts = F.storey_drifts(s.structure, c.h, s.storey_pairs)
    if c.drifts:
        s.coords["storey"] = list(c.drifts)
        _put_spec(s, "storey_drift", c.name, np.column_stack([d for d, _ in c.drifts.values()]))
        _put_spec(s, "drift_ratio", c.name, np.column_stack([r for _, r in c.drifts.values()]))


def _drifts_3d(s: Settings, c: Case):
    """The interstorey drift ratios ``drift_ratio_x``, ``drift_ratio_y`` (time, storey), the largest
    over each plan's corners."""
    c.drifts = F3.storey_drifts(s.structure, c.h)
    if not c.drifts:
        return
    s.coords["storey"] = list(c.drifts)
    for axis in "xy":
        ratios = np.column_stack([d[f"max_ratio_{axis}"] for d in c.drifts.values()])
        _put_spec(s, f"drift_ratio_{axis}", c.name, ratios)


def _constraints(s: Settings, c: Case):
    """The histories of the yield and friction elements (:class:`~unilateral.analysis.inelastic.Inelastic`)
    and (2-D) the deformations the constraints act on (time, constraint): the elements' strains,
    then the footings' patches (upward motion plus the gap) and, sliding, their horizontal motion for
    the shears and slip pairs."""
    structure, h = s.structure, c.h
    if not structure.m or not (s.inelastic or s.dim.constraint_deformation):
        return
    e, _ = structure.element_deformations(h.u, h.v, h.t)
    c.histories = s.inelastic.histories(h, e)
    if s.dim.constraint_deformation:
        foundation = getattr(structure, "foundation", None)
        if foundation is not None:
            e = np.hstack([e, h.u @ foundation.T(structure.dofs, structure.coords) + foundation.gap])
            if foundation.sliding:
                x = h.u @ foundation.Tx(structure.dofs)
                e = np.hstack([e, x, np.repeat(x, 2, axis=1)])
        _put_spec(s, "constraint_deformation", c.name, e)
    for name, (dims, values, long_name, unit) in c.histories.items():
        _put(s.variables, name, dims, c.name, values, long_name, unit)


def _energy(s: Settings, c: Case):
    """The energy balance (``energy_*``, time), with a load."""
    if s.load_samples is None:
        return
    c.energy = energy_results(s.variables, s.structure, c.h, s.load_samples, case=c.name, contact=c.contact,
                              keys=s.energy_keys, unit=s.units.moment, rule=pairing_rule(c.sol, s.rule),
                              stats=c.sol.stats if s.dim.rigid_contacts else None)


#: The steps by their names in :attr:`Dimension.steps <unilateral.analysis.dimension.Dimension>`.
STEPS = {"accelerations": _accelerations, "node_accelerations": _node_accelerations, "end_forces": _end_forces,
         "footings": _footings, "reactions_2d": _reactions_2d, "reactions_3d": _reactions_3d, "base_2d": _base_2d,
         "base_3d": _base_3d, "drifts_2d": _drifts_2d, "drifts_3d": _drifts_3d, "constraints": _constraints,
         "energy": _energy}


def _end_force_peaks(s: Settings, c: Case) -> dict:
    return {name: {comp: _abs_peak(c.h.t, f[:, k]) for k, comp in enumerate(s.dim.end_components) if np.any(f[:, k])}
            for name, f in c.ends.items()}


def _peaks_2d(s: Settings, c: Case) -> dict:
    """The summary of a case of a plane frame: the peaks of the base forces, end forces, reactions and
    drifts with their times, each frame's, the static residual, the footings', the rigid contacts',
    the note on linear members, the energy balance's and the inelastic ones."""
    t, structure = c.h.t, s.structure
    peaks = _peaks(t, c.base, c.ends, c.reaction, c.drifts, c.energy, h=c.h, ground_motions=c.motions,
                   structure=structure)
    if c.per_frame:
        peaks["frames"] = {label: {key: _extreme(t, value) for key, value in b.items()}
                           for label, b in c.per_frame.items()}
    peaks |= {"overturning_point": list(s.point)} | residual_peaks(
        structure, c.sol, t, s.static_load, s.load_samples, s.storey_pairs)
    if c.footings is not None:
        peaks["footings"] = footing_peaks(t, c.footings)
    if getattr(structure, "rigid", None) is not None:
        peaks["rigid_contacts"] = rigid_summary(structure, c.solved)
    note = _linear_drift_note(structure, peaks)
    if note:
        peaks["linear_members_note"] = note
    if c.energy is not None:
        peaks["energy"] = energy_peaks(t, c.energy, s.energy_keys)
    if s.inelastic:
        peaks |= s.inelastic.peaks(t, c.h, c.histories, None if c.energy is None else c.energy["unknown_work"])
    return peaks


def _peaks_3d(s: Settings, c: Case) -> dict:
    """The summary of a case of a 3-D frame: the peaks of the base forces, end forces, footings,
    absolute accelerations and drift ratios with their times, the energy balance's and the inelastic ones."""
    t = c.h.t
    peaks = {"base_forces": {key: _extreme(t, values) for key, values in c.base.items()},
             "end_forces": _end_force_peaks(s, c)}
    if c.footings is not None:
        peaks["footings"] = footing_peaks(t, c.footings)
    if s.ground_motions:
        peaks["absolute_acceleration"] = acceleration_peaks(s.structure, c.h, c.motions, s.dim.acceleration_directions)
    if c.energy is not None:
        peaks["energy"] = energy_peaks(t, c.energy, s.energy_keys)
    if s.inelastic:
        peaks |= s.inelastic.peaks(t, c.h, c.histories, None if c.energy is None else c.energy["unknown_work"])
    if c.drifts:
        peaks["drift_ratio"] = {f"{label} {axis}": _abs_peak(t, d[f"max_ratio_{axis}"])
                                for label, d in c.drifts.items() for axis in "xy"}
    return peaks


#: The summary of a case by the dimension's name.
PEAKS = {"2-D": _peaks_2d, "3-D": _peaks_3d}
