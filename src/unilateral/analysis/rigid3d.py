"""The results of a 3-D frame with rigid contacts (``Frame3D.contact``, ``Frame3D.rigid_box``) for
``results.nc`` and ``summary.json``: :func:`structure_results_rigid_3d`.

Those of :func:`unilateral.analysis.results3d.structure_results_3d` on the frame's own part of the
solution (:func:`unilateral.analysis.rigid.frame_solution`), completed for the rigid contacts: their
forces and the boxes' held bases join the ground's reactions in the base forces
(:func:`unilateral.analysis.rigid.rigid_ground_reactions`), the energy balance takes the work of their
forces and the march's own terms (:func:`unilateral.analysis.rigid.add_rigid_energy`: the energy lost
at impacts, closing to round-off with the trapezoidal rule), and ``rigid_contacts`` holds the summary
of the contacts and boxes (:func:`unilateral.analysis.rigid.rigid_summary`).
"""

from __future__ import annotations

import numpy as np


def structure_results_rigid_3d(structure, model, cases, *, load, units, rule, point, storeys=None):
    """:func:`~unilateral.analysis.results3d.structure_results_3d` of a 3-D frame with rigid contacts
    (see the module): the same dict (``variables``, ``coords``, ``static``, ``peaks``, ``attrs``),
    its ``base_*`` variables and peaks with the contact forces, its ``energy_*`` with their work and
    ``peaks[case]["rigid_contacts"]``.

    Parameters
    ----------
    structure : the built 3-D frame with ``rigid`` (a ``RigidStructure3D``);  model : its Model
    cases : dict case -> Solution (every unknown: the frame's own, then the rigid contacts)
    load, units, rule, point, storeys : as for ``structure_results_3d``
    """
    from ..structure import forces3d as F3
    from .result_parts import _extreme, energy_peaks, energy_results, motions_at, pairing_rule, step_means
    from .results import _energy_keys, ground_motion_samples, load_samples_of
    from .results3d import structure_results_3d
    from .rigid import frame_solution, rigid_ground_reactions, rigid_summary

    parts = {case: frame_solution(structure, sol) for case, sol in cases.items()}
    out = structure_results_3d(structure, model, {case: frame for case, (_, frame) in parts.items()}, load=load,
                               units=units, rule=rule, point=point, storeys=storeys)
    units = units or {}
    moment = f"{units.get('force', '')} {units.get('length', '')}".strip()
    main = max(cases.values(), key=lambda sol: len(sol.t))
    samples = load_samples_of(load, main.t, main.stats.get("dt"))
    motions = ground_motion_samples(structure, load, main.t, main.stats.get("dt"))
    keys = _energy_keys(structure)
    for case, sol in cases.items():
        if case not in out["peaks"]:
            continue
        contact, frame = parts[case]
        h = F3.histories(structure, frame, rule, load0=None if samples is None else samples[0])
        reaction = F3.reactions(structure, h, frame)
        forces, at = rigid_ground_reactions(structure, h, sol, motions_at(step_means(motions, sol), h.t))
        reaction["ground_elements"] = {**reaction["ground_elements"], **forces}
        reaction["at"] = {**reaction["at"], **at}
        base = F3.base_forces(structure, reaction, out["attrs"]["base_point"])
        for key, values in base.items():
            out["variables"][f"base_{key}"][1][case] = np.asarray(values, dtype=float)
        out["peaks"][case]["base_forces"] = {key: _extreme(sol.t, values) for key, values in base.items()}
        if samples is not None:
            energy = energy_results(out["variables"], structure, h, samples, case=case, contact=contact, keys=keys,
                                    unit=moment, rule=pairing_rule(sol, rule), stats=sol.stats)
            out["peaks"][case]["energy"] = energy_peaks(h.t, energy, keys)
        out["peaks"][case]["rigid_contacts"] = rigid_summary(structure, sol)
    return out

