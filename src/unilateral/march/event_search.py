"""The search for the next event of the exact event march (:mod:`unilateral.march.event`).

Between decisions a configuration's event functions ``e = E Y(t)`` are scanned on a sub-grid that
resolves its fastest oscillation; where the modal bound of the configuration proves that no event
function crosses zero between two samples of a sparse grid, the samples in between are not
evaluated (the module docstring of :mod:`unilateral.march.event`, "Sparse sampling"). The first
sub-interval found is the one the full sub-grid finds, and :meth:`EventSearch._locate` finds the
root in it by :func:`find_root`.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.linalg as sla

#: Round-off of an output ``E Y``: this many ulps of ``|E| |Y|`` count as zero.
NOISE_ULPS = 256
ROUNDOFF = NOISE_ULPS * np.finfo(float).eps
#: A configuration whose modes grow by more than ``exp`` of this over a stretch is sampled finely.
MAX_GROWTH = 30.0
#: Where the bounds of the sparse sampling do not clear an interval, it is split in about four
#: until blocks of at most this many fine sub-intervals, which are evaluated in full.
FINE_BLOCK = 16
#: Fewer sub-intervals than this per stretch are evaluated in full (no sparse sampling).
SPARSE_MIN = 8
#: Where the full sub-grid is evaluated (no sparse sampling), it is in chunks of at most this many
#: sub-intervals (the powers of the step are kept: a (J, NY, NY) array for a long output step).
FINE_CHUNK = 1024


class EventSearch:
    """The scan of :class:`~unilateral.march.event._March` for its next event (a mixin: it uses the
    march's ``plan``, ``gen``, ``grid``, ``m``, ``tol`` and ``substeps``)."""

    def _scan(self, cfg, Y, t, J, h):
        """Look for the first sub-interval of the grid ``t + j h`` (j = 1..J) at whose end an event
        function is above zero.

        Returns ``(Y(t + J h), None)`` if there is none, else ``(Y(t + J h), (j, Y_left, Ys, es,
        j_local))``: ``j`` the index of the first sub-interval with an event function over zero
        at its end, ``Ys`` (k, NY) and ``es`` (k, m) the states and event functions at the ends of
        the sub-intervals of a stretch that starts at ``Y_left`` and contains it, ``j_local`` its
        index there (the arguments of :meth:`_locate`).

        The sub-grid resolves the fastest oscillation of the configuration (``cfg.hmax``), but it is
        only evaluated where needed: on a sparse grid of every ``r``-th point (:meth:`_plan`), an
        interval between two sparse points is passed over when the bound of the plan proves that no
        event function is over zero at any point of the fine grid inside it, so the sub-interval
        found is the one the fine grid alone finds. The fine grid is evaluated in the other
        intervals.
        """
        plan = self._plan_for(cfg, Y, t, J, h)
        if plan is None:                                         # the full sub-grid, in chunks
            a, Ya = 0, Y
            while True:
                n = min(FINE_CHUNK, J - a)
                Ys = cfg.powers(h, n) @ Ya                        # (n, NY)
                self.substeps += n
                es = Ys @ cfg.E.T                                 # (n, m)
                over = es > np.maximum(cfg.zero, _noise(cfg.absE, Ys))
                if over.any():
                    j = int(np.argmax(over.any(axis=1)))
                    Y_end = Ys[-1] if a + n == J else cfg.propagator((J - a - n) * h) @ Ys[-1]
                    return Y_end, (a + j, Ya, Ys, es, j)
                if a + n == J:
                    return Ys[-1], None
                a, Ya = a + n, Ys[-1]
        r = plan[4]
        if r >= J:                                               # the usual case: one interval
            Y_end = cfg.propagator(J * h) @ Y
            self.substeps += 1
            high = (np.maximum(cfg.E @ Y, cfg.E @ Y_end) + _slack(plan, J * h)
                    + ROUNDOFF * (cfg.absE @ (np.abs(Y) + np.abs(Y_end))))
            if np.all(high <= cfg.zero):
                return Y_end, None
            return Y_end, self._search(cfg, Y, 0, J, h, _split_width(J), plan)
        Yc, hit = self._sparse(cfg, Y, 0, J, h, r, plan)
        return Yc[-1], hit

    def _sparse(self, cfg, Y, a, n, h, r, plan):
        """Sample fine sub-intervals ``a + 1 .. a + n`` (from ``Y`` at ``a``) every ``r``-th; search
        the intervals that the plan's bound does not clear. ``(states at the samples, hit)``."""
        Q, rest = divmod(n, r)
        Yc = cfg.powers(r * h, Q) @ Y                             # (Q, NY) at r h, 2 r h, ...
        if rest:
            Yc = np.vstack([Yc, cfg.propagator(rest * h) @ Yc[-1]])
        self.substeps += Yc.shape[0]
        ends = np.minimum(r * np.arange(1, Yc.shape[0] + 1), n)   # fine index of each sample
        starts = np.concatenate([[0], ends[:-1]])
        Yl = np.vstack([Y, Yc[:-1]])
        slack = np.vstack([_slack(plan, r * h)] * Q + ([_slack(plan, rest * h)] if rest else []))
        # noise: the round-off of E Y at both ends (as the fine grid's threshold)
        high = (np.maximum(Yl @ cfg.E.T, Yc @ cfg.E.T) + slack
                + ROUNDOFF * (np.abs(Yl) + np.abs(Yc)) @ cfg.absE.T)
        for q in np.flatnonzero((high > cfg.zero).any(axis=1)):
            width = int(ends[q] - starts[q])
            hit = self._search(cfg, Yl[q], a + int(starts[q]), width, h, _split_width(width), plan)
            if hit is not None:
                return Yc, hit
        return Yc, None

    def _search(self, cfg, Y, a, n, h, r, plan):
        """The first of the fine sub-intervals ``a + 1 .. a + n`` (from ``Y`` at ``a``) with an event
        function over zero at its end, as :meth:`_scan` returns it, or None: sampled every ``r``-th
        (:meth:`_sparse`) down to blocks of at most :data:`FINE_BLOCK` evaluated in full."""
        if r > 1:
            return self._sparse(cfg, Y, a, n, h, r, plan)[1]
        Ys = cfg.powers(h, n) @ Y
        self.substeps += n
        es = Ys @ cfg.E.T
        over = es > np.maximum(cfg.zero, _noise(cfg.absE, Ys))
        if not over.any():
            return None
        jl = int(np.argmax(over.any(axis=1)))
        return a + jl, Y, Ys, es, jl

    def _plan_for(self, cfg, Y, t, J, h):
        """The plan of :meth:`_scan` at ``t``: the last one if it holds (same configuration, no
        decision since, same sub-grid, ``t + J h`` before its horizon), else a new one
        (:meth:`_plan`). None: the fine grid everywhere."""
        plan = self.plan
        if plan is not None and plan[0] is cfg and plan[1] == (J, h) and t + J * h <= plan[2]:
            return plan if plan[4] > 1 else None
        self.plan = plan = self._plan(cfg, Y, t, J, h)
        return plan if plan[4] > 1 else None

    def _plan(self, cfg, Y, t, J, h):
        """``(cfg, (J, h), horizon, t, r, 2 B, D / 8, slacks)``: every ``r``-th point of the fine grid
        ``j h`` makes the sparse grid of :meth:`_scan`, and ``2 B``, ``D`` (m, cuts) bound the event
        functions between two sparse points ``a``, ``b`` (:func:`_slack`), from ``Y`` at ``t`` until
        the ``horizon`` (the next load breakpoint, the end of the grid) as long as no decision
        changes the state (:meth:`_bounds`).

        By the modal split of the configuration (:class:`~unilateral.march.event_config.Spectral`)
        each event function is ``e_i = s_i + f_i`` with ``f_i`` the share of the modes faster than a
        cut: ``|f_i| <= B_i`` and ``|s_i''| <= D_i`` until the horizon (no new excitation of the
        modes: the solution is exactly the sum of the modes and the load generator's share), so
        that ``e_i <= max(e_i(a), e_i(b)) + 2 B_i + (b - a)^2 D_i / 8`` between sparse points. ``B``
        includes the round-off of the modal split. The cut and ``r`` (a power of 2, or ``J``) are
        chosen so that the bound leaves at least half of the distance to zero of the event
        functions that are not already close to it; ``r = 1`` (the fine grid everywhere) when the
        split is not available or does not pay.
        """
        bps = self.gen.breakpoints
        k = int(np.searchsorted(bps, t, side="right"))
        horizon = min(float(bps[k]) if k < bps.size else np.inf, float(self.grid[-1]))
        horizon = max(horizon, t + J * h)
        fine = (cfg, (J, h), horizon, t, 1, None, None, None)
        sp = cfg.spectral() if J >= SPARSE_MIN else None
        if sp is None:
            return fine
        bounds = self._bounds(cfg, sp, Y, horizon - t)
        if bounds is None:
            return fine
        twice_fast, curv8 = bounds
        budget = -0.5 * (cfg.E @ Y)[:, None] - twice_fast - cfg.zero[:, None]
        positive = budget > 0
        # r^2 <= budget / (h^2 D / 8), capped at J^2 (and no division by zero)
        denominator = np.maximum(np.maximum(h * h * curv8, np.abs(budget) / (J * J)), np.finfo(float).tiny)
        rmax = np.sqrt(np.where(positive, budget / denominator, 0.0))
        usable = positive.any(axis=1)
        if not usable.any():
            return fine
        rcut = rmax[usable].min(axis=0)
        p = int(np.argmax(rcut))
        r = float(rcut[p])
        if not r >= max(2.0, J / FINE_CHUNK):                    # not worth it (or too many samples)
            return fine
        r = J if r >= J else 2 ** int(math.floor(math.log2(r)))
        return (cfg, (J, h), horizon, t, r, twice_fast, curv8, {})

    def _bounds(self, cfg, sp, Y, L):
        """``(2 B, D / 8)`` (m, ny + 1): for each cut ``p`` (the modes ``p..`` of ``sp`` fast), bounds of
        the fast share ``|f_i| <= B_i`` (with the round-off of the split) and of ``|s_i''| <= D_i``,
        over ``[0, L]`` from ``Y`` (see :meth:`_plan`); None if a mode grows too much or a bound is
        not finite."""
        ny = cfg.ny
        if sp.max_growth * L > MAX_GROWTH:                        # a growing mode: no bound worth it
            return None
        absY = np.abs(Y)
        c = np.abs(sp.W @ Y) + ROUNDOFF * (sp.absW @ absY)       # modal amplitudes, with round-off
        if sp.max_growth > 0.0:
            c *= np.exp(sp.growth * L)
        amp = sp.absEV * c                                        # (m, ny): |E_i V_k| |c_k|
        fast = np.zeros((self.m, ny + 1))                         # cut p: the modes p.. are fast
        fast[:, :ny] = np.cumsum(amp[:, ::-1], axis=1)[:, ::-1]
        fast += (ROUNDOFF * sp.condition * (cfg.absE @ absY))[:, None]
        curv = np.zeros((self.m, ny + 1))                         # |s''|: the modes ..p-1, the load
        curv[:, 1:] = np.cumsum(amp * sp.mag2, axis=1)
        curv += (sp.absEXS2 @ self._z_bound(Y[ny:], L))[:, None]
        if not (np.isfinite(fast).all() and np.isfinite(curv).all()):
            return None
        return 2.0 * fast, curv / 8.0

    def _z_bound(self, z, L):
        """``|z(t)|`` bounded over ``[0, L]`` (the load generator's polynomials and sinusoids, the
        frozen values constant)."""
        zb = np.abs(z)
        for off, d, trig in self.gen.blocks:
            poly = zb[off: off + d + 1].copy()
            for i in range(d + 1):
                zb[off + i] = sum(poly[i + l] * L ** l / math.factorial(l) for l in range(d + 1 - i))
            if trig:
                k = off + d + 1
                zb[k] = zb[k + 1] = math.hypot(z[k], z[k + 1])
        return zb

    def _locate(self, cfg, Y0, Ys, es, j, h):
        """Earliest root in sub-interval j (of the stretch from ``Y0``): ``(tau from the start of
        sub-interval j, triggering constraints)``."""
        e_left = (cfg.E @ Y0) if j == 0 else es[j - 1]
        Y_left = Y0 if j == 0 else Ys[j - 1]
        candidates = np.flatnonzero(es[j] > np.maximum(cfg.zero, _noise(cfg.absE, Ys[j])))
        best, roots = np.inf, {}
        for i in candidates:
            Ei = cfg.E[i]
            if e_left[i] >= 0.0:
                r = 0.0
            else:
                f = lambda s: float(Ei @ (sla.expm(cfg.A * s) @ Y_left))
                r = find_root(f, 0.0, h, xtol=min(self.tol, h) * 0.25, rtol=4 * np.finfo(float).eps,
                              maxiter=200)
            roots[i] = r
            best = min(best, r)
        which = tuple(i for i, r in roots.items() if r <= best + self.tol)
        return best, which


def _slack(plan, width):
    """How far above ``max(e_i(a), e_i(b))`` the event functions can be between two samples ``width``
    apart (m,): ``2 B_i + width^2 D_i / 8`` of the plan (:meth:`EventSearch._plan`), the least over the
    cuts (kept in the plan by width)."""
    slack = plan[7].get(width)
    if slack is None:
        slack = plan[7][width] = np.min(plan[5] + (width * width) * plan[6], axis=1)
    return slack


def _split_width(n):
    """The sampling of a stretch of ``n`` fine sub-intervals that the bound did not clear: every
    ``r``-th, a power of 2 giving about 4 pieces, or 1 (all) for :data:`FINE_BLOCK` or fewer."""
    if n <= FINE_BLOCK:
        return 1
    return 2 ** max(int(math.ceil(math.log2(n))) - 2, 0)


def find_root(f, a, b, *, xtol, rtol, maxiter):
    """A root of ``f`` in ``[a, b]`` (``f(a)``, ``f(b)`` of opposite signs) to ``xtol + rtol |x|``.

    Regula falsi with the Anderson-Bjorck modification (Anderson & Bjorck 1973, BIT 13, 253-264):
    when the same end of the bracket is kept twice, its value is scaled by ``1 - f_new / f_old``
    (by 1/2 if that is not positive), which makes the method superlinear (order about 1.7); a
    bisection whenever the bracket has not halved over two steps, and steps of at least the
    tolerance, bound it by bisection's count. The root lies within the tolerance of the value
    returned (the bracket's midpoint once it is narrower than twice the tolerance). Here, not
    ``scipy.optimize``, whose import takes 0.2-0.5 s.

    Raises
    ------
    ValueError
        ``f(a)``, ``f(b)`` of the same sign, or a NaN value of ``f``.
    RuntimeError
        No convergence in ``maxiter`` evaluations.
    """
    def value(x):
        fx = float(f(x))
        if math.isnan(fx):
            raise ValueError(f"the function is NaN at x = {x!r}; cannot locate its root")
        return fx

    x0, x1 = float(a), float(b)
    f0, f1 = value(x0), value(x1)
    if f0 == 0.0:
        return x0
    if f1 == 0.0:
        return x1
    if math.copysign(1.0, f0) == math.copysign(1.0, f1):
        raise ValueError("f(a) and f(b) must have different signs")
    widths = [abs(x1 - x0)] * 2
    for _ in range(maxiter):
        width = abs(x1 - x0)
        tol = xtol + rtol * max(abs(x0), abs(x1))
        if width <= 2.0 * tol:
            return 0.5 * (x0 + x1)
        if width > 0.5 * widths[-2]:
            x = 0.5 * (x0 + x1)                             # not halving: bisect
        else:
            x = x1 - f1 * (x1 - x0) / (f1 - f0)             # false position
            step = tol if x0 > x1 else -tol
            if not min(x0, x1) < x < max(x0, x1) or abs(x - x1) < tol:
                x = x1 + step if abs(x - x1) < tol else 0.5 * (x0 + x1)
        widths.append(width)
        fx = value(x)
        if fx == 0.0:
            return x
        if math.copysign(1.0, fx) != math.copysign(1.0, f1):
            x0, f0 = x1, f1                                 # the root lies between x1 and x
        else:
            scale = 1.0 - fx / f1                           # x0 kept again: Anderson-Bjorck
            f0 *= scale if scale > 0.0 else 0.5
        x1, f1 = x, fx
    raise RuntimeError(f"the root was not located to {xtol:g} in {maxiter} evaluations (last x = {x1!r})")


def _noise(absE, absY):
    """Round-off level of ``E Y`` (rows of ``absY`` or one vector)."""
    return NOISE_ULPS * np.finfo(float).eps * (np.abs(absY) @ absE.T)
