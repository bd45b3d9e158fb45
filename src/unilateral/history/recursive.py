"""Exact recursions for the convolution-quadrature weights of rational kernels.

A rule with generating function ``delta(zeta) = a(zeta) / b(zeta)`` (polynomials) maps the pole
term ``1/(s - p)`` to ``b(zeta) / (a(zeta)/dt - p b(zeta))``: its CQ weights are the impulse
response of the rule applied to the scalar ODE ``y' = p y + u``,

    sum_i (a_i/dt - p b_i) y_{n-i} = sum_i b_i u_{n-i},

and the weights of ``s`` (a Kelvin dashpot) are those of
``sum_i b_i z_{n-i} = sum_i a_i u_{n-i} / dt`` (for the trapezoidal rule ``b(zeta) = 1 + zeta`` and
these do not decay, so they are never stored).

=============  ===================  =========
rule           a(zeta)              b(zeta)
=============  ===================  =========
bdf1           1 - zeta             1
bdf2           3/2 - 2 zeta + zeta^2/2   1
trapezoidal    2 - 2 zeta           1 + zeta
=============  ===================  =========

:class:`RecursiveHistory` evaluates ``h_n = sum_{j=1..n} W_j dv_{n-j}`` of a
:class:`~unilateral.kernels.PoleResidueKernel` with these recursions: ``O(r m + m^2)`` work per step
for ``r`` stored poles, against ``O(n m^2)`` for direct summation.
"""

from __future__ import annotations

import numpy as np

from ..rules import get_rule

_POLYNOMIALS = {
    "bdf1": ((1.0, -1.0), (1.0,)),
    "bdf2": ((1.5, -2.0, 0.5), (1.0,)),
    "trapezoidal": ((2.0, -2.0), (1.0, 1.0)),
}


