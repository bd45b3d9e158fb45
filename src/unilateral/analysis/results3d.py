"""The results of a 3-D frame for ``results.nc`` and ``summary.json`` (:func:`structure_results_3d`).

The 3-D counterpart of :func:`unilateral.analysis.results.structure_results`: base forces, support
and ground reactions, drift ratios, accelerations (relative, absolute, of every node), end forces,
yield and friction histories and the energy balance, from the load and ground-motion samples the
run used (:func:`unilateral.analysis.results.load_samples_of`,
:func:`unilateral.analysis.results.ground_motion_samples`).
"""

from __future__ import annotations

import numpy as np


def structure_results_3d(structure, model, cases, *, load, units, rule, point, storeys=None):
    """The results of a 3-D frame for :func:`unilateral.analysis.outputs._with_results`, per case: the base forces of
    :func:`unilateral.structure.forces3d.base_forces` (``base_Fx`` ... ``base_Mz``, time) about
    ``point`` (default: the centre of the base), the support and ground reactions, the drift ratios,
    the accelerations (``acceleration``, ``absolute_acceleration``, ``ground_acceleration``), the end
    forces of :func:`unilateral.structure.forces3d.end_forces` (``end_force``, ``axial_force``), the
    histories of the yield and friction elements (:mod:`unilateral.analysis.inelastic`: hinges and
    friction cones with the components ``roty``, ``rotz`` and ``t1``, ``t2``) and, with a load, the
    energy balance (``energy_*``), and their peaks."""
    from ..structure import forces3d as F3
    from .inelastic import Inelastic
    from .results import (_abs_peak, _energy_keys, _extreme, _put, acceleration_peaks, acceleration_results,
                          bilateral_modes, energy_peaks, energy_results, ground_motion_samples, load_samples_of,
                          pairing_rule, step_means)

    units = units or {}
    force, length, time = units.get("force", ""), units.get("length", ""), units.get("time", "")
    acc_unit = f"{length}/{time}^2" if length and time else ""
    moment = f"{force} {length}".strip()
    main = max(cases.values(), key=lambda sol: len(sol.t))
    samples = load_samples_of(load, main.t, main.stats.get("dt"))
    motions = ground_motion_samples(structure, load, main.t, main.stats.get("dt"))
    point = F3.base_point(structure) if point is None else tuple(float(x) for x in point)
    variables, peaks, coords = {}, {}, {}
    energy_keys = _energy_keys(structure)
    inelastic = Inelastic(structure, units)
    coords |= inelastic.coords()
    for case, sol in cases.items():
        if sol.u is None or len(sol.t) < 2:
            continue
        h = F3.histories(structure, sol, rule, load0=None if samples is None else samples[0])
        case_motions = step_means(motions, sol)
        acceleration_results(variables, coords, structure, h, case_motions, case=case, unit=acc_unit)
        _node_accelerations(variables, structure, h, case_motions, case=case, unit=acc_unit)
        ends = _end_forces(variables, coords, structure, h, case=case, units=units)
        base = _reactions(variables, coords, structure, h, sol, case=case, point=point, units=units)
        peaks[case] = {"base_forces": {key: _extreme(sol.t, values) for key, values in base.items()},
                       "end_forces": {name: {comp: _abs_peak(h.t, f[:, k]) for k, comp in enumerate(F3.END_COMPONENTS)
                                             if np.any(f[:, k])} for name, f in ends.items()}}
        if structure.foundation is not None:
            peaks[case]["footings"] = _footings(variables, coords, structure, h, sol, case=case, units=units)
        if motions:
            peaks[case]["absolute_acceleration"] = acceleration_peaks(structure, h, case_motions, ("ux", "uy", "uz"))
        energy = None
        if samples is not None:
            fnd = structure.foundation
            energy = energy_results(variables, structure, h, samples, case=case,
                                    contact=None if fnd is None else fnd.contact_load(structure, sol),
                                    keys=energy_keys, unit=moment, rule=pairing_rule(sol, rule))
            peaks[case]["energy"] = energy_peaks(h.t, energy, energy_keys)
        if inelastic:                           # the frame's own unknowns (h: without the footings')
            histories = inelastic.histories(h, structure.element_deformations(h.u, h.v, h.t)[0])
            for name, (dims, values, long_name, unit) in histories.items():
                _put(variables, name, dims, case, values, long_name, unit)
            peaks[case] |= inelastic.peaks(h.t, h, histories, None if energy is None else energy["unknown_work"])
        drift_peaks = _drift_ratios(variables, coords, structure, h, sol, case=case)
        if drift_peaks is not None:
            peaks[case]["drift_ratio"] = drift_peaks
    _, static = bilateral_modes(structure, model, peaks, coords, time_unit=units.get("time", ""))
    return {"variables": variables, "coords": coords, "static": static, "peaks": peaks,
            "attrs": {"base_point": list(point)}}


