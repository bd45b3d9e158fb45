"""Constraint families: groups of constraint unknowns that share a law.

A model's ``m`` unknowns ``v`` (columns of ``F``, rows and columns of ``H``) are split into
families. Each family names its unknowns (indices into ``0..m-1``) and says

* its **law**: ``"holonomic"`` (the paper's contact: ``v >= 0, psi <= 0, psi^T v = 0``),
  ``"rate"`` (plasticity and friction: the unknown is a multiplier that only accumulates, and
  complementarity holds for its increment, ``d lambda >= 0, phi <= 0, phi^T d lambda = 0``) or
  ``"free"`` (a force of either sign whose row is an equation, ``psi = 0``: the shear of a footing
  patch that sticks to the soil or slides by the slips of its friction pair);
* its **rows**: the constraint function of an unknown is, by default, its own ``psi`` (the
  associated law, ``psi = F^T u - H v - g``); friction replaces the ``psi`` of a slip by
  ``psi_slip + mu psi_normal`` (``T - mu N``): a non-associated law, a non-symmetric step LCP;
* its **row sign**: :class:`SoilContact` rows (a soil in the Laplace domain, in the dual form:
  the unknown is the contact force, the row the opening) enter the LCP with ``P_ii = -1``;
* its **unknown coupling**: :class:`SoilFriction` rows take the normal force from the *unknown*
  of a soil contact (``w = mu c -+ f``), not from its row;
* its **kind** (``"contact"``, ``"yield"``, ``"friction"``, ``"shear"``), for reports and figures.

Methods never look at families: they receive the :class:`~unilateral.constraints.law.StepLaw`
that :func:`~unilateral.constraints.law.step_law` assembles from them.
"""

from __future__ import annotations

from typing import ClassVar

import numpy as np


def _indices(name, value) -> np.ndarray:
    idx = np.atleast_1d(np.asarray(value))
    if idx.ndim != 1 or (idx.size and not np.issubdtype(idx.dtype, np.integer)):
        raise ValueError(f"{name} must be a sequence of constraint indices (integers), got {value!r}")
    return idx.astype(np.int64)


class ConstraintFamily:
    """Unknowns ``indices`` (k,) of a model that obey one law.

    Parameters
    ----------
    indices : sequence of int
        Which of the model's ``m`` unknowns belong to the family.
    name : str, optional
        A label for reports (default: the kind).
    """

    #: ``"holonomic"`` or ``"rate"``.
    law: ClassVar[str] = "holonomic"
    #: What the family models, for reports and figures.
    kind: ClassVar[str] = "contact"
    #: The unknowns are forces and the rows openings (the dual form: :class:`SoilContact`).
    dual_form: ClassVar[bool] = False
    #: The rows are rigid contacts that obey an impact law (:class:`RigidContact`: ``restitution``, ``mu``).
    impact_law: ClassVar[bool] = False

    def __init__(self, indices, *, name=None):
        self.indices = _indices("indices", indices)
        self.name = str(name or self.kind)

    def row_coupling(self):
        """Entries ``(row, column, factor)`` added to the identity row map (none by default)."""
        return ()

    def unknown_coupling(self):
        """Entries ``(row, unknown, factor)``: the row's ``w`` gains ``factor`` times that unknown's
        value (none by default; :class:`SoilFriction`)."""
        return ()

    def pairs(self):
        """Pairs ``(i, j)`` of unknowns with opposite columns (the two faces of a two-sided
        surface): never both active, which the pivoting solvers respect (none by default)."""
        return ()

    def polygons(self):
        """Groups (sequences of unknowns) that are the facets of one polygon of more than four
        facets (a friction cone, the interaction polygon of a 3-D hinge): any three of their
        columns are dependent, so at most two are active, which the pivoting solvers respect
        (none by default)."""
        return ()

    def check(self, m: int) -> None:
        """Raise if an index lies outside ``0..m-1``."""
        bad = self.indices[(self.indices < 0) | (self.indices >= m)]
        if bad.size:
            raise ValueError(f"constraint family {self.name!r} names unknown {int(bad[0])}, but the model "
                             f"has m = {m} unknowns (indices 0..{m - 1})")

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.indices.tolist()}, name={self.name!r})"


