"""Energy balance of a solved structure, step by step.

From the equations of motion in natural form, ``M u'' + C u' + G sigma = q`` with
``sigma = E eps + E_v eps'``, ``eps = G^T u - B v - theta``, and ``B^T sigma = psi + A v + r``:

    W_in = (T - T_0) + (U - U_0) + D_damping + D_contact + W_plastic + W_friction

* ``T = u'^T M u' / 2``: kinetic energy (relative to the ground under a ground motion);
* ``U = sum eps^T E eps / 2``: elastic energy, of the bilateral elements (``elastic_structure``,
  beams with plastic hinges included) and of the unilateral elements (``elastic_unilateral``: soil,
  gaps, cables, yield links, sliders);
* ``D_damping = int u'^T C u' dt``: dissipated by Rayleigh damping and attached dashpots;
* the work of ``B^T sigma = psi + A v + r`` (elastic and Kelvin ``sigma``) on ``v'``, split by the
  family of the unknowns (:mod:`unilateral.constraints`):

  - ``D_contact = int (eps'^T E_v eps' + (B^T sigma)_c^T v_c') dt``: dissipated by the Kelvin
    dashpots of the unilateral elements (``c``, ``ct``), by slip at a contact's capacity ``r``, and
    lost by the reactions at the switches of contact (``psi^T v' = 0`` in continuous time; the
    discrete contact switch loses ``-psi^T dv`` over a step, which vanishes as ``dt -> 0``);
  - ``W_plastic = int (B^T sigma)_y^T v_y' dt``: the plastic work of yield links and hinges
    (``(psi + r)^T v'`` with ``psi = 0`` while a face yields), dissipated, plus the energy stored by
    kinematic hardening (``v^T A v / 2``);
  - ``W_friction = int (B^T sigma)_f^T v_f' dt``: the work of the tangential forces on the slips
    (Coulomb friction), dissipated;

* ``W_in = int q^T u' dt``: the work of the applied loads (gravity, pulses, ``-M r a_g``).

The integrals use the trapezoidal rule on the step increments, e.g.
``W_in += (q_n + q_{n-1})^T (u_n - u_{n-1}) / 2``. With these quadratures the balance of the
trapezoidal time-stepping rule is exact (to round-off) for linear structures, with or without
contact, yield and friction; other rules leave an error of their order (measured in
``tests/test_energy.py``). The relative error is the balance residual over the largest energy of
the run (input work, kinetic energy, change of elastic energy or energy dissipated).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..model import ConstantStrain

#: Matrices with at most this many entries are multiplied dense (one BLAS call on the histories).
DENSE_ENTRIES = 1 << 14


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
    ``damping_dissipated``, ``contact_dissipated``, ``plastic_work``, ``friction_work``,
    ``input_work``, ``balance_error`` (the residual ``W_in - dT - dU - D``), ``relative_error``
    (the residual over the largest energy of the run: input work, kinetic, change of elastic, or
    dissipated); ``unknown_work`` (m,): the work on each unknown's ``v'`` over the run (a yield
    pair's plastic work, a slip pair's friction work, summed over its two unknowns); and
    ``max_relative_error`` (float).
    """
    from ..structure.forces import StateRows

    return EnergyBalance(structure)(StateRows.of(h.u, h.udot, h.v, h.vdot), q)


@dataclass(frozen=True)
class LoadFactors:
    """Load samples ``q = constant + factors @ vectors`` (N+1, n), not formed (a LoadHistory's
    :meth:`~unilateral.loads.LoadHistory.grid_factors`): the work of the loads is
    ``constant^T du + sum_j f_j vectors_j^T du``, one product with the increments."""

    constant: np.ndarray        # (n,)
    vectors: np.ndarray         # (terms, n)
    factors: np.ndarray         # (N+1, terms)


