"""Static checks of unilateral.soil against Boussinesq, Love/Steinbrenner and the rigid punch."""

import numpy as np
import pytest

from unilateral.soil import (HalfSpace, RectangularPatches, disc, mean_inverse_distance,
                             rectangle_corner_displacement)

G, NU = 2.0e7, 0.3


def test_point_load_equals_boussinesq():
    hs = HalfSpace(G=G, nu=NU, rho=1800.0)
    r = np.array([0.5, 1.0, 7.0])
    w = hs.point_green(r, 0.0)[0]
    np.testing.assert_allclose(w.real, (1 - NU) / (2 * np.pi * G * r), rtol=1e-14)
    # continuity: a tiny s gives the same
    np.testing.assert_allclose(hs.point_green(r, 1e-6)[0].real, w.real, rtol=1e-5)


def test_small_patch_far_away_is_a_point_load():
    hs = HalfSpace(G=G, nu=NU, rho=1800.0)
    p = RectangularPatches([[0.0, 0.0]], (0.02, 0.02))
    w = hs.surface_displacement([[3.0, 4.0]], p, 0.0)[0, 0, 0]
    assert w.real == pytest.approx((1 - NU) / (2 * np.pi * G * 5.0), rel=1e-5)


@pytest.mark.parametrize("B, L", [(1.0, 1.0), (2.0, 3.0), (0.5, 4.0)])
def test_corner_displacement_love_steinbrenner(B, L):
    hs = HalfSpace(G=G, nu=NU, rho=1800.0)
    p = RectangularPatches([[B / 2, L / 2]], (B, L))
    q = 1.0 / (B * L)                                     # unit resultant
    w = hs.surface_displacement([[0.0, 0.0], [B, L]], p, 0.0)[0, :, 0].real
    # Steinbrenner influence factor, written independently of the code
    m = L / B
    Is = (m * np.log((1 + np.sqrt(1 + m * m)) / m) + np.log(m + np.sqrt(1 + m * m))) / np.pi
    E = 2 * G * (1 + NU)
    expected = q * B * (1 - NU ** 2) / E * Is
    np.testing.assert_allclose(w, expected, rtol=1e-12)
    assert rectangle_corner_displacement(B, L, q, G, NU) == pytest.approx(expected, rel=1e-12)


def test_mean_inverse_distance_against_quadrature():
    x, wq = np.polynomial.legendre.leggauss(40)
    for dx, dy, rs, ss in [(3.0, 1.0, (1, 2), (1.5, 0.5)), (2.2, -1.7, (1, 1), (1, 1)),
                           (9.0, 2.0, (1, 1), (2, 1))]:
        xr, yr, xs, ys = (0.5 * a * x for a in (*rs, *ss))
        W = np.einsum("a,b,c,d->abcd", wq, wq, wq, wq) / 16
        X = dx + xr[:, None, None, None] - xs[None, :, None, None]
        Y = dy + yr[None, None, :, None] - ys[None, None, None, :]
        brute = np.sum(W / np.hypot(X, Y))
        assert mean_inverse_distance(dx, dy, rs, ss) == pytest.approx(brute, rel=1e-10)
    # self term of the unit square: 4 ln(1 + sqrt2) - 4 (sqrt2 - 1)/3 = 2.97320959...
    assert mean_inverse_distance(0, 0, (1, 1), (1, 1)) == pytest.approx(
        4 * np.log(1 + np.sqrt(2)) - 4 * (np.sqrt(2) - 1) / 3, rel=1e-13)


def test_rigid_disc_static_stiffness_converges():
    """K = 1^T Phi(0)^-1 1 -> 4 G R/(1 - nu) (Boussinesq 1885 rigid punch)."""
    hs = HalfSpace(G=G, nu=NU, rho=1800.0)
    R = 1.5
    errs, hs_ = [], []
    for n in (8, 12, 16, 24):
        p = disc(R, n)
        F = hs.surface_flexibility(p, 0.0)[0].real
        K = np.ones(p.m) @ np.linalg.solve(F, np.ones(p.m))
        Req = np.sqrt(p.areas.sum() / np.pi)               # equal-area radius of the staircase
        errs.append(K / (4 * G * Req / (1 - NU)) - 1)
        hs_.append(2 * R / n)
    errs = np.array(errs)
    assert np.all(errs < 0) and np.all(np.diff(np.abs(errs)) < 0)
    assert abs(errs[-1]) < 0.005
    rate = np.polyfit(np.log(hs_), np.log(np.abs(errs)), 1)[0]
    assert rate > 0.7                                      # measured ~1.0-1.2
