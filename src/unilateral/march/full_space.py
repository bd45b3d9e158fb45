"""Direct stepping of large sparse models in compiled code, the LCP solved in the full space.

The compiled form of :mod:`unilateral.march.active_set` (the same equations and the same pivoting
rule, so the same solution to round-off): per step the free terms of the rule, then block
principal pivoting over trial sets ``A`` of open constraints, each solved with the structure
without the open constraints,

    (D_eff - a Fp_A Hs_AA^-1 Fp_A^T) du = r' + a Fp_A Hs_AA^-1 c'_A,

factorised in envelope storage (:mod:`unilateral.march.envelope`). ``Hs = H(c1)`` is diagonal (one
spring per constraint), so opening or closing a constraint changes only the rows of its DOFs and
below: only those rows are factorised again. No dense ``n x n`` or ``n x m`` array is formed; the
loads and offsets are evaluated in chunks of steps. It applies to a fresh stepper of a model whose
constraints have the trivial law, with a symmetric positive definite ``D_eff`` and a diagonal
``Hs`` without zeros (:func:`march_full_space`, None otherwise).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from numba import njit

from . import envelope
from ..lcp.pivoting import BLOCK_TRIES
from .compiled import REASSOCIATE, _advance, _matvec_add, _rule_history
from .direct import ChunkedMarch, direct_outputs
from .step_log import StepLog

#: Loads of at most this many entries (steps x DOFs) are evaluated at once (a chunk of steps).
CHUNK_ENTRIES = 1_000_000


# ---------------------------------------------------------------------- compiled kernels
@njit(cache=True, fastmath=REASSOCIATE)
def _columns_times(cols, coef, scale, out):
    """``out += scale * F coef`` for ``F`` in CSC ``cols = (indptr, indices, data, empty)``; the same
    arrays are ``F^T`` in CSR, for :func:`~unilateral.march.compiled._matvec_add`."""
    indptr, indices, data, _ = cols
    for b in range(indptr.shape[0] - 1):
        cb = scale * coef[b]
        if cb != 0.0:
            for p in range(indptr[b], indptr[b + 1]):
                out[indices[p]] += data[p] * cb


@njit(cache=True)
def _refactor(env, cons, a, active, factored, count):
    """Factorise ``D_eff - a Fp_A Hs_AA^-1 Fp_A^T`` for the set ``active`` from the first row that
    differs from the set ``factored`` (updated); return -1, or the row of a non-positive pivot
    (after which ``factored`` differs from ``active`` everywhere, so the next call starts afresh)."""
    ptr, first, base, A, L = env
    cols, h, pair_ptr, pair_pos, pair_val, row0 = cons
    n = first.shape[0]
    r0 = n
    for b in range(h.shape[0]):
        if active[b] != factored[b]:
            r0 = min(r0, row0[b])
    if r0 == n:
        return -1
    count[0] += 1
    start = ptr[r0]
    for p in range(start, A.shape[0]):
        A[p] = base[p]
    for b in range(h.shape[0]):
        factored[b] = active[b]
        if active[b]:
            w = a / h[b]
            for p in range(pair_ptr[b], pair_ptr[b + 1]):
                if pair_pos[p] >= start:
                    A[pair_pos[p]] -= w * pair_val[p]
    bad = envelope.cholesky_rows(ptr, first, A, L, r0)
    if bad >= 0:                            # rows from r0 on are no factor of any set now
        for b in range(h.shape[0]):
            factored[b] = not active[b]
    return bad


@njit(cache=True, fastmath=REASSOCIATE)
def full_space_lcp(env, cons, a, rc, state, max_iter):
    """One step's LCP by block principal pivoting in the full space; iterations, or -iterations.

    ``rc = (r, cp, x, v, psi)``: right-hand side ``r' = r - a Fp v_b`` (n,) and offset
    ``c' = c + Hs v_b`` (m,), the solution ``du`` (n,), ``v`` (m, total) and ``psi`` (m,) written.
    ``state = (active, factored, bad, count)``: the trial set (warm start, updated), the set of the
    current factorisation and work arrays; ``count[0]`` counts factorisations.
    """
    ptr, first, base, A, L = env
    cols, h, pair_ptr, pair_pos, pair_val, row0 = cons
    r, cp, x, v, psi = rc
    active, factored, bad, count = state
    m = h.shape[0]
    rhs = np.empty(r.shape[0])
    scale = 1.0
    for b in range(m):
        scale = max(scale, abs(cp[b]))
    scale *= 1e-13
    best, tries = m + 1, BLOCK_TRIES
    for it in range(1, max_iter + 1):
        if _refactor(env, cons, a, active, factored, count) >= 0:
            return -it
        for i in range(r.shape[0]):
            rhs[i] = r[i]
        for b in range(m):
            v[b] = cp[b] / h[b] if active[b] else 0.0
        _columns_times(cols, v, a, rhs)
        envelope.solve(ptr, first, L, rhs, x)
        for b in range(m):
            psi[b] = cp[b]
        _matvec_add(cols, x, 1.0, psi)
        nbad = 0
        for b in range(m):
            if active[b]:
                v[b] = psi[b] / h[b]
                psi[b] = 0.0
                bad[b] = v[b] < -scale
            else:
                v[b] = 0.0
                bad[b] = psi[b] > scale
            nbad += bad[b]
        if nbad == 0:
            for b in range(m):
                v[b] = max(v[b], 0.0)
            return it
        if nbad < best:
            best, tries = nbad, BLOCK_TRIES
        elif tries > 0:
            tries -= 1
        else:                               # Murty: flip only the last infeasible index
            last = -1
            for b in range(m):
                if bad[b]:
                    last = b
                bad[b] = False
            bad[last] = True
        for b in range(m):
            if bad[b]:
                active[b] = not active[b]
    return -max_iter


# The pieces of a step of :func:`full_space_steps`. Each is loops over arrays that calls nothing:
# numba then prunes the reference counts of its arrays (a piece that calls another compiled
# function keeps them, and pays them in every step). The compiled callees (:func:`_matvec_add`,
# :func:`_advance`, the envelope's solves, :func:`full_space_lcp`) are called from the loop. A call
# of a piece costs some 10-20 ns (numba's calling convention passes every array as its fields;
# LLVM does not inline a piece with a loop): nothing against a large model's step, but the step of
# a small condensed model takes 0.5 us, which is why :func:`unilateral.march.compiled.direct_steps`
# is one function.
@njit(cache=True)
def _step_workspace(n, m):
    """Per-step arrays of :func:`full_space_steps`: ``h1, h2, rhs, x, ud, acc`` (n,) and ``k1, k2,
    c, dv, dvd, dvdd, cp, vn, psin`` (m,), of which ``k1``, ``k2``, ``dv`` and ``cp`` are zero."""
    return (np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n), np.empty(n),
            np.zeros(m), np.zeros(m), np.empty(m), np.zeros(m), np.empty(m), np.empty(m),
            np.zeros(m), np.empty(m), np.empty(m))


@njit(cache=True, fastmath=REASSOCIATE)
def _scaled_row(a, table, k, out):
    """``out = a table[k]``: a row of a table (rows, n), such as the reaction offsets of a step."""
    for i in range(out.shape[0]):
        out[i] = a * table[k, i]


@njit(cache=True, fastmath=REASSOCIATE)
def _add_scaled(alpha, acc, rhs):
    """``rhs += alpha acc`` (n,): HHT-alpha's share of the previous step."""
    for i in range(rhs.shape[0]):
        rhs[i] += alpha * acc[i]


