"""The laws of a 2-D plastic hinge beyond elastic-perfectly-plastic (:meth:`Frame2D.hinge
<unilateral.structure.Frame2D.hinge>`): a convex multi-linear moment-rotation backbone and a polygonal
axial force - moment interaction surface.

**Backbone.** A convex multi-linear backbone ``(theta_1, M_1), ..., (theta_n, M_n)`` (slopes
``S_1 = M_1/theta_1 > S_2 > ... > S_n > S_{n+1} >= 0``, ``S_{n+1}`` the slope beyond the last point)
is the sum of ``n`` elastic-perfectly-plastic springs in parallel (Iwan's parallel model), spring
``s`` of stiffness ``k_s = S_s - S_{s+1}`` yielding at the rotation ``theta_s``, and an elastic spring
``S_{n+1}``: exactly, in loading and in unloading (kinematic hardening, Masing's rule: the unloading
branch is the backbone scaled by two). :func:`backbone_springs` gives the springs;
:func:`.elements.backbone_hinge` their natural form.

**Interaction.** A convex polygon in the plane of the beam's axial force ``N`` (tension positive)
and the end moment ``M``, given by its vertices or by a named shape (:data:`INTERACTION_SHAPES`);
:func:`interaction_polygon` gives its facets ``n_k . (N, M) <= r_k``.
"""

from __future__ import annotations

import numpy as np

#: The named interaction polygons of a 2-D hinge, vertices ``(N/Ny, M/My)`` counter-clockwise:
#: ``"aisc"`` is the bilinear interaction of AISC 360 eq. H1-1 (``|N|/Ny + 8/9 |M|/My <= 1`` for
#: ``|N|/Ny >= 0.2``, ``|N|/(2 Ny) + |M|/My <= 1`` below), exactly a polygon of 8 facets.
INTERACTION_SHAPES = {"aisc": ((1.0, 0.0), (0.2, 0.9), (0.0, 1.0), (-0.2, 0.9),
                               (-1.0, 0.0), (-0.2, -0.9), (0.0, -1.0), (0.2, -0.9))}


def _points(where, arg, value, width=2) -> np.ndarray:
    """``value`` as an (n, width) array of finite floats, n >= 1."""
    try:
        points = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{where}: {arg} must be a list of pairs, got {value!r}") from None
    if points.ndim != 2 or points.shape[1] != width or not len(points) or not np.all(np.isfinite(points)):
        raise ValueError(f"{where}: {arg}={value!r} must be a non-empty list of finite pairs")
    return points


def _branch_slopes(where, points) -> tuple[np.ndarray, np.ndarray]:
    """The yield rotations (increasing magnitudes) and the slopes of one branch of a backbone."""
    theta, M = np.abs(points[:, 0]), np.abs(points[:, 1])
    steps = np.diff(np.concatenate([[0.0], theta]))
    if np.any(steps <= 0):
        raise ValueError(f"{where}: backbone rotations {points[:, 0].tolist()} must grow in magnitude away from "
                         "0, point after point, on each side")
    return theta, np.diff(np.concatenate([[0.0], M])) / steps


