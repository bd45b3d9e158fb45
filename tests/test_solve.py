"""solve(): the CLCP against direct stepping, closed-form solutions, convergence order, identities."""

import numpy as np
import pytest

import unilateral as ul
from conftest import GRAVITY, MASS, bouncing_exact, rocking_load, rocking_model

DT, T_END = 2e-3, 1.2


def rocking_pulses(t):
    """Gravity plus alternating horizontal pulses: repeated uplift of both foundation edges."""
    out = np.zeros(5)
    out[1] = -MASS * GRAVITY
    if 0.0 < t <= 0.1:
        out[0] = 300.0
    elif 0.5 < t <= 0.6:
        out[0] = -300.0
    return out


def rel(a, b):
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


@pytest.fixture(scope="module")
def solutions():
    """CQ and direct runs for every rule, with and without Kelvin soil elements.

    Without Kelvin elements the soil dashpots stay attached (part of C) and two opposite pulses
    rock the structure onto each edge in turn. With Kelvin elements the load is the seed's pulse:
    harder impacts make dashpots in series with a contact chatter, and in closed contacts psi
    then carries round-off times ``W0 ~ c s*`` (1e7 kN/m here), which hides the equivalence
    below 1e-8 behind conditioning rather than testing it.
    """
    out = {}
    for kelvin, load in ((False, rocking_pulses), (True, rocking_load())):
        model = rocking_model(kelvin=kelvin)
        for rule in ("bdf1", "bdf2", "trapezoidal"):
            for method in ("cq", "direct"):
                out[kelvin, rule, method] = ul.solve(model, load, dt=DT, t_end=T_END,
                                                     method=method, rule=rule)
    return out


@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
def test_cq_equals_direct_stepping(solutions, kelvin, rule):
    cq, direct = solutions[kelvin, rule, "cq"], solutions[kelvin, rule, "direct"]
    assert cq.success and direct.success, (cq.message, direct.message)
    # the scenario really has repeated uplift and re-contact of both edges
    lifted = cq.v > 1e-6
    assert lifted[:, 0].any() and lifted[:, 2].any()
    assert cq.stats["contact_changes"] >= 4
    assert rel(cq.v, direct.v) <= 1e-8
    assert rel(cq.psi, direct.psi) <= 1e-8
    assert rel(cq.u, direct.u) <= 1e-8


@pytest.mark.parametrize("method", ["cq", "direct"])
def test_complementarity_holds_at_every_step(solutions, method):
    sol = solutions[True, "bdf2", method]
    scale = np.max(np.abs(sol.psi))
    assert np.all(sol.v >= 0)
    assert np.all(sol.psi <= 1e-9 * scale)
    assert np.max(np.abs(sol.v * sol.psi)) <= 1e-9 * scale * np.max(sol.v)
    assert sol.stats["max_lcp_error"] <= 1e-10


def test_static_start_is_the_seed_value():
    sol = ul.solve(rocking_model(), rocking_load(), dt=DT, t_end=0.01)
    np.testing.assert_allclose(sol.dof("y2")[0], -MASS * GRAVITY / (3 * 200e3), rtol=1e-6)
    np.testing.assert_allclose(sol.dof("y2")[0], -0.667e-3, rtol=1e-3)


@pytest.mark.parametrize("method", ["cq", "direct"])
def test_bilateral_and_unilateral_agree_until_first_uplift(method):
    model, load = rocking_model(), rocking_load()
    uni = ul.solve(model, load, dt=DT, t_end=0.5, method=method)
    bil = ul.solve(model, load, dt=DT, t_end=0.5, method=method, bilateral=True)
    first = int(np.argmax(np.any(uni.v > 0, axis=1)))
    assert first >= 3
    np.testing.assert_array_equal(uni.v[:first], 0.0)
    np.testing.assert_array_equal(uni.psi[:first], bil.psi[:first])
    np.testing.assert_array_equal(uni.u[:first], bil.u[:first])
    assert np.all(bil.v == 0)
    # after uplift the responses differ by far: the seed's conclusion (Fig. 2)
    node3 = lambda sol: sol.dof("y2") - 5.0 * sol.dof("r2")     # left edge, x = -5 m
    assert np.max(node3(uni)) > 5 * np.max(node3(bil)) > 0


