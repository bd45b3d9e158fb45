"""Compiled pivoting for the step LCPs (numba): block principal pivoting and Lemke's method.

:func:`bpp` is the block principal pivoting of every compiled march (Judice & Pires 1994, with
Murty's single pivots), with the face rules of the step laws: the two faces of a pair never both
active, at most two facets of a polygon of more than four facets active. A polygon's facet columns
are linearly dependent (more than two facets in two tangential strains), so a step LCP with such a
polygon is not a P-matrix: block principal pivoting may meet a singular principal submatrix or
cycle. :func:`solve_step` then solves the step by :func:`lemke`, the complementary pivoting of
:class:`unilateral.lcp.Lemke` (covering vector of ones, lexicographic ratio test), which keeps
a nonsingular basis and so never takes three dependent facets. The compiled marches and the step
solver of the Python marches (:class:`unilateral.lcp.faces.FaceSetPivoting`) both call
:func:`solve_step`: whatever solves a step in one engine solves it in the other.
"""

from __future__ import annotations

import numpy as np
from numba import njit

#: Number of non-improving block pivots before Murty's single pivot (Judice & Pires 1994).
BLOCK_TRIES = 3
#: Entries of Lemke's entering column below this fraction of its largest entry are no pivots, and
#: ratios within this fraction of the largest candidate tie (:mod:`unilateral.lcp.lemke` uses 1e-12):
#: a polygon's dependent facets make exact ties and exact zeros (all facets of a contact that opens
#: reach their limit at once) that round-off splits into near-ties and tiny pivots.
PIVOT_TOL = 1e-9
TIE_TOL = 1e-9
# Integer variables passed to a callee start as ``np.int64(0)``, not ``0``: numba types a
# variable first from its constant and compiles the callee once for ``Literal[int](0)`` and again
# for ``int64`` (a whole second specialisation of the callee, on a cold cache seconds each).


@njit(cache=True)
def _cholesky_solve(W, idx, k, rhs, S, x):
    """Solve ``W[idx[:k], idx[:k]] x = rhs[:k]`` by Cholesky; False if not positive definite."""
    for a in range(k):
        for b in range(k):
            S[a, b] = W[idx[a], idx[b]]
    for j in range(k):
        d = S[j, j]
        for p in range(j):
            d -= S[j, p] * S[j, p]
        if d <= 0.0:
            return False
        d = np.sqrt(d)
        S[j, j] = d
        for i in range(j + 1, k):
            t = S[i, j]
            for p in range(j):
                t -= S[i, p] * S[j, p]
            S[i, j] = t / d
    for i in range(k):                      # forward: L y = rhs
        t = rhs[i]
        for p in range(i):
            t -= S[i, p] * x[p]
        x[i] = t / S[i, i]
    for i in range(k - 1, -1, -1):          # backward: L^T x = y
        t = x[i]
        for p in range(i + 1, k):
            t -= S[p, i] * x[p]
        x[i] = t / S[i, i]
    return True


@njit(cache=True)
def _lu_solve_principal(W, idx, k, rhs, S, x):
    """Solve ``W[idx[:k], idx[:k]] x = rhs[:k]`` by LU with partial pivoting; False if singular."""
    for a in range(k):
        for b in range(k):
            S[a, b] = W[idx[a], idx[b]]
        x[a] = rhs[a]
    scale = 0.0
    for a in range(k):
        for b in range(k):
            scale = max(scale, abs(S[a, b]))
    for j in range(k):
        p = j
        for i in range(j + 1, k):
            if abs(S[i, j]) > abs(S[p, j]):
                p = i
        if abs(S[p, j]) <= 1e-14 * scale:
            return False
        if p != j:
            for b in range(k):
                t = S[j, b]
                S[j, b] = S[p, b]
                S[p, b] = t
            t = x[j]
            x[j] = x[p]
            x[p] = t
        for i in range(j + 1, k):
            f = S[i, j] / S[j, j]
            if f != 0.0:
                for b in range(j + 1, k):
                    S[i, b] -= f * S[j, b]
                x[i] -= f * x[j]
    for i in range(k - 1, -1, -1):
        t = x[i]
        for b in range(i + 1, k):
            t -= S[i, b] * x[b]
        x[i] = t / S[i, i]
    return True


