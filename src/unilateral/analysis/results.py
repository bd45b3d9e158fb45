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

A 3-D frame's results (:func:`unilateral.analysis.results3d.structure_results_3d`) share the
accelerations (:func:`acceleration_results`), the energy balance (:func:`energy_results`, the
arithmetic of :mod:`unilateral.analysis.energy` is that of the natural form, free of the dimension)
and the yield and friction elements' histories (:class:`~unilateral.analysis.inelastic.Inelastic`:
a 3-D hinge's and a friction cone's with the dimension ``yield_component`` or ``friction_component``);
its ``end_force`` has the twelve components of :func:`unilateral.structure.forces3d.end_forces`.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg import dense as _dense
from ..model import Model
from ..structure import forces as F
from ..structure import forces3d as F3
from .energy import energy_balance, unknown_kinds
from .rigid import frame_solution
from .inelastic import Inelastic
from ..structure.modes import modes

#: Models with more DOFs than this get no modes in the outputs (a dense eigenproblem).
MODES_MAX_N = 3000
ENERGY_KEYS = ("kinetic", "elastic_structure", "elastic_unilateral", "geometric", "damping_dissipated",
               "contact_dissipated", "plastic_work", "friction_work", "numerical_dissipation",
               "numerical_storage", "input_work", "support_work", "balance_error", "relative_error")
#: The energy terms written only for a structure with unknowns of that family.
FAMILY_ENERGY = {"plastic_work": "yield", "friction_work": "friction"}


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


def motions_at(ground_motions, t) -> list:
    """``[(direction, a_g (N+1,))]`` of ``ground_motions`` at the times ``t`` (N+1,): a time function is
    evaluated there, samples (of a longer run, :func:`ground_motion_samples`) are cut to ``t``'s length."""
    t = np.asarray(t, dtype=float)
    return [(d, np.asarray(a_g(t), dtype=float) if callable(a_g) else np.asarray(a_g, dtype=float)[: t.size])
            for d, a_g in ground_motions]


def step_means(ground_motions, sol) -> list:
    """``ground_motions`` as ``sol``'s accelerations read them: for a run of ``method="moreau-jean"``,
    whose accelerations are the means of the steps (:meth:`~unilateral.structure.forces.Histories.from_solution`),
    the theta-weighted means ``theta a_k + (1 - theta) a_{k-1}`` of the samples the step integrated
    (``[(direction, (N+1,))]``); the samples themselves for any other run."""
    stats = getattr(sol, "stats", None) or {}
    if stats.get("method") != "moreau-jean" or not ground_motions:
        return ground_motions
    theta, out = float(stats.get("theta", 0.5)), []
    for direction, a in motions_at(ground_motions, sol.t):
        mean = a.copy()
        mean[1:] = theta * a[1:] + (1.0 - theta) * a[:-1]
        out.append((direction, mean))
    return out


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
        point = (F3.base_point if dim.three_d else F.base_point)(structure)
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
    if model is not None and not dim.three_d:
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


def _frame_part(structure, foundation, sol, *, rigid=True):
    """``(contact, full, frame)``: the load (N+1, n) of the contact forces of the footings on a soil
    (``T c``, contact forces ``c = -psi``) or, with ``rigid``, of the rigid contacts (``N v``) on the
    frame, or None; the solution as solved; and the frame's own part of it, whose results are those
    of the frame alone loaded by ``q + contact``."""
    if foundation is not None:
        from ..structure.foundation import structural_solution

        return foundation.contact_load(structure, sol), sol, structural_solution(sol, foundation.first)
    if rigid and getattr(structure, "rigid", None) is not None:
        contact, frame = frame_solution(structure, sol)
        return contact, sol, frame
    return None, sol, sol


def _energy_keys(structure) -> tuple:
    """:data:`ENERGY_KEYS` without the plastic and friction work of families the structure lacks."""
    kinds = set(unknown_kinds(structure).tolist()) if structure.m else set()
    p_delta = getattr(structure, "geometric", None) is not None         # the geometric energy: with P-Delta only
    moving = getattr(structure.natural.theta, "motions", None) is not None    # support motions: their work
    return tuple(key for key in ENERGY_KEYS if (key not in FAMILY_ENERGY or FAMILY_ENERGY[key] in kinds)
                 and (key != "geometric" or p_delta) and (key != "support_work" or moving))


