"""method="moreau-jean": rigid contacts with Newton's impact law at the velocity level, impacts
located within the step (march/impact.py, methods/moreau_jean.py, analysis/rigid.py).

The block: width 2b = 0.4 m, height 2h = 1.2 m, m = 1 t (kN, m, s), released at rest from the
tilt theta0 = 0.05 rad on its right corner: Housner's r = 1 - 2 m b^2 / I0 = 0.85, the impact
times of the linearised rocking from RigidBlock.impact_times.
"""

import math
import re
import warnings

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import block_results, contact_results, energy_balance, one_sine_pulse
from unilateral.loads import LoadHistory
from unilateral.methods import METHODS, MoreauJean
from unilateral.structure import Frame2D, rigid

THETA0 = 0.05


def _block(**kw):
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, **kw)
    st = fr.build()
    return st, st.to_model(), block


def _released(dt, t_end=0.8, rule="trapezoidal", **options):
    st, model, block = _block()
    u0 = np.array([block.b * THETA0, -THETA0])                 # on the right corner
    sol = ul.solve(model, LoadHistory(st.gravity(block.g)), dt=dt, t_end=t_end, method=MoreauJean(**options),
                   rule=rule, initial={"u0": u0})
    assert sol.success, sol.message
    return st, model, sol, block


def _ratios(sol, st, block):
    """omega+ / omega- at each located impact (the impact's velocities; the block's rz row)."""
    row = st.dofs.T[st.dofs.full_index(block.base, "rz")].toarray().ravel()
    return [float(row @ np.array(ev["udot_after"]) / (row @ np.array(ev["udot_before"])))
            for ev in sol.stats["impacts"]]


def _slope(dts, errors):
    return float(np.polyfit(np.log(dts), np.log(np.abs(errors)), 1)[0])


# ---------------------------------------------------------------------- the method
def test_registered_chosen_by_name_and_refuses_other_problems():
    assert METHODS["moreau-jean"] is MoreauJean
    st, model, block = _block()
    load = LoadHistory(st.gravity(block.g))
    with pytest.raises(ValueError, match="rule='bdf2': method='moreau-jean' is the theta-method"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="moreau-jean", initial="rest")
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False)
    fr.mass(1, 1.0)
    fr.soil("s", 1, 100.0)
    soil = fr.build().to_model()
    with pytest.raises(ValueError, match="every unknown is a rigid contact.*'s'"):
        ul.solve(soil, None, dt=1e-3, t_end=0.01, method="moreau-jean", rule="trapezoidal")
    # auto: moreau-jean for rigid contacts with a rule of the theta-method, direct (warned) with BDF2
    sol = ul.solve(model, load, dt=1e-3, t_end=0.05, rule="bdf1")
    assert sol.stats["method"] == "moreau-jean" and sol.stats["theta"] == 1.0
    with pytest.warns(UserWarning, match="BDF2 spreads an impact"):
        sol = ul.solve(model, load, dt=1e-3, t_end=0.05, initial="rest")
    assert sol.stats["method"] == "direct" and "moreau-jean" in sol.stats["rigid_contact_warning"]


def test_direct_warns_with_the_rules_that_give_no_impact_law():
    st, model, block = _block()
    load = LoadHistory(st.gravity(block.g))
    with pytest.warns(UserWarning, match="reverses the velocity"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="direct", rule="trapezoidal", initial="rest")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        sol = ul.solve(model, load, dt=1e-3, t_end=0.01, method="direct", rule="bdf1", initial="rest")
    assert "rigid_contact_warning" not in sol.stats


def test_bad_restitution_and_friction_are_refused():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.mass(1, 1.0)
    with pytest.raises(ValueError, match=r"restitution=1.5 must lie in \[0, 1\]"):
        fr.contact("c", 1, restitution=1.5)
    with pytest.raises(ValueError, match="restitution=-0.1"):
        fr.contact("c", 1, restitution=-0.1)
    fr.node("c", 0.0, 2.0)
    with pytest.raises(ValueError, match="mu=-0.5 must be finite and >= 0"):
        fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, mu=-0.5)
    with pytest.raises(ValueError, match="width=0"):
        fr.rigid_block("B", "c", width=0.0, height=1.2, mass=1.0)


