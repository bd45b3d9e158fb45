"""The compiled angular sums of :mod:`unilateral.soil.lamb` against the straightforward numpy sums.

The reference functions below are the previous implementation of the angular factors (one
``cos``/``sin`` per distinct key and angle, batched products over the angles): the compiled loop
evaluates the same quadrature (same wavenumber and angular nodes), so the flexibilities must agree
to round-off.
"""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, RectangularPatches, grid, lamb, strips
from unilateral.soil.patches import pair_table

RTOL = 1e-12


# --- reference: the straightforward numpy sums -----------------------------------------------------

def _factor(kc, d, a1, a2):
    """``sinc(kc a1/2) sinc(kc a2/2) cos(kc d)``."""
    out = np.cos(kc * d)
    for a in (a1, a2):
        if a > 0:
            z = 0.5 * a * kc
            out = out * (np.sin(z) / z)
    return out


def _factors(kc, keys, odd=False):
    """:func:`_factor` (or with ``sin(kc d)`` when ``odd``) of every key (U, 3), stacked: (..., U)."""
    trig = np.sin if odd else np.cos
    sizes, group = np.unique(keys[:, 1:], axis=0, return_inverse=True)
    sincs = [_factor(kc, 0.0, a1, a2) for a1, a2 in sizes]
    return np.stack([trig(kc * d) * sincs[g] for (d, _, _), g in zip(keys, group.ravel())], axis=-1)


REFERENCE_WEIGHTS = {"1": (None, False, False), "cc": (lambda c, s: c * c, False, False),
                     "cs": (lambda c, s: c * s, True, True), "c": (lambda c, s: c, True, False),
                     "s": (lambda c, s: s, False, True)}


