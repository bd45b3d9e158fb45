"""Time-discretisation rules, shared by convolution quadrature and direct time stepping.

For direct stepping a rule expresses the derivatives at the new step through the new value and a
history of known past values:

    y'_n  = c1 y_n - h1,        y''_n = c0 y_n - h2

so that the equations of motion become ``D_eff u_n = ...`` with ``D_eff = c0 M + c1 C + K``
(for HHT-alpha, the stiffness and damping terms are weighted by ``1 - alpha``).
For convolution quadrature (Lubich 1988) the same rule is given by its generating function
``delta(zeta)``; with zero initial data the two discretisations produce identical sequences, which
is the exact equivalence ``method="cq"`` == ``method="direct"`` that the tests check.

=============  =========================  ============  ===================================
name           delta(zeta)                c1 = s*       notes
=============  =========================  ============  ===================================
bdf1           1 - zeta                   1/dt          first order, strongly dissipative
bdf2           (1-zeta) + (1-zeta)^2/2    3/(2 dt)      second order, L-stable (default)
trapezoidal    2 (1-zeta)/(1+zeta)        2/dt          = Newmark(1/2, 1/4), no dissipation
newmark        (direct only)              gamma/(beta dt)
hht            (direct only)              gamma/(beta dt)  alpha in [0, 1/3]
=============  =========================  ============  ===================================
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from . import _validate as V


class Rule(ABC):
    """Base class of time-discretisation rules.

    Subclasses implement ``coefficients``, ``start``, ``history`` and ``advance``; rules usable
    by convolution quadrature also implement ``delta``.
    """

    name = "rule"
    #: HHT weight of the previous step in the stiffness, damping and load terms.
    alpha = 0.0
    #: Order of accuracy.
    order = 1

    @property
    def supports_cq(self) -> bool:
        return type(self).delta is not Rule.delta

    def delta(self, zeta):
        """Generating function ``delta(zeta)`` of the rule (convolution quadrature)."""
        raise TypeError(
            f"rule {self.name!r} has no convolution-quadrature form; "
            "use rule='bdf1', 'bdf2' or 'trapezoidal' with method='cq'"
        )

    def delta_coefficients(self, N: int) -> np.ndarray:
        """Taylor coefficients of ``delta(zeta)`` up to ``zeta^N``, shape (N+1,)."""
        return Rule.delta(self, None)

    def s_star(self, dt: float) -> float:
        """``delta(0)/dt`` = c1: the real Laplace argument at which ``W_0 = Lambda(s*)``."""
        return self.coefficients(dt)[0]

    @abstractmethod
    def coefficients(self, dt: float) -> tuple[float, float]:
        """Return ``(c1, c0)``."""

    @abstractmethod
    def start(self, y0, yd0, ydd0, dt):
        """Initial state from value, rate and second rate at t = 0 (arrays of equal shape)."""

    @abstractmethod
    def history(self, state, dt):
        """Return ``(h1, h2)`` for the next step."""

    @abstractmethod
    def advance(self, state, y, yd, ydd):
        """Return the state after appending the new value and its rates."""

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


class BDF(Rule):
    """Backward differentiation formula of order 1 or 2, applied to u and to u'.

    ``y'_n = (a_0 y_n - sum_{k>=1} a_k y_{n-k}) / dt``.
    """

    _COEFFS = {1: (1.0, 1.0), 2: (1.5, 2.0, -0.5)}

    def __init__(self, order: int = 2):
        if order not in self._COEFFS:
            raise ValueError(f"order={order!r} is not valid for BDF; valid: 1, 2")
        self.order = order
        self.name = f"bdf{order}"
        self._a = self._COEFFS[order]

    def delta(self, zeta):
        zeta = np.asarray(zeta)
        if self.order == 1:
            return 1.0 - zeta
        return (1.0 - zeta) + 0.5 * (1.0 - zeta) ** 2

    def delta_coefficients(self, N):
        out = np.zeros(N + 1)
        poly = (1.0, -1.0) if self.order == 1 else (1.5, -2.0, 0.5)
        out[: min(N + 1, len(poly))] = poly[: N + 1]
        return out

    def coefficients(self, dt):
        a0 = self._a[0]
        return a0 / dt, (a0 / dt) ** 2

    def start(self, y0, yd0, ydd0, dt):
        # Past values for the multistep formula. With zero data (the convolution-quadrature
        # setting) they are zero; otherwise a second-order Taylor extrapolation backwards.
        ys, yds = [y0], [yd0]
        for k in range(1, self.order):
            ys.append(y0 - k * dt * yd0 + 0.5 * (k * dt) ** 2 * ydd0)
            yds.append(yd0 - k * dt * ydd0)
        return ys, yds

    def history(self, state, dt):
        ys, yds = state
        if self.order == 1:
            h1 = ys[0] / dt
            return h1, (h1 + yds[0]) / dt
        h1 = (2.0 * ys[0] - 0.5 * ys[1]) / dt
        return h1, (1.5 * h1 + 2.0 * yds[0] - 0.5 * yds[1]) / dt

    def advance(self, state, y, yd, ydd):
        ys, yds = state
        return [y] + ys[: self.order - 1], [yd] + yds[: self.order - 1]

    def __repr__(self):
        return f"BDF(order={self.order})"


@dataclass(frozen=True, repr=True)
class Newmark(Rule):
    """Newmark's method with parameters (gamma, beta), optionally HHT-alpha weighted.

    ``alpha = 0`` is plain Newmark; ``gamma = 1/2, beta = 1/4`` is the average-acceleration
    (trapezoidal) rule. The viscous terms of Kelvin constraints use the same velocity formula
    for ``v'`` as for ``u'``, so that the condensed LCP matrix stays symmetric.
    """

    gamma: float = 0.5
    beta: float = 0.25
    alpha: float = 0.0

    def __post_init__(self):
        for field in ("gamma", "beta"):
            V.positive_float(field, getattr(self, field))
        if not 0.0 <= self.alpha <= 1.0 / 3.0:
            raise ValueError(f"alpha={self.alpha!r} is not valid for HHT; valid: 0 <= alpha <= 1/3")

    @property
    def name(self):
        if self.alpha:
            return "hht"
        return "trapezoidal" if (self.gamma, self.beta) == (0.5, 0.25) else "newmark"

    @property
    def order(self):
        return 2 if abs(self.gamma - 0.5 - self.alpha) < 1e-14 else 1

    def delta(self, zeta):
        if (self.gamma, self.beta, self.alpha) != (0.5, 0.25, 0.0):
            return Rule.delta(self, zeta)
        zeta = np.asarray(zeta)
        return 2.0 * (1.0 - zeta) / (1.0 + zeta)

    @property
    def supports_cq(self) -> bool:
        return (self.gamma, self.beta, self.alpha) == (0.5, 0.25, 0.0)

    def delta_coefficients(self, N):
        if not self.supports_cq:
            return Rule.delta(self, None)
        out = 4.0 * (-1.0) ** np.arange(N + 1)          # 2 (1 - zeta)/(1 + zeta) = 2 - 4 zeta + 4 zeta^2 - ...
        out[0] = 2.0
        return out

    def coefficients(self, dt):
        return self.gamma / (self.beta * dt), 1.0 / (self.beta * dt * dt)

    def start(self, y0, yd0, ydd0, dt):
        return y0, yd0, ydd0

    def history(self, state, dt):
        y, yd, ydd = state
        g, b = self.gamma, self.beta
        h1 = g / (b * dt) * y + (g / b - 1.0) * yd + dt * (g / (2 * b) - 1.0) * ydd
        h2 = (y + dt * yd + dt * dt * (0.5 - b) * ydd) / (b * dt * dt)
        return h1, h2

    def advance(self, state, y, yd, ydd):
        return y, yd, ydd


def HHT(alpha: float = 0.05) -> Newmark:
    """Hilber-Hughes-Taylor alpha method: ``gamma = 1/2 + alpha``, ``beta = (1 + alpha)^2 / 4``.

    The library's ``alpha`` in ``[0, 1/3]`` weights the previous step (``alpha = 0``: the
    trapezoidal rule; more: more high-frequency dissipation). Hilber, Hughes and Taylor's own
    convention ``alpha_HHT`` in ``[-1/3, 0]`` is accepted too and mapped to ``alpha = -alpha_HHT``:
    ``HHT(-0.1)`` is ``HHT(0.1)``.
    """
    if isinstance(alpha, (int, float)) and not isinstance(alpha, bool) and -1.0 / 3.0 <= alpha < 0.0:
        alpha = -float(alpha)
    elif isinstance(alpha, (int, float)) and not isinstance(alpha, bool) and not 0.0 <= alpha <= 1.0 / 3.0:
        raise ValueError(f"alpha={alpha!r} is not valid for HHT; valid: 0 <= alpha <= 1/3 (or Hilber's "
                         "convention -1/3 <= alpha <= 0, mapped to -alpha)")
    return Newmark(gamma=0.5 + alpha, beta=(1.0 + alpha) ** 2 / 4.0, alpha=alpha)


RULES = {
    "bdf1": lambda: BDF(1),
    "bdf2": lambda: BDF(2),
    "trapezoidal": lambda: Newmark(0.5, 0.25),
    "newmark": lambda: Newmark(0.5, 0.25),
    "hht": lambda: HHT(),
}
CQ_RULES = ("bdf1", "bdf2", "trapezoidal")


def alias_note(requested, rule: Rule) -> str | None:
    """What the terminal and ``summary.json`` say when a rule was asked for by another name.

    ``"newmark"`` without parameters is Newmark(1/2, 1/4), the trapezoidal rule: every method
    runs it as ``"trapezoidal"`` (``method="cq"`` too) and records that name.

    Returns
    -------
    str or None
        None when ``requested`` is a Rule or the rule's own name.
    """
    if not isinstance(requested, str) or requested.lower() == rule.name:
        return None
    return (f"rule {requested.lower()!r} without parameters is Newmark(gamma={rule.gamma:g}, beta={rule.beta:g}), "
            f"the {rule.name} rule: it ran as rule {rule.name!r}")


def get_rule(rule, *, cq: bool = False) -> Rule:
    """Return a rule from a name or a ``Rule`` instance.

    Parameters
    ----------
    rule : str or Rule
    cq : bool
        If True the rule must have a convolution-quadrature form.
    """
    if isinstance(rule, Rule):
        out = rule
    elif isinstance(rule, str):
        valid = CQ_RULES if cq and rule.lower() not in RULES else RULES
        out = RULES[V.choice("rule", rule, valid)]()
    else:
        raise TypeError(f"rule must be a name or a Rule instance, got {V.describe(rule)}")
    if cq and not out.supports_cq:
        shown = rule if isinstance(rule, str) else out
        raise ValueError(
            f"rule={shown!r} has no convolution-quadrature form; valid for method='cq': "
            + ", ".join(repr(r) for r in CQ_RULES)
            + " (use method='direct' for Newmark and HHT)"
        )
    return out


class EnergyPairing:
    """The discrete energy identity of a rule: how the work terms are summed and what it dissipates.

    The energy balance (:mod:`unilateral.analysis.energy`) pairs the equations of motion with an
    increment of the state. With the pairing of the rule that made the steps the balance is an
    exact identity (to round-off), and the rule's numerical dissipation is a term of it:

    * trapezoidal rule (``Newmark(1/2, 1/4)``): the mean of the equations at ``n-1`` and ``n``
      with ``x_n - x_{n-1}``; ``f^T dx ~ (f_n + f_{n-1})^T (x_n - x_{n-1}) / 2``, no numerical
      dissipation (it conserves the discrete energy);
    * BDF1: the equation at ``n`` with ``x_n - x_{n-1} = dt x'_n``; for a quadratic energy
      ``y^T Q y / 2`` it dissipates ``(y_n - y_{n-1})^T Q (y_n - y_{n-1}) / 2`` per step;
    * BDF2: the equation at ``n`` with ``(3 x_n - 4 x_{n-1} + x_{n-2}) / 2 = dt x'_n``. Its energy is
      the G-norm ``(y_n^T Q y_n + (2 y_n - y_{n-1})^T Q (2 y_n - y_{n-1})) / 4`` (Dahlquist's
      G-stability), which equals ``y^T Q y / 2`` for a constant ``y`` and differs from the energy at
      the step by a bounded term of order ``dt`` (:attr:`lead`: the state needs one value before
      the start, that of the rule's start); it dissipates
      ``(y_n - 2 y_{n-1} + y_{n-2})^T Q (y_n - 2 y_{n-1} + y_{n-2}) / 4`` per step.

    Other rules (Newmark with ``gamma != 1/2``, HHT-alpha) are paired as the trapezoidal rule
    without a dissipation term (:attr:`exact` False): their balance closes to their order only.

    Parameters
    ----------
    rule : Rule, a rule's name, or None (the trapezoidal pairing)
    """

    def __init__(self, rule=None):
        rule = get_rule(rule) if isinstance(rule, str) else rule
        name = "trapezoidal" if rule is None else rule.name
        if isinstance(rule, Newmark) and (rule.gamma, rule.beta, rule.alpha) == (0.5, 0.25, 0.0):
            name = "trapezoidal"
        self.kind = name if name in ("bdf1", "bdf2", "trapezoidal") else "other"
        #: Whether the balance is an exact identity of the rule (its numerical dissipation a term of it).
        self.exact = self.kind != "other"
        #: States before ``t = 0`` the pairing needs (BDF2: one).
        self.lead = 1 if self.kind == "bdf2" else 0

    def weights(self, f) -> np.ndarray:
        """The force factor of each step's work (k, N) from rows ``f`` (k, N+1) at ``t_0 .. t_N``."""
        if self.kind in ("bdf1", "bdf2"):
            return f[:, 1:]
        return 0.5 * (f[:, 1:] + f[:, :-1])

    def increments(self, x) -> np.ndarray:
        """The increment of each step (k, N) from rows ``x`` (k, N+1+lead) (``x_{-1}`` first for BDF2)."""
        if self.kind == "bdf2":
            return 1.5 * x[:, 2:] - 2.0 * x[:, 1:-1] + 0.5 * x[:, :-2]
        return np.diff(x, axis=1)

    @classmethod
    def of_stats(cls, stats) -> EnergyPairing:
        """The pairing of a run from its ``stats`` (a dict or its JSON text): its ``rule``; the
        trapezoidal pairing for ``method="event"`` (no rule steps it) or a rule not named."""
        import json

        try:
            stats = json.loads(stats) if isinstance(stats, str) else dict(stats)
        except (ValueError, TypeError):          # not a run's statistics
            stats = {}
        rule = stats.get("rule") if isinstance(stats, dict) else None
        method = stats.get("method") if isinstance(stats, dict) else None
        return cls(rule if isinstance(rule, str) and rule in RULES and method != "event" else None)

    def series_work(self, f, x) -> float:
        """The work of a force history ``f`` (N+1,) on a deformation ``x`` (N+1,) of constraint unknowns
        (``x`` before ``t = 0`` is ``x_0``, as the stepping starts); NaN steps left out."""
        x = np.concatenate([x[:1]] * self.lead + [x])
        return float(np.nansum(self.weights(f[None]) * self.increments(x[None])))

    def pairs(self, f, x) -> np.ndarray:
        """Work increments (N,) of rows ``f`` (k, N+1) on rows ``x`` (k, N+1+lead)."""
        return np.einsum("ik,ik->k", self.weights(f), self.increments(x))

    def quadratic(self, y, Qy) -> tuple[np.ndarray, np.ndarray]:
        """The rule's energy of ``y^T Q y / 2`` and its numerical dissipation.

        Parameters
        ----------
        y, Qy : (k, N+1+lead) rows of a state and of ``Q`` times it (``Q`` symmetric)

        Returns
        -------
        energy : (N+1,) the rule's energy at ``t_0 .. t_N`` (the G-norm for BDF2)
        dissipated : (N,) dissipated by the rule over each step (zero for the trapezoidal rule)
        """
        dot = lambda a, b: np.einsum("ik,ik->k", a, b)
        if self.kind == "bdf2":
            energy = 0.25 * (dot(y[:, 1:], Qy[:, 1:]) + dot(2 * y[:, 1:] - y[:, :-1], 2 * Qy[:, 1:] - Qy[:, :-1]))
            second = lambda a: a[:, 2:] - 2.0 * a[:, 1:-1] + a[:, :-2]
            return energy, 0.25 * dot(second(y), second(Qy))
        energy = 0.5 * dot(y, Qy)
        if self.kind == "bdf1":
            return energy, 0.5 * dot(np.diff(y, axis=1), np.diff(Qy, axis=1))
        return energy, np.zeros(y.shape[1] - 1)
