"""Compiled inner loops (numba): the per-step LCP and the CLCP march.

The Python march (:mod:`unilateral.march.clcp`) calls an LCP solver object per step; its overhead
(tens of microseconds) dominates for the small ``m`` of most structures. These loops run the
whole march in machine code with a block principal pivoting solver specialised for the
symmetric positive definite ``W0`` of the CLCP, warm-started from the previous step's active set.
Compiled code is cached on disk (``cache=True``), so a second process does not compile again.

The results equal the Python march with ``lcp="bpp"`` (the same pivoting rule, exact linear
solves), which the tests check. :func:`direct_steps` is the direct march of ``method="direct"``
(every rule, the condensed LCP on ``W0`` by :func:`~unilateral.lcp.pivoting.solve_step`),
:func:`sweep` the linear sweep of the CLCP methods. The step LCP solvers are in
:mod:`unilateral.lcp.pivoting` (block principal pivoting with the face rules, Lemke's method
where a polygon's dependent facets defeat it), shared with the Python marches.

Compile cost: a cold cache compiles these loops once (seconds, see
:mod:`unilateral.march.policy`). Rows are copied by explicit loops, never by ``a[0] = b`` between
arrays: numba compiles that with shape checks whose error messages format strings (its string and
``repr`` machinery, 4-6 s of a cold compile of the direct march). The two products by ``@`` stay
(BLAS's round-off is that of the frozen outputs). :func:`unilateral.march.loops.cache_state` says whether the cache
holds a loop.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..lcp.pivoting import BLOCK_TRIES, bpp, lcp_error, solve_step  # noqa: F401  (re-exported)

#: Floating-point liberties of the loops of matrix-vector products and triangular solves: sums
#: may be reassociated (vectorised, several accumulators) and multiply-adds fused. Results change
#: at round-off only; NaN and infinity keep their meaning (no "fast" flags beyond these).
REASSOCIATE = {"reassoc", "contract"}


@njit(cache=True)
def law_vector(code, rate, P, W0, q, v_prev, o, t):
    """The step law (:mod:`unilateral.constraints.law`) in place: ``o = rate v_prev`` and
    ``q <- P (q + W0 o)``; ``code`` 0 (contact only) leaves ``q`` and sets ``o = 0``."""
    m = q.shape[0]
    if code == 0:
        for a in range(m):
            o[a] = 0.0
        return
    for a in range(m):
        o[a] = rate[a] * v_prev[a]
    for a in range(m):
        u = q[a]
        for b in range(m):
            u += W0[a, b] * o[b]
        t[a] = u
    for a in range(m):
        if code == 2:
            u = 0.0
            for b in range(m):
                u += P[a, b] * t[b]
            q[a] = u
        else:
            q[a] = t[a]


@njit(cache=True)
def law_matrix(code, P, W0):
    """The step LCP matrix ``P W0`` (``W0`` itself unless ``code`` is 2).

    ``P @ W0`` is BLAS's product (numba compiles its binding, about 1.4 s of a cold compile): a
    loop would change the round-off of every frozen output of a law with a projection.
    """
    if code == 2:
        return P @ W0
    return W0


@njit(cache=True)
def _outputs(W0, psi_affine, v_b):
    """Histories of a march initialised at step 0, its statistics, the contact set, ``W0 v_b``."""
    N1, m = psi_affine.shape
    v, psi, dv = np.zeros((N1, m)), np.zeros((N1, m)), np.zeros((N1, m))
    for a in range(m):                      # (loops: see the module's note on compile cost)
        v[0, a] = v_b[a]
        psi[0, a] = psi_affine[0, a]
    active = v_b > 0.0
    return v, psi, dv, np.zeros(5), active, active.copy(), W0 @ v_b     # (BLAS: see law_matrix)


@njit(cache=True)
def _workspace(m):
    """Per-step arrays: q, v, w and the pivoting solver's workspace."""
    return (np.empty(m), np.empty(m), np.empty(m), np.empty(m, dtype=np.int64), np.empty((m, m)),
            np.empty(m), np.empty(m))