# ---------------------------------------------------------------------- Housner's block
def test_housner_ratio_at_every_impact_and_second_order_impact_times():
    """The impact LCP at the located impact gives Housner's r exactly (linearised kinematics);
    the impact times converge at second order (trapezoidal) to the closed form, 1e-9 at 6.25e-5."""
    dts = [1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5]
    first, third = [], []
    for dt in dts:
        st, model, sol, block = _released(dt)
        ratios = _ratios(sol, st, block)
        assert len(ratios) == 3 and np.allclose(ratios, block.restitution, atol=1e-12, rtol=0)
        times = [ev["time"] for ev in sol.stats["impacts"]]
        exact = block.impact_times(THETA0, 3)
        first.append(times[0] - exact[0])
        third.append(times[2] - exact[2])
        assert sol.stats["impacts"][0]["contacts"] == ["B.left"] and sol.stats["unlocated_steps"] == 0
    assert abs(first[-1]) < 1e-9
    assert _slope(dts, first) == pytest.approx(2.0, abs=0.05)
    assert _slope(dts, third) == pytest.approx(2.0, abs=0.05)
    # the arriving corner lands on the ground: no penetration (the opening of either corner >= 0)
    assert (-sol.psi).min() > -1e-15


def test_plain_moreau_jean_impacts_at_first_order_and_bdf1():
    """locate=False: the impact at the end of its step, Housner's ratio at first order; rule='bdf1'
    (theta = 1) with located impacts: the impact times at first order, the ratios exact."""
    dts = [1e-3, 5e-4, 2.5e-4]
    errors = []
    for dt in dts:
        st, model, sol, block = _released(dt, locate=False)
        imp = rigid.impacts(st, sol, "B")                          # ratio from the energies either side
        errors.append(imp[0]["ratio"] - block.restitution)
        assert sol.stats["impacts"] == []
    assert _slope(dts, errors) == pytest.approx(1.0, abs=0.2)
    times = []
    for dt in dts:
        st, model, sol, block = _released(dt, rule="bdf1")
        assert np.allclose(_ratios(sol, st, block), block.restitution, atol=1e-12)
        times.append(sol.stats["impacts"][0]["time"] - block.first_impact_time(THETA0))
    assert _slope(dts, times) == pytest.approx(1.0, abs=0.05)


def test_energy_balance_closes_and_the_impact_loss_is_housners():
    st, model, sol, block = _released(5e-4, t_end=1.2)
    energy = energy_balance(model, sol)
    assert energy["relative_error"] < 1e-12
    assert np.abs(energy["numerical_dissipation"]).max() == 0.0            # trapezoidal: theta = 1/2
    omega = block.p * math.sqrt(2 * block.b / block.h * THETA0 - THETA0 ** 2)   # at the first impact
    losses = []
    for ev in sol.stats["impacts"]:
        losses.append(ev["loss"])
        assert ev["loss"] == pytest.approx(0.5 * block.I0 * omega ** 2 * (1 - block.restitution ** 2), rel=1e-9)
        omega *= block.restitution
    assert energy["impact_loss"][-1] == pytest.approx(sum(losses), rel=1e-12)
    corners = contact_results(sol)
    assert sum(len(c["impacts"]) for c in corners.values()) == len(losses)
    res = block_results(st, sol, "B")
    assert not res["overturned"] and res["peak_rotation"] == pytest.approx(THETA0, abs=1e-12)
    np.testing.assert_allclose(res["uplift"], np.abs(res["rotation"]) * 2 * block.b, atol=1e-14)