@njit(cache=True, fastmath=REASSOCIATE)
def _kelvin_rates(c0, c1, dv, k1, k2, dvd, dvdd):
    """The rates of the step's ``dv`` (m,) for the rule state of ``dv``
    (:func:`~unilateral.march.compiled._advance`): ``dvd = c1 dv - k1``, ``dvdd = c0 dv - k2``
    (``k1``, ``k2`` (m,) the rule's history)."""
    for b in range(dv.shape[0]):
        dvd[b] = c1 * dv[b] - k1[b]
        dvdd[b] = c0 * dv[b] - k2[b]


@njit(cache=True, fastmath=REASSOCIATE)
def _permuted_row(a, table, row, perm, out):
    """``out[i] = a table[row, perm[i]]`` (n,): a row of the loads (original DOF order) in the
    envelope numbering (``perm`` (n,) the original index of each row)."""
    for i in range(out.shape[0]):
        out[i] = a * table[row, perm[i]]


@njit(cache=True, fastmath=REASSOCIATE)
def _held_reactions(v_b, c, vn, psin, dv):
    """A bilateral step: ``v`` held at ``v_b`` (``vn = v_b``, ``dv = 0``) and ``psin = c`` (m,),
    to which the step adds ``Fp^T du``."""
    for b in range(v_b.shape[0]):
        vn[b] = v_b[b]
        psin[b] = c[b]
        dv[b] = 0.0


