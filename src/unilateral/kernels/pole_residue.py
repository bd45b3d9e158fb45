"""Rational (pole-residue) kernels and the exact recursive CLCP history.

For a matrix model ``Lambda(s) = H(s) - F(s)^T D(s)^-1 F(s)`` is rational:

    Lambda(s) = P0 + s P1 + sum_k b_k c_k^T / (s - p_k)

with poles ``p_k`` (the eigenvalues of the structure with every constraint bilateral; a multiple
pole is listed once per eigenvector), rank-one residues kept as factors ``b_k, c_k`` (m,), and a
polynomial part from the Kelvin dashpots (``P1``) and the instantaneous stiffness (``P0``).
Under convolution quadrature each pole is a scalar recursion (:mod:`unilateral.history.recursive`),
so the history sum of the CLCP costs ``O(r m)`` per step instead of ``O(n m^2)``, and equals the
CQ history to round-off.

Two constructions (:meth:`PoleResidueKernel.from_model`):

* all poles, exactly, from the state-space form of a dense model (:mod:`unilateral.kernels.poles_dense`);
* the lowest modes of a classically damped (possibly sparse, large) model plus the static
  correction of the truncated modes (:mod:`unilateral.kernels.poles_truncated`).
"""

from __future__ import annotations

import time

import numpy as np

from .base import Kernel
from .matrix import MatrixKernel
from .poles_dense import DENSE_MAX_N, check_points, dense_poles
from ..history.recursive import (LinearRecursion, RecursiveHistory, pole_coefficients,
                              rate_coefficients)
from .poles_truncated import truncated_poles
from ..rules import get_rule

__all__ = ["DENSE_MAX_N", "PoleResidueKernel", "RecursiveHistory", "modal_history"]