# ---------------------------------------------------------------------- Newton's law: a ball on a floor
def test_ball_bounces_to_e2_of_its_height_accumulates_at_the_zeno_time_and_rests():
    H, e, g, m = 1.0, 0.5, 9.81, 2.0
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False, rz=True)
    fr.mass(1, m)
    fr.contact("floor", 1, direction="uy", gap=H, restitution=e)
    st = fr.build()
    model = st.to_model()
    t0 = math.sqrt(2 * H / g)
    t_zeno = t0 * (1 + e) / (1 - e)
    sol = ul.solve(model, LoadHistory(st.gravity(g)), dt=1e-3, t_end=t_zeno + 0.5, method="moreau-jean",
                   rule="trapezoidal", initial="rest")
    assert sol.success, sol.message
    impacts = sol.stats["impacts"]
    # constant acceleration: the trapezoidal flights are exact, so is each located impact
    for k, ev in enumerate(impacts[:6]):
        v_before = -math.sqrt(2 * g * H) * e ** k
        expected = t0 + 2 * t0 * sum(e ** j for j in range(1, k + 1))
        assert ev["time"] == pytest.approx(expected, abs=1e-9)
        assert ev["before"][0] == pytest.approx(v_before, rel=1e-9)
        assert ev["after"][0] == pytest.approx(-e * v_before, rel=1e-9)               # Newton's law
        assert ev["loss"] == pytest.approx((1 - e * e) * 0.5 * m * v_before ** 2, rel=1e-9)
    # each bounce rises to e^2 of the previous height
    u = sol.u[:, 0]
    tops = [u[(sol.t > a["time"]) & (sol.t < b["time"])].max() for a, b in zip(impacts[:4], impacts[1:5])]
    heights = np.array(tops) + H
    np.testing.assert_allclose(heights[1:] / heights[:-1], e * e, rtol=1e-3)
    # the impacts accumulate before the Zeno time, the ball then rests on the floor carrying its weight
    assert max(ev["time"] for ev in impacts) < t_zeno + 2e-3
    after = sol.t > t_zeno + 0.05
    assert np.abs(u[after] + H).max() < 1e-12 and np.abs(sol.udot[after, 0]).max() < 1e-12
    np.testing.assert_allclose(sol.v[after, 0], m * g, rtol=1e-9)
    energy = energy_balance(model, sol)
    assert energy["relative_error"] < 1e-12
    assert energy["impact_loss"][-1] == pytest.approx(m * g * H, rel=1e-9)      # all of it, at rest


# ---------------------------------------------------------------------- the uplift threshold
@pytest.mark.parametrize("factor, lifts", [(0.98, False), (1.05, True)])
def test_one_sine_pulse_lifts_the_block_only_above_g_tan_alpha(factor, lifts):
    """The closed form: a rigid block on a base accelerated by a_g lifts a corner only where
    |a_g| > g b / h (= g tan alpha); below, the contact forces stay positive and nothing moves."""
    st, model, block = _block()
    wp = 4.0 * block.p
    a_g = one_sine_pulse(factor * block.uplift_acceleration, wp)
    load = LoadHistory(st.gravity(block.g), [rigid.ground_motion(st, a_g)])
    sol = ul.solve(model, load, dt=1e-3, t_end=2 * math.pi / wp + 0.5, method="moreau-jean", rule="trapezoidal")
    assert sol.success, sol.message
    res = block_results(st, sol, "B")
    if lifts:
        assert res["peak_uplift"] > 1e-5 and not res["overturned"]
    else:
        assert res["peak_uplift"] < 1e-15 and res["peak_rotation"] < 1e-15
        assert sol.v.min() > 0.0
        np.testing.assert_allclose(sol.v.sum(axis=1), block.W, rtol=1e-12)


def test_static_initial_of_a_block_and_of_a_column_on_it():
    """initial='static': a block standing on its base is at rest at u = 0 (K indefinite); a column
    with massless end rotations on the block (condensed in the impulse response) stays at rest."""
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    fr.node("top", 0.0, 3.0)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    fr.beam("col", "c", "top", E=30e6, A=0.01, I=1e-4)
    fr.mass("top", 0.2)
    st = fr.build()
    model = st.to_model()
    sol = ul.solve(model, LoadHistory(st.gravity(block.g)), dt=1e-3, t_end=0.2, method="moreau-jean",
                   rule="trapezoidal")
    assert sol.success and np.abs(sol.u).max() < 1e-4
    np.testing.assert_allclose(sol.v[-1].sum(), block.W + 0.2 * block.g, rtol=1e-6)
    st2, model2, block2 = _block()
    with pytest.raises(ValueError, match="initial has unknown keys"):
        ul.solve(model2, None, dt=1e-3, t_end=0.01, method="moreau-jean", rule="trapezoidal",
                 initial={"u0": [0.0, 0.0], "bad": 1})


