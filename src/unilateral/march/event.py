"""An exact event-driven reference march for small models with piecewise-analytic loads.

Between two contact changes the model is linear with constant coefficients: for the contact set
of the moment (open constraints ``psi_i = 0``, closed ones ``v_i = 0``) the unknowns
``x = (u, v_open)`` obey a linear system (:mod:`unilateral.march.event_config`: massive DOFs
second order, massless damped DOFs and the gaps of open Kelvin contacts first order, massless
undamped DOFs and the gaps of open spring contacts condensed statically), and the load is the
output of a small linear generator on each piece of its time functions
(:mod:`unilateral.march.event_load`). The augmented system is integrated exactly by matrix
exponentials.

Events
    A closed constraint's reaction ``psi_i`` reaching 0 from below, or an open constraint's gap
    ``v_i`` reaching 0 from above. They are bracketed on a sub-grid of the exact solution (finer
    than half a radian of the fastest oscillation of the configuration) and located by Brent's
    method to ``tol`` (1e-13 s by default).
Sparse sampling
    The sub-grid is evaluated only where a crossing cannot be ruled out. The exact solution of a
    configuration is a sum of modes and of the load generator's share
    (:class:`~unilateral.march.event_config.Spectral`); from the modal amplitudes at the start of a
    smooth stretch (no decision, no load breakpoint) each event function is bounded between two
    samples ``a``, ``b``: ``e_i <= max(e_i(a), e_i(b)) + 2 B_i + (b - a)^2 D_i / 8``, ``B_i`` the
    share of the modes above a cut and ``D_i`` a bound of the second derivative of the rest. An
    interval whose bound stays below zero is passed over; the others are split until blocks of
    :data:`FINE_BLOCK` sub-intervals, evaluated in full. The first sub-interval found is therefore
    the one the full sub-grid finds: the events, and the results, are those of the full sub-grid
    (to round-off). Where the bound clears whole output steps, up to :data:`GLIDE` of them are
    taken at once. A stiff structure (an axially rigid column: 1.7e5 rad/s) no longer costs
    ``duration x fastest frequency`` sub-intervals whatever the output step, only about one
    matrix-vector product per output step away from the events.
Decision
    At an event, a load breakpoint and the start, the constraints at the boundary (a closed one
    with ``psi_i ~ 0``, an open one with ``v_i ~ 0``) and the triggering ones are critical. The new
    contact set is the one whose exact solution just after ``t`` is admissible: for each critical
    closed constraint the first non-negligible term of ``(psi, psi' d, psi'' d^2/2, psi''' d^3/6)``
    is negative, for each critical open one that of ``(v, v' d, ...)`` is positive, and no other
    constraint jumps out of its admissible side. Candidates are enumerated by increasing number of
    switches, which solves the rate-level LCP when several constraints change at once. With
    Kelvin contacts the reaction jumps at closure (``v'`` jumps to 0): the value level decides.

Rate-type unknowns
    A plastic multiplier (:class:`~unilateral.constraints.Yield`) or a slip
    (:class:`~unilateral.constraints.Friction`) only grows and is complementary to its constraint
    function ``phi`` (a row of ``P psi``) in its increments. An *active* one (yielding, slipping)
    is handled as an open contact: ``phi_i = 0`` is held and ``lambda_i`` is free. An *inactive*
    one is held at its **frozen** value, the ``lambda_i`` it had when it stopped (an imposed
    constant, like a gap, where a closed contact is held at 0). Its events: an inactive one's
    ``phi_i`` reaching 0 from below (yield, slip), as a closed contact's reaction; an active one's
    rate ``lambda_i'`` reaching 0 from above (elastic unloading, stick), where an open contact's
    gap reaches 0. At a decision an active rate unknown is admissible when the first
    non-negligible term of ``(lambda', lambda'' d, lambda''' d^2/2, lambda'''' d^3/6)`` is positive
    (the rate level), an inactive one as a closed contact. ``event_kinds`` names the changes
    "open"/"close" (contacts), "yield"/"unload" (plastic multipliers), "slip"/"stick" (slips).
    Friction on a Kelvin contact (the row map ``P`` meeting ``F_v``, ``H_v``) is refused.

Output on the grid ``t_k`` is the **left limit** ``lim_{t -> t_k-}`` (at ``t_0`` the initial
state): at a grid time that coincides with an event or a load jump, u, u', v and psi are those
before it. (Only quantities that can jump differ from the right limit: psi of a Kelvin contact at
closure, u' of massless DOFs, psi under a load jump on massless DOFs.)
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import scipy.linalg as sla

from unilateral.linalg import dense
from unilateral.march.event_config import Config
from unilateral.march.event_load import load_generator
from unilateral.march.event_search import ROUNDOFF, SPARSE_MIN, EventSearch, _noise, _slack

#: Bracketing sub-grid: at most this many radians of the fastest oscillation per sub-interval.
SUBSTEP_RADIANS = 0.5
#: Minimum number of sub-intervals per output interval.
MIN_SUBSTEPS = 4
#: Relative size (to the reference reaction / displacement) of a value that counts as zero.
ZERO_RTOL = 1e-12
#: Relative distance to the boundary within which a constraint is critical at a decision.
CRITICAL_RTOL = 1e-9
#: Largest number of critical constraints whose contact states are enumerated (2^k candidates).
MAX_ENUMERATED = 12
#: At most this many output steps are taken at once where the bound clears them (``_glide``).
GLIDE = 32
#: Default limit on the contact changes: this many per output step and unknown, so the limit
#: grows with the duration ``t_end / dt`` (:func:`default_max_events`).
EVENTS_PER_STEP = 100


class EventMarchStop(RuntimeError):
    """The march cannot go on: too many contact changes, no admissible contact set, or a motion
    that grows without bound. :func:`march_event` returns the grid up to where it stopped."""


def default_max_events(steps: int, m: int) -> int:
    """The default ``max_events`` of a march of ``steps`` output steps and ``m`` unknowns:
    :data:`EVENTS_PER_STEP` per step and unknown, ``EVENTS_PER_STEP * (steps + 1) * max(m, 1)``."""
    return EVENTS_PER_STEP * (int(steps) + 1) * max(int(m), 1)


def march_event(model, load, t_grid, u0, udot0, v0, *, tol=1e-13, max_events=None):
    """Follow a matrix model exactly from event to event; output on ``t_grid``.

    Parameters
    ----------
    model : Model
        Dense or sparse (densified; meant for n up to a few hundred), with constant ``g`` and
        ``q_imposed``; ``C``, ``H_v`` positive semidefinite.
    load : LoadHistory, ndarray (len(t_grid), n) or None
        A LoadHistory whose time functions have a piecewise form (the time functions of
        :mod:`unilateral.loads` and GroundMotion records), integrated exactly; an array of samples
        at ``t_grid``, taken as piecewise linear between them (constant before ``t_grid[0]``);
        or None (only the model's imposed load). A plain callable raises ValueError.
    t_grid : (N+1,) increasing output times; the initial state is at ``t_grid[0]``.
    u0, udot0 : (n,) initial displacement and velocity (only the velocity of the DOFs with mass
        matters; the others follow from the equations).
    v0 : (m,) initial unilateral deformations (``v0 > 0``: open) and rate unknowns (the
        multipliers accumulated so far; all start inactive, the decision at ``t_grid[0]`` activates
        those on their yield surface).
    tol : float
        Accuracy (s) of the event times.
    max_events : int, optional
        The most contact changes over the march, allowed in proportion to the time reached: by
        ``t``, ``max_events (t - t_0 + dt) / (t_N - t_0 + dt)`` (``dt`` the mean grid step), so
        that chattering or changes accumulating at one time stop early. Default
        :func:`default_max_events`: :data:`EVENTS_PER_STEP` (100) per output step and unknown,
        proportional to the duration ``t_N - t_0`` on a given grid.

    Returns
    -------
    u, udot : (K+1, n);  v, psi : (K+1, m)
        Left limits at the grid times, ``K = N`` unless the march stopped (``info["failure"]``).
    info : dict
        ``event_times`` (k,), ``event_constraints`` (k,) int, ``event_kinds`` (k,) "open"/"close"
        (contacts), "yield"/"unload" (plastic multipliers), "slip"/"stick" (slips),
        ``events`` (number of contact changes), ``decisions``, ``configurations``,
        ``undecided`` (decisions where no candidate was strictly admissible), ``substeps`` (the
        states evaluated on the sub-grid and its sparse samples), and
        ``failure``: None, or why the march stopped after grid time ``K`` (more than
        ``max_events`` contact changes, no admissible contact set, a motion growing without
        bound; :class:`EventMarchStop`).

    Raises
    ------
    ValueError
        A time-dependent ``g``, a load without an exact form, friction on a Kelvin contact.
    """
    march = EventMarch.of(model, load, t_grid, u0, udot0, v0, tol=tol, max_events=max_events)
    march.extend(march.N)
    return march.outputs()


class EventMarch:
    """The event march of :func:`march_event`, advanced on request (as far as it is pulled).

    ``EventMarch(march)`` of a prepared :class:`_March`; :meth:`extend` follows the motion up to a
    grid index, :meth:`outputs` returns ``(u, udot, v, psi, info)`` of the grid times reached.
    Pulled in any pieces it performs the same operations as one call of :func:`march_event`.

    Attributes
    ----------
    N : int;  done : int, the last grid index written;  failure : str ("" if none)
    """

    def __init__(self, march):
        self.march, self.N = march, march.grid.size - 1
        N1, n, m = self.N + 1, march.n, march.m
        self.out = (np.empty((N1, n)), np.empty((N1, n)), np.empty((N1, m)), np.empty((N1, m)))
        for array, x in zip(self.out, (march.u0, march.udot0, march.v0, march.psi0)):
            array[0] = x
        self._steps = None
        self.failure = ""

    @classmethod
    def of(cls, model, load, t_grid, u0, udot0, v0, *, tol=1e-13, max_events=None):
        """The march of :func:`march_event` (same arguments), begun at ``t_grid[0]``."""
        t_grid = np.asarray(t_grid, dtype=float)
        if t_grid.ndim != 1 or t_grid.size < 1 or np.any(np.diff(t_grid) <= 0):
            raise ValueError("t_grid must be a 1-D array of increasing times")
        n, m = model.n, model.m
        if not model.g_is_constant:
            raise ValueError("method='event' needs a constant constraint offset g; this model's g is a "
                             "function of time")
        gen = load_generator(model, load, t_grid)
        mats = _matrices(model)
        _check_law(model.law, mats)
        u0, udot0, v0 = (np.asarray(a, dtype=float).reshape(size) for a, size in ((u0, n), (udot0, n), (v0, m)))
        if max_events is None:
            max_events = default_max_events(t_grid.size - 1, m)
        return cls(_March(model.law, mats, gen, t_grid, (u0, udot0, v0), tol=tol, max_events=max_events))

    @property
    def done(self) -> int:
        return self.march.done

    def extend(self, k: int) -> int:
        """Follow the motion up to grid index ``k`` at least (or to where it stops); the last index."""
        march = self.march
        if self._steps is None and k > 0:
            self._steps = march._follow(march._stops(), self.out)
        try:
            with np.errstate(over="ignore", invalid="ignore"):     # a diverging motion: stopped below
                while march.done < min(k, self.N) and not self.failure:
                    next(self._steps)
        except EventMarchStop as exc:
            self.failure = str(exc)
        except StopIteration:
            pass
        return march.done

    def outputs(self):
        """``(u, udot, v, psi, info)`` of the grid times reached (``done + 1`` rows)."""
        K = self.march.done + 1
        u, ud, v, psi = (array[:K] for array in self.out)
        return u, ud, v, psi, self.march.info(self.failure or None)


# ---------------------------------------------------------------------- the march
def _matrices(model):
    n, m = model.n, model.m
    M, C, K, F = (dense(A).astype(float) for A in (model.M, model.damping(), model.K, model.F))
    Fv = np.zeros((n, m)) if model.F_v is None else dense(model.F_v).astype(float)
    H = dense(model.H).astype(float)
    Hv = np.zeros((m, m)) if model.H_v is None else dense(model.H_v).astype(float)
    g = np.asarray(model.g(0.0), dtype=float).reshape(m)
    return M, C, K, F, Fv, H, Hv, g


def _check_law(law, mats):
    """Refuse friction rows that take their normal force from a Kelvin contact (``F_v``, ``H_v``)."""
    if law.P is None:
        return
    _, _, _, _, Fv, _, Hv, _ = mats
    normals = np.flatnonzero(np.any((law.P != 0) & ~np.eye(law.m, dtype=bool), axis=0))
    if np.any(Fv[:, normals] != 0) or np.any(Hv[normals] != 0) or np.any(Hv[:, normals] != 0):
        raise ValueError("method='event' does not solve friction on a Kelvin contact (the normal force "
                         "of a friction row has a viscous part F_v, H_v); use method='cq', 'modal' or "
                         "'direct'")


#: Names of an unknown's changes by its kind: (becomes inactive, becomes active).
CHANGE_NAMES = {"contact": ("close", "open"), "yield": ("unload", "yield"), "friction": ("stick", "slip")}


class _March(EventSearch):
    def __init__(self, law, mats, gen, t_grid, state0, *, tol, max_events):
        u0, udot0, v0 = state0
        self.law = law
        self.mats, self.gen, self.grid = mats, gen, t_grid
        self.tol, self.max_events = float(tol), int(max_events)
        self.u0, self.udot0, self.v0 = u0, udot0, v0
        M, C, K, F, Fv, H, Hv, g = mats
        n, m = K.shape[0], F.shape[1]
        self.n, self.m = n, m
        # reference sizes for "zero": displacement and reaction of the load patterns
        qref = np.abs(gen.Gq[:, 0]).copy()
        for vector, f in gen.terms:
            amp = np.max(np.abs(f.poly[:, 0])) + np.max(np.hypot(f.trig[:, 0], f.trig[:, 1]))
            qref += amp * np.abs(vector)
        try:
            uq = np.linalg.solve(K, qref)
        except np.linalg.LinAlgError:
            uq = np.zeros(n)
        psi0 = F.T @ u0 + Fv.T @ udot0 - H @ v0 - g
        self.psi0 = law.rows(psi0)
        uref = max(np.abs(uq).max(initial=0.0), np.abs(u0).max(initial=0.0), np.abs(v0).max(initial=0.0))
        psiref = max(np.abs(F.T @ uq).max(initial=0.0), np.abs(psi0).max(initial=0.0),
                     np.abs(g).max(initial=0.0), np.abs(F).max(initial=0.0) * uref)
        hmax = np.abs(np.diag(H)).max(initial=0.0)
        vref = max(uref, psiref / hmax if hmax > 0 else 0.0)
        self.psiref = psiref if psiref > 0 else 1.0
        self.vref = vref if vref > 0 else 1.0
        self.configs = {}
        self.omega_load = max([f.omega for _, f in gen.terms if f.has_trig], default=0.0)
        self.wref = self._reference_rate(t_grid)
        self.rateref = self.vref * self.wref
        # uniform grid: full intervals use the canonical step (no drift from t_k - t_{k-1})
        steps = np.diff(t_grid)
        self.dt = float(steps.mean()) if steps.size else 0.0
        self.uniform = steps.size > 0 and np.allclose(steps, self.dt, rtol=1e-9, atol=0.0)
        self.event_times, self.event_constraints, self.event_kinds = [], [], []
        self.decisions = 0
        self.undecided = 0
        self.substeps = 0
        self.plan = None                        # the sparse sampling of the smooth stretch (_plan)
        self.same_time = 0
        self.last_decision = -np.inf
        self.done = 0                           # the last grid index written
        self.skipped = None                     # (t, why) of the last singular candidate

    def _reference_rate(self, t_grid):
        """A frequency (1/s) that turns ``vref`` into the size of a rate ``lambda'``: the fastest of
        the elastic structure (every unknown inactive), of the load and ``1 / span`` of the grid."""
        span = t_grid[-1] - t_grid[0]
        try:
            elastic = Config(self.mats, self.gen, np.zeros(self.m, dtype=bool), self.law).max_rate
        except ValueError:
            elastic = 0.0
        return max(elastic, self.omega_load, 1.0 / span if span > 0 else 1.0)

    # ------------------------------------------------------------------ configurations
    def config(self, open_mask):
        """The :class:`Config` of the active set ``open_mask`` (cached; ValueError if singular)."""
        key = tuple(bool(b) for b in open_mask)
        cfg = self.configs.get(key)
        if isinstance(cfg, ValueError):
            raise cfg
        if cfg is None:
            try:
                cfg = Config(self.mats, self.gen, np.array(key, dtype=bool), self.law)
            except ValueError as exc:
                self.configs[key] = exc
                raise
            cfg.scale = self._scales(cfg.open)
            cfg.zero = ZERO_RTOL * cfg.scale
            cfg.absE, cfg.absA = np.abs(cfg.E), np.abs(cfg.A)
            freq = max(cfg.max_frequency, self.omega_load)
            cfg.hmax = SUBSTEP_RADIANS / freq if freq > 0 else np.inf
            self.configs[key] = cfg
        return cfg

    def _scales(self, open_mask):
        """Per unknown, the size of its event function: a reaction (inactive), a gap (open
        contact) or a rate (active rate unknown)."""
        return np.where(open_mask, np.where(self.law.rate, self.rateref, self.vref), self.psiref)

    # ------------------------------------------------------------------ main loop
    def info(self, failure):
        """The statistics of the march so far, with ``failure`` (None or why it stopped)."""
        return {
            "event_times": np.array(self.event_times),
            "event_constraints": np.array(self.event_constraints, dtype=int),
            "event_kinds": np.array(self.event_kinds, dtype=object),
            "events": len(self.event_times),
            "decisions": self.decisions,
            "configurations": sum(isinstance(c, Config) for c in self.configs.values()),
            "undecided": self.undecided,
            "substeps": self.substeps,
            "tol": self.tol,
            "failure": failure,
        }

    def _stops(self):
        """``(time, grid index or None, is a load breakpoint)`` of the grid times and of the load
        breakpoints inside ``(t_0, t_N]`` (snapped to grid times they round to), in time order."""
        grid = self.grid
        N = grid.size - 1
        t0, t_end = grid[0], grid[-1]
        bps = self.gen.breakpoints[(self.gen.breakpoints > t0) & (self.gen.breakpoints <= t_end)]
        snap = 1e-12 * max(abs(t_end), abs(t0), self.dt)
        k_near = np.clip(np.searchsorted(grid, bps), 0, N)
        on_grid = {}
        for b, k in zip(bps, k_near):
            for kk in (k - 1, k):
                if 0 <= kk <= N and abs(grid[kk] - b) <= snap:
                    on_grid[kk] = True
                    break
            else:
                on_grid[float(b)] = False
        stops = [(float(grid[k]), k, k in on_grid) for k in range(1, N + 1)]
        stops += [(b, None, True) for b, flag in on_grid.items() if flag is False]
        return sorted(stops, key=lambda s: s[0])

    def _follow(self, stops, out):
        """March through ``stops`` (time, grid index or None, is a load breakpoint), writing the grid
        outputs into ``out = (u, ud, v, psi)``; a generator that yields the last grid index written
        after each stop (the march advances as far as it is pulled)."""
        grid, gen = self.grid, self.gen
        cfg = self.config((self.v0 > 0) & ~self.law.rate)
        Y = cfg.state_from(self.u0, self.udot0, self.v0, gen.state(grid[0], "right"))
        cfg, Y = self.decide(cfg, Y, grid[0], ())
        t = grid[0]
        s = 0
        while s < len(stops):
            t_stop, k, is_bp = stops[s]
            full = k is not None and self.done == k - 1 and t == grid[k - 1] and self.uniform
            if full and not is_bp:
                count, Y = self._glide(cfg, Y, t, stops, s, out)
                if count:
                    s += count
                    t = stops[s - 1][0]
                    yield self.done
                    continue
            cfg, Y, pending = self.advance(cfg, Y, t, t_stop, self.dt if full else None)
            t = t_stop
            if k is not None:
                self._output(cfg, Y, k, out)
            if is_bp:
                Y = Y.copy()
                Y[cfg.ny: cfg.ny + gen.size] = gen.state(t, "right")
            if is_bp or pending:
                cfg, Y = self.decide(cfg, Y, t, pending or ())
            s += 1
            yield self.done

    def _glide(self, cfg, Y, t, stops, s, out):
        """Several full output steps at once from ``stops[s]`` on, as :meth:`advance` takes them one by
        one when the plan's bound clears each whole step (:meth:`_scan`): the plain grid stops that
        follow (no load breakpoint) within the plan's horizon, at most :data:`GLIDE`, up to the first
        step the bound does not clear. Writes their outputs; returns ``(count, Y)`` (0: none)."""
        L = self.dt
        J = max(MIN_SUBSTEPS, math.ceil(L / cfg.hmax - 1e-9)) if np.isfinite(cfg.hmax) else MIN_SUBSTEPS
        if J < SPARSE_MIN:
            return 0, Y
        plan = self._plan_for(cfg, Y, t, J, L / J)
        if plan is None or plan[4] < J:
            return 0, Y
        K = 0
        while K < GLIDE and s + K < len(stops):
            t_stop, k, is_bp = stops[s + K]
            if k is None or is_bp or t_stop > plan[2]:
                break
            K += 1
        if K < 2:
            return 0, Y
        Ys = np.vstack([Y, cfg.powers(L, GLIDE)[:K] @ Y])        # (K + 1, NY) at t + i dt
        e = Ys @ cfg.E.T
        noise = ROUNDOFF * (np.abs(Ys) @ cfg.absE.T)
        high = np.maximum(e[:-1], e[1:]) + noise[:-1] + noise[1:] + _slack(plan, J * (L / J))
        clear = (high <= cfg.zero).all(axis=1)
        count = K if clear.all() else int(np.argmin(clear))
        if count == 0:
            return 0, Y
        block = Ys[1:count + 1]
        values = (block @ cfg.U.T, block @ cfg.UD.T, block @ cfg.V.T, block @ cfg.PSI.T)
        if not all(np.isfinite(x).all() for x in values):
            return 0, Y                                           # the step by step march says why
        k0 = stops[s][1]
        for array, x in zip(out, values):
            array[k0:k0 + count] = x
        self.done = k0 + count - 1
        self.substeps += count
        return count, block[-1]

    def _output(self, cfg, Y, k, out):
        """Write the outputs at grid time ``k``; stop if they are not finite (the motion diverged)."""
        values = (cfg.U @ Y, cfg.UD @ Y, cfg.V @ Y, cfg.PSI @ Y)
        if not np.isfinite(np.concatenate(values)).all():
            raise EventMarchStop(f"the motion grows without bound: u, v are not finite at t = {self.grid[k]:.6g} "
                                 f"({self._instability(cfg)})")
        for array, x in zip(out, values):
            array[k] = x
        self.done = k

    def _instability(self, cfg):
        """Why the configuration ``cfg`` diverges, for the message."""
        growth = float(np.max(np.linalg.eigvals(cfg.A).real, initial=-np.inf))
        where = f"with unknowns {np.flatnonzero(cfg.open).tolist()} open (active)" if cfg.open.any() else "all closed"
        return (f"the configuration {where} has a growing mode, rate {growth:.3g} 1/time: the stiffness of "
                "the structure with those constraints open is not positive semidefinite; check K, F and H")

    # ------------------------------------------------------------------ exact advance
    def advance(self, cfg, Y, ta, tb, length=None):
        """Advance from ``ta`` to ``tb``, handling the events on the way.

        Returns ``(cfg, Y(tb-), pending)`` with ``pending`` the constraints of an event found at
        ``tb`` itself (decided by the caller after recording the left limit).
        """
        while True:
            L = (tb - ta) if length is None else length
            if L <= 0:
                return cfg, Y, ()
            J = max(MIN_SUBSTEPS, math.ceil(L / cfg.hmax - 1e-9)) if np.isfinite(cfg.hmax) else MIN_SUBSTEPS
            h = L / J
            Y_end, hit = self._scan(cfg, Y, ta, J, h)
            if hit is None:
                return cfg, Y_end, ()
            j, Y_left, Ys, es, j_local = hit
            best, which = self._locate(cfg, Y_left, Ys, es, j_local, h)
            tau = j * h + best
            t_e = ta + tau
            if t_e >= tb - self.tol:                              # the event is at tb
                return cfg, Y_end, which
            Y = sla.expm(cfg.A * tau) @ Y if tau > 0 else Y
            cfg, Y = self.decide(cfg, Y, t_e, which)
            ta, length = t_e, None

    # ------------------------------------------------------------------ decisions
    def decide(self, cfg, Y, t, forced):
        """Choose the admissible configuration at ``t`` (see the module docstring)."""
        self.decisions += 1
        self.plan = None                        # the state changes (or may): a new bound
        self._guard(t)
        e = cfg.E @ Y
        near = CRITICAL_RTOL * cfg.scale
        critical = set(int(i) for i in forced) | set(np.flatnonzero(e > -near).tolist())
        if not critical:
            return cfg, Y
        # the massive velocity is continuous; state_from projects u' on the massive DOFs
        state = (cfg.U @ Y, cfg.UD @ Y, cfg.V @ Y, Y[cfg.ny: cfg.ny + self.gen.size])
        new, Yn, violation = self._choose(cfg, state, critical, t)
        if violation > 0.0:
            self.undecided += 1
        self._record(cfg, new, t)
        return new, Yn

    def _choose(self, cfg, state, critical, t):
        """The first admissible candidate, else the least violating: ``(config, Y, violation)``.

        Candidates switch the ``critical`` unknowns of ``cfg``, fewest switches first; the set
        grows by the unknowns that a candidate makes jump. A singular candidate (both faces of a
        yield pair active, say) is skipped.
        """
        delta = 1e-6 * (self.dt if self.dt > 0 else 1.0)
        failure = None
        for _ in range(self.m + 1):
            crit = sorted(critical)
            best, best_violation, grown = None, np.inf, False
            for switches in _patterns(len(crit)):
                mask = cfg.open.copy()
                mask[[i for i, s in zip(crit, switches) if s]] ^= True
                try:
                    new = self.config(mask)
                except ValueError as exc:
                    failure = failure or exc
                    self.skipped = (t, str(exc))
                    continue
                Yn = new.state_from(*state)
                violation, jumped = self._violation(new, Yn, crit, delta)
                if jumped:
                    critical |= jumped
                    grown = True
                    continue
                if violation <= 0.0:
                    return new, Yn, 0.0
                if violation < best_violation:
                    best, best_violation = (new, Yn), violation
            if not grown:
                break
        if best is None:
            if failure is not None:
                raise failure
            raise EventMarchStop(f"no admissible contact set at t = {t!r}")
        return best + (best_violation,)

    def _guard(self, t):
        """Raise if decisions keep coming back to the same time ``t`` (no admissible set)."""
        if abs(t - self.last_decision) <= 10 * self.tol:
            self.same_time += 1
            if self.same_time > 4 * self.m + 10:
                raise EventMarchStop(f"the decisions keep coming back to t = {t!r} (no admissible "
                                     "contact set found)" + self._skipped_at(t))
        else:
            self.same_time = 0
        self.last_decision = t

    def _skipped_at(self, t):
        """Why candidates were skipped near ``t`` (singular configurations), for a message."""
        if self.skipped is None or abs(self.skipped[0] - t) > 10 * self.tol:
            return ""
        return f"; candidates skipped there: {self.skipped[1]}"

    def _record(self, cfg, new, t):
        """Log the changes from ``cfg`` to ``new`` at ``t``."""
        changed = np.flatnonzero(new.open != cfg.open)
        for i in changed:
            self.event_times.append(float(t))
            self.event_constraints.append(int(i))
            self.event_kinds.append(CHANGE_NAMES[self.law.kinds[i]][int(new.open[i])])
        limit = self._event_limit(t)
        if len(self.event_times) > limit:
            raise EventMarchStop(f"more than {limit} contact changes by t = {t:.6g} (max_events = {self.max_events} "
                                 "over the run, allowed in proportion to the time reached): chattering, or "
                                 "changes accumulating at one time; raise max_events if this is expected, or "
                                 "use method='cq' or 'direct'")

    def _event_limit(self, t):
        """The contact changes allowed by ``t``: ``max_events`` in proportion to the time reached,
        ``(t - t_0 + dt) / (t_N - t_0 + dt)`` of it."""
        t0, span = self.grid[0], self.grid[-1] - self.grid[0] + self.dt
        if span <= 0:
            return self.max_events
        return math.ceil(self.max_events * min(1.0, (t - t0 + self.dt) / span))

    def _violation(self, cfg, Y, crit, delta):
        """How much the critical constraints leave their admissible side just after now (<= 0:
        admissible), and the non-critical constraints that jump out of theirs."""
        D, noise = [cfg.E @ Y], [_noise(cfg.absE, Y)]
        W, absW = Y, np.abs(Y)
        for _ in range(3):
            W, absW = cfg.A @ W, cfg.absA @ absW
            D.append(cfg.E @ W)
            noise.append(_noise(cfg.absE, absW))
        scale = np.array([delta ** k / math.factorial(k) for k in range(4)])[:, None]
        terms = np.array(D) * scale                                          # (4, m)
        # a derivative is negligible below round-off and below zero * wref^k (the size of "zero"
        # in the units of the derivative)
        floor = np.array([(self.wref * delta) ** k / math.factorial(k) for k in range(4)])[:, None]
        thr = np.maximum(np.array(noise) * scale, floor * cfg.zero[None, :])
        thr[0] = np.maximum(thr[0], 1e3 * cfg.zero)
        crit_mask = np.zeros(self.m, dtype=bool)
        crit_mask[crit] = True
        jumped = set(np.flatnonzero(~crit_mask & (terms[0] > thr[0])).tolist())
        violation = -np.inf
        for i in crit:
            big = np.flatnonzero(np.abs(terms[:, i]) > thr[:, i])
            if big.size and terms[big[0], i] > 0:
                violation = max(violation, terms[big[0], i] / thr[big[0], i])
            else:
                violation = max(violation, -1.0)
        return violation, jumped


def _patterns(k):
    """Switch patterns of k critical constraints, fewest switches first."""
    if k > MAX_ENUMERATED:
        yield (True,) * k                       # too many to enumerate: switch them all
        yield (False,) * k
        return
    for r in range(k + 1):
        for on in itertools.combinations(range(k), r):
            pattern = [False] * k
            for i in on:
                pattern[i] = True
            yield tuple(pattern)
