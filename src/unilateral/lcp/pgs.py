"""Projected Gauss-Seidel (projected SOR) iteration."""

from __future__ import annotations

import numpy as np

from .base import LCPSolver, PrincipalSystems, SolverOutcome, lcp_error


class ProjectedGaussSeidel(LCPSolver):
    """Projected Gauss-Seidel / projected SOR.

    One sweep updates, for ``i = 0 .. m-1`` in turn,
    ``v_i <- max(0, v_i - omega (W_i . v + q_i) / W_ii)``. The error is
    checked before every sweep; the method stops when it is ``<= tol``.
    Convergence is linear, so this is the slowest solver for tight
    tolerances; it is simple and robust for well-conditioned problems.

    Requirements: positive diagonal (checked; otherwise ``success=False``).
    Convergence is guaranteed for symmetric positive semidefinite ``W`` with
    positive diagonal (and a solvable LCP) and ``0 < omega < 2``, and for
    diagonally dominant ``W``; other P-matrices may diverge.

    ``iterations`` counts sweeps. A warm start ``active`` initializes
    ``v = max(0, v_F)`` from the complementary solution on that set (one
    linear solve), so the exact active set converges in 0 sweeps.

    Parameters
    ----------
    tol : float, default 1e-10
        Stopping and success threshold on the LCP error.
    max_iter : int, optional
        Sweep limit; default 10000.
    omega : float, default 1.0
        Relaxation factor in (0, 2); 1 is Gauss-Seidel, > 1 over-relaxation.
    """

    name = "pgs"
    symmetric_only = True

    def __init__(self, *, tol=1e-10, max_iter=None, omega=1.0):
        super().__init__(tol=tol, max_iter=max_iter)
        if not 0.0 < omega < 2.0:
            raise ValueError(f"omega must lie in (0, 2), got omega={omega!r}")
        self.omega = float(omega)

    def default_max_iter(self, m):
        return 10000

    def _solve(self, W, q, active):
        m = q.size
        diagonal = W.diagonal()
        if not (diagonal > 0.0).all():
            i = int(np.argmin(diagonal > 0.0))
            return SolverOutcome(
                np.zeros(m), np.zeros(m, dtype=bool), 0, False,
                f"PGS needs a positive diagonal, but W[{i}, {i}] = {diagonal[i]:.3g}; use solver='lemke'",
            )
        v = PrincipalSystems(W, q).start(active)
        rows = list(W)
        steps = (self.omega / diagonal).tolist()
        offsets = q.tolist()
        max_iter = self.iteration_limit(m)
        with np.errstate(over="ignore", invalid="ignore"):  # divergence is detected and reported
            for sweep in range(max_iter + 1):
                error = lcp_error(v, W @ v + q, q)
                if error <= self.tol:
                    return SolverOutcome(v, v > 0.0, sweep, True, f"PGS: converged in {sweep} sweeps")
                if not np.isfinite(error):
                    return SolverOutcome(
                        np.zeros(m), np.zeros(m, dtype=bool), sweep, False,
                        f"PGS diverged after {sweep} sweeps (returning v = 0); it needs W symmetric "
                        "positive semidefinite or diagonally dominant: use solver='bpp' or 'lemke'",
                    )
                if sweep == max_iter:
                    break
                for i in range(m):
                    vi = v[i] - steps[i] * (rows[i] @ v + offsets[i])
                    v[i] = vi if vi > 0.0 else 0.0
        return SolverOutcome(
            v, v > 0.0, max_iter, False,
            f"PGS did not converge in {max_iter} sweeps (error {error:.1e} > tol {self.tol:.1e}); "
            "use solver='bpp' or 'lemke', or raise max_iter",
        )
