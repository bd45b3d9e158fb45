"""The result of a pushover: the capacity curve and the state at every event, exactly.

Between two consecutive points of the path every quantity is linear in the path parameter, so
:meth:`PushoverResult.sample` gives the exact state at any number of points by linear
interpolation.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np


class Event(NamedTuple):
    """One change of a constraint's state along the path.

    Attributes
    ----------
    load_factor : float, the load factor at the event (1)
    displacement : float, the control displacement at the event (length or rad)
    name : str, the constraint (``"h1.plastic+"``, ``"s1"``, ...)
    kind : str, ``"yield"`` (a plastic multiplier starts to grow), ``"unload"`` (it stops: elastic
        unloading, or a slip that sticks), ``"uplift"`` (a contact opens: its force has vanished),
        ``"contact"`` (an open contact closes) or ``"slip"`` (a friction slip starts)
    point : int, the index of the event's point along the path (-1: not given)
    """

    load_factor: float
    displacement: float
    name: str
    kind: str
    point: int = -1


@dataclass
class PushoverResult:
    """A static pushover: the path from the gravity state, at its start, every event and its end.

    Attributes
    ----------
    success : bool, the target was reached
    message : str, what happened (a mechanism under load control: ``"mechanism at load factor ..."``)
    stats : dict, ``events``, ``points``, ``rate_problems``, ``lcp_iterations``, ``max_residual``
        (relative equilibrium error ``|K u - q0 - lambda p - F v| / |K u|`` over the points),
        ``max_lcp_error`` (constraint violations over the size of ``psi`` and ``v``), ``mechanism``,
        ``control``, ``time`` (s)
    parameter : (P,) the path parameter: the load factor (load control) or the distance of the
        control DOF from its gravity value (displacement control)
    load_factor : (P,) lambda, the multiplier of the pattern (1)
    displacement : (P,) the control DOF (length or rad), gravity's part included
    base_shear : (P,) ``lambda r^T p``: the resultant of the applied pattern along the direction
        ``r`` of ``dof`` (force), which by the static equilibrium is minus the resultant of the
        reactions along it (gravity acts across it and adds nothing)
    u : (P, n) every DOF at each point
    v : (P, m) constraint unknowns at each point (openings, plastic multipliers, slips)
    psi : (P, m) constraint functions ``P psi`` at each point (contacts: the reaction, ``<= 0``;
        yield and friction: the yield function, ``<= 0``)
    events : list of :class:`Event`, in path order
    pattern : (n,) the lateral load vector ``p`` (force)
    gravity : (n,) the gravity load (force), zero without gravity
    dof_names : (n,) str;  constraint_names : (m,) str;  control_dof : str (``"node.dof"``)
    """

    success: bool
    message: str
    stats: dict
    parameter: np.ndarray
    load_factor: np.ndarray
    displacement: np.ndarray
    base_shear: np.ndarray
    u: np.ndarray
    v: np.ndarray
    psi: np.ndarray
    events: list = field(default_factory=list)
    pattern: np.ndarray | None = None
    gravity: np.ndarray | None = None
    dof_names: tuple = ()
    constraint_names: tuple = ()
    control_dof: str = ""

    def sample(self, count: int) -> PushoverResult:
        """The same path at ``count`` (>= 2) equally spaced values of :attr:`parameter` (exact:
        the path is linear between its points). Events and stats are those of the path."""
        count = int(count)
        if count < 2:
            raise ValueError(f"count must be at least 2, got {count}")
        t = np.linspace(self.parameter[0], self.parameter[-1], count)
        return replace(self, parameter=t, **{name: self._interp(t, getattr(self, name))
                                             for name in ("load_factor", "displacement", "base_shear", "u", "v",
                                                          "psi")})

    def at(self, parameter) -> dict:
        """The state at the path parameter(s) ``parameter`` (scalar or (k,)): a dict of
        ``load_factor``, ``displacement``, ``base_shear``, ``u``, ``v``, ``psi`` interpolated exactly."""
        t = np.asarray(parameter, dtype=float)
        return {name: self._interp(t, getattr(self, name))
                for name in ("load_factor", "displacement", "base_shear", "u", "v", "psi")}

    def _interp(self, t, y):
        """Piecewise-linear interpolation of ``y`` (P, ...) along :attr:`parameter` at ``t``."""
        y = np.asarray(y, dtype=float)
        flat = y.reshape(y.shape[0], -1)
        cols = np.stack([np.interp(np.ravel(t), self.parameter, flat[:, k]) for k in range(flat.shape[1])], axis=-1)
        return cols.reshape(np.shape(t) + y.shape[1:])

    def events_of(self, kind: str) -> list:
        """The events of one kind (``"yield"``, ``"unload"``, ``"uplift"``, ``"contact"``, ``"slip"``)."""
        return [e for e in self.events if e.kind == kind]

    def table(self) -> str:
        """The capacity curve as a text table: point, load factor, control displacement, base shear,
        and the events at each point."""
        lines = [f"{'point':>5} {'load factor':>14} {self.control_dof + ' disp.':>14} {'base shear':>14}  events"]
        for k, (lam, d, V) in enumerate(zip(self.load_factor, self.displacement, self.base_shear)):
            here = [f"{e.kind} {e.name}" for e in self.events
                    if e.point == k or (e.point < 0 and e.load_factor == lam and e.displacement == d)]
            lines.append(f"{k:>5} {lam:>14.6g} {d:>14.6g} {V:>14.6g}  {', '.join(here)}")
        return "\n".join(lines)
