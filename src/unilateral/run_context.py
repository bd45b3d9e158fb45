"""What a run carries besides the problem and the grid: :class:`RunContext`."""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field

from .lcp import LCPSolver, get_lcp_solver


class Timer:
    """Wall time per phase: ``lap(name)`` adds the time since the previous lap to ``name``."""

    def __init__(self):
        self._start = self._last = time.perf_counter()
        self._laps = {}

    def lap(self, name: str) -> None:
        now = time.perf_counter()
        self._laps[name] = self._laps.get(name, 0.0) + now - self._last
        self._last = now

    def laps(self) -> dict:
        """Seconds per phase and ``total`` since the timer started."""
        out = dict(self._laps)
        out["total"] = time.perf_counter() - self._start
        return out


@dataclass
class RunContext:
    """The LCP solver, the bilateral switch, the progress callback, and the run's statistics.

    Attributes
    ----------
    solver : LCPSolver
        Solves the LCP of every step (and the static one).
    bilateral : bool
        Hold every constraint at its initial state (``v = v(0)``): the "without uplift" case.
    callback : callable ``callback(k, N)`` or None
        Called after steps (progress bars).
    stats : dict
        Filled by the method; becomes ``Solution.stats``.
    timer : Timer
        Wall time per phase; becomes ``stats["time"]``.
    """

    solver: LCPSolver
    bilateral: bool = False
    callback: Callable | None = None
    stats: dict = field(default_factory=dict)
    timer: Timer = field(default_factory=Timer)

    @classmethod
    def from_user(cls, lcp="bpp", lcp_options=None, bilateral=False, callback=None) -> RunContext:
        """Resolve the LCP solver (name or object, with options) and check the switches."""
        if callback is not None and not callable(callback):
            raise TypeError(f"callback must be callable callback(k, N) or None, got {callback!r}")
        return cls(solver=get_lcp_solver(lcp, **(lcp_options or {})), bilateral=bool(bilateral),
                   callback=callback)
