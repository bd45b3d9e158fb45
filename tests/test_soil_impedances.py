"""Veletsos-Verbic and Wolf cone impedances; rigorous rigid-disc impedances from patches."""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, cone, cone_flexibility, disc, grid, veletsos_verbic

G, RHO, R = 8e7, 2000.0, 2.0
CS = np.sqrt(G / RHO)


def network_impedance(net, s):
    """Impedance of spring K, dashpot C and mass M on the footing plus an internal mass M_int linked by
    a dashpot C_int - written from the network, independently of the models' formulas."""
    Z = net["K"] + net["C"] * s + net["M"] * s ** 2
    if net["M_int"]:
        a, b = net["C_int"] * s, net["M_int"] * s ** 2
        Z = Z + np.where(s == 0, 0.0, a * b / np.where(s == 0, 1.0, a + b))
    return Z


# Shye & Robinson (1980) Table 4.1 / evaluated Veletsos-Verbic values (nu = 1/3): (k, c) at a0
VV_13 = {"vertical": {0.5: (0.9517, 0.7886), 1.0: (0.8634, 0.8593), 2.0: (0.7483, 0.9513)},
         "rocking": {0.5: (0.9529, 0.0235), 1.0: (0.8400, 0.0800), 2.0: (0.6000, 0.2000)}}


@pytest.mark.parametrize("dof", ["vertical", "rocking"])
def test_veletsos_verbic_values_and_network(dof):
    vv = veletsos_verbic(dof, G, 1 / 3, RHO, R)
    for a0, (k, c) in VV_13[dof].items():
        kk, cc = vv.coefficients(a0)
        assert kk == pytest.approx(k, abs=6e-5) and cc == pytest.approx(c, abs=6e-5)
    s = np.array([0.0, 3.0, 40j, 5 + 100j])
    np.testing.assert_allclose(vv(s), network_impedance(vv.network, s), rtol=1e-12)
    K0 = 4 * G * R / (1 - 1 / 3) if dof == "vertical" else 8 * G * R ** 3 / (3 * (1 - 1 / 3))
    assert vv(0.0)[0] == pytest.approx(K0)
    assert np.all(vv(1j * np.linspace(0, 500, 50)).real > 0) or dof == "vertical"


def test_veletsos_verbic_horizontal():
    vv = veletsos_verbic("horizontal", G, 0.0, RHO, R)
    assert vv(0.0)[0] == pytest.approx(8 * G * R / 2)
    assert vv(1j * CS / R)[0] == pytest.approx(4 * G * R * (1 + 0.775j))


@pytest.mark.parametrize("nu", [0.25, 0.4])
@pytest.mark.parametrize("dof", ["vertical", "horizontal", "rocking", "torsion"])
def test_cones_static_network_and_frequency_form(dof, nu):
    c = cone(dof, G, nu, RHO, R)
    K0 = {"vertical": 4 * G * R / (1 - nu), "horizontal": 8 * G * R / (2 - nu),
          "rocking": 8 * G * R ** 3 / (3 * (1 - nu)), "torsion": 16 * G * R ** 3 / 3}[dof]
    assert c(0.0)[0] == pytest.approx(K0, rel=1e-12)
    s = np.array([2.0, 30j, 4 + 200j])
    np.testing.assert_allclose(c(s), network_impedance(c.network, s), rtol=1e-12)
    if dof in ("rocking", "torsion"):                  # Wolf (1994) frequency-domain form
        w = np.array([10.0, 100.0])
        b0 = w * c.z0 / c.c
        wolf = c.K * (1 - b0 ** 2 / (3 * (1 + b0 ** 2)) + 1j * b0 ** 3 / (3 * (1 + b0 ** 2))) - w ** 2 * c.dM
        np.testing.assert_allclose(c(1j * w), wolf, rtol=1e-12)
    if nu > 1 / 3 and dof in ("vertical", "rocking"):
        assert c.c == pytest.approx(2 * CS) and c.dM > 0
    elif dof == "vertical":
        assert c.c == pytest.approx(CS * np.sqrt(2 * (1 - nu) / (1 - 2 * nu))) and c.dM == 0


def test_cone_flexibility_static_coupling_is_boussinesq():
    p = grid(8.0, 8.0, 2, 2)
    F = cone_flexibility(p, G, 0.3, RHO, [0.0, 10j])
    r = 4.0
    assert F[0, 0, 1].real == pytest.approx(0.7 / (2 * np.pi * G * r))
    assert F[0, 0, 0].real == pytest.approx((1 - 0.3) / (4 * G * np.sqrt(16 / np.pi)))
    np.testing.assert_allclose(F, F.transpose(0, 2, 1))
    assert abs(F[1, 0, 1]) == pytest.approx(abs(F[0, 0, 1]))   # pure delay, no decay in time


def _disc_impedances(n, a0, nu=1 / 3):
    hs = HalfSpace(G=1.0, nu=nu, rho=1.0)
    p = disc(1.0, n)
    F = hs.surface_flexibility(p, np.concatenate([[0.0], 1j * np.asarray(a0)]))
    one, x = np.ones(p.m), p.centres[:, 0]
    Kv = np.array([one @ np.linalg.solve(Fi, one) for Fi in F])
    Kr = np.array([x @ np.linalg.solve(Fi, x) for Fi in F])
    return Kv[1:] / Kv[0], Kr[1:] / Kr[0]


def test_rigid_disc_dynamic_stiffness_vs_veletsos_verbic():
    """Rigorous (patches, relaxed contact) vs Veletsos-Verbic, nu = 1/3, normalised by the same mesh's
    static stiffness. Tolerance = VV's stated accuracy: ~10 % for a0 <= 1.5 ; 15 % at a0 = 2 where
    their fit is known to degrade (measured at n=12: vertical 1.8/4.2/5.8 %, rocking 1.9/6.3/12.7 %)."""
    a0 = np.array([0.5, 1.0, 2.0])
    kv, kr = _disc_impedances(12, a0)
    vv_v = veletsos_verbic("vertical", 1.0, 1 / 3, 1.0, 1.0)(1j * a0) / (4 / (1 - 1 / 3))
    vv_r = veletsos_verbic("rocking", 1.0, 1 / 3, 1.0, 1.0)(1j * a0) / (8 / (3 * (1 - 1 / 3)))
    ev = np.abs(kv - vv_v) / np.abs(vv_v)
    er = np.abs(kr - vv_r) / np.abs(vv_r)
    assert np.all(ev < [0.05, 0.06, 0.10])
    assert np.all(er < [0.05, 0.10, 0.15])
    # radiation damping is positive and the vertical dashpot approaches Lysmer/VV c ~ 0.93-0.95
    assert np.all(kv.imag > 0) and np.all(kr.imag > 0)


@pytest.mark.slow
def test_rigid_disc_dynamic_mesh_converged():
    a0 = np.array([0.5, 1.0, 2.0])
    kv1, kr1 = _disc_impedances(12, a0)
    kv2, kr2 = _disc_impedances(20, a0)
    assert np.max(np.abs(kv1 - kv2) / np.abs(kv2)) < 0.02
    assert np.max(np.abs(kr1 - kr2) / np.abs(kr2)) < 0.03
