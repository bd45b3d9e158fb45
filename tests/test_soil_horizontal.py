"""Horizontal and coupled surface flexibilities of unilateral.soil.HalfSpace; rigid-footing impedances."""

import numpy as np
import pytest
from scipy.special import j0, j1

from unilateral.soil import (HalfSpace, RectangularPatches, disc, grid, rigid_impedance, strips,
                             veletsos_verbic)
from unilateral.soil.statics import _CERRUTI_KERNELS, cerruti, cerruti_averages

NU = 1 / 3


def _xyz(F, m, i, j):
    """3x3 tensor block (row patch i, column patch j) of an (3m, 3m) matrix."""
    return np.array([[F[a * m + i, b * m + j] for b in range(3)] for a in range(3)])


# --- statics -------------------------------------------------------------------------------------

@pytest.mark.parametrize("s", [0.0, 1e-6])
def test_cerruti_between_small_distant_patches(s):
    """Small (0.1) patches 5 apart: Cerruti's values within 1e-3 (the patch-size effect is ~1e-4)."""
    G, r = 2.0e7, 5.0
    hs = HalfSpace(G=G, nu=NU, rho=1800.0)
    # receivers ahead of an x force (patch 1) and across it (patch 2)
    p = RectangularPatches([[0.0, 0.0], [r, 0.0], [0.0, r]], (0.1, 0.1))
    F = hs.surface_flexibility(p, s, components="xyz")[0]
    assert np.all(np.abs(F.imag) <= 1e-12 * np.abs(F).max())
    m = 3
    along, across = F[1, 0].real, F[2, 0].real                        # u_x at (r,0), (0,r) per P_x
    assert along == pytest.approx(1 / (2 * np.pi * G * r), rel=1e-3)
    assert across == pytest.approx((1 - NU) / (2 * np.pi * G * r), rel=1e-3)
    c = (1 - 2 * NU) / (4 * np.pi * G * r)
    # sign convention (docstring): z down; a +x force pushes the surface DOWN ahead of it
    assert F[2 * m + 1, 0].real == pytest.approx(c, rel=1e-3)          # u_z at (r, 0) per P_x
    assert F[2 * m + 2, 0].real == pytest.approx(0.0, abs=1e-6 * c)    # u_z at (0, r) per P_x
    assert F[1, 2 * m].real == pytest.approx(-c, rel=1e-3)             # u_x at (r, 0) per P_z: inward
    assert F[m + 2, 2 * m].real == pytest.approx(-c, rel=1e-3)         # u_y at (0, r) per P_z
    # the full tensor against the point formula
    T = cerruti(r, 0.0, G, NU)
    np.testing.assert_allclose(_xyz(F.real, m, 1, 0), T, rtol=1e-3, atol=1e-6 * T.max())
    T = cerruti(0.0, -r, G, NU)                                          # patch 0 seen from patch 2
    np.testing.assert_allclose(_xyz(F.real, m, 0, 2), T, rtol=1e-3, atol=1e-6 * T.max())


def test_cerruti_averages_closed_form_vs_quadrature():
    x, wq = np.polynomial.legendre.leggauss(40)
    W = np.einsum("a,b,c,d->abcd", wq, wq, wq, wq) / 16
    for dx, dy, rs, ss in [(3.0, 1.0, (1, 2), (1.5, 0.5)), (2.2, -1.7, (1, 1), (1, 1)),
                           (-1.3, 0.4, (1.0, 0.7), (0.8, 0.5)), (9.0, -2.0, (1, 1), (2, 1))]:
        xr, yr, xs, ys = (0.5 * a * x for a in (*rs, *ss))
        X = dx + xr[:, None, None, None] - xs[None, :, None, None]
        Y = dy + yr[None, None, :, None] - ys[None, None, None, :]
        brute = np.array([np.sum(W * f(X, Y)) for f in _CERRUTI_KERNELS])
        got = cerruti_averages(dx, dy, rs, ss)
        np.testing.assert_allclose(got, brute, rtol=1e-9, atol=1e-12)
    # touching / overlapping pairs: d2r/dx2 + d2r/dy2 = 1/r, odd kernels vanish on symmetric pairs
    for dx, dy, rs, ss in [(0.0, 0.0, (1, 1), (1, 1)), (1.0, 0.0, (1, 1), (1, 1)), (0.3, 0.2, (1, .6), (.5, .9))]:
        a = cerruti_averages(dx, dy, rs, ss)
        assert a[1] + a[2] == pytest.approx(a[0], rel=1e-12)
    a = cerruti_averages(0.0, 0.0, (1.0, 0.5), (0.3, 0.8))
    assert np.all(np.abs(a[3:]) < 1e-14)


