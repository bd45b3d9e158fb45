"""Convolution-quadrature weights of a structure's flexibility ``T^T D(s)^-1 T`` by compiled stepping.

The CQ weights of ``T^T D(s)^-1 T``, ``D(s) = K + s C + s^2 M``, for a rule with a
convolution-quadrature form (BDF1, BDF2, trapezoidal) are the impulse responses of that rule applied
to the structure from rest: a unit contact-force increment ``T b`` at step 1 and nothing after,
``W_j b = T^T du_{j+1}`` (``docs/theory.md``, section 12). They are computed this way, not by the FFT
on a circle, because ``D(s)`` is ill-conditioned at small ``|s|`` (a footing resting only on the
soil: ``K`` singular, a pole of ``D(s)^-1`` at ``s = 0``; axially rigid members), where the FFT
loses digits while the stepping only needs ``D_eff = c0 M + c1 C + K`` (positive definite as ``M``
is) to be factorised.

:func:`structure_weights` performs the operations of one linear sweep per impulse
(:func:`unilateral.march.direct.sweep_direct` with a
:class:`~unilateral.march.stepper.StructureStepper`, as ``FoundationModel.weights`` did), but

* all ``r`` impulses are stepped together: each step solves one (n, r) block;
* ``D_eff`` is factorised once;
* the recursion over the steps is one call of compiled code (numba, imported on first use).

Why stepping and not a closed form
----------------------------------
The rule's one-step map ``z_{k+1} = A z_k`` (state ``z``: the ``2n``-``4n`` past displacements,
velocities, accelerations) gives ``W_j = G A^j B``. A modal (eigen) decomposition of ``A`` would
turn this into scalar recursions, but it is not exact where it matters most: a footing resting only
on the soil has a rigid mode of ``K``, i.e. a double eigenvalue 1 of ``A`` with a single eigenvector
(a Jordan block: the response to an impulse drifts linearly), which no diagonalisation represents;
eigenvalues of ``K`` that should be zero come out as ``eps * |K|`` and bend the drift by about
``eps |K|/|M| t^2`` relative (an estimate: with the example tower's ``|K| = 2e11`` kN/m and masses
of 40 t, 1e-6 per s^2, 3e-5 after 5 s), against the 1e-12 agreement required with the stepping.
A non-proportional ``C`` needs the complex quadratic eigenproblem, whose eigenvectors are
ill-conditioned near critical damping. Powers of ``A`` (doubling) cost
``O(n^3)`` per step and need all ``N`` of them anyway. The stepping is exact (it *is* the
definition of the weights) and costs per step and impulse

* ``"small"`` path (up to :data:`DENSE_MAX_N` DOFs): the operations of the compiled sweep
  :func:`unilateral.march.compiled.sweep` (its own helpers; the same LAPACK LU of ``D_eff``):
  ``rhs = M h2 + C h1``, two triangular solves, ``T^T x``: about ``n^2 + (n + nnz) + n m``
  multiply-adds per impulse;
* ``"dense"`` path (larger dense matrices): ``x = P h2 + Q h1`` with ``P = D_eff^-1 M`` and
  ``Q = D_eff^-1 C`` formed once, one BLAS ``gemm`` per step for all impulses: ``2 n^2``
  (``n^2`` undamped) plus ``n m``;
* ``"sparse"`` path: ``(nnz(M) + nnz(C) + nnz(L) + nnz(U) + nnz(T))``: products in CSR and the
  triangular solves with SuperLU's factors of ``D_eff`` (``splu``, once), all in the compiled loop.

So the time is linear in ``N`` and in ``r`` (the columns of the impulse basis, at most ``m``), with a
per-step constant free of Python overhead; ``engine="auto"`` picks ``"small"`` up to
:data:`DENSE_MAX_N` DOFs, otherwise the cheaper of ``"dense"`` and ``"sparse"`` by the counts above
(a dense input with more than :data:`SPARSE_FRACTION` nonzeros is stepped dense).

Agreement with the sweeps: the existing compiled and Python sweeps themselves differ by round-off
that the rigid drift of a footing resting on the soil (a Jordan block at ``zeta = 1``) and massless
DOFs amplify: from zero to 2e-12 on the tests' structures (300 steps), 3.5e-10 at 5000 steps on the
half-space example's tower (axial stiffness 2e11 kN/m against masses of 40 t, massless footing), whose
weights the float64 data determine only to about 1e-6 (solves refined in extended precision move
them that much). The loops here agree with either sweep to that floor: at most 2e-12 on the tests'
structures, and on the tower 0 to 4e-12 with the compiled sweep, 8e-12 to 3.5e-10 with the Python
one (``tests/test_structure_weights.py``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..linalg import Factorization, SingularMatrixError, dense

__all__ = ["structure_weights"]

#: Structures with at most this many DOFs are always stepped with dense operators.
DENSE_MAX_N = 64
#: A dense input above :data:`DENSE_MAX_N` DOFs with at most this fraction of nonzeros in ``M``,
#: ``C`` and ``K`` is tried as a sparse matrix (and stepped sparse if that is cheaper).
SPARSE_FRACTION = 0.25

#: Rule kinds of the compiled loops (those of :mod:`unilateral.march.compiled`).
_KINDS = {"bdf1": 0, "bdf2": 1, "trapezoidal": 2}


def structure_weights(M, K, C, T, rule, dt, N, *, basis=None, engine="auto") -> np.ndarray:
    """CQ weights ``W_0 .. W_N`` of ``T^T D(s)^-1 T`` (``D(s) = K + s C + s^2 M``) on an impulse basis.

    ``W[j] = T^T du_{j+1}``: the opening ``T^T du`` at steps ``1 .. N+1`` of the structure stepped
    from rest by ``rule`` under the contact-force increment ``basis`` (one column per impulse) at
    step 1 only; the numbers of the linear sweeps of ``FoundationModel.weights`` (one
    :func:`~unilateral.march.direct.sweep_direct` per column of ``basis``), to round-off.

    Parameters
    ----------
    M, K : (n, n) ndarray or scipy.sparse
        Mass (kg, or t) and stiffness (N/m, or kN/m) of the structure, symmetric positive
        semidefinite; ``K`` may be singular (a footing resting only on the soil) as long as
        ``c0 M + c1 C + K`` is not (every zero-stiffness mode has mass or damping).
    C : (n, n) ndarray or scipy.sparse, or None
        Damping (N s/m); None: undamped.
    T : (n, m) ndarray or scipy.sparse
        Upward displacement of the foundation at each contact per DOF displacement (-).
    rule : str or Rule
        ``"bdf1"``, ``"bdf2"``, ``"trapezoidal"`` (a rule with a convolution-quadrature form).
    dt : float
        Time step (s), > 0.
    N : int
        Last weight index (>= 0): ``N + 1`` weights.
    basis : (m, r) ndarray, optional
        Impulses (contact-force increments, N) whose responses are computed, e.g.
        ``FoundationModel.impulse_basis()``; default the identity (``r = m``).
    engine : {"auto", "small", "dense", "sparse"}
        ``"small"``: the compiled sweep's operations per impulse (LAPACK LU of ``D_eff``);
        ``"dense"``: ``P = D_eff^-1 M``, ``Q = D_eff^-1 C`` formed once, a ``gemm`` per step;
        ``"sparse"``: CSR products and SuperLU's triangular factors per step; ``"auto"``: small up
        to :data:`DENSE_MAX_N` DOFs, otherwise the cheaper per step (see the module's notes).

    Returns
    -------
    W : (N + 1, m, r) ndarray, float
        Opening at the contacts (m) per unit impulse (N) of each basis column: m/N. With
        ``basis = V`` (orthonormal columns spanning the row space of ``T``) the full weights are
        ``W @ V.T`` (N + 1, m, m).

    Raises
    ------
    ValueError
        Inconsistent shapes, a rule without a CQ form, ``dt <= 0``, ``N < 0``, or
        ``c0 M + c1 C + K`` singular (a mode without stiffness, mass or damping).
    """
    rule, dt, N, basis = _checked_arguments(M, K, C, T, rule, dt, N, basis=basis, engine=engine)
    if basis.shape[1] == 0:
        return np.zeros((N + 1, T.shape[1], 0))
    return _stepped_weights(M, K, C, T, rule, dt, N, basis=basis, engine=engine)


def _checked_arguments(M, K, C, T, rule, dt, N, *, basis, engine):
    """The arguments of :func:`structure_weights` checked: ``(rule, dt, N, basis)`` as a
    :class:`~unilateral.rules.Rule` with a CQ form, a float (s), an int and an (m, r) float array
    (the identity if None); ValueError for a bad one (see :func:`structure_weights`)."""
    from ..rules import get_rule

    rule = get_rule(rule, cq=True)
    if rule.name not in _KINDS or rule.alpha:
        raise ValueError(f"structure_weights needs rule 'bdf1', 'bdf2' or 'trapezoidal', got {rule!r}")
    dt = float(dt)
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt must be a positive time step (s), got {dt!r}")
    N = int(N)
    if N < 0:
        raise ValueError(f"N must be >= 0, got {N}")
    if engine not in ("auto", "small", "dense", "sparse"):
        raise ValueError(f"engine must be 'auto', 'small', 'dense' or 'sparse', got {engine!r}")
    n = K.shape[0]
    for name, A in (("M", M), ("K", K), ("C", C)):
        if A is not None and A.shape != (n, n):
            raise ValueError(f"{name} has shape {A.shape}, expected ({n}, {n})")
    if T.ndim != 2 or T.shape[0] != n:
        raise ValueError(f"T has shape {T.shape}, expected ({n}, m)")
    m = T.shape[1]
    basis = np.eye(m) if basis is None else np.asarray(basis, dtype=float)
    if basis.ndim != 2 or basis.shape[0] != m:
        raise ValueError(f"basis has shape {basis.shape}, expected ({m}, r)")
    return rule, dt, N, basis


def _stepped_weights(M, K, C, T, rule, dt, N, *, basis, engine) -> np.ndarray:
    """The weights ``W`` (N + 1, m, r) of :func:`structure_weights` (checked arguments, ``r > 0``
    impulses): the engine chosen (:func:`_choose_engine`), ``D_eff = c0 M + c1 C + K`` factorised
    once, the impulses ``B = T basis`` (n, r) stepped by the compiled loop of the engine."""
    n = K.shape[0]
    c1, c0 = rule.coefficients(dt)
    kind, rp = _rule_parameters(rule, dt)
    damped = C is not None and (C.nnz if sp.issparse(C) else np.count_nonzero(C)) > 0
    plan, sparse_parts = _choose_engine(engine, (M, K, C if damped else None, T), (c1, c0), N)
    march_small, march_dense, march_sparse = _kernels()
    B = np.ascontiguousarray(dense(T @ basis) if sp.issparse(T) else np.asarray(T, float) @ basis,
                             dtype=float)                           # (n, r): the load T b at step 1
    if plan == "sparse":
        return march_sparse(kind, rp, sparse_parts[0], damped, B, N + 1)
    Md, Kd = dense(M).astype(float), dense(K).astype(float)
    Cd = dense(C).astype(float) if damped else np.zeros((n, n))
    D = c0 * Md + 1.0 * (c1 * Cd + Kd)              # the stepper's c0 M + (1 - alpha)(c1 C + K)
    lu = Factorization(D, what="the effective stiffness c0 M + c1 C + K of the structure")
    if plan == "small":
        from ..march.stepper import matvec_operand

        Fp = np.ascontiguousarray(dense(T), dtype=float)
        lu_piv = lu.dense_factors
        factors = (np.ascontiguousarray(lu_piv[0]), lu_piv[1])
        loads = (Fp, np.ascontiguousarray(Fp.T), np.ascontiguousarray(basis))
        return march_small(kind, (dt, c1, c0), factors, (matvec_operand(Md), matvec_operand(Cd)),
                           loads, N + 1)
    P = np.ascontiguousarray(lu.solve(Md))
    Q = np.ascontiguousarray(lu.solve(Cd)) if damped else np.zeros((n, n))
    X1 = np.ascontiguousarray(lu.solve(B))
    Tt = np.ascontiguousarray(dense(T).T, dtype=float)
    return march_dense(kind, rp, (P, Q), damped, (X1, Tt), N + 1)

def _choose_engine(engine, mats, coefficients, N):
    """``(engine, sparse_parts)``: the loop ``engine="auto"`` takes (the given one otherwise) and
    ``(operands, cost)`` of the sparse loop if they were built (None otherwise).

    ``mats = (M, K, C, T)`` (``C`` None if undamped), ``coefficients = (c1, c0)`` of the rule.
    """
    M, K, C, T = mats
    c1, c0 = coefficients
    n, m = K.shape[0], T.shape[1]
    plan = engine
    if plan == "auto":
        plan = "small" if n <= DENSE_MAX_N else None
    if plan is None and not any(sp.issparse(A) for A in (M, K, C) if A is not None):
        nonzeros = sum(np.count_nonzero(A) for A in (M, K, C) if A is not None)
        if nonzeros > SPARSE_FRACTION * n * n:
            plan = "dense"
    sparse_parts = None
    if plan in (None, "sparse"):
        sparse_parts = _sparse_operators(M, K, C, T, c0, c1)
        if plan is None:
            damped = C is not None
            dense_cost = n * n * (2 if damped else 1) + n * m + (4 if damped else 3) * n ** 3 / (N + 1)
            plan = "sparse" if sparse_parts[1] <= dense_cost else "dense"
    return plan, sparse_parts


def _rule_parameters(rule, dt):
    """``(kind, rp)``: the rule's kind and ``rp = (dt, c1, c0, n1, n2, n3, n4, n5, n6)`` (Newmark's
    history coefficients, as in :meth:`StructureStepper.march_arrays`)."""
    c1, c0 = rule.coefficients(dt)
    rp = np.zeros(9)
    rp[0], rp[1], rp[2] = dt, c1, c0
    if rule.name == "trapezoidal":
        g, b = rule.gamma, rule.beta
        rp[3:9] = (g / (b * dt), g / b - 1.0, dt * (g / (2 * b) - 1.0), dt, dt * dt * (0.5 - b),
                   1.0 / (b * dt * dt))
    return _KINDS[rule.name], rp


def _sparse_operators(M, K, C, T, c0, c1):
    """``(operands, cost)``: the operands of the sparse loop and its cost per step and impulse
    (multiply-adds).

    ``D_eff = c0 M + c1 C + K`` is factorised by SuperLU, ``Pr D_eff Pc = L U``; the loop gets the
    strictly triangular parts of ``L`` and ``U`` (CSC) and their diagonals.
    """
    Ms = sp.csr_matrix(M, dtype=float)
    Ks = sp.csr_matrix(K, dtype=float)
    Cs = sp.csr_matrix(C, dtype=float) if C is not None else sp.csr_matrix(Ms.shape)
    D = (c0 * Ms + (c1 * Cs + Ks)).tocsc()
    what = "the effective stiffness c0 M + c1 C + K of the structure"
    try:
        lu = spla.splu(D)
    except RuntimeError as exc:
        raise SingularMatrixError(f"{what} is singular ({exc})") from None
    L, U = lu.L.tocsc(), lu.U.tocsc()
    Ld, Ud = L.diagonal().astype(float), U.diagonal().astype(float)
    if Ud.size and np.abs(Ud).min() <= 1e-13 * np.abs(Ud).max():
        raise SingularMatrixError(f"{what} is singular or nearly so (pivot ratio "
                                  f"{np.abs(Ud).min() / np.abs(Ud).max():.2e})")
    Ls, Us = sp.tril(L, -1, format="csc"), sp.triu(U, 1, format="csc")
    Tt = sp.csr_matrix(sp.csr_matrix(T, dtype=float).T)
    csr = lambda A: (A.indptr.astype(np.int64), A.indices.astype(np.int64), A.data.astype(float))
    cost = Ms.nnz + Cs.nnz + Ls.nnz + Us.nnz + Tt.nnz + 2 * Ms.shape[0]
    operands = (csr(Ms), csr(Cs), (*csr(Ls), Ld), (*csr(Us), Ud),
                (lu.perm_r.astype(np.int64), lu.perm_c.astype(np.int64)), csr(Tt))
    return operands, cost


# ---------------------------------------------------------------------- compiled loops
# Plain functions here, compiled by :func:`_kernels` on first use (numba is imported then, as the
# rest of the package does), with the on-disk cache: a second process loads the machine code.

def _history(kind, rp, state, h1, h2):
    """``h1, h2`` (n, r) of :meth:`unilateral.rules.Rule.history` from the state
    ``(y0, y1, y0', y1', y0'')``, in place."""
    y0, y1, yd0, yd1, ydd0 = state
    dt = rp[0]
    n, r = y0.shape
    for i in range(n):
        for j in range(r):
            if kind == 0:
                a = y0[i, j] / dt
                h1[i, j] = a
                h2[i, j] = (a + yd0[i, j]) / dt
            elif kind == 1:
                a = (2.0 * y0[i, j] - 0.5 * y1[i, j]) / dt
                h1[i, j] = a
                h2[i, j] = (1.5 * a + 2.0 * yd0[i, j] - 0.5 * yd1[i, j]) / dt
            else:
                h1[i, j] = rp[3] * y0[i, j] + rp[4] * yd0[i, j] + rp[5] * ydd0[i, j]
                h2[i, j] = (y0[i, j] + rp[6] * yd0[i, j] + rp[7] * ydd0[i, j]) * rp[8]


def _advance(rp, x, h1, h2, state):
    """Append the step: ``du' = c1 x - h1``, ``du'' = c0 x - h2``; shift the past values of the
    state ``(y0, y1, y0', y1', y0'')`` in place."""
    y0, y1, yd0, yd1, ydd0 = state
    c1, c0 = rp[1], rp[2]
    n, r = x.shape
    for i in range(n):
        for j in range(r):
            y1[i, j] = y0[i, j]
            yd1[i, j] = yd0[i, j]
            y0[i, j] = x[i, j]
            yd0[i, j] = c1 * x[i, j] - h1[i, j]
            ydd0[i, j] = c0 * x[i, j] - h2[i, j]


def _csr_times_add(indptr, indices, data, X, out):
    """``out += A X`` for ``A`` in CSR and ``X``, ``out`` (., r) C-ordered."""
    r = X.shape[1]
    for i in range(indptr.shape[0] - 1):
        for p in range(indptr[i], indptr[i + 1]):
            a = data[p]
            col = indices[p]
            for j in range(r):
                out[i, j] += a * X[col, j]


def _march_dense(kind, rp, operators, damped, start, N1):
    """The dense loop: ``x_k = P h2 + Q h1`` (``x_1 = X1``), ``W[k-1] = Tt x_k``; (N1, m, r).

    ``operators = (P, Q)`` (n, n), ``start = (X1, Tt)``: (n, r) and (m, n)."""
    P, Q = operators
    X1, Tt = start
    n, r = X1.shape
    m = Tt.shape[0]
    W = np.empty((N1, m, r))
    y0, y1, yd0, yd1, ydd0 = (np.zeros((n, r)), np.zeros((n, r)), np.zeros((n, r)),
                              np.zeros((n, r)), np.zeros((n, r)))
    h1, h2 = np.zeros((n, r)), np.zeros((n, r))
    x = X1.copy()
    for k in range(N1):
        _history(kind, rp, (y0, y1, yd0, yd1, ydd0), h1, h2)
        if k > 0:
            x = P @ h2
            if damped:
                x += Q @ h1
        W[k] = Tt @ x
        _advance(rp, x, h1, h2, (y0, y1, yd0, yd1, ydd0))
    return W


def _march_small(kind, coefficients, factors, operands, loads, N1):
    """The small dense loop: per step and impulse the operations of
    :func:`unilateral.march.compiled.sweep` (its helpers ``_c_*``), so that the weights are those
    of the per-contact compiled sweeps to round-off; (N1, m, r).

    ``coefficients = (dt, c1, c0)``, ``factors = (lu, piv)`` of ``D_eff`` (LAPACK), ``operands``
    those of ``M`` and ``C`` for ``_matvec_add``, ``loads = (Fp, Ft, basis)``: ``T`` (n, m), ``T^T``
    (m, n) C-ordered and the impulses (m, r)."""
    dt, c1, c0 = coefficients
    lu, piv = factors
    Mop, Cop = operands
    Fp, Ft, basis = loads
    n = lu.shape[0]
    m, r = basis.shape
    W = np.zeros((N1, m, r))
    state = np.zeros((r, 5, n))                     # y0, y1, y0', y1', y0'' of each impulse
    h1, h2, rhs, x = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    ud, acc = np.empty(n), np.empty(n)
    for k in range(N1):
        for j in range(r):
            _c_history(kind, dt, state[j], h1, h2)
            for i in range(n):
                t = 0.0
                if k == 0:
                    for b in range(m):
                        t += Fp[i, b] * basis[b, j]
                rhs[i] = t
            _c_matvec_add(Mop, h2, 1.0, rhs)
            _c_matvec_add(Cop, h1, 1.0, rhs)
            _c_lu_solve(lu, piv, rhs, x)
            for b in range(m):
                t = 0.0
                for i in range(n):
                    t += Ft[b, i] * x[i]
                W[k, b, j] = t
            for i in range(n):
                ud[i] = c1 * x[i] - h1[i]
                acc[i] = c0 * x[i] - h2[i]
            _c_advance(state[j], x, ud, acc)
    return W


def _march_sparse(kind, rp, operands, damped, B, N1):
    """The sparse loop: ``rhs = M h2 + C h1`` (``B`` at step 1), ``x = D_eff^-1 rhs`` by SuperLU's
    factors (``Pr D_eff Pc = L U``), ``W[k-1] = T^T x``; (N1, m, r).

    ``operands``: ``M``, ``C`` (CSR), ``L``, ``U`` (strict triangles in CSC and diagonals), the
    permutations ``(perm_r, perm_c)`` and ``T^T`` (CSR), as :func:`_sparse_operators` gives them.
    All impulses are stepped together (rows of r values: the inner loops run over the impulses);
    the past values are rotated, not copied. (Blocks of fewer impulses, to stay in cache, were
    slower at n = 2000, r = 40.)
    """
    (Mp, Mi, Mx), (Cp, Ci, Cx), (Lp, Li, Lx, Ld), (Up, Ui, Ux, Ud), (perm_r, perm_c), (Tp, Ti, Tx) = operands
    n, r = B.shape
    m = Tp.shape[0] - 1
    W = np.zeros((N1, m, r))
    y0, y1, yd0, yd1, ydd0 = (np.zeros((n, r)), np.zeros((n, r)), np.zeros((n, r)),
                              np.zeros((n, r)), np.zeros((n, r)))
    h1, h2, z, x = np.zeros((n, r)), np.zeros((n, r)), np.zeros((n, r)), np.zeros((n, r))
    for k in range(N1):
        _history(kind, rp, (y0, y1, yd0, yd1, ydd0), h1, h2)
        for i in range(n):                      # z = Pr rhs
            zi = z[perm_r[i]]
            for j in range(r):
                zi[j] = B[i, j] if k == 0 else 0.0
            if k > 0:
                for p in range(Mp[i], Mp[i + 1]):
                    a = Mx[p]
                    hrow = h2[Mi[p]]
                    for j in range(r):
                        zi[j] += a * hrow[j]
                if damped:
                    for p in range(Cp[i], Cp[i + 1]):
                        a = Cx[p]
                        hrow = h1[Ci[p]]
                        for j in range(r):
                            zi[j] += a * hrow[j]
        for c in range(n):                      # L z = z (columns of L, CSC)
            zc = z[c]
            d = Ld[c]
            for j in range(r):
                zc[j] /= d
            for p in range(Lp[c], Lp[c + 1]):
                zr = z[Li[p]]
                a = Lx[p]
                for j in range(r):
                    zr[j] -= a * zc[j]
        for c in range(n - 1, -1, -1):          # U z = z
            zc = z[c]
            d = Ud[c]
            for j in range(r):
                zc[j] /= d
            for p in range(Up[c], Up[c + 1]):
                zr = z[Ui[p]]
                a = Ux[p]
                for j in range(r):
                    zr[j] -= a * zc[j]
        for i in range(n):                      # x = Pc z
            xi, zi = x[i], z[perm_c[i]]
            for j in range(r):
                xi[j] = zi[j]
        _csr_times_add(Tp, Ti, Tx, x, W[k])
        # append the step: y1 <- y0 <- x, yd1 <- yd0 <- c1 x - h1, ydd0 <- c0 x - h2
        c1, c0 = rp[1], rp[2]
        y1, y0, x = y0, x, y1
        yd1, yd0 = yd0, yd1
        for i in range(n):
            for j in range(r):
                yd0[i, j] = c1 * y0[i, j] - h1[i, j]
        if kind == 2:
            for i in range(n):
                for j in range(r):
                    ydd0[i, j] = c0 * y0[i, j] - h2[i, j]
    return W


_COMPILED = None
#: The helpers of :mod:`unilateral.march.compiled` that ``_march_small`` calls, bound by
#: :func:`_kernels` (not imported at module level: that would import numba).
_c_history = _c_advance = _c_matvec_add = _c_lu_solve = None


def _kernels():
    """``(march_small, march_dense, march_sparse)`` compiled by numba (imported here, on first use).

    ``march_small`` calls the helpers of :mod:`unilateral.march.compiled` (so that it performs the
    sweep's very operations). numba's disk cache does not follow calls into another file: after
    editing those helpers, touch this file (or clear its ``__pycache__``) to recompile.
    """
    global _COMPILED
    if _COMPILED is None:
        import numba

        from ..march import compiled

        jit = numba.njit(cache=True)
        module = globals()
        for name in ("_history", "_advance", "_csr_times_add"):    # the loops call compiled helpers
            if not isinstance(module[name], numba.core.dispatcher.Dispatcher):
                module[name] = jit(module[name])
        for name in ("_history", "_advance", "_matvec_add", "_lu_solve"):
            module["_c" + name] = getattr(compiled, name)
        _COMPILED = (jit(_march_small), jit(_march_dense), jit(_march_sparse))
    return _COMPILED
