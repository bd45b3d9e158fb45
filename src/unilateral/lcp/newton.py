"""Semismooth Newton method on an NCP function, with active-set polishing."""

from __future__ import annotations

import math

import numpy as np

from .base import LCPSolver, PrincipalSystems, SolverOutcome, lcp_error, solve_linear

#: Armijo sufficient-decrease constant.
ARMIJO = 1e-4
#: Maximum number of step halvings in the line search.
MAX_HALVINGS = 40
#: The Newton direction d is replaced by the steepest descent direction
#: unless grad . d <= -DESCENT_RHO ||d||^DESCENT_POWER
#: (De Luca, Facchinei & Kanzow, Math Program 75, 1996).
DESCENT_RHO = 1e-8
DESCENT_POWER = 2.1
#: Derivative of the Fischer-Burmeister function at its kink (0, 0): an
#: element (xi - 1, rho - 1) of the generalized gradient with xi = rho.
FB_KINK = 1.0 / math.sqrt(2.0) - 1.0


def _fb_residual(v, w):
    """Fischer-Burmeister function ``sqrt(v^2 + w^2) - v - w``, componentwise."""
    return np.hypot(v, w) - v - w


def _fb_jacobian(v, w, W):
    """An element of the generalized Jacobian of ``v -> phi_FB(v, W v + q)``."""
    r = np.hypot(v, w)
    kink = r == 0.0
    r[kink] = 1.0
    dv = v / r - 1.0
    dw = w / r - 1.0
    dv[kink] = dw[kink] = FB_KINK
    J = dw[:, None] * W
    J.reshape(-1)[:: v.size + 1] += dv  # the diagonal, as a view
    return J


def _min_residual(v, w):
    """Natural map ``min(v, w)``, componentwise."""
    return np.minimum(v, w)


def _min_jacobian(v, w, W):
    """An element of the generalized Jacobian of ``v -> min(v, W v + q)``.

    Ties ``v_i = w_i`` take the ``v`` branch (row ``e_i``).
    """
    J = W.copy()
    rows = (v <= w).nonzero()[0]
    J[rows] = 0.0
    J[rows, rows] = 1.0
    return J


MERITS = {"fb": (_fb_residual, _fb_jacobian), "min": (_min_residual, _min_jacobian)}


class SemismoothNewton(LCPSolver):
    """Globalized semismooth Newton method.

    Solves ``phi(v, W v + q) = 0`` for the NCP function ``phi``
    (Fischer-Burmeister or min) with generalized Newton steps, an Armijo
    line search on the merit ``0.5 ||phi||^2`` and a steepest-descent
    fallback when the Newton direction is not a good descent direction.
    Polishing: before every iteration the active set ``{v_i > w_i}`` of the
    current iterate is identified (unless unchanged since the last try) and
    its complementary solution (one linear solve, cheaper than a Newton
    step) is accepted if its error is ``<= tol``. The result is then accurate
    to round-off, with ``v`` exactly 0 off the active set, and the method
    usually stops as soon as the active set is identified, before the Newton
    iterates themselves converge.

    Requirements: with ``merit="fb"`` the method converges for P-matrices
    (symmetric positive definite or not); for P0-matrices such as merely
    positive semidefinite ``W`` every stationary point of the merit solves the
    LCP, which usually suffices, but the iterates may fail to converge (use
    ``solver='lemke'``). With ``merit="min"`` the Newton step is a primal-dual
    active-set step: fast for symmetric positive definite ``W`` but without a
    global convergence guarantee.

    ``iterations`` counts Newton iterations. A warm start ``active`` starts
    from ``max(0, v_F)`` on that set (an exact active set needs 0 iterations).

    Parameters
    ----------
    tol : float, default 1e-10
        Success threshold on the LCP error.
    max_iter : int, optional
        Newton iteration limit; default 100.
    merit : {"fb", "min"}, default "fb"
        NCP function: Fischer-Burmeister or the natural (min) map.
    """

    name = "newton"

    def __init__(self, *, tol=1e-10, max_iter=None, merit="fb"):
        super().__init__(tol=tol, max_iter=max_iter)
        if merit not in MERITS:
            raise ValueError(f"merit={merit!r} is not valid; use 'fb' (Fischer-Burmeister) or 'min'")
        self.merit = merit

    def default_max_iter(self, m):
        return 100

    def _solve(self, W, q, active):
        m = q.size
        residual, jacobian = MERITS[self.merit]
        systems = PrincipalSystems(W, q)
        v = systems.start(active)
        w = W @ v + q
        phi = residual(v, w)
        psi = 0.5 * (phi @ phi)
        tried = None
        max_iter = self.iteration_limit(m)
        for it in range(max_iter + 1):
            candidate = v > w
            if tried is None or not np.array_equal(candidate, tried):
                tried = candidate
                polished = systems.solve(candidate)
                if lcp_error(polished, W @ polished + q, q) <= self.tol:
                    return SolverOutcome(polished, candidate, it, True,
                                         f"semismooth Newton ({self.merit}): solved in {it} iterations")
            error = lcp_error(v, w, q)
            if error <= self.tol:
                return SolverOutcome(v, v > 0.0, it, True,
                                     f"semismooth Newton ({self.merit}): converged in {it} iterations")
            if it == max_iter:
                break
            J = jacobian(v, w, W)
            gradient = J.T @ phi
            d = solve_linear(J, -phi)
            slope = gradient @ d
            if not slope <= -DESCENT_RHO * (d @ d) ** (0.5 * DESCENT_POWER):
                d = -gradient
                slope = -(gradient @ gradient)
            t = 1.0  # Armijo backtracking; no descent direction (slope >= 0) fails at once
            for _ in range(MAX_HALVINGS if slope < 0.0 else 0):
                v_trial = v + t * d
                w_trial = W @ v_trial + q
                phi_trial = residual(v_trial, w_trial)
                psi_trial = 0.5 * (phi_trial @ phi_trial)
                if psi_trial <= psi + ARMIJO * t * slope:
                    break
                t *= 0.5
            else:
                return SolverOutcome(
                    v, v > 0.0, it, False,
                    f"semismooth Newton ({self.merit}) line search failed at iteration {it} (error "
                    f"{error:.1e}): the iterate is near a stationary point of the merit function that "
                    "is not a solution; W may not be a P0-matrix: try solver='lemke'",
                )
            v, w, phi, psi = v_trial, w_trial, phi_trial, psi_trial
        return SolverOutcome(
            v, v > 0.0, max_iter, False,
            f"semismooth Newton ({self.merit}) did not converge in {max_iter} iterations (error "
            f"{error:.1e} > tol {self.tol:.1e}); use solver='bpp' or 'lemke', or raise max_iter",
        )
