"""Rigid contacts (H = 0, force form) and the rocking rigid block (structure/rigid.py, docs/rocking.md).

The block: width 2b = 0.4 m, height 2h = 1.2 m, m = 1 t (kN, m, s), released at rest from the
tilt theta0 = 0.05 rad on its right corner. Housner's r = 1 - 2 m b^2 / I0 = 0.85, the linearised
first impact at t1 = acosh((b/h) / (b/h - theta0)) / p = 0.176330 s.
"""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import LoadHistory, Tabulated
from unilateral.structure import Frame2D, rigid

THETA0 = 0.05


def _block(**kw):
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, **kw)
    st = fr.build()
    return st, st.to_model(), block


def _released(rule, dt, t_end=1.2):
    st, model, block = _block()
    u0 = np.array([block.b * THETA0, -THETA0])                 # on the right corner: uy = b theta0, rz = -theta0
    q = st.gravity(block.g)
    v0 = rigid.initial_forces(model, u0, q)
    sol = ul.solve(model, LoadHistory(q), dt=dt, t_end=t_end, method="direct", rule=rule,
                   initial={"u0": u0, "v0": v0})
    assert sol.success, sol.message
    return st, sol, block


# ---------------------------------------------------------------------- the builder
def test_block_model_is_the_linearised_rocking():
    st, model, block = _block()
    b, h, m, g = 0.2, 0.6, 1.0, block.g
    J = m * (b * b + h * h) / 3
    assert model.dof_names == ["B.base.uy", "B.base.rz"]
    assert model.constraint_names == ["B.left", "B.right"]
    np.testing.assert_allclose(model.M.toarray(), np.diag([m, J + m * h * h]))
    np.testing.assert_allclose(model.K.toarray(), np.diag([0.0, -m * g * h]))     # -W h: the weight's 2nd order
    np.testing.assert_allclose(model.F, [[1.0, 1.0], [-b, b]])                     # corner uy = uy_b -+ b theta
    assert not model.H.any() and not model.g(0.0).any()
    assert block.I0 == pytest.approx(4.0 / 3.0 * m * (b * b + h * h))
    alpha = math.atan(b / h)
    assert block.restitution == pytest.approx(1.0 - 1.5 * math.sin(alpha) ** 2) == pytest.approx(0.85)
    assert block.uplift_acceleration == pytest.approx(g * b / h)
    assert [type(f).__name__ for f in model.families] == ["RigidContact"]
    np.testing.assert_array_equal(np.diag(model.law.P), [-1.0, -1.0])              # w = the opening


def test_contact_refusals_are_clear():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.mass(1, 1.0)
    with pytest.raises(ValueError, match="mu=-0.5 must be finite and >= 0"):
        fr.contact("c", 1, mu=-0.5)
    with pytest.raises(ValueError, match="gap"):
        fr.contact("c", 1, gap=-1e-3)
    fr.support(1, ux=True, uy=True)
    fr.node(2, 1.0, 0.0)
    fr.support(2, ux=True, uy=False)
    fr.spring("k", 2, 1.0)
    fr.contact("c", 1)
    with pytest.raises(ValueError, match="cannot move along the normal"):
        fr.build()
    fr2 = Frame2D()
    fr2.node("c", 0.0, 0.6)
    fr2.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    fr2.p_delta()
    with pytest.raises(ValueError, match="p_delta with rigid contacts"):
        fr2.build()


@pytest.mark.parametrize("method, why", [("cq", "not stable by itself"), ("modal", "not stable by itself"),
                                         ("event", "no impact law")])
def test_methods_that_cannot_take_a_rocking_block_refuse_it(method, why):
    st, model, block = _block()
    with pytest.raises(ValueError, match=why):
        ul.solve(model, LoadHistory(st.gravity(block.g)), dt=1e-3, t_end=0.01, method=method, initial="rest")
    sol = ul.solve(model, LoadHistory(st.gravity(block.g)), dt=1e-3, t_end=0.01, initial="rest")   # auto: direct
    assert sol.success and sol.stats["method"] == "direct"