@njit(cache=True)
def bpp(W, q, active, v, w, max_iter, work_idx, work_S, work_rhs, work_x, symmetric, faces):
    """Block principal pivoting for ``w = W v + q >= 0, v >= 0, v.w = 0``.

    ``W`` symmetric positive definite on the principal submatrices it visits (Cholesky), or with
    ``symmetric=False`` a nonsymmetric matrix whose visited principal submatrices are
    nonsingular (LU with partial pivoting: the step LCP of friction).
    ``faces = (partner, group)`` (int, m each; -1: none). ``partner`` pairs unknowns with opposite
    columns (two-sided yield and slip): an unknown does not enter while its partner stays active,
    and of two partners that would enter together only the one with the smaller ``w`` does (the
    one of lower index on a tie: both active would make ``W_AA`` singular; in a solution at most
    one is). ``group`` gathers the facets of one polygon of more than four facets (a friction cone,
    a 3-D hinge's interaction polygon: any three of its columns are dependent, they span two
    strains): at most two of a group are active after any exchange (:func:`_two_per_group`), those
    that enter of the smallest ``w`` first, then those that stay of the largest ``v`` (in a
    solution at most two adjacent facets are active, a vertex).
    ``active`` (bool, m) is the warm start and is updated in place to the final active set
    (``v > 0``). ``v`` and ``w`` are outputs. Returns the number of linear solves, or minus
    that number if the method failed (``W_AA`` not positive definite or singular, or no
    convergence).
    """
    m = q.shape[0]
    partner, group = faces
    grouped = False
    for i in range(m):
        grouped = grouped or group[i] >= 0
    eps, eps_v = _thresholds(W, q)
    best = m + 1
    tries = BLOCK_TRIES
    for it in range(1, max_iter + 1):
        if not _complementary(W, q, active, v, w, (work_idx, work_S, work_rhs, work_x), symmetric):
            return -it
        count = 0
        last = np.int64(-1)
        for i in range(m):
            if (active[i] and v[i] < -eps_v) or (not active[i] and w[i] < -eps):
                count += 1
                last = i
        if count == 0:
            for i in range(m):
                if active[i]:
                    w[i] = 0.0
                    if v[i] < 0.0:
                        v[i] = 0.0
            return it
        murty = False
        if count < best:
            best = count
            tries = BLOCK_TRIES
        elif tries > 0:
            tries -= 1
        else:                               # Murty: flip only the largest infeasible index
            murty = True
        _flips(active, v, w, partner, (eps, eps_v), murty, last, work_x)
        if grouped:
            _two_per_group(active, v, w, group, work_x)
        for i in range(m):
            if work_x[i] != 0.0:
                active[i] = not active[i]
    return -max_iter


@njit(cache=True)
def _thresholds(W, q):
    """``(eps, eps_v)``: the feasibility thresholds of :func:`bpp` in the units of ``w`` and ``v``."""
    m = q.shape[0]
    scale = 1.0
    w_max = 1e-300
    for i in range(m):
        scale = max(scale, abs(q[i]))
        for j in range(m):
            w_max = max(w_max, abs(W[i, j]))
    eps = 1e-13 * scale
    return eps, eps / w_max


@njit(cache=True)
def _complementary(W, q, active, v, w, work, symmetric):
    """The complementary solution of the set ``active``: ``v_A = -W_AA^-1 q_A``, ``v = 0`` off ``A``
    and ``w = W v + q``, in place; False if ``W_AA`` is not positive definite (``symmetric``) or is
    singular."""
    work_idx, work_S, work_rhs, work_x = work
    m = q.shape[0]
    k = np.int64(0)
    for i in range(m):
        if active[i]:
            work_idx[k] = i
            work_rhs[k] = -q[i]
            k += 1
    if symmetric:
        solved = _cholesky_solve(W, work_idx, k, work_rhs, work_S, work_x)
    else:
        solved = _lu_solve_principal(W, work_idx, k, work_rhs, work_S, work_x)
    if not solved:
        return False
    for i in range(m):
        v[i] = 0.0
    for a in range(k):
        v[work_idx[a]] = work_x[a]
    for i in range(m):
        t = q[i]
        for j in range(m):
            t += W[i, j] * v[j]
        w[i] = t
    return True


@njit(cache=True)
def _flips(active, v, w, partner, eps, murty, last, flip):
    """The exchange of :func:`bpp` in ``flip`` (m,) (1.0 where an unknown changes): every infeasible
    unknown, or with ``murty`` the ``last`` one only, with the pair rule. ``eps = (eps, eps_v)``."""
    eps_w, eps_v = eps
    for i in range(active.shape[0]):
        if murty:
            change = i == last
        else:
            change = (active[i] and v[i] < -eps_v) or (not active[i] and w[i] < -eps_w)
            if change and not active[i] and partner[i] >= 0:
                p = partner[i]
                stays = active[p] and not v[p] < -eps_v
                enters = not active[p] and (w[p] < w[i] or (w[p] == w[i] and p < i))
                change = not (stays or enters)
        flip[i] = 1.0 if change else 0.0
    if murty and not active[last] and partner[last] >= 0 and active[partner[last]]:
        flip[partner[last]] = 1.0           # the partner leaves as the face enters