@njit(cache=True)
def _law_step(law, W0, WL, q, v_prev, vn, wn, active, max_iter, work, o, t):
    """The step LCP of the law on the associated vector ``q``: ``vn`` the new unknowns, ``wn``
    the LCP's ``w = -P psi``, ``q`` left as the LCP vector. ``max_iter = (solves, tol)``. Returns
    ``(solves, error, fallback)`` of :func:`~unilateral.lcp.pivoting.solve_step`."""
    code, rate, P, partner, group = law
    law_vector(code, rate, P, W0, q, v_prev, o, t)
    it, err, fallback = solve_step(WL, q, active, vn, wn, max_iter[0], max_iter[1], work, code != 2,
                                   (partner, group))
    if code != 0:
        for a in range(vn.shape[0]):
            vn[a] += o[a]
    return it, err, fallback


@njit(cache=True)
def _record(n, step, tol, active, previous, vn, wn, v_b, v, psi, dv, stats):
    """Store the LCP result ``step = (solves, error, fallback)`` of step n and update the
    statistics; False if the step failed."""
    it, err, fallback = step
    if it < 0 or err > tol:
        return False
    stats[0] += it
    stats[4] += fallback
    stats[1] = max(stats[1], it)
    stats[3] = max(stats[3], err)
    for a in range(vn.shape[0]):
        if active[a] != previous[a]:
            stats[2] += 1
        previous[a] = active[a]
        v[n, a] = vn[a]
        psi[n, a] = -wn[a]
        dv[n, a] = vn[a] - v_b[a]
    return True


@njit(cache=True)
def march_naive(W, psi_affine, v_b, max_iter, tol, law):
    """The CLCP march with direct summation of the history; see :func:`clcp.march_cq`.

    Parameters
    ----------
    W : (N+1, m, m) weights (``W[0]`` symmetric positive definite)
    psi_affine : (N+1, m)
    v_b : (m,)
    max_iter : int, linear solves per LCP at most
    tol : float, largest acceptable LCP error of a step
    law : ``(code, rate, P)`` of :meth:`unilateral.constraints.StepLaw.compiled`

    Returns
    -------
    v, psi : (N+1, m)
    stats : (5,) float: total solves, largest solves in a step, contact changes, max LCP error,
        steps solved by the fallback (Lemke's method, :func:`~unilateral.lcp.pivoting.solve_step`)
    failed_step : int, 0 if every step succeeded, else the step whose LCP failed
    """
    carry = naive_start(W[0], psi_affine, v_b)
    failed = naive_steps(W, psi_affine, v_b, max_iter, tol, law, carry, 1, psi_affine.shape[0])
    v, psi, stats = carry[0], carry[1], carry[3]
    if failed:
        return v[:failed], psi[:failed], stats, failed
    return v, psi, stats, 0


@njit(cache=True)
def naive_start(W0, psi_affine, v_b):
    """The state a chunked naive march carries: outputs, statistics, contact sets, ``first``."""
    v, psi, dv, stats, active, previous, base = _outputs(W0, psi_affine, v_b)
    first = np.full(1, -1, dtype=np.int64)   # first step with a nonzero increment
    return v, psi, dv, stats, active, previous, base, first


@njit(cache=True)
def naive_steps(W, psi_affine, v_b, max_iter, tol, law, carry, n0, n1):
    """Steps ``n0 <= n < n1`` of :func:`march_naive` on the carried state; the failed step or 0."""
    v, psi, dv, stats, active, previous, base, first = carry
    m = psi_affine.shape[1]
    W0 = W[0]
    WL = law_matrix(law[0], law[2], W0)
    q, vn, wn, idx, S, rhs, x = _workspace(m)
    o, t1 = np.empty(m), np.empty(m)
    for n in range(n0, n1):
        for a in range(m):
            q[a] = -psi_affine[n, a] - base[a]
        if first[0] >= 0:
            for j in range(1, n - first[0] + 1):
                Wj = W[j]
                d = dv[n - j]
                for a in range(m):
                    t = 0.0
                    for b in range(m):
                        t += Wj[a, b] * d[b]
                    q[a] += t
        step = _law_step(law, W0, WL, q, v[n - 1], vn, wn, active, (max_iter, tol), (idx, S, rhs, x), o, t1)
        if not _record(n, step, tol, active, previous, vn, wn, v_b, v, psi, dv, stats):
            return n
        if first[0] < 0:
            for a in range(m):
                if dv[n, a] != 0.0:
                    first[0] = n
    return 0