class EnergyBalance:
    """:func:`energy_balance` with the structure's matrices prepared once (for many runs of one model).

    The state is a :class:`~unilateral.structure.forces.StateRows` (one row per unknown), so that
    every product is one matrix times all the steps, with two matrices:

        [eps; E eps] = S [u; v] - [theta; E theta],  S = [A; E A],  A = [G^T, -B]
        [M u'; C u'; E_v eps'] = R [u'; v']          (eps' = A [u'; v'])

    The strains are reordered, those of the bilateral elements first and those of the unilateral
    elements (``Structure.unilateral_strains``) last, so that both parts are blocks of rows; the
    rows of ``C u'`` without damping and of ``E_v eps'`` without Kelvin elements are left out. The
    work on ``v'`` takes ``B^T sigma`` per unknown, summed by family (:func:`unknown_kinds`). Small
    matrices are multiplied dense, large ones sparse.

    Parameters
    ----------
    structure : Structure
    """

    def __init__(self, structure):
        nat = structure.natural
        n, (ne, m) = structure.M.shape[0], nat.B.shape
        unilateral = structure.unilateral_strains
        order = np.concatenate([np.setdiff1d(np.arange(ne), unilateral), unilateral])
        A = sp.hstack([sp.csr_matrix(nat.G).T, -sp.csr_matrix(nat.B)]).tocsr()[order]
        E = sp.csr_matrix(nat.E)[order][:, order]
        if not isinstance(nat.theta, ConstantStrain):
            raise ValueError("energy balance: not available with support motions (the work of the moving "
                             "supports is not in the balance)")
        theta = np.asarray(nat.theta(0.0), dtype=float)[order]
        zeros = sp.csr_matrix((n, m))
        rates = [sp.hstack([structure.M, zeros])]
        if structure.C is not None:
            rates.append(sp.hstack([structure.C, zeros]))
        if nat.E_v is not None:
            rates.append(sp.csr_matrix(nat.E_v)[order][:, order] @ A)
        self.n, self.ne, self.bilateral = n, ne, ne - unilateral.size
        self.damped, self.kelvin = structure.C is not None, nat.E_v is not None
        self.S = _prepared(sp.vstack([A, E @ A]))
        self.offset = np.concatenate([theta, E @ theta])[:, None]
        self.imposed = bool(self.offset.any())
        self.R = _prepared(sp.vstack(rates))
        self.Bt = _prepared(sp.csr_matrix(nat.B)[order].T)           # (m, ne): B^T sigma per unknown
        kinds = unknown_kinds(structure)
        self.families = {key: kinds == kind for key, kind in FAMILY_TERMS.items()}

    def __call__(self, state, q) -> dict:
        """The energies of :func:`energy_balance` of a run.

        Parameters
        ----------
        state : :class:`~unilateral.structure.forces.StateRows` (``v'`` used with Kelvin elements only)
        q : (N+1, n) load samples (a transposed view of rows (n, N+1) is used without a copy), or
            :class:`LoadFactors`
        """
        n, ne, nb, x, xdot = self.n, self.ne, self.bilateral, state.x, state.xdot
        strains = self.S @ x
        if self.imposed:
            strains -= self.offset
        eps, Eeps = strains[:ne], strains[ne:]
        rates = self.R @ xdot
        kinetic = 0.5 * np.einsum("ik,ik->k", xdot[:n], rates[:n])
        elastic_s = 0.5 * np.einsum("ik,ik->k", eps[:nb], Eeps[:nb])     # E is block diagonal
        elastic_u = 0.5 * np.einsum("ik,ik->k", eps[nb:], Eeps[nb:])
        du = np.diff(x[:n], axis=1)
        work = _cumulative(_work(q, du))
        damping = _cumulative(_pairs(rates[n:2 * n], du)) if self.damped else np.zeros(x.shape[1])
        sigma_b = self.Bt @ Eeps                                          # B^T sigma, elastic part
        increments = np.zeros(x.shape[1] - 1)                           # of the Kelvin dashpots
        if self.kelvin:
            viscous = rates[2 * n if self.damped else n:]
            increments = _pairs(viscous, np.diff(eps, axis=1))
            sigma_b = sigma_b + self.Bt @ viscous
        # work of B^T sigma = psi + A v + r on v' per unknown: contact switches and capacity slip,
        # plastic flow, friction
        per_unknown = 0.5 * (sigma_b[:, 1:] + sigma_b[:, :-1]) * np.diff(x[n:], axis=1)
        terms = {key: per_unknown[mask].sum(axis=0) for key, mask in self.families.items()}
        terms["contact_dissipated"] = terms["contact_dissipated"] + increments
        terms = {key: _cumulative(value) for key, value in terms.items()}
        dissipated = damping + sum(terms.values())
        T0, U0 = kinetic[0], elastic_s[0] + elastic_u[0]
        elastic = elastic_s + elastic_u - U0
        residual = work - (kinetic - T0) - elastic - dissipated
        scale = max(np.abs(work).max(), kinetic.max(), np.abs(elastic).max(), dissipated.max(), 0.0)
        relative = np.abs(residual) / scale if scale > 0 else np.zeros_like(residual)
        return {"kinetic": kinetic, "elastic_structure": elastic_s, "elastic_unilateral": elastic_u,
                "damping_dissipated": damping, **terms, "input_work": work,
                "balance_error": residual, "relative_error": relative,
                "unknown_work": per_unknown.sum(axis=1), "max_relative_error": float(relative.max())}


#: The energy term of each family of constraint unknowns.
FAMILY_TERMS = {"contact_dissipated": "contact", "plastic_work": "yield", "friction_work": "friction"}


def unknown_kinds(structure) -> np.ndarray:
    """The family (``"contact"``, ``"yield"``, ``"friction"``) of each of the ``m`` unknowns (m,).

    From the elements' :class:`~unilateral.structure.elements.Unknown` s; a structure built by hand
    (no elements) has contacts only.
    """
    m = structure.natural.B.shape[1]
    kinds = [u.kind for _, u in structure.constraints]
    return np.array(kinds if len(kinds) == m else ["contact"] * m, dtype=str)


def _work(q, du) -> np.ndarray:
    """Increments (N,) of the work of the loads ``(q_n + q_{n-1})^T (u_n - u_{n-1}) / 2``; ``du`` (n, N)."""
    if isinstance(q, LoadFactors):
        constant, each = np.split(np.vstack([q.constant, q.vectors]) @ du, [1])   # (1, N), (terms, N)
        return constant[0] + 0.5 * np.einsum("kj,jk->k", q.factors[1:] + q.factors[:-1], each)
    return _pairs(np.asarray(q, dtype=float).T, du)


def _prepared(A):
    """``A`` dense if it has at most :data:`DENSE_ENTRIES` entries, else sparse csr."""
    if A.shape[0] * A.shape[1] <= DENSE_ENTRIES:
        return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)
    return sp.csr_matrix(A)


def _pairs(f, dx) -> np.ndarray:
    """Trapezoidal increments ``(f_n + f_{n-1})^T (x_n - x_{n-1}) / 2`` (N,) of rows ``f`` (k, N+1), ``dx`` (k, N)."""
    return 0.5 * np.einsum("ik,ik->k", f[:, 1:] + f[:, :-1], dx)


def _cumulative(increments) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(increments)])
