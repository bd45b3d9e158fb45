"""The result of :func:`unilateral.solve`."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Solution:
    """Time histories of a unilateral dynamic analysis.

    Attributes
    ----------
    t : (N+1,) times ``t_k = k dt``
    v : (N+1, m) unilateral deformations (uplift, gap opening, slack), ``v >= 0``
    psi : (N+1, m) constraint reactions, ``psi <= 0``, ``psi^T v = 0``
    psiL : (N+1, m) reactions of the same structure with every constraint bilateral (eq. 22)
    u : (N+1, n) displacements, or None (kernel-only models)
    udot : (N+1, n) velocities, or None
    success : bool
        False if a step's LCP failed; the histories then stop at the last good step.
    message : str
        What happened, and on failure what to try.
    stats : dict
        ``steps``, ``method``, ``rule``, ``lcp_solver``, ``lcp_iterations`` (total),
        ``lcp_max_iterations``, ``contact_changes``, ``max_lcp_error``, ``time`` (seconds per phase),
        and method-specific entries.
    dof_names, constraint_names : list of str
    """

    t: np.ndarray
    v: np.ndarray
    psi: np.ndarray
    psiL: np.ndarray
    u: np.ndarray | None = None
    udot: np.ndarray | None = None
    success: bool = True
    message: str = ""
    stats: dict = field(default_factory=dict)
    dof_names: list = field(default_factory=list)
    constraint_names: list = field(default_factory=list)

    def dof(self, name: str) -> np.ndarray:
        """Displacement history (N+1,) of the DOF called ``name``."""
        if self.u is None:
            raise ValueError("this solution has no displacements (the model was given by its kernel)")
        return self.u[:, _index("DOF", name, self.dof_names)]

    def constraint(self, name: str) -> tuple[np.ndarray, np.ndarray]:
        """``(v, psi)`` histories (N+1,) of the constraint called ``name``."""
        i = _index("constraint", name, self.constraint_names)
        return self.v[:, i], self.psi[:, i]

    def __repr__(self) -> str:
        status = "success" if self.success else "FAILED"
        return (f"Solution({status}: {self.message!r}, steps={len(self.t) - 1}, "
                f"m={self.v.shape[1]}, n={None if self.u is None else self.u.shape[1]})")


@dataclass(frozen=True)
class State:
    """The state of an analysis after step ``k``: what :attr:`unilateral.Simulation.state` gives.

    Attributes
    ----------
    t : float, time ``t_k = k dt``, s
    k : int, the step
    u, udot : (n,) displacements and velocities, or None (kernel-only models)
    v : (m,) unilateral deformations;  psi : (m,) constraint reactions
    """

    t: float
    k: int
    u: np.ndarray | None
    udot: np.ndarray | None
    v: np.ndarray
    psi: np.ndarray


def _index(kind, name, names):
    try:
        return names.index(name)
    except ValueError:
        shown = ", ".join(names[:12]) + (", ..." if len(names) > 12 else "")
        raise KeyError(f"no {kind} named {name!r}; known: {shown}") from None
