"""The step law: what the constraint families make of each step's LCP.

Every method reduces a step to ``psi_n = a_n - W0 v_n`` (``a_n``: the known part, the bilateral
response minus the history). Holonomic unknowns enter the LCP as they are. A rate unknown
(plastic multiplier, slip) enters by its increment ``z = v_n - v_{n-1}``, so with
``o = [0 (holonomic); v_{n-1} (rate)]``, ``v_n = z + o`` and

    w = -P psi_n = P W0 z + P (W0 o - a_n),     z >= 0,  w >= 0,  z^T w = 0,

one LCP per step with the same ``W0`` for every method (the constraint functions ``P psi``:
``P = I`` but for friction rows, ``psi_slip + mu psi_normal``). The history and the recovery of
``u`` use ``v`` as for contact alone. ``Solution.psi`` holds the constraint functions ``P psi``
(contact: the reaction; yield and friction: the yield function, ``<= 0``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .families import ConstraintFamily, Contact, SoilContact

#: Compiled marches: no rate unknowns and ``P = I``; rate unknowns only; rate unknowns and ``P``.
LAW_CONTACT, LAW_RATE, LAW_GENERAL = 0, 1, 2


@dataclass(frozen=True)
class StepLaw:
    """The law of each of ``m`` unknowns, as the marches use it.

    Attributes
    ----------
    rate : (m,) bool, True for unknowns complementary in their increments
    P : (m, m) row map of the constraint functions, or None (identity)
    kinds : tuple of m str, ``"contact"``, ``"yield"`` or ``"friction"``
    partner : (m,) int, the opposite face of a two-sided pair (-1: none); a pivoting solver never
        makes both active (their columns are opposite: the pair's block of ``W0`` is singular)
    """

    rate: np.ndarray
    P: np.ndarray | None
    kinds: tuple
    partner: np.ndarray

    @property
    def m(self) -> int:
        return self.rate.size

    @property
    def trivial(self) -> bool:
        """Only holonomic unknowns with their own rows: the paper's LCP as it is."""
        return self.P is None and not self.rate.any()

    @property
    def symmetric(self) -> bool:
        """The step LCP matrix is ``W0`` itself (symmetric)."""
        return self.P is None

    @property
    def code(self) -> int:
        """:data:`LAW_CONTACT`, :data:`LAW_RATE` or :data:`LAW_GENERAL` (compiled marches)."""
        return LAW_CONTACT if self.trivial else (LAW_RATE if self.P is None else LAW_GENERAL)

    def rows(self, psi):
        """The constraint functions ``P psi`` of associated values ``psi`` (..., m)."""
        return psi if self.P is None else psi @ self.P.T

    def matrix(self, W0) -> np.ndarray:
        """The step LCP matrix ``P W0``."""
        return W0 if self.P is None else self.P @ W0

    def offset(self, v_prev) -> np.ndarray:
        """``o`` (m,): the previous value of the rate unknowns, zero for holonomic ones."""
        return np.where(self.rate, v_prev, 0.0)

    def vector(self, W0, q, o) -> np.ndarray:
        """The step LCP vector ``P (q + W0 o)`` of the associated vector ``q = -a_n``."""
        if self.rate.any():
            q = q + W0 @ o
        return q if self.P is None else self.P @ q

    def compiled(self):
        """``(code, rate (m,) float, P (m, m), partner (m,) int)`` for the compiled marches."""
        P = np.eye(self.m) if self.P is None else np.ascontiguousarray(self.P)
        return self.code, self.rate.astype(float), P, self.partner


def contact_law(m: int) -> StepLaw:
    """The law of ``m`` contact unknowns (the paper's LCP)."""
    return StepLaw(rate=np.zeros(m, dtype=bool), P=None, kinds=("contact",) * m,
                   partner=np.full(m, -1, dtype=np.int64))


def step_law(families, m: int) -> StepLaw:
    """Assemble the :class:`StepLaw` of ``families``; unknowns that no family names are contacts.

    Raises
    ------
    ValueError
        An unknown in two families, an index out of range, or a friction row whose normal unknown
        is not a contact.
    """
    families = list(families or ())
    owner = np.full(m, -1)
    for f, family in enumerate(families):
        if not isinstance(family, ConstraintFamily):
            raise TypeError(f"families[{f}] must be a ConstraintFamily (Contact, Yield, Friction), "
                            f"got {type(family).__name__}")
        family.check(m)
        twice = family.indices[owner[family.indices] >= 0]
        if twice.size or np.unique(family.indices).size != family.indices.size:
            i = int(twice[0]) if twice.size else int(family.indices[0])
            raise ValueError(f"constraint unknown {i} belongs to two families (family {family.name!r})")
        owner[family.indices] = f
    rate = np.zeros(m, dtype=bool)
    kinds = ["contact"] * m
    P = None
    partner = np.full(m, -1, dtype=np.int64)
    for family in families:
        rate[family.indices] = family.law == "rate"
        for i in family.indices:
            kinds[i] = family.kind
        for i, j in family.pairs():
            partner[i], partner[j] = j, i
    dual = np.zeros(m, dtype=bool)
    for family in families:
        dual[family.indices] = isinstance(family, SoilContact)
    for family in families:
        for row, col, factor in family.row_coupling():
            if row != col and dual[col]:
                raise ValueError(f"friction row {row} of family {family.name!r} takes its normal force from "
                                 f"unknown {col}, a contact with a soil in the Laplace domain (its row is the "
                                 "opening, not the force): friction on such patches is not available; give "
                                 "the footing a slider or a friction element on a spring contact")
            if rate[col]:
                raise ValueError(f"friction row {row} of family {family.name!r} takes its normal force from "
                                 f"unknown {col}, which is not a contact")
            if P is None:
                P = np.eye(m)
            P[row, col] += factor
    return StepLaw(rate=rate, P=P, kinds=tuple(kinds), partner=partner)


def default_families(m: int):
    """One contact family over every unknown."""
    return [Contact(np.arange(m))]