@njit(cache=True, fastmath=REASSOCIATE)
def _shifted(shift, h, v_b, c, rhs, cp):
    """The LCP's data of the set's solve: ``rhs -= shift`` (``shift = a Fp v_b``, (n,)) and
    ``cp = c + Hs v_b`` (m,) (``h`` (m,) the diagonal of ``Hs``)."""
    for i in range(rhs.shape[0]):
        rhs[i] -= shift[i]
    for b in range(cp.shape[0]):
        cp[b] = c[b] + h[b] * v_b[b]


@njit(cache=True, fastmath=REASSOCIATE)
def _record_full_space(k, it, c, vn, psin, v, stats):
    """The statistics of step k's LCP solved in ``it`` trial sets into ``stats`` (4,): the contact
    changes of ``vn`` (m,) against ``v[k-1]`` and the error ``|min(v, -psi)| / (1 + |c|)``
    (``psin`` (m,) its ``psi``, ``c`` (m,) the free reactions)."""
    err, norm_c = 0.0, 0.0
    for b in range(vn.shape[0]):
        e = min(vn[b], -psin[b])
        err += e * e
        norm_c += c[b] * c[b]
        stats[2] += (vn[b] > 0.0) != (v[k - 1, b] > 0.0)
    stats[0] += it
    stats[1] = max(stats[1], it)
    stats[3] = max(stats[3], np.sqrt(err) / (1.0 + np.sqrt(norm_c)))


@njit(cache=True, fastmath=REASSOCIATE)
def _increment(vn, v_b, dv):
    """The step's increment ``dv = vn - v_b`` (m,) of the unknowns over the base deformations."""
    for b in range(vn.shape[0]):
        dv[b] = vn[b] - v_b[b]


@njit(cache=True, fastmath=REASSOCIATE)
def _rates(c0, c1, x, h1, h2, ud, acc):
    """The rates of the step's ``x = du`` (n,) for the rule state
    (:func:`~unilateral.march.compiled._advance`): ``ud = du' = c1 du - h1``, ``acc = du'' = c0 du -
    h2`` (``h1``, ``h2`` (n,) the rule's history)."""
    for i in range(x.shape[0]):
        ud[i] = c1 * x[i] - h1[i]
        acc[i] = c0 * x[i] - h2[i]


@njit(cache=True, fastmath=REASSOCIATE)
def _store_permuted(k, perm, x, ud, du, dud):
    """Row k of ``du`` and ``dud`` (N+1, n, original DOF order) from the step's ``x = du`` and
    ``ud = du'`` (n, envelope order; ``perm`` (n,) the original index of each row)."""
    for i in range(x.shape[0]):
        du[k, perm[i]] = x[i]
        dud[k, perm[i]] = ud[i]


@njit(cache=True, fastmath=REASSOCIATE)
def _store_unknowns(k, vn, psin, dv, v, psi, dv_prev):
    """Row k of ``v`` and ``psi`` (N+1, m) and ``dv_prev = dv`` (m,)."""
    for b in range(vn.shape[0]):
        v[k, b] = vn[b]
        psi[k, b] = psin[b]
        dv_prev[b] = dv[b]