@njit(cache=True)
def march_recursive(W0, coef, gain, out, inp, psi_affine, v_b, max_iter, tol, law):
    """The CLCP march with the exact recursive history of a pole-residue kernel.

    The history is ``Re(free @ out)`` with ``free = sum_i coef_i state_i`` of the scalar filters
    (channels c) of :class:`~unilateral.history.RecursiveHistory`; the filters are then
    advanced with the input ``inp @ dv_n``. O(c m) work per step, independent of n and N.

    Parameters
    ----------
    W0 : (m, m) symmetric positive definite
    coef : (2q, c) complex, rows ``-alpha_i/alpha_0`` and ``beta_i/alpha_0`` interleaved
    gain : (c,) complex, ``beta_0/alpha_0``
    out, inp : (c, m) complex output and input factors
    psi_affine : (N+1, m);  v_b : (m,);  max_iter : int;  tol : float
    law : ``(code, rate, P)`` of :meth:`unilateral.constraints.StepLaw.compiled`

    Returns
    -------
    As :func:`march_naive`.
    """
    carry = recursive_start(W0, coef, psi_affine, v_b)
    failed = recursive_steps(W0, (coef, gain, out, inp), psi_affine, v_b, max_iter, tol, law, carry,
                             (1, psi_affine.shape[0]))
    v, psi, stats = carry[0], carry[1], carry[3]
    if failed:
        return v[:failed], psi[:failed], stats, failed
    return v, psi, stats, 0


@njit(cache=True)
def recursive_start(W0, coef, psi_affine, v_b):
    """The state a chunked recursive march carries: outputs, statistics, contact sets, filters."""
    v, psi, dv, stats, active, previous, base = _outputs(W0, psi_affine, v_b)
    rows, c = coef.shape
    state = np.zeros((rows, c), dtype=np.complex128)
    return v, psi, dv, stats, active, previous, base, state


@njit(cache=True)
def recursive_steps(W0, filters, psi_affine, v_b, max_iter, tol, law, carry, steps):
    """Steps ``steps[0] <= n < steps[1]`` of :func:`march_recursive`; the failed step or 0.

    ``filters`` is ``(coef, gain, out, inp)``; ``carry`` the state of :func:`recursive_start`.
    """
    coef, gain, out, inp = filters
    v, psi, dv, stats, active, previous, base, state = carry
    m = psi_affine.shape[1]
    rows, c = coef.shape
    q, vn, wn, idx, S, rhs, x = _workspace(m)
    WL = law_matrix(law[0], law[2], W0)
    o, t1 = np.empty(m), np.empty(m)
    free = np.empty(c, dtype=np.complex128)
    for n in range(steps[0], steps[1]):
        for k in range(c):
            t = 0j
            for i in range(rows):
                t += coef[i, k] * state[i, k]
            free[k] = t
        for a in range(m):
            t = 0.0
            for k in range(c):
                t += (free[k] * out[k, a]).real
            q[a] = t - psi_affine[n, a] - base[a]
        step = _law_step(law, W0, WL, q, v[n - 1], vn, wn, active, (max_iter, tol), (idx, S, rhs, x), o, t1)
        if not _record(n, step, tol, active, previous, vn, wn, v_b, v, psi, dv, stats):
            return n
        for i in range(rows - 1, 1, -1):
            for k in range(c):
                state[i, k] = state[i - 2, k]
        for k in range(c):
            u = 0j
            for a in range(m):
                u += inp[k, a] * dv[n, a]
            state[0, k] = free[k] + gain[k] * u
            state[1, k] = u
    return 0


@njit(cache=True)
def _pivoted(piv, b, x):
    """``x = P b``: ``b`` with LAPACK's row interchanges ``piv`` (``scipy.linalg.lu_factor``)."""
    for i in range(b.shape[0]):
        x[i] = b[i]
    for i in range(b.shape[0]):
        p = piv[i]
        if p != i:
            t = x[i]
            x[i] = x[p]
            x[p] = t