def test_slowly_ramped_load_reproduces_the_static_lcp():
    """A slow ramp from gravity to gravity + a large lateral force ends in the static solution."""
    model = rocking_model()
    P = 150.0

    def ramp(t):
        out = np.zeros(5)
        out[1] = -MASS * GRAVITY
        out[0] = P * min(t / 8.0, 1.0)
        return out

    sol = ul.solve(model, ramp, dt=0.01, t_end=10.0, rule="bdf1")
    static = ul.solve(model, lambda t: ramp(10.0), dt=0.01, t_end=0.01)
    assert static.v[0, 0] > 1e-4                       # the load lifts the left edge statically
    np.testing.assert_allclose(sol.v[-1], static.v[0], rtol=1e-4, atol=1e-9)
    np.testing.assert_allclose(sol.psi[-1], static.psi[0], rtol=1e-4, atol=1e-6)


# ---------------------------------------------------------------------- closed form
BOUNCE = dict(m=2.0, k=2000.0, g=10.0, V0=1.0)


def bounce(dt, rule, method="cq", t_end=1.0):
    m, k, g, V0 = BOUNCE["m"], BOUNCE["k"], BOUNCE["g"], BOUNCE["V0"]
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    return ul.solve(model, lambda t: np.array([-m * g]), dt=dt, t_end=t_end, method=method, rule=rule,
                    initial={"u0": [-m * g / k], "udot0": [V0]})


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_bouncing_mass_closed_form(rule):
    sol = bounce(1e-4, rule)
    exact, info = bouncing_exact(sol.t, **BOUNCE)
    assert np.max(np.abs(sol.u[:, 0] - exact)) <= 1e-3 * info["peak_uplift"]
    np.testing.assert_allclose(sol.v.max(), info["peak_uplift"], rtol=1e-3)
    # in flight v = u (the spring end is free), in contact v = 0
    flying = sol.v[:, 0] > 0
    np.testing.assert_allclose(sol.v[flying, 0], sol.u[flying, 0], rtol=0, atol=1e-10)


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_convergence_order(rule):
    dts = 2e-3 / 2.0 ** np.arange(5)
    errors = []
    for dt in dts:
        sol = bounce(dt, rule, t_end=0.8)
        exact, _ = bouncing_exact(sol.t, **BOUNCE)
        errors.append(np.max(np.abs(sol.u[:, 0] - exact)))
    slope = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert slope >= 1.7, (slope, errors)


# ---------------------------------------------------------------------- the Laplace-domain route
def test_kernel_model_equals_matrix_model():
    """A user's Lambda(s) and psiL give the same CLCP solution as the matrices."""
    model = rocking_model()
    full = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="cq")
    bil = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, bilateral=True, method="cq")
    kern = ul.MatrixKernel(model)
    km = ul.KernelModel(lambda s: kern(s), bil.psiL, vectorized=True)
    got = ul.solve(km, dt=DT, t_end=0.6)
    assert got.success and got.u is None
    assert rel(got.v, full.v) <= 1e-8
    assert rel(got.psi, full.psi) <= 1e-8


def test_kernel_model_from_rest_with_callable_psiL():
    # one mass on a tensionless spring pushed away by a prescribed bilateral reaction
    k, m = 100.0, 1.0
    km = ul.KernelModel(lambda s: k * m * s * s / (m * s * s + k), lambda t: np.array([np.sin(3 * t)]), m=1)
    sol = ul.solve(km, dt=1e-3, t_end=3.0, initial="rest")
    assert sol.success and sol.v.max() > 0
    assert np.all(sol.psi <= 1e-9)


