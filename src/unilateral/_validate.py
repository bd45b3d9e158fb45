"""Argument checks at the public boundary.

Every check raises ``ValueError`` or ``TypeError`` whose message names the argument, shows the
offending value (or shape) and says what would be valid, so that bad input never surfaces as a
traceback from deep inside numpy or scipy.
"""

from __future__ import annotations

import sys
from collections.abc import Callable

import numpy as np

SYMMETRY_RTOL = 1e-9


def _issparse(value) -> bool:
    """``scipy.sparse.issparse(value)`` without importing scipy: nothing is sparse before scipy.sparse is
    imported (the figure process checks its inputs with these functions and never needs it)."""
    sparse = sys.modules.get("scipy.sparse")
    return sparse is not None and sparse.issparse(value)


def describe(value) -> str:
    """Short description of a value for error messages."""
    if isinstance(value, np.ndarray) or _issparse(value):
        return f"array of shape {value.shape}"
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def as_matrix(name: str, value, shape: tuple[int | None, int | None], *, allow_sparse=True, copy=True):
    """Return ``value`` as a float dense array or a CSR sparse matrix of the given shape.

    ``None`` in ``shape`` accepts any size along that axis. ``copy=False`` (internal: a matrix its
    caller has just computed and hands over) keeps a float ndarray ``value`` itself instead of a
    copy; every check is the same.
    """
    if value is None:
        raise TypeError(f"{name} is required (got None); pass an array of shape {_shape_text(shape)}")
    _refuse_complex(name, value)
    if _issparse(value):
        import scipy.sparse as sp

        if not copy and allow_sparse and type(value) is sp.csr_matrix and value.dtype == np.float64:
            pass                        # handed over: kept as it is (a new wrapper would share its arrays)
        else:
            value = sp.csr_matrix(value, dtype=float) if allow_sparse else value.toarray().astype(float)
    else:
        try:
            value = np.array(value, dtype=float) if copy else np.asarray(value, dtype=float)
        except (TypeError, ValueError) as exc:
            raise TypeError(f"{name} must be a real array, got {describe(value)} ({exc})") from None
        if value.ndim == 1 and shape[1] == 1:
            value = value[:, None]
        if value.ndim == 0 and shape == (1, 1):
            value = value.reshape(1, 1)
    if value.ndim != 2:
        raise ValueError(f"{name} must be a 2-D array of shape {_shape_text(shape)}, got shape {value.shape}")
    for axis, expected in enumerate(shape):
        if expected is not None and value.shape[axis] != expected:
            raise ValueError(f"{name} has shape {value.shape}, expected {_shape_text(shape)}")
    check_finite(name, value.data if _issparse(value) else value)
    return value


def as_vector(name: str, value, size: int | None) -> np.ndarray:
    """Return ``value`` as a finite float vector of the given size (a scalar is broadcast)."""
    _refuse_complex(name, value)
    try:
        arr = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real vector, got {describe(value)}") from None
    if arr.ndim == 0 and size is not None:
        arr = np.full(size, float(arr))
    if arr.ndim != 1 or (size is not None and arr.shape[0] != size):
        raise ValueError(f"{name} must have shape ({size},), got shape {arr.shape}")
    check_finite(name, arr)
    return arr


def _refuse_complex(name: str, value) -> None:
    """Complex input would lose its imaginary part silently in a conversion to float."""
    dtype = getattr(value, "dtype", None)
    if dtype is None and not isinstance(value, (str, bytes)):
        try:
            dtype = np.asarray(value).dtype
        except (TypeError, ValueError):
            return
    if dtype is not None and np.issubdtype(dtype, np.complexfloating):
        raise TypeError(f"{name} must be real; got a complex array ({describe(value)})")


def check_finite(name: str, data) -> None:
    data = np.asarray(data)
    if data.dtype.kind == "f" and data.size > SMALL_DENSE_SIZE and np.isfinite(np.add.reduce(data, axis=None)):
        return                  # a finite sum: no inf or nan among the entries (one cheap pass)
    if not np.all(np.isfinite(data)):
        bad = np.argwhere(~np.isfinite(data))[0]
        where = tuple(int(i) for i in bad)
        raise ValueError(f"{name} contains {float(data[where])!r} at index {where}; all entries must be finite")


