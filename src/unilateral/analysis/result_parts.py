"""The parts of the structure's results that both dimensions share, for
:func:`unilateral.analysis.results.structure_results` and its steps (:mod:`unilateral.analysis.result_steps`):
the ground motions as a case's accelerations read them (:func:`motions_at`, :func:`step_means`), the
frame's own part of a solution (:func:`_frame_part`), the variables' table (:func:`_put`), the
accelerations (:func:`acceleration_results`), the end forces as one array (:func:`element_end_forces`),
the energy balance (:func:`energy_results`) and the peaks with their times (:func:`_extreme`,
:func:`_abs_peak`, :func:`_peaks`, :func:`energy_peaks`). :mod:`unilateral.analysis.results` gives
them by their names there too.
"""

from __future__ import annotations

import numpy as np

from ..structure import forces as F
from .energy import energy_balance
from .rigid import frame_solution

#: The terms of the energy balance written as ``energy_<key>`` (those the structure has:
#: :func:`unilateral.analysis.results._energy_keys`).
ENERGY_KEYS = ("kinetic", "elastic_structure", "elastic_unilateral", "geometric", "damping_dissipated",
               "contact_dissipated", "plastic_work", "friction_work", "numerical_dissipation",
               "numerical_storage", "input_work", "support_work", "balance_error", "relative_error")
#: The energy terms written only for a structure with unknowns of that family.
FAMILY_ENERGY = {"plastic_work": "yield", "friction_work": "friction"}


def motions_at(ground_motions, t) -> list:
    """``[(direction, a_g (N+1,))]`` of ``ground_motions`` at the times ``t`` (N+1,): a time function is
    evaluated there, samples (of a longer run,
    :func:`unilateral.analysis.results.ground_motion_samples`) are cut to ``t``'s length."""
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
