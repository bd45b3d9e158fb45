"""Time-domain kernels: numerical Laplace inversion, product-integration weights, the CLCP."""

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg as sla

import unilateral as ul
from conftest import bouncing_exact, rocking_load, rocking_model
from unilateral.kernels import invert_laplace
from unilateral.kernels import TimeKernel, TimeKernelModel, time_kernel_weights
from unilateral.methods import solve_time_kernel

METHODS = ["dehoog", "durbin"]
OMEGA = 2 * np.pi


def two_mode_pair():
    """``(K + s a K + s^2 M)^-1`` and its inverse transform, a sum of damped modal sines."""
    K = np.array([[3.0, -1.0], [-1.0, 2.0]])
    M = np.diag([1.0, 0.5])
    a = 0.004
    w2, phi = sla.eigh(K, M)                      # mass-normalised modes
    w = np.sqrt(w2)
    zeta_w = 0.5 * a * w2
    wd = np.sqrt(w2 - zeta_w ** 2)

    def F(s):
        s = np.asarray(s)[:, None, None]
        return np.linalg.inv(K + s * a * K + s * s * M)

    def f(t):
        g = np.exp(-np.outer(t, zeta_w)) * np.sin(np.outer(t, wd)) / wd        # (n, 2)
        return np.einsum("nk,ik,jk->nij", g, phi, phi)

    return F, f


# name: (F, f, t_max, accepted max error for dehoog, for durbin); errors measured with 2000
# times: exp 1e-12 / 5e-10, sine 2e-12 / 5e-12, damped 1e-13 / 1e-12, matrix 9e-13 / 4e-12
PAIRS = {
    "exp": (lambda s: 1.0 / (s + 1.0), lambda t: np.exp(-t), 10.0, 1e-11, 1e-8),
    "undamped sine, 10 periods": (lambda s: OMEGA / (s * s + OMEGA ** 2), lambda t: np.sin(OMEGA * t),
                                  10.0, 1e-10, 1e-10),
    "damped sine": (lambda s: 1.0 / ((s + 0.5) ** 2 + OMEGA ** 2),
                    lambda t: np.exp(-0.5 * t) * np.sin(OMEGA * t) / OMEGA, 10.0, 1e-11, 1e-10),
    "matrix, two modes": two_mode_pair() + (30.0, 1e-10, 1e-10),
}