class Contact(ConstraintFamily):
    """The paper's unilateral contact: ``v >= 0`` (opening), ``psi <= 0`` (reaction), ``psi v = 0``."""

    law = "holonomic"
    kind = "contact"


class SoilContact(Contact):
    """Contacts with a soil given in the Laplace domain, in the dual (force) form.

    A footing patch ``j`` touches a soil whose surface displacement is a convolution of the contact
    forces (``Phi * c``, :class:`~unilateral.soil.SoilFlexibility`): its unknown is the compressive
    contact force ``c_j >= 0`` and its constraint function the opening ``o_j >= 0``
    (:class:`~unilateral.soil.FoundationModel`). In the kernel of a model that also has the paper's
    (primal) unknowns, its row carries ``+o`` (a symmetric ``Lambda``); the row map turns it into
    the LCP's ``w = o`` (``P`` has ``-1`` on its diagonal), so that methods see only the step law.
    """

    law = "holonomic"
    kind = "contact"
    dual_form = True

    def row_coupling(self):
        return tuple((int(i), int(i), -2.0) for i in self.indices)


class RigidContact(SoilContact):
    """Rigid unilateral contacts (no compliance: ``H = 0``), in the dual (force) form.

    The unknown ``v_j >= 0`` is the compressive contact force, the column ``F_j = N_j`` the
    direction in which it pushes the structure away from the obstacle, and the row
    ``psi_j = N_j^T u - g_j`` the opening (``g_j = -gap``). The row map ``P_jj = -1`` (that of
    :class:`SoilContact`) makes the LCP's ``w = psi >= 0``: the opening, complementary to the
    force, with the positive definite step matrix ``N^T D_eff^-1 N``
    (:mod:`unilateral.structure.rigid`). ``K`` is then the stiffness of the structure *without* its
    rigid contacts, which may be singular or indefinite (a free block, the negative stiffness of
    rocking).

    ``restitution`` (k,) holds Newton's coefficient ``e`` of each contact (0 <= e <= 1; a scalar
    for all), used by the velocity-level impact law of ``method="moreau-jean"``; ``mu`` (k,) the
    Coulomb coefficients (0: no friction) and ``tangent`` the contacts' tangential directions on the
    DOFs, for the friction of ``method="moreau-jean"`` (the only method that takes it): (n, k), one
    tangent per contact (a 2-D contact: ``|T| <= mu N`` on that line), or (n, k, 2), the axes
    ``t1``, ``t2`` of each contact's tangent plane (a 3-D contact), whose friction cone is the
    polygon of ``facets`` (k,) facets (even, >= 4) circumscribing Coulomb's circle ``|T| <= mu N``:
    facet ``j`` of the unit normal ``d_j = (cos th_j, sin th_j)`` on ``(t1, t2)``, ``th_j = 2 pi j /
    facets``, keeps ``d_j . T <= mu N`` (:func:`friction_polygon`; the convention of the 3-D
    frictional contacts and footings, :func:`unilateral.structure.elements3d.facet_directions`).
    """

    impact_law = True

    def __init__(self, indices, *, restitution=0.0, mu=0.0, tangent=None, facets=None, name=None):
        super().__init__(indices, name=name)
        e = np.broadcast_to(np.asarray(restitution, dtype=float), self.indices.shape).copy()
        if not np.all((e >= 0) & (e <= 1)):
            raise ValueError(f"restitution={restitution!r} must lie in [0, 1] (Newton's coefficient of restitution)")
        self.restitution = e
        self.mu = np.broadcast_to(np.asarray(mu, dtype=float), self.indices.shape).copy()
        if not np.all(self.mu >= 0) or (self.mu.any() and tangent is None):
            raise ValueError(f"mu={mu!r} must be >= 0, and friction needs the contacts' tangent directions")
        self.tangent = None if tangent is None else np.asarray(tangent, dtype=float)
        k = self.indices.size
        if self.tangent is not None and (self.tangent.ndim not in (2, 3) or self.tangent.shape[1] != k
                                         or (self.tangent.ndim == 3 and self.tangent.shape[2] != 2)):
            raise ValueError(f"tangent has the shape {self.tangent.shape}; give (n, {k}) (one tangent per contact) "
                             f"or (n, {k}, 2) (the axes t1, t2 of each contact's tangent plane)")
        plane = self.tangent is not None and self.tangent.ndim == 3
        if plane:
            self.facets = np.broadcast_to(np.asarray(4 if facets is None else facets), (k,)).copy()
            bad = [f for f in self.facets.tolist() if isinstance(f, bool) or not isinstance(f, int) or f < 4 or f % 2]
            if bad:
                raise ValueError(f"facets={facets!r} is not valid; give the facets of the friction polygon of each "
                                 "contact, an even int >= 4 (opposite facets in pairs; 4: the pyramid of t1, t2)")
        elif facets is not None:
            raise ValueError(f"facets={facets!r} is for contacts with a tangent plane (tangent of shape (n, k, 2))")
        else:
            self.facets = np.full(k, 2, dtype=np.int64)

    def tangent_axes(self, j) -> np.ndarray:
        """The tangent axes (n, r) of the contact at position ``j`` of the family: r = 1 (2-D) or 2."""
        return self.tangent[:, j][:, None] if self.tangent.ndim == 2 else self.tangent[:, j, :]


