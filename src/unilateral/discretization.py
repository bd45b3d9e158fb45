"""The time grid and the rule of an analysis: :class:`Discretization`."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import _validate as V
from .rules import Rule, get_rule

#: Most time steps of one analysis: beyond this, ``t_end / dt`` is a mistake (units, a typo).
MAX_STEPS = 10**9


def step_count(t_end: float, dt: float) -> int:
    """The number of steps ``round(t_end / dt)``, refused beyond :data:`MAX_STEPS`.

    Parameters
    ----------
    t_end, dt : float
        End time and time step, both finite and > 0.

    Returns
    -------
    int

    Raises
    ------
    ValueError
        ``t_end / dt`` is not finite or exceeds :data:`MAX_STEPS`; the message names both values.
    """
    ratio = t_end / dt
    if not ratio <= MAX_STEPS:                  # also inf and nan
        raise ValueError(f"t_end={t_end!r} with dt={dt!r} gives t_end/dt = {ratio:.3g} steps, more than the "
                         f"{MAX_STEPS:.0e} an analysis may have: shorten t_end or increase dt")
    return int(round(ratio))


@dataclass(frozen=True)
class Discretization:
    """``N`` steps of ``dt`` on ``t_k = k dt``, k = 0..N, with a time-discretisation rule.

    Attributes
    ----------
    dt : float
        Time step, s (in the model's time unit).
    N : int
        Number of steps, ``round(t_end / dt)``.
    rule : Rule
        BDF1, BDF2, trapezoidal (also convolution quadrature) or a Newmark/HHT rule (direct only).
    """

    dt: float
    N: int
    rule: Rule

    @classmethod
    def from_user(cls, dt, t_end, rule="bdf2") -> Discretization:
        """Check ``dt`` and ``t_end`` (floats > 0, ``dt <= t_end``, at most :data:`MAX_STEPS` steps)
        and resolve ``rule`` (name or Rule)."""
        dt = V.positive_float("dt", dt)
        t_end = V.positive_float("t_end", t_end)
        if t_end < dt * (1 - 1e-12):
            raise ValueError(f"t_end={t_end!r} must be >= dt={dt!r}")
        return cls(dt=dt, N=step_count(t_end, dt), rule=get_rule(rule))

    @property
    def t(self) -> np.ndarray:
        """The grid ``t_k = k dt``, shape (N+1,)."""
        return self.dt * np.arange(self.N + 1)

    @property
    def t_end(self) -> float:
        return self.N * self.dt
