"""Common interface of the LCP solvers: result type, error measure, registry.

The linear complementarity problem LCP(W, q) is: given ``W`` (m, m) and
``q`` (m,), find ``v`` (m,) with::

    v >= 0,    w = W v + q >= 0,    v . w = 0.

Every solver derives from :class:`LCPSolver` and implements ``_solve``; the
base class validates the input, handles the trivial case ``q >= 0``
(``v = 0`` exactly, ``w = q`` exactly), cleans the returned ``v`` and
measures the error honestly, so all solvers report results the same way.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np
import scipy.linalg.lapack

#: Below this size W is not checked for symmetry (the check costs more than
#: Cholesky saves over LU) and principal systems are solved by LU.
CHOLESKY_MIN_SIZE = 16

#: Registry of the solvers by name, filled by :meth:`LCPSolver.__init_subclass__`.
LCP_SOLVERS: dict[str, type[LCPSolver]] = {}


@dataclass
class LCPResult:
    """Solution of an LCP as returned by every solver.

    Attributes
    ----------
    v : ndarray, shape (m,)
        The unknown, ``v >= 0`` (tiny negative round-off is clipped to 0).
    w : ndarray, shape (m,)
        ``W v + q``, recomputed from the returned ``v``.
    active : ndarray of bool, shape (m,)
        True where ``v`` is basic (pivoting solvers: the final complementary
        basis) or positive (iterative solvers); usable as the warm start
        ``active`` of the next solve.
    iterations : int
        Pivots (Lemke), linear solves (block principal pivoting),
        sweeps (projected Gauss-Seidel), Newton iterations (semismooth
        Newton) or principal subsets tried (enumeration). 0 if ``q >= 0``.
    error : float
        ``lcp_error(v, w, q)``.
    success : bool
        True iff the method terminated normally and ``error <= tol``.
    message : str
        What happened; on failure, what went wrong and what to try.
    fallback : bool
        The step solver of a law with faces (:class:`~unilateral.lcp.faces.FaceSetPivoting`)
        solved it by its fallback, Lemke's method, block principal pivoting having failed.
    """

    v: np.ndarray
    w: np.ndarray
    active: np.ndarray
    iterations: int
    error: float
    success: bool
    message: str
    fallback: bool = False


class SolverOutcome(NamedTuple):
    """What a solver's ``_solve`` hands back to :meth:`LCPSolver.solve`.

    Attributes
    ----------
    v : ndarray, shape (m,)
        Raw solution candidate (may be owned and modified by the caller).
    active : ndarray of bool, shape (m,)
        Basic / positive set belonging to ``v``.
    iterations : int
        Work counter, see :attr:`LCPResult.iterations`.
    terminated : bool
        True if the method stopped normally (solution found), False on a
        breakdown (ray, iteration limit, failed line search, ...).
    message : str
        Description of the outcome; on breakdown, the advice to the user.
    """

    v: np.ndarray
    active: np.ndarray
    iterations: int
    terminated: bool
    message: str


def lcp_error(v, w, q) -> float:
    """Scaled natural-map residual of an LCP candidate.

    ``||v - max(0, v - w)||_2 / (1 + ||q||_2)``, evaluated as the identical
    but cancellation-free ``||min(v, w)||_2 / (1 + ||q||_2)``. It is zero iff
    ``(v, w)`` solves the LCP.

    Parameters
    ----------
    v, w, q : array_like, shape (m,)
        Candidate, ``W v + q`` and the LCP vector.

    Returns
    -------
    float
    """
    r = np.minimum(v, w)
    q = np.asarray(q, dtype=float)
    return math.sqrt(r @ r) / (1.0 + math.sqrt(q @ q))


def solve_linear(A, b, symmetric=False):
    """Solve the square system ``A x = b`` accurately and with little overhead.

    Calls LAPACK directly (``numpy.linalg.solve`` costs several times more
    for small systems): Cholesky (``dposv``) if ``symmetric`` and it
    succeeds, else LU with partial pivoting (``dgesv``). A singular ``A``
    (possible when W is only positive semidefinite) gets the minimum-norm
    least-squares solution, which solves the system whenever it is
    consistent.

    Parameters
    ----------
    A : ndarray, shape (n, n), n >= 1
    b : ndarray, shape (n,)
    symmetric : bool, default False
        ``A`` is known to be symmetric, so Cholesky is worth trying.

    Returns
    -------
    ndarray, shape (n,)
    """
    if symmetric:
        x, info = scipy.linalg.lapack.dposv(A, b)[1:]
        if info == 0:
            return x
    x, info = scipy.linalg.lapack.dgesv(A, b)[2:]
    if info == 0:
        return x
    return np.linalg.lstsq(A, b, rcond=None)[0]


class PrincipalSystems:
    """Complementary solutions of one LCP for varying active sets.

    For an active set ``F``, ``v_F = -W_FF^-1 q_F`` and ``v = 0`` (exactly)
    elsewhere, so that ``w_F = (W v + q)_F = 0`` up to round-off. Symmetry of
    ``W`` is checked once (for ``m >= CHOLESKY_MIN_SIZE``) so that the
    principal submatrices are factorized by Cholesky when possible.

    Parameters
    ----------
    W : ndarray, shape (m, m)
    q : ndarray, shape (m,)
    """

    def __init__(self, W, q):
        self.W = W
        self.q = q
        self.symmetric = q.size >= CHOLESKY_MIN_SIZE and np.array_equal(W, W.T)

    def solve(self, active):
        """Complementary solution for ``active``.

        Parameters
        ----------
        active : ndarray of bool, shape (m,)

        Returns
        -------
        v : ndarray, shape (m,)
        """
        v = np.zeros(self.q.size)
        idx = active.nonzero()[0]
        if idx.size:
            v[idx] = solve_linear(self.W[idx[:, None], idx], -self.q[idx], self.symmetric)
        return v

    def start(self, active):
        """Nonnegative starting point for iterative solvers.

        Parameters
        ----------
        active : ndarray of bool, shape (m,), or None
            Warm start.

        Returns
        -------
        v : ndarray, shape (m,)
            ``max(0, solve(active))``, or zeros without a warm start.
        """
        return np.zeros(self.q.size) if active is None else np.maximum(self.solve(active), 0.0)


def check_lcp(W, q, active=None):
    """Validate and convert an LCP.

    Parameters
    ----------
    W : array_like, shape (m, m)
    q : array_like, shape (m,)
    active : array_like of bool, shape (m,), optional

    Returns
    -------
    W : ndarray of float, shape (m, m)
    q : ndarray of float, shape (m,)
    active : ndarray of bool, shape (m,), or None

    Raises
    ------
    ValueError
        If ``W`` is not square, ``q`` or ``active`` do not match it, or
        ``W`` / ``q`` contain NaN or inf; the message names the argument.
    """
    W = np.asarray(W, dtype=float)
    q = np.asarray(q, dtype=float)
    if W.ndim != 2 or W.shape[0] != W.shape[1]:
        raise ValueError(f"W must be a square 2-D array, got shape {W.shape}")
    m = W.shape[0]
    if q.shape != (m,):
        raise ValueError(f"q must have shape ({m},) to match W {W.shape}, got shape {q.shape}")
    for name, a in (("W", W), ("q", q)):
        finite = np.isfinite(a)
        if not finite.all():
            bad = tuple(int(i) for i in np.argwhere(~finite)[0])
            raise ValueError(f"{name} must be finite, got {name}[{', '.join(map(str, bad))}] = {a[bad]}")
    if active is not None:
        active = np.asarray(active)
        if active.shape != (m,) or active.dtype != bool:
            raise ValueError(
                f"active must be a boolean array of shape ({m},), "
                f"got dtype {active.dtype} and shape {active.shape}"
            )
    return W, q, active


class LCPSolver(ABC):
    """Base class of the LCP solvers.

    Subclasses set ``name`` (which registers them in ``LCP_SOLVERS``) and
    implement ``_solve``.

    Parameters
    ----------
    tol : float, default 1e-10
        Success threshold on :func:`lcp_error`.
    max_iter : int, optional
        Iteration limit (in the solver's own unit, see
        :attr:`LCPResult.iterations`); None uses the solver's default for the
        problem size.
    """

    name: ClassVar[str]
    #: Largest problem size the method accepts (None: unlimited).
    max_size: ClassVar[int | None] = None
    #: The method needs a symmetric ``W`` (friction makes the step LCP nonsymmetric).
    symmetric_only: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "name" in cls.__dict__:
            LCP_SOLVERS[cls.name] = cls

    def __init__(self, *, tol: float = 1e-10, max_iter: int | None = None):
        if not tol > 0:
            raise ValueError(f"tol must be positive, got tol={tol!r}")
        if max_iter is not None and (int(max_iter) != max_iter or max_iter < 1):
            raise ValueError(f"max_iter must be a positive integer or None, got max_iter={max_iter!r}")
        self.tol = float(tol)
        self.max_iter = None if max_iter is None else int(max_iter)

    def __repr__(self):
        options = ", ".join(f"{key}={value!r}" for key, value in vars(self).items())
        return f"{type(self).__name__}({options})"

    def solve(self, W, q, active=None) -> LCPResult:
        """Solve LCP(W, q).

        Parameters
        ----------
        W : array_like, shape (m, m)
            LCP matrix (see the solver class for what it must satisfy).
        q : array_like, shape (m,)
            LCP vector.
        active : array_like of bool, shape (m,), optional
            Warm start, e.g. the previous time step's ``result.active``.
            Solvers that cannot use it ignore it.

        Returns
        -------
        LCPResult
            Never raises on non-convergence: check ``success``.

        Raises
        ------
        ValueError
            On malformed input (see :func:`check_lcp`) or ``m`` above the
            solver's ``max_size``.
        """
        W, q, active = check_lcp(W, q, active)
        m = q.size
        if self.max_size is not None and m > self.max_size:
            raise ValueError(
                f"m={m} is too large for {type(self).__name__} (limit m <= {self.max_size}); "
                "use solver='bpp' or 'lemke'"
            )
        if m == 0 or q.min() >= 0.0:
            return LCPResult(np.zeros(m), q.copy(), np.zeros(m, dtype=bool), 0, 0.0, True,
                             "q >= 0: v = 0 is the solution")
        out = self._solve(W, q, active)
        v = out.v
        negative = v < 0.0
        if negative.any():
            v[negative & (v >= -self.tol * (1.0 + math.sqrt(q @ q)))] = 0.0
        w = W @ v + q
        error = lcp_error(v, w, q)
        success = out.terminated and error <= self.tol
        message = out.message
        if out.terminated and not success:
            message = (
                f"{message}, but the error {error:.2e} exceeds tol {self.tol:.1e}: the problem is "
                "ill-conditioned or degenerate at this tolerance, or W is outside the class the "
                "solver handles (solver='lemke' handles positive semidefinite W); rescale W and q, "
                "loosen tol, or try another solver"
            )
        return LCPResult(v, w, out.active, out.iterations, error, success, message)

    __call__ = solve

    def iteration_limit(self, m: int) -> int:
        """``max_iter`` if given, else the solver's default for size ``m``."""
        return self.max_iter if self.max_iter is not None else self.default_max_iter(m)

    @abstractmethod
    def default_max_iter(self, m: int) -> int:
        """Default iteration limit for an LCP of size ``m``."""

    @abstractmethod
    def _solve(self, W, q, active) -> SolverOutcome:
        """Solve a validated, non-trivial LCP (``m >= 1``, ``min(q) < 0``).

        Parameters
        ----------
        W : ndarray of float, shape (m, m)
        q : ndarray of float, shape (m,)
        active : ndarray of bool, shape (m,), or None
            Warm start.

        Returns
        -------
        SolverOutcome
        """


