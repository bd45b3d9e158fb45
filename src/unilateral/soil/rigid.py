"""Impedances of rigid surface footings from the patch flexibility by rigid-body condensation.

A rigid massless footing covering the patches moves with the generalised displacements ``q`` (the
DOFs below); the patch-averaged displacements are ``u = A q`` (exact for a rigid body: the average of
a linear field over a rectangle is its value at the centre), the patch forces ``F = Phi(s)^{-1} u``
and the generalised forces ``Q = A^T F``, so

    K(s) = A^T Phi(s)^{-1} A                                   (Galerkin / boundary-element condensation)

with ``Phi`` from :meth:`.HalfSpace.surface_flexibility`. Axes: ``x, y`` along the patch coordinates,
``z`` positive down (into the soil), right-handed; rotations by the right-hand rule about the axes
through the origin, so that for the patch centre ``(x, y)``

* ``"x"``: ``u_x = 1``; ``"y"``: ``u_y = 1``; ``"z"``: ``u_z = 1`` (down);
* ``"rx"``: ``u_z = y``; ``"ry"``: ``u_z = -x`` (a positive ``ry`` lifts the ``+x`` edge);
  ``"rz"``: ``u_x = -y``, ``u_y = x``;

and the generalised forces are the force components and the moments ``M = sum r x F`` about the
origin. Contact models:

* ``"relaxed"`` (default): the classical mixed boundary-value problems of Luco & Westmann (1971,
  *J. Eng. Mech. Div. ASCE* 97, 1381-1395) and Veletsos & Wei (1971, *J. Soil Mech. Found. Div. ASCE*
  97, 1227-1248): no shear traction for the vertical and rocking DOFs, no normal traction for the
  horizontal and torsional ones; the horizontal-rocking coupling is then zero. Static values of a
  disc of radius ``R``: ``4GR/(1-nu)`` (vertical), ``8GR/(2-nu)`` (horizontal), ``8GR^3/(3(1-nu))``
  (rocking), ``16GR^3/3`` (torsion).
* ``"welded"``: all three traction components act on every patch (bonded footing), which couples the
  horizontal and rocking DOFs through the ``(1 - 2 nu)`` terms of the surface Green's tensor and
  stiffens the footing slightly for ``nu < 1/2``.

Discretisation: piecewise-constant tractions on the patches miss the inverse-square-root edge
singularity, so the stiffness converges like ``O(h)`` from below (``h`` the patch side); a staircase
disc (:func:`.patches.disc`) also has an ``O(h)`` area error - compare with the equal-area radius
``sqrt(areas.sum()/pi)``.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from .patches import RectangularPatches

__all__ = ["rigid_impedance", "rigid_kinematics"]

_DOFS = ("x", "y", "z", "rx", "ry", "rz")
_HORIZONTAL = {"x", "y", "rz"}


def rigid_kinematics(patches: RectangularPatches, dofs) -> np.ndarray:
    """Rigid-body matrix ``A`` (3m, nd): x, y, z displacement blocks of the patch centres per DOF.

    Parameters
    ----------
    patches : RectangularPatches
        ``m`` patches.
    dofs : sequence of {"x", "y", "z", "rx", "ry", "rz"}
        Generalised displacements (m and rad), see the module docstring for the signs.

    Returns
    -------
    (3m, nd) float ndarray
        Rows ``0..m-1`` the x components, ``m..2m-1`` y, ``2m..3m-1`` z (the order of
        ``surface_flexibility(..., components="xyz")``).
    """
    x, y = patches.centres[:, 0], patches.centres[:, 1]
    m = patches.m
    one, zero = np.ones(m), np.zeros(m)
    cols = {"x": (one, zero, zero), "y": (zero, one, zero), "z": (zero, zero, one),
            "rx": (zero, zero, y), "ry": (zero, zero, -x), "rz": (-y, x, zero)}
    return np.column_stack([np.concatenate(cols[d]) for d in dofs])


def rigid_impedance(halfspace, patches: RectangularPatches, s, dofs=("x", "z", "ry"), *,
                    contact="relaxed", kmax_factor=1.0) -> np.ndarray:
    """Impedance matrix ``K(s) = A^T Phi(s)^{-1} A`` of a rigid massless footing on the patches.

    Parameters
    ----------
    halfspace : HalfSpace
        The soil.
    patches : RectangularPatches
        Contact area (e.g. :func:`.patches.disc`, :func:`.patches.grid`, :func:`.patches.strips`).
    s : complex scalar or (ns,) array, 1/s
        Laplace variable(s), ``Re s >= 0`` (``s = i omega`` for the frequency response).
    dofs : sequence of {"x", "y", "z", "rx", "ry", "rz"}
        Generalised displacements, in the order of the rows/columns of ``K``.
    contact : {"relaxed", "welded"}
        See the module docstring.
    kmax_factor : float
        Passed to :meth:`.HalfSpace.surface_flexibility`.

    Returns
    -------
    K : (ns, nd, nd) complex
        N/m (force per translation), N m/rad (moment per rotation), N/rad or N m/m (coupling).
        Symmetric; ``K(conj s) = conj K(s)``.

    Notes
    -----
    Normalised dynamic coefficients in the frequency domain: ``K(i omega) = K_static (k + i a0 c)``,
    ``a0 = omega R / c_s``. References for a disc: Luco & Westmann (1971), Veletsos & Wei (1971), and
    the Veletsos & Verbic (1973) fits in :mod:`.impedances`.
    """
    if not isinstance(patches, RectangularPatches):
        raise TypeError(f"patches must be RectangularPatches, got {V.describe(patches)}")
    dofs = tuple(dofs)
    bad = [d for d in dofs if d not in _DOFS]
    if bad or not dofs or len(set(dofs)) != len(dofs):
        raise ValueError(f"dofs must be distinct names among {_DOFS}, got {dofs!r}")
    contact = V.choice("contact", contact, {"relaxed", "welded"})
    m = patches.m
    A = rigid_kinematics(patches, dofs)                                   # (3m, nd)
    horiz = [i for i, d in enumerate(dofs) if d in _HORIZONTAL]
    vert = [i for i, d in enumerate(dofs) if d not in _HORIZONTAL]
    if contact == "welded" or horiz:
        Phi = halfspace.surface_flexibility(patches, s, components="xyz", kmax_factor=kmax_factor)
    else:
        Phi = halfspace.surface_flexibility(patches, s, kmax_factor=kmax_factor)
        Phi = np.pad(Phi, ((0, 0), (2 * m, 0), (2 * m, 0)))              # only the z block is used
    ns = Phi.shape[0]
    K = np.zeros((ns, len(dofs), len(dofs)), dtype=complex)
    if contact == "welded":
        groups = [(slice(0, 3 * m), list(range(len(dofs))))]
    else:
        groups = [(slice(0, 2 * m), horiz), (slice(2 * m, 3 * m), vert)]
    for rows, cols in groups:
        if not cols:
            continue
        Ag = A[rows][:, cols]
        sol = np.linalg.solve(Phi[:, rows, rows], np.broadcast_to(Ag, (ns,) + Ag.shape))
        ii, jj = np.ix_(cols, cols)
        K[:, ii, jj] = np.einsum("ia,sib->sab", Ag, sol)
    return K