def friction_polygon(facets: int) -> tuple[np.ndarray, np.ndarray]:
    """The friction cone of a rigid contact on its tangent axes, for ``mu N = 1``:
    ``(normals (F, r), generators (F, r))``.

    ``facets = 2`` (a 2-D contact, ``r = 1``): the segment ``|T| <= 1``, normals and generators
    ``+1``, ``-1``. ``facets >= 4`` (even; ``r = 2``): the polygon circumscribing the unit circle,
    facet ``j`` of the outward normal ``d_j = (cos th_j, sin th_j)``, ``th_j = 2 pi j / facets``,
    at distance 1 (``d_j . T <= 1``), its vertices the generators ``sec(pi/F) (cos(th_j + pi/F),
    sin(th_j + pi/F))``. Components within 1e-12 of 0 or +-1 are made exact (``facets=4``: the
    facets ``+-t1``, ``+-t2`` and the vertices ``(+-1, +-1)``).
    """
    if facets == 2:
        unit = np.array([[1.0], [-1.0]])
        return unit, unit.copy()
    th = 2.0 * np.pi * np.arange(facets) / facets
    out = []
    for angle, radius in ((th, 1.0), (th + np.pi / facets, 1.0 / np.cos(np.pi / facets))):
        d = radius * np.column_stack([np.cos(angle), np.sin(angle)])
        for exact in (0.0, 1.0, -1.0):
            d[np.abs(d - exact) < 1e-12] = exact
        out.append(d)
    return out[0], out[1]


class SoilShear(ConstraintFamily):
    """The horizontal force of a footing patch on a soil given in the Laplace domain (dual form).

    Its unknown ``f`` is the patch's horizontal force on the soil (either sign; the soil's force on
    the footing is ``-f``); its row is the equation ``psi = slip - (x_footing - x_soil) = 0``: the
    footing and the soil surface move together horizontally but for the slip of the patch (the
    increments of a :class:`SoilFriction` pair). Each step's LCP eliminates these unknowns by the
    Schur complement of their (definite) block of ``W0`` before pivoting.
    """

    law = "free"
    kind = "shear"


