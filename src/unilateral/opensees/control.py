"""``integrator('DisplacementControl', node, dof, incr)`` on a ``Static`` analysis, by the path
following of :func:`unilateral.pushover.pushover`.

OpenSees's displacement control makes the domain time ``lambda`` a free unknown and prescribes
``u_c`` (``incr`` per step); the loads are those of the patterns at time ``lambda``. Here the patterns
that follow the time must be ``Plain`` ones of ``Linear`` series (the reference load
``p = sum factor * cFactor * f``); those held by ``loadConst`` (gravity) are the constant load
``q_0``. The static path from the state at the first step (which must be the static state under
``q_0 + t_0 p`` with no plastic deformation: a pushover from gravity) is followed exactly, event by
event (yielding, uplift, contact), and each step returns the point of the path where ``u_c`` has
advanced by ``incr``: the same state OpenSees converges to at each step of a monotonic pushover.
A step that reverses ``incr`` (unloading) is refused: the path followed is the monotonic one.
"""

from __future__ import annotations

import numpy as np

from .eleloads import pattern_forces
from .refusals import refuse

__all__ = ["parse_displacement_control", "DisplacementPath"]

_ALTERNATIVE = "integrator('DisplacementControl', node, dof, incr) after loadConst of the gravity, with Linear " \
               "Plain patterns, increments of one sign"


def parse_displacement_control(what, args):
    """``(node, dof, incr)`` of ``integrator('DisplacementControl', node, dof, incr[, numIter, dUmin, dUmax])``."""
    if len(args) < 3 or any(isinstance(a, str) for a in args[:3]):
        refuse(what, "node, dof and incr are needed", "integrator('DisplacementControl', node, dof, incr)")
    node, dof, incr = int(args[0]), int(args[1]), float(args[2])
    if incr == 0.0:
        refuse(what, "incr = 0 does not move the control DOF", "incr != 0")
    if len(args) > 4 and any(float(a) != incr for a in args[4:6]):
        refuse(what, "an automatic increment (dUmin, dUmax different from incr) is not in the subset",
               "integrator('DisplacementControl', node, dof, incr)")
    return node, dof, incr


class DisplacementPath:
    """The monotonic static path of one displacement-controlled analysis (see the module)."""

    def __init__(self, analysis, node, dof, incr):
        self.analysis, self.incr = analysis, incr
        b, d = analysis.built, analysis.domain
        self.key = (analysis.built_version, d.load_version, node, dof)
        self.c = _control_index(b, d, node, dof)
        self.p, q0 = _loads(analysis)
        self.t0, self.u0, self.start = d.time, float(analysis.u[self.c]), np.array(analysis.u, dtype=float)
        self.q_g = q0 + self.t0 * self.p
        model = b.model
        if np.any(analysis.v[model.law.rate] != 0):
            refuse("analyze (DisplacementControl)", "the state has plastic deformations: the path followed here "
                   "starts from the virgin static state", "a displacement control right after the gravity analysis")
        self.sign = 1.0 if incr > 0 else -1.0
        self.result, self.reach = None, 0.0

    def _follow(self, distance):
        """The path to ``distance`` beyond the start (at least), from the start state."""
        from ..pushover import pushover

        model = self.analysis.built.model
        reach = max(distance, 2.0 * self.reach, 16 * abs(self.incr))
        target = self.u0 + self.sign * reach
        errors = []
        for s in (1.0, -1.0):                       # the pattern pushes the DOF one way or the other
            try:
                r = pushover(model, s * self.p, node=self.c, target=target, gravity=self.q_g,
                             control="displacement", max_events=100_000)
            except ValueError as exc:
                errors.append(str(exc))
                continue
            if not r.success:
                refuse("analyze (DisplacementControl)", f"the path cannot be followed: {r.message}", _ALTERNATIVE)
            self.result, self.scale, self.reach = r, s, reach
            self._check_start()
            return
        refuse("analyze (DisplacementControl)", f"no static path from the state: {'; '.join(errors)}", _ALTERNATIVE)

    def _check_start(self):
        u = self.result.u[0]
        if np.abs(u - self.start).max() > 1e-8 * max(np.abs(u).max(), 1e-300):
            refuse("analyze (DisplacementControl)", "the state is not the static state under the loads held "
                   "(loadConst) and the Linear patterns at the current time", _ALTERNATIVE)

    def step(self) -> dict:
        """The state one ``incr`` further: ``u``, ``v`` and the domain time ``lambda``."""
        a = self.analysis
        distance = self.sign * (float(a.u[self.c]) + self.incr - self.u0)
        if distance < -1e-12 * abs(self.incr) or self.sign * self.incr < 0:
            refuse("analyze (DisplacementControl) reversing", "unloading leaves the monotonic path followed "
                   "here", _ALTERNATIVE)
        if self.result is None or distance > self.reach * (1 + 1e-12):
            self._follow(distance)
        at = self.result.at(distance)
        return {"u": at["u"], "v": at["v"], "time": self.t0 + self.scale * float(at["load_factor"])}


def _control_index(b, d, node, dof):
    what = f"integrator('DisplacementControl', {node}, {dof}, ...)"
    if node not in d.nodes or dof not in range(1, d.ndf + 1):
        refuse(what, f"node {node} or DOF {dof} is not defined", "a defined node and a DOF 1..ndf")
    row = b.P.getrow(b.row[node] + dof - 1)
    if row.nnz != 1 or row.data[0] != 1.0:
        refuse(what, f"DOF {dof} of node {node} is not a DOF of the model (fixed, or following a rigid link)",
               "a free DOF")
    return int(row.indices[0])


def _loads(analysis):
    """The reference load ``p`` (of the Linear patterns) and the held load ``q_0`` (reduced)."""
    b, d = analysis.built, analysis.domain
    p, q0 = np.zeros(b.model.n), np.zeros(b.model.n)
    for tag, pat in d.patterns.items():
        if pat.frozen is None and (pat.kind != "Plain" or d.series[pat.series].kind != "Linear"):
            refuse(f"analyze (DisplacementControl) with pattern {tag}", "only Plain patterns of Linear series "
                   "(and patterns held by loadConst) are loads of a displacement control here", _ALTERNATIVE)
        f = pattern_forces(b, d, pat) if pat.kind == "Plain" else np.zeros(b.mass.size)
        if pat.frozen is not None:
            q0 += pat.frozen * b.reduced(f)
        else:
            p += pat.factor * d.series[pat.series].factor * b.reduced(f)
    if not np.any(p):
        refuse("analyze (DisplacementControl)", "no load follows the time (every pattern is held)", _ALTERNATIVE)
    return p, q0