def reference_angular_components(k, keys, names, chunk_entries=2_000_000):
    """Angular factors ``{name: (nk, P)}`` by batched products over the angles."""
    k = np.asarray(k)
    P = keys.shape[0]
    xkeys, ix = np.unique(np.round(keys[:, [0, 2, 4]], 12), axis=0, return_inverse=True)
    ykeys, iy = np.unique(np.round(keys[:, [1, 3, 5]], 12), axis=0, return_inverse=True)
    ix, iy = ix.ravel(), iy.ravel()
    Rmax = float(lamb.pair_extent(keys).max())
    specs = [(nm,) + REFERENCE_WEIGHTS[nm] for nm in names]
    out = {nm: np.empty((k.size, P), dtype=complex) for nm in names}
    for idx, n in lamb._angular_groups(k, Rmax):
        step = max(1, chunk_entries // (n * (2 * len(xkeys) + 2 * len(ykeys) + len(names) * P)))
        theta = (np.arange(n) + 0.5) * (0.5 * np.pi / n)
        c, s = np.cos(theta), np.sin(theta)
        for j in range(0, idx.size, step):
            sel = idx[j:j + step]
            kk = k[sel][:, None]
            kx, ky = kk * c[None, :], kk * s[None, :]
            for nm, wfun, ox, oy in specs:
                Sx = _factors(kx, xkeys, ox)
                if wfun is not None:
                    Sx = Sx * wfun(c, s)[None, :, None]
                M = np.matmul(Sx.transpose(0, 2, 1), _factors(ky, ykeys, oy))
                out[nm][sel] = (2.0 * np.pi / n) * M[:, ix, iy]
    return out


def reference_angular(k, keys):
    return reference_angular_components(k, keys, ["1"])["1"]


# --- cases ---------------------------------------------------------------------------------------

def _two_footings():
    a = strips(2.0, 2.0, 3)
    return RectangularPatches(np.vstack([a.centres, a.centres + [3.0, 0.0]]), np.vstack([a.sizes, a.sizes]))


def _unequal():
    rng = np.random.default_rng(7)
    return RectangularPatches(rng.uniform(-1.5, 1.5, (4, 2)), rng.uniform(0.3, 1.2, (4, 2)))


PATCH_SETS = {
    "strips": lambda: strips(3.0, 3.0, 4),
    "strips_thirds": lambda: strips(1.0, 2.0, 3),           # offsets off a binary grid (rounding)
    "two_footings": _two_footings,
    "grid": lambda: grid(2.0, 1.5, 3, 2),
    "unequal": _unequal,
}
S_VALUES = np.array([0.0, 0.7, 1e-4 + 2e-4j, 2.0 + 5.0j, 0.3 - 4.0j, 12.0j])


def _relative_error(new, ref):
    return np.max(np.abs(new - ref)) / np.max(np.abs(ref))


@pytest.mark.parametrize("name", sorted(PATCH_SETS))
@pytest.mark.parametrize("components", ["z", "xz", "xyz"])
def test_surface_flexibility_equals_reference_sums(name, components, monkeypatch):
    hs = HalfSpace(G=1.0, nu=0.3, rho=1.0)
    patches = PATCH_SETS[name]()
    new = hs.surface_flexibility(patches, S_VALUES, components=components)
    monkeypatch.setattr(lamb, "angular", reference_angular)
    monkeypatch.setattr(lamb, "angular_components", reference_angular_components)
    ref = hs.surface_flexibility(patches, S_VALUES, components=components)
    assert _relative_error(new, ref) <= RTOL
    for i in range(S_VALUES.size):                        # and per s, relative to its largest entry
        assert _relative_error(new[i], ref[i]) <= RTOL


def _contour_nodes(keys, kmax):
    D = float(lamb.pair_extent(keys).max())
    k, _ = lamb.contour(0.3, D, kmax)
    return k


@pytest.mark.parametrize("name", sorted(PATCH_SETS))
def test_angular_components_equal_reference(name):
    patches = PATCH_SETS[name]()
    keys, _ = pair_table(patches, patches, symmetric=True)
    k = _contour_nodes(keys, 60.0)
    names = ["1", "cc", "cs", "c", "s"]
    new = lamb.angular_components(k, keys, names)
    ref = reference_angular_components(k, keys, names)
    scale = np.max(np.abs(ref["1"]))
    for nm in names:
        assert np.max(np.abs(new[nm] - ref[nm])) <= RTOL * scale
    assert np.max(np.abs(lamb.angular(k, keys) - ref["1"])) <= RTOL * scale


def test_long_progressions_and_unsorted_offsets():
    """More steps than ``_ANCHOR`` (re-anchored powers), offsets that are not multiples of the step,
    points (zero sides) and a receiver table (no zero offset)."""
    d = np.arange(0, 140) * 0.05
    keys = np.column_stack([d, np.zeros_like(d), np.full_like(d, 0.05), np.full_like(d, 0.4),
                            np.full_like(d, 0.05), np.full_like(d, 0.4)])
    keys = np.vstack([keys, [[0.3 + 3e-12, 0.2, 0.05, 0.4, 0.05, 0.4], [1.234567, 0.7, 0.0, 0.0, 0.1, 0.3]]])
    k = _contour_nodes(keys, 15.0)
    m, r = lamb._axis_plan(np.unique(np.round(keys[:, [0, 2, 4]], 12), axis=0), np.abs(k).max())[3:5]
    assert m.max() > lamb._ANCHOR and np.any(r != 0.0) and np.any(m < 0)     # all three paths
    ref = reference_angular_components(k, keys, ["1", "c", "cs"])
    new = lamb.angular_components(k, keys, ["1", "c", "cs"])
    scale = np.max(np.abs(ref["1"]))
    for nm in ref:
        assert np.max(np.abs(new[nm] - ref[nm])) <= RTOL * scale

    recv = RectangularPatches([[0.25, 0.1], [1.75, -0.4], [3.1, 0.0]], np.zeros((3, 2)))
    src = strips(2.0, 1.0, 4)
    keys, _ = pair_table(recv, src, symmetric=False)
    k = _contour_nodes(keys, 40.0)
    ref = reference_angular(k, keys)
    assert np.max(np.abs(lamb.angular(k, keys) - ref)) <= RTOL * np.max(np.abs(ref))


def test_surface_displacement_equals_reference_sums(monkeypatch):
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    src = _two_footings()
    pts = np.array([[0.0, 0.0], [1.3, 0.2], [4.0, -0.5]])
    new = hs.surface_displacement(pts, src, S_VALUES)
    monkeypatch.setattr(lamb, "angular", reference_angular)
    ref = hs.surface_displacement(pts, src, S_VALUES)
    assert _relative_error(new, ref) <= RTOL