# --- dynamics ------------------------------------------------------------------------------------

def hankel_parts(s, nu, r, kmax=150.0, fine=1200):
    """Independent reference (G = rho = 1): the Hankel-transform representation of the surface Green's
    tensor of Lamb's problem, integrated on the REAL k axis (needs Re s > 0) with panelled 16-point
    Gauss-Legendre, ``fine`` panels on ``[0, 3|s|]`` (branch points, Rayleigh pole), 0.25 beyond.
    For a unit force at the origin and a receiver at ``(r cos t, r sin t)``:

        u_xx = A0 - A2 cos 2t,  u_yy = A0 + A2 cos 2t,  u_xy = -A2 sin 2t,
        u_zx = C1 cos t,  u_zy = C1 sin t,  u_zz = Z0,
        A0 = (1/2pi) int k (K_rr + K_tt)/2 J0(kr) dk,   A2 = (1/2pi) int k (K_rr - K_tt)/2 J2(kr) dk,
        C1 = (1/2pi) int k K_c J1(kr) dk,               Z0 = (1/2pi) int k K_zz J0(kr) dk,

    K_rr = S beta/R, K_tt = 1/beta, K_c = k (2 alpha beta - 2k^2 - S)/R, K_zz = S alpha/R, statics
    subtracted in the integrand and added in closed form (Cerruti/Boussinesq). Returns (A0, A2, C1, Z0),
    each of the shape of ``r``."""
    r = np.atleast_1d(np.asarray(r, dtype=float))
    eta = (1 - 2 * nu) / (2 * (1 - nu))
    S = s * s
    edges = np.unique(np.concatenate([np.linspace(0, 3 * abs(s), fine + 1),
                                      np.arange(3 * abs(s), kmax, 0.25), [kmax]]))
    x, w = np.polynomial.legendre.leggauss(16)
    lo, hi = edges[:-1, None], edges[1:, None]
    k = (0.5 * (lo + hi) + 0.5 * (hi - lo) * x).ravel()
    g = (0.5 * (hi - lo) * w).ravel() * k / (2 * np.pi)
    al, be = np.sqrt(k * k + eta * S), np.sqrt(k * k + S)
    a = 2 * k * k + S
    R = a * a - 4 * k * k * al * be
    krr = S * be / R - (1 - nu) / k
    ktt = 1 / be - 1 / k
    kc = k * (2 * al * be - a) / R - (1 - 2 * nu) / (2 * k)
    kzz = S * al / R - (1 - nu) / k
    kr = k[:, None] * r[None, :]
    J0, J1 = j0(kr), j1(kr)
    J2 = 2 * J1 / kr - J0
    return ((g * 0.5 * (krr + ktt)) @ J0 + (2 - nu) / (4 * np.pi * r),
            (g * 0.5 * (krr - ktt)) @ J2 - nu / (4 * np.pi * r),
            (g * kc) @ J1 + (1 - 2 * nu) / (4 * np.pi * r),
            (g * kzz) @ J0 + (1 - nu) / (2 * np.pi * r))


