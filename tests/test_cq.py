"""Convolution quadrature weights against exact power series."""

import numpy as np
import numpy.polynomial.polynomial as P
import pytest

import unilateral as ul

# delta(zeta) = num(zeta) / den(zeta) for each rule
DELTAS = {"bdf1": ([1.0, -1.0], [1.0]), "bdf2": ([1.5, -2.0, 0.5], [1.0]), "trapezoidal": ([2.0, -2.0], [1.0, 1.0])}


def exact_oscillator_weights(k, m, c, dt, rule, N):
    """Taylor coefficients of Lambda(delta(zeta)/dt) for Lambda(s) = k - k^2 / (m s^2 + c s + k).

    With s = num / (den dt): k^2 / (m s^2 + c s + k) = k^2 dt^2 den^2 / (m num^2 + c dt num den + k dt^2 den^2),
    a rational function of zeta whose series follows by long division.
    """
    num, den = (np.array(x) for x in DELTAS[rule])
    A = P.polyadd(P.polyadd(m * P.polymul(num, num), c * dt * P.polymul(num, den)), k * dt * dt * P.polymul(den, den))
    B = np.zeros(N + 1)
    top = k * k * dt * dt * P.polymul(den, den)
    B[: top.size] = top
    a = np.zeros(N + 1)
    for j in range(N + 1):
        a[j] = (B[j] - sum(A[i] * a[j - i] for i in range(1, min(j, A.size - 1) + 1))) / A[0]
    W = -a
    W[0] += k
    return W


@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
def test_weights_of_lightly_damped_oscillator(rule):
    k, m, c, dt, N = 200.0, 4.0, 0.2, 0.01, 1000      # damping ratio 0.35 %
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]], C=[[c]])
    W = ul.cq_weights(ul.MatrixKernel(model), N, dt, ul.get_rule(rule))
    exact = exact_oscillator_weights(k, m, c, dt, rule, N)
    err = np.max(np.abs(W[:, 0, 0] - exact)) / np.max(np.abs(exact))
    assert err <= 1e-9
    # W_0 = Lambda(s*) with s* = delta(0)/dt
    s_star = ul.get_rule(rule).s_star(dt)
    np.testing.assert_allclose(W[0, 0, 0], ul.MatrixKernel(model)(s_star)[0, 0], rtol=1e-11)


def test_weights_of_a_polynomial_kernel_are_finite_differences():
    # Lambda(s) = s: BDF2 weights are (3/2, -2, 1/2)/dt and zero after
    kern = ul.CallableKernel(lambda s: np.asarray(s)[:, None, None], m=1, vectorized=True)
    W = ul.cq_weights(kern, 20, 0.1, ul.get_rule("bdf2"))[:, 0, 0]
    np.testing.assert_allclose(W[:3], [15.0, -20.0, 5.0], rtol=1e-10)
    assert np.max(np.abs(W[3:])) < 1e-8


@pytest.mark.parametrize("kw, match", [({"L": 10}, "L=10 must be at least N"), ({"rho": 1.5}, "rho must lie in"),
                                       ({"dt": -1.0}, "dt must be a positive")])
def test_bad_arguments(kw, match):
    kern = ul.CallableKernel(lambda s: np.ones((1, 1)), m=1)
    args = {"dt": 0.1}
    args.update(kw)
    dt = args.pop("dt")
    with pytest.raises(ValueError, match=match):
        ul.cq_weights(kern, 20, dt, ul.get_rule("bdf2"), **args)