# ---------------------------------------------------------------------- other rules
def test_hht_with_zero_alpha_is_trapezoidal_and_dissipative_hht_runs():
    model = rocking_model()
    trap = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="direct", rule="trapezoidal")
    nm = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="direct", rule=ul.Newmark(0.5, 0.25))
    np.testing.assert_allclose(nm.v, trap.v, rtol=0, atol=1e-15)
    for rule in (ul.HHT(0.1), ul.Newmark(0.6, 0.3025)):
        sol = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="direct", rule=rule)
        assert sol.success and sol.v.max() > 1e-4
        assert sol.stats["max_lcp_error"] <= 1e-10
        # same physics: the peak uplift agrees with the trapezoidal rule to a few percent
        np.testing.assert_allclose(sol.v.max(), trap.v.max(), rtol=0.05)


@pytest.mark.parametrize("lcp", ["bpp", "lemke", "pgs", "newton"])
def test_every_lcp_solver_gives_the_same_history(lcp):
    model = rocking_model()
    ref = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="direct")
    sol = ul.solve(model, rocking_pulses, dt=DT, t_end=0.6, method="direct", lcp=lcp,
                   lcp_options={"tol": 1e-12})
    assert sol.success
    assert rel(sol.v, ref.v) <= 1e-7


def test_lcp_failure_is_reported_not_hidden():
    sol = ul.solve(rocking_model(), rocking_pulses, dt=DT, t_end=0.6, method="direct", lcp="pgs",
                   lcp_options={"max_iter": 1, "tol": 1e-14})
    assert not sol.success
    assert "LCP of step" in sol.message and "failed" in sol.message
    assert len(sol.t) == sol.stats["steps_done"] + 1 < 301


@pytest.mark.parametrize("method", ["cq", "direct"])
def test_a_model_without_constraints_is_plain_linear_dynamics(method):
    """m = 0: both methods reduce to the linear structure (a damped oscillator under a step)."""
    model = ul.Model(M=[[1.0]], K=[[100.0]], C=[[2.0]], F=np.zeros((1, 0)), H=np.zeros((0, 0)))
    sol = ul.solve(model, lambda t: np.array([1.0 if t > 0 else 0.0]), dt=1e-3, t_end=2.0, method=method)
    assert sol.success and sol.v.shape == (2001, 0)
    w, z = 10.0, 0.1
    wd = w * np.sqrt(1 - z * z)
    exact = 0.01 * (1 - np.exp(-z * w * sol.t) * (np.cos(wd * sol.t) + z * w / wd * np.sin(wd * sol.t)))
    assert np.max(np.abs(sol.u[:, 0] - exact)) < 1e-2 * 0.01


def test_fft_blocked_history_equals_naive_history_in_a_march():
    model = rocking_model()
    runs = {h: ul.solve(model, rocking_load(), dt=1e-3, t_end=1.0, cq_options={"history": h})
            for h in ("naive", "fft")}
    assert runs["fft"].stats["history"] == "fft" and runs["naive"].stats["history"] == "naive"
    assert rel(runs["fft"].v, runs["naive"].v) <= 1e-10
    assert rel(runs["fft"].psi, runs["naive"].psi) <= 1e-10
    with pytest.raises(ValueError, match=r"cq_options\['history'\]='tree' is not valid; valid names: 'fft', 'naive'"):
        ul.solve(model, rocking_load(), dt=1e-3, t_end=0.01, cq_options={"history": "tree"})
    with pytest.raises(ValueError, match=r"cq_options has unknown keys \['order'\]"):
        ul.solve(model, rocking_load(), dt=1e-3, t_end=0.01, cq_options={"order": 2})