#: Sparse matrices with at most this many entries are checked in dense form (scipy's sparse
#: arithmetic costs tens of microseconds a call whatever the size).
SMALL_DENSE_SIZE = 64 * 64


def check_symmetric(name: str, A, *, diagonal=False) -> None:
    """Raise ``ValueError`` if ``A`` is not symmetric to ``SYMMETRY_RTOL`` relative.

    ``diagonal=True``: ``A`` is known to be a diagonal matrix (:func:`is_diagonal`), symmetric.
    """
    if diagonal:
        return
    if _issparse(A) and A.shape[0] * A.shape[1] <= SMALL_DENSE_SIZE:
        A = A.toarray()         # a small sparse matrix: dense arithmetic costs microseconds
    if _exactly_symmetric(A):
        return
    if (not _issparse(A) and A.ndim == 2 and A.shape[0] == A.shape[1] and A.size <= SMALL_DENSE_SIZE
            and bool((A == A.T).all())):
        return                  # small and exactly symmetric: max |A - A^T| = 0 passes the test below
    diff = A - A.T
    if _issparse(diff):
        err = abs(diff).max() if diff.nnz else 0.0
        scale = abs(A).max() if A.nnz else 0.0
    else:
        err = np.max(np.abs(diff)) if diff.size else 0.0
        scale = np.max(np.abs(A)) if A.size else 0.0
    if err > SYMMETRY_RTOL * max(scale, np.finfo(float).tiny):
        raise ValueError(
            f"{name} must be symmetric; max |{name} - {name}^T| = {err:.3g} "
            f"(relative {err / scale:.3g} > {SYMMETRY_RTOL:g})"
        )


def _exactly_symmetric(A) -> bool:
    """Whether ``A`` is large and ``A == A^T`` entry by entry, found cheaply (False: not known; the
    full check of :func:`check_symmetric` decides). Sparse: the transpose's CSR arrays are those of
    ``A``; dense: every nonzero entry equals its mirror (the zeros are skipped)."""
    if A.ndim != 2 or A.shape[0] != A.shape[1] or A.shape[0] * A.shape[1] <= SMALL_DENSE_SIZE:
        return False
    if _issparse(A):
        if A.format != "csr" or not A.has_canonical_format:
            return False                # (a product's unsorted indices: sorting costs as much as the full check)
        At = A.T.tocsr()
        return (np.array_equal(A.indptr, At.indptr) and np.array_equal(A.indices, At.indices)
                and np.array_equal(A.data, At.data))
    flat = np.ravel(A)
    nonzero = flat != 0
    if np.count_nonzero(nonzero) == np.count_nonzero(np.diagonal(A)):
        return True                     # diagonal
    where = nonzero.nonzero()[0]
    rows, cols = np.divmod(where, A.shape[1])
    return bool(np.array_equal(A[cols, rows], flat[where]))


def is_diagonal(A) -> bool:
    """Whether the dense square ``A`` is larger than :data:`SMALL_DENSE_SIZE` entries and diagonal
    (every nonzero entry on the diagonal), as :func:`check_symmetric` and :func:`check_psd` find it;
    False: not known."""
    if _issparse(A) or A.ndim != 2 or A.shape[0] != A.shape[1] or A.size <= SMALL_DENSE_SIZE:
        return False
    return np.count_nonzero(A) == np.count_nonzero(np.diagonal(A))


#: Matrices larger than this are checked block by block (their uncoupled diagonal blocks).
PSD_BLOCKS_MIN_M = 64