@njit(cache=True, fastmath=REASSOCIATE)
def full_space_steps(rule, env, cons, mats, tables, carry, steps):
    """Steps ``steps[0] <= k < steps[1]`` of the full-space direct march; the failed step or 0.

    The operations of :func:`unilateral.march.active_set.march_direct_active_set` with
    :class:`~unilateral.march.stepper.StructureStepper` in the envelope numbering of the DOFs.

    Parameters
    ----------
    rule : ``(kind, rp, c0, alpha, viscous, bilateral, max_iter)`` (``kind``, ``rp`` as in
        :func:`unilateral.march.compiled.direct_steps`)
    env : ``(ptr, first, base, A, L)``: the envelope of ``D_eff``, its values, the assembled matrix
        of the current set and its factor
    cons : ``(cols, h, pair_ptr, pair_pos, pair_val, row0)``: ``Fp`` (n, m) in CSC, the diagonal
        of ``Hs``, the envelope positions and values of the entries of each ``Fp_b Fp_b^T`` and
        the first row each constraint touches
    mats : ``(M, C, K, F, F_v, H_v, perm)``: operands of :func:`_matvec_add` (permuted), ``F`` and
        ``F_v`` (n, m) in CSC, ``H_v`` (m, m) operand, ``perm`` (n,) the original index of each row
    tables : ``(f, offset, first_row, v_b, shift)``: load increments (original DOF order) and
        reaction offsets of the steps from ``first_row`` on (the rows of a chunk), ``v_b`` (m,),
        ``shift = a Fp v_b`` (n,)
    carry : ``(du, dud, v, psi, stats, active, factored, us, vs, dv_prev, bad, count)``
    steps : ``(first, stop)``
    """
    kind, rp, c0, alpha, viscous, bilateral, max_iter = rule
    M, C, K, F, F_v, H_v, perm = mats
    f, offset, row_first, v_b, shift = tables
    du, dud, v, psi, stats, active, factored, us, vs, dv_prev, bad, count = carry
    ptr, first, L = env[0], env[1], env[4]
    c1, a = rp[7], 1.0 - alpha
    h1, h2, rhs, x, ud, acc, k1, k2, c, dv, dvd, dvdd, cp, vn, psin = _step_workspace(f.shape[1], offset.shape[1])
    lcp_state = (active, factored, bad, count)
    for k in range(steps[0], steps[1]):
        row = k - row_first
        _rule_history(kind, rp, us, h1, h2)
        if viscous:
            _rule_history(kind, rp, vs, k1, k2)
        _permuted_row(a, f, row, perm, rhs)     # free_terms: rhs = a f + M h2 + a C h1 ...
        _matvec_add(M, h2, 1.0, rhs)
        _matvec_add(C, h1, a, rhs)
        if alpha != 0.0:                    # HHT: alpha (f_prev - C u' - K u + F dv + F_v dv')
            _permuted_row(1.0, f, row - 1, perm, acc)
            _columns_times(F, dv_prev, 1.0, acc)
            _columns_times(F_v, vs[2], 1.0, acc)
            _matvec_add(C, us[2], -1.0, acc)
            _matvec_add(K, us[0], -1.0, acc)
            _add_scaled(alpha, acc, rhs)
        _scaled_row(1.0, offset, row, c)
        if viscous:
            _columns_times(F_v, k1, -a, rhs)
            _matvec_add(F_v, h1, -1.0, c)
            _matvec_add(H_v, k1, 1.0, c)
        if bilateral:                       # v held at v_b: the factor of D_eff itself
            envelope.solve(ptr, first, L, rhs, x)
            _held_reactions(v_b, c, vn, psin, dv)
            _matvec_add(cons[0], x, 1.0, psin)
        else:
            _shifted(shift, cons[1], v_b, c, rhs, cp)
            it = full_space_lcp(env, cons, a, (rhs, cp, x, vn, psin), lcp_state, max_iter)
            if it < 0:
                return k
            _record_full_space(k, it, c, vn, psin, v, stats)
            _increment(vn, v_b, dv)
        _rates(c0, c1, x, h1, h2, ud, acc)
        _store_permuted(k, perm, x, ud, du, dud)
        _advance(us, x, ud, acc)
        if viscous:
            _kelvin_rates(c0, c1, dv, k1, k2, dvd, dvdd)
            _advance(vs, dv, dvd, dvdd)
        _store_unknowns(k, vn, psin, dv, v, psi, dv_prev)
    return 0


# ---------------------------------------------------------------------- set-up
def _csc(A, perm, n, m):
    """``(indptr, indices, data, empty)`` of ``A`` (n, m) in CSC with rows renumbered (zeros if
    ``A`` is None): ``A^T`` in CSR as an operand of :func:`~unilateral.march.compiled._matvec_add`."""
    S = sp.csc_matrix((n, m)) if A is None else sp.csc_matrix(A)
    inverse = np.empty(n, dtype=np.int64)
    inverse[perm] = np.arange(n)
    S = sp.csc_matrix((S.data.astype(float), inverse[S.indices], S.indptr), shape=(n, m))
    S.sort_indices()
    return S.indptr.astype(np.int64), S.indices.astype(np.int64), S.data.astype(float), np.zeros((0, 0))