def get_lcp_solver(spec="bpp", **options) -> LCPSolver:
    """Build (or pass through) an LCP solver.

    Parameters
    ----------
    spec : str or LCPSolver, default "bpp"
        A name from ``LCP_SOLVERS`` (case-insensitive), or a solver instance,
        which is returned as is.
    **options
        Keyword arguments of the solver class (``tol``, ``max_iter``, ...);
        must be empty when ``spec`` is an instance.

    Returns
    -------
    LCPSolver

    Raises
    ------
    ValueError
        Unknown name.
    TypeError
        ``spec`` of the wrong type, options with an instance, or options the
        solver does not accept.
    """
    if isinstance(spec, LCPSolver):
        if options:
            raise TypeError(
                f"lcp={spec!r} is already a solver instance; options {sorted(options)} cannot be "
                "applied to it: configure the instance, or pass a solver name with the options"
            )
        return spec
    valid = ", ".join(repr(name) for name in sorted(LCP_SOLVERS))
    if not isinstance(spec, str):
        raise TypeError(f"lcp must be a solver name ({valid}) or an LCPSolver instance, got {spec!r}")
    cls = LCP_SOLVERS.get(spec.lower())
    if cls is None:
        raise ValueError(
            f"lcp={spec!r} is not a known LCP solver; valid names: {valid}, or pass an LCPSolver instance"
        )
    return cls(**options)


def solve_lcp(W, q, solver="bpp", *, active=None, **options) -> LCPResult:
    """Solve LCP(W, q) in one call.

    Parameters
    ----------
    W : array_like, shape (m, m)
    q : array_like, shape (m,)
    solver : str or LCPSolver, default "bpp"
        See :func:`get_lcp_solver`.
    active : array_like of bool, shape (m,), optional
        Warm start (ignored by solvers that cannot use it).
    **options
        Solver options, see :func:`get_lcp_solver`.

    Returns
    -------
    LCPResult

    Raises
    ------
    ValueError
        Malformed ``W``, ``q`` or ``active`` (the message names it), unknown
        solver name.
    """
    return get_lcp_solver(solver, **options).solve(W, q, active)
