"""Static pushover by path-following (unilateral.pushover): closed forms, an independent event-to-event
analysis, equilibrium and the LCP conditions at every event, and the errors of bad input."""

import numpy as np
import pytest
import yield_portal
from pushover_frames import (HINGES, I_COL, MP_BEAM, MP_COL, A, E, H, L, cantilever, independent_events, portal,
                             rocking_block, sdof)

import unilateral as ul
from unilateral.pushover import PushoverResult, pushover
from unilateral.structure import Frame2D


def check_path(r: PushoverResult, *, tol=1e-10):
    """(d) K u = lambda p + q_g + F v and the LCP conditions at every point of the path."""
    assert r.stats["max_residual"] < tol, r.stats
    assert r.stats["max_lcp_error"] < tol, r.stats


def check_equilibrium(st, r, tol=1e-10):
    """Equilibrium recomputed from the model itself at every point (not from the stats)."""
    model = st.to_model()
    for lam, u, v in zip(r.load_factor, r.u, r.v):
        Ku = model.K @ u
        rhs = lam * r.pattern + r.gravity + model.q_imposed(0.0) + model.F @ v
        assert np.linalg.norm(Ku - rhs) <= tol * max(np.linalg.norm(Ku), np.linalg.norm(rhs))
        psi = model.law.rows(model.F.T @ u - model.H @ v - model.g(0.0))
        scale = max(np.abs(psi).max(), np.abs(model.g(0.0)).max())
        assert psi.max() <= tol * scale and v.min() >= -tol * max(1.0, v.max())


# ---------------------------------------------------------------------- (a) the portal frame
def test_portal_plateau_is_the_sway_mechanism_and_hinges_form_where_elastic_analysis_says():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1)
    assert r.success, r.message
    collapse = (2 * MP_COL + 2 * MP_BEAM) / H                   # P h = 2 Mp_base + 2 Mp_beam-end
    assert r.load_factor[-1] == pytest.approx(collapse, rel=1e-9)
    assert np.max(r.load_factor) == pytest.approx(collapse, rel=1e-9)
    expected = independent_events()
    assert [e.kind for e in r.events] == ["yield"] * len(HINGES)
    assert [e.name.split(".")[0] for e in r.events] == [name for name, _, _ in expected]
    for event, (_, P, d) in zip(r.events, expected):
        assert event.load_factor == pytest.approx(P, rel=1e-9)
        assert event.displacement == pytest.approx(d, rel=1e-9)
    assert r.base_shear == pytest.approx(r.load_factor, rel=1e-15)       # a unit force along ux
    check_path(r)
    check_equilibrium(st, r)


def test_portal_curve_is_exact_whatever_the_number_of_output_points():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.05)
    (P1, d1), (Pc, dc) = [(e.load_factor, e.displacement) for e in r.events[::3]]
    for count in (2, 7, 200):
        s = r.sample(count)
        assert s.displacement[-1] == pytest.approx(0.05, rel=1e-12)
        elastic = s.displacement <= d1
        assert s.load_factor[elastic] == pytest.approx(s.displacement[elastic] * P1 / d1, rel=1e-9)
        assert s.load_factor[s.displacement >= dc] == pytest.approx(Pc, rel=1e-9)
        check_equilibrium(st, s)
    coarse, fine = r.sample(5), r.sample(9)
    assert coarse.u == pytest.approx(fine.u[::2], rel=1e-12, abs=1e-15)


def test_portal_under_load_control_stops_at_the_mechanism():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=500.0, control="load")
    collapse = (2 * MP_COL + 2 * MP_BEAM) / H
    assert not r.success and r.stats["mechanism"]
    assert r.message.startswith("mechanism at load factor 120")
    assert r.load_factor[-1] == pytest.approx(collapse, rel=1e-9)
    assert len(r.events) == 4 and r.events[-1].load_factor == pytest.approx(collapse, rel=1e-9)
    check_path(r)
    below = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=119.0, control="load")
    assert below.success and below.load_factor[-1] == 119.0 and len(below.events) == 2