def hankel_reference(s, nu):
    """u_xx (receiver along the force), u_yy (across), u_zx (ahead), u_zz at r = 1."""
    A0, A2, C1, Z0 = (v[0] for v in hankel_parts(s, nu, 1.0))
    return np.array([A0 - A2, A0 + A2, C1, Z0])


def _point_values(hs, s):
    p = RectangularPatches([[0.0, 0.0], [1.0, 0.0]], (0.02, 0.02))
    F = hs.surface_flexibility(p, s, components="xyz")
    m = 2
    return np.stack([F[:, 1, 0], F[:, m + 1, m], F[:, 2 * m + 1, 0], F[:, 2 * m + 1, 2 * m]], axis=-1)


# Wong (1975, Caltech EERL 75-01: exact contour integration) as tabulated by Apsel (1979, UCSD PhD
# thesis, Table 5.1): surface point loads on an elastic half-space, nu = 0.33 (printed), G r u / P at
# r0 = omega r / c_s, e^{+i omega t} (our s = i omega), three decimals. Columns: U_r0 (radial
# displacement per vertical force), U_z0 (vertical per vertical), U_r1 (radial per horizontal, times
# cos theta: along the force) and U_theta1 (tangential per horizontal, times sin theta: across it).
# Static row: Boussinesq and Cerruti exactly (-.027 = -(1-2nu)/(4 pi), .106 = (1-nu)/(2 pi), ...).
WONG_APSEL = {  # r0: (U_r0, U_z0, U_r1, U_theta1), each (Re, Im)
    0.5: ((-.032, .007), (.087, -.062), (.146, -.058), (-.089, .058)),
    1.0: ((-.033, .025), (.037, -.102), (.112, -.105), (-.045, .099)),
    1.5: ((-.020, .047), (-.029, -.108), (.063, -.133), (.015, .112)),
    2.0: ((.006, .060), (-.087, -.077), (.011, -.137), (.075, .093)),
    2.5: ((.041, .058), (-.120, -.017), (-.034, -.120), (.118, .045)),
    3.0: ((.074, .035), (-.114, .053), (-.064, -.090), (.132, -.020)),
    3.5: ((.092, -.005), (-.070, .110), (-.076, -.054), (.111, -.084)),
    4.0: ((.087, -.054), (-.001, .134), (-.075, -.024), (.059, -.132)),
    4.5: ((.056, -.096), (.072, .118), (-.065, -.004), (-.014, -.144)),
    5.0: ((.005, -.120), (.127, .064), (-.054, .004), (-.088, -.129)),
    5.5: ((-.054, -.116), (.144, -.013), (-.048, .003), (-.145, -.077)),
}


def _wong_apsel_in_our_terms(r0):
    """The table's four columns as ``(u_xx, u_yy, u_zx, u_zz)`` of :func:`_point_values` (receiver
    at +x of the source): along the force ``U_r1``; across it ``-U_theta1`` (at theta = 90 deg the
    tangential unit vector points against the force; statically ``-U_theta1 = (1 - nu)/(2 pi)``,
    Cerruti); ``u_z`` per ``P_x`` is ``-U_r0`` (reciprocity, z down); ``u_z`` per ``P_z`` is ``U_z0``."""
    u_r0, u_z0, u_r1, u_t1 = (complex(*c) for c in WONG_APSEL[r0])
    return np.array([u_r1, -u_t1, -u_r0, u_z0])