def test_a_simulation_that_steps_gives_the_solve():
    st, model, block = _block()
    load = LoadHistory(st.gravity(block.g))
    u0 = np.array([block.b * THETA0, -THETA0])
    kw = dict(dt=1e-3, t_end=0.6, method="moreau-jean", rule="trapezoidal", initial={"u0": u0})
    sim = ul.Simulation(model, load, **kw)
    sim.advance(7)
    assert sim.state.k == 7 and sim.stats["stepping"] == "step"
    sim.advance_to(0.3)
    part = sim.solution()
    assert len(part.t) == 301 and part.success
    sim.advance_to(0.6)
    whole = ul.solve(model, load, **kw)
    np.testing.assert_array_equal(sim.solution().u, whole.u)
    np.testing.assert_array_equal(sim.solution().v, whole.v)
    assert len(whole.stats["impacts"]) == len(sim.solution().stats["impacts"]) > len(part.stats["impacts"])


# ---------------------------------------------------------------------- model files
EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples"


def test_the_model_file_of_a_rocking_block_runs_with_its_results(tmp_path):
    """examples/rocking_block.toml ([[rigid_blocks]], moreau-jean) through unilateral.run: the
    block's rotation, uplift and impacts in the summary, the energy balance closed to round-off."""
    import json

    from unilateral.analysis.run import run_model_file
    from unilateral.modelfile import load_model_file

    spec = load_model_file(EXAMPLES / "rocking_block.toml")
    block = spec.structure.rigid.blocks["cabinet"]
    assert (block.b, block.h, block.mass) == (0.3, 0.9, 2.0) and spec.model.constraint_names == [
        "cabinet.left", "cabinet.right"]
    run_model_file(EXAMPLES / "rocking_block.toml", tmp_path / "out", figures=(), t_end=2.5)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["method"] == "moreau-jean" and summary["success"]
    results = summary["results"]["unilateral"]
    rocking = results["rigid_contacts"]["blocks"]["cabinet"]
    assert 0.05 < rocking["peak_rotation"] < block.b / block.h and not rocking["overturned"]
    assert rocking["impacts"] > 2 and rocking["impact_loss"] > 0
    assert rocking["peak_uplift"] == pytest.approx(2 * block.b * rocking["peak_rotation"], rel=1e-9)
    assert results["energy"]["max_relative_error"] < 1e-10
    assert results["energy"]["contact_dissipated"] == pytest.approx(rocking["impact_loss"], rel=1e-9)


def _model_file(tmp_path, tables, analysis='method = "moreau-jean"\nrule = "trapezoidal"\n'):
    text = ('[units]\nlength = "m"\nforce = "kN"\ntime = "s"\n\n[[nodes]]\nid = 1\nx = 0.0\ny = 0.0\n\n'
            '[[supports]]\nnode = 1\nux = true\nuy = false\n\n[[masses]]\nnode = 1\nm = 1.0\n\n' + tables
            + '\n[loads.gravity]\ng = 9.81\n\n[analysis]\ndt = 0.001\nt_end = 0.5\n'
            + 'bilateral_reference = false\ninitial = "rest"\n' + analysis)
    path = tmp_path / "m.toml"
    path.write_text(text)
    return path


def test_a_model_file_contact_bounces_by_its_restitution(tmp_path):
    from unilateral.modelfile import load_model_file

    spec = load_model_file(_model_file(tmp_path, '[[contacts]]\nname = "floor"\nnode = 1\ngap = 0.2\n'
                                                 'restitution = 0.5\n'))
    sol = ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.5, method="moreau-jean", rule="trapezoidal",
                   initial="rest")
    first = sol.stats["impacts"][0]
    assert first["time"] == pytest.approx(math.sqrt(2 * 0.2 / 9.81), abs=1e-12)
    assert first["after"][0] == pytest.approx(-0.5 * first["before"][0], rel=1e-12)