def check_psd(name: str, A: np.ndarray, *, strict=False, diagonal=False) -> None:
    """Raise ``ValueError`` if the dense symmetric ``A`` has a negative (or, if strict, zero) eigenvalue.

    The eigenvalues of a block-diagonal matrix are those of its blocks: above
    :data:`PSD_BLOCKS_MIN_M` rows the uncoupled blocks (connected components of the pattern of
    ``A``) are checked one by one, so that a diagonal ``H`` (one soil spring per contact) costs
    O(m), not an O(m^3) eigendecomposition. ``diagonal=True``: ``A`` is known to be diagonal
    (:func:`is_diagonal`).
    """
    if A.size == 0:
        return
    if A.shape[0] > PSD_BLOCKS_MIN_M:
        if diagonal:
            nonzero = None
        else:
            if not strict and not A.any():
                return              # zero: semidefinite
            nonzero = np.ravel(A) != 0                 # the pattern of A != 0
            if np.count_nonzero(nonzero) == np.count_nonzero(np.diagonal(A)):
                nonzero = None                         # diagonal: 1 x 1 blocks
        if nonzero is None:
            eig = np.diag(A).copy()
        else:
            eig = _block_eigenvalues(A, nonzero.nonzero()[0])
        eig.sort()
    else:
        eig = np.linalg.eigvalsh(A)
    scale = max(np.max(np.abs(eig)), np.finfo(float).tiny)
    limit = 1e-12 * scale
    if eig[0] < -limit or (strict and eig[0] <= limit):
        need = "positive definite" if strict else "positive semidefinite"
        raise ValueError(
            f"{name} must be symmetric {need}; its smallest eigenvalue is {eig[0]:.3g} "
            f"(largest {eig[-1]:.3g})"
        )


def _block_eigenvalues(A, where) -> np.ndarray:
    """The eigenvalues of ``A`` (unsorted), those of the uncoupled blocks of its pattern (the flat
    indices ``where`` of its nonzero entries)."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.csgraph import connected_components

    n = A.shape[0]
    pattern = csr_matrix((np.ones(where.size, dtype=bool), np.divmod(where, n)), shape=A.shape)
    count, label = connected_components(pattern, directed=False)
    order = np.argsort(label, kind="stable")
    bounds = np.searchsorted(label[order], np.arange(count + 1))
    single = np.diff(bounds) == 1                      # 1 x 1 blocks: their diagonal entries
    eig = [np.diag(A)[order[bounds[:-1][single]]]]
    for k in np.flatnonzero(~single):
        idx = order[bounds[k]:bounds[k + 1]]
        eig.append(np.linalg.eigvalsh(A[np.ix_(idx, idx)]))
    return np.concatenate(eig)


def positive_float(name: str, value) -> float:
    """``value`` as a float > 0 and finite; strings and booleans are refused, not converted."""
    if isinstance(value, (str, bytes, bool)) or value is None:
        raise TypeError(f"{name} must be a positive number, got {describe(value)}")
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a positive number, got {describe(value)}") from None
    if not np.isfinite(x) or x <= 0:
        raise ValueError(f"{name} must be a positive finite number, got {value!r}")
    return x


def choice(name: str, value, valid) -> str:
    """Validate a case-insensitive name against ``valid`` (an iterable of lower-case names)."""
    valid = sorted(valid)
    if not isinstance(value, str) or value.lower() not in valid:
        names = ", ".join(repr(v) for v in valid)
        raise ValueError(f"{name}={value!r} is not valid; valid names: {names}")
    return value.lower()


def time_function(name: str, value, size: int) -> tuple[Callable[[float], np.ndarray], bool]:
    """Normalise a constant vector or a callable ``f(t) -> (size,)``.

    Returns
    -------
    f : callable
        ``f(t)`` returning a float array of shape ``(size,)``.
    constant : bool
        True if ``value`` was a constant.
    """
    if value is None:
        zero = np.zeros(size)
        return (lambda t: zero), True
    if callable(value):
        def checked(t, _f=value):
            out = np.asarray(_f(t), dtype=float)
            if out.shape != (size,):
                raise ValueError(f"{name}(t) must return shape ({size},), got shape {out.shape} at t={t}")
            check_finite(f"{name}(t={t})", out)
            return out
        return checked, False
    vec = as_vector(name, value, size)
    return (lambda t: vec), True


def _shape_text(shape) -> str:
    return "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"
