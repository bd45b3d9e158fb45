"""Runs that advance on request: what a method's :meth:`~unilateral.methods.Method.start` returns.

A run holds a march begun at step 0 and performs its steps when asked
(:meth:`extend`); :class:`~unilateral.simulation.Simulation` steps through it and
:func:`unilateral.solve` extends it to the end at once. Every run has

* ``N`` (the steps of the grid), ``done`` (the last step performed) and ``failure`` (why step
  ``done + 1`` failed, "" if none did);
* ``extend(k) -> done``: perform the steps up to ``k`` at least (a run may compute ahead);
* ``state(k) -> State``: the state after step ``k <= done``;
* ``solution(K) -> Solution``: the steps ``0..K`` as a :class:`~unilateral.result.Solution`.

:class:`MarchRun` steps a matrix model's direct march (:mod:`unilateral.march.direct`);
:class:`SolvedRun` wraps a method that marches all its steps in one call: its march is performed
at the first :meth:`~SolvedRun.extend` (``stats["stepping"] = "whole"``).
"""

from __future__ import annotations

import copy

import numpy as np

from ..result import Solution, State
from .common import finish


class WholeMarch:
    """A march performed in one call, ``march() -> (du, dudot, v, psi, log)``, at the first request.

    The interface of :class:`~unilateral.march.direct.DirectMarch` for the marches that do not
    step (the full sparse space, the bilateral sweep).
    """

    def __init__(self, march, N):
        self._march, self.N = march, N
        self.done, self.failure, self._out = 0, "", None

    def extend(self, k: int) -> int:
        if self._out is None and k > 0:
            self._out = self._march()
            self.done = self._out[2].shape[0] - 1
            self.failure = self._out[4].failure
        return self.done

    def outputs(self):
        if self._out is None:
            raise RuntimeError("the march has not been performed (extend it first)")
        return self._out


class MarchRun:
    """A matrix model's direct march as a run (see the module's docstring).

    Parameters
    ----------
    model : Model;  run : RunContext;  disc : Discretization
    init : InitialState, the base state (the march steps ``du = u - u_b``, ``u_b = init.u``)
    march : DirectMarch, CompiledDirectMarch or WholeMarch
    stepping : str, how the march advances (``"step"``, ``"chunk"`` or ``"whole"``), in the stats
    """

    def __init__(self, model, run, disc, init, march, stepping):
        self.model, self.run, self.disc, self.march = model, run, disc, march
        self.init, self.u_b = init, init.u
        self.N = disc.N
        run.stats["stepping"] = stepping

    @property
    def done(self) -> int:
        return self.march.done

    @property
    def failure(self) -> str:
        return self.march.failure

    def extend(self, k: int) -> int:
        done = self.march.extend(k)
        if done >= self.N or self.march.failure:
            self.run.timer.lap("steps")
        return done

    def state(self, k: int) -> State:
        if k == 0 and self.march.done == 0:            # before the first step (a march not begun)
            init = self.init
            udot = np.zeros_like(init.u) if init.udot is None else init.udot
            return State(t=0.0, k=0, u=init.u.copy(), udot=np.array(udot), v=init.v.copy(),
                         psi=self.model.law.rows(init.psi).copy())
        du, dud, v, psi = self._rows(k)
        return State(t=float(self.disc.t[k]), k=k, u=self.u_b + du, udot=dud.copy(), v=v.copy(),
                     psi=psi.copy())

    def _rows(self, k):
        du, dud, v, psi = self.march.outputs()[:4]
        return du[k], dud[k], v[k], psi[k]

    def solution(self, K: int) -> Solution:
        du, dud, v, psi, log = self.march.outputs()
        K1 = K + 1
        run = copy.copy(self.run)
        run.stats = dict(self.run.stats)
        return finish(self.model, run, log if K == self.done else _without_failure(log),
                      t=self.disc.t[:K1], v=v[:K1], psi=psi[:K1], u=self.u_b + du[:K1], udot=dud[:K1])


def _without_failure(log):
    """The log of a solution cut before the march's last step done: no failure yet (its LCP
    statistics are those of the steps done)."""
    cut = copy.copy(log)
    cut.failure = ""
    return cut


class SolvedRun:
    """A run of a method that marches in one call: ``solve() -> Solution`` at the first extend."""

    def __init__(self, solve, N, *, solution=None):
        self._solve, self.N, self._sol = solve, N, solution
        self.done, self.failure = 0, ""
        if solution is not None:
            self._take(solution)

    @classmethod
    def of(cls, solution, N) -> SolvedRun:
        """The run of a solution already computed (e.g. a run that failed at its start)."""
        return cls(None, N, solution=solution)

    def _take(self, sol):
        self._sol = sol
        sol.stats.setdefault("stepping", "whole")
        self.done = len(sol.t) - 1
        self.failure = "" if sol.success else sol.message

    def extend(self, k: int) -> int:
        if self._sol is None and k > 0:
            self._take(self._solve())
        return self.done

    def state(self, k: int) -> State:
        if self._sol is None:
            self.extend(self.N)
        sol = self._sol
        pick = lambda h: None if h is None else np.array(h[k])
        return State(t=float(sol.t[k]), k=k, u=pick(sol.u), udot=pick(sol.udot), v=pick(sol.v),
                     psi=pick(sol.psi))

    def solution(self, K: int) -> Solution:
        if self._sol is None:
            self.extend(self.N)
        sol = self._sol
        if K == len(sol.t) - 1:
            return sol
        cut = lambda h: None if h is None else h[: K + 1]
        stats = dict(sol.stats, steps_done=K)
        return Solution(t=sol.t[: K + 1], v=sol.v[: K + 1], psi=sol.psi[: K + 1], psiL=cut(sol.psiL),
                        u=cut(sol.u), udot=cut(sol.udot), success=True,
                        message=f"{K} of {self.N} steps so far", stats=stats,
                        dof_names=list(sol.dof_names), constraint_names=list(sol.constraint_names))