@njit(cache=True)
def _two_per_group(active, v, w, group, flip):
    """At most two members of each group active after the exchange ``active ^ flip`` (``flip``
    (m,) nonzero where a member changes, updated in place): the members that enter of the smallest
    ``w`` first, then those that stay of the largest ``v`` (a facet that enters a polygon with two
    active facets replaces the one that carries less slip; see :func:`bpp`)."""
    m = active.shape[0]
    for i in range(m):
        g = group[i]
        if g < 0:
            continue
        first = True
        for j in range(i):
            if group[j] == g:
                first = False
                break
        if not first:
            continue                        # each group once, at its first member
        count = 0
        for j in range(i, m):
            if group[j] == g and active[j] != (flip[j] != 0.0):
                count += 1
        if count <= 2:
            continue
        kept0, kept1 = -1, -1
        for entering in (True, False):
            for _ in range(2):
                if kept1 >= 0:
                    break
                pick = -1
                for j in range(i, m):
                    if group[j] != g or j == kept0 or active[j] == entering or (flip[j] != 0.0) != entering:
                        continue
                    if pick < 0 or (w[j] < w[pick] if entering else v[j] > v[pick]):
                        pick = j
                if pick < 0:
                    break
                if kept0 < 0:
                    kept0 = pick
                else:
                    kept1 = pick
        for j in range(i, m):
            if group[j] == g:
                keep = j == kept0 or j == kept1
                flip[j] = 1.0 if keep != active[j] else 0.0


@njit(cache=True)
def lcp_error(v, w, q):
    """``||min(v, w)|| / (1 + ||q||)``, the scaled natural-map residual."""
    num = 0.0
    den = 0.0
    for i in range(v.shape[0]):
        r = min(v[i], w[i])
        num += r * r
        den += q[i] * q[i]
    return np.sqrt(num) / (1.0 + np.sqrt(den))


# ---------------------------------------------------------------------- Lemke's method
@njit(cache=True)
def _pivot(T, d, r):
    """Pivot the tableau ``T`` (in place) on row ``r`` of the entering column ``d`` (``d[r]`` zeroed)."""
    m, cols = T.shape
    dr = d[r]
    for c in range(cols):
        T[r, c] /= dr
    d[r] = 0.0
    for i in range(m):
        f = d[i]
        if f != 0.0:
            for c in range(cols):
                T[i, c] -= f * T[r, c]


@njit(cache=True)
def _lexmin(T, col, d, rows, n):
    """Keep in ``rows[:n]`` those of least ratio ``T[i, col] / d[i]`` (ties within :data:`TIE_TOL`
    of the largest ratio); their new count."""
    low, big = np.inf, 0.0
    for a in range(n):
        ratio = T[rows[a], col] / d[rows[a]]
        low = min(low, ratio)
        big = max(big, abs(ratio))
    k = 0
    for a in range(n):
        if T[rows[a], col] / d[rows[a]] <= low + TIE_TOL * big:
            rows[k] = rows[a]
            k += 1
    return k


@njit(cache=True)
def _leaving_row(T, d, basis, z0, rows):
    """The lexicographic minimum ratio test of :func:`lemke` (the artificial variable ``z0`` leaves
    whenever it ties); -1 if no entry of ``d`` qualifies (a ray)."""
    d_max = 0.0
    for i in range(d.shape[0]):
        d_max = max(d_max, abs(d[i]))
    n = np.int64(0)
    for i in range(d.shape[0]):
        if d[i] > PIVOT_TOL * d_max:
            rows[n] = i
            n += 1
    if n == 0:
        return -1
    col = np.int64(0)
    n = _lexmin(T, col, d, rows, n)
    if n == 1:
        return rows[0]
    for a in range(n):
        if basis[rows[a]] == z0:
            return rows[a]
    col = np.int64(1)
    while n > 1 and col < T.shape[1]:
        n = _lexmin(T, col, d, rows, n)
        col += 1
    return rows[0]


