"""CLCPs given directly by their kernel, without matrices.

``psi(t) = psiL(t) - (Lambda * v)(t)`` (eq. 26) needs only the kernel and the bilateral response
``psiL(t)``: for example the impedance of an unbounded soil computed elsewhere, or a structure
analysed by another program. :class:`KernelModel` holds a Laplace-domain ``Lambda(s)``,
:class:`TimeKernelModel` a time-domain :class:`~unilateral.kernels.time_domain.TimeKernel`.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from ..constraints import default_families, step_law
from .base import CallableKernel, Kernel
from .time_domain import TimeKernel


class KernelModel:
    """Unilateral problem defined by its kernel ``Lambda`` and ``psiL``.

    The kernel is given in the Laplace domain (a :class:`~unilateral.kernels.Kernel` or a
    callable ``Lambda(s)``: ``domain = "laplace"``, solved by ``method="cq"``) or in the time
    domain (a :class:`~unilateral.kernels.TimeKernel`, ``Lambda(t)``: ``domain = "time"``, solved
    by ``method="time-kernel"``, product integration).

    Parameters
    ----------
    Lambda : callable, Kernel or TimeKernel
        ``Lambda(s) -> (m, m)`` for complex ``s`` with ``Re s > 0``; real for real ``s``
        and ``Lambda(conj s) = conj Lambda(s)``; or a time-domain kernel.
    psiL : callable ``psiL(t) -> (m,)`` or array (N+1, m)
        Constraint reactions of the structure with every constraint bilateral (eq. 22),
        including the offset ``-g``; an array is sampled at ``t_k = k dt``.
    m : int, optional
        Number of constraints (inferred from an array psiL or from ``Lambda(1)``).
    vectorized : bool
        ``Lambda`` accepts an array of s of shape (L,) and returns (L, m, m).
    constraint_names : sequence of m str, optional
    families : sequence of ConstraintFamily, optional
        The laws of the unknowns (:mod:`unilateral.constraints`; default: every one a contact;
        a time-domain kernel takes contacts only).

    Attributes
    ----------
    kernel : Kernel or TimeKernel;  domain : ``"laplace"`` or ``"time"``;  m : int
    kind : ``"laplace kernel"`` or ``"time kernel"``, as the methods know it
        (:attr:`unilateral.methods.Method.solves`)
    """

    def __init__(self, Lambda, psiL, *, m=None, vectorized=False, constraint_names=None, families=None):
        if isinstance(psiL, np.ndarray) or (not callable(psiL) and psiL is not None):
            psiL = V.as_matrix("psiL", psiL, (None, m))
            m = psiL.shape[1]
        elif not callable(psiL):
            raise TypeError(f"psiL must be a callable psiL(t) or an array (N+1, m), got {V.describe(psiL)}")
        if isinstance(Lambda, TimeKernel) and families is not None:
            raise ValueError("families: a time-domain kernel (TimeKernel) takes contacts only; "
                             "give Lambda(s) for other laws")
        if isinstance(Lambda, (Kernel, TimeKernel)):
            kernel = Lambda
            if m is not None and m != kernel.m:
                raise ValueError(f"psiL has {m} columns but the kernel Lambda is {kernel.m} x {kernel.m}: "
                                 "give one column per constraint")
        else:
            if m is None:
                if not callable(Lambda):
                    raise TypeError(f"Lambda must be callable, got {V.describe(Lambda)}")
                m = np.atleast_2d(np.asarray(Lambda(np.array([1.0]) if vectorized else 1.0))).shape[-1]
            kernel = CallableKernel(Lambda, m, vectorized=vectorized)
        self.kernel = kernel
        self.domain = "time" if isinstance(kernel, TimeKernel) else "laplace"
        self.kind = f"{self.domain} kernel"
        self.m = kernel.m
        self.psiL = psiL
        self.constraint_names = (
            [f"c{i}" for i in range(self.m)] if constraint_names is None
            else [str(c) for c in constraint_names]
        )
        if len(self.constraint_names) != self.m:
            raise ValueError(f"constraint_names must have {self.m} entries, got {len(self.constraint_names)}")
        self.families = list(families) if families is not None else default_families(self.m)
        self.law = step_law(self.families, self.m)

    def Lambda_real(self, s: float) -> np.ndarray:
        """``Lambda(s)`` at a real ``s >= 0`` as a real symmetric (m, m) matrix (Laplace domain)."""
        if self.domain != "laplace":
            raise ValueError("Lambda_real needs a kernel in the Laplace domain; this one is a TimeKernel")
        value = np.asarray(self.kernel(np.array([s], dtype=float))[0])
        if np.iscomplexobj(value):
            scale = max(np.max(np.abs(value)), 1.0)
            if np.max(np.abs(value.imag)) > 1e-10 * scale:
                raise ValueError(f"Lambda(s) must be real for real s; Lambda({s}) has an imaginary part")
            value = value.real
        return 0.5 * (value + value.T)

    def psiL_samples(self, N: int, dt: float) -> np.ndarray:
        """``psiL`` at ``t_k = k dt``, k = 0..N, shape (N+1, m)."""
        if callable(self.psiL):
            out = np.array([np.asarray(self.psiL(k * dt), dtype=float) for k in range(N + 1)])
            if out.shape != (N + 1, self.m):
                raise ValueError(f"psiL(t) must return shape ({self.m},), got {out.shape[1:]}")
            V.check_finite("psiL(t)", out)
            return out
        if self.psiL.shape[0] < N + 1:
            raise ValueError(
                f"psiL has {self.psiL.shape[0]} samples but t_end/dt = {N} steps need {N + 1}"
            )
        return self.psiL[: N + 1]

    def __repr__(self) -> str:
        return f"KernelModel(m={self.m})" if self.domain == "laplace" else f"KernelModel(m={self.m}, {self.kernel!r})"


def TimeKernelModel(kernel, psiL, constraint_names=None) -> KernelModel:  # noqa: N802 (the former class)
    """The :class:`KernelModel` of a time-domain kernel (``domain = "time"``).

    Parameters
    ----------
    kernel : TimeKernel
    psiL : callable ``psiL(t) -> (m,)`` or array (N+1, m)
        Constraint reactions of the structure with every constraint bilateral (samples at
        ``t_k = k dt``).
    constraint_names : sequence of m str, optional
    """
    if not isinstance(kernel, TimeKernel):
        raise TypeError(f"kernel must be a TimeKernel, got {V.describe(kernel)}")
    return KernelModel(kernel, psiL, constraint_names=constraint_names)
