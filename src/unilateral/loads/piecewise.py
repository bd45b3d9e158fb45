"""Piecewise-analytic form of a load time function, and load samples that keep a rule's order.

A :class:`Piecewise` function is, on each piece ``(e_{j-1}, e_j)`` between its breakpoints,

    f(t) = sum_i c_ji tau^i + a_j cos(omega tau) + b_j sin(omega tau),   tau = t - origin_j

(a polynomial plus one sinusoid of a frequency shared by all pieces). The first and the last piece
extend to -inf and +inf and must be constant. At a breakpoint ``f`` may jump (a pulse edge) or
kink (a triangle's peak); :meth:`Piecewise.limits` gives both one-sided values.

Samples on a time grid
----------------------
A step of BDF2 or of the trapezoidal rule uses the load at grid points only. For a load that jumps
between two grid points, the point value gives the jump a timing error of up to ``dt``: the
impulse delivered is wrong by ``O(dt)`` and the response converges at order 1 only.
:meth:`Piecewise.grid_samples` returns instead the **hat-function averages**

    Q_k = (1/dt) int f(t) phi_k(t) dt,   phi_k the piecewise-linear hat of half-width dt at t_k,

which equal ``f(t_k) + dt^2/12 f''(t_k) + O(dt^4)`` where ``f`` is smooth, are exact for
piecewise-linear ``f`` on the grid, give the mean of both sides at a jump on a grid point, and
deliver the exact impulse ``int f`` to every later grid point for both rules (their quadratures
``dt sum_k Q_k - dt/2 (Q_0 + Q_n)`` and the BDF2 sum reproduce ``int_0^{t_n} f`` exactly). At
``t = 0`` the dynamic run starts after the static preload under ``f(0-)``: its sample is the
one-sided half-hat average over ``[0, dt]`` (``f(0+) + O(dt)``, whose impulse error is
``O(dt^2)``). The integrals are evaluated piece by piece by 6-point Gauss-Legendre quadrature
(exact for polynomials of degree <= 11, round-off accurate for the sinusoids of pulses resolved by
the grid).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Gauss-Legendre nodes and weights on [-1, 1] used for the sample integrals.
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(6)

#: Sampling schemes of :meth:`Piecewise.grid_samples`.
SAMPLINGS = ("hat", "box", "point")


@dataclass(frozen=True, eq=False)
class Piecewise:
    """A scalar time function made of polynomial and sinusoidal pieces.

    Parameters
    ----------
    edges : (P-1,) array_like
        Strictly increasing breakpoints, s.
    poly : (P, d+1) array_like
        Polynomial coefficients of each piece in ``tau = t - origin`` (lowest degree first). The
        origin of piece ``j >= 1`` is ``edges[j-1]``; the first piece (constant) uses ``edges[0]``.
    trig : (P, 2) array_like, optional
        Coefficients ``(a, b)`` of ``a cos(omega tau) + b sin(omega tau)`` (default zero).
    omega : float, optional
        Angular frequency of the sinusoids, rad/s.
    """

    edges: np.ndarray
    poly: np.ndarray
    trig: np.ndarray | None = None
    omega: float = 0.0

    def __post_init__(self):
        edges = np.atleast_1d(np.asarray(self.edges, dtype=float))
        poly = np.atleast_2d(np.asarray(self.poly, dtype=float))
        P = edges.size + 1
        if poly.shape[0] != P:
            raise ValueError(f"poly must have one row per piece ({P}), got shape {poly.shape}")
        trig = np.zeros((P, 2)) if self.trig is None else np.asarray(self.trig, dtype=float).reshape(P, 2)
        if edges.size and np.any(np.diff(edges) <= 0):
            raise ValueError("edges must increase strictly")
        for j in (0, P - 1):
            if np.any(poly[j, 1:]) or np.any(trig[j]):
                raise ValueError("the first and the last piece (to -inf and +inf) must be constant")
        # drop trailing zero columns: the degree is that of the highest nonzero coefficient
        nonzero = np.flatnonzero(np.any(poly != 0.0, axis=0))
        poly = poly[:, : (nonzero[-1] + 1 if nonzero.size else 1)]
        object.__setattr__(self, "edges", edges)
        object.__setattr__(self, "poly", poly)
        object.__setattr__(self, "trig", trig)
        object.__setattr__(self, "omega", float(self.omega))
        origins = np.concatenate([edges[:1], edges]) if edges.size else np.zeros(1)
        object.__setattr__(self, "origins", origins)

    # ------------------------------------------------------------------ structure
    @property
    def degree(self) -> int:
        """Highest polynomial degree of the pieces."""
        return self.poly.shape[1] - 1

    @property
    def has_trig(self) -> bool:
        """True if some piece has a sinusoid."""
        return bool(np.any(self.trig))

    def piece(self, t, side: str = "right") -> np.ndarray:
        """Index of the piece holding ``t+`` (side="right") or ``t-`` (side="left")."""
        return np.searchsorted(self.edges, t, side="right" if side == "right" else "left")

    # ------------------------------------------------------------------ values
    def evaluate(self, t, side: str = "right", derivative: int = 0):
        """``f^(derivative)(t+)`` or ``(t-)`` at time(s) ``t``."""
        t = np.asarray(t, dtype=float)
        j = self.piece(t, side)
        return self._at(t, j, derivative)[()]

    def _at(self, t, j, derivative=0):
        tau = t - self.origins[j]
        out = np.zeros(np.shape(t))
        d = self.degree
        for i in range(derivative, d + 1):
            coef = self.poly[j, i]
            fact = float(np.prod(np.arange(i - derivative + 1, i + 1))) if derivative else 1.0
            out = out + coef * fact * tau ** (i - derivative)
        if self.has_trig:
            w = self.omega
            a, b = self.trig[j, 0], self.trig[j, 1]
            c, s = np.cos(w * tau), np.sin(w * tau)
            # d^k/dtau^k (a cos + b sin) = w^k (a cos(x + k pi/2) + b sin(x + k pi/2))
            k = derivative % 4
            ck, sk = [(c, s), (-s, c), (-c, -s), (s, -c)][k]
            out = out + w ** derivative * (a * ck + b * sk)
        return out

    def limits(self, t) -> tuple[float, float]:
        """One-sided values ``(f(t-), f(t+))``."""
        return float(self.evaluate(t, "left")), float(self.evaluate(t, "right"))

    def poly_state(self, t, side="right") -> np.ndarray:
        """Derivatives ``p(t), p'(t), ..., p^(d)(t)`` of the polynomial part, (d+1,)."""
        t = float(t)
        j = int(self.piece(t, side))
        tau = t - self.origins[j]
        out = np.zeros(self.degree + 1)
        for k in range(self.degree + 1):
            for i in range(k, self.degree + 1):
                out[k] += self.poly[j, i] * float(np.prod(np.arange(i - k + 1, i + 1))) * tau ** (i - k)
        return out

    def trig_state(self, t, side="right") -> np.ndarray:
        """``(s, s'/omega)`` of the sinusoidal part ``s = a cos + b sin``, (2,)."""
        t = float(t)
        j = int(self.piece(t, side))
        x = self.omega * (t - self.origins[j])
        a, b = self.trig[j]
        return np.array([a * np.cos(x) + b * np.sin(x), -a * np.sin(x) + b * np.cos(x)])

    # ------------------------------------------------------------------ samples
    def grid_samples(self, dt: float, N: int, sampling: str = "hat") -> np.ndarray:
        """Samples ``Q_k`` at ``t_k = k dt``, k = 0..N, for a dynamic run starting at t = 0+.

        ``sampling="hat"``: hat-function averages (see the module docstring), ``"box"``: averages
        over ``[t_k - dt/2, t_k + dt/2]``, ``"point"``: point values, the mean of both sides at a
        jump on a grid point. All three take one-sided data at t = 0 (the half hat or half box
        over ``[0, dt]`` normalised, or ``f(0+)``).
        """
        if sampling == "point":
            t = dt * np.arange(N + 1)
            Q = 0.5 * (self.evaluate(t, "left") + self.evaluate(t, "right"))
            Q[0] = self.evaluate(0.0, "right")
            return Q
        if sampling not in SAMPLINGS:
            raise ValueError(f"sampling={sampling!r} is not valid; valid: {', '.join(map(repr, SAMPLINGS))}")
        end = (N + 1) * dt
        nodes = dt / 2 * np.arange(2 * N + 3)
        inside = self.edges[(self.edges > 0.0) & (self.edges < end)]
        nodes = np.union1d(nodes, inside)
        a, b = nodes[:-1], nodes[1:]
        keep = b > a
        a, b = a[keep], b[keep]
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        x = mid[:, None] + half[:, None] * _GAUSS_X[None, :]            # (S, 6), inside one piece
        j = np.searchsorted(self.edges, mid, side="right")
        fx = self._at(x, j[:, None])
        wfx = fx * (half[:, None] * _GAUSS_W[None, :]) / dt
        Q = np.zeros(N + 2)
        if sampling == "hat":
            k = np.minimum(np.floor(mid / dt).astype(int), N + 1)
            s = (x - k[:, None] * dt) / dt
            np.add.at(Q, k, np.sum(wfx * (1.0 - s), axis=1))
            np.add.at(Q, np.minimum(k + 1, N + 1), np.sum(wfx * s, axis=1))
        else:                                                           # box
            k = np.minimum(np.floor(mid / dt + 0.5).astype(int), N + 1)
            np.add.at(Q, k, np.sum(wfx, axis=1))
        Q[0] *= 2.0                                                     # one-sided at t = 0
        return Q[: N + 1]


def constant(value: float) -> Piecewise:
    """A constant as a :class:`Piecewise` (one piece)."""
    return Piecewise(np.zeros(0), [[float(value)]])


def linear_table(t, values, left: float, right: float) -> Piecewise:
    """Linear interpolation of ``values`` at ``t`` (strictly increasing), ``left``/``right`` outside."""
    t = np.asarray(t, dtype=float)
    values = np.asarray(values, dtype=float)
    if t.size == 1:
        return Piecewise(t, [[left], [right]])
    slopes = np.diff(values) / np.diff(t)
    poly = np.zeros((t.size + 1, 2))
    poly[0, 0], poly[-1, 0] = left, right
    poly[1:-1, 0], poly[1:-1, 1] = values[:-1], slopes
    return Piecewise(t, poly)