def _operand(A, n, perm=None):
    """``(indptr, indices, data, full)`` of ``A`` (n, n) in CSR, in the envelope numbering if ``perm``
    is given (zero if ``A`` is None), for :func:`~unilateral.march.compiled._matvec_add`."""
    S = sp.csr_matrix((n, n)) if A is None else sp.csr_matrix(A)
    if perm is not None:
        S = S[perm][:, perm].tocsr()
    S.sort_indices()
    return S.indptr.astype(np.int64), S.indices.astype(np.int64), S.data.astype(float), np.zeros((0, 0))


def _diagonal(H):
    """The diagonal of ``H`` (m, m) if it is diagonal without zeros, else None."""
    d = H.diagonal() if sp.issparse(H) else np.diag(np.asarray(H))
    nonzero = H.count_nonzero() if sp.issparse(H) else np.count_nonzero(H)
    return None if nonzero != np.count_nonzero(d) or not np.all(d != 0.0) else np.asarray(d, dtype=float)


def _symmetric(D) -> bool:
    S = sp.csr_matrix(D)
    scale = abs(S).max() if S.nnz else 1.0
    return S.nnz == 0 or abs(S - S.T).max() <= 1e-14 * scale


class FullSpace:
    """The compiled full-space LCP of a stepper: the envelope of ``D_eff`` and the constraints.

    Build with :meth:`of`, which returns None where it does not apply (a ``Hs`` that is not
    diagonal or has zeros, a ``D_eff`` that is not symmetric positive definite).
    """

    @classmethod
    def of(cls, D, Fp, Hs, extra=()):
        """For ``D`` (n, n), ``Fp`` (n, m) and ``Hs`` (m, m); ``extra``: more (n, m) matrices whose
        pattern the envelope must cover (``F``, ``F_v``)."""
        h = _diagonal(Hs)
        if h is None or not _symmetric(D):
            return None
        self = cls()
        n, m = Fp.shape
        Fp = sp.csc_matrix(Fp)
        pattern = abs(sp.csr_matrix(D)) + abs(Fp) @ abs(Fp).T
        for E in extra:
            if E is not None:
                pattern = pattern + abs(sp.csr_matrix(E)) @ abs(sp.csr_matrix(E)).T
        env = envelope.Envelope(pattern)
        self.perm = env.perm
        base = env.values(D)
        L = np.zeros_like(base)
        if envelope.cholesky_rows(env.ptr, env.first, base, L, 0) >= 0:
            return None
        self.env = (env.ptr, env.first, base, base.copy(), L)
        cols = _csc(Fp, env.perm, n, m)
        self.cons = (cols, h, *_pairs(env, cols, m))
        return self


def _pairs(env, cols, m):
    """Envelope positions and values of the entries of each column's ``Fp_b Fp_b^T`` (lower
    triangle), their offsets per column, and each column's first row."""
    indptr, indices, data, _ = cols
    counts = np.diff(indptr)
    col = np.repeat(np.arange(m), counts)               # the column of every stored entry
    # every entry e with every entry of its column: e repeated, its column's entries in turn
    e = np.repeat(np.arange(indices.size), counts[col])
    start = np.repeat(indptr[col], counts[col])
    within = np.arange(e.size) - np.repeat(np.cumsum(counts[col]) - counts[col], counts[col])
    f = start + within
    keep = indices[e] >= indices[f]
    e, f = e[keep], f[keep]
    pair_ptr = np.zeros(m + 1, dtype=np.int64)
    np.cumsum(np.bincount(col[e], minlength=m), out=pair_ptr[1:])
    row0 = np.full(m, env.n, dtype=np.int64)
    held = counts > 0                                   # the columns with an entry: their least row
    row0[held] = np.minimum.reduceat(indices, indptr[:-1][held])
    return (pair_ptr, env.position(indices[e], indices[f]).astype(np.int64), data[e] * data[f], row0)


