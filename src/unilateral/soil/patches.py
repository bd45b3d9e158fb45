"""Rectangular surface patches (boundary elements with uniform vertical traction).

A patch ``j`` is an axis-parallel rectangle with centre ``(x_j, y_j)`` and sides ``(a_j, b_j)``.
Flexibilities are defined for a *uniform* vertical traction of unit resultant on the source patch and
the vertical displacement *averaged* over the receiver patch; this Galerkin-type definition makes the
flexibility matrix symmetric (reciprocity).  A patch with zero sides is a point.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V

__all__ = ["RectangularPatches", "strips", "grid", "disc", "points"]


class RectangularPatches:
    """A set of ``m`` axis-parallel rectangular patches on the surface ``z = 0``.

    Parameters
    ----------
    centres : (m, 2) array_like, m
        Patch centres ``(x, y)``.
    sizes : (m, 2) array_like or (2,), m
        Sides ``(a, b)`` along x and y, >= 0 (zero sides: a point load/receiver). A single pair is
        broadcast to all patches.

    Attributes
    ----------
    centres, sizes : (m, 2) float ndarray
    m : int
        Number of patches.
    areas : (m,) float ndarray, m^2
    """

    def __init__(self, centres, sizes):
        c = V.as_matrix("centres", centres, (None, 2), allow_sparse=False)
        sz = np.asarray(sizes, dtype=float)
        if sz.ndim == 1 and sz.shape == (2,):
            sz = np.tile(sz, (c.shape[0], 1))
        sz = V.as_matrix("sizes", sz, (c.shape[0], 2), allow_sparse=False)
        if np.any(sz < 0):
            raise ValueError(f"sizes must be >= 0, got minimum {sz.min()!r}")
        self.centres = c
        self.sizes = sz

    @property
    def m(self) -> int:
        return self.centres.shape[0]

    def __len__(self) -> int:
        return self.m

    @property
    def areas(self) -> np.ndarray:
        return self.sizes[:, 0] * self.sizes[:, 1]

    def __repr__(self) -> str:
        return f"RectangularPatches(m={self.m})"


def strips(width, length, m) -> RectangularPatches:
    """``m`` strips side by side across the width of a ``width x length`` footing.

    Strip ``j`` has sides ``(width/m, length)`` and centre ``(-width/2 + (j + 1/2) width/m, 0)``: the
    footing is centred at the origin, its width along x. Suited to a long (quasi-2D) footing whose
    contact varies across the width only.
    """
    width = V.positive_float("width", width)
    length = V.positive_float("length", length)
    m = int(m)
    if m < 1:
        raise ValueError(f"m must be >= 1, got {m}")
    h = width / m
    x = -0.5 * width + (np.arange(m) + 0.5) * h
    return RectangularPatches(np.column_stack([x, np.zeros(m)]), (h, length))


def grid(Lx, Ly, nx, ny) -> RectangularPatches:
    """Regular ``nx x ny`` grid of patches covering ``[-Lx/2, Lx/2] x [-Ly/2, Ly/2]``.

    Patches are ordered with x varying fastest (index ``i + nx j``).
    """
    Lx = V.positive_float("Lx", Lx)
    Ly = V.positive_float("Ly", Ly)
    nx, ny = int(nx), int(ny)
    if nx < 1 or ny < 1:
        raise ValueError(f"nx, ny must be >= 1, got {nx}, {ny}")
    hx, hy = Lx / nx, Ly / ny
    x = -0.5 * Lx + (np.arange(nx) + 0.5) * hx
    y = -0.5 * Ly + (np.arange(ny) + 0.5) * hy
    X, Y = np.meshgrid(x, y)
    return RectangularPatches(np.column_stack([X.ravel(), Y.ravel()]), (hx, hy))


def disc(R, n) -> RectangularPatches:
    """Square patches approximating a disc of radius ``R``.

    The square ``[-R, R]^2`` is cut into ``n x n`` cells of side ``h = 2R/n``; cells whose centre lies
    inside the circle are kept. The kept area differs from ``pi R^2`` by O(h); use
    ``sqrt(areas.sum()/pi)`` as an equal-area radius if wanted.
    """
    R = V.positive_float("R", R)
    n = int(n)
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    g = grid(2 * R, 2 * R, n, n)
    keep = np.hypot(g.centres[:, 0], g.centres[:, 1]) < R
    return RectangularPatches(g.centres[keep], g.sizes[keep])


def points(xy) -> RectangularPatches:
    """Point receivers/loads at ``xy`` ((m, 2), m): patches of zero size."""
    xy = V.as_matrix("xy", xy, (None, 2), allow_sparse=False)
    return RectangularPatches(xy, np.zeros_like(xy))


def pair_table(recv: RectangularPatches, src: RectangularPatches, symmetric: bool):
    """Distinct receiver/source pair geometries.

    The flexibility of a pair depends only on ``(|dx|, |dy|)`` and the two sizes (the kernel is even in
    ``dx`` and ``dy``), and, for a symmetric (same patches) table, is invariant under swapping receiver
    and source. Returns ``(keys, index)``: ``keys`` (P, 6) = ``|dx|, |dy|, a_r, b_r, a_s, b_s`` and
    ``index`` (m_r, m_s) int mapping each pair to its row in ``keys``.
    """
    d = recv.centres[:, None, :] - src.centres[None, :, :]
    ar = np.broadcast_to(recv.sizes[:, None, :], d.shape)
    as_ = np.broadcast_to(src.sizes[None, :, :], d.shape)
    keys = np.concatenate([np.abs(d), ar, as_], axis=-1).reshape(-1, 6)
    if symmetric:
        swapped = keys[:, [0, 1, 4, 5, 2, 3]]
        # choose the lexicographically smaller of (sizes, swapped sizes) per row
        a = keys[:, 2:]
        b = swapped[:, 2:]
        use_b = np.zeros(len(keys), dtype=bool)
        undecided = np.ones(len(keys), dtype=bool)
        for c in range(4):
            lt = undecided & (b[:, c] < a[:, c])
            gt = undecided & (b[:, c] > a[:, c])
            use_b |= lt
            undecided &= ~(lt | gt)
        keys = np.where(use_b[:, None], swapped, keys)
    scale = max(float(np.max(np.abs(keys))), 1e-300)
    q = np.round(keys * (1e9 / scale)).astype(np.int64)
    order = np.lexsort(q.T[::-1])
    qs = q[order]
    new_group = np.ones(len(qs), dtype=bool)
    new_group[1:] = np.any(qs[1:] != qs[:-1], axis=1)
    group = np.cumsum(new_group) - 1
    inverse = np.empty(len(qs), dtype=np.int64)
    inverse[order] = group
    first = order[new_group]
    return keys[first], inverse.reshape(recv.m, src.m)