@njit(cache=True, fastmath=REASSOCIATE)
def _lu_solve(lu, piv, b, x):
    """Solve with LAPACK-style LU factors (``scipy.linalg.lu_factor``) into ``x``."""
    n = b.shape[0]
    _pivoted(piv, b, x)
    for i in range(n):                      # unit lower triangle
        t = x[i]
        for j in range(i):
            t -= lu[i, j] * x[j]
        x[i] = t
    for i in range(n - 1, -1, -1):          # upper triangle
        t = x[i]
        for j in range(i + 1, n):
            t -= lu[i, j] * x[j]
        x[i] = t / lu[i, i]


@njit(cache=True)
def _lu_solve_by_columns(luT, piv, b, x):
    """:func:`_lu_solve` with the factors transposed (``luT = lu.T``, C-ordered), applied column
    by column as LAPACK's ``getrs`` does: the inner loops update independent entries (they
    vectorise without reassociation) and a zero entry skips its column. 0.12 us of the 0.9 us
    step of a 17-DOF frame, so :func:`direct_steps` uses it; the sweeps keep :func:`_lu_solve`.
    """
    n = b.shape[0]
    _pivoted(piv, b, x)
    for j in range(n):                      # unit lower triangle
        t = x[j]
        if t != 0.0:
            for i in range(j + 1, n):
                x[i] -= luT[j, i] * t
    for j in range(n - 1, -1, -1):          # upper triangle
        t = x[j] / luT[j, j]
        x[j] = t
        if t != 0.0:
            for i in range(j):
                x[i] -= luT[j, i] * t


@njit(cache=True)
def _history(kind, dt, state, h1, h2):
    """``h1, h2`` of the rule (0: BDF1, 1: BDF2, 2: trapezoidal) from its state (5, n), in place."""
    for i in range(state.shape[1]):
        if kind == 0:
            h1[i] = state[0, i] / dt
            h2[i] = (h1[i] + state[2, i]) / dt
        elif kind == 1:
            h1[i] = (2.0 * state[0, i] - 0.5 * state[1, i]) / dt
            h2[i] = (1.5 * h1[i] + 2.0 * state[2, i] - 0.5 * state[3, i]) / dt
        else:
            h1[i] = 2.0 / dt * state[0, i] + state[2, i]
            h2[i] = 4.0 / (dt * dt) * state[0, i] + 4.0 / dt * state[2, i] + state[4, i]


@njit(cache=True)
def _advance(state, y, yd, ydd):
    """Shift a rule's state ``(5, n)`` (rows ``y0, y1, y0', y1', y0''``) by one step, in place:
    the new ``y, y', y''`` in rows 0, 2, 4, the old rows 0, 2 in rows 1, 3. Rows are indexed in
    place, never sliced: a view of a row costs more than the arithmetic of a small model's step."""
    for i in range(state.shape[1]):
        state[1, i] = state[0, i]
        state[3, i] = state[2, i]
        state[0, i] = y[i]
        state[2, i] = yd[i]
        state[4, i] = ydd[i]