class Yield(ConstraintFamily):
    """Plastic multipliers: ``lambda`` only grows; ``d lambda >= 0, phi <= 0, phi d lambda = 0``.

    ``phi = F^T u - H lambda - g`` is the yield function of one face of a piecewise-linear yield
    surface: ``F`` carries the plastic strain into the structure as an imposed strain, ``H`` holds
    its self-stress and the hardening, ``g`` the yield force. A two-sided surface
    (``-F_c <= N <= F_t``) is two multipliers with opposite columns.

    Parameters
    ----------
    indices : sequence of int
        The multipliers; with ``two_sided`` (default) in pairs ``(+ face, - face)``.
    two_sided : bool
        The indices come in pairs of opposite faces of two-sided surfaces.
    polygons : sequence of sequences of int, optional
        The multipliers that are the facets of one polygonal yield surface of more than four
        facets (a 3-D hinge's interaction polygon in the plane of its two end moments; see
        :meth:`ConstraintFamily.polygons`).
    name : str, optional
    """

    law = "rate"
    kind = "yield"

    def __init__(self, indices, *, two_sided=True, polygons=(), name=None):
        super().__init__(indices, name=name)
        self.two_sided = bool(two_sided)
        if self.two_sided and self.indices.size % 2:
            raise ValueError(f"a two-sided yield family needs its multipliers in pairs (+ face, - face); "
                             f"got {self.indices.size} indices (give two_sided=False for one-sided faces)")
        self._polygons = tuple(tuple(int(i) for i in group) for group in polygons)
        outside = {i for group in self._polygons for i in group} - set(self.indices.tolist())
        if outside:
            raise ValueError(f"polygons name unknown {min(outside)}, which is not a multiplier of the family")

    def pairs(self):
        if not self.two_sided:
            return ()
        return tuple(zip(self.indices[0::2].tolist(), self.indices[1::2].tolist()))

    def polygons(self):
        return self._polygons


class Bearing(Yield):
    """One-sided plastic multipliers: the compression face of a contact with a bearing capacity.

    A soil spring with a bearing capacity (:meth:`Frame2D.soil <unilateral.structure.Frame2D.soil>`
    with ``bearing``) carries its contact ``v`` (holonomic, the opening: ``sigma <= r``) and a
    plastic settlement ``w`` (rate: ``dw >= 0``, ``phi = -sigma - Q <= 0``, ``phi dw = 0``) on one
    strain with opposite columns of ``B``. The two are never active together (``sigma = r >= 0``
    against ``sigma = -Q < 0``); their block of ``W0`` is singular, so each settlement is the
    ``partner`` of its contact (:meth:`ConstraintFamily.pairs`) for the pivoting solvers.

    Parameters
    ----------
    indices : sequence of int, the settlement multipliers
    contacts : sequence of int, per multiplier the index of its element's contact unknown
    name : str, optional
    """

    def __init__(self, indices, *, contacts, name=None):
        super().__init__(indices, two_sided=False, name=name or "bearing")
        self.contacts = _indices("contacts", contacts)
        if self.contacts.shape != self.indices.shape:
            raise ValueError(f"contacts must name one contact per settlement multiplier ({self.indices.size}), "
                             f"got {self.contacts.size}")

    def pairs(self):
        return tuple(zip(self.contacts.tolist(), self.indices.tolist()))

    def check(self, m: int) -> None:
        super().check(m)
        bad = self.contacts[(self.contacts < 0) | (self.contacts >= m)]
        if bad.size:
            raise ValueError(f"bearing family {self.name!r} names contact {int(bad[0])}, but the model has "
                             f"m = {m} unknowns")