def element_end_forces(coords, structure, ends, components, steps=0) -> np.ndarray:
    """The end forces ``ends`` (element name -> (N+1, c)) as one array (N+1, elements, c), with the
    coordinates ``element``, ``element_kind`` and ``end_component`` (``components``) set in ``coords``
    (2-D and 3-D frames alike)."""
    names = list(ends)
    coords["element"] = names
    coords["element_kind"] = ("element", [_kind(structure, name) for name in names])
    coords["end_component"] = list(components)
    if not names:                       # a frame of rigid blocks only: no element
        return np.zeros((steps, 0, len(components)))
    return np.stack([ends[name] for name in names], axis=1)


def _kind(structure, name):
    for e in list(structure.elements) + list(structure.dashpots):
        if e.name == name:
            return e.kind
    return ""


def _extreme(t, y) -> dict:
    i, j = int(np.argmax(y)), int(np.argmin(y))
    return {"max": float(y[i]), "t_max": float(t[i]), "min": float(y[j]), "t_min": float(t[j])}


def _abs_peak(t, y) -> dict:
    i = int(np.argmax(np.abs(y)))
    return {"value": float(y[i]), "t": float(t[i])}


#: Storey drift ratio above which a model whose members cannot yield gets a note.
LINEAR_DRIFT_LIMIT = 0.02


def _linear_drift_note(structure, peaks: dict) -> str | None:
    """A note when the members are linear (no yield unknown: no hinge, no yield link) and a storey's
    peak drift ratio exceeds :data:`LINEAR_DRIFT_LIMIT`, else None."""
    drifts = peaks.get("drift_ratio") or {}
    if not drifts or any(u.kind == "yield" for _, u in structure.constraints):
        return None
    label, d = max(drifts.items(), key=lambda item: abs(item[1]["value"]))
    if abs(d["value"]) <= LINEAR_DRIFT_LIMIT:
        return None
    return (f"the members do not yield in this model: drifts above {100 * LINEAR_DRIFT_LIMIT:g} % (here "
            f"{100 * abs(d['value']):.3g} %, storey {label}) are those of elastic members, beyond what real members "
            "carry elastically; add plastic hinges or yield links for an inelastic response")


def _peaks(t, base, ends, reaction, drifts, energy, *, h, ground_motions, structure) -> dict:
    """Peaks with their times, for summary.json."""
    out = {key: _extreme(t, value) for key, value in base.items()}
    out["end_forces"] = {name: {comp: _abs_peak(t, f[:, k]) for k, comp in enumerate(F.END_COMPONENTS)
                                if np.any(f[:, k])} for name, f in ends.items()}
    out["support_reactions"] = {label: _extreme(t, f) for label, f in reaction["support"].items()}
    out["ground_reactions"] = {name: {c: _extreme(t, f[:, k]) for k, c in enumerate(("fx", "fy", "mz"))
                                      if np.any(f[:, k])}
                               for name, f in reaction["ground_elements"].items()}
    if drifts:
        out["drift_ratio"] = {label: _abs_peak(t, ratio) for label, (_, ratio) in drifts.items()}
        out["residual_drift"] = _residual_drift(t, drifts)
    if ground_motions:
        out["absolute_acceleration"] = acceleration_peaks(structure, h, ground_motions)
    if energy is not None:
        out["energy"] = energy_peaks(t, energy)
    return out


def _put(variables, name, dims, case, array, long_name, unit=""):
    """Add case ``case`` of the variable ``name`` to ``variables`` (name -> (dims, {case: array}, attrs))."""
    entry = variables.setdefault(name, (dims, {}, {"long_name": long_name} | ({"units": unit} if unit else {})))
    entry[1][case] = np.asarray(array, dtype=float)