def rule_polynomials(rule) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients of ``a`` and ``b`` in ``delta(zeta) = a(zeta)/b(zeta)``, padded to equal length.

    Parameters
    ----------
    rule : str or Rule
        A rule with a convolution-quadrature form (``"bdf1"``, ``"bdf2"``, ``"trapezoidal"``).

    Returns
    -------
    a, b : (q+1,) float, lowest power first
    """
    rule = get_rule(rule, cq=True)
    if rule.name not in _POLYNOMIALS:
        raise ValueError(f"rule {rule!r} has no known rational generating function; "
                         f"valid: {', '.join(repr(k) for k in _POLYNOMIALS)}")
    a, b = (np.asarray(c, dtype=float) for c in _POLYNOMIALS[rule.name])
    q = max(a.size, b.size)
    a, b = np.pad(a, (0, q - a.size)), np.pad(b, (0, q - b.size))
    zeta = np.array([0.3, -0.2 + 0.4j, 0.5j])
    ratio = np.polyval(a[::-1], zeta) / np.polyval(b[::-1], zeta)
    if not np.allclose(ratio, rule.delta(zeta), rtol=1e-14, atol=0.0):
        raise ValueError(f"rule {rule!r} does not have the generating function of {rule.name!r}")
    return a, b


class LinearRecursion:
    """Independent channels of ``sum_i alpha_i y_{n-i} = sum_i beta_i u_{n-i}``, zero before n = 0.

    One step is split in two so that the convolution history (input ``u_n`` still unknown) is
    available before the step is completed: :meth:`free` is ``y_n`` for ``u_n = 0`` and
    :meth:`advance` completes the step with ``y_n = free + (beta_0/alpha_0) u_n``.

    Parameters
    ----------
    alpha, beta : (q+1, c) real or complex, ``q >= 1``, ``alpha_0`` nonzero
    """

    def __init__(self, alpha: np.ndarray, beta: np.ndarray):
        inv0 = 1.0 / alpha[0]
        q, self.channels = alpha.shape[0] - 1, alpha.shape[1]
        dtype = np.result_type(alpha, beta)
        # Past values interleaved as rows y_{n-1}, u_{n-1}, y_{n-2}, u_{n-2}, ...: one product
        # gives the free response and one slice assignment shifts the state.
        self._coef = np.empty((2 * q, self.channels), dtype=dtype)
        self._coef[0::2] = -alpha[1:] * inv0
        self._coef[1::2] = beta[1:] * inv0
        self._gain = beta[0] * inv0                        # (c,)
        self._state = np.zeros_like(self._coef)
        #: Multiply-adds per step (free + advance).
        self.work_per_step = (2 * q + 1) * self.channels

    def free(self) -> np.ndarray:
        """``y_n`` of the next step for ``u_n = 0``, shape (c,)."""
        return np.einsum("ic,ic->c", self._coef, self._state)

    def advance(self, free: np.ndarray, u: np.ndarray) -> None:
        """Complete the step with input ``u`` (c,), given its ``free()`` value."""
        self._state[2:] = self._state[:-2]
        self._state[0] = free + self._gain * u
        self._state[1] = u

    def impulse_response(self, N: int) -> np.ndarray:
        """Outputs ``y_0 .. y_N`` (N+1, c) for ``u = (1, 0, 0, ...)`` from a fresh (zero) state."""
        out = np.empty((N + 1, self.channels), dtype=self._coef.dtype)
        u = np.ones(self.channels)
        for n in range(N + 1):
            free = self.free()
            out[n] = free + self._gain * u
            self.advance(free, u)
            u = np.zeros(self.channels)
        return out


def pole_coefficients(poles: np.ndarray, dt: float, rule) -> tuple[np.ndarray, np.ndarray]:
    """``(alpha, beta)`` (q+1, r), one channel per pole: the CQ weights of ``1/(s - p_k)``."""
    a, b = rule_polynomials(rule)
    poles = np.asarray(poles, dtype=complex)
    return a[:, None] / dt - b[:, None] * poles[None, :], np.repeat(b[:, None], poles.size, axis=1)


def rate_coefficients(channels: int, dt: float, rule) -> tuple[np.ndarray, np.ndarray]:
    """``(alpha, beta)`` (q+1, c) of ``channels`` channels of the CQ weights of ``s``."""
    a, b = rule_polynomials(rule)
    return np.repeat(b[:, None], channels, axis=1), np.repeat(a[:, None] / dt, channels, axis=1)


class RecursiveHistory:
    """``h_n = sum_{j=1..n} W_j dv_{n-j}`` of a pole-residue kernel, by exact recursion.

    Same interface as :class:`~unilateral.history.NaiveHistory`: ``value(n)`` then
    ``push(n, dv_n)`` for ``n = 1, 2, ..., N`` in order; ``dv_0 = 0``.

    With ``Lambda(s) = P0 + s P1 + sum_k b_k c_k^T/(s - p_k)`` the history is
    ``sum_k b_k y_{k,n} + P1 z_n`` with scalar filters ``y_k`` driven by ``c_k^T dv`` and, if
    ``P1`` is nonzero, m filters ``z`` driven by ``dv`` (``P0`` acts on ``dv_n`` only, in ``W_0``).
    All run as the channels of one :class:`LinearRecursion`. A stored complex pole stands for a
    conjugate pair: its output counts twice, real part taken.

    Parameters
    ----------
    kernel : PoleResidueKernel
    N : int, last step
    dt : float
    rule : str or Rule

    Attributes
    ----------
    work_per_step : int
        Scalar multiply-adds per step (complex counted once): ``2 c m + (2 q + 1) c`` for
        ``c = r`` channels (``r`` stored poles), or ``c = r + m`` with Kelvin dashpots (``P1``);
        ``q`` is 1 or 2. Independent of ``n`` and ``N``.
    stats : dict
        ``steps`` done and ``multiply_adds`` spent so far.
    """

    name = "modal"

    def __init__(self, kernel, N: int, dt: float, rule):
        self.N = int(N)
        self.m = m = kernel.m
        alpha, beta = pole_coefficients(kernel.poles, dt, rule)
        out = kernel.B * kernel.multiplicity[:, None]                  # (r, m)
        inp = kernel.Cf                                                # (r, m)
        if np.any(kernel.P1):
            ra, rb = rate_coefficients(m, dt, rule)
            alpha, beta = np.hstack([alpha, ra]), np.hstack([beta, rb])
            out, inp = np.vstack([out, kernel.P1.T]), np.vstack([inp, np.eye(m)])
        self._recursion = LinearRecursion(alpha, beta)
        self._out, self._in = out, inp
        self.work_per_step = 2 * out.shape[0] * m + self._recursion.work_per_step
        self.stats = {"steps": 0, "multiply_adds": 0}
        self._n = 0
        self._free = None

    def arrays(self):
        """``(coef, gain, out, inp)`` of the recursion, for the compiled march.

        ``coef`` (2q, c) holds ``-alpha_i/alpha_0`` and ``beta_i/alpha_0`` interleaved,
        ``gain`` (c,) is ``beta_0/alpha_0``, ``out`` and ``inp`` (c, m) the output and input
        factors (complex).
        """
        r = self._recursion
        return (r._coef.astype(complex), np.asarray(r._gain, dtype=complex),
                self._out.astype(complex), self._in.astype(complex))

    def value(self, n: int) -> np.ndarray:
        """``sum_{j=1..n} W_j dv_{n-j}``, shape (m,)."""
        self._check(n, "value")
        self._free = self._recursion.free()
        return (self._free @ self._out).real

    def push(self, n: int, dv_n: np.ndarray) -> None:
        """Record the increment ``dv_n`` (m,) of step ``n``."""
        self._check(n, "push")
        if self._free is None:
            self.value(n)
        self._recursion.advance(self._free, self._in @ dv_n)
        self._free = None
        self._n = n
        self.stats["steps"] = n
        self.stats["multiply_adds"] += self.work_per_step

    def _check(self, n: int, what: str) -> None:
        if n != self._n + 1 or n > self.N:
            raise ValueError(f"{what}({n}) out of order: steps 1..{self.N} are taken in turn, "
                             f"the next one is {self._n + 1}")