class Friction(ConstraintFamily):
    """Coulomb slip multipliers of 2D contacts: ``|T| <= mu N``, slip increments in the sense of ``T``.

    Each slip pair ``(s+, s-)`` is two multipliers with opposite columns (the tangential force
    ``T = psi(s+) = -psi(s-)``); their constraint functions are ``psi(s+-) + mu psi(n)``, i.e.
    ``+-T - mu N <= 0`` with ``N = -psi(n)`` the compressive force of the normal contact ``n``.
    With ``normal = None`` the normal force is a constant already in ``g`` (a flat slider).

    Parameters
    ----------
    indices : sequence of int, the slip multipliers in pairs (``s+``, ``s-``)
    normal : sequence of int or None, per slip multiplier the index of its normal contact
        (``-1``: constant normal force)
    mu : float or sequence of float, per slip multiplier, >= 0
    """

    law = "rate"
    kind = "friction"

    def __init__(self, indices, *, normal=None, mu=0.0, name=None):
        super().__init__(indices, name=name)
        k = self.indices.size
        self.normal = (np.full(k, -1, dtype=np.int64) if normal is None
                       else _indices("normal", normal))
        self.mu = np.broadcast_to(np.asarray(mu, dtype=float), (k,)).copy()
        if self.normal.shape != (k,):
            raise ValueError(f"normal must name one contact per slip multiplier ({k}), got {self.normal.size}")
        if np.any(~np.isfinite(self.mu)) or np.any(self.mu < 0):
            raise ValueError(f"mu must be finite and >= 0 (friction coefficients), got {self.mu.tolist()}")
        if k % 2:
            raise ValueError(f"friction slips come in pairs (s+, s-); got {k} indices")

    def pairs(self):
        return tuple(zip(self.indices[0::2].tolist(), self.indices[1::2].tolist()))

    def polygons(self):
        """The slips of more than four facets sharing one normal contact: a polygonal friction cone
        (a contact in 3-D)."""
        groups = {}
        for i, n in zip(self.indices.tolist(), self.normal.tolist()):
            if n >= 0:
                groups.setdefault(n, []).append(i)
        return tuple(tuple(g) for g in groups.values() if len(g) > 4)

    def row_coupling(self):
        return tuple((int(i), int(n), float(mu)) for i, n, mu in zip(self.indices, self.normal, self.mu)
                     if n >= 0 and mu != 0.0)

    def check(self, m: int) -> None:
        super().check(m)
        bad = self.normal[(self.normal >= m) | (self.normal < -1)]
        if bad.size:
            raise ValueError(f"friction family {self.name!r} names normal contact {int(bad[0])}, but the model "
                             f"has m = {m} unknowns")


class SoilFriction(Friction):
    """Coulomb slip of footing patches on a soil given in the Laplace domain (dual form).

    A footing in plan has per patch a polygonal cone of ``N`` facets (opposite facets in pairs,
    ``(k, k + N/2)``), each a slip multiplier with the same law ``w_k = mu c - d_k . f``: the rows
    ``psi_k = d_k . f`` come from the kernel's constant coupling to the shears
    (:meth:`FoundationModel.weights <unilateral.soil.FoundationModel.weights>`), so the family is
    the same, with ``normal`` naming the patch's contact for each of its ``N`` multipliers.

    A slip pair ``(s+, s-)`` of a patch whose normal unknown is the compressive force ``c`` of a
    :class:`SoilContact` and whose shear unknown ``f`` a :class:`SoilShear`: the pair's rows are
    ``psi(s+-) = +-f`` and the law ``w = mu c -+ f >= 0``, complementary to the slip increments: the
    patch slides only where ``|f| = mu c``, in the sense of ``f``. The normal force is the
    soil contact's unknown (not its row, the opening): the coupling is to unknowns.

    Parameters
    ----------
    indices : sequence of int, the slip multipliers in pairs (``s+``, ``s-``)
    normal : sequence of int, per slip multiplier the index of its patch's soil contact
    mu : float or sequence of float, per slip multiplier, >= 0
    """

    def __init__(self, indices, *, normal, mu, name=None):
        super().__init__(indices, normal=normal, mu=mu, name=name)
        if np.any(self.normal < 0):
            raise ValueError("soil friction takes its normal force from a soil contact: give the index of "
                             "one for every slip multiplier")

    def row_coupling(self):
        return ()

    def unknown_coupling(self):
        return tuple((int(i), int(n), float(mu)) for i, n, mu in zip(self.indices, self.normal, self.mu)
                     if mu != 0.0)
