"""Fragility functions: lognormal fits by maximum likelihood (Baker 2015).

A fragility function ``P(exceedance | IM = x) = Phi(ln(x / theta) / beta)`` is fitted to the
results of analyses at intensity levels ``x_j``: ``z_j`` of the ``n_j`` analyses at level ``j``
exceed the limit state. The likelihood of the counts is binomial,

    L(theta, beta) = prod_j C(n_j, z_j) p_j^z_j (1 - p_j)^(n_j - z_j),   p_j = Phi(ln(x_j / theta) / beta),

and ``theta`` (the median) and ``beta`` (the dispersion) maximise it (J. W. Baker, "Efficient
analytical fragility function fitting using dynamic structural analysis", Earthquake Spectra 31(1),
2015). For IDA data (the same records at every level) this is the standard estimate for data
censored by the levels. Degenerate data are reported, not hidden: no exceedance at all (or
exceedance everywhere) gives no fit, and perfectly separated data (all below one level, all above
the next) drive ``beta`` to its lower bound.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

BETA_BOUNDS = (0.01, 5.0)


@dataclass
class FragilityFit:
    """A fitted lognormal fragility function and the data behind it."""

    theta: float
    beta: float
    levels: np.ndarray          # intensity levels x_j
    n: np.ndarray               # analyses behind each level (failed analyses excluded)
    z: np.ndarray               # of them exceeding
    note: str = ""

    def __call__(self, x):
        from scipy.special import ndtr

        x = np.asarray(x, dtype=float)
        if not (math.isfinite(self.theta) and math.isfinite(self.beta)):
            return np.full(x.shape, np.nan)
        return ndtr(np.log(x / self.theta) / self.beta)


def fit_fragility(levels, n, z) -> FragilityFit:
    """Maximum-likelihood lognormal fragility (binomial likelihood over the levels).

    Parameters
    ----------
    levels : (J,) array_like
        Intensity levels, > 0.
    n, z : (J,) array_like of int
        Analyses at each level and how many of them exceed the limit state.
    """
    from scipy.optimize import minimize
    from scipy.special import gammaln, ndtr, xlog1py, xlogy

    x = np.asarray(levels, dtype=float)
    n = np.asarray(n, dtype=int)
    z = np.asarray(z, dtype=int)
    keep = (n > 0) & (x > 0)
    x, n, z = x[keep], n[keep], z[keep]
    if x.size == 0:
        return FragilityFit(math.nan, math.nan, x, n, z, "no analyses")
    if z.sum() == 0:
        return FragilityFit(math.nan, math.nan, x, n, z, "never exceeded: no fit (theta above the levels)")
    if (z == n).all():
        return FragilityFit(math.nan, math.nan, x, n, z, "always exceeded: no fit (theta below the levels)")
    lx = np.log(x)

    log_choose = gammaln(n + 1) - gammaln(z + 1) - gammaln(n - z + 1)

    def nll(p):                                  # minus the log of the binomial likelihood
        prob = ndtr((lx - p[0]) / p[1])
        prob = np.clip(prob, 1e-300, 1 - 1e-16)
        return -np.sum(log_choose + xlogy(z, prob) + xlog1py(n - z, -prob))

    # start: the mean and spread of ln x weighted by the exceedance increments
    frac = z / n
    start = [float(np.interp(0.5, np.maximum.accumulate(frac), lx)) if frac.max() >= 0.5 else lx.max(), 0.4]
    bounds = [(lx.min() - 5.0, lx.max() + 5.0), BETA_BOUNDS]
    best = None
    for beta0 in (0.2, 0.4, 0.8):
        res = minimize(nll, [start[0], beta0], method="L-BFGS-B", bounds=bounds)
        if best is None or res.fun < best.fun:
            best = res
    theta, beta = math.exp(best.x[0]), float(best.x[1])
    note = ""
    if beta <= BETA_BOUNDS[0] * 1.0001:
        note = f"perfectly separated data: beta at its lower bound {BETA_BOUNDS[0]}"
    elif beta >= BETA_BOUNDS[1] * 0.9999:
        note = f"beta at its upper bound {BETA_BOUNDS[1]}"
    return FragilityFit(theta, beta, x, n, z, note)