class PoleResidueKernel(Kernel):
    """``Lambda(s) = P0 + s P1 + sum_k b_k c_k^T / (s - p_k)``, with real-kernel symmetry.

    Conjugate pairs are stored once: a pole with ``Im p > 0`` stands for itself **and** its
    conjugate, whose factors are ``conj(b_k), conj(c_k)``; real poles have real factors. Poles with
    ``Im p < 0`` are not accepted. So ``Lambda(conj s) = conj Lambda(s)`` by construction.

    The kernel is evaluated anchored at ``s = 0``,

        Lambda(s) = Lambda0 + s P1 + sum_k b_k c_k^T s / (p_k (s - p_k)),   Lambda0 = Lambda(0),

    which is the same function (``P0 = Lambda0 + sum_k b_k c_k^T / p_k``) but does not cancel a
    large ``P0`` against fast poles at low ``s``: give ``Lambda0`` when it is known directly
    (``H - F^T K^-1 F``), as :meth:`from_model` does.

    Parameters
    ----------
    poles : (r,) complex, ``Im p >= 0``, nonzero
    B, Cf : (r, m) complex; the residue of pole k is ``B[k][:, None] * Cf[k][None, :]``
    P0 : (m, m) real; give either ``P0`` or ``Lambda0``
    P1 : (m, m) real, optional (zero)
    Lambda0 : (m, m) real, ``Lambda(0)``
    info : dict, optional
        How the kernel was built (see :meth:`from_model`).

    Attributes
    ----------
    P0, Lambda0, P1 : (m, m)
    multiplicity : (r,) float, 2 for a stored conjugate pair, 1 for a real pole
    n_poles : int, number of poles counting both members of each pair
    """

    def __init__(self, poles, B, Cf, P0=None, P1=None, *, Lambda0=None, info=None):
        if (P0 is None) == (Lambda0 is None):
            raise ValueError("give exactly one of P0 and Lambda0 (the other follows: "
                             "Lambda0 = P0 - sum_k b_k c_k^T / p_k)")
        poles = np.atleast_1d(np.asarray(poles, dtype=complex))
        const = np.asarray(P0 if Lambda0 is None else Lambda0, dtype=float)
        m = const.shape[0]
        if const.shape != (m, m):
            raise ValueError(f"{'P0' if Lambda0 is None else 'Lambda0'} must be square (m, m), "
                             f"got shape {const.shape}")
        if np.any(poles == 0):
            raise ValueError("a pole at s = 0 (a rigid-body mode) is not supported: "
                             "Lambda(0) must be finite")
        r = poles.shape[0]
        B = np.asarray(B, dtype=complex).reshape(r, m)
        Cf = np.asarray(Cf, dtype=complex).reshape(r, m)
        P1 = np.zeros((m, m)) if P1 is None else np.asarray(P1, dtype=float)
        if P1.shape != (m, m):
            raise ValueError(f"P1 must have shape ({m}, {m}), got {P1.shape}")
        if np.any(poles.imag < 0):
            k = int(np.argmax(poles.imag < 0))
            raise ValueError(f"poles[{k}] = {poles[k]} has Im p < 0: store each conjugate pair "
                             "once, by its member with Im p > 0")
        real = poles.imag == 0
        bad = real & ~(_nearly_real(B) & _nearly_real(Cf))
        if np.any(bad):
            k = int(np.argmax(bad))
            raise ValueError(f"the real pole poles[{k}] = {poles[k].real} has complex factors "
                             "B[k], Cf[k]: a real kernel needs real residues at real poles")
        B[real] = B[real].real
        Cf[real] = Cf[real].real
        self.poles, self.B, self.Cf, self.P1 = poles, B, Cf, P1
        self.m = m
        self.multiplicity = np.where(real, 1.0, 2.0)
        static = np.einsum("k,ka,kb->ab", self.multiplicity / poles, B, Cf).real   # sum_k R_k / p_k
        if Lambda0 is None:
            self.P0, self.Lambda0 = const, const - static
        else:
            self.P0, self.Lambda0 = const + static, const
        self.n_poles = int(self.multiplicity.sum())
        self.info = {} if info is None else dict(info)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_model(cls, model, *, modes: int | None = None, tol: float = 1e-8) -> PoleResidueKernel:
        """The kernel of a matrix :class:`~unilateral.model.Model`.

        Parameters
        ----------
        model : Model
        modes : int, optional
            None (default): every pole, exactly, from the state-space form of the dense model
            (any damping; massless DOFs allowed; ``n <= DENSE_MAX_N``). An integer: the ``modes``
            lowest undamped modes (sparse eigensolver) with the static correction of the others;
            needs classical damping and no Kelvin coupling ``F_v``.
        tol : float
            Dense path: largest accepted relative error of the reconstructed ``Lambda(s)`` at a few
            check points. Truncated path: largest accepted relative residual of the modal damping
            check ``C phi_k = c_k M phi_k``.

        Returns
        -------
        PoleResidueKernel
            ``info`` holds ``path`` ("dense" or "truncated"), ``poles`` (counting conjugates),
            ``modes`` (oscillating pole pairs; truncated: modes kept), ``time`` (s) and checks:
            dense: ``reconstruction_error`` (relative, at three s spanning the poles),
            ``eigvec_condition``, ``states``, ``dofs`` (massive / first-order / condensed);
            truncated: ``static_correction`` (relative error of Lambda(0) that the correction
            removes), ``static_error`` (of Lambda(0) with it), ``damping_residual``, ``omega``.
        """
        start = time.perf_counter()
        if modes is None:
            kernel = cls(**dense_poles(model))
            err = kernel.relative_error(MatrixKernel(model), check_points(kernel.poles))
            kernel.info["reconstruction_error"] = err
            if not err <= tol:
                raise ValueError(
                    f"the pole-residue form reproduces Lambda(s) only to {err:.2e} relative "
                    f"(tol = {tol:.0e}) at the check points: nearly multiple poles (eigenvector "
                    f"condition {kernel.info['eigvec_condition']:.1e}) or poles spanning too "
                    "many decades; use the Laplace-domain kernel (method='cq') instead")
        else:
            if isinstance(modes, bool) or not isinstance(modes, (int, np.integer)) or modes < 1:
                raise ValueError(f"modes must be a positive integer or None, got {modes!r}")
            kernel = cls(**truncated_poles(model, int(modes), tol))
            kernel.info["static_error"] = kernel.relative_error(MatrixKernel(model), np.zeros(1))
        kernel.info["time"] = time.perf_counter() - start
        return kernel

    # ------------------------------------------------------------------ evaluation
    def evaluate(self, s: np.ndarray) -> np.ndarray:
        """``Lambda(s)`` for ``s`` of shape (L,); returns (L, m, m), real if every s is real."""
        s = np.asarray(s)
        p = self.poles[None, :]
        out = np.einsum("lk,ka,kb->lab", s[:, None] / (p * (s[:, None] - p)), self.B, self.Cf)
        pair = self.multiplicity == 2.0
        if np.any(pair):
            pc = self.poles[pair].conj()[None, :]
            out += np.einsum("lk,ka,kb->lab", s[:, None] / (pc * (s[:, None] - pc)),
                             self.B[pair].conj(), self.Cf[pair].conj())
        out += self.Lambda0[None] + s[:, None, None] * self.P1[None]
        return out.real if np.isrealobj(s) else out

    def relative_error(self, reference, s) -> float:
        """``max_s ||Lambda(s) - reference(s)||_F / ||reference(s)||_F`` over ``s`` (L,)."""
        s = np.atleast_1d(np.asarray(s))
        ref = reference(s)
        diff = np.linalg.norm(self(s) - ref, axis=(1, 2))
        size = np.linalg.norm(ref, axis=(1, 2))
        return float(np.max(diff / np.where(size > 0, size, 1.0)))

    def W0(self, dt: float, rule) -> np.ndarray:
        """``W_0 = Lambda(s*)``, ``s* = delta(0)/dt``: real symmetric (m, m)."""
        W = self(get_rule(rule, cq=True).s_star(dt))
        return 0.5 * (W + W.T)

    def weights(self, N: int, dt: float, rule) -> np.ndarray:
        """Exact convolution-quadrature weights ``W_0 .. W_N`` by the recursions: (N+1, m, m).

        ``O(N r m^2)`` work and ``O(N m^2)`` memory: for checks; marches use :meth:`history`.
        """
        rule = get_rule(rule, cq=True)
        (pa, pb), (ra, rb) = pole_coefficients(self.poles, dt, rule), rate_coefficients(1, dt, rule)
        g = LinearRecursion(np.hstack([pa, ra]), np.hstack([pb, rb])).impulse_response(N)
        W = np.einsum("jk,ka,kb->jab", g[:, :-1] * self.multiplicity, self.B, self.Cf).real
        W += g[:, -1].real[:, None, None] * self.P1[None]
        W[0] = self(rule.s_star(dt))                 # = P0 + the above, without cancellation
        return W

    def history(self, N: int, dt: float, rule) -> RecursiveHistory:
        """The ``O(r m)``-per-step history of the CLCP march (``name = "modal"``)."""
        return RecursiveHistory(self, N, dt, get_rule(rule, cq=True))

    def __repr__(self) -> str:
        return (f"PoleResidueKernel(m={self.m}, poles={self.n_poles}, stored={self.poles.size}, "
                f"viscous={bool(np.any(self.P1))})")


def modal_history(model, N: int, dt: float, rule, *, modes: int | None = None):
    """``(W0, history)`` of a matrix model for :func:`unilateral.march.clcp.march_cq`.

    Parameters
    ----------
    model : Model
    N : int, number of steps
    dt : float
    rule : str or Rule (``"bdf1"``, ``"bdf2"``, ``"trapezoidal"``)
    modes : int, optional
        None: all poles (exact, dense models with ``n <= DENSE_MAX_N``); else the truncated
        modal kernel (see :meth:`PoleResidueKernel.from_model`).

    Returns
    -------
    W0 : (m, m) real symmetric
    history : RecursiveHistory
    """
    rule = get_rule(rule, cq=True)
    kernel = PoleResidueKernel.from_model(model, modes=modes)
    return kernel.W0(dt, rule), kernel.history(N, dt, rule)


def _nearly_real(X: np.ndarray) -> np.ndarray:
    """Rows of X (r, m) whose imaginary part is round-off: (r,) bool."""
    return np.abs(X.imag).max(axis=1, initial=0.0) <= 1e-12 * np.abs(X).max(axis=1, initial=0.0)
