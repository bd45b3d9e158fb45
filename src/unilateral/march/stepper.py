"""Direct time stepping of the full model with a rule, in increments around a base state.

Unknowns are increments ``du = u - u_b`` and ``dv = v - v_b`` about a base state
``(u_b, v_b)`` (the static state, or the given initial state). With the rule's

    du'_n = c1 du_n - h1,   du''_n = c0 du_n - h2,   dv'_n = c1 dv_n - k1

(HHT-alpha weights the previous step by alpha) the equations of motion at a step become

    D_eff du_n = r_n + (1 - alpha) F(c1) dv_n,       D_eff = c0 M + (1 - alpha)(c1 C + K)

so ``du_n = du_free + X dv_n`` with ``X = D_eff^-1 (1 - alpha) F(c1)`` and

    psi_n = psi_free - W0 dv_n,        W0 = H(c1) - (1 - alpha) F(c1)^T D_eff^-1 F(c1)

For the rules with a convolution-quadrature form ``W0 = Lambda(s*)``, and one step of this
stepper is one step of the CLCP with the same rule.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..linalg import Factorization, SingularMatrixError, dense, is_diagonal, transpose_times
from .policy import current_policy



class StructureStepper:
    """Steps the increments of a matrix :class:`~unilateral.model.Model` with a rule.

    Parameters
    ----------
    model : Model
    rule : Rule
    dt : float
    load : callable or ndarray
        ``load(k) -> (n,)``: the load increment ``f_k = q(t_k) + F v_b - K u_b`` at step k; or
        the array (N+1, n) of all of them.
    offset : callable or ndarray
        ``offset(k) -> (m,)``: ``F^T u_b - H v_b - g(t_k)``, the reaction of the base state; or
        the array (N+1, m) of all of them.
    udot0 : (n,) initial velocity increment (the given initial velocity; zero from statics).
    """

    def __init__(self, model, rule, dt, load, offset, udot0=None, *, condensed=True):
        self.model, self.rule, self.dt = model, rule, dt
        self.tables = (load, offset) if isinstance(load, np.ndarray) else None
        as_step = lambda f: f.__getitem__ if isinstance(f, np.ndarray) else f
        self.load, self.offset = as_step(load), as_step(offset)
        c1, c0 = rule.coefficients(dt)
        self.c1, self.alpha = c1, rule.alpha
        a = 1.0 - self.alpha
        # Small models step with dense arrays: sparse products cost more than they save there.
        small = model.n <= current_policy().dense_stepping_max_n
        as_used = (lambda A: None if A is None else dense(A)) if small else (lambda A: A)
        self.M, self.K, self.F, self.F_v = (as_used(A) for A in (model.M, model.K, model.F, model.F_v))
        C = as_used(model.damping())
        D_eff = c0 * self.M + a * (c1 * C + self.K)
        self.D_eff = D_eff
        self.lu = Factorization(D_eff, what="the effective stiffness c0 M + c1 C + K")
        self.Fp = self.F if self.F_v is None else self.F + c1 * self.F_v
        self.Hs = model.H_of(c1)
        if condensed:
            self.X = self.lu.solve(a * dense(self.Fp))                  # (n, m)
            W0 = self.Hs - transpose_times(self.Fp, self.X)
            self.W0 = 0.5 * (W0 + W0.T)
        self.C = C
        n, m = model.n, model.m
        ud0 = np.zeros(n) if udot0 is None else udot0
        f0 = self.load(0)
        rhs = f0 - C @ ud0
        a0 = _initial_acceleration(self.M, rhs) if np.any(rhs) else np.zeros(n)
        zero_n, zero_m = np.zeros(n), np.zeros(m)
        self.state = rule.start(zero_n, ud0, a0, dt)
        self.vstate = rule.start(zero_m, zero_m, zero_m, dt) if model.viscous else None
        self.k = 0
        self.u, self.ud = zero_n, ud0
        self.dv, self.dvd = zero_m, zero_m
        self.f_prev = f0

    def predict(self):
        """Free step (``dv_n = 0`` increment coupling): return ``(du_free, psi_free)``."""
        rhs, c = self.free_terms()
        du_free = self.lu.solve(rhs)
        self._du_free = du_free
        return du_free, c + transpose_times(self.Fp, du_free)

    def free_terms(self):
        """Right-hand side and reaction offset of the next step.

        Returns
        -------
        rhs : (n,) with ``D_eff du_n = rhs + (1 - alpha) F(c1) dv_n``
        c : (m,) with ``psi_n = F(c1)^T du_n + c - H(c1) dv_n``
        """
        model, rule, dt = self.model, self.rule, self.dt
        k = self.k + 1
        a = 1.0 - self.alpha
        h1, h2 = rule.history(self.state, dt)
        f = self.load(k)
        rhs = a * f + self.M @ h2 + a * (self.C @ h1)
        psi = self.offset(k)
        if self.alpha:
            rhs = rhs + self.alpha * (self.f_prev - self.C @ self.ud - self.K @ self.u
                                      + self.F @ self.dv)
            if self.F_v is not None:
                rhs = rhs + self.alpha * (self.F_v @ self.dvd)
        if self.vstate is not None:
            k1, _ = rule.history(self.vstate, dt)
            if self.F_v is not None:
                rhs = rhs - a * (self.F_v @ k1)
                psi = psi - transpose_times(self.F_v, h1)
            if model.H_v is not None:
                psi = psi + model.H_v @ k1
        self._pending = (k, f, h1, h2)
        return rhs, psi

    def sweep_arrays(self, N):
        """Arguments of :func:`unilateral.march.compiled.sweep` for N steps, or None if it does not apply.

        It applies to models of at most the policy's
        :attr:`~unilateral.march.policy.SizePolicy.compiled_max_n` DOFs (``D_eff`` factorised densely
        here if the stepper's factorisation is sparse) stepped by a rule with a
        convolution-quadrature form (BDF1, BDF2, trapezoidal) from a fresh stepper. The loads and
        offsets of all steps are taken from the arrays given, or evaluated here step by step.
        """
        kinds = {"bdf1": 0, "bdf2": 1, "trapezoidal": 2}
        if (self.rule.name not in kinds or self.alpha or self.k != 0
                or self.model.n > current_policy().compiled_max_n):
            return None
        lu_piv = self._dense_factors()
        n, m = self.model.n, self.model.m
        zeros_nm, zeros_mm = np.zeros((n, m)), np.zeros((m, m))
        c1, c0 = self.rule.coefficients(self.dt)
        state = self.state
        if self.rule.name == "trapezoidal":
            y0, yd0, ydd0 = state
            y1, yd1 = np.zeros(n), np.zeros(n)
        else:
            (y0, *ys), (yd0, *yds) = state
            y1, yd1 = (ys[0], yds[0]) if ys else (np.zeros(n), np.zeros(n))
            ydd0 = np.zeros(n)
        start = np.array([y0, y1, yd0, yd1, ydd0], dtype=float)
        if self.tables is not None:
            f, offset = (np.ascontiguousarray(table[: N + 1]) for table in self.tables)
        else:
            f = np.array([self.load(k) for k in range(N + 1)], dtype=float).reshape(N + 1, n)
            offset = np.array([self.offset(k) for k in range(N + 1)], dtype=float).reshape(N + 1, m)
        dense_or = lambda A, zero: zero if A is None else np.ascontiguousarray(dense(A), dtype=float)
        return (kinds[self.rule.name], self.dt, c1, c0, *lu_piv, matvec_operand(self.M),
                matvec_operand(self.C), dense_or(self.Fp, None), dense_or(self.F_v, zeros_nm),
                np.ascontiguousarray(self.Hs, dtype=float), dense_or(self.model.H_v, zeros_mm),
                self.vstate is not None, f, offset, start)

    def compiled_rule(self):
        """``(kind, rp, ustart)`` of the compiled direct marches, or None for a stepped or foreign rule.

        ``kind``: :data:`~unilateral.march.compiled.RULE_BDF1`, ``RULE_BDF2`` or ``RULE_NEWMARK``;
        ``rp`` (8,): ``dt``, the Newmark coefficients of the history terms and ``c1`` (see
        :func:`unilateral.march.compiled._rule_history`); ``ustart`` (5, n): the rule's state
        ``y0, y1, y0', y1', y0''`` of a fresh stepper.
        """
        from ..rules import BDF, Newmark
        from .compiled import RULE_BDF1, RULE_BDF2, RULE_NEWMARK

        rule, dt, n = self.rule, self.dt, self.model.n
        if self.k != 0 or type(rule) not in (BDF, Newmark):
            return None
        c1 = rule.coefficients(dt)[0]
        rp = np.zeros(8)
        rp[0], rp[7] = dt, c1
        if isinstance(rule, Newmark):
            kind, (g, b) = RULE_NEWMARK, (rule.gamma, rule.beta)
            rp[1:7] = (g / (b * dt), g / b - 1.0, dt * (g / (2 * b) - 1.0), dt, dt * dt * (0.5 - b),
                       1.0 / (b * dt * dt))
            y0, yd0, ydd0 = self.state
            y1, yd1 = np.zeros(n), np.zeros(n)
        else:
            kind = RULE_BDF1 if rule.order == 1 else RULE_BDF2
            (y0, *ys), (yd0, *yds) = self.state
            y1, yd1 = (ys[0], yds[0]) if ys else (np.zeros(n), np.zeros(n))
            ydd0 = np.zeros(n)
        return kind, rp, np.array([y0, y1, yd0, yd1, ydd0], dtype=float)

    def march_arrays(self, N):
        """Arguments of :func:`unilateral.march.compiled.direct_steps` for N steps, or None.

        Every rule of :mod:`unilateral.rules` (BDF1, BDF2, Newmark with trapezoidal and HHT-alpha)
        from a fresh condensed stepper; a user's own :class:`~unilateral.rules.Rule` subclass is
        stepped in Python. ``D_eff`` is factorised densely here if the stepper's factorisation
        is sparse. The loads and offsets of all steps are taken from the arrays given, or
        evaluated here step by step.

        Returns
        -------
        dict with ``kind``, ``rp``, ``mats``, ``sparse``, ``f``, ``offset``, ``ustart`` (5, n)
        and the scalars ``c0``, ``alpha``, ``viscous``; or None
        """
        compiled_rule = self.compiled_rule()
        if compiled_rule is None or not hasattr(self, "X"):
            return None
        kind, rp, ustart = compiled_rule
        n, m = self.model.n, self.model.m
        c0 = self.rule.coefficients(self.dt)[1]
        lu_piv = self._dense_factors()
        if self.tables is not None:
            f, offset = (np.ascontiguousarray(table[: N + 1], dtype=float) for table in self.tables)
        else:
            f = np.array([self.load(k) for k in range(N + 1)], dtype=float).reshape(N + 1, n)
            offset = np.array([self.offset(k) for k in range(N + 1)], dtype=float).reshape(N + 1, m)
        as_dense = lambda A, shape: (np.zeros(shape) if A is None
                                     else np.ascontiguousarray(dense(A), dtype=float))
        mats = (np.ascontiguousarray(lu_piv[0].T, dtype=float), lu_piv[1].astype(np.int64),
                as_dense(self.Fp, (n, m)).T.copy(), as_dense(self.F, (n, m)), as_dense(self.F_v, (n, m)),
                as_dense(self.F_v, (n, m)).T.copy(), as_dense(self.model.H_v, (m, m)),
                as_dense(self.X, (n, m)), as_dense(self.W0, (m, m)))
        return {"kind": kind, "rp": rp, "mats": mats,
                "sparse": tuple(matvec_operand(A) for A in (self.M, self.C, self.K)),
                "f": f, "offset": offset, "ustart": ustart,
                "c0": c0, "alpha": float(self.alpha), "viscous": self.vstate is not None}

    def _dense_factors(self):
        """``(lu, piv)`` of ``D_eff`` (LAPACK convention): the stepper's own, or a dense LU of it."""
        lu_piv = self.lu.dense_factors
        if lu_piv is None:
            import scipy.linalg as sla

            lu_piv = sla.lu_factor(dense(self.D_eff))
        return lu_piv

    def step_with(self, dv):
        """Next step with a prescribed increment ``dv`` (m,): return ``(du, psi)`` (no LCP)."""
        rhs, c = self.free_terms()
        if dv.any():
            rhs = rhs + (1.0 - self.alpha) * (self.Fp @ dv)
        du = self.lu.solve(rhs)
        return du, c + transpose_times(self.Fp, du) - self.Hs @ dv

    def correct(self, dv, du=None):
        """Complete the step with the unilateral increment ``dv`` (m,); return ``(du, du')``.

        ``du`` is the displacement increment if the caller solved for it; otherwise it is
        ``du_free + X dv`` from the last :meth:`predict`.
        """
        k, f, h1, h2 = self._pending
        if du is None:
            du = self._du_free + self.X @ dv if dv.any() else self._du_free
        c1 = self.c1
        c0 = self.rule.coefficients(self.dt)[1]
        ud = c1 * du - h1
        self.state = self.rule.advance(self.state, du, ud, c0 * du - h2)
        if self.vstate is not None:
            k1, k2 = self.rule.history(self.vstate, self.dt)
            dvd = c1 * dv - k1
            self.vstate = self.rule.advance(self.vstate, dv, dvd, c0 * dv - k2)
            self.dvd = dvd
        self.k, self.u, self.ud, self.dv, self.f_prev = k, du, ud, dv, f
        return du, ud


#: A matrix with more than this fraction of nonzeros is multiplied as a dense array in compiled code.
DENSE_FRACTION = 0.25


def matvec_operand(A):
    """``(indptr, indices, data, full)`` of :func:`unilateral.march.compiled._matvec_add`: CSR
    arrays, and ``A`` itself (dense) if more than :data:`DENSE_FRACTION` of it is nonzero."""
    S = A if sp.issparse(A) and A.format == "csr" else sp.csr_matrix(A)     # (no new matrix of a CSR one)
    n = S.shape[0]
    full = dense(A).astype(float) if S.nnz > DENSE_FRACTION * n * n else np.zeros((0, 0))
    return (S.indptr.astype(np.int64), S.indices.astype(np.int64), S.data.astype(float),
            np.ascontiguousarray(full))


def _initial_acceleration(M, rhs):
    """Solve ``M a0 = rhs``; for a singular (lumped, partly massless) M use the massive DOFs."""
    diag = M.diagonal() if sp.issparse(M) else np.diag(M)
    if is_diagonal(M):                      # lumped masses: what both factorisations below give
        massive = diag > 0
        return np.where(massive, rhs / np.where(massive, diag, 1.0), 0.0)
    try:
        return Factorization(M, what="M").solve(rhs)
    except SingularMatrixError:
        idx = np.flatnonzero(diag > 0)
        a0 = np.zeros_like(rhs)
        if idx.size:
            Mm = M[idx][:, idx]
            a0[idx] = Factorization(Mm, what="M on the DOFs with mass").solve(rhs[idx])
        return a0