@pytest.mark.parametrize("kelvin", [False, True])
def test_compiled_march_equals_python_march(kelvin):
    model = rocking_model(kelvin=kelvin)
    load = rocking_pulses if not kelvin else rocking_load()
    runs = {e: ul.solve(model, load, dt=DT, t_end=0.6, cq_options={"history": "naive", "engine": e})
            for e in ("compiled", "python")}
    assert runs["compiled"].stats["engine"] == "compiled" and runs["python"].stats["engine"] == "python"
    np.testing.assert_allclose(runs["compiled"].v, runs["python"].v, rtol=0, atol=1e-14)
    assert rel(runs["compiled"].psi, runs["python"].psi) <= 1e-12
    assert runs["compiled"].stats["contact_changes"] == runs["python"].stats["contact_changes"]
    # cq picks the compiled loop for the default LCP solver and a short run
    assert ul.solve(model, load, dt=DT, t_end=0.1, method="cq").stats["engine"] == "compiled"
    with pytest.raises(ValueError, match="engine'\\]='compiled' needs history='naive' and lcp='bpp'"):
        ul.solve(model, load, dt=DT, t_end=0.1, lcp="lemke", cq_options={"engine": "compiled"})


@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
def test_modal_recursion_equals_direct_stepping(solutions, kelvin, rule):
    """method="modal" (exact pole-residue recursion, every pole) is the same CLCP as "cq"."""
    direct = solutions[kelvin, rule, "direct"]
    model = rocking_model(kelvin=kelvin)
    load = rocking_pulses if not kelvin else rocking_load()
    modal = ul.solve(model, load, dt=DT, t_end=T_END, method="modal", rule=rule)
    assert modal.success and modal.stats["history"] == "modal"
    assert rel(modal.v, direct.v) <= 1e-8
    assert rel(modal.psi, direct.psi) <= 1e-8
    assert rel(modal.u, direct.u) <= 1e-8


def test_modal_compiled_equals_python():
    model = rocking_model()
    runs = {e: ul.solve(model, rocking_load(), dt=DT, t_end=0.6, method="modal",
                        modal_options={"engine": e}) for e in ("compiled", "python")}
    assert runs["compiled"].stats["engine"] == "compiled" and runs["python"].stats["engine"] == "python"
    np.testing.assert_allclose(runs["compiled"].v, runs["python"].v, rtol=0, atol=1e-14)
    assert rel(runs["compiled"].psi, runs["python"].psi) <= 1e-12
    with pytest.raises(ValueError, match=r"modal_options has unknown keys \['order'\]"):
        ul.solve(model, rocking_load(), dt=DT, t_end=0.01, method="modal", modal_options={"order": 1})


class _OwnBDF2(type(ul.get_rule("bdf2"))):
    """BDF2 as a rule class of the user's own (not one of unilateral.rules)."""


def test_auto_method_is_reported_with_its_reason():
    auto = ul.solve(rocking_model(), rocking_load(), dt=DT, t_end=0.2)
    assert auto.stats["method"] == "direct" and "small model" in auto.stats["method_reason"]
    assert "fastest" in auto.stats["method_reason"] and auto.stats["engine"] == "compiled"
    modal = ul.solve(rocking_model(), rocking_load(), dt=DT, t_end=0.2, method="modal")
    assert rel(auto.v, modal.v) <= 1e-8
    own = ul.solve(rocking_model(), rocking_load(), dt=DT, t_end=0.2, rule=_OwnBDF2(2))
    assert own.stats["method"] == "modal" and "rule of its own" in own.stats["method_reason"]
    assert rel(own.v, modal.v) <= 1e-12
    assert ul.solve(rocking_model(), rocking_load(), dt=DT, t_end=0.2, rule="hht").stats["method"] == "direct"
    km = ul.KernelModel(ul.MatrixKernel(rocking_model()), np.zeros((101, 3)) - 1.0)
    assert ul.solve(km, dt=DT, t_end=0.2).stats["method"] == "cq"