def test_portal_with_p_delta_softens_after_the_mechanism():
    st = portal(p_delta=True)
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81)
    assert r.success and len(r.events) == 4
    slope = np.diff(r.load_factor)[-1] / np.diff(r.displacement)[-1]
    # the consistent geometric stiffness of the columns, v = (0, 0, d, d/h) in the mechanism: about
    # N/h 34/30; exactly (closed form: tests/test_pushover_cyclic.py) with the joints' rotational terms
    # and the beam's shortening
    N = sum(st.axial_forces[c] for c in ("c1", "c2"))
    assert slope == pytest.approx(N / H * 34 / 30, rel=1e-4)
    beta = N / 2 * H * H / (90 * E * I_COL)
    s = N / 2 * (33 + (1 + 3 * beta) / (1 + 4 * beta)) / (30 * H)
    assert slope == pytest.approx(s + E * A / L * s / (E * A / L + s), rel=1e-9)
    assert r.load_factor[-1] < r.load_factor[-2]
    check_path(r)
    check_equilibrium(st, r)


# ---------------------------------------------------------------------- (b) one degree of freedom
@pytest.mark.parametrize("hardening", [0.0, 0.1])
def test_sdof_bilinear_curve(hardening):
    k, Fy = 100.0, 5.0
    st = sdof(k=k, Fy=Fy, hardening=hardening)
    r = pushover(st, st.nodal_load(1, ux=1.0), node=1, dof="ux", target=0.3)
    assert r.success and [(e.name, e.kind) for e in r.events] == [("y.plastic+", "yield")]
    assert r.events[0].load_factor == pytest.approx(Fy, rel=1e-12)
    assert r.events[0].displacement == pytest.approx(Fy / k, rel=1e-12)
    s = r.sample(31)
    d = s.displacement
    closed = np.where(d <= Fy / k, k * d, Fy + k * hardening / (1 + hardening) * (d - Fy / k))
    assert s.load_factor == pytest.approx(closed, rel=1e-12, abs=1e-12)
    check_path(r)


def test_sdof_pushed_the_other_way_and_under_load_control():
    st = sdof(hardening=0.1)
    r = pushover(st, st.nodal_load(1, ux=-1.0), node=1, dof="ux", target=-0.3)
    assert r.events[0].name == "y.plastic-" and r.load_factor[-1] == pytest.approx(5 + 100 / 11 * 0.25)
    r = pushover(st, st.nodal_load(1, ux=1.0), node=1, dof="ux", target=7.0, control="load")
    assert r.success and r.displacement[-1] == pytest.approx(0.05 + 2.0 / (100 / 11), rel=1e-12)
    epp = sdof()
    r = pushover(epp, epp.nodal_load(1, ux=1.0), node=1, dof="ux", target=7.0, control="load")
    assert not r.success and "mechanism at load factor 5" in r.message


def test_cantilever_with_an_elastic_plastic_spring_hinge():
    k, My, h, hh = 2e4, 50.0, 3.0, 0.05
    st = cantilever(k=k, My=My, hardening=hh, h=h)
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1)
    EI = 30e6 * 6.75e-4
    k1 = 1 / (h ** 3 / (3 * EI) + h ** 2 / k)
    k2 = 1 / (h ** 3 / (3 * EI) + h ** 2 / (k * hh / (1 + hh)))
    assert r.events[0].load_factor == pytest.approx(My / h, rel=1e-12)
    assert r.events[0].displacement == pytest.approx(My / h / k1, rel=1e-12)
    assert r.load_factor[-1] == pytest.approx(My / h + k2 * (0.1 - My / h / k1), rel=1e-10)


def test_a_bare_model_and_a_frame_builder():
    k, Fy = 100.0, 5.0
    st = sdof(k=k, Fy=Fy)
    model = st.to_model()
    r = pushover(model, [1.0], node=0, target=0.1)
    assert r.load_factor[-1] == pytest.approx(Fy) and r.control_dof == "1.ux"
    r2 = pushover(model, [1.0], node=1, dof="ux", target=0.1)
    assert r2.load_factor == pytest.approx(r.load_factor)
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=False, uy=True, rz=True)
    fr.yield_link("y", 1, k=k, Fy=Fy, direction="ux")
    fr.mass(1, 2.0)
    r3 = pushover(fr, "uniform", node=1, target=0.1)
    assert r3.load_factor[-1] == pytest.approx(Fy / 2.0) and r3.base_shear[-1] == pytest.approx(Fy)


