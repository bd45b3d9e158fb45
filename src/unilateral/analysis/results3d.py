"""The results of a 3-D frame for ``results.nc`` and ``summary.json``: :func:`structure_results_3d`.

Those of :func:`unilateral.analysis.results.structure_results`, the one pipeline of 2-D and 3-D
frames (the 3-D names, components and units: :data:`unilateral.analysis.dimension.THREE_D`): base
forces, support and ground reactions, drift ratios, accelerations (relative, absolute, of every
node), end forces, yield and friction histories and the energy balance, from the load and
ground-motion samples the run used (:func:`unilateral.analysis.results.load_samples_of`,
:func:`unilateral.analysis.results.ground_motion_samples`).
"""

from __future__ import annotations

from .results import results_of_load


def structure_results_3d(structure, model, cases, *, load, units, rule, point, storeys=None) -> dict:
    """The results of a 3-D frame per case (:func:`unilateral.analysis.results.results_of_load`): the base
    forces of :func:`unilateral.structure.forces3d.base_forces` (``base_Fx`` ... ``base_Mz``, time) about
    ``point`` (default: the centre of the base), the support and ground reactions, the drift ratios,
    the accelerations (``acceleration``, ``absolute_acceleration``, ``ground_acceleration``,
    ``node_acceleration``), the end forces of :func:`unilateral.structure.forces3d.end_forces`
    (``end_force``, ``axial_force``), the histories of the yield and friction elements
    (:mod:`unilateral.analysis.inelastic`: hinges and friction cones with the components ``roty``,
    ``rotz`` and ``t1``, ``t2``) and, with a load, the energy balance (``energy_*``), and their peaks.

    Parameters
    ----------
    structure : Structure3D;  model : its Model;  cases : dict case -> Solution
    load : LoadHistory, array or callable (or None);  units : dict of the base units
    rule : the time rule of the runs;  point : (x, y, z) of the base moments, or None
    storeys : unused (the storeys of a 3-D frame are its levels)

    Returns
    -------
    dict: ``variables``, ``coords``, ``static``, ``peaks``, ``attrs`` (``base_point``)
    """
    return results_of_load(structure, model, cases, load=load, units=units, rule=rule, point=point, storeys=storeys)
