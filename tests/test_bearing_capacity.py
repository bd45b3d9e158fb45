"""Bearing capacity of soil springs and footings (issue 34, "footings that yield the soil").

A soil spring with ``bearing=Q`` (Frame2D.soil, Frame2D.soils) carries at most the compression ``Q``;
beyond it the soil settles plastically by ``w`` (the rate-type unknown ``"name.plastic-"``), and
unloads elastically with the permanent settlement. Defining properties:

* a single spring pushed in compression beyond ``Q``: the force is ``Q`` exactly, ``w`` is the
  displacement beyond ``Q/k``, unloading is elastic from the settled position;
* a rigid footing of width ``B`` on ``n`` springs (Frame2D.spring_footing, ``q_ult`` per unit area)
  under a vertical load ``N``, rotated by a static pushover: the moment plateau is the discrete
  closed form ``M_ult - q_ult L h^2 f (1 - f) / 2`` and tends to ``M_ult = N B/2 (1 - N/N_ult)`` with
  the order 2 (``N / N_ult = 1/3``: the relative error is ``1/n^2`` exactly);
* a rocking footing under a cyclic moment: the settlement grows every cycle, no spring's compression
  exceeds ``Q``, and the energy balance closes with the plastic work counted;
* bad capacities and the soil medium (a Laplace-domain foundation) are refused with clear messages.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.constraints import Bearing, Contact
from unilateral.pushover import pushover
from unilateral.structure import Frame2D, Frame3D
from unilateral.structure import forces as F

K, Q = 1000.0, 10.0                     # kN/m, kN
ROOT = Path(__file__).resolve().parents[1]


def one_spring(*, bulk=False, parallel=None, mass=None):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False)
    if bulk:
        fr.soils(["s"], [1], K, bearing=Q)
    else:
        fr.soil("s", 1, K, bearing=Q)
    if parallel is not None:
        fr.spring("k2", 1, parallel)
    if mass is not None:
        fr.mass(1, mass)
    return fr.build()


@pytest.mark.parametrize("bulk", [False, True])
def test_a_spring_pushed_beyond_its_capacity_carries_q_and_settles_by_the_rest(bulk):
    st = one_spring(bulk=bulk)
    assert st.constraint_names == ("s", "s.plastic-")
    families = st.families()
    assert [type(f) for f in families] == [Contact, Bearing] and families[1].pairs() == ((0, 1),)
    r = pushover(st, st.nodal_load(1, uy=-1.0), node=1, dof="uy", target=[-0.05, -0.045, -0.02, -0.08])
    assert r.success, r.message
    d, force, w = r.displacement, r.psi[:, 0], r.v[:, 1]      # contact psi = sigma (capacity 0)
    at = {round(x, 6): k for k, x in enumerate(d)}
    k = at[-0.05]
    assert -force[k] == pytest.approx(Q, rel=1e-12) and r.load_factor[k] == pytest.approx(Q, rel=1e-12)
    assert w[k] == pytest.approx(0.05 - Q / K, rel=1e-12)                      # beyond Q/k: plastic
    k = at[-0.045]                                                            # unloading: elastic
    assert force[k] == pytest.approx(K * (-0.045 + 0.04), rel=1e-12) and w[k] == pytest.approx(0.04, rel=1e-12)
    k = at[-0.02]                                                             # lifted off the settled soil
    assert abs(force[k]) <= 1e-12 * Q and r.v[k, 0] == pytest.approx(0.02, rel=1e-12) and w[k] == pytest.approx(0.04, rel=1e-12)
    assert -force[-1] == pytest.approx(Q, rel=1e-12) and w[-1] == pytest.approx(0.07, rel=1e-12)
    assert np.all(-force <= Q * (1 + 1e-12)) and np.all(np.diff(w) >= 0)
    kinds = [e.kind for e in r.events]
    assert kinds == ["yield", "unload", "uplift", "contact", "yield"]


def test_a_dynamic_overload_never_compresses_the_spring_beyond_q():
    st = one_spring(parallel=200.0, mass=1.0)                 # the parallel spring takes the rest
    dt, t_end = 1e-3, 1.0
    t = dt * np.arange(int(round(t_end / dt)) + 1)
    P = -2.5 * Q * np.minimum(t / 0.5, 1.0)
    q = np.outer(P, st.nodal_load(1, uy=1.0))
    sol = ul.solve(st.to_model(), q, dt=dt, t_end=t_end, method="direct")
    assert sol.success
    sigma = st.element_forces(sol.t, sol.u, sol.v)[:, list(st.strain_names).index("s")]
    assert sigma.min() >= -Q * (1 + 1e-12) and sigma.min() == pytest.approx(-Q, rel=1e-12)
    w = sol.v[:, 1]
    assert np.all(np.diff(w) >= -1e-15) and w[-1] > 0
    yielding = np.diff(w) > 1e-12                                             # settles only at Q
    assert np.allclose(sigma[1:][yielding], -Q, rtol=1e-12)


def footing(n, *, B=2.0, L=1.0, q_ult=100.0, k=1e4, c=0.0, mass=None):
    fr = Frame2D()
    fr.node("c", 0.0, 0.0)
    fr.support("c", ux=True, uy=False)
    fr.spring_footing("f", "c", width=B, length=L, k=k, c=c, springs=n, q_ult=q_ult)
    if mass is not None:
        fr.mass("c", mass, J=mass * B ** 2 / 12)
    return fr.build()


def plateau(n, ratio, *, B=2.0, L=1.0, q_ult=100.0):
    st = footing(n, B=B, L=L, q_ult=q_ult)
    N = ratio * q_ult * B * L
    r = pushover(st, st.nodal_load("c", rz=1.0), node="c", dof="rz", target=0.5, gravity=st.nodal_load("c", uy=-N),
                 max_events=4 * n + 20)
    assert r.success, r.message
    bearing = [k for k, name in enumerate(st.constraint_names) if name.endswith(".plastic-")]
    assert np.all(r.psi[:, bearing] <= 1e-12 * q_ult)                       # no spring beyond its capacity
    return r.load_factor.max(), N * B / 2 * (1 - N / (q_ult * B * L))


def test_the_moment_capacity_of_a_footing_on_springs_converges_to_m_ult_with_order_2():
    ns = (4, 8, 16, 32, 64)
    errors = []
    for n in ns:
        M, M_ult = plateau(n, 1 / 3)
        errors.append((M_ult - M) / M_ult)
        assert errors[-1] == pytest.approx(1 / n ** 2, rel=1e-9)         # f = 1/3 or 2/3 at every n
    order = -np.polyfit(np.log(ns), np.log(errors), 1)[0]
    assert order == pytest.approx(2.0, abs=1e-8)


@pytest.mark.parametrize("n", [5, 12, 40])
def test_the_plateau_is_the_discrete_closed_form(n):
    B, L, q_ult, ratio = 2.0, 1.5, 100.0, 0.3
    M, M_ult = plateau(n, ratio, B=B, L=L, q_ult=q_ult)
    h, f = B / n, math.modf(ratio * n)[0]
    assert M == pytest.approx(M_ult - q_ult * L * h * h * f * (1 - f) / 2, rel=1e-12)


def test_a_rocking_footing_settles_more_with_each_cycle_and_the_energy_balance_closes():
    n, B, q_ult, g = 8, 2.0, 100.0, 10.0
    m = q_ult * B / 3 / g                                                     # N = N_ult / 3
    st = footing(n, B=B, q_ult=q_ult, c=5.0, mass=m)
    dt, T, cycles = 2e-3, 1.0, 5
    t = dt * np.arange(int(round(cycles * T / dt)) + 1)
    M_ult = m * g * B / 2 * (1 - m * g / (q_ult * B))
    q = np.tile(st.gravity(g), (t.size, 1)) + np.outer(0.9 * M_ult * np.sin(2 * np.pi * t / T),
                                                       st.nodal_load("c", rz=1.0))
    sol = ul.solve(st.to_model(), q, dt=dt, t_end=cycles * T, method="direct", rule="trapezoidal")
    assert sol.success
    bearing = [k for k, name in enumerate(st.constraint_names) if name.endswith(".plastic-")]
    settlement = sol.v[:, bearing].mean(axis=1)                              # the footing's mean plastic settlement
    per_cycle = settlement[[int(round(k * T / dt)) for k in range(cycles + 1)]]
    assert np.all(np.diff(per_cycle) > 0), per_cycle
    assert np.all(sol.psi[:, bearing] <= 1e-12 * q_ult)
    h = F.Histories.from_solution(st, sol, "trapezoidal", load0=q[0])
    e = energy_balance(st, h, q)
    assert e["max_relative_error"] < 1e-10
    assert e["plastic_work"][-1] > 0.05 * e["input_work"].max()
    assert np.all(np.diff(e["plastic_work"]) >= -1e-12)
    assert e["unknown_work"][bearing].sum() == pytest.approx(e["plastic_work"][-1], rel=1e-12)


@pytest.mark.parametrize("bad, error", [(0.0, ValueError), (-5.0, ValueError), (math.nan, ValueError),
                                        (math.inf, ValueError), ("10", TypeError), (True, TypeError)])
def test_a_bearing_capacity_must_be_a_positive_finite_force(bad, error):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    with pytest.raises(error, match="bearing"):
        fr.soil("s", 1, K, bearing=bad)
    if error is ValueError:
        with pytest.raises(ValueError, match=r"bearing\[1\]"):
            fr.soils(["a", "b"], [1, 1], K, bearing=[Q, bad])
    assert not fr._elements                                                  # nothing was added
    fr.node(2, 1.0, 0.0)
    with pytest.raises(error, match="q_ult"):
        fr.spring_footing("f", 2, width=1.0, k=1e4, q_ult=bad)
    assert set(fr._coords) == {1, 2}


def test_a_spring_footing_refuses_a_bad_number_of_springs_and_a_taken_name():
    fr = Frame2D()
    fr.node("c", 0.0, 0.0)
    for springs in (0, 2.0, True):
        with pytest.raises(ValueError, match="springs"):
            fr.spring_footing("f", "c", width=1.0, k=1e4, springs=springs)
    fr.node("f.1", 5.0, 0.0)
    with pytest.raises(ValueError, match="'f.1' is already a node"):
        fr.spring_footing("f", "c", width=1.0, k=1e4, springs=2)


def test_a_footing_on_a_soil_medium_refuses_q_ult_and_names_the_springs_instead():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"q_ult=150.*soil medium.*spring_footing"):
        fr.foundation("f", 1, width=2.0, length=1.0, soil={"model": "winkler-kelvin", "k": 1e4, "c": 0.0},
                      q_ult=150.0)
    assert not fr._foundations


def test_a_model_file_soil_takes_a_bearing_capacity(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file
    from unilateral.modelfile.schema3d import Soil3D

    text = (ROOT / "examples" / "liolios1990.toml").read_text()
    text = text.replace('name = "soil3", node = 3, k = 200e3, c = 10e3 }',
                        'name = "soil3", node = 3, k = 200e3, c = 10e3, bearing = 150.0 }')
    (tmp_path / "model.toml").write_text(text)
    spec = load_model_file(tmp_path / "model.toml")
    assert "soil3.plastic-" in spec.structure.constraint_names
    (unknown,) = [u for _, u in spec.structure.constraints if u.name == "soil3.plastic-"]
    assert (unknown.r, unknown.b, unknown.kind) == (150.0, -1.0, "yield")
    (tmp_path / "bad.toml").write_text(text.replace("bearing = 150.0", "bearing = 0.0"))
    with pytest.raises(ModelFileError, match=r"unilateral\[0\]\.bearing = 0\.0"):
        load_model_file(tmp_path / "bad.toml")
    assert "bearing" in Soil3D.model_fields                        # 3-D soils take it too


def test_the_summary_of_a_run_reports_the_settlement_of_a_bearing_spring(tmp_path):
    from unilateral.analysis.run import run_model_file

    text = (ROOT / "examples" / "liolios1990.toml").read_text()
    text = text.replace('name = "soil4", node = 4, k = 200e3, c = 10e3 }',
                        'name = "soil4", node = 4, k = 200e3, c = 10e3, bearing = 250.0 }')
    (tmp_path / "model.toml").write_text(text)
    summary = run_model_file(tmp_path / "model.toml", tmp_path / "out", figures=(), t_end=0.3)
    soil = summary["results"]["unilateral"]["yield_elements"]["soil4"]
    assert soil["kind"] == "soil" and soil["yielded"]
    assert soil["peak_force_ratio"]["value"] == pytest.approx(1.0, abs=1e-9)      # at Q, never beyond
    assert soil["residual_plastic_deformation"] < 0                                # settled (shortened)
    assert soil["yield_deformation"][1] == pytest.approx(250.0 / 200e3) and soil["ductility"]["value"] > 1


def test_soils_makes_the_elements_of_soil_with_a_bearing_capacity():
    def build(bulk):
        fr = Frame2D()
        fr.nodes([1, 2], [0.0, 1.0], [0.0, 0.0])
        if bulk:
            fr.soils(["a", "b"], [1, 2], [K, 2 * K], c=3.0, capacity=[0.0, 1.0], bearing=[Q, 2 * Q])
        else:
            fr.soil("a", 1, K, c=3.0, bearing=Q)
            fr.soil("b", 2, 2 * K, c=3.0, capacity=1.0, bearing=2 * Q)
        return fr._elements

    for one, many in zip(build(False), build(True)):
        assert one.unknowns == many.unknowns and one.dofs == many.dofs
        assert np.array_equal(one.E, many.E) and np.array_equal(one.E_v, many.E_v)


def _plane_footing(frame, n=6, B=2.0, q_ult=100.0, m=10.0):
    """A rigid footing ``c`` of width ``B`` on ``n`` bearing springs (k 1e4 per unit area, 1 m long),
    in the x-y plane of a Frame2D or the x-z plane of a Frame3D (its out-of-plane DOFs held)."""
    three = isinstance(frame, Frame3D)
    at = (lambda x, z: (x, 0.0, z)) if three else (lambda x, z: (x, z))
    frame.node("c", *at(0.0, 0.0))
    if three:
        frame.support("c", ux=True, uy=True, uz=False, rx=True, ry=False, rz=True)
        frame.mass("c", m, Jy=m * B * B / 12)
    else:
        frame.support("c", ux=True, uy=False, rz=False)
        frame.mass("c", m, J=m * B * B / 12)
    for j in range(n):
        x = -B / 2 + B * (j + 0.5) / n
        frame.node(f"s{j}", *at(x, 0.0))
        frame.rigid_link("c", f"s{j}")
        frame.soil(f"s{j}", f"s{j}", 1e4 * B / n, c=50.0 * B / n, bearing=q_ult * B / n)
    return frame.build()


def test_a_3d_footing_on_bearing_springs_in_a_plane_is_the_2d_one():
    st2, st3 = _plane_footing(Frame2D()), _plane_footing(Frame3D())
    assert st3.constraint_names == st2.constraint_names
    dt, t_end, g = 2e-3, 3.0, 10.0
    runs = []
    for st, rot in ((st2, dict(rz=1.0)), (st3, dict(ry=-1.0))):          # ry about +y is -rz of the plane
        t = dt * np.arange(int(round(t_end / dt)) + 1)
        q = np.tile(st.gravity(g, (0.0, -1.0) if st is st2 else (0.0, 0.0, -1.0)), (t.size, 1))
        q += np.outer(40.0 * np.sin(2 * np.pi * t), st.nodal_load("c", **rot))
        sol = ul.solve(st.to_model(), q, dt=dt, t_end=t_end, method="direct", rule="trapezoidal")
        assert sol.success, sol.message
        runs.append(sol)
    a, b = runs
    plastic = [k for k, name in enumerate(st2.constraint_names) if name.endswith(".plastic-")]
    assert a.v[-1, plastic].max() > 1e-3                                    # the soil yields
    np.testing.assert_allclose(b.v, a.v, rtol=0, atol=1e-10 * np.abs(a.v).max())
