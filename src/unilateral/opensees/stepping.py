"""The analysis of an OpenSees script: ``integrator``, ``analysis``, ``analyze``, ``wipeAnalysis``.

A script builds its model step by step and analyses it in pieces; the model here is built once
(:func:`.build.build`) at the first ``analyze`` after a change. The state (``u``, ``u'``,
``u''`` and the constraint unknowns ``v``) is carried from analysis to analysis by DOF name.

* ``Static`` + ``LoadControl dLambda``: each step advances the time by ``dLambda`` and solves the
  static unilateral equilibrium (an LCP) under the loads at that time. Path-dependent yielding
  in a static analysis is refused (a yield multiplier that is or becomes nonzero).
* ``Transient`` + ``Newmark gamma beta``: one :class:`~unilateral.Simulation`
  (``method="direct"``, the trapezoidal rule for 1/2, 1/4, else the library's Newmark rule) over a
  horizon of steps from the current state (``initial={"u0", "udot0", "v0"}``), with the loads
  sampled at the times OpenSees reaches (``t += dt``, step by step). ``analyze(n, dt)`` performs
  ``n`` steps of it, so ``n`` calls of ``analyze(1, dt)`` are the same steps, bit for bit. The
  first horizon is :data:`FIRST_HORIZON` steps; when it is used up the simulation is restarted
  from the state at its last step with a horizon twice as long (at the same steps however the
  script cuts its calls), and also when ``dt``, the time, the model or the loads change. OpenSees starts Newmark from the acceleration of the
  domain (zero after a static analysis); a restart checks that it is the acceleration of
  equilibrium with the load (otherwise the two codes integrate different problems, and the
  analysis is refused).
"""

from __future__ import annotations

import sys

import numpy as np

from ..initial import given_state, static_state
from ..lcp import get_lcp_solver
from ..rules import Newmark
from ..solve import Simulation
from .build import build
from .control import DisplacementPath, parse_displacement_control
from .eleloads import pattern_forces
from .pdelta import MAX_ITER, STATIC_TOL, axial_forces, with_axial
from .queries import spring_state
from .refusals import OpenSeesRefused, refuse

__all__ = ["Analysis"]

#: The steps of the first horizon of a transient simulation, at least.
FIRST_HORIZON = 1024
#: A horizon holds at most this many load entries (steps x DOFs).
MAX_ENTRIES = 20_000_000