#: The long names of the base forces (``base_Fx`` ... ``base_Mz``).
BASE_WORDS = {"Fx": "base shear along x", "Fy": "base shear along y", "Fz": "vertical force of the ground (up)",
              "Mx": "base moment about x", "My": "base moment about y", "Mz": "base torque about z"}


def _end_forces(variables, coords, structure, h, *, case, units) -> dict:
    """The variables ``end_force`` (time, element, end_component) and ``axial_force`` (time, element)
    of ``case``; returns :func:`unilateral.structure.forces3d.end_forces` (the peaks use it)."""
    from ..structure import forces3d as F3
    from .results import _put, element_end_forces

    force, length = units.get("force", ""), units.get("length", "")
    moment = f"{force} {length}".strip()
    ends = F3.end_forces(structure, h)
    end = element_end_forces(coords, structure, ends, F3.END_COMPONENTS)
    _put(variables, "end_force", ("time", "element", "end_component"), case, end,
         "end forces and moments on the element in its local axes x' (i->j), y', z' (N, Vy, Vz along them; T, "
         "My, Mz about them, right-hand positive)", f"{force} (N, V); {moment} (T, M)".strip())
    axial = np.where(np.any(end[:, :, 6] != 0, axis=0), end[:, :, 6], end[:, :, 9])
    _put(variables, "axial_force", ("time", "element"), case, axial,
         "element force along its axis, tension positive (moment of a rotational spring)", force)
    return ends


def _reactions(variables, coords, structure, h, sol, *, case, point, units) -> dict:
    """The reactions of ``case``: ``support_reaction`` (time, support), ``ground_reaction``
    (:func:`_ground_reactions`) and the base forces ``base_Fx`` ... ``base_Mz`` (time,) about
    ``point`` (x, y, z); returns :func:`unilateral.structure.forces3d.base_forces`."""
    from ..structure import forces3d as F3

    force, length = units.get("force", ""), units.get("length", "")
    moment = f"{force} {length}".strip()
    reaction = F3.reactions(structure, h, sol)
    base = F3.base_forces(structure, reaction, point)
    if reaction["support"]:
        coords["support"] = list(reaction["support"])
        entry = variables.setdefault("support_reaction", (("time", "support"), {}, {
            "long_name": "force (moment about rx, ry, rz) of the support on the structure at node.dof",
            **({"units": f"{force} or {moment}"} if force else {})}))
        entry[1][case] = np.column_stack(list(reaction["support"].values()))
    _ground_reactions(variables, coords, case, {**reaction["ground_elements"], **reaction.get("footings", {})},
                      units)
    for key, values in base.items():
        unit = force if key.startswith("F") else f"{force} {length}".strip()
        entry = variables.setdefault(f"base_{key}", (("time",), {}, {
            "long_name": f"{BASE_WORDS[key]}, the resultant of the ground's forces on the structure"
                         + ("" if key.startswith("F") else " about base_point"), **({"units": unit} if unit else {})}))
        entry[1][case] = np.asarray(values, dtype=float)
    return base