def test_point_flexibilities_against_wong_apsel_table():
    """Every component of the surface Green's tensor (horizontal along and across the force, the
    horizontal-vertical coupling, vertical) at a0 = 1 within 0.005 of the published table (issue
    acceptance), and within the table's stated precision where it is exact: measured 1.3e-3 at a0 = 1
    for the horizontal columns, 8e-4 for the vertical-force ones, 4.9e-3 over a0 = 0.5 .. 5.5 (the
    horizontal columns drift from the table at large a0 by a few 1e-3; Apsel's own wavenumber
    integration differs from Wong's by up to 0.005 too)."""
    hs = HalfSpace(G=1.0, nu=NU, rho=1.0)
    r0 = np.array(sorted(WONG_APSEL))
    got = _point_values(hs, 1j * r0)
    ref = np.array([_wong_apsel_in_our_terms(x) for x in r0])
    err = np.abs(got - ref)
    at1 = err[list(r0).index(1.0)]
    print(f"\n  |module - Wong/Apsel| at a0 = 1 (u_xx, u_yy, u_zx, u_zz): {np.round(at1, 4)}; "
          f"largest over a0 = 0.5..5.5: {err.max(axis=0).round(4)}")
    assert at1.max() < 0.005                                 # the tolerance at a0 = 1
    assert at1[2:].max() < 1.5e-3 and err[:, 2:].max() < 1.5e-3     # vertical-force columns, all a0
    assert err.max() < 6e-3                                  # horizontal columns over the whole table


def test_point_flexibilities_at_a0_1_against_real_axis_hankel_integral():
    """G r u/P at a0 = omega r/c_s = 1, nu = 1/3 (small patches at r = 1).

    The reference is the independent real-axis Hankel quadrature above: at s = eps + i directly,
    and at s = i by Richardson extrapolation eps = 0.02, 0.01 -> 0 (the published table is checked
    in :func:`test_point_flexibilities_against_wong_apsel_table`)."""
    hs = HalfSpace(G=1.0, nu=NU, rho=1.0)
    got = _point_values(hs, np.array([0.02 + 1j, 1j]))
    ref_eps = hankel_reference(0.02 + 1j, NU)
    ref_0 = 2 * hankel_reference(0.01 + 1j, NU) - ref_eps
    err_eps, err_0 = np.abs(got[0] - ref_eps).max(), np.abs(got[1] - ref_0).max()
    print(f"\n  a0=1 point flexibilities u_xx, u_yy, u_zx, u_zz = {np.round(got[1], 5)}"
          f"\n  |module - Hankel ref|: {err_eps:.1e} at s=0.02+i, {err_0:.1e} at s=i (extrapolated)")
    assert err_eps < 5e-5 and err_0 < 1e-4                   # measured 7.9e-6 and 1.7e-5
    # Apsel (1979, Table 5.1; Wong 1975) vertical, a0 = 1: .037 - .102 i (3 decimals)
    assert abs(got[1, 3] - (0.037 - 0.102j)) < 0.005
    # radiation: the imaginary parts are negative (e^{+i omega t}, energy flows out)
    assert np.all(got[1, [0, 1, 3]].imag < 0)


def test_finite_patches_oblique_all_components_against_hankel_integral():
    """Two unequal patches in an oblique direction, s = 0.05 + 1.5i, nu = 1/4: every tensor component
    (including x-y and the signed odd ones) equals the real-axis Hankel reference integrated over both
    patches (4 x 4 Gauss points each; the integrand is smooth at this distance). Measured <= 1.3e-9
    (values ~1e-2)."""
    nu, s = 0.25, 0.05 + 1.5j
    hs = HalfSpace(G=1.0, nu=nu, rho=1.0)
    c = np.array([[0.0, 0.0], [2.5, 1.7]])
    sz = np.array([[1.0, 0.6], [0.8, 0.5]])
    F = hs.surface_flexibility(RectangularPatches(c, sz), s, components="xyz")[0]
    g, w = np.polynomial.legendre.leggauss(4)

    def nodes(i):
        X, Y = np.meshgrid(c[i, 0] + 0.5 * sz[i, 0] * g, c[i, 1] + 0.5 * sz[i, 1] * g, indexing="ij")
        return np.column_stack([X.ravel(), Y.ravel()]), np.outer(w, w).ravel() / 4

    (pr, wr), (ps, ws) = nodes(1), nodes(0)                  # receiver patch 1, source patch 0
    d = (pr[:, None, :] - ps[None, :, :]).reshape(-1, 2)
    r, t = np.hypot(d[:, 0], d[:, 1]), np.arctan2(d[:, 1], d[:, 0])
    W = (wr[:, None] * ws[None, :]).ravel()
    A0, A2, C1, Z0 = hankel_parts(s, nu, r, fine=300)
    m = 2
    pairs = [(F[1, 0], A0 - A2 * np.cos(2 * t)), (F[m + 1, m], A0 + A2 * np.cos(2 * t)),
             (F[1, m], -A2 * np.sin(2 * t)), (F[m + 1, 0], -A2 * np.sin(2 * t)),
             (F[2 * m + 1, 0], C1 * np.cos(t)), (F[2 * m + 1, m], C1 * np.sin(t)),
             (F[0, 2 * m + 1], C1 * np.cos(t)), (F[2 * m + 1, 2 * m], Z0)]
    err = max(abs(got - np.sum(W * ref)) for got, ref in pairs)
    print(f"\n  oblique finite patches, max |module - Hankel ref| = {err:.1e}")
    assert err < 1e-7


