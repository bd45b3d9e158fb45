"""Energy balance of a solved structure, step by step.

From the equations of motion in natural form, ``M u'' + C u' + G sigma = q`` with
``sigma = E eps + E_v eps'``, ``eps = G^T u - B v - theta``, and ``B^T sigma = psi + r`` (``A = 0``):

    W_in = (T - T_0) + (U - U_0) + D_damping + D_contact

* ``T = u'^T M u' / 2``: kinetic energy (relative to the ground under a ground motion);
* ``U = sum eps^T E eps / 2``: elastic energy, of the bilateral elements (``elastic_structure``) and
  of the unilateral elements (``elastic_unilateral``);
* ``D_damping = int u'^T C u' dt``: dissipated by Rayleigh damping and attached dashpots;
* ``D_contact = int (eps'^T E_v eps' + (r - psi)^T v') dt``: dissipated by the Kelvin dashpots of
  contacts, by slip at a capacity ``r``, and by the reactions at the switches of contact
  (``psi^T v' = 0`` in continuous time; the discrete contact switch loses ``-psi^T dv`` over a
  step, which vanishes as ``dt -> 0``);
* ``W_in = int q^T u' dt``: the work of the applied loads (gravity, pulses, ``-M r a_g``).

The integrals use the trapezoidal rule on the step increments, e.g.
``W_in += (q_n + q_{n-1})^T (u_n - u_{n-1}) / 2``. With these quadratures the balance of the
trapezoidal time-stepping rule is exact (to round-off) for linear structures, with or without
contact; other rules leave an error of their order (measured in ``tests/test_energy.py``).
The relative error is the balance residual over the largest energy of the run (input work,
kinetic energy, change of elastic energy or energy dissipated).
"""

from __future__ import annotations

import numpy as np


def energy_balance(structure, h, q) -> dict:
    """Energies (N+1,) of a solved structure and the relative error of their balance.

    Parameters
    ----------
    structure : Structure
    h : :class:`unilateral.structure.forces.Histories`
    q : (N+1, n) applied load at the steps (as the run used it; imposed strains excluded)

    Returns
    -------
    dict of (N+1,) arrays: ``kinetic``, ``elastic_structure``, ``elastic_unilateral``,
    ``damping_dissipated``, ``contact_dissipated``, ``input_work``, ``balance_error`` (the
    residual ``W_in - dT - dU - D``), ``relative_error`` (the residual over the largest energy
    of the run: input work, kinetic, change of elastic, or dissipated); and ``max_relative_error`` (float).
    """
    nat = structure.natural
    q = np.asarray(q, dtype=float)
    M, C = structure.M, structure.C
    udot, u, v, vdot = h.udot, h.u, h.v, h.vdot
    kinetic = 0.5 * np.einsum("ki,ki->k", udot, (M @ udot.T).T)
    theta = nat.theta(0.0)
    eps = (nat.G.T @ u.T).T - (nat.B @ v.T).T - theta
    Eeps = (nat.E @ eps.T).T
    density = 0.5 * eps * Eeps                      # per strain (E is block diagonal)
    unilateral = np.zeros(eps.shape[1], dtype=bool)
    unilateral[structure.constraint_strains] = True
    elastic_u = density[:, unilateral].sum(axis=1)
    elastic_s = density[:, ~unilateral].sum(axis=1)
    du = np.diff(u, axis=0)
    work = _cumulative(0.5 * np.einsum("ki,ki->k", q[1:] + q[:-1], du))
    damping = np.zeros(len(h.t))
    if C is not None:
        Cud = (C @ udot.T).T
        damping = _cumulative(0.5 * np.einsum("ki,ki->k", Cud[1:] + Cud[:-1], du))
    contact = np.zeros(len(h.t))
    if nat.E_v is not None:
        eps_rate = (nat.G.T @ udot.T).T - (nat.B @ vdot.T).T
        viscous = (nat.E_v @ eps_rate.T).T
        contact += _cumulative(0.5 * np.einsum("ki,ki->k", viscous[1:] + viscous[:-1], np.diff(eps, axis=0)))
    if v.shape[1]:
        b = np.asarray(nat.B.sum(axis=0)).ravel()
        sigma_b = (np.asarray(Eeps)[:, structure.constraint_strains] * b)     # b sigma, elastic part
        if nat.E_v is not None:
            sigma_b = sigma_b + viscous[:, structure.constraint_strains] * b
        # work of b sigma = psi + r on v': the capacity slip and the contact switches
        contact += _cumulative(0.5 * np.einsum("ki,ki->k", sigma_b[1:] + sigma_b[:-1], np.diff(v, axis=0)))
    T0, U0 = kinetic[0], elastic_s[0] + elastic_u[0]
    residual = work - (kinetic - T0) - (elastic_s + elastic_u - U0) - damping - contact
    scale = float(np.max(np.maximum.reduce([np.abs(work), kinetic, np.abs(elastic_s + elastic_u - U0),
                                            damping + contact]), initial=0.0))
    relative = np.abs(residual) / scale if scale > 0 else np.zeros_like(residual)
    return {"kinetic": kinetic, "elastic_structure": elastic_s, "elastic_unilateral": elastic_u,
            "damping_dissipated": damping, "contact_dissipated": contact, "input_work": work,
            "balance_error": residual, "relative_error": relative,
            "max_relative_error": float(relative.max()) if relative.size else 0.0}


def _cumulative(increments) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(increments)])