# ---------------------------------------------------------------------- (c) uplift of a rigid block
def test_rigid_block_lifts_off_at_the_closed_form_load():
    b, height, mass, g = 1.0, 2.0, 50.0, 9.81
    st = rocking_block(b=b, height=height, mass=mass)
    r = pushover(st, st.nodal_load("t", ux=1.0), node="t", dof="ux", target=0.05, gravity=g)
    assert r.success
    assert [(e.name, e.kind) for e in r.events] == [("sl", "uplift")]
    assert r.events[0].load_factor == pytest.approx(mass * g * b / height, rel=1e-12)   # P h = W b
    assert r.load_factor[-1] == pytest.approx(mass * g * b / height, rel=1e-12)          # rocking: a plateau
    assert r.v[-1, 0] > 0 and r.psi[-1, 1] == pytest.approx(-mass * g, rel=1e-12)
    check_path(r)
    check_equilibrium(st, r)
    load = pushover(st, st.nodal_load("t", ux=1.0), node="t", dof="ux", target=1e3, gravity=g, control="load")
    assert "mechanism at load factor 245.25" in load.message


# ---------------------------------------------------------------------- (d) everything at once
@pytest.mark.parametrize("pattern", ["uniform", "triangular", "mode"])
def test_portal_with_friction_yield_and_contact_is_in_equilibrium_at_every_event(pattern):
    st = yield_portal.frame()
    r = pushover(st, pattern, node=2, dof="ux", target=0.05, gravity=9.81)
    assert r.success, r.message
    assert {e.kind for e in r.events} >= {"yield", "slip"}
    r_x = st.influence("ux")
    assert r_x @ r.pattern == pytest.approx(r_x @ (st.M @ r_x), rel=1e-12)      # lambda: shear per mass
    check_path(r)
    check_equilibrium(st, r)


# ---------------------------------------------------------------------- (e) bad input
@pytest.mark.parametrize("kwargs, words", [
    (dict(target=-0.1), ["target=-0.1", "wrong sign", "2.ux"]),
    (dict(target=0.0), ["target=0.0", "wrong sign"]),
    (dict(target=0.0, control="load"), ["target=0.0", "load factor", "> 0"]),
    (dict(target=float("nan")), ["target=nan", "finite"]),
    (dict(pattern="parabolic"), ["pattern='parabolic'", "'uniform'", "'triangular'", "'mode'"]),
    (dict(pattern=np.ones(3)), ["pattern", "shape (6,)"]),
    (dict(node=7), ["node=7", "not a node", "1, 2, 3, 4"]),
    (dict(dof="uz"), ["dof='uz'", "'ux', 'uy', 'rz'"]),
    (dict(node=1), ["node=1", "cannot move"]),
    (dict(control="force"), ["control='force'", "'displacement'", "'load'"]),
    (dict(max_events=0), ["max_events=0", "positive integer"]),
    (dict(gravity=np.ones(2)), ["gravity", "shape (6,)"]),
])
def test_bad_input_is_refused_naming_the_argument(kwargs, words):
    st = portal()
    args = dict(pattern=st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1) | kwargs
    with pytest.raises(ValueError) as info:
        pushover(st, args.pop("pattern"), **args)
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_bad_structure_and_model_only_arguments():
    with pytest.raises(TypeError, match="structure_or_model must be"):
        pushover("frame", "uniform", node=1, target=0.1)
    model = sdof().to_model()
    with pytest.raises(ValueError, match="triangular.*heights"):
        pushover(model, "triangular", node=0, target=0.1)
    with pytest.raises(ValueError, match="gravity=9.81: a bare Model"):
        pushover(model, [1.0], node=0, target=0.1, gravity=9.81)
    with pytest.raises(ValueError, match="node='9.ux'|node=9"):
        pushover(model, [1.0], node=9, target=0.1)
    with pytest.raises(ValueError, match="needs masses"):
        pushover(portal(mass=0.0), "uniform", node=2, target=0.1)


def test_max_events_stops_the_path_with_a_message():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, max_events=2)
    assert not r.success and "max_events=2" in r.message and len(r.load_factor) == 3


def test_a_model_built_by_hand_with_a_contact():
    # a mass on a tensionless spring k pressed by a weight w, pulled up: lifts off at lambda = w
    k, w = 1000.0, 20.0
    model = ul.Model(M=[[1.0]], K=[[k]], F=[[k]], H=[[k]])
    r = pushover(model, [1.0], node=0, target=0.1, gravity=[-w])
    assert [(e.kind, e.load_factor) for e in r.events] == [("uplift", pytest.approx(w, rel=1e-12))]
    assert r.load_factor[-1] == pytest.approx(w, rel=1e-12) and r.v[-1, 0] == pytest.approx(0.1 - (-w / k) - w / k)