def march_full_space(stepper, N, v_b, psi0, *, dt, bilateral=False, callback=None, max_iter=50):
    """The full-space direct march in compiled code; None if it does not apply.

    Same arguments and returns as :func:`unilateral.march.active_set.march_direct_active_set`; a
    fresh full-space ``stepper`` (``condensed=False``) with a rule of :mod:`unilateral.rules`
    (BDF1, BDF2, Newmark, HHT-alpha).
    """
    march = full_space_march(stepper, N, v_b, psi0, dt=dt, bilateral=bilateral, callback=callback,
                             max_iter=max_iter)
    if march is None:
        return None
    march.extend(N)
    return march.outputs()


def full_space_march(stepper, N, v_b, psi0, *, dt, bilateral=False, callback=None, max_iter=50):
    """The march of :func:`march_full_space` begun at step 0 (a :class:`FullSpaceMarch`), or None."""
    compiled_rule = stepper.compiled_rule()
    if compiled_rule is None:
        return None
    kind, rp, ustart = compiled_rule
    model = stepper.model
    a = 1.0 - stepper.alpha
    space = FullSpace.of(stepper.D_eff, stepper.Fp, stepper.Hs, extra=(model.F, model.F_v))
    if space is None:
        return None
    n, m = model.n, model.m
    perm = space.perm
    c0 = stepper.rule.coefficients(dt)[1]
    us = ustart[:, perm].copy()
    mats = (_operand(stepper.M, n, perm), _operand(stepper.C, n, perm), _operand(stepper.K, n, perm),
            _csc(model.F, perm, n, m), _csc(model.F_v, perm, n, m), _operand(model.H_v, m), perm)
    v_b = np.ascontiguousarray(v_b, dtype=float)
    shift = np.zeros(n)
    _columns_times(space.cons[0], v_b, a, shift)
    rule_args = (kind, rp, float(c0), float(stepper.alpha), stepper.vstate is not None, bool(bilateral),
                 int(max_iter))
    du, dud, v, psi, log = direct_outputs(stepper, N, v_b, psi0)
    stats, count = np.zeros(4), np.zeros(1, dtype=np.int64)
    active = v_b > 0
    carry = (du, dud, v, psi, stats, active, np.zeros(m, dtype=bool), us, np.zeros((5, m)), np.zeros(m),
             np.zeros(m, dtype=bool), count)
    chunk = max(1, CHUNK_ENTRIES // max(n, m, 1))

    def run(k0, k1):
        for lo in range(k0, k1, chunk):
            hi = min(k1, lo + chunk)
            f, offset = _rows(stepper, lo - 1, hi)
            failed = full_space_steps(rule_args, space.env, space.cons, mats, (f, offset, lo - 1, v_b, shift),
                                      carry, (lo, hi))
            if failed:
                return failed
        return 0

    return FullSpaceMarch(run, carry, N, v_b, dt=dt, max_iter=max_iter, callback=callback)


class FullSpaceMarch(ChunkedMarch):
    """The compiled full-space march (:func:`march_full_space`) as a
    :class:`~unilateral.march.direct.ChunkedMarch`."""

    def __init__(self, call, carry, N, v_b, *, dt, max_iter, callback=None):
        super().__init__(call, carry[:4], N, callback=callback)
        self.carry, self.v_b, self.dt, self.max_iter = carry, v_b, dt, max_iter

    def log(self, failed=0):
        log = StepLog.of_compiled(self.v_b, self.carry[4], 0, dt=self.dt, max_iter=self.max_iter, tol=np.inf)
        log.factorizations = int(self.carry[11][0])
        if failed:
            log.failure = (f"the LCP of step {failed} (t = {failed * self.dt:.6g}) failed: block principal "
                           f"pivoting in the full space did not converge in {self.max_iter} trial contact sets, "
                           "or a trial set left the structure without stiffness (a mechanism); try lcp='lemke' "
                           "with a condensed method (method='cq')")
        return log


def _rows(stepper, k0, k1):
    """Load increments and reaction offsets of steps ``k0 .. k1 - 1``, as arrays."""
    if stepper.tables is not None:
        return tuple(np.ascontiguousarray(table[k0:k1], dtype=float) for table in stepper.tables)
    f = np.empty((k1 - k0, stepper.model.n))
    offset = np.empty((k1 - k0, stepper.model.m))
    for k in range(k0, k1):
        f[k - k0], offset[k - k0] = stepper.load(k), stepper.offset(k)
    return f, offset
