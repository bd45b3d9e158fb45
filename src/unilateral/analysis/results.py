"""The structure's results of solved cases: variables for ``results.nc`` and peaks for the summary.

:func:`structure_results` computes, per case, from a :class:`~unilateral.structure.Structure` and
its :class:`~unilateral.Solution` (sign conventions in :mod:`unilateral.structure.forces`):

========================  =====================================  ===================================
variable                  dims                                   content
========================  =====================================  ===================================
``acceleration``          time, dof                              ``u''`` of the rule (relative)
``absolute_acceleration`` time, dof                              ``u'' + r a_g`` (ground motion only)
``ground_acceleration``   time, excitation                       ``a_g`` as the run sampled it
``end_force``             time, element, end_component           ``N_i, V_i, M_i, N_j, V_j, M_j``
``axial_force``           time, element                          ``N_j``: tension positive
``support_reaction``      time, support                          force of the ground at ``node.dof``
``ground_reaction``       time, ground_element, component        ``fx, fy, mz`` of soil and springs
``base_shear``            time                                   sum of the ground's x forces
``base_vertical``         time                                   sum of the ground's y forces
``overturning_moment``    time                                   about ``overturning_point``
``storey_drift``          time, storey                           ``ux`` upper - lower
``drift_ratio``           time, storey                           drift / storey height
``constraint_deformation`` time, constraint                      total strain of each constraint's strain
``plastic_deformation``,  time, yield_element;                   yield and friction elements
``slip``, ...             time, friction_element                 (:mod:`unilateral.analysis.inelastic`)
``energy_*``              time                                   :mod:`unilateral.analysis.energy`
``mode_period``,          mode; mode, dof                        bilateral periods and shapes
``mode_shape``, ...
========================  =====================================  ===================================

A 3-D frame's results come from the same function, one pipeline for both dimensions
(:mod:`unilateral.analysis.result_steps`), what differs reduced to the data of a
:class:`~unilateral.analysis.dimension.Dimension`: the names of the components (``end_force`` has the
twelve of :func:`unilateral.structure.forces3d.end_forces`, ``ground_reaction`` ``Fx ... Mz``), the
units and long names that differ, the base point (``base_point``: the six resultants ``base_Fx`` ...
``base_Mz`` about it), the directions of the ground's translations, and which steps write what in
which order (``node_acceleration`` and ``drift_ratio_x``, ``drift_ratio_y`` in 3-D;
``constraint_deformation``, ``storey_drift``, the static residual and each frame's base shear in
2-D). They share the accelerations (:func:`acceleration_results`), the energy balance
(:func:`energy_results`, the arithmetic of :mod:`unilateral.analysis.energy` is that of the natural
form, free of the dimension) and the yield and friction elements' histories
(:class:`~unilateral.analysis.inelastic.Inelastic`: a 3-D hinge's and a friction cone's with the
dimension ``yield_component`` or ``friction_component``). The shared parts live in
:mod:`unilateral.analysis.result_parts` and are importable from here by their names.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg import dense as _dense
from ..model import Model
from ..structure import forces as F
from ..structure.modes import modes
from .energy import unknown_kinds
from .inelastic import Inelastic
from .result_parts import ENERGY_KEYS, FAMILY_ENERGY

#: Models with more DOFs than this get no modes in the outputs (a dense eigenproblem).
MODES_MAX_N = 3000

def ground_terms(structure, load) -> list:
    """``[(direction, term, c)]``: the ground-motion terms ``(-M r, a_g)`` of a LoadHistory, each as
    the index ``term`` of its term in ``load.terms`` and the share ``c`` of it along ``direction``
    (``ux``, ``uy`` and, for a 3-D frame, ``uz``). A term along a vector ``d`` (``r = sum_k d_k r_k``,
    a record at an angle in plan) is one entry per axis it moves along, ``(axis, term, d_k)``; a
    term along one axis is ``(axis, term, 1.0)``."""
    out = []
    names = getattr(structure.dofs, "dof_names", ("ux", "uy", "rz"))
    axes = [d for d in ("ux", "uy", "uz") if d in names]
    patterns = np.column_stack([-np.asarray(structure.M @ structure.influence(d)).ravel() for d in axes])
    # -T^T M_full r_full: with a mass on a slave of a held master that rotates (a rigid box's centre
    # over its held base) it differs from -M r (rigid.ground_motion builds the terms so)
    weights = np.column_stack([-structure.gravity(1.0, tuple(float(a == d) for a in axes)) for d in axes])
    for term, (vector, _) in enumerate(getattr(load, "terms", ())):
        vector = np.asarray(vector, dtype=float)
        single = [d for k, d in enumerate(axes)
                  if any(p[:, k].any() and np.allclose(vector, p[:, k], rtol=1e-12, atol=0.0) for p in (patterns, weights))]
        if single:
            out.append((single[0], term, 1.0))
            continue
        if len(axes) < 3 or not vector.any():
            continue                                        # vectors: 3-D frames (model files, Frame3D.influence)
        d, *_ = np.linalg.lstsq(patterns, vector, rcond=None)
        along = np.abs(d) > 1e-15
        if (along.sum() >= 2 and np.abs(patterns @ d - vector).max() <= 1e-12 * np.abs(vector).max()
                and abs(np.linalg.norm(d) - 1.0) <= 1e-9):
            out += [(axis, term, float(c)) for axis, c, on in zip(axes, d, along) if on]
    return out


def ground_motions_of(structure, load) -> list:
    """``[(direction, a_g)]`` of the ground-motion terms of a LoadHistory (:func:`ground_terms`), ``a_g``
    the time function of the record (its point values; the run used :func:`ground_motion_samples`).
    The accelerations and spectra that sum ``r_k a_g,k`` see the same ground motion."""
    out = []
    for direction, term, c in ground_terms(structure, load):
        f = load.terms[term][1]
        out.append((direction, f if c == 1.0 else _Scaled(f, c)))
    return out


def ground_motion_samples(structure, load, t, dt=None) -> list:
    """``[(direction, a_g)]`` with ``a_g`` (N+1,) the ground accelerations the run used at the times ``t``.

    The time-stepping integrates each term of a :class:`~unilateral.loads.LoadHistory` through its
    samples of :meth:`~unilateral.loads.LoadHistory.grid_factors` (hat-function averages, row 0
    one-sided at ``t = 0+``; :func:`unilateral.methods.common.step_loads`), not through the record's
    point values: with these samples the absolute accelerations close the equations of motion at every
    step (base shear = ``r^T (M a_abs + C u')``), and they are the ones the input work of the energy
    balance takes. A time axis that is not uniform (step ``dt``, default ``t[1] - t[0]``) takes the
    point values.

    Parameters
    ----------
    structure : Structure
    load : LoadHistory, or anything else (no ground motion: ``[]``)
    t : (N+1,) times [time unit], ``t_k = k dt``
    dt : float, optional: the run's time step [time unit]

    Returns
    -------
    list of ``(direction, ndarray (N+1,))`` [length/time^2], in the order of :func:`ground_terms`
    """
    terms = ground_terms(structure, load)
    if not terms:
        return []
    t = np.asarray(t, dtype=float)
    step = float(dt) if dt else (float(t[1] - t[0]) if t.size > 1 else 0.0)
    if t.size > 1 and callable(getattr(load, "grid_factors", None)) and \
            np.allclose(np.diff(t), step, rtol=1e-9, atol=0.0):
        factors = load.grid_factors(step, t.size - 1)[0]
        return [(direction, c * np.asarray(factors[:, term], dtype=float)) for direction, term, c in terms]
    return [(direction, c * np.asarray(load.terms[term][1](t), dtype=float)) for direction, term, c in terms]


def load_samples_of(load, t, dt=None):
    """The applied load (N+1, n) the run used at the times ``t`` (step ``dt``, default ``t[1] - t[0]``),
    or None without a load.

    A :class:`~unilateral.loads.LoadHistory` gives the samples the time-stepping used, its hat-function
    averages (:meth:`~unilateral.loads.LoadHistory.grid_samples`, row 0 one-sided at ``t = 0+``, as
    :mod:`unilateral.methods.common` and the batch's energy balance take them), not its point values:
    with these the accelerations of the rule satisfy the equations of motion at every step (the
    initial acceleration is that of row 0) and the work of the loads is the work the run put in.
    """
    if load is None:
        return None
    if isinstance(load, np.ndarray):
        return np.asarray(load, dtype=float)[: len(t)]
    if callable(getattr(load, "grid_samples", None)) and len(t) > 1:
        step = float(dt) if dt else float(t[1] - t[0])
        if np.allclose(np.diff(t), step, rtol=1e-9, atol=0.0):
            return np.asarray(load.grid_samples(step, len(t) - 1)[0], dtype=float)
    if callable(getattr(load, "sample", None)):
        return np.asarray(load.sample(t), dtype=float)
    if callable(load):
        return np.array([load(tk) for tk in t], dtype=float)
    return None


class _Scaled:
    """``c f(t)``: the component of a ground acceleration ``f`` along one axis."""

    def __init__(self, f, c):
        self.f, self.c = f, c

    def __call__(self, t):
        return self.c * np.asarray(self.f(t), dtype=float)


def structure_results(structure, model, cases: dict, *, rule, load_samples=None, ground_motions=(),
                      point=None, storey_pairs=None, units=None, static_load=None) -> dict:
    """Results of each solved case of a frame, 2-D or 3-D.

    One pipeline for both (:func:`unilateral.analysis.result_steps.case_results`), the dimension's
    names, components, units and steps from its :class:`~unilateral.analysis.dimension.Dimension`.
    A 3-D frame's rigid contacts are completed by
    :func:`unilateral.analysis.rigid3d.structure_results_rigid_3d` (``cases``: the frame's parts).

    Parameters
    ----------
    structure : Structure (2-D) or Structure3D
    model : Model (for the modes)
    cases : dict name -> Solution
    rule : the time rule of the runs (name or Rule)
    load_samples : (N+1, n) applied load at the steps, optional (energy input and initial
        acceleration; without it no energy balance is computed)
    ground_motions : ``[(direction, a_g)]``: the samples (N+1,) the run used, :func:`ground_motion_samples`
        (or time functions, :func:`ground_motions_of`, evaluated at the steps)
    point : (x0, y0) of the overturning moment of a 2-D frame, (x, y, z) of the base forces of a
        3-D one; default: the centre of the base (:func:`unilateral.structure.forces.base_point`:
        the mean x of the ground-connected nodes at the lowest level;
        :func:`unilateral.structure.forces3d.base_point`)
    storey_pairs : ``[(lower, upper)]`` nodes of the storeys of a 2-D frame; default: levels by elevation
    units : dict of the base units (for the attributes)
    static_load : (n,) the load without the excitation, for the static residual of a 2-D frame
        (default: ``load_samples[0]``)

    Returns
    -------
    dict with ``variables`` (name -> (dims, {case: array}, attrs)), ``coords`` (name -> values),
    ``static`` (name -> (dims, array, attrs)): case-independent variables (modes),
    ``peaks`` (case -> summary dict), ``attrs`` (dataset attributes).
    """
    from .dimension import Units, dimension_of
    from .result_steps import Settings, case_results

    dim = dimension_of(structure)
    if point is None:
        point = dim.forces.base_point(structure)
    else:
        point = tuple(float(x) for x in point) if dim.three_d else (float(point[0]), float(point[1]))
    unit_dict = dict(units or {})
    s = Settings(structure, dim, Units.of(unit_dict), unit_dict, rule, point, Inelastic(structure, unit_dict),
                 _energy_keys(structure), load_samples=load_samples, ground_motions=list(ground_motions),
                 storey_pairs=storey_pairs, static_load=static_load)
    s.coords |= s.inelastic.coords()
    peaks = {case: case_results(s, case, sol) for case, sol in cases.items()
             if sol.u is not None and len(sol.t) >= 2}
    model, static = bilateral_modes(structure, model, peaks, s.coords, time_unit=s.units.time)
    if model is not None and dim.frame_periods:
        apart = _frame_periods(structure, model)
        for p in peaks.values():
            if apart:
                p["frame_periods"] = apart
    return {"variables": s.variables, "coords": s.coords, "static": static, "peaks": peaks,
            "attrs": {dim.point_attribute: list(point)}}


def results_of_load(structure, model, cases, *, load, units, rule, point, storeys=None) -> dict:
    """:func:`structure_results` of ``cases`` under ``load`` (a LoadHistory, array or callable): with the
    load and ground-motion samples the runs used (:func:`load_samples_of`, :func:`ground_motion_samples`)
    on the longest time axis of the cases, and the load's ``constant`` part as the static load."""
    main = max(cases.values(), key=lambda sol: len(sol.t))        # the longest time axis
    dt = main.stats.get("dt")
    return structure_results(structure, model, cases, rule=rule, load_samples=load_samples_of(load, main.t, dt),
                             ground_motions=ground_motion_samples(structure, load, main.t, dt), point=point,
                             storey_pairs=storeys, units=units, static_load=getattr(load, "constant", None))


def bilateral_modes(structure, model, peaks: dict, coords: dict, *, time_unit="", directions=("x", "y")):
    """The modes of the bilateral structure (a footing on the soil's static springs): ``(model, static)``
    with ``static`` the variables ``mode_period``, ``mode_frequency``, ``mode_shape`` and
    ``mode_mass_ratio_<direction>`` (the coordinate ``mode`` added to ``coords``, the periods to
    every case of ``peaks``); ``model`` is None (and ``static`` empty) where there are none (a soil
    without static flexibility) or the model is too large (:data:`MODES_MAX_N`)."""
    static = {}
    if getattr(structure, "foundation", None) is not None:     # the bilateral structure: on static springs
        try:
            model = model.static_model()
        except ValueError:                  # a soil without static flexibility (creep): no modes
            return None, static
    if model.n > MODES_MAX_N:
        return model, static
    info = modes(model, count=10, influence={d: structure.influence(f"u{d}") for d in directions})
    if info["period"].size:
        coords["mode"] = np.arange(1, info["period"].size + 1)
        static["mode_period"] = (("mode",), info["period"], {"long_name": "period of the bilateral structure",
                                                              "units": time_unit})
        static["mode_frequency"] = (("mode",), info["frequency"], {"long_name": "frequency",
                                                                    "units": f"1/{time_unit}"})
        static["mode_shape"] = (("mode", "dof"), info["shape"], {"long_name": "mode shape (largest component 1)"})
        for name, values in info["effective_mass"].items():
            total = info["total_mass"][name]
            static[f"mode_mass_ratio_{name}"] = (("mode",), values / total if total else values,
                                                 {"long_name": f"effective modal mass ratio along {name}"})
        for p in peaks.values():
            p["periods"] = info["period"].tolist()
    return model, static


def _frame_periods(structure, model, count=3) -> dict:
    """The lowest periods of each separate frame with the gaps between them open, if there are several.

    The bilateral structure's modes hold every gap closed: two buildings that pound move as one.
    Each frame alone is its part of ``K`` without the gap elements (``G E G^T`` over the other
    elements' strains) and of ``M``. Returns frame label -> up to ``count`` periods; empty for one
    frame (or a foundation model).
    """
    from types import SimpleNamespace

    groups = F.frames(structure)
    gaps = [e for e in structure.elements if e.kind == "gap"]
    if len(groups) < 2 or not gaps or not isinstance(model, Model):
        return {}
    nat = structure.natural
    keep = np.concatenate([np.full(e.E.shape[0], e.kind != "gap") for e in structure.elements])
    G = sp.csr_matrix(nat.G)[:, np.flatnonzero(keep)]
    E = sp.csr_matrix(nat.E)[np.flatnonzero(keep)][:, np.flatnonzero(keep)]
    K = (G @ E @ G.T).toarray()
    if structure.geometric is not None:
        K = K + structure.geometric.toarray()
    M = _dense(model.M)
    dofs = structure.dofs
    out = {}
    for nodes in groups:
        members = {dofs.masters.get(node, node) for node in nodes}
        idx = [k for k, (node, _) in enumerate(dofs.free) if node in members]
        if not idx:
            continue
        info = modes(SimpleNamespace(K=K[np.ix_(idx, idx)], M=M[np.ix_(idx, idx)]), count=count)
        if info["period"].size:
            out[f"frame of node {nodes[0]}"] = info["period"].tolist()
    return out


def _energy_keys(structure) -> tuple:
    """:data:`ENERGY_KEYS` without the plastic and friction work of families the structure lacks."""
    kinds = set(unknown_kinds(structure).tolist()) if structure.m else set()
    p_delta = getattr(structure, "geometric", None) is not None         # the geometric energy: with P-Delta only
    moving = getattr(structure.natural.theta, "motions", None) is not None    # support motions: their work
    return tuple(key for key in ENERGY_KEYS if (key not in FAMILY_ENERGY or FAMILY_ENERGY[key] in kinds)
                 and (key != "geometric" or p_delta) and (key != "support_work" or moving))