def rel(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


# ---------------------------------------------------------------------- Laplace inversion
@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("name", PAIRS)
def test_inversion_of_known_pairs(method, name):
    F, f, t_max, tol_dehoog, tol_durbin = PAIRS[name]
    t = np.linspace(t_max / 2000, t_max, 2000)
    got = invert_laplace(F, t, method=method)
    assert got.shape == f(t).shape
    assert np.max(np.abs(got - f(t))) <= (tol_dehoog if method == "dehoog" else tol_durbin)


@pytest.mark.parametrize("method", METHODS)
def test_undamped_sine_over_fifty_periods_and_few_times(method):
    t = np.linspace(0.05, 50.0, 1000)
    got = invert_laplace(PAIRS["undamped sine, 10 periods"][0], t, method=method)
    assert np.max(np.abs(got - np.sin(OMEGA * t))) <= 1e-9
    # few times: the default omega_max (pi n / t_max) is below the frequency; give it
    few = np.array([3.3, 17.1, 41.7])
    got = invert_laplace(PAIRS["undamped sine, 10 periods"][0], few, method=method, omega_max=4 * OMEGA)
    assert np.max(np.abs(got - np.sin(OMEGA * few))) <= 1e-6


@pytest.mark.parametrize("method", METHODS)
def test_matrix_function_called_per_s(method):
    F, f, *_ = PAIRS["matrix, two modes"]
    t = np.array([0.7, 5.0, 21.0])
    got = invert_laplace(lambda s: F(np.array([s]))[0], t, method=method, vectorized=False)
    np.testing.assert_allclose(got, f(t), rtol=0, atol=1e-9)


@pytest.mark.parametrize("method", METHODS)
def test_delayed_step_converges_away_from_the_jump_only(method):
    tau = 1.0
    t = np.linspace(2 * tau / 2000, 2 * tau, 2000)
    got = invert_laplace(lambda s: np.exp(-s * tau) / s, t, method=method)
    err = np.abs(got - (t > tau))
    assert np.max(err[np.abs(t - tau) > 0.05 * tau]) <= 1e-6
    # Gibbs: next to the jump the series overshoots, at the jump it is near the mean
    assert np.max(err[np.abs(t - tau) < 0.01 * tau]) > 0.3


def test_zero_entries_and_plain_durbin_series():
    # an identically zero entry is returned as zero (its quotient-difference table would be 0/0)
    F = lambda s: np.stack([1.0 / (s + 1.0), 0.0 * s], axis=-1)
    t = np.linspace(0.01, 5.0, 500)
    got = invert_laplace(F, t)
    np.testing.assert_allclose(got[:, 0], np.exp(-t), rtol=0, atol=1e-11)
    assert np.all(got[:, 1] == 0.0)
    # without acceleration the tail of Durbin's series (terms ~ 1/k) is left out
    plain = invert_laplace(F, t, method="durbin", acceleration="none")[:, 0]
    assert np.max(np.abs(plain - np.exp(-t))) > 1e-4


def test_a_delta_function_breaks_the_quotient_difference_table():
    with pytest.raises(ValueError, match="a delta function in f"):
        invert_laplace(lambda s: np.ones_like(s), [1.0, 2.0])


@pytest.mark.parametrize("kw, exc, match", [
    (dict(t=[1.0, 0.0]), ValueError, "t must be > 0"),
    (dict(t=[]), ValueError, "at least one time"),
    (dict(t=[1.0, np.nan]), ValueError, "t contains nan"),
    (dict(method="talbot"), ValueError, "method='talbot' is not valid"),
    (dict(M=0), ValueError, "M must be a positive integer"),
    (dict(p=3), ValueError, r"unknown options \['p'\] for method='dehoog'"),
    (dict(method="durbin", acceleration="euler"), ValueError, "acceleration='euler' is not valid"),
    (dict(tol=2.0), ValueError, "tol must lie in"),
    (dict(scale=0.5), ValueError, "scale must be >= 1"),
    (dict(ratio=1.0), ValueError, "ratio must be > 1"),
    (dict(F=3.0), TypeError, "F must be callable"),
    (dict(F=lambda s: np.ones(3)), ValueError, "F\\(s\\) for s of shape"),
])
def test_inversion_argument_checks(kw, exc, match):
    args = dict(F=lambda s: 1.0 / (s + 1.0), t=[1.0, 2.0])
    args.update(kw)
    with pytest.raises(exc, match=match):
        invert_laplace(args.pop("F"), args.pop("t"), **args)


# ---------------------------------------------------------------------- the time-domain kernel
K_SPRING, M_SPRING = 2000.0, 2.0
W_SPRING = np.sqrt(K_SPRING / M_SPRING)


def spring_kernel(s):
    """One mass on one spring: ``Lambda(s) = k m s^2 / (m s^2 + k) = k - k^2 / (m s^2 + k)``."""
    return K_SPRING * M_SPRING * s * s / (M_SPRING * s * s + K_SPRING)


@pytest.mark.parametrize("method", METHODS)
def test_one_spring_kernel_from_laplace(method):
    dt, N = 1e-3, 1000
    kern = TimeKernel.from_laplace(spring_kernel, 1, dt=dt, N=N, method=method, vectorized=True)
    np.testing.assert_allclose(kern.Lambda_inf, [[K_SPRING]], rtol=1e-12)
    assert kern.Lambda_rate is None
    np.testing.assert_allclose(kern.Lambda0, [[0.0]], atol=1e-9)       # a free mass needs no force
    t = dt * np.arange(N + 1)
    exact = -K_SPRING * W_SPRING * np.sin(W_SPRING * t)
    samples = kern.samples(N, dt)[:, 0, 0]
    assert rel(samples[1:], exact[1:]) <= 1e-9
    assert abs(samples[0]) <= 1e-7 * np.max(np.abs(exact))             # cubic extrapolation to t = 0
    assert kern.info["check_relative"] <= 1e-9 and kern.info["asymptote_misfit"] <= 1e-12


def test_kelvin_spring_rate_and_instantaneous_parts():
    k, m, c = K_SPRING, M_SPRING, 4.0
    kelvin = lambda s: (k + c * s) - (k + c * s) ** 2 / (m * s * s + c * s + k)
    dt, N = 1e-3, 1000
    kern = TimeKernel.from_laplace(kelvin, 1, dt=dt, N=N, vectorized=True)
    np.testing.assert_allclose(kern.Lambda_inf, [[k - c * c / m]], rtol=1e-10)
    np.testing.assert_allclose(kern.Lambda_rate, [[c]], rtol=1e-10)
    # remainder -((2kc - c^3/m) s + k (k - c^2/m)) / (m s^2 + c s + k), a damped oscillation
    t = dt * np.arange(N + 1)
    a, b = -(2 * k * c - c ** 3 / m), -k * (k - c * c / m)
    alpha = c / (2 * m)
    wd = np.sqrt(k / m - alpha ** 2)
    exact = np.exp(-alpha * t) * (a * np.cos(wd * t) + (b - a * alpha) / wd * np.sin(wd * t)) / m
    samples = kern.samples(N, dt)[:, 0, 0]
    assert rel(samples[1:], exact[1:]) <= 1e-9
    assert abs(samples[0] - exact[0]) <= 1e-5 * abs(exact[0])           # extrapolated: O(dt^4)
    # the same with the asymptote given
    given = TimeKernel.from_laplace(kelvin, 1, dt=dt, N=N, vectorized=True,
                                    Lambda_inf=k - c * c / m, Lambda_rate=c)
    assert given.info["asymptote"] == "given" and given.info["asymptote_misfit"] <= 1e-12
    assert rel(given.samples(N, dt), kern.samples(N, dt)) <= 1e-9


def test_kernel_without_a_static_value():
    # Lambda(s) = 3 + 2/s: Lambda_r = 2 (a constant), Lambda(0) does not exist
    kern = TimeKernel.from_laplace(lambda s: 3.0 + 2.0 / s, 1, dt=0.01, N=40, vectorized=True)
    np.testing.assert_allclose(kern.Lambda_inf, [[3.0]], rtol=1e-12)
    np.testing.assert_allclose(kern.samples(40, 0.01), 2.0, rtol=1e-10)
    assert kern.Lambda0 is None and kern.info["Lambda0"].startswith("not available")


def test_a_wrong_asymptote_is_reported():
    with pytest.warns(RuntimeWarning, match="asymptote_misfit"):
        kern = TimeKernel.from_laplace(spring_kernel, 1, dt=1e-3, N=50, vectorized=True,
                                       Lambda_inf=0.9 * K_SPRING)
    assert kern.info["asymptote_misfit"] > 0.01


def test_kelvin_soil_under_a_rigid_column_is_reported_as_unresolved():
    """The seed's example with Kelvin soil elements has no asymptote at the grid's scale."""
    model = rocking_model(kelvin=True)
    with pytest.warns(RuntimeWarning, match="asymptote_misfit"):
        kern = TimeKernel.from_laplace(ul.MatrixKernel(model), model.m, dt=1e-3, N=50)
    assert kern.info["asymptote_misfit"] > 1e-3


def test_trapezoidal_product_rule_is_second_order():
    """``(Lambda_r * v)(1)`` for a smooth kernel and ``v(0) = 0``: trapezoidal order 2, rectangle 1."""
    lam = lambda t: np.exp(-t) * np.cos(3 * t)
    v = lambda t: np.sin(2 * t) ** 2 + t
    exact = scipy.integrate.quad(lambda tau: lam(tau) * v(1.0 - tau), 0.0, 1.0, epsabs=1e-14, epsrel=1e-14)[0]
    kern = TimeKernel(0.0, lambda t: [[lam(t)]])
    dts = 0.1 / 2.0 ** np.arange(5)
    slopes = {}
    for quadrature in ("trapezoidal", "rectangle"):
        errors = []
        for dt in dts:
            N = int(round(1.0 / dt))
            W = time_kernel_weights(kern, N, dt, quadrature=quadrature)[:, 0, 0]
            errors.append(abs(W @ v(1.0 - dt * np.arange(N + 1)) - exact))
        slopes[quadrature] = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert slopes["trapezoidal"] >= 1.95
    assert 0.9 <= slopes["rectangle"] <= 1.1


@pytest.mark.parametrize("rate, expected", [("bdf2", [1.5, -2.0, 0.5, 0.0]), ("bdf1", [1.0, -1.0, 0.0, 0.0])])
def test_rate_part_weights_are_backward_differences(rate, expected):
    kern = TimeKernel([[2.0]], np.zeros(4), dt=0.1, Lambda_rate=[[3.0]])
    W = time_kernel_weights(kern, 3, 0.1, rate=rate)[:, 0, 0]
    np.testing.assert_allclose(W, 3.0 * np.array(expected) / 0.1 + [2.0, 0.0, 0.0, 0.0], rtol=1e-14)


@pytest.mark.parametrize("call, exc, match", [
    (lambda: TimeKernel(np.ones((2, 3)), np.zeros((3, 2, 2)), dt=0.1), ValueError, "must be square"),
    (lambda: TimeKernel(np.eye(2), np.zeros((3, 3, 3)), dt=0.1), ValueError, r"shape \(N\+1, 2, 2\)"),
    (lambda: TimeKernel(np.eye(2), np.zeros((3, 2, 2))), ValueError, "dt is required"),
    (lambda: TimeKernel(1.0, "x", dt=0.1), TypeError, "Lambda_r must be a callable"),
    (lambda: TimeKernel(1.0, np.zeros(3), dt=0.1).samples(2, 0.2), ValueError, "differs from the spacing"),
    (lambda: TimeKernel(1.0, np.zeros(3), dt=0.1).samples(5, 0.1), ValueError, "has 3 samples"),
    (lambda: TimeKernel(np.eye(2), lambda t: np.ones(3)).samples(2, 0.1), ValueError,
     r"must return shape \(2, 2\), got \(3,\) at t=0"),
    (lambda: time_kernel_weights(TimeKernel(1.0, np.zeros(3), dt=0.1), 2, 0.1, quadrature="simpson"),
     ValueError, "quadrature='simpson' is not valid"),
    (lambda: TimeKernel.from_laplace(spring_kernel, 1, dt=1e-3, N=0), ValueError, "N must be a positive"),
    (lambda: TimeKernelModel(np.eye(1), np.zeros((3, 1))), TypeError, "kernel must be a TimeKernel"),
    (lambda: solve_time_kernel(TimeKernelModel(TimeKernel(1.0, np.zeros(3), dt=0.1), np.zeros((3, 1))),
                               dt=0.1, t_end=0.2), ValueError, "initial='static' needs the static kernel"),
])
def test_time_kernel_argument_checks(call, exc, match):
    with pytest.raises(exc, match=match):
        call()


# ---------------------------------------------------------------------- the bouncing mass
BOUNCE = dict(m=M_SPRING, k=K_SPRING, g=10.0, V0=1.0)


def bounce_psiL(t):
    """Bilateral spring force ``k u_L`` of the mass thrown up from its static position."""
    return np.array([-BOUNCE["m"] * BOUNCE["g"] + K_SPRING * BOUNCE["V0"] / W_SPRING * np.sin(W_SPRING * t)])


def bounce_time_kernel(dt, t_end, initial="rest"):
    N = int(round(t_end / dt))
    kern = TimeKernel.from_laplace(spring_kernel, 1, dt=dt, N=N, vectorized=True)
    return solve_time_kernel(TimeKernelModel(kern, bounce_psiL), dt=dt, t_end=t_end, initial=initial)


def test_bouncing_mass_converges_at_second_order_to_the_closed_form():
    """In flight the spring end is free and v = u, in contact v = 0: v = max(u, 0)."""
    dts = 2e-3 / 2.0 ** np.arange(5)
    errors, laplace_errors, differences = [], [], []
    for dt in dts:
        sol = bounce_time_kernel(dt, 0.8)
        assert sol.success and sol.stats["method"] == "time-kernel" and sol.stats["contact_changes"] == 5
        exact, info = bouncing_exact(sol.t, **BOUNCE)
        errors.append(np.max(np.abs(sol.v[:, 0] - np.maximum(exact, 0.0))))
        laplace = ul.solve(ul.KernelModel(spring_kernel, bounce_psiL, m=1), dt=dt, t_end=0.8,
                           rule="trapezoidal", initial="rest")
        laplace_errors.append(np.max(np.abs(laplace.v[:, 0] - np.maximum(exact, 0.0))))
        differences.append(np.max(np.abs(sol.v - laplace.v)))
    # measured: errors 4.7e-4 .. 1.6e-6 (slope 2.04); Laplace route 1.2e-4 .. 6.9e-7 (1.89)
    slope = lambda e: np.polyfit(np.log(dts), np.log(e), 1)[0]
    assert slope(errors) >= 1.9, errors
    assert slope(laplace_errors) >= 1.7, laplace_errors
    assert slope(differences) >= 1.8 and differences[-1] <= 5e-6, differences
    # peak uplift at the fine steps (measured 5.3e-5 at dt = 5e-4, 3.3e-6 at 1.25e-4)
    np.testing.assert_allclose(sol.v.max(), info["peak_uplift"], rtol=1e-5)


def test_bouncing_mass_static_start_equals_rest_and_histories_agree():
    rest = bounce_time_kernel(1e-3, 0.4)
    static = bounce_time_kernel(1e-3, 0.4, initial="static")
    assert static.stats["static_lcp_iterations"] >= 0 and static.stats["history"] == "fft"
    np.testing.assert_allclose(static.v, rest.v, rtol=0, atol=1e-14)
    kern = TimeKernel.from_laplace(spring_kernel, 1, dt=1e-3, N=400, vectorized=True)
    naive = solve_time_kernel(TimeKernelModel(kern, bounce_psiL), dt=1e-3, t_end=0.4, history="naive")
    np.testing.assert_allclose(naive.v, rest.v, rtol=0, atol=1e-12)
    bilateral = solve_time_kernel(TimeKernelModel(kern, bounce_psiL), dt=1e-3, t_end=0.4, bilateral=True)
    assert np.all(bilateral.v == 0) and np.array_equal(bilateral.psi, bilateral.psiL)


# ---------------------------------------------------------------------- the rocking structure
def test_rocking_structure_time_kernel_agrees_with_direct_stepping():
    """The seed's example with attached dashpots: the time-domain route against direct BDF2."""
    model, load = rocking_model(kelvin=False), rocking_load()
    differences = []
    for dt in (1e-3, 5e-4):
        N = int(round(0.6 / dt))
        kern = TimeKernel.from_laplace(ul.MatrixKernel(model), model.m, dt=dt, N=N)
        # measured: inversions agree to 2e-10, asymptote misfit 1e-7
        assert kern.info["check_relative"] <= 1e-8 and kern.info["asymptote_misfit"] <= 1e-6
        psiL = ul.solve(model, load, dt=dt, t_end=0.6, method="cq", bilateral=True).psiL
        sol = solve_time_kernel(TimeKernelModel(kern, psiL, constraint_names=model.constraint_names),
                                dt=dt, t_end=0.6)
        ref = ul.solve(model, load, dt=dt, t_end=0.6, method="direct")
        assert sol.success and ref.success
        assert sol.v[:, 0].max() > 1e-4                    # the left edge lifts off
        differences.append(rel(sol.v, ref.v))
        assert rel(sol.psi, ref.psi) <= 1e-3
    # measured: 4.6e-4 at dt = 1e-3, 1.0e-4 at 5e-4
    assert differences[0] <= 1e-3
    assert differences[1] <= 0.35 * differences[0]


def test_solve_dispatches_a_time_kernel_model():
    """unilateral.solve accepts a TimeKernelModel and refuses options that do not apply."""
    k, m = 100.0, 1.0
    w = np.sqrt(k / m)
    kernel = ul.TimeKernel(np.array([[k]]), lambda t: np.array([[-k * w * np.sin(w * t)]]),
                           Lambda0=np.array([[0.0]]))
    model = ul.TimeKernelModel(kernel, lambda t: np.array([np.sin(3 * t)]))
    sol = ul.solve(model, dt=1e-3, t_end=1.0, initial="rest")
    assert sol.success and sol.stats["method"] == "time-kernel" and sol.v.max() > 0
    with pytest.raises(ValueError, match=r"\(TimeKernelModel\) is solved by product integration"):
        ul.solve(model, dt=1e-3, t_end=1.0, method="cq")


def test_a_time_kernel_is_a_kind_of_kernel_model():
    """TimeKernelModel gives a KernelModel of domain "time": method="time-kernel" by name solves it
    (as auto does, the same numbers), cq refuses it with the method to use, and cq's Laplace-domain
    kernel model is refused by time-kernel."""
    k, m = 100.0, 1.0
    w = np.sqrt(k / m)
    kernel = ul.TimeKernel(np.array([[k]]), lambda t: np.array([[-k * w * np.sin(w * t)]]),
                           Lambda0=np.array([[0.0]]))
    model = ul.TimeKernelModel(kernel, lambda t: np.array([np.sin(3 * t)]))
    assert isinstance(model, ul.KernelModel) and model.domain == "time"
    auto = ul.solve(model, dt=1e-3, t_end=0.5, initial="rest")
    named = ul.solve(ul.KernelModel(kernel, lambda t: np.array([np.sin(3 * t)])), dt=1e-3, t_end=0.5,
                     initial="rest", method="time-kernel")
    np.testing.assert_array_equal(auto.v, named.v)
    from unilateral.methods import CQ, TimeKernelMethod

    assert "use method='time-kernel'" in CQ().applies(model, ul.get_rule("bdf2"))
    laplace = ul.KernelModel(lambda s: np.array([[k * s * s / (s * s + w * w)]]), np.zeros((4, 1)))
    assert laplace.domain == "laplace"
    assert "use method='cq'" in TimeKernelMethod().applies(laplace, ul.get_rule("bdf2"))
    with pytest.raises(ValueError, match="psiL has 2 columns but the kernel Lambda is 1 x 1"):
        ul.KernelModel(kernel, np.zeros((4, 2)))