class Analysis:
    """The analysis state of one session (see the module's docstring)."""

    def __init__(self, domain):
        self.domain = domain
        self.on_commit = None                        # called with the time after each step (recorders)
        self.wipe()

    def wipe(self):
        """Forget the model built, the state and the analysis settings (``wipe``)."""
        self.built, self.built_version = None, None
        self.u = self.ud = self.udd = None           # reduced state of self.built
        self.v = None
        self.sim = None
        self.axial = {}                              # the P-Delta axial forces of the last static state
        self.wipe_analysis()

    def wipe_analysis(self):
        """Forget the analysis settings (``wipeAnalysis``); the state is kept."""
        self.integrator, self.kind = None, None
        self.sim = self.path = None

    # ------------------------------------------------------------------ settings
    def set_integrator(self, kind, *args):
        """``integrator('Newmark', gamma, beta)`` or ``integrator('LoadControl', dLambda, ...)``."""
        what = f"integrator({kind!r}, {', '.join(map(repr, args))})"
        if kind == "Newmark":
            if len(args) < 2 or any(isinstance(a, str) for a in args[:2]):
                refuse(what, "gamma and beta are needed", "integrator('Newmark', 0.5, 0.25)")
            if len(args) > 2:
                refuse(what, f"the options {args[2:]!r} are not in the subset", "integrator('Newmark', gamma, beta)")
            gamma, beta = float(args[0]), float(args[1])
            if not (gamma >= 0.5 and beta >= 0.25 * (0.5 + gamma) ** 2 * (1 - 1e-12)):
                refuse(what, "only unconditionally stable Newmark rules (gamma >= 1/2, beta >= (gamma + 1/2)^2 / 4) "
                       "are in the subset: an explicit or conditionally stable one is not the implicit stepping "
                       "with one LCP per step", "integrator('Newmark', 0.5, 0.25)")
            self.integrator = ("Newmark", gamma, beta)
        elif kind == "LoadControl":
            if not args:
                refuse(what, "dLambda is needed", "integrator('LoadControl', 1.0)")
            d = float(args[0])
            if len(args) > 1 and int(args[1]) < 1:
                refuse(what, "numIter must be >= 1", "integrator('LoadControl', dLambda)")
            if len(args) > 2 and (float(args[2]) != d or (len(args) > 3 and float(args[3]) != d)):
                refuse(what, "an automatic load increment (minLambda, maxLambda different from dLambda) is not in "
                       "the subset", "integrator('LoadControl', dLambda)")
            self.integrator = ("LoadControl", d)
        elif kind == "DisplacementControl":
            self.integrator = ("DisplacementControl", *parse_displacement_control(what, args))
        elif kind in ("HHT", "GeneralizedAlpha", "CentralDifference", "TRBDF2", "ExplicitDifference"):
            refuse(what, "the direct stepping here is Newmark's (with gamma, beta); this integrator is another "
                   "rule", "integrator('Newmark', 0.5, 0.25)")
        else:
            refuse(what, "only Newmark (transient), LoadControl and DisplacementControl (static) are in the subset",
                   "integrator('Newmark', 0.5, 0.25) or integrator('LoadControl', 1.0)")
        self.sim = None
        if kind != "DisplacementControl":            # a new increment goes on along the same path
            self.path = None

    def set_analysis(self, kind, *args):
        """``analysis('Static')`` or ``analysis('Transient')``."""
        if kind not in ("Static", "Transient") or args:
            refuse(f"analysis({kind!r})", "only Static and Transient analyses are in the subset "
                   "(VariableTransient changes dt by its own rule)", "analysis('Static') or analysis('Transient')")
        self.kind = kind
        self.sim = None

    # ------------------------------------------------------------------ the model and the state
    def current(self):
        """The model built for the domain as it is now (rebuilt after a change, the state carried)."""
        d = self.domain
        if self.built is None or self.built_version != d.version:
            old, state = self.built, (self.u, self.ud, self.udd, self.v)
            self.built, self.built_version = build(d), d.version
            self.sim = None
            self._carry(old, state)
            if self.built.pdelta:
                with_axial(self.built, self.axial)
        return self.built

    def _carry(self, old, state):
        """The state of the model ``old`` on the model just built, by DOF and constraint name; the
        unknowns of new constraints (all of a first model: open gaps) consistent with ``u``."""
        new = self.built.model
        n = new.n
        if old is None:
            self.u, self.ud, self.udd = np.zeros(n), np.zeros(n), np.zeros(n)
            vat = {}
        else:
            at = {name: k for k, name in enumerate(old.model.dof_names)}
            self.u, self.ud, self.udd = (np.array([x[at[name]] if name in at else 0.0 for name in new.dof_names])
                                         for x in state[:3])
            vat = {name: k for k, name in enumerate(old.model.constraint_names)}
        fresh = None
        if any(name not in vat for name in new.constraint_names):
            fresh = given_state(new, {"u0": self.u, "udot0": self.ud}).v
            fresh[new.law.rate] = 0.0                  # plastic multipliers start from the virgin state
        self.v = np.array([state[3][vat[name]] if name in vat else fresh[k]
                           for k, name in enumerate(new.constraint_names)])

    def load(self, times) -> np.ndarray:
        """The reduced loads (len(times), n) of the patterns at ``times``."""
        b, d = self.built, self.domain
        times = np.asarray(times, dtype=float)
        q = np.zeros((times.size, b.model.n))
        mass = b.mass
        for p in d.patterns.values():
            if p.kind == "Plain":
                f = pattern_forces(b, d, p)
                _check_loaded(b, d, p, f)
            else:
                f = np.zeros(mass.size)
                f[p.direction - 1::b.ndf] = -mass[p.direction - 1::b.ndf]
            factor = np.full(times.size, p.frozen) if p.frozen is not None else p.factor * d.series[p.series](times)
            q += np.outer(factor, b.reduced(f))
        return q

    # ------------------------------------------------------------------ analyze
    def analyze(self, steps=1, dt=None):
        """``analyze(numIncr, dt)``.

        Parameters
        ----------
        steps : int, the number of steps
        dt : float, the time step (transient analyses)

        Returns
        -------
        int
            0 on success, -3 if a step failed (the reason is printed on stderr).
        """
        if self.kind is None:
            refuse("analyze", "no analysis is defined", "analysis('Static') or analysis('Transient') first")
        steps = int(steps)
        if self.kind == "Static":
            if self.integrator is None:
                self.integrator = ("LoadControl", 1.0)
            if self.integrator[0] == "DisplacementControl":
                return self._displacement_control(steps)
            if self.integrator[0] != "LoadControl":
                refuse("analyze", "a Static analysis takes the LoadControl or DisplacementControl integrator",
                       "integrator('LoadControl', 1.0)")
            return self._static(steps)
        if self.integrator is None:
            self.integrator = ("Newmark", 0.5, 0.25)
        if self.integrator[0] != "Newmark":
            refuse("analyze", "a Transient analysis takes the Newmark integrator", "integrator('Newmark', 0.5, 0.25)")
        if dt is None or not float(dt) > 0:
            refuse(f"analyze({steps}, {dt!r})", "a transient step needs dt > 0", "analyze(numIncr, dt)")
        return self._transient(steps, float(dt))

    def _static(self, steps):
        b = self.current()
        model, d = b.model, self.domain
        rate = model.law.rate
        for _ in range(steps):
            if np.any(self.v[rate] != 0):
                refuse("analyze (Static) after yielding", "a static analysis here solves the equilibrium under the "
                       "total load in one increment, which is the path of a yielding structure only from the virgin "
                       "state", "a transient analysis, or static loads that do not yield")
            d.time = d.time + self.integrator[1]
            q = self.load([d.time])[0] + model.q_imposed(d.time)
            state = self._static_state(q)
            if state.message:
                print(f"unilateral.opensees: static step failed at time {d.time:g}: {state.message}", file=sys.stderr)
                return -3
            if np.any(state.v[rate] > 0):
                names = [model.constraint_names[k] for k in np.flatnonzero(rate & (state.v > 0))]
                refuse("analyze (Static)", f"the static load yields {', '.join(names)}: the path of a yielding "
                       "static analysis is not that of one increment", "static loads that do not yield (gravity), "
                       "then a transient analysis")
            self.u, self.v = state.u, state.v
            self._check_gaps()
            if self.on_commit is not None:
                self.on_commit(d.time)
        self.sim = None
        return 0

    def _static_state(self, q):
        """The static state under ``q``; with P-Delta elements, at the fixed point of their axial forces."""
        b = self.built
        solver = get_lcp_solver("bpp")
        if not b.pdelta:
            return static_state(b.model, q, solver)
        N = axial_forces(b.pdelta, b.nodal(self.u))
        for _ in range(MAX_ITER):
            with_axial(b, N)
            state = static_state(b.model, q, solver)
            if state.message:
                return state
            new = axial_forces(b.pdelta, b.nodal(state.u))
            scale = max(max(abs(x) for x in new.values()), 1e-300)
            if max(abs(new[tag] - N[tag]) for tag in new) <= STATIC_TOL * scale:
                self.axial = N
                return state
            N = new
        state.message = (f"the P-Delta axial forces did not converge in {MAX_ITER} iterations (a load near "
                         "the buckling load)")
        return state

    def _displacement_control(self, steps):
        """Steps of ``DisplacementControl`` on the monotonic static path (:mod:`.control`)."""
        if self.current().pdelta:
            refuse("analyze (DisplacementControl) with geomTransf('PDelta')", "the path followed here is that of "
                   "a constant K, while OpenSees's P-Delta follows the axial forces along the pushover",
                   "geomTransf('Linear', tag), or unilateral.pushover(..., p_delta='string') on a Frame2D")
        _, node, dof, incr = self.integrator
        d = self.domain
        path = self.path
        if path is None or path.key != (self.built_version, d.load_version, node, dof):
            self.path = path = DisplacementPath(self, node, dof, incr)
        path.incr = incr                             # (a new increment on the same path)
        for _ in range(steps):
            state = path.step()
            self.u, self.v, d.time = state["u"], state["v"], state["time"]
            self.ud, self.udd = np.zeros_like(self.u), np.zeros_like(self.u)
            self._check_gaps()
            if self.on_commit is not None:
                self.on_commit(d.time)
        self.sim = None
        return 0

    def _transient(self, steps, dt):
        b = self.current()
        d = self.domain
        _, gamma, beta = self.integrator
        key = (self.built_version, d.load_version, dt)
        c1, c2 = 1.0 / (beta * dt * dt), 1.0 / (beta * dt)
        done = 0
        while done < steps:
            sim = self.sim
            if sim is None or sim["key"] != key or sim["times"][sim["sim"].n] != d.time:
                self.sim = sim = self._start(key, dt, FIRST_HORIZON, gamma, beta)
            elif sim["sim"].n == sim["sim"].N:          # the horizon is used up: on from the state
                horizon = min(2 * sim["sim"].N, max(FIRST_HORIZON, MAX_ENTRIES // max(b.model.n, 1)))
                self.sim = sim = self._start(key, dt, horizon, gamma, beta)
            s = sim["sim"]
            for _ in range(min(steps - done, s.N - s.n)):
                message = s.step()
                if message:
                    print(f"unilateral.opensees: transient step failed at time {d.time + dt:g}: {message}",
                          file=sys.stderr)
                    return -3
                state = s.state
                self.udd = c1 * (state.u - self.u) - c2 * self.ud - (0.5 / beta - 1.0) * self.udd
                self.u, self.ud, self.v = state.u, state.udot, state.v
                d.time = sim["times"][s.n]
                self._check_gaps()
                if self.on_commit is not None:
                    self.on_commit(d.time)
                done += 1
        return 0

    def _start(self, key, dt, horizon, gamma, beta):
        """A simulation of ``horizon`` steps from the current state and time."""
        model, d = self.built.model, self.domain
        times = np.cumsum(np.r_[d.time, np.full(horizon, dt)])
        q = self.load(times)
        self._check_acceleration(q[0] + model.q_imposed(d.time))
        rule = "trapezoidal" if (gamma, beta) == (0.5, 0.25) else Newmark(gamma=gamma, beta=beta)
        try:
            sim = Simulation(model, q, dt=dt, t_end=horizon * dt, method="direct", rule=rule,
                             initial={"u0": self.u, "udot0": self.ud, "v0": np.maximum(self.v, 0.0)},
                             bilateral=getattr(self, "bilateral", False))         # (ops.bilateral, .extensions)
        except ValueError as exc:
            raise OpenSeesRefused("analyze (Transient)", f"the state cannot start a simulation: {exc}",
                                  "a consistent state (start from rest or from a static analysis)") from None
        if sim.N != horizon:
            raise RuntimeError(f"the simulation has {sim.N} steps, not {horizon}")
        return {"key": key, "sim": sim, "times": times}

    def _check_acceleration(self, q0):
        """Refuse a start whose acceleration (OpenSees: the domain's) is not that of equilibrium."""
        model = self.built.model
        M = model.M.diagonal()
        residual = q0 - model.damping() @ self.ud - model.K @ self.u + model.F @ self.v
        residual = np.asarray(residual).ravel()
        massive = M > 0
        a = np.where(massive, residual / np.where(massive, M, 1.0), 0.0)
        scale = max(float(np.max(np.abs(np.asarray(q0)[massive] / M[massive]), initial=0.0)),
                    float(np.max(np.abs(self.udd), initial=0.0)), 1e-300)
        gap = np.abs(a - self.udd)[massive]
        if gap.size and float(gap.max()) > 1e-8 * scale:
            k = int(np.flatnonzero(massive)[np.argmax(gap)])
            refuse("analyze (Transient)", f"OpenSees starts Newmark from the acceleration the domain holds "
                   f"({self.udd[k]:.6g} at DOF {model.dof_names[k]}), but the load at t = {self.domain.time:g} "
                   f"is in equilibrium with {a[k]:.6g} there: the two codes would integrate different initial "
                   "conditions", "a load (ground motion) that starts at zero, e.g. '-prependZero' or a first "
                   "sample 0")

    def _check_gaps(self):
        """An ElasticPPGap whose force reaches its yield force is refused (its yielding is not modelled)."""
        b = self.built
        gaps = getattr(b, "_gaps", None)
        if gaps is None:                                 # (tag, k, material) of the gaps, listed once per model
            gaps = b._gaps = [(tag, k, material) for tag, table in b.springs.items()
                              for k, (material, *_) in enumerate(table) if material.kind == "ElasticPPGap"]
        if not gaps:
            return
        springs = spring_state(self)
        forces, columns = springs["f"][0], springs.table.columns
        for tag, k, material in gaps:
            f = float(forces[columns[tag].start + k])
            if abs(f) > abs(material.Fy) * (1 + 1e-12):
                refuse(f"ElasticPPGap of element {tag}", f"its force {f:.6g} passed its yield force "
                       f"{material.Fy:.6g} at time {self.domain.time:g}: the yielding of a gap is not in this "
                       "slice", "a larger Fy (an elastic gap) or ENT")


def _check_loaded(b, d, p, f):
    """Refuse a nodal load on a DOF that is neither a DOF of the model nor fixed."""
    moved = np.asarray(abs(b.P).sum(axis=1)).ravel() > 0
    for node, values in p.loads:
        for k in range(b.ndf):
            fixed = d.fixes.get(node, (0,) * b.ndf)[k]
            if values[k] and not moved[b.row[node] + k] and not fixed:
                refuse(f"load({node})", f"DOF {k + 1} of node {node} is not a DOF of the model: nothing stiffens "
                       "it (a rotation without a beam or a rotational spring)", "a load on a DOF an element "
                       "resists")
