"""The analysis of a script with extensions: footings on a soil medium and the bilateral reference.

A frame with an ``ops.footing`` on a soil medium is a :class:`~unilateral.soil.FoundationModel`
(:func:`.soil_model.on_soil`: the script's model on its reduced DOFs, the footings' ``T`` through the ties). The
soil remembers the motion (its flexibility is a convolution), so a transient analysis is one
:class:`~unilateral.Simulation` from where it starts (``method="auto"``: ``"cq"`` on a half-space
or a layered soil, ``"modal"`` on cones and Winkler-Kelvin patches; Newmark ``0.5, 0.25`` only,
the trapezoidal rule of the convolution quadrature): from rest (no load at its start) or from
the static state under the load at its start (``initial="static"``, the state of a static
analysis: the soil's static flexibility ``Phi(0)``). When its horizon is used up the simulation is
solved again from the same start over a longer horizon (the first steps agree to round-off). A
static analysis solves the static problem with ``Phi(0)`` (``FoundationModel.static_model``).

A frame with an ``ops.rigidContact`` is stepped by Moreau-Jean's theta-method (``method="moreau-jean"``,
theta = 1/2 for Newmark 0.5, 0.25) with Newton's impact law, from the current state.

``bilateral(1)``: every simulation holds the constraints at the state it starts from
(``bilateral=True`` of :func:`unilateral.solve`, the model files' ``bilateral_reference``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..constraints import RigidContact as RigidFamily
from ..lcp import get_lcp_solver
from ..methods.foundation_solve import foundation_base_state, primal_columns
from ..soil.foundation_model import FoundationModel
from ..solve import Simulation
from .refusals import OpenSeesRefused, refuse
from .stepping import Analysis

__all__ = ["ExtendedAnalysis"]

_START = ("a transient analysis from rest (no load at its start) or right after a static analysis under the "
          "load it starts with")


class ExtendedAnalysis(Analysis):
    """:class:`~.stepping.Analysis` with footings on a soil medium and the bilateral reference."""

    def wipe(self):
        """Forget the model, the state and the settings (``wipe``); the bilateral reference is off."""
        self.bilateral = False
        self.static_result = None
        super().wipe()

    def _soil(self) -> bool:
        return isinstance(getattr(self.built, "model", None), FoundationModel)

    # ------------------------------------------------------------------ state carried on a rebuild
    def _carry(self, old, state):
        if not self._soil():
            return super()._carry(old, state)
        b = self.built
        soil_model = b.model
        b.model = b.frame_model
        try:
            super()._carry(old, state)
        finally:
            b.model = soil_model
        frame_v = self.v
        v = np.zeros(soil_model.m)
        v[:frame_v.size] = frame_v
        contacts = soil_model.contacts
        v[contacts] = np.maximum(np.asarray(soil_model.T.T @ self.u).ravel() + soil_model.gap, 0.0)
        if old is not None:
            at = {name: k for k, name in enumerate(old.model.constraint_names)}
            for k, name in enumerate(soil_model.constraint_names[frame_v.size:], start=frame_v.size):
                if name in at:
                    v[k] = state[3][at[name]]
        self.v = v

    # ------------------------------------------------------------------ static
    def _static_state(self, q):
        if self._rigid():
            try:
                state = super()._static_state(q)
            except ValueError as exc:
                raise OpenSeesRefused("analyze (Static) with a rigid contact", f"no static state: {exc}",
                                      "a transient analysis from rest (the body settles on its contacts), or "
                                      "a spring that holds it") from None
        elif not self._soil():
            state = super()._static_state(q)
        else:                        # the library's static start of a footing (the soil's Phi(0)), in its columns
            model = self.built.model
            load = q - model.q_imposed(self.domain.time)
            state = foundation_base_state(model, load, "static", get_lcp_solver("bpp"))
            v, psi = primal_columns(model, state.v, state.psi)
            state = replace(state, v=np.asarray(v), psi=np.asarray(psi))
        self.static_result = state
        return state

    # ------------------------------------------------------------------ transient
    def analyze(self, steps=1, dt=None):
        """``analyze(numIncr, dt)``; a footing on the soil's simulation starts with a horizon of
        ``numIncr`` steps (its soil's weights are computed for the horizon)."""
        self._asked = int(steps)
        return super().analyze(steps, dt)

    def _start(self, key, dt, horizon, gamma, beta):
        if self._rigid():
            return self._start_rigid(key, dt, horizon, (gamma, beta))
        if not self._soil():
            return super()._start(key, dt, horizon, gamma, beta)
        if (gamma, beta) != (0.5, 0.25):
            refuse(f"integrator('Newmark', {gamma!r}, {beta!r}) with a footing on a soil medium", "the soil's "
                   "convolution is marched by the trapezoidal rule (or BDF) only", "integrator('Newmark', 0.5, 0.25)")
        d = self.domain
        old = self.sim
        if old is not None and old["key"] == key and old["sim"].n == old["sim"].N and \
                old["times"][old["sim"].n] == d.time:                 # go on: the same start, a longer horizon
            segment = old["segment"]
            done = old["sim"].n
        else:
            segment = {"t0": d.time, "initial": self._initial()}
            done, horizon = 0, max(getattr(self, "_asked", 1), 1)
        total = done + horizon
        times = np.cumsum(np.r_[segment["t0"], np.full(total, dt)])
        q = self.load(times)
        try:
            sim = Simulation(self.built.model, q, dt=dt, t_end=total * dt, method="auto", rule="trapezoidal",
                             initial=segment["initial"], bilateral=self.bilateral)
        except ValueError as exc:
            raise OpenSeesRefused("analyze (Transient)", f"the footing on the soil cannot start: {exc}",
                                  _START) from None
        if done:
            sim.advance(done)
        return {"key": key, "sim": sim, "times": times, "segment": segment}

    def _rigid(self) -> bool:
        return any(isinstance(f, RigidFamily) for f in getattr(getattr(self.built, "model", None), "families", ()))

    def _start_rigid(self, key, dt, horizon, newmark):
        """A Moreau-Jean simulation (the theta-method, theta = 1/2) of ``horizon`` steps from the state."""
        if newmark != (0.5, 0.25):
            refuse(f"integrator('Newmark', {newmark[0]!r}, {newmark[1]!r}) with a rigid contact", "rigid contacts "
                   "are stepped by Moreau-Jean's theta-method with Newton's impact law; Newmark 0.5, 0.25 is its "
                   "theta = 1/2", "integrator('Newmark', 0.5, 0.25)")
        model, d = self.built.model, self.domain
        times = np.cumsum(np.r_[d.time, np.full(horizon, dt)])
        q = self.load(times)
        self._check_acceleration(q[0] + model.q_imposed(d.time))
        try:
            sim = Simulation(model, q, dt=dt, t_end=horizon * dt, method="moreau-jean", rule="trapezoidal",
                             initial={"u0": self.u, "udot0": self.ud}, bilateral=self.bilateral)
        except ValueError as exc:
            raise OpenSeesRefused("analyze (Transient)", f"the state cannot start a simulation: {exc}",
                                  "a consistent state (start from rest or from a static analysis)") from None
        return {"key": key, "sim": sim, "times": times}

    def _initial(self):
        """``"rest"`` or ``"static"``: the start of a simulation of a footing on the soil."""
        model = self.built.model
        q0 = self.load([self.domain.time])[0] + model.q_imposed(self.domain.time)
        scale = max(float(np.abs(self.u).max(initial=0.0)), 1e-300)
        if not np.any(self.u) and not np.any(self.ud) and not np.any(q0):
            return "rest"
        if np.any(self.ud):
            refuse("analyze (Transient) with a footing on a soil medium", "the state moves: the soil's memory of "
                   "an earlier transient is not carried into a new analysis (a change of dt, of the loads or of "
                   "the model)", _START)
        static = self._static_state(q0)
        if np.abs(static.u - self.u).max() > 1e-9 * scale:
            refuse("analyze (Transient) with a footing on a soil medium", "the state is not the static state under "
                   f"the load at t = {self.domain.time:g}", _START)
        return "static"