@pytest.mark.parametrize("table, message", [
    ('[[contacts]]\nname = "c"\nnode = 1\nrestitution = 1.5\n', "contacts[0].restitution"),
    ('[[contacts]]\nname = "c"\nnode = 1\nmu = -0.3\n', "contacts[0].mu"),
    ('[[nodes]]\nid = 2\nx = 0.0\ny = 1.0\n[[rigid_blocks]]\nname = "B"\nnode = 2\nwidth = 0.0\nheight = 1.0\n'
     'mass = 1.0\n', "rigid_blocks[0].width"),
    ('[[contacts]]\nname = "c"\nnode = 9\n', "no node 9"),
])
def test_model_file_bad_rigid_tables_are_named(tmp_path, table, message):
    from unilateral.modelfile import ModelFileError, load_model_file

    with pytest.raises(ModelFileError, match=re.escape(message)):
        load_model_file(_model_file(tmp_path, table))


def test_model_file_with_a_method_that_has_no_impact_law_is_refused(tmp_path):
    from unilateral.modelfile import load_model_file

    spec = load_model_file(_model_file(tmp_path, '[[contacts]]\nname = "floor"\nnode = 1\ngap = 0.2\n'))
    with pytest.raises(ValueError, match="no impact law.*moreau-jean"):
        ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.1, method="event", initial="rest")


@pytest.mark.slow
def test_the_overturning_map_example_runs_quick():
    """examples/overturning_map.py --quick: nothing lifts below g tan(alpha) (the closed form), a
    long pulse overturns the block at a large amplitude, the short pulse only rocks it."""
    import runpy

    module = runpy.run_path(str(EXAMPLES / "overturning_map.py"))
    result = module["main"](quick=True)
    assert all(result[(f, 0.9)] == "rest" for f in (2.0, 4.0, 8.0))
    assert result[(2.0, 8.0)].startswith("mode") and result[(8.0, 3.0)] == "rocks"


def test_bilateral_holds_every_contact():
    """bilateral=True (the "without uplift" reference): the contacts are held at their initial
    opening; a block then does not rotate under a pulse that rocks it, and its contact forces take
    either sign."""
    st, model, block = _block()
    a_g = one_sine_pulse(3.0 * block.uplift_acceleration, 4.0 * block.p)
    load = LoadHistory(st.gravity(block.g), [rigid.ground_motion(st, a_g)])
    sol = ul.solve(model, load, dt=1e-3, t_end=1.0, method="moreau-jean", rule="trapezoidal", bilateral=True)
    assert sol.success and np.abs(sol.u).max() < 1e-15 and sol.v.min() < 0 < sol.v.max()
    assert sol.stats["impacts"] == []


# ---------------------------------------------------------------------- friction: sliding or rocking
@pytest.mark.parametrize("mu, a, mode", [(0.15, 0.25, "slides"), (0.5, 0.45, "rocks")])
def test_a_block_slides_when_mu_is_below_b_over_h_and_rocks_otherwise(mu, a, mode):
    """A constant base acceleration a g (from rest): with mu < b/h = 1/3 and mu < a < b/h the block
    slides without rocking, its slip the closed form (a - mu) g t^2 / 2; with mu > b/h and a > b/h
    it rocks without sliding. The balance closes with the friction work."""
    g = 9.81
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, mu=mu, g=g)
    st = fr.build()
    model = st.to_model()
    load = LoadHistory(st.gravity(g), [rigid.ground_motion(st, lambda t: a * g)])
    sol = ul.solve(model, load, dt=1e-3, t_end=0.5, method="moreau-jean", rule="trapezoidal", initial="rest")
    assert sol.success, sol.message
    slip, theta = sol.dof("B.base.ux"), sol.dof("B.base.rz")
    energy = energy_balance(model, sol)
    assert energy["relative_error"] < 1e-12
    if mode == "slides":
        np.testing.assert_allclose(slip, -0.5 * (a - mu) * g * sol.t ** 2, rtol=1e-9, atol=1e-15)
        assert np.abs(theta).max() < 1e-12
        assert energy["friction_work"][-1] == pytest.approx(mu * g * abs(slip[-1]), rel=1e-9)
    else:
        assert np.abs(slip).max() < 1e-12 and np.abs(theta).max() > 0.1
        assert np.abs(energy["friction_work"]).max() < 1e-12
    with pytest.raises(ValueError, match="friction.*only method='moreau-jean'"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="direct", rule="bdf1", initial="rest")
