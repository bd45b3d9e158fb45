"""LCP statistics of a march, step by step, and its first failure."""

from __future__ import annotations

import numpy as np


class StepLog:
    """LCP statistics over a march, and the first failure."""

    def __init__(self, m: int, active0: np.ndarray):
        self.iterations = 0
        self.max_iterations = 0
        self.max_error = 0.0
        self.contact_changes = 0
        self.fallbacks = 0
        self.active = active0.copy()
        self.failure = ""

    def record(self, k: int, t: float, res) -> bool:
        """Account for the LCP of step k; return False (and keep a message) on failure."""
        self.iterations += res.iterations
        self.max_iterations = max(self.max_iterations, res.iterations)
        self.max_error = max(self.max_error, res.error)
        self.fallbacks += int(getattr(res, "fallback", False))
        active = res.v > 0
        self.contact_changes += int(np.count_nonzero(active != self.active))
        self.active = active
        if not res.success:
            self.failure = f"the LCP of step {k} (t = {t:.6g}) failed: {res.message}"
            return False
        return True

    @classmethod
    def of_compiled(cls, v_b, stats, failed: int, *, dt: float, max_iter: int, tol: float) -> StepLog:
        """The log of a compiled march: its ``stats`` (iterations, largest count, contact changes,
        largest LCP error and, if given, the steps solved by the fallback of
        :func:`~unilateral.lcp.pivoting.solve_step`) and the step that ``failed`` (0: none)."""
        log = cls(v_b.shape[0], v_b > 0)
        log.iterations, log.max_iterations = int(stats[0]), int(stats[1])
        log.contact_changes, log.max_error = int(stats[2]), float(stats[3])
        log.fallbacks = int(stats[4]) if stats.shape[0] > 4 else 0
        if failed:
            log.failure = (
                f"the LCP of step {failed} (t = {failed * dt:.6g}) failed: block principal pivoting "
                f"found a principal submatrix of W0 that is not positive definite, did not converge in "
                f"{max_iter} solves, or left an LCP error above tol = {tol:g} (with pairs or polygons of "
                "facets, Lemke's method failed on it too); try lcp='lemke'")
        return log

    def stats(self) -> dict:
        return {"lcp_iterations": self.iterations, "lcp_max_iterations": self.max_iterations,
                "max_lcp_error": self.max_error, "contact_changes": self.contact_changes,
                "lcp_fallbacks": self.fallbacks}
