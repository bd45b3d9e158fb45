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

Two generalisations serve footings that slide on a soil given in the Laplace domain (dual
unknowns): an **unknown map** ``Q`` (friction whose normal force is an unknown ``c``, not a row),
``w = (P W0 + Q) z + ...`` (``Q`` couples only to holonomic unknowns, so ``Q o = 0``); and **free**
unknowns (the patches' shear forces ``f``, of either sign, whose rows are equations ``w = 0``),
eliminated from each step's LCP by the Schur complement of their block
(:class:`FreeCondensation`). Footings that slide in plan have per patch a cone of facets whose
multipliers share the patch's contact as their normal unknown (their row of ``Q``): at most two
facets of a cone are active in a solution, which the pivoting solver respects (``group``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..lcp.base import LCPResult
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
    Q : (m, m) unknown map, or None: ``w`` gains ``Q v`` (friction on a soil contact's force)
    free : (m,) bool, unknowns of either sign whose rows are equations (eliminated each step)
    group : (m,) int, the polygon (of more than four facets) each unknown is a facet of (-1: none);
        a pivoting solver keeps at most two of a polygon active (any three columns are dependent)
    """

    rate: np.ndarray
    P: np.ndarray | None
    kinds: tuple
    partner: np.ndarray
    Q: np.ndarray | None = None
    free: np.ndarray | None = None
    group: np.ndarray | None = None

    def __post_init__(self):
        if self.free is None:
            object.__setattr__(self, "free", np.zeros(self.rate.size, dtype=bool))
        if self.group is None:
            object.__setattr__(self, "group", np.full(self.rate.size, -1, dtype=np.int64))

    @property
    def m(self) -> int:
        return self.rate.size

    @property
    def trivial(self) -> bool:
        """Only holonomic unknowns with their own rows: the paper's LCP as it is."""
        return self.P is None and self.Q is None and not self.rate.any() and not self.free.any()

    @property
    def symmetric(self) -> bool:
        """The step LCP matrix is ``W0`` itself (symmetric)."""
        return self.P is None and self.Q is None

    @property
    def compiled_ok(self) -> bool:
        """The compiled marches apply (no unknown map, no free unknowns)."""
        return self.Q is None and not self.free.any()

    @property
    def faced(self) -> bool:
        """Some unknowns are faces of a pair or facets of a polygon (``W0`` is not a P-matrix)."""
        return bool((self.partner >= 0).any() or (self.group >= 0).any())

    @property
    def code(self) -> int:
        """:data:`LAW_CONTACT`, :data:`LAW_RATE` or :data:`LAW_GENERAL` (compiled marches)."""
        return LAW_CONTACT if self.trivial else (LAW_RATE if self.P is None else LAW_GENERAL)

    def rows(self, psi, v=None):
        """The constraint functions ``P psi - Q v`` of associated values ``psi`` (..., m) and the
        unknowns ``v`` (..., m) (``Q v`` left out when ``v`` is not given)."""
        out = psi if self.P is None else psi @ self.P.T
        return out if self.Q is None or v is None else out - v @ self.Q.T

    def matrix(self, W0) -> np.ndarray:
        """The step LCP matrix ``P W0 + Q``."""
        out = W0 if self.P is None else self.P @ W0
        return out if self.Q is None else out + self.Q

    def step_solver(self, solver, M):
        """What solves the step LCPs of matrix ``M`` (``matrix(W0)``): a :class:`FreeCondensation`
        of ``solver`` when the law has free unknowns; for block principal pivoting on a law with
        faces (:attr:`faced`), :class:`~unilateral.lcp.faces.FaceSetPivoting` with its ``tol`` and
        ``max_iter`` (the step solver of the compiled marches: the face rules, Lemke's method where
        they fail); else ``solver`` itself. Each has ``solve(M, q, active=...)`` returning an
        :class:`~unilateral.lcp.base.LCPResult` over all ``m`` unknowns."""
        if self.free.any():
            return FreeCondensation(solver, M, self.free, self.partner, group=self.group)
        if getattr(solver, "name", "") == "bpp" and self.faced:
            from ..lcp.faces import FaceSetPivoting

            return FaceSetPivoting.of(solver, self.partner, self.group, symmetric=self.symmetric)
        return solver

    def offset(self, v_prev) -> np.ndarray:
        """``o`` (m,): the previous value of the rate unknowns, zero for holonomic ones."""
        return np.where(self.rate, v_prev, 0.0)

    def vector(self, W0, q, o) -> np.ndarray:
        """The step LCP vector ``P (q + W0 o)`` of the associated vector ``q = -a_n``."""
        if self.rate.any():
            q = q + W0 @ o
        return q if self.P is None else self.P @ q

    def compiled(self):
        """``(code, rate (m,) float, P (m, m), partner (m,) int, group (m,) int)`` for the compiled
        marches."""
        if not self.compiled_ok:
            raise ValueError("the compiled marches take no free unknowns and no unknown map (footings "
                             "that slide on a soil); use engine='python'")
        P = np.eye(self.m) if self.P is None else np.ascontiguousarray(self.P)
        return self.code, self.rate.astype(float), P, self.partner, self.group


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
    free = np.zeros(m, dtype=bool)
    kinds = ["contact"] * m
    P = Q = None
    partner = np.full(m, -1, dtype=np.int64)
    group = np.full(m, -1, dtype=np.int64)
    for family in families:
        for polygon in family.polygons():
            group[list(polygon)] = group.max() + 1
        rate[family.indices] = family.law == "rate"
        free[family.indices] = family.law == "free"
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
                                 f"the row of unknown {col}, a contact with a soil in the Laplace domain (its row "
                                 "is the opening, its unknown the force): let the footing slide on the soil with "
                                 "horizontal='soil' and mu (SoilFriction), or use a friction element on a spring "
                                 "contact")
            if rate[col]:
                raise ValueError(f"friction row {row} of family {family.name!r} takes its normal force from "
                                 f"unknown {col}, which is not a contact")
            if P is None:
                P = np.eye(m)
            P[row, col] += factor
        for row, col, factor in family.unknown_coupling():
            if not dual[col]:
                raise ValueError(f"friction row {row} of family {family.name!r} takes its normal force from "
                                 f"unknown {col}, which is not the force of a soil contact (SoilContact)")
            if Q is None:
                Q = np.zeros((m, m))
            Q[row, col] += factor
    return StepLaw(rate=rate, P=P, kinds=tuple(kinds), partner=partner, Q=Q, free=free, group=group)


def default_families(m: int):
    """One contact family over every unknown."""
    return [Contact(np.arange(m))]


class FreeCondensation:
    """Step LCPs with free unknowns, solved by eliminating them first.

    With ``F`` the free unknowns (rows ``w_F = 0``, values of either sign) and ``R`` the others,
    ``M_FF z_F + M_FR z_R + q_F = 0`` gives ``z_F = -M_FF^-1 (q_F + M_FR z_R)``, and the LCP in
    ``z_R`` has the Schur complement ``M_RR - M_RF M_FF^-1 M_FR`` (formed once: ``M`` is the same at
    every step) and ``q_R - M_RF M_FF^-1 q_F``. ``M_FF`` must be invertible (a footing's shear block
    is a negative definite flexibility).

    The two faces of a slip pair have opposite columns: block principal pivoting (``lcp="bpp"``)
    runs compiled with the pair rule of the compiled marches (never both faces active); another
    solver that leaves both active (an open patch, whose slip is free) is asked again from the
    basis that carries their net value on one face (the same ``w``, a regular basis).

    Parameters
    ----------
    solver : LCPSolver
    M : (m, m) the step LCP matrix
    free : (m,) bool
    partner : (m,) int, the opposite face of each pair member (-1: none)
    group : (m,) int, optional
        The polygon of more than four facets (a friction cone in plan) of each unknown, -1 for none:
        at most two of a polygon active at once (:func:`unilateral.lcp.pivoting.bpp`); a step
        that block principal pivoting fails is solved by Lemke's method
        (:func:`unilateral.lcp.pivoting.solve_step`).
    """

    def __init__(self, solver, M, free, partner, *, group=None):
        self.solver = solver
        self.F, self.R = np.flatnonzero(free), np.flatnonzero(~free)
        position = np.full(free.size, -1)
        position[self.R] = np.arange(self.R.size)
        first = [i for i in self.R if partner[i] > i]
        self.pairs = (position[first], position[partner[first]]) if first else None
        self.partner = np.where(partner[self.R] >= 0, position[np.maximum(partner[self.R], 0)], -1)
        self.group = (np.full(self.R.size, -1, dtype=np.int64) if group is None
                      else np.ascontiguousarray(np.asarray(group, dtype=np.int64)[self.R]))
        M_FF = M[np.ix_(self.F, self.F)]
        try:
            inverse = np.linalg.inv(M_FF)
        except np.linalg.LinAlgError:
            raise ValueError("the block of W0 of the free unknowns (footing shear forces) is singular: "
                             "the patches' horizontal flexibility must be definite") from None
        self.back = -inverse @ M[np.ix_(self.F, self.R)]            # z_F = back z_R + gain q_F
        self.gain = -inverse
        self.M_RF = M[np.ix_(self.R, self.F)]
        self.reduced = np.ascontiguousarray(M[np.ix_(self.R, self.R)] + self.M_RF @ self.back)
        self.m = M.shape[0]
        self._faces = None

    def solve(self, M, q, active=None) -> LCPResult:
        """The step LCP ``(M, q)`` over all ``m`` unknowns (``M`` the matrix given at construction)."""
        F, R = self.F, self.R
        q_F = q[F]
        q_R = q[R] + self.M_RF @ (self.gain @ q_F)
        if active is not None:
            active = active[R]
            if self.pairs is not None:              # a warm start with one face of each pair at most
                both = active[self.pairs[0]] & active[self.pairs[1]]
                active[self.pairs[0][both]] = active[self.pairs[1][both]] = False
        if getattr(self.solver, "name", "") == "bpp":
            res = self._bpp(q_R, active)
        else:
            res = self.solver.solve(self.reduced, q_R, active=active)
            if self.pairs is not None:
                res = self._net_pairs(res, q_R)
        v = np.zeros(self.m)
        w = np.zeros(self.m)
        act = np.ones(self.m, dtype=bool)
        v[R], w[R], act[R] = res.v, res.w, res.active
        v[F] = self.back @ res.v + self.gain @ q_F
        return LCPResult(v=v, w=w, active=act, iterations=res.iterations, error=res.error, success=res.success,
                         message=res.message, fallback=res.fallback)

    def _net_pairs(self, res, q_R):
        """``res``, or where a pair is active on both faces, the solution from the basis that carries
        their net value on one face (opposite columns: the same ``w``)."""
        plus, minus = self.pairs
        both = (res.v[plus] > 0) & (res.v[minus] > 0)
        if not both.any():
            return res
        net = res.v[plus] - res.v[minus]
        active = res.v > 0
        active[plus[both]], active[minus[both]] = net[both] > 0, net[both] < 0
        again = self.solver.solve(self.reduced, q_R, active=active)
        return again if again.success or not res.success else res

    def _bpp(self, q_R, active) -> LCPResult:
        """The step solver of the compiled marches on the reduced LCP: block principal pivoting with
        the pair and polygon rules, Lemke's method where it fails
        (:class:`~unilateral.lcp.faces.FaceSetPivoting`)."""
        from ..lcp.faces import FaceSetPivoting

        if self._faces is None:
            self._faces = FaceSetPivoting.of(self.solver, self.partner, self.group, symmetric=False)
        return self._faces.solve(self.reduced, q_R, active=active)