def test_auto_falls_back_to_direct_when_the_poles_are_refused():
    """A critically damped oscillator has a defective double pole: no pole-residue form."""
    model = ul.Model(M=[[1.0]], K=[[100.0]], C=[[20.0]], F=[[100.0]], H=[[100.0]])
    load = lambda t: np.array([-10.0 + 30.0 * (0.0 < t <= 0.2)])
    auto = ul.solve(model, load, dt=1e-3, t_end=0.5, rule=_OwnBDF2(2))      # auto would take modal
    assert auto.success and auto.stats["method"] == "direct"
    assert "modal refused" in auto.stats["method_reason"]
    np.testing.assert_array_equal(auto.v, ul.solve(model, load, dt=1e-3, t_end=0.5, method="direct",
                                                   rule=_OwnBDF2(2)).v)
    with pytest.raises(ValueError):
        ul.solve(model, load, dt=1e-3, t_end=0.5, method="modal")


@pytest.mark.parametrize("kelvin", [False, True])
@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal"])
def test_compiled_sweep_equals_python_sweep(kelvin, rule):
    """The compiled linear sweep performs the stepper's operations: equal to round-off, also
    from a moving initial state and with prescribed increments."""
    from unilateral.march.direct import sweep_direct
    from unilateral.initial import given_state
    from unilateral.march.stepper import StructureStepper

    model, load, dt, N = rocking_model(kelvin=kelvin), rocking_load(), 1e-3, 400
    init = given_state(model, {"u0": np.full(5, 1e-4), "udot0": np.linspace(-0.01, 0.02, 5)})
    f = lambda k: load(k * dt) + model.F @ init.v - model.K @ init.u
    off = lambda k: model.F.T @ init.u - model.H @ init.v - model.g(k * dt)
    dv = np.zeros((N + 1, 3))
    dv[50:200, 0] = np.linspace(0.0, 1e-3, 150)
    make = lambda: StructureStepper(model, ul.get_rule(rule), dt, f, off, init.udot, condensed=False)
    assert make().sweep_arrays(N) is not None
    compiled = sweep_direct(make(), N, init.v, init.psi, dv)
    python = sweep_direct(make(), N, init.v, init.psi, dv, compiled=False)
    for a, b in zip(compiled[:4], python[:4]):
        assert rel(a, b) <= 1e-12


def test_bpp_feasibility_is_measured_in_the_units_of_v():
    """Regression: W0 entries of 1e10 (stiff column, Kelvin dashpots at a fine step) once let a
    slightly negative v pass as feasible; clipping it then left an LCP error of 2e-5."""
    from unilateral.structure.examples import liolios1990

    st, load, _ = liolios1990()
    sol = ul.solve(st.to_model(), load, dt=0.5 / 8000, t_end=0.15, method="direct")
    assert sol.success, sol.message
    assert sol.stats["max_lcp_error"] < 1e-12


@pytest.mark.parametrize("method", ["cq", "modal", "direct"])
def test_load_history_equals_its_grid_samples_given_as_an_array(method):
    """A LoadHistory is sampled by hat averages (one-sided at t = 0) and the static state is taken
    under q(0-): the same as its grid samples passed as an array from that static state."""
    from unilateral.initial import static_state
    from unilateral.lcp import get_lcp_solver
    from unilateral.loads import LoadHistory, Rectangular
    from unilateral.structure import liolios1990
    structure, _, _ = liolios1990()
    q = LoadHistory(structure.gravity(10.0), [(structure.nodal_load(1, ux=200.0), Rectangular(1.0, t_end=0.1))])
    model = structure.to_model()
    args = dict(dt=2e-3, t_end=0.4, method=method)
    Q, q0 = q.grid_samples(2e-3, 200)
    assert np.array_equal(q0, q(0.0)) and np.array_equal(Q[0], q(1e-3))      # q(0-) and q(0+)
    init = static_state(model, q0, get_lcp_solver("bpp"))
    sampled = ul.solve(model, q, **args)
    called = ul.solve(model, Q, initial={"u0": init.u, "v0": init.v}, **args)
    assert sampled.success and called.success and sampled.stats["contact_changes"] > 2
    for name in ("u", "v", "psi"):
        scale = np.abs(getattr(called, name)).max()
        np.testing.assert_allclose(getattr(sampled, name), getattr(called, name), rtol=0, atol=1e-12 * scale)