@njit(cache=True)
def sweep(kind, dt, c1, c0, lu, piv, M, C, Fp, F_v, Hs, H_v, viscous, f, offset, dv, start):
    """A linear sweep of a small dense model (see :func:`clcp.sweep_direct`), compiled.

    The rules with a convolution-quadrature form only (``alpha = 0``): ``kind`` 0 BDF1, 1 BDF2,
    2 trapezoidal (Newmark 1/2, 1/4). It performs exactly the operations of
    :class:`~unilateral.march.stepper.StructureStepper` (``free_terms``, ``step_with``, ``correct``).

    Parameters
    ----------
    lu, piv : LU factors of ``D_eff``;  M, C : operands of :func:`_matvec_add` (CSR or dense);
    Fp, F_v : (n, m);  Hs, H_v : (m, m)
    viscous : bool, Kelvin terms present;  f : (N+1, n) load increments;  offset : (N+1, m)
    dv : (N+1, m) prescribed increments;  start : (5, n) the u-state ``y0, y1, yd0, yd1, ydd0``

    Returns
    -------
    du, dud : (N+1, n);  psi : (N+1, m) (row 0 left to the caller)
    """
    N1, n = f.shape
    m = offset.shape[1]
    du, dud, psi = np.zeros((N1, n)), np.zeros((N1, n)), np.zeros((N1, m))
    us, vs = start.copy(), np.zeros((5, m))
    h1, h2, k1, k2 = np.empty(n), np.empty(n), np.zeros(m), np.zeros(m)
    rhs, x, ud, a = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    dvk, vd, vdd = np.empty(m), np.empty(m), np.empty(m)
    dud[0] = us[2]
    for k in range(1, N1):
        _history(kind, dt, us, h1, h2)
        if viscous:
            _history(kind, dt, vs, k1, k2)
        for i in range(n):
            t = f[k, i]
            for b in range(m):
                t += Fp[i, b] * dv[k, b] - F_v[i, b] * k1[b]
            rhs[i] = t
        _matvec_add(M, h2, 1.0, rhs)
        _matvec_add(C, h1, 1.0, rhs)
        _lu_solve(lu, piv, rhs, x)
        for b in range(m):
            t = offset[k, b]
            for i in range(n):
                t += Fp[i, b] * x[i] - F_v[i, b] * h1[i]
            for c in range(m):
                t += H_v[b, c] * k1[c] - Hs[b, c] * dv[k, c]
            psi[k, b] = t
        for i in range(n):
            ud[i] = c1 * x[i] - h1[i]
            a[i] = c0 * x[i] - h2[i]
            du[k, i] = x[i]
            dud[k, i] = ud[i]
        _advance(us, x, ud, a)
        if viscous:
            for b in range(m):
                dvk[b] = dv[k, b]
                vd[b] = c1 * dv[k, b] - k1[b]
                vdd[b] = c0 * dv[k, b] - k2[b]
            _advance(vs, dvk, vd, vdd)
    return du, dud, psi


# ---------------------------------------------------------------------- direct stepping
#: Rule kinds of the compiled direct march: BDF1, BDF2 and Newmark (trapezoidal, HHT-alpha).
RULE_BDF1, RULE_BDF2, RULE_NEWMARK = 0, 1, 2


@njit(cache=True)
def _rule_history(kind, rp, state, h1, h2):
    """``h1, h2`` of :meth:`unilateral.rules.Rule.history` from the state (5, n), in place.

    ``rp`` holds ``dt`` and, for Newmark, the coefficients ``h1 = rp[1] y + rp[2] y' + rp[3] y''``
    and ``h2 = (y + rp[4] y' + rp[5] y'') rp[6]`` (those of :meth:`Newmark.history`).
    """
    dt = rp[0]
    for i in range(state.shape[1]):
        if kind == RULE_BDF1:
            h1[i] = state[0, i] / dt
            h2[i] = (h1[i] + state[2, i]) / dt
        elif kind == RULE_BDF2:
            h1[i] = (2.0 * state[0, i] - 0.5 * state[1, i]) / dt
            h2[i] = (1.5 * h1[i] + 2.0 * state[2, i] - 0.5 * state[3, i]) / dt
        else:
            h1[i] = rp[1] * state[0, i] + rp[2] * state[2, i] + rp[3] * state[4, i]
            h2[i] = (state[0, i] + rp[4] * state[2, i] + rp[5] * state[4, i]) * rp[6]


@njit(cache=True, fastmath=REASSOCIATE)
def _matvec_add(A, x, scale, out):
    """``out += scale * A x`` for ``A = (indptr, indices, data, full)``: CSR, or ``full`` (n, n) if
    it has rows (a dense matrix, whose rows vectorise)."""
    indptr, indices, data, full = A
    if full.shape[0]:
        for i in range(out.shape[0]):
            t = 0.0
            for j in range(full.shape[1]):
                t += full[i, j] * x[j]
            out[i] += scale * t
        return
    for i in range(out.shape[0]):
        t = 0.0
        for p in range(indptr[i], indptr[i + 1]):
            t += data[p] * x[indices[p]]
        out[i] += scale * t