def test_symmetry_conjugation_and_vertical_block():
    hs = HalfSpace(G=3e7, nu=0.3, rho=1900.0)
    rng = np.random.default_rng(3)
    # unequal sizes, irregular positions: exercises the swapped (receiver <-> source) pair keys
    c = np.array([[0.0, 0.0], [1.3, 0.2], [-0.7, 1.9], [2.5, -1.1], [0.4, -2.0]])
    p = RectangularPatches(c, rng.uniform(0.5, 1.0, size=(5, 2)))
    s = np.array([0.0, 1e-6, 20.0, 50j, 3 + 80j, 3 - 80j])
    F3 = hs.surface_flexibility(p, s, components="xyz")
    F2 = hs.surface_flexibility(p, s, components="xz")
    Fz = hs.surface_flexibility(p, s)
    m = p.m
    assert F3.shape == (6, 3 * m, 3 * m) and F2.shape == (6, 2 * m, 2 * m) and Fz.shape == (6, m, m)
    for F in (F2, F3):
        sym = np.abs(F - F.transpose(0, 2, 1)).max() / np.abs(F).max()
        assert sym < 1e-10
        np.testing.assert_allclose(F[5], np.conj(F[4]), rtol=1e-13)
        np.testing.assert_allclose(F[1], F[0], rtol=2e-6, atol=2e-6 * np.abs(F[0]).max())
        assert np.all(F[0].imag == 0)
        for i in (0, 2):                                      # energy: positive definite
            assert np.linalg.eigvalsh(F[i].real).min() > 0
    np.testing.assert_allclose(F3[:, 2 * m:, 2 * m:], Fz, rtol=1e-12, atol=1e-14 * np.abs(Fz).max())
    np.testing.assert_allclose(F2[:, m:, m:], Fz, rtol=1e-12, atol=1e-14 * np.abs(Fz).max())
    xz = np.r_[0:m, 2 * m:3 * m]
    np.testing.assert_allclose(F2, F3[:, xz][:, :, xz], rtol=1e-12, atol=1e-14 * np.abs(F3).max())
    # the x-z coupling is odd in the separation: zero between patches with equal x, sign of dx else
    zx = F3[0, 2 * m:, :m]
    dx = c[:, 0][:, None] - c[:, 0][None, :]
    assert np.all(np.sign(zx[np.abs(dx) > 0.5]) == np.sign(dx[np.abs(dx) > 0.5]))
    assert np.all(np.diag(zx) == 0)


def test_tensor_wavenumber_truncation_converged():
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    p = grid(6.0, 4.0, 3, 2)
    s = np.array([0.5, 2j, 0.01 + 3j])
    a = hs.surface_flexibility(p, s, components="xyz")
    b = hs.surface_flexibility(p, s, components="xyz", kmax_factor=2.0)
    assert np.max(np.abs(a - b)) / np.max(np.abs(b)) < 1e-4


def test_bad_components():
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    with pytest.raises(ValueError, match="components"):
        hs.surface_flexibility(grid(1.0, 1.0, 1, 1), 1.0, components="xy")