def _footings(variables, coords, structure, h, sol, *, case, units) -> dict:
    """The footings' histories of ``case`` as variables (time, foundation); returns their peaks
    (:func:`unilateral.analysis.footing_results.footing_peaks`)."""
    from .footing_results import footing_histories, footing_peaks, footing_variables
    from .results import _put

    footings = footing_histories(structure.foundation, structure, h.u, sol, three_d=True)
    coords["foundation"] = list(footings)
    for name, (values, long_name, unit) in footing_variables(footings, units).items():
        _put(variables, name, ("time", "foundation"), case, values, long_name, unit)
    return footing_peaks(h.t, footings)


def _drift_ratios(variables, coords, structure, h, sol, *, case) -> dict | None:
    """The interstorey drift ratios ``drift_ratio_x``, ``drift_ratio_y`` (time, storey) of ``case``,
    the largest over each plan's corners; returns their peaks (``"<storey> <axis>"`` -> peak), or
    None without storeys."""
    from ..structure import forces3d as F3
    from .results import _abs_peak

    drifts = F3.storey_drifts(structure, h)
    if not drifts:
        return None
    coords["storey"] = list(drifts)
    for axis in "xy":
        entry = variables.setdefault(f"drift_ratio_{axis}", (("time", "storey"), {}, {
            "long_name": f"interstorey drift ratio along {axis}, the largest over the plan's corners",
            "units": "1"}))
        entry[1][case] = np.column_stack([d[f"max_ratio_{axis}"] for d in drifts.values()])
    return {f"{label} {axis}": _abs_peak(sol.t, d[f"max_ratio_{axis}"]) for label, d in drifts.items() for axis in "xy"}


def _ground_reactions(variables, coords, case, grounded: dict, units) -> None:
    """The variable ``ground_reaction`` (time, ground_element, force_component) of ``case``: the force and
    moment (N+1, 6) of the ground on the structure through each element or footing patch of ``grounded``."""
    from ..structure.forces3d import BASE_COMPONENTS

    if not grounded:
        return
    force, length = units.get("force", ""), units.get("length", "")
    coords["ground_element"] = list(grounded)
    coords["force_component"] = list(BASE_COMPONENTS)
    entry = variables.setdefault("ground_reaction", (("time", "ground_element", "force_component"), {}, {
        "long_name": "force and moment of the ground on the structure through the element or the footing "
                     "patch, at its node", **({"units": f"{force} (F); {force} {length} (M)"} if force else {})}))
    entry[1][case] = np.stack(list(grounded.values()), axis=1)


def _node_accelerations(variables, structure, h, motions, *, case, unit):
    """``node_acceleration`` (time, node, component) of a 3-D frame: the accelerations of the rule of every
    node's six DOFs relative to the ground (supported DOFs 0, rigidly linked nodes following their
    masters) and, under ground motions, ``node_absolute_acceleration``: plus the ground's translation
    ``sum a_g,k d_k`` on the ``ux``, ``uy``, ``uz`` of every node (a supported node moves with the ground)."""
    from .results import _put

    from .results import motions_at

    relative = structure.dofs.nodal(h.uddot)                    # (N+1, nodes, 6)
    _put(variables, "node_acceleration", ("time", "node", "component"), case, relative,
         "acceleration of every node relative to the ground (of the time rule)", f"{unit} (ux, uy, uz); rad/s^2 "
         "(rx, ry, rz)" if unit else "")
    if motions:
        absolute = relative.copy()
        for direction, a_g in motions_at(motions, h.t):
            d = np.zeros(relative.shape[2])
            d[list(structure.dofs.dof_names).index(direction)] = 1.0
            absolute += a_g[:, None, None] * d
        _put(variables, "node_absolute_acceleration", ("time", "node", "component"), case, absolute,
             "absolute acceleration of every node: relative plus the ground's", f"{unit} (ux, uy, uz); rad/s^2 "
             "(rx, ry, rz)" if unit else "")
