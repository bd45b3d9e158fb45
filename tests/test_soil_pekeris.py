"""Time domain: CQ inversion of the Laplace-domain point Green's function vs Pekeris (1955)."""

import numpy as np
import pytest

from unilateral.soil import HalfSpace, arrival_times, lamb_step_vertical, pekeris_quarter, step_response


def test_pekeris_explicit_equals_root_form_and_limits():
    tau = np.linspace(0, 3, 3001)
    a, b = lamb_step_vertical(tau, 0.25), pekeris_quarter(tau)
    ok = np.isfinite(a)
    assert np.array_equal(ok, np.isfinite(b))
    np.testing.assert_allclose(a[ok], b[ok], atol=1e-12)
    tp, ts, tr = arrival_times(0.25)
    assert tp == pytest.approx(1 / np.sqrt(3)) and tr == pytest.approx(np.sqrt(3 + np.sqrt(3)) / 2)
    assert np.all(a[tau < tp] == 0) and np.allclose(a[tau > tr], 0.75 / (2 * np.pi))
    # continuous at the S arrival
    assert lamb_step_vertical(1 - 1e-9, 0.25) == pytest.approx(lamb_step_vertical(1 + 1e-9, 0.25), abs=1e-6)


def _cq_error(N, windows):
    hs = HalfSpace(G=1.0, nu=0.25, rho=1.0)
    T = 2.0
    dt = T / N
    u = step_response(lambda s: hs.point_green(1.0, s)[:, 0], N, dt)
    t = np.arange(N + 1) * dt                          # = tau since c_s = r = 1
    exact = lamb_step_vertical(t, 0.25)
    f = 0.75 / (2 * np.pi)                             # Boussinesq value: the scale of the response
    return [np.max(np.abs(u[(t >= lo) & (t <= hi)] - exact[(t >= lo) & (t <= hi)])) / f
            for lo, hi in windows]


def test_cq_step_response_matches_pekeris_fast():
    before_p, p_to_s, after_r = _cq_error(300, [(0.0, 0.5), (0.65, 0.9), (1.6, 2.0)])
    assert before_p < 1e-3
    assert p_to_s < 0.02
    assert after_r < 1e-3


@pytest.mark.slow
def test_cq_step_response_matches_pekeris_within_one_percent():
    errs = _cq_error(600, [(0.0, 0.5), (0.65, 0.95), (1.45, 2.0)])
    assert max(errs) < 0.01