# --- rigid footings ------------------------------------------------------------------------------

def test_rigid_disc_static_impedances_converge():
    """Relaxed contact, equal-area radius: 8GR/(2-nu), 4GR/(1-nu), 8GR^3/(3(1-nu))."""
    hs = HalfSpace(G=1.0, nu=NU, rho=1.0)
    ns, errs = (8, 12, 16, 20), []
    for n in ns:
        p = disc(1.0, n)
        R = np.sqrt(p.areas.sum() / np.pi)
        K = rigid_impedance(hs, p, 0.0, dofs=("x", "z", "ry"))[0]
        assert np.all(K.imag == 0) and K[0, 2] == 0 and K[0, 1] == 0
        exact = np.array([8 * R / (2 - NU), 4 * R / (1 - NU), 8 * R ** 3 / (3 * (1 - NU))])
        errs.append(np.diag(K.real) / exact - 1)
    errs = np.array(errs)
    h = 2.0 / np.array(ns)
    rates = [np.polyfit(np.log(h), np.log(np.abs(e)), 1)[0] for e in errs.T]
    print(f"\n  static disc errors (x, z, ry) vs n = {ns}:\n{np.round(100 * errs, 3)} %"
          f"\n  fitted rates h^p: {np.round(rates, 2)}")
    assert np.all(errs < 0)                                          # from below (missing edge singularity)
    assert np.all(np.abs(errs[-1]) < [0.005, 0.005, 0.015])          # measured 0.38, 0.41, 1.24 %
    assert np.all(np.abs(errs[-1]) < np.abs(errs[0]))
    assert min(rates) > 0.8                                          # measured 1.26-1.34


def test_welded_disc_vertical_ratio_mossakovskii():
    """Bonded vs frictionless rigid punch: K_welded/K_relaxed = (1 - nu) ln(3 - 4 nu)/(1 - 2 nu)
    (Mossakovskii 1954; Spence 1968; e.g. Borodich & Keer 2004, Proc. R. Soc. A 460, 507) = 1.02165 at
    nu = 1/3. The ratio depends on the horizontal-vertical coupling only; measured 1.0209 at n = 16
    (1.0212 at n = 28), converging upward."""
    hs = HalfSpace(G=1.0, nu=NU, rho=1.0)
    p = disc(1.0, 16)
    Kr = rigid_impedance(hs, p, 0.0, dofs=("x", "z", "ry"))[0].real
    Kw = rigid_impedance(hs, p, 0.0, dofs=("x", "z", "ry"), contact="welded")[0].real
    ratio = Kw[1, 1] / Kr[1, 1]
    exact = (1 - NU) * np.log(3 - 4 * NU) / (1 - 2 * NU)
    print(f"\n  welded/relaxed vertical: {ratio:.5f} (exact {exact:.5f}); horizontal {Kw[0, 0] / Kr[0, 0]:.5f},"
          f" rocking {Kw[2, 2] / Kr[2, 2]:.5f}; coupling K_x,ry/sqrt(K_x K_ry) = "
          f"{Kw[0, 2] / np.sqrt(Kw[0, 0] * Kw[2, 2]):.4f}")
    assert ratio == pytest.approx(exact, rel=1e-3)
    assert Kw[0, 2] != 0 and Kw[0, 1] == pytest.approx(0.0, abs=1e-9 * Kw[0, 0])
    np.testing.assert_allclose(Kw, Kw.T, rtol=1e-10, atol=1e-12 * Kw.max())
    # no coupling for a vertical force in the relaxed model; welded is stiffer in every DOF
    assert np.all(np.diag(Kw) > np.diag(Kr))


