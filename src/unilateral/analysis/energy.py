"""Energy balance of a solved structure, step by step.

From the equations of motion in natural form, ``M u'' + C u' + G sigma = q`` with
``sigma = E eps + E_v eps'``, ``eps = G^T u - B v - theta``, and ``B^T sigma = psi + A v + r``:

    W_in + W_s = (T - T_0) + (U - U_0) + D_damping + D_contact + W_plastic + W_friction + D_numerical

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

* ``W_in = int q^T u' dt``: the work of the applied loads (gravity, pulses, ``-M r a_g``);
* ``W_s = -int theta'(t)^T sigma dt``: the work of the moving supports (multiple-support excitation,
  :mod:`unilateral.structure.support_motion`: ``theta(t) = theta_0 - L_s u_s(t)``, taken at the
  times of the steps; ``sigma`` the total stresses, Kelvin ones included), ``support_work``;
* ``geometric = u^T K_G u / 2``: with P-Delta, the energy of the geometric stiffness of the constant
  gravity axial forces (negative where they compress: the gravity loads' work through the sway);
* ``numerical_dissipation``: what the time-stepping rule dissipated, and ``numerical_storage``: the
  energy BDF2's two-step state holds beyond ``T + U`` (bounded, of order ``dt``).

The sums over the steps pair the equations of motion with the increments of the run's rule
(:class:`unilateral.rules.EnergyPairing`): for the trapezoidal rule the mean of two steps' equations
with ``x_n - x_{n-1}``, e.g. ``W_in += (q_n + q_{n-1})^T (u_n - u_{n-1}) / 2``; for BDF1 and BDF2 the
equation at the step with ``dt x'_n``, e.g. ``W_in += q_n^T (3 u_n - 4 u_{n-1} + u_{n-2}) / 2``. The
balance is then an exact identity of the discrete equations (to round-off), with contact, yield
and friction, and the numerical dissipation of BDF1 and BDF2 is a quadratic form in the first and
second differences of the state (G-stability; docs/theory.md, section 14). Newmark with
``gamma != 1/2`` and HHT are paired as the trapezoidal rule with no dissipation term: their
residual is their dissipation, of their order. The relative error is the balance residual over the
largest energy of the run (input work, kinetic energy, change of elastic energy or energy
dissipated).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ..model import ConstantStrain

#: Matrices with at most this many entries are multiplied dense (one BLAS call on the histories).
DENSE_ENTRIES = 1 << 14


def energy_balance(structure, h, q, *, rule=None, contact=None) -> dict:
    """Energies (N+1,) of a solved structure and the relative error of their balance.

    Parameters
    ----------
    structure : Structure
    h : :class:`unilateral.structure.forces.Histories`
    q : (N+1, n) applied load at the steps (as the run used it; imposed strains excluded)
    rule : the rule of the run (name or Rule; see :class:`EnergyBalance`), or None: the trapezoidal
        pairing with no numerical-dissipation term (then the balance of a BDF run closes to its order)
    contact : (N+1, n) the footings' contact load ``T c`` on a frame on a soil medium, or None

    Returns
    -------
    dict of (N+1,) arrays: ``kinetic``, ``elastic_structure``, ``elastic_unilateral``, ``geometric``
    (P-Delta), ``damping_dissipated``, ``contact_dissipated``, ``plastic_work``, ``friction_work``,
    ``numerical_dissipation``, ``numerical_storage``, ``input_work`` (of the loads ``q``),
    ``support_work`` (of the moving supports, zero without them), ``balance_error`` (the residual
    ``W_in + W_s - dT - dU - D``), ``relative_error`` (the residual over the largest energy of the
    run: input work ``W_in + W_s``, kinetic, change of elastic, or dissipated); ``unknown_work`` (m,): the work on each
    unknown's ``v'`` over the run (a yield pair's plastic work, a slip pair's friction work, summed
    over its two unknowns); the floats ``max_relative_error`` and ``numerical_share`` (the
    numerical dissipation at the end over the same scale); ``exact`` (bool): the rule's pairing is
    an exact identity (BDF1, BDF2, trapezoidal).
    """
    from ..structure.forces import StateRows

    dt = float(h.t[1] - h.t[0]) if len(h.t) > 1 else None
    return EnergyBalance(structure)(StateRows.of(h.u, h.udot, h.v, h.vdot, t=h.t), q, rule=rule, dt=dt,
                                    contact=contact)


@dataclass(frozen=True)
class LoadFactors:
    """Load samples ``q = constant + factors @ vectors`` (N+1, n), not formed (a LoadHistory's
    :meth:`~unilateral.loads.LoadHistory.grid_factors`): the work of the loads is
    ``constant^T du + sum_j f_j vectors_j^T du``, one product with the increments."""

    constant: np.ndarray        # (n,)
    vectors: np.ndarray         # (terms, n)
    factors: np.ndarray         # (N+1, terms)

    def at(self, k) -> np.ndarray:
        """The load (n,) at step ``k``."""
        return self.constant + self.factors[k] @ self.vectors


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
    matrices are multiplied dense, large ones sparse. The sums over the steps are those of the
    run's rule (:class:`~unilateral.rules.EnergyPairing`): with BDF1, BDF2 and the trapezoidal rule
    the balance is an exact identity whose ``numerical_dissipation`` is the rule's.

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
        self.natural, self.order, self.E = nat, order, E
        self.moving = not isinstance(nat.theta, ConstantStrain)     # support motions: theta(t)
        theta = np.asarray(nat.theta(0.0), dtype=float)[order]
        zeros = sp.csr_matrix((n, m))
        rates = [sp.hstack([structure.M, zeros])]
        if structure.C is not None:
            rates.append(sp.hstack([structure.C, zeros]))
        self.E_v = None if nat.E_v is None else sp.csr_matrix(nat.E_v)[order][:, order]
        if nat.E_v is not None:
            rates.append(self.E_v @ A)
        self.n, self.ne, self.bilateral = n, ne, ne - unilateral.size
        self.damped, self.kelvin = structure.C is not None, nat.E_v is not None
        self.S = _prepared(sp.vstack([A, E @ A]))
        self.offset = np.concatenate([theta, E @ theta])[:, None]
        self.imposed = bool(self.offset.any())
        self.R = _prepared(sp.vstack(rates))
        self.Bt = _prepared(sp.csr_matrix(nat.B)[order].T)           # (m, ne): B^T sigma per unknown
        self.Gt = A[:, :n]                                             # (ne, n): G^T in strain order
        self.M = sp.csr_matrix(structure.M)
        geometric = getattr(structure, "geometric", None)
        self.Kg = None if geometric is None else _prepared(sp.csr_matrix(geometric))
        kinds = unknown_kinds(structure)
        self.families = {key: kinds == kind for key, kind in FAMILY_TERMS.items()}

    def __call__(self, state, q, *, rule=None, dt=None, contact=None, t=None) -> dict:
        """The energies of :func:`energy_balance` of a run.

        Parameters
        ----------
        state : :class:`~unilateral.structure.forces.StateRows` (``v'`` used with Kelvin elements only)
        q : (N+1, n) load samples (a transposed view of rows (n, N+1) is used without a copy), or
            :class:`LoadFactors`
        rule : the run's rule (name or Rule), or None: the trapezoidal pairing
        dt : the time step (needed by BDF2, whose start takes the state before ``t = 0``)
        contact : (N+1, n) the footings' contact load on a frame on a soil medium, or None: its work
            went into the soil and is counted in ``contact_dissipated``
        t : (N+1,) the times of the steps (s), by default the state's (:attr:`StateRows.t`); needed
            with support motions (``theta(t)`` varies)
        """
        from ..rules import EnergyPairing

        t = getattr(state, "t", None) if t is None else t

        pairing = EnergyPairing(rule)
        offset, viscous_offset = self._offsets(t, state.x.shape[1], pairing)
        x, xdot = self._extended(state, q, pairing, dt, contact, offset, viscous_offset)
        n, ne, nb, lead = self.n, self.ne, self.bilateral, pairing.lead
        strains = self.S @ x
        if offset is not None:
            strains -= offset
        eps, Eeps = strains[:ne], strains[ne:]
        rates = self.R @ xdot
        if viscous_offset is not None:                   # E_v eps' with eps' = A x' - theta'(t)
            rates[(2 if self.damped else 1) * n:] -= viscous_offset
        energies = [pairing.quadratic(xdot[:n], rates[:n]), pairing.quadratic(eps[:nb], Eeps[:nb]),
                    pairing.quadratic(eps[nb:], Eeps[nb:])]     # E is block diagonal
        if self.Kg is not None:
            energies.append(pairing.quadratic(x[:n], self.Kg @ x[:n]))
        now = lambda a, b: 0.5 * np.einsum("ik,ik->k", a[:, lead:], b[:, lead:])
        physical = [now(xdot[:n], rates[:n]), now(eps[:nb], Eeps[:nb]), now(eps[nb:], Eeps[nb:])]
        physical.append(now(x[:n], self.Kg @ x[:n]) if self.Kg is not None else np.zeros(x.shape[1] - lead))
        work = _cumulative(_work(q, x[:n], pairing))
        damping = rates[n:2 * n] if self.damped else None
        viscous = rates[2 * n if self.damped else n:]
        terms = self._dissipated(pairing, x, eps, Eeps, viscous, damping)
        if contact is not None:             # the work of the contact forces went into the soil
            terms["contact_dissipated"] -= pairing.pairs(np.asarray(contact, dtype=float).T, x[:n])
        support = np.zeros_like(work)
        if self.moving:                     # W_s = -int theta'^T sigma dt, sigma = E eps + E_v eps'
            sigma = Eeps + viscous if self.kelvin else Eeps
            support = -_cumulative(pairing.pairs(sigma[:, lead:], offset[:ne]))
        per_unknown = terms.pop("unknown_work")
        terms = {key: _cumulative(value) for key, value in terms.items()}
        numerical = _cumulative(sum(d for _, d in energies))
        storage = sum(e for e, _ in energies) - sum(physical)
        return _balance(physical, (work, support), terms, numerical, storage - storage[0], per_unknown,
                        pairing.exact)

    def _offsets(self, t, steps, pairing):
        """The imposed strains ``[theta; E theta]`` (2 ne, N+1+lead) or (2 ne, 1), or None without
        them, and the viscous ``E_v theta'`` (ne, N+1+lead) or None. With support motions ``theta``
        is taken at the times ``t`` of the steps; before ``t = 0`` (BDF2) it is extrapolated
        linearly, ``theta_{-1} = 2 theta_0 - theta_1`` (the pairing is an identity for any value)."""
        if not self.moving:
            return (self.offset if self.imposed else None), None
        if t is None or len(t) != steps:
            raise ValueError(f"t: the energy balance with support motions needs the {steps} times of the steps, "
                             f"got {None if t is None else len(t)}")
        t = np.asarray(t, dtype=float)
        theta = np.asarray(self.natural.imposed_strains(t), dtype=float)[:, self.order].T      # (ne, N+1)
        if pairing.lead:
            before = 2 * theta[:, 0] - theta[:, 1] if steps > 1 else theta[:, 0]
            theta = np.column_stack([before, theta])
        offset = np.vstack([theta, self.E @ theta])
        rate = self.natural.theta_rate
        if not self.kelvin or rate is None:
            return offset, None
        theta_rate = np.array([np.asarray(rate(tk), dtype=float) for tk in t])[:, self.order].T
        viscous = np.asarray(self.E_v @ theta_rate)
        if pairing.lead:
            viscous = np.column_stack([viscous[:, 0], viscous])
        return offset, viscous

    def _extended(self, state, q, pairing, dt, contact, offset, viscous_offset):
        """``[u; v]`` and ``[u'; v']`` (n + m, N+1+lead): for BDF2 the rule's start before ``t = 0``
        first, ``u_{-1} = u_0 - dt u'_0 + dt^2 a_0 / 2``, ``u'_{-1} = u'_0 - dt a_0``, ``v_{-1} = v_0``
        (``M a_0`` the residual of the equations at ``t = 0``, as the stepping starts)."""
        x, xdot = state.x, state.xdot
        if not pairing.lead:
            return x, xdot
        n = self.n
        if dt is None:
            raise ValueError("dt: the energy balance of a BDF2 run needs the time step (its start)")
        sigma = self.S[self.ne:] @ x[:, :1]
        if offset is not None:
            sigma = sigma - offset[self.ne:, -x.shape[1]:][:, :1]
        if self.kelvin:
            sigma = sigma + self.R[(2 if self.damped else 1) * n:] @ xdot[:, :1]
            if viscous_offset is not None:
                sigma = sigma - viscous_offset[:, 1:2]
        q0 = q.at(0) if isinstance(q, LoadFactors) else np.asarray(q[0], dtype=float)
        residual = q0 - self.Gt.T @ sigma[:, 0] - (self.R[n:2 * n] @ xdot[:, 0] if self.damped else 0.0)
        if self.Kg is not None:
            residual = residual - self.Kg @ x[:n, 0]
        if contact is not None:
            residual = residual + np.asarray(contact[0], dtype=float)
        a0 = _massive_solve(self.M, residual)
        before, rate_before = x[:, 0].copy(), xdot[:, 0].copy()
        before[:n] += dt * (0.5 * dt * a0 - xdot[:n, 0])
        rate_before[:n] -= dt * a0
        return np.column_stack([before, x]), np.column_stack([rate_before, xdot])

    def _dissipated(self, pairing, x, eps, Eeps, viscous, damping) -> dict:
        """Increments (N,) of the dissipation terms, and ``unknown_work`` (m,): the work on each
        unknown of ``B^T sigma = psi + A v + r`` (elastic and Kelvin ``sigma``) on ``v'``."""
        n, lead = self.n, pairing.lead
        steps = x.shape[1] - 1 - lead
        out = {"damping_dissipated": pairing.pairs(damping[:, lead:], x[:n]) if damping is not None
               else np.zeros(steps)}
        sigma_b = self.Bt @ Eeps                                          # B^T sigma, elastic part
        kelvin = np.zeros(steps)                                        # of the Kelvin dashpots
        if self.kelvin:
            kelvin = pairing.pairs(viscous[:, lead:], eps)
            sigma_b = sigma_b + self.Bt @ viscous
        # work of B^T sigma = psi + A v + r on v' per unknown: contact switches and capacity slip,
        # plastic flow, friction
        per_unknown = pairing.weights(sigma_b[:, lead:]) * pairing.increments(x[n:])
        for key, mask in self.families.items():
            out[key] = per_unknown[mask].sum(axis=0)
        out["contact_dissipated"] = out["contact_dissipated"] + kelvin
        out["unknown_work"] = per_unknown.sum(axis=1)
        return out


#: The scale of the relative error is at least this fraction of the energy stored (the static state's
#: included): the changes of a run that barely moves (a static load held, 1e-15 kN m of work beside
#: 0.1 kN m stored) are round-off of the stored energy, and their residual is no error of the balance
#: (it read 7-15 % there, with a warning).
STORED_FLOOR = 1e-8


def _balance(physical, inputs, terms, numerical, storage, per_unknown, exact) -> dict:
    """The energy dict of :func:`energy_balance` from its terms (each (N+1,), from ``t = 0``);
    ``inputs``: the work of the loads and of the moving supports."""
    kinetic, elastic_s, elastic_u, geometric = physical
    work, support = inputs
    dissipated = sum(terms.values())
    T0 = kinetic[0]
    elastic = elastic_s + elastic_u + geometric - (elastic_s[0] + elastic_u[0] + geometric[0])
    residual = work + support - (kinetic - T0) - elastic - dissipated - numerical - storage
    scale = max(np.abs(work + support).max(), kinetic.max(), np.abs(elastic).max(), (dissipated + numerical).max(),
                STORED_FLOOR * (np.abs(elastic_s).max() + np.abs(elastic_u).max() + np.abs(geometric).max()), 0.0)
    relative = np.abs(residual) / scale if scale > 0 else np.zeros_like(residual)
    return {"kinetic": kinetic, "elastic_structure": elastic_s, "elastic_unilateral": elastic_u,
            "geometric": geometric, "damping_dissipated": terms["damping_dissipated"],
            **{key: terms[key] for key in FAMILY_TERMS}, "numerical_dissipation": numerical,
            "numerical_storage": storage, "input_work": work, "support_work": support, "balance_error": residual,
            "relative_error": relative, "unknown_work": per_unknown,
            "max_relative_error": float(relative.max()),
            "numerical_share": float(numerical[-1] / scale) if scale > 0 else 0.0, "exact": exact}


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


def _work(q, u, pairing) -> np.ndarray:
    """Increments (N,) of the work of the loads ``q`` on rows ``u`` (n, N+1+lead), paired as the rule
    (:class:`~unilateral.rules.EnergyPairing`)."""
    du = pairing.increments(u)
    if isinstance(q, LoadFactors):
        constant, each = np.split(np.vstack([q.constant, q.vectors]) @ du, [1])   # (1, N), (terms, N)
        return constant[0] + np.einsum("jk,jk->k", pairing.weights(q.factors.T), each)
    return np.einsum("ik,ik->k", pairing.weights(np.asarray(q, dtype=float).T), du)


def _massive_solve(M, f) -> np.ndarray:
    """``a`` (n,) with ``M a = f`` on the DOFs with mass, 0 on the massless ones (as the stepping starts)."""
    d = M.diagonal()
    massive = np.flatnonzero(d > 0)
    a = np.zeros_like(f, dtype=float)
    if massive.size == 0:
        return a
    if M.nnz == np.count_nonzero(d):                    # lumped masses
        a[massive] = f[massive] / d[massive]
        return a
    a[massive] = np.linalg.solve(M[massive][:, massive].toarray(), f[massive])
    return a


def _prepared(A):
    """``A`` dense if it has at most :data:`DENSE_ENTRIES` entries, else sparse csr."""
    if A.shape[0] * A.shape[1] <= DENSE_ENTRIES:
        return np.asarray(A.toarray() if sp.issparse(A) else A, dtype=float)
    return sp.csr_matrix(A)


def _cumulative(increments) -> np.ndarray:
    return np.concatenate([[0.0], np.cumsum(increments)])