@njit(cache=True)
def direct_start(N1, n, m, v_b, psi0, ustart):
    """The state a chunked direct march carries (see :func:`direct_steps`).

    Returns ``(du, dud, v, psi, stats, active, previous, ustate, vstate, dv_prev)``: the
    histories (N1 rows) with row 0 set, the statistics of :func:`march_naive`, the contact sets,
    the rule states of ``du`` (5, n: ``y0, y1, y0', y1', y0''``) and of ``dv`` (5, m) and the
    previous increment ``dv``.
    """
    du, dud = np.empty((N1, n)), np.empty((N1, n))        # every row is written by the steps
    v, psi = np.empty((N1, m)), np.empty((N1, m))
    ustate = ustart.copy()
    for i in range(n):                      # (loops, not ``dud[0] = ustate[2]``: the module's note)
        du[0, i] = 0.0
        dud[0, i] = ustate[2, i]
    for b in range(m):
        v[0, b] = v_b[b]
        psi[0, b] = psi0[b]
    active = v_b > 0.0
    return (du, dud, v, psi, np.zeros(5), active, active.copy(), ustate, np.zeros((5, m)),
            np.zeros(m))


@njit(cache=True, fastmath=REASSOCIATE)
def direct_steps(kind, rp, mats, sparse, tables, v_b, flags, law, carry, steps):
    """Steps ``steps[0] <= k < steps[1]`` of the direct march, compiled; the failed step or 0.

    The operations of :func:`unilateral.march.direct.march_direct` with
    :class:`~unilateral.march.stepper.StructureStepper` (``predict``, the condensed LCP on
    ``W0`` by :func:`~unilateral.lcp.pivoting.solve_step` warm-started from the previous contact
    set, ``correct``), for every
    rule: ``kind`` :data:`RULE_BDF1`, :data:`RULE_BDF2` or :data:`RULE_NEWMARK` (trapezoidal,
    Newmark, HHT-alpha).

    Parameters
    ----------
    kind : int;  rp : (8,) ``dt``, the Newmark coefficients of :func:`_rule_history`, ``c1``
        (rp[7]) -- ``c0``, ``alpha`` follow in ``flags``
    mats : ``(luT, piv, FpT, F, F_v, F_vT, H_v, X, W0)``: LU factors of ``D_eff``, transposed
        (n, n), and pivots (n,) (see :func:`_lu_solve_by_columns`);
        ``FpT = (F + c1 F_v)^T`` (m, n); ``F``, ``F_v`` (n, m) and ``F_vT`` (m, n); ``H_v``, ``W0``
        (m, m); ``X`` (n, m)
    sparse : ``(M, C, K)`` each ``(indptr, indices, data, full)``, see :func:`_matvec_add`
    tables : ``(f, offset, base)``: load increments (N+1, n), reaction offsets (N+1, m),
        ``W0 v_b`` (m,)
    v_b : (m,) base deformations
    flags : ``(c0, alpha, viscous, bilateral, max_iter, tol)``
    law : ``(code, rate, P)`` of :meth:`unilateral.constraints.StepLaw.compiled`; ``psi`` holds
        the constraint functions ``P psi``
    carry : the state of :func:`direct_start`, updated in place
    steps : ``(first, stop)``
    """
    luT, piv, FpT, F, F_v, F_vT, H_v, X, W0 = mats
    M, C, K = sparse
    f, offset, base = tables
    c0, alpha, viscous, bilateral, max_iter, tol = flags
    du, dud, v, psi, stats, active, previous, us, vs, dv_prev = carry
    n, m = f.shape[1], offset.shape[1]
    c1 = rp[7]
    a = 1.0 - alpha
    h1, h2, k1, k2 = np.empty(n), np.empty(n), np.zeros(m), np.zeros(m)
    rhs, x, ud, acc = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    c, dv, dvd, dvdd = np.empty(m), np.zeros(m), np.empty(m), np.empty(m)
    q, vn, wn, idx, S, work_rhs, work_x = _workspace(m)
    code, rate, P, partner, group = law
    WL = law_matrix(code, P, W0)
    o, t1 = np.zeros(m), np.empty(m)
    for k in range(steps[0], steps[1]):
        _rule_history(kind, rp, us, h1, h2)
        if viscous:
            _rule_history(kind, rp, vs, k1, k2)
        for i in range(n):                  # free_terms: rhs = a f + M h2 + a C h1 ...
            rhs[i] = a * f[k, i]
        _matvec_add(M, h2, 1.0, rhs)
        _matvec_add(C, h1, a, rhs)
        if alpha != 0.0:                    # HHT: alpha (f_prev - C u' - K u + F dv + F_v dv')
            for i in range(n):
                acc[i] = f[k - 1, i]
                for b in range(m):
                    acc[i] += F[i, b] * dv_prev[b] + F_v[i, b] * vs[2, b]
            _matvec_add(C, us[2], -1.0, acc)
            _matvec_add(K, us[0], -1.0, acc)
            for i in range(n):
                rhs[i] += alpha * acc[i]
        for b in range(m):
            c[b] = offset[k, b]
        if viscous:
            for i in range(n):
                t = 0.0
                for b in range(m):
                    t += F_v[i, b] * k1[b]
                rhs[i] -= a * t
            for b in range(m):
                t = 0.0
                for i in range(n):
                    t += F_vT[b, i] * h1[i]
                for e in range(m):
                    t -= H_v[b, e] * k1[e]
                c[b] -= t
        _lu_solve_by_columns(luT, piv, rhs, x)  # predict: du_free, psi_free
        for b in range(m):
            t = c[b]
            for i in range(n):
                t += FpT[b, i] * x[i]
            c[b] = t
        if bilateral:
            for b in range(m):
                vn[b] = v_b[b]
                dv[b] = 0.0
        else:
            q_min = 0.0
            for b in range(m):
                q[b] = -(c[b] + base[b])
            if code != 0:                   # (a row of v is sliced only where the law needs it)
                law_vector(code, rate, P, W0, q, v[k - 1], o, t1)
            for b in range(m):
                q_min = min(q_min, q[b])
            if q_min >= 0.0:                # v = 0 solves it (no linear solve), as in LCPSolver.solve
                for b in range(m):
                    vn[b] = 0.0
                    wn[b] = q[b]
                    active[b] = False
                it, err = 0, 0.0
            else:
                it, err, fallback = solve_step(WL, q, active, vn, wn, max_iter, tol, (idx, S, work_rhs, work_x),
                                               code != 2, (partner, group))
                stats[4] += fallback
            if it < 0 or err > tol:
                return k
            if code != 0:
                for b in range(m):
                    vn[b] += o[b]
            stats[0] += it
            stats[1] = max(stats[1], it)
            stats[3] = max(stats[3], err)
            nonzero = False
            for b in range(m):
                if active[b] != previous[b]:
                    stats[2] += 1
                previous[b] = active[b]
                dv[b] = vn[b] - v_b[b]
                nonzero = nonzero or dv[b] != 0.0
            if nonzero:                     # correct: du = du_free + X dv
                for i in range(n):
                    t = x[i]
                    for b in range(m):
                        t += X[i, b] * dv[b]
                    x[i] = t
        for i in range(n):
            du[k, i] = x[i]
            ud[i] = c1 * x[i] - h1[i]
            dud[k, i] = ud[i]
            acc[i] = c0 * x[i] - h2[i]
        _advance(us, x, ud, acc)
        if viscous:
            for b in range(m):
                dvd[b] = c1 * dv[b] - k1[b]
                dvdd[b] = c0 * dv[b] - k2[b]
            _advance(vs, dv, dvd, dvdd)
        for b in range(m):
            t = c[b]
            for e in range(m):
                t -= W0[b, e] * dv[e]
            t1[b] = t
            v[k, b] = vn[b]
            dv_prev[b] = dv[b]
        for b in range(m):
            if code == 2:
                t = 0.0
                for e in range(m):
                    t += P[b, e] * t1[e]
                psi[k, b] = t
            else:
                psi[k, b] = t1[b]
    return 0