def test_rigid_stop_under_a_spring_mass_direct_cq_modal_agree():
    """K definite (a mass on a spring thrown against a rigid stop 1 cm below): the three methods
    give the same solution (W0 = Lambda(s*)); BDF1 makes the impact perfectly plastic."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False)
    fr.spring("k", 1, 100.0, direction="uy")
    fr.mass(1, 1.0)
    fr.contact("stop", 1, direction="uy", gap=0.01)
    model = fr.build().to_model()
    load = LoadHistory(np.zeros(1))
    sols = {method: ul.solve(model, load, dt=1e-3, t_end=0.5, method=method, rule="bdf1",
                             initial={"udot0": [-1.0]}) for method in ("direct", "cq", "modal")}
    ref = sols["direct"]
    assert ref.success and ref.u.min() >= -0.01 - 1e-15              # the opening -psi = u + 0.01 >= 0
    for sol in sols.values():
        np.testing.assert_allclose(sol.u, ref.u, atol=1e-12)
        np.testing.assert_allclose(sol.v, ref.v, rtol=1e-9, atol=1e-9)
    k = int(np.argmax(ref.v[:, 0] > 0))                            # the step of the impact
    assert ref.u[k, 0] == pytest.approx(-0.01, abs=1e-15) and ref.udot[k - 1, 0] < -0.9
    assert abs(ref.udot[k + 1, 0]) < 1e-12                         # plastic: the stop takes the velocity (2 steps)
    assert 0 < ref.udot[k + 2, 0] < 2e-3 and not ref.v[k + 2:].any()   # then the spring lifts it off slowly


# ---------------------------------------------------------------------- free rocking
def _slope(dts, errors):
    return float(np.polyfit(np.log(dts), np.log(np.abs(errors)), 1)[0])


@pytest.mark.parametrize("rule, order, tol", [("bdf1", 1, 1e-4), ("trapezoidal", 2, 5e-9), ("bdf2", 2, 2e-8)])
def test_time_to_the_first_impact(rule, order, tol):
    """The first impact against the closed form of the linearised equation (the crossing located
    on the closed-form pivoting motion of the last step before it)."""
    dts = [1e-3, 5e-4, 2.5e-4, 1.25e-4]
    errors = []
    for dt in dts:
        st, sol, block = _released(rule, dt, t_end=0.25)
        errors.append(rigid.impacts(st, sol, "B")[0]["time"] - block.first_impact_time(THETA0))
    assert abs(errors[-1]) < tol
    assert _slope(dts, errors) == pytest.approx(order, abs=0.1)
    # before the impact the tilt follows b/h + (theta0 - b/h) cosh(p t) to the rule's order
    n = int(0.9 * block.first_impact_time(THETA0) / dts[-1])
    np.testing.assert_allclose(-sol.u[:n, 1], block.tilt(sol.t[:n], THETA0), atol=50 * dts[-1] ** order)


def test_bdf1_impacts_converge_to_housner_at_first_order():
    """Position-level BDF1 (Moreau-like): a perfectly plastic impact, the ratio of the angular
    velocities tends to Housner's r = 0.85 as dt -> 0 (every impact)."""
    dts = [1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5]
    first = []
    for dt in dts:
        st, sol, block = _released("bdf1", dt)
        ratios = [imp["ratio"] for imp in rigid.impacts(st, sol, "B")[:3]]
        first.append(ratios[0])
    assert np.allclose(ratios, block.restitution, atol=1.5e-3)
    errors = np.array(first) - block.restitution
    assert np.all(errors < 0) and abs(errors[-1]) < 1e-3
    assert 0.7 < _slope(dts, errors) < 1.5                        # about first order (the crossing's phase in the step scatters it)


