"""Dynamic surface Green's function and patch flexibilities of unilateral.soil.HalfSpace."""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, RectangularPatches, grid, strips

# Wong (1975) exact contour integration as tabulated by Apsel (1979, UCSD PhD, Table 5.1):
# nu = 0.33 (printed; the values fit nu = 1/3 better: max deviation 7.8e-4 vs 1.6e-3), vertical point force, surface receiver, G r u_z / P at r0 = omega r / c_s
# (e^{+i omega t}, i.e. our s = i omega). Printed to 3 decimals.
APSEL = {0.5: (.087, -.062), 1.0: (.037, -.102), 1.5: (-.029, -.108), 2.0: (-.087, -.077),
         2.5: (-.120, -.017), 3.0: (-.114, .053), 3.5: (-.070, .110), 4.0: (-.001, .134),
         4.5: (.072, .118), 5.0: (.127, .064), 5.5: (.144, -.013)}


def test_point_green_matches_wong_apsel_table():
    hs = HalfSpace(G=1.0, nu=1 / 3, rho=1.0)
    r0 = np.array(sorted(APSEL))
    g = hs.point_green(1.0, 1j * r0)[:, 0]
    ref = np.array([complex(*APSEL[x]) for x in r0])
    assert np.max(np.abs(g - ref)) < 1e-3                 # table rounding 5e-4 (values ~0.13)


def test_point_green_real_axis_against_direct_quadrature():
    """For real s > 0 the integrand is smooth on the real k axis: plain adaptive quadrature."""
    from scipy.integrate import quad
    from scipy.special import j0
    nu, s, r = 0.25, 1.3, 1.0
    hs = HalfSpace(G=1.0, nu=nu, rho=1.0)
    eta = (1 - 2 * nu) / (2 * (1 - nu))

    def f(k):
        a, b = np.sqrt(k * k + eta * s * s), np.sqrt(k * k + s * s)
        return (s * s * a / ((2 * k * k + s * s) ** 2 - 4 * k * k * a * b) - (1 - nu) / k) * k * j0(k * r)

    val = sum(quad(f, 0.5 * i, 0.5 * i + 0.5, limit=200)[0] for i in range(600))
    expected = (1 - nu) / (2 * np.pi * r) + val / (2 * np.pi)
    assert hs.point_green(r, s)[0, 0].real == pytest.approx(expected, abs=2e-7)


def test_flexibility_symmetry_conjugation_and_statics():
    hs = HalfSpace(G=3e7, nu=0.3, rho=1900.0)
    p = grid(6.0, 4.0, 3, 2)
    s = np.array([0.0, 1e-6, 20.0, 50j, 3 + 80j, 3 - 80j])
    F = hs.surface_flexibility(p, s)
    assert F.shape == (6, 6, 6)
    np.testing.assert_array_equal(F, F.transpose(0, 2, 1))
    np.testing.assert_allclose(F[5], np.conj(F[4]), rtol=1e-13)
    np.testing.assert_allclose(F[1], F[0], rtol=1e-6)
    assert np.all(np.abs(F[0].imag) == 0)
    # positive definite static and real-s flexibilities (energy)
    for i in (0, 2):
        assert np.linalg.eigvalsh(F[i].real).min() > 0


def test_wavenumber_truncation_converged():
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    p = grid(10.0, 10.0, 4, 5)
    s = np.array([0.5, 2j, 0.01 + 3j, 5.0])
    a = hs.surface_flexibility(p, s)
    b = hs.surface_flexibility(p, s, kmax_factor=2.0)
    assert np.max(np.abs(a - b)) / np.max(np.abs(b)) < 1e-4


def test_patch_source_equals_integrated_point_green():
    """Displacement at a point from a uniformly loaded patch = point Green's function integrated over
    the patch (8 x 8 Gauss; the integrand is smooth at this distance)."""
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    a, b = 1.0, 0.6
    p = RectangularPatches([[0.0, 0.0]], (a, b))
    x, w = np.polynomial.legendre.leggauss(8)
    X, Y = np.meshgrid(0.5 * a * x, 0.5 * b * x, indexing="ij")
    W = np.outer(w, w).ravel() / 4
    recv = np.array([3.0, 4.0])
    r = np.hypot(recv[0] - X.ravel(), recv[1] - Y.ravel())
    s = np.array([0.5, 2j, 0.01 + 3j])
    ref = hs.point_green(r, s) @ W
    got = hs.surface_displacement([recv], p, s)[:, 0, 0]
    np.testing.assert_allclose(got, ref, rtol=1e-5)
    # and the averaged flexibility between two small distant patches tends to the point value
    q = RectangularPatches([[0.0, 0.0], [3.0, 4.0]], (0.1, 0.1))
    F = hs.surface_flexibility(q, s)[:, 0, 1]
    np.testing.assert_allclose(F, hs.point_green(5.0, s)[:, 0], rtol=2e-2)


def test_strips_layout():
    p = strips(4.0, 20.0, 8)
    assert p.m == 8 and np.allclose(p.sizes, [0.5, 20.0]) and p.areas.sum() == pytest.approx(80.0)
    assert p.centres[0, 0] == pytest.approx(-1.75)


def test_damping_models():
    hs = HalfSpace(G=1.0, nu=0.3, rho=1.0, damping=0.05, omega_ref=10.0)
    Gs = hs.modulus(np.array([10j, 100j, 1j]))
    # constant Q: loss tangent 2 xi at every frequency, exactly G(1 + 2 i xi) at omega_ref
    np.testing.assert_allclose(Gs.imag / Gs.real, 0.1, rtol=1e-12)
    assert Gs[0] == pytest.approx(1 + 0.1j, rel=1e-12)
    kv = HalfSpace(G=1.0, nu=0.3, rho=1.0, damping=0.05, damping_model="kelvin_voigt", omega_ref=10.0)
    assert kv.modulus(10j) == pytest.approx(1 + 0.1j)
    # damping reduces the far-field amplitude of the wave
    el = HalfSpace(G=1.0, nu=0.3, rho=1.0)
    assert abs(hs.point_green(10.0, 5j)[0, 0]) < abs(el.point_green(10.0, 5j)[0, 0])
    with pytest.raises(ValueError, match="constant_q"):
        hs.point_green(1.0, 0.0)


def test_bad_input():
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    with pytest.raises(ValueError, match="Re s"):
        hs.point_green(1.0, -1.0)
    with pytest.raises(ValueError, match="nu"):
        HalfSpace(G=1.0, nu=0.5, rho=1.0)
    with pytest.raises(ValueError, match="positive sides"):
        hs.surface_flexibility(RectangularPatches([[0, 0]], (0.0, 1.0)), 1.0)