def backbone_springs(where, backbone, hardening=0.0) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """The parallel elastic-perfectly-plastic springs of a convex multi-linear backbone.

    Parameters
    ----------
    where : the hinge's label, for the messages
    backbone : sequence of ``(theta, M)`` pairs [rad, force length]
        The points of the moment-rotation backbone beyond the origin, in order away from it. Points
        with ``theta > 0`` (``M > 0``) form the positive branch; points with ``theta < 0`` (``M < 0``),
        if any, the negative branch, which must have the same slopes (the springs' stiffnesses) and
        may yield at other rotations; without them the backbone is symmetric.
    hardening : the slope beyond the last point over the initial slope (0: flat)

    Returns
    -------
    K : the initial stiffness ``M_1/theta_1`` [force length/rad]
    k : (n,) the springs' stiffnesses ``S_s - S_{s+1}``
    theta_plus, theta_minus : (n,) their yield rotations in the positive and negative senses (> 0)

    Raises
    ------
    ValueError
        A point off its quadrant, rotations that do not grow, or a slope that does not decrease
        (softening, or a stiffening segment: a non-convex backbone, which no sum of
        elastic-plastic springs gives and whose step problem may have no solution or several).
    """
    points = _points(where, "backbone", backbone)
    if np.any(points[:, 0] * points[:, 1] <= 0):
        raise ValueError(f"{where}: backbone={backbone!r}: every point (theta, M) needs theta and M nonzero and "
                         "of one sign (positive branch: both > 0; negative branch: both < 0)")
    positive, negative = points[points[:, 0] > 0], points[points[:, 0] < 0]
    if not len(positive):
        raise ValueError(f"{where}: backbone={backbone!r} has no point with theta > 0 (the positive branch)")
    theta_plus, slopes = _branch_slopes(where, positive)
    theta_minus = theta_plus
    if len(negative):
        theta_minus, negative_slopes = _branch_slopes(where, negative)
        if negative_slopes.shape != slopes.shape or not np.allclose(negative_slopes, slopes, rtol=1e-12, atol=0):
            raise ValueError(f"{where}: backbone={backbone!r}: the negative branch's slopes "
                             f"{negative_slopes.tolist()} differ from the positive branch's {slopes.tolist()}; "
                             "a parallel model of elastic-plastic springs (Masing unloading) shares the springs' "
                             "stiffnesses between the two senses, only their yield rotations may differ")
    beyond = hardening * slopes[0]
    full = np.concatenate([slopes, [beyond]])
    if np.any(np.diff(full) >= 0):
        raise ValueError(f"{where}: backbone={backbone!r} has the slopes {slopes.tolist()} and {beyond!r} beyond "
                         "the last point (hardening); they must decrease strictly and stay >= 0 (a convex, "
                         "hardening backbone): a softening or stiffening segment is not convex, no sum of "
                         "elastic-plastic springs gives it and its step problem may have no solution or several")
    return float(slopes[0]), -np.diff(full), theta_plus, theta_minus


def interaction_polygon(where, interaction, *, Ny=None, My=None) -> tuple[np.ndarray, np.ndarray]:
    """The facets ``n_k . (N, M) <= r_k`` of a hinge's axial force - moment interaction polygon.

    Parameters
    ----------
    where : the hinge's label, for the messages
    interaction : str or sequence of ``(N, M)`` vertices [force, force length]
        A shape of :data:`INTERACTION_SHAPES` (scaled by ``Ny`` and ``My``), or the vertices of a
        convex polygon strictly containing ``(0, 0)``, in order around it (either sense), an even
        number of them (the facets are paired ``k, k + n/2``, never both active).
    Ny, My : the yield force in pure tension or compression and the plastic moment, of a shape

    Returns
    -------
    n : (facets, 2) the unit outward normals of the facets in the plane ``(N/N0, M/M0)``, expressed on
        ``(N, M)`` (``N0``, ``M0`` the largest ``|N|``, ``|M|`` of the vertices), as for a 3-D hinge
        (:func:`.elements3d.hinge_polygon`)
    r : (facets,) their resistances (> 0)
    """
    if isinstance(interaction, str):
        if interaction not in INTERACTION_SHAPES:
            raise ValueError(f"{where}: interaction={interaction!r} is not a shape; use one of "
                             f"{', '.join(map(repr, INTERACTION_SHAPES))} or a list of (N, M) vertices")
        if Ny is None or My is None:
            raise ValueError(f"{where}: interaction={interaction!r} needs Ny (the axial yield force) and My "
                             "(the plastic moment), > 0")
        vertices = np.array(INTERACTION_SHAPES[interaction]) * np.array([Ny, My])
    else:
        vertices = _points(where, "interaction", interaction)
    scale = np.max(np.abs(vertices), axis=0)
    x = vertices / np.where(scale > 0, scale, 1.0)
    edges = np.roll(x, -1, axis=0) - x
    g = np.column_stack([edges[:, 1], -edges[:, 0]])          # outward for counter-clockwise vertices
    if np.sum(x[:, 0] * np.roll(x[:, 1], -1) - np.roll(x[:, 0], -1) * x[:, 1]) < 0:
        g = -g
    c = np.sum(g * x, axis=1)
    turns = edges[:, 0] * np.roll(edges[:, 1], -1) - edges[:, 1] * np.roll(edges[:, 0], -1)
    if len(x) < 4 or len(x) % 2 or np.any(c <= 0) or np.any(turns * np.sign(turns.sum()) <= 0):
        raise ValueError(f"{where}: interaction={interaction!r}: give an even number (>= 4) of vertices of a "
                         "strictly convex polygon, in order around the origin (which it must strictly contain): "
                         "the facets are paired (k, k + n/2) as the faces of a yield surface")
    scaled = g / np.where(scale > 0, scale, 1.0)
    s = np.linalg.norm(scaled, axis=1)
    return scaled / s[:, None], c / s