def acceleration_results(variables, coords, structure, h, ground_motions, *, case, unit=""):
    """The accelerations of a case, 2-D or 3-D: ``acceleration`` (time, dof), the ``u''`` of the time
    rule relative to the ground, and under ground motions ``absolute_acceleration`` (time, dof),
    ``u'' + sum r_k a_g,k``, and ``ground_acceleration`` (time, excitation), each ``a_g,k`` (the
    coordinate ``excitation``: ``"<k>:<direction>"``)."""
    _put(variables, "acceleration", ("time", "dof"), case, h.uddot,
         "acceleration relative to the ground (of the time rule)", unit)
    if ground_motions:
        motions = motions_at(ground_motions, h.t)
        _put(variables, "absolute_acceleration", ("time", "dof"), case,
             F.absolute_acceleration(structure, h, motions), "absolute acceleration u'' + r a_g", unit)
        _put(variables, "ground_acceleration", ("time", "excitation"), case,
             np.column_stack([a_g for _, a_g in motions]),
             "ground acceleration a_g as the run used it (the record's hat-function averages over the steps, "
             "those of the input work)", unit)
        coords["excitation"] = [f"{k}:{d}" for k, (d, _) in enumerate(ground_motions)]


def acceleration_peaks(structure, h, ground_motions, directions=("ux", "uy")) -> dict:
    """The peak absolute acceleration (``value``, ``t``) of each free DOF with mass along ``directions``."""
    acc = F.absolute_acceleration(structure, h, motions_at(ground_motions, h.t))
    names = structure.dofs.names
    return {names[k]: _abs_peak(h.t, acc[:, k]) for k in range(acc.shape[1])
            if names[k].endswith(directions) and structure.M[k, k] > 0}


def energy_results(variables, structure, h, load_samples, *, case, contact=None, keys=ENERGY_KEYS, unit="",
                   rule=None, stats=None):
    """The energy balance of a case (:func:`unilateral.analysis.energy.energy_balance`, 2-D or 3-D, paired
    as the run's ``rule``), its terms ``keys`` added to ``variables`` as ``energy_<key>`` (time); returns
    the energies.

    ``contact`` (N+1, n): the footings' contact load ``T c`` on a frame on a soil medium (its work
    went into the soil, counted in ``contact_dissipated``); ``stats``: the run's, for the energies of
    rigid contacts (:func:`unilateral.analysis.rigid.add_rigid_energy`)."""
    energy = energy_balance(structure, h, np.asarray(load_samples)[: len(h.t)], rule=rule, contact=contact)
    if getattr(structure, "rigid", None) is not None:       # rigid contacts: analysis/rigid.py
        from .rigid import add_rigid_energy

        energy = add_rigid_energy(energy, structure, h.u, h.udot, stats or {})
    for key in keys:
        _put(variables, f"energy_{key}", ("time",), case, energy[key], f"energy: {key.replace('_', ' ')}",
             "1" if key == "relative_error" else unit)
    return energy


def pairing_rule(sol, rule):
    """The rule the energy balance of a run is paired with: the run's ``rule``, or None (the
    trapezoidal pairing) for a run that did not step by a rule (``method="event"``: exact
    integration between events)."""
    return None if sol.stats.get("method") == "event" else rule


def energy_peaks(t, energy, keys=()) -> dict:
    """The ``energy`` entry of a case's peaks: the largest relative error and its time, the input work,
    the damping and contact dissipation and the plastic and friction work among ``keys`` at the end,
    the largest kinetic energy."""
    k = int(np.argmax(energy["relative_error"]))
    out = {"max_relative_error": energy["max_relative_error"], "t_max_relative_error": float(t[k]),
           "input_work": float(energy["input_work"][-1]),
           "damping_dissipated": float(energy["damping_dissipated"][-1]),
           "contact_dissipated": float(energy["contact_dissipated"][-1]),
           "kinetic_max": float(energy["kinetic"].max()),
           "numerical_dissipation": float(energy["numerical_dissipation"][-1]),
           "numerical_share": energy["numerical_share"], "rule_identity": bool(energy["exact"])}
    return out | {key: float(energy[key][-1]) for key in (*FAMILY_ENERGY, "geometric", "support_work") if key in keys}


def _residual_drift(t, drifts) -> dict:
    """The storey drifts at the last step: the largest (``storey``, ``drift``, ``ratio``, ``t``) and
    every storey's (``storeys``: label -> ``drift``, ``ratio``)."""
    storeys = {label: {"drift": float(d[-1]), "ratio": float(r[-1])} for label, (d, r) in drifts.items()}
    label = max(storeys, key=lambda s: abs(storeys[s]["ratio"]))
    return {"storey": label, **storeys[label], "t": float(t[-1]), "storeys": storeys}