@njit(cache=True)
def lemke(W, q, active, max_iter):
    """Lemke's method for ``w = W v + q >= 0, v >= 0, v.w = 0`` (:class:`unilateral.lcp.Lemke`).

    The revised tableau ``[x_B, B^-1]`` of ``w - W z - e z0 = q`` with the lexicographic ratio
    test. ``active`` (bool, m) is set to the final complementary basis (``z`` basic). Returns the
    number of pivots, or minus that number on a secondary ray or at ``max_iter``; the solution
    is the complementary solution of ``active`` (:func:`_complementary`).
    """
    m = q.shape[0]
    z0 = 2 * m                              # variable ids: w_i -> i, z_i -> m + i, z0 -> 2m
    T = np.zeros((m, m + 1))
    basis = np.arange(m)
    d, rows = np.empty(m), np.empty(m, dtype=np.int64)
    r = np.int64(0)
    for i in range(m):
        T[i, 0] = q[i]
        T[i, 1 + i] = 1.0
        if q[i] <= q[r]:                    # the last index of min(q): the lexicographic least row
            r = i
        d[i] = -1.0
    _pivot(T, d, r)
    entering, basis[r] = m + r, z0
    for pivots in range(2, max_iter + 1):
        for i in range(m):
            if entering < m:
                d[i] = T[i, 1 + entering]
            else:
                t = 0.0
                for j in range(m):
                    t += T[i, 1 + j] * W[j, entering - m]
                d[i] = -t
        r = _leaving_row(T, d, basis, z0, rows)
        if r < 0:
            return -(pivots - 1)
        leaving = basis[r]
        _pivot(T, d, r)
        basis[r] = entering
        if leaving == z0:
            for i in range(m):
                active[i] = False
            for i in range(m):
                if basis[i] >= m:
                    active[basis[i] - m] = True
            return pivots
        entering = leaving + m if leaving < m else leaving - m
    return -max_iter


# ---------------------------------------------------------------------- the step solver
@njit(cache=True)
def solve_step(W, q, active, v, w, max_iter, tol, work, symmetric, faces):
    """One step LCP ``(W, q)``: ``v = 0`` if ``q >= 0``, else :func:`bpp` warm-started from ``active``,
    and where it fails on a law
    with faces (pairs or polygons: ``W`` not a P-matrix), :func:`lemke`, then :func:`bpp` from
    Lemke's basis if its solution misses ``tol`` (a polish of the round-off of the tableau).

    ``work = (idx, S, rhs, x)`` as :func:`bpp`'s workspace. ``active``, ``v`` and ``w`` are updated
    in place (the final set, the solution, ``W v + q``). Returns ``(solves, error, fallback)``:
    the linear solves of :func:`bpp` plus the pivots of :func:`lemke` (each at most ``max_iter``;
    negative: failed), the LCP
    error (:func:`lcp_error`) and 1 if the step needed Lemke's method, else 0.
    """
    idx, S, rhs, x = work
    m = q.shape[0]
    q_min = 0.0
    for i in range(m):
        q_min = min(q_min, q[i])
    if q_min >= 0.0:                        # v = 0 solves it (no linear solve), as in LCPSolver.solve
        for i in range(m):
            v[i] = 0.0
            w[i] = q[i]
            active[i] = False
        return 0, 0.0, 0
    it = bpp(W, q, active, v, w, max_iter, idx, S, rhs, x, symmetric, faces)
    err = lcp_error(v, w, q) if it >= 0 else np.inf
    if it >= 0 and err <= tol:
        return it, err, 0
    partner, group = faces
    faced = False
    for i in range(q.shape[0]):
        faced = faced or partner[i] >= 0 or group[i] >= 0
    if not faced:
        return it, err, 0
    spent = abs(it)
    pivots = lemke(W, q, active, max_iter)
    spent += abs(pivots)
    # (``not faced`` is False here: a variable, not the constant, so that _complementary has one
    # specialisation, not a second one for the literal False)
    if pivots < 0 or not _complementary(W, q, active, v, w, work, not faced):
        return -spent, np.inf, 1
    _clip(W, q, active, v, w, tol)
    err = lcp_error(v, w, q)
    if err > tol:                           # polish: block principal pivoting from Lemke's basis
        again = bpp(W, q, active, v, w, max_iter, idx, S, rhs, x, symmetric, faces)
        spent += abs(again)
        err = lcp_error(v, w, q) if again >= 0 else np.inf
        if again < 0:
            return -spent, err, 1
    if err > tol:
        return -spent, err, 1
    for i in range(q.shape[0]):             # as block principal pivoting leaves a solution
        if active[i]:
            w[i] = 0.0
            v[i] = max(v[i], 0.0)
    return spent, err, 1


@njit(cache=True)
def _clip(W, q, active, v, w, tol):
    """Round-off of a complementary solution: ``v`` within ``-tol (1 + ||q||)`` of 0 made 0 (as
    :meth:`unilateral.lcp.LCPSolver.solve`) and ``w = W v + q`` again."""
    m = q.shape[0]
    norm = 0.0
    for i in range(m):
        norm += q[i] * q[i]
    floor = -tol * (1.0 + np.sqrt(norm))
    changed = False
    for i in range(m):
        if v[i] < 0.0 and v[i] >= floor:
            v[i] = 0.0
            changed = True
    if changed:
        for i in range(m):
            t = q[i]
            for j in range(m):
                t += W[i, j] * v[j]
            w[i] = t
