"""AAA rational fits of impedances (unilateral.soil.fit)."""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, disc, fit_rational, read_table, veletsos_verbic


def test_fit_recovers_known_poles():
    p = np.array([-1.0, -0.5 + 3j, -0.5 - 3j, -2 + 8j, -2 - 8j])
    r = np.array([3.0, 1 + 2j, 1 - 2j, 0.5 - 1j, 0.5 + 1j])
    H = lambda s: 2 + 0.5 * s + np.sum(r / (s[:, None] - p), axis=1)
    f = np.linspace(0, 3, 200)
    fit = fit_rational(f, H(2j * np.pi * f))
    np.testing.assert_allclose(np.sort_complex(fit.poles), np.sort_complex(p), atol=1e-8)
    assert fit.constant == pytest.approx(2) and fit.linear == pytest.approx(0.5)
    assert fit.fit_error < 1e-10
    s = np.array([0.3, 5 + 2j])
    np.testing.assert_allclose(fit(s), H(s), rtol=1e-9)


def test_fit_flips_unstable_pole_and_reports():
    f = np.linspace(0, 2, 150)
    s = 2j * np.pi * f
    y = 1 + 1 / (s - (0.3 + 4j)) + 1 / (s - (0.3 - 4j))        # unstable data
    fit = fit_rational(f, y)
    assert fit.report["flipped"] >= 1
    assert np.all(fit.poles.real < 0)
    np.testing.assert_allclose(np.sort(np.abs(fit.poles.imag)), [4, 4], rtol=1e-6)


def test_fit_of_veletsos_verbic_and_passivity(tmp_path):
    vv = veletsos_verbic("vertical", 1e8, 1 / 3, 2000.0, 2.0)
    f = np.linspace(0, 30, 121)
    y = vv(2j * np.pi * f)
    path = tmp_path / "imp.csv"
    with open(path, "w") as fh:
        fh.write("# impedance of a disc\nfreq_hz,Kv_re,Kv_im\n")
        for fi, yi in zip(f, y):
            fh.write(f"{float(fi)!r},{float(yi.real)!r},{float(yi.imag)!r}\n")
    freq, data = read_table(path)
    fit = fit_rational(freq, data["Kv"], passive=True)
    assert fit.fit_error < 1e-8
    assert fit.report["passivity_shift"] == 0.0
    np.testing.assert_allclose(fit.poles, [-1 / (0.8 * 2.0 / np.sqrt(1e8 / 2000))], rtol=1e-6)


def test_fit_of_rigorous_disc_impedance_reports_error():
    hs = HalfSpace(G=1.0, nu=1 / 3, rho=1.0)
    p = disc(1.0, 8)
    a0 = np.linspace(0, 3, 31)
    F = hs.surface_flexibility(p, 1j * a0)
    one = np.ones(p.m)
    K = np.array([one @ np.linalg.solve(Fi, one) for Fi in F])
    fit = fit_rational(a0 / (2 * np.pi), K, passive=True, rtol=1e-5, max_terms=12)
    assert np.all(fit.poles.real < 0)
    assert fit.fit_error < 0.01
    assert np.min(fit(1j * np.linspace(0, 30, 300)).real) >= -1e-12 * abs(K[0])