def test_bdf2_first_impact_ratio_and_trapezoidal_bounce():
    """BDF2: the first impact loses Housner's energy in the limit (r to 2e-4 at dt = 1.25e-4), but
    it is spread over a few steps of flight, and later impacts scatter. Trapezoidal: the
    position-level hold reverses the impacting corner's velocity: the block flies off both corners
    (an elastic bounce, no Housner law)."""
    st, sol, block = _released("bdf2", 1.25e-4)
    imp = rigid.impacts(st, sol, "B")
    assert imp[0]["ratio"] == pytest.approx(block.restitution, abs=5e-4)
    st, sol, block = _released("trapezoidal", 1e-3, t_end=0.3)
    k = rigid.impacts(st, sol, "B")[0]["step"]
    openings = -sol.psi[k + 2]
    assert np.all(openings > 1e-4) and not sol.v[k + 2].any()      # both corners off the ground


# ---------------------------------------------------------------------- a shaking base
def _shaken(factor):
    st, model, block = _block()
    q = st.gravity(block.g)
    t = np.linspace(0.0, 1.0, 2001)
    a_g = Tabulated(t, factor * block.uplift_acceleration * np.sin(2 * np.pi * 2.0 * t))
    load = LoadHistory(q, [rigid.ground_motion(st, a_g)])
    v0 = rigid.initial_forces(model, np.zeros(2), q)
    np.testing.assert_allclose(v0, [block.W / 2, block.W / 2])
    sol = ul.solve(model, load, dt=1e-3, t_end=1.0, method="direct", rule="bdf1", initial={"u0": np.zeros(2), "v0": v0})
    assert sol.success, sol.message
    return sol, block


def test_below_the_uplift_threshold_nothing_lifts():
    sol, block = _shaken(0.9)                                     # a_g = 0.9 g b / h
    assert np.abs(sol.u).max() < 1e-15 and np.abs(sol.psi).max() < 1e-15       # no opening, no rotation
    assert sol.v.min() > 0.04 * block.W                            # both corners stay loaded
    np.testing.assert_allclose(sol.v.sum(axis=1), block.W, rtol=1e-13)
    assert sol.stats["contact_changes"] == 0


def test_above_the_uplift_threshold_the_block_rocks():
    sol, block = _shaken(1.5)
    assert np.abs(sol.u[:, 1]).max() > 1e-2                        # it rocks (and returns: no overturning)
    assert np.abs(sol.u[:, 1]).max() < block.alpha
    assert sol.stats["contact_changes"] > 2


def test_the_example_runs():
    path = Path(__file__).resolve().parents[1] / "examples" / "rocking_block.py"
    env = {"PYTHONPATH": str(Path(__file__).resolve().parents[1] / "src"), "PATH": "/usr/bin:/bin"}
    out = subprocess.run([sys.executable, str(path), "--quick"], capture_output=True, text=True, timeout=600, env=env)
    assert out.returncode == 0, out.stderr
    assert "Housner" in out.stdout and "impact" in out.stdout


def test_a_column_on_the_block_builds_and_starts_at_rest():
    """A beam on the block's centre (a slave node): massless rotations condensed in initial_forces."""
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    fr.node("top", 0.0, 3.0)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    fr.beam("col", "c", "top", E=30e6, A=0.01, I=1e-4)
    fr.mass("top", 0.2)
    st = fr.build()
    model = st.to_model()
    assert model.constraint_names == ["B.left", "B.right"] and st.rigid.blocks["B"] is block
    q = st.gravity(block.g)
    v0 = rigid.initial_forces(model, np.zeros(model.n), q)
    np.testing.assert_allclose(v0, [block.W / 2] * 2)          # at t = 0 the column is not yet compressed
    sol = ul.solve(model, LoadHistory(q), dt=1e-3, t_end=0.1, method="direct", rule="bdf1",
                   initial={"u0": np.zeros(model.n), "v0": v0})
    assert sol.success and np.abs(sol.u).max() < 1e-4


# ---------------------------------------------------------------------- the velocity-level impact law
# method="moreau-jean" (Newton's law, impacts located in the step): tests/test_moreau_jean.py
