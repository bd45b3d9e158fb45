"""A reference for the rocking of a rigid rectangular block: Housner's equation integrated with
``scipy.integrate.solve_ivp``, independent of the package's own marches.

It is a *reference* for the tests and the examples (``tests/test_rocking_reference.py``,
``examples/overturning_map.py``), not a method of the package: one scalar equation, a free-standing
block whose base does not slide or bounce, on a base shaken horizontally by ``a_g(t)``.

The equation (Housner 1963), with the package's signs (the tilt ``theta`` counter-clockwise; a base
acceleration ``a_g > 0`` puts the inertia force ``-m a_g`` on the centre and tips the block to
``theta > 0``, pivoting on its left corner), ``s = sgn(theta)`` the side it pivots on:

    nonlinear:   theta'' = -p^2 (sin(alpha s - theta) - (a_g / g) cos(alpha s - theta))
    linearised:  theta'' = p^2 cos(alpha) (theta - s tan(alpha) + a_g / g)

``p^2 = g R / i0`` (``i0 = I0 / m`` the rotary inertia about a corner over the mass, ``4 R^2 / 3``
for a uniform rectangle), ``R = sqrt(b^2 + h^2)``, ``tan(alpha) = b / h``. The linearised equation
is the first order in ``theta`` of the nonlinear one, with the exact coefficients
``R sin(alpha) = b``, ``R cos(alpha) = h`` (and the term ``a_g theta sin(alpha)`` dropped): that of
``Frame2D.rigid_block`` (``docs/rocking.md``), whose frequency parameter ``RigidBlock.p`` is
``p sqrt(cos(alpha))``. Housner's sign is the opposite one (``theta_Housner = -theta``, or
``a_g`` for ``-u_g''``).

* The block lifts when ``|a_g| > g tan(alpha)`` (both equations); until then it rests.
* Impact at ``theta = 0``: the pivot changes and ``theta' -> r theta'`` (Housner's
  ``r = 1 - 2 b^2 / i0``, ``1 - 3/2 sin^2(alpha)`` for the uniform rectangle).
* Overturning: the tilt passes the unstable equilibrium of the free block, ``alpha`` (nonlinear) or
  ``tan(alpha) = b / h`` (linearised). With ``criterion="tilt"`` the first passing is the overturn
  (as ``examples/overturning_map.py`` and ``block_results`` take it); with ``criterion="free"`` the
  integration goes on while the base still moves (a pulse can pull the block back) and the block
  overturns when it passes the equilibrium outwards once the base is at rest (``pulse_end``), or
  reaches ``pi / 2``. After ``pulse_end`` a block whose energy is below the equilibrium's cannot
  overturn any more (free rocking conserves it, the impacts lose it): the run ends there.

Functions: :class:`ReferenceBlock`, :func:`rocking_response` (a :class:`RockingResponse`),
:func:`one_sine_class` (the class of one point of an overturning map).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from .rigid import one_sine_pulse, rocking_onset_phase

STANDARD_GRAVITY = 9.80665


@dataclass(frozen=True)
class ReferenceBlock:
    """A rigid rectangular block ``2b`` wide and ``2h`` tall (length), gravity ``g``.

    Parameters
    ----------
    b, h : half width and half height, > 0
    g : gravity, length/time^2
    i0 : rotary inertia about a base corner over the mass (length^2); None: the uniform
        rectangle's ``4 (b^2 + h^2) / 3``
    """

    b: float
    h: float
    g: float = STANDARD_GRAVITY
    i0: float | None = None

    @property
    def R(self) -> float:
        """Distance from a base corner to the centre of mass."""
        return math.hypot(self.b, self.h)

    @property
    def inertia(self) -> float:
        """``i0`` (the uniform rectangle's when not given)."""
        return 4.0 * self.R ** 2 / 3.0 if self.i0 is None else float(self.i0)

    @property
    def alpha(self) -> float:
        """Slenderness angle ``atan(b / h)``, rad."""
        return math.atan2(self.b, self.h)

    @property
    def p(self) -> float:
        """Housner's frequency parameter ``sqrt(g R / i0)`` (``sqrt(3 g / (4 R))``), rad/time."""
        return math.sqrt(self.g * self.R / self.inertia)

    @property
    def p_linear(self) -> float:
        """The linearised equation's ``p sqrt(cos(alpha)) = sqrt(g h / i0)`` (``RigidBlock.p``)."""
        return math.sqrt(self.g * self.h / self.inertia)

    @property
    def restitution(self) -> float:
        """Housner's ratio of the angular velocities after/before an impact, ``1 - 2 b^2 / i0``."""
        return 1.0 - 2.0 * self.b ** 2 / self.inertia

    @property
    def uplift_acceleration(self) -> float:
        """``g tan(alpha) = g b / h``: the base acceleration that lifts the block."""
        return self.g * self.b / self.h


@dataclass
class RockingResponse:
    """A run of :func:`rocking_response`.

    Attributes
    ----------
    start : time the block first lifts (None: it never does)
    impacts : list of ``(time, omega_before, omega_after)``
    overturned : bool;  overturn_time : time of the overturn (None)
    tilt_time : first time ``|theta|`` passed the equilibrium (``alpha`` or ``tan alpha``; None)
    peak_rotation : largest ``|theta|`` before the end (or the overturn)
    end : time the run ended (``t_end``, the overturn, or the end of the pulse once the block
        cannot overturn any more)
    mode : ``"rest"``, ``"rocks"``, ``"mode 1"`` (overturns after impacts), ``"mode 2"`` (no impact)
    """

    start: float | None = None
    impacts: list = field(default_factory=list)
    overturned: bool = False
    overturn_time: float | None = None
    tilt_time: float | None = None
    peak_rotation: float = 0.0
    end: float = 0.0
    pieces: list = field(default_factory=list, repr=False)

    @property
    def mode(self) -> str:
        if self.overturned:
            return "mode 1" if self.impacts else "mode 2"
        return "rocks" if self.start is not None else "rest"

    @property
    def impact_times(self) -> np.ndarray:
        return np.array([i[0] for i in self.impacts])

    def state(self, t) -> np.ndarray:
        """``(2, len(t))``: ``theta`` and ``theta'`` at the times ``t`` (0 at rest; NaN after ``end``).
        At an impact time the value after it."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        out = np.zeros((2, t.size))
        end = self.end + 1e-12 * max(1.0, abs(self.end))           # a grid's last time, rounded
        out[:, t > end] = np.nan
        for k, (t0, t1, dense) in enumerate(self.pieces):
            inside = (t >= t0) & (t <= (end if k == len(self.pieces) - 1 else t1))
            if inside.any():
                out[:, inside] = dense(t[inside])
        return out


def _rhs(block, a_g, side, linear):
    p2, g, alpha = block.p ** 2, block.g, block.alpha
    if linear:
        q2, a = block.p_linear ** 2, math.tan(alpha)
        return lambda t, y: (y[1], q2 * (y[0] - side * a + a_g(t) / g))
    return lambda t, y: (y[1], -p2 * (math.sin(alpha * side - y[0]) - a_g(t) / g * math.cos(alpha * side - y[0])))


def _event(fun, direction):
    fun.terminal, fun.direction = True, direction
    return fun


def _lift_time(block, a_g, t0, t_end, scan):
    """The first time after ``t0`` at which ``|a_g|`` exceeds ``g tan(alpha)`` (None)."""
    over = lambda t: abs(a_g(t)) - block.uplift_acceleration
    grid = np.arange(t0, t_end + scan, scan)
    grid[-1] = min(grid[-1], t_end)
    values = [over(t) for t in grid]
    for k, v in enumerate(values):
        if v > 0:
            return float(grid[0]) if k == 0 else brentq(over, grid[k - 1], grid[k], xtol=1e-14, rtol=1e-15)
    return None


def _energy_below_equilibrium(block, theta, omega, side, linear) -> bool:
    """Free rocking cannot take the block past the equilibrium (its energy is below it)."""
    if linear:
        return 0.5 * omega ** 2 - 0.5 * block.p_linear ** 2 * (theta - side * math.tan(block.alpha)) ** 2 < 0 \
            and abs(theta) < math.tan(block.alpha)
    return 0.5 * omega ** 2 + block.p ** 2 * math.cos(block.alpha * side - theta) < block.p ** 2 \
        and abs(theta) < block.alpha


def _phase(block, a_g, span, y, side, *, limit, past, linear, rtol, atol):
    """One rocking phase on the corner ``side`` over ``span``, to its end or the first event:
    ``(event, time, state, dense, peak)``, ``event`` 0 impact, 1 ``pi / 2``, 2 the equilibrium
    (outwards, or back in if ``past``), None the end of ``span``."""
    events = [_event(lambda _, z: side * z[0], -1), _event(lambda _, z: side * z[0] - math.pi / 2, 1),
              _event(lambda _, z: side * z[0] - limit, -1 if past else 1)]
    sol = solve_ivp(_rhs(block, a_g, side, linear), span, y, method="DOP853", rtol=rtol, atol=atol, events=events,
                    dense_output=True)
    if sol.status < 0:
        raise RuntimeError(f"rocking_response: solve_ivp failed at t = {sol.t[-1]!r}: {sol.message}")
    hit = next((k for k in range(3) if sol.t_events[k].size), None)
    t, y = (sol.t_events[hit][0], sol.y_events[hit][0].copy()) if hit is not None else (span[1], sol.y[:, -1].copy())
    return hit, t, y, sol.sol, max(float(np.max(np.abs(sol.y[0]))), abs(float(y[0])))


def rocking_response(block, a_g, t_end, *, linear=False, pulse_end=None, criterion="tilt", settle=True,
                     theta0=0.0, omega0=0.0, rtol=1e-11, atol=1e-13, max_impacts=400) -> RockingResponse:
    """The rocking of ``block`` under the base acceleration ``a_g(t)`` until ``t_end``, from rest or
    from the tilt ``theta0`` and its rate ``omega0`` at ``t = 0``.

    Parameters
    ----------
    block : :class:`ReferenceBlock`
    a_g : callable ``a_g(t)`` (length/time^2), smooth between ``0``, ``pulse_end`` and ``t_end``
    t_end : time to stop (time)
    linear : the linearised equation (``Frame2D.rigid_block``'s) instead of Housner's nonlinear one
    pulse_end : time after which ``a_g = 0`` (a break of the integration; None: ``t_end``)
    criterion : ``"tilt"`` (the first passing of the equilibrium overturns) or ``"free"`` (see the
        module)
    theta0, omega0 : the initial state (rad, rad/time); ``theta0 = 0`` with ``omega0 != 0``
        pivots on the side ``omega0`` turns to
    settle : end the run once the base is at rest and the block cannot overturn any more (else
        follow its free rocking until ``t_end``)
    rtol, atol : of ``solve_ivp`` (``DOP853``)
    max_impacts : consecutive impacts after which the block is taken to rest (their accumulation,
        Zeno; while the base moves the run waits for the next lift)

    Returns
    -------
    RockingResponse
    """
    if criterion not in ("tilt", "free"):
        raise ValueError(f"criterion={criterion!r}; valid: 'tilt', 'free'")
    pulse_end = t_end if pulse_end is None else min(float(pulse_end), t_end)
    limit = math.tan(block.alpha) if linear else block.alpha
    r, out = block.restitution, RockingResponse()
    t, y, past, count = 0.0, np.array([theta0, omega0], dtype=float), False, 0
    side = int(np.sign(theta0 if theta0 else omega0))
    if side:
        out.start = 0.0
        if abs(theta0) >= limit:
            raise ValueError(f"rocking_response: |theta0|={abs(theta0)!r} must be below the equilibrium {limit!r}")
    scan = min(pulse_end, t_end) / 4000 if pulse_end > 0 else t_end / 4000
    while t < t_end:
        if side == 0:
            start = _lift_time(block, a_g, t, pulse_end, scan) if t < pulse_end else None
            if start is None:
                break
            out.start = start if out.start is None else out.start
            t, y, count = start, np.zeros(2), 0
            side = 1 if a_g(start + 1e-9 * scan) > 0 else -1
        stop = pulse_end if t < pulse_end else t_end
        hit, t_new, y, dense, peak = _phase(block, a_g, (t, stop), y, side, limit=limit, past=past, linear=linear,
                                            rtol=rtol, atol=atol)
        out.pieces.append((t, t_new, dense))
        out.peak_rotation = max(out.peak_rotation, peak)
        t = t_new
        if hit == 0:                                     # impact: the other corner
            out.impacts.append((t, float(y[1]), r * float(y[1])))
            y, side, count = np.array([0.0, r * y[1]]), -side, count + 1
            if count >= max_impacts:
                y, side = np.zeros(2), 0
        elif hit == 1:                                              # lies on its side
            out.overturned, out.overturn_time = True, t
            break
        elif hit == 2:                                              # the equilibrium, out or back in
            if not past:
                out.tilt_time = t if out.tilt_time is None else out.tilt_time
                if criterion == "tilt" or t >= pulse_end:
                    out.overturned, out.overturn_time = True, t
                    break
            past = not past
        if t >= pulse_end and not out.overturned:
            if past and side * y[1] > 0:                            # free and moving out past it
                out.overturned, out.overturn_time = True, t
                break
            if side == 0 or (settle and _energy_below_equilibrium(block, y[0], y[1], side, linear)):
                break
    out.end = t
    return out


def one_sine_class(block, amplitude, frequency, *, linear=False, psi=False, criterion="tilt", after=3.0,
                   normal=None) -> RockingResponse:
    """One point of the one-sine overturning map: the response to ``a_p sin(omega_p t + psi)``,
    ``0 <= t <= 2 pi / omega_p``.

    Parameters
    ----------
    block : :class:`ReferenceBlock`
    amplitude : ``a_p / (g tan alpha)``;  frequency : ``omega_p / normal``
    linear, criterion : of :func:`rocking_response`
    psi : False: ``psi = 0`` (``one_sine_pulse``); True: Zhang & Makris' phase
        ``sin(psi) = g tan(alpha) / a_p`` (the block lifts at ``t = 0``; the pulse lasts a full
        cycle from there)
    after : time after the pulse to follow the block (time)
    normal : the frequency ``frequency`` is relative to (default ``block.p_linear``, ``RigidBlock.p``)
    """
    wp = frequency * (block.p_linear if normal is None else normal)
    a_p = amplitude * block.uplift_acceleration
    phase = rocking_onset_phase(a_p, block.uplift_acceleration) if psi and a_p >= block.uplift_acceleration else 0.0
    end = 2.0 * math.pi / wp
    return rocking_response(block, one_sine_pulse(a_p, wp, psi=phase), end + after, linear=linear, pulse_end=end,
                            criterion=criterion)