def test_rigid_disc_dynamic_vs_veletsos_verbic():
    """Relaxed disc (n = 12), nu = 1/3, normalised by the same mesh's static stiffness, against the
    Veletsos & Verbic (1973) fits of the rigorous Veletsos & Wei (1971) / Luco & Westmann (1971)
    solutions (VV's stated accuracy 5-10 % for a0 <= 1.5; no table of the original papers was found).
    Horizontal: VV k = 1, c = 0.65 (measured here k = 0.990/0.966, c = 0.578/0.592 at a0 = 0.5/1)."""
    hs = HalfSpace(G=1.0, nu=NU, rho=1.0)
    a0 = np.array([0.5, 1.0])
    K = rigid_impedance(hs, disc(1.0, 12), np.r_[0.0, 1j * a0], dofs=("x", "ry"))
    kx = K[1:, 0, 0] / K[0, 0, 0]
    kr = K[1:, 1, 1] / K[0, 1, 1]
    vx = veletsos_verbic("horizontal", 1.0, NU, 1.0, 1.0)(1j * a0) / (8 / (2 - NU))
    vr = veletsos_verbic("rocking", 1.0, NU, 1.0, 1.0)(1j * a0) / (8 / (3 * (1 - NU)))
    ex, er = np.abs(kx - vx) / np.abs(vx), np.abs(kr - vr) / np.abs(vr)
    print(f"\n  horizontal k, c: {np.round(kx.real, 4)}, {np.round(kx.imag / a0, 4)}  rel. diff VV {np.round(ex, 3)}"
          f"\n  rocking    k, c: {np.round(kr.real, 4)}, {np.round(kr.imag / a0, 4)}  rel. diff VV {np.round(er, 3)}")
    assert np.all(ex < 0.08) and np.all(er < 0.08)                  # measured 3.4/5.6 %, 1.9/6.3 %
    assert np.all(kx.imag > 0) and np.all(kr.imag > 0)
    # conjugate symmetry and reciprocity of the impedance matrix
    Kc = rigid_impedance(hs, disc(1.0, 8), [2 + 1j, 2 - 1j], dofs=("x", "y", "z", "rx", "ry", "rz"),
                         contact="welded")
    np.testing.assert_allclose(Kc[1], np.conj(Kc[0]), rtol=1e-12)
    np.testing.assert_allclose(Kc[0], Kc[0].T, rtol=1e-9, atol=1e-12 * np.abs(Kc[0]).max())


def test_rigid_rectangle_and_strip_static():
    """Rigid square (grid) and long footing (strips), 6 DOFs: symmetric, positive definite, x-ry and
    y-rx coupled (opposite signs, by the rotation conventions) only when welded; the square's x and y
    stiffnesses are equal. (No exact reference value is asserted for rectangles.)"""
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    sq = grid(2.0, 2.0, 6, 6)
    K = rigid_impedance(hs, sq, 0.0, dofs=("x", "y", "z", "rx", "ry", "rz"), contact="welded")[0].real
    np.testing.assert_allclose(K, K.T, rtol=1e-10, atol=1e-12 * np.abs(K).max())
    assert np.linalg.eigvalsh(K).min() > 0
    assert K[0, 0] == pytest.approx(K[1, 1], rel=1e-10) and K[3, 3] == pytest.approx(K[4, 4], rel=1e-10)
    # sign of the welded coupling: x translation pairs with ry, y with rx, with opposite signs
    assert K[0, 4] != 0 and K[1, 3] == pytest.approx(-K[0, 4], rel=1e-8)
    Kr = rigid_impedance(hs, sq, 0.0, dofs=("x", "ry"))[0].real
    assert Kr[0, 1] == 0 and Kr[0, 0] < K[0, 0]
    st = strips(2.0, 8.0, 4)
    Ks = rigid_impedance(hs, st, [0.0, 1j], dofs=("x", "z", "ry"), contact="welded")
    np.testing.assert_allclose(Ks, Ks.transpose(0, 2, 1), rtol=1e-9, atol=1e-12 * np.abs(Ks).max())
    assert np.linalg.eigvalsh(Ks[0].real).min() > 0 and np.all(np.diag(Ks[1]).imag > 0)
