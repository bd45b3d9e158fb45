"""Elements with several constraint unknowns: yield links, plastic hinges, friction on contacts, sliders.

Defining properties, each checked at every step of a run: a yield link carries at most its yield
force and flows plastically at it (with kinematic hardening on the post-yield slope
``k h/(1+h)``); a hinge yields when the end moment reaches ``My`` (a cantilever: ``P L = My``); an
elastic-plastic hinge adds the flexibility ``1/k`` in series; a soil element with friction sticks
until ``|T| = mu N`` and carries no tangential force once lifted off; a slider is a yield link with
``Fy = mu N``; cq, modal and direct agree; the structure's results (reactions, base forces,
energy) stay consistent; a model file builds the same model as :class:`Frame2D`.
"""

import re

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.constraints import Contact, Friction, Yield
from unilateral.modelfile import ModelFileError, build_model_spec
from unilateral.structure import Frame2D
from unilateral.structure import forces as F
from yield_portal import PORTAL_TOML, frame

RAMP = ul.loads.Ramp


def ramp_load(st, t_ramp, constant=None, **components):
    """``constant + (t / t_ramp) * nodal load`` (``components``: ``node=..., ux=..., ...``)."""
    base = np.zeros(st.n) if constant is None else constant
    return ul.LoadHistory(base, [(st.nodal_load(**components), RAMP(t_ramp, 1.0))])


def forces(st, sol):
    """Forces of the strains of the constraint unknowns (Kelvin-free elements)."""
    return st.element_forces(sol.t, sol.u, sol.v)


def yielding(v, column):
    """Steps (bool, N+1) at which the multiplier ``column`` grew."""
    return np.diff(v[:, column], prepend=v[0, column]) > 1e-12


# ---------------------------------------------------------------------- yield link
def spring_on_mass(*, k=100.0, m=1.0, **kw):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=False, uy=True)
    fr.mass(1, m)
    fr.yield_link("y", 1, k=k, direction="ux", **kw)
    fr.rayleigh(a0=5.0)
    return fr.build()


def test_yield_link_reaches_Fy_then_deforms_plastically_by_u_minus_Fy_over_k():
    k, Fy = 100.0, 5.0
    st = spring_on_mass(k=k, Fy=Fy)
    assert st.constraint_names == ("y.plastic+", "y.plastic-")
    sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=1, ux=10.0), dt=0.01, t_end=10.0, method="cq")
    force, u, p = forces(st, sol)[:, 0], sol.u[:, 0], sol.v[:, 0] - sol.v[:, 1]
    assert force.max() == pytest.approx(Fy, rel=1e-10)                    # exactly Fy, never more
    elastic = sol.v[:, 0] == 0.0
    np.testing.assert_allclose(force[elastic], k * u[elastic], rtol=1e-12)
    flows = yielding(sol.v, 0)
    assert flows.sum() > 100 and not yielding(sol.v, 1).any()
    np.testing.assert_allclose(force[flows], Fy, rtol=1e-10)
    np.testing.assert_allclose(p[flows], u[flows] - Fy / k, rtol=0, atol=1e-12 * np.abs(u).max())
    assert (force[:np.argmax(flows)] < Fy).all()                         # elastic until it first yields


@pytest.mark.parametrize("h", [0.1, 1.0])
def test_kinematic_hardening_gives_the_post_yield_slope_k_h_over_1_plus_h(h):
    k, Fy = 100.0, 5.0
    st = spring_on_mass(k=k, Fy=Fy, hardening=h)
    sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=1, ux=10.0), dt=0.01, t_end=10.0, method="modal")
    force, u, p = forces(st, sol)[:, 0], sol.u[:, 0], sol.v[:, 0] - sol.v[:, 1]
    flows = yielding(sol.v, 0)
    assert flows.sum() > 100
    np.testing.assert_allclose(force[flows] - h * k * p[flows], Fy, rtol=1e-10)   # the shifted surface
    both = flows[1:] & flows[:-1]
    slope = np.diff(force)[both] / np.diff(u)[both]
    np.testing.assert_allclose(slope, k * h / (1 + h), rtol=1e-8)


def test_a_brace_with_Fy_c_greater_than_Fy_t_yields_asymmetrically():
    Fy_t, Fy_c = 4.0, 7.0
    st = spring_on_mass(Fy_t=Fy_t, Fy_c=Fy_c)
    load = ul.LoadHistory(np.zeros(st.n), [(st.nodal_load(1, ux=12.0), ul.loads.HalfSine(1.0, duration=2.0)),
                                           (st.nodal_load(1, ux=-15.0), ul.loads.HalfSine(1.0, t_start=3.0,
                                                                                         duration=2.0))])
    sol = ul.solve(st.to_model(), load, dt=0.01, t_end=6.0, method="direct")
    force = forces(st, sol)[:, 0]
    assert force.max() == pytest.approx(Fy_t, rel=1e-10)
    assert force.min() == pytest.approx(-Fy_c, rel=1e-10)
    np.testing.assert_allclose(force[yielding(sol.v, 0)], Fy_t, rtol=1e-10)
    np.testing.assert_allclose(force[yielding(sol.v, 1)], -Fy_c, rtol=1e-10)
    assert yielding(sol.v, 0).any() and yielding(sol.v, 1).any()


def test_yield_link_between_two_nodes_is_the_link_to_the_ground_when_one_node_is_fixed():
    def run(two_nodes):
        fr = Frame2D()
        fr.node(1, 0.0, 0.0)
        fr.node(2, 0.0, 0.0)
        fr.support(1, ux=True, uy=True)
        fr.support(2, ux=False, uy=True)
        fr.mass(2, 1.0)
        if two_nodes:
            fr.yield_link("y", 1, 2, k=100.0, Fy=5.0, hardening=0.2)
        else:
            fr.yield_link("y", 2, k=100.0, Fy=5.0, hardening=0.2)
        st = fr.build()
        return ul.solve(st.to_model(), ramp_load(st, 2.0, node=2, ux=8.0), dt=0.01, t_end=3.0, method="cq")
    a, b = run(True), run(False)
    np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-13)
    np.testing.assert_allclose(a.v, b.v, rtol=0, atol=1e-13)


# ---------------------------------------------------------------------- hinges
E_COL, A_COL, I_COL, L_COL, MY = 1.0e4, 1.0, 1.0, 2.0, 10.0


def cantilever(*, k=None, hardening=0.0, downwards=False):
    """A column fixed at node 1 (base), tip node 2 at height L, a hinge at the base."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, L_COL)
    fr.support(1, ux=True, uy=True, rz=True)
    if downwards:                                        # the beam from the tip to the base: end j
        fr.beam("col", 2, 1, E_COL, A_COL, I_COL)
        fr.hinge("H", "col", "j", My=MY, k=k, hardening=hardening)
    else:
        fr.beam("col", 1, 2, E_COL, A_COL, I_COL)
        fr.hinge("H", "col", "i", My=MY, k=k, hardening=hardening)
    fr.mass(2, 1e-3)
    fr.rayleigh(a0=50.0)
    return fr.build()


def test_rigid_plastic_hinge_yields_when_P_L_reaches_My_and_then_rotates_at_My():
    st = cantilever()
    P = 1.5 * MY / L_COL
    sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=2, ux=P), dt=0.01, t_end=10.0, method="cq")
    M = forces(st, sol)[:, 0]                           # the end moment on the beam at the base
    first = np.argmax(sol.v[:, 0] > 0)
    P_t = P * sol.t / 10.0
    assert P_t[first - 1] * L_COL < MY <= P_t[first] * L_COL + 1e-12
    np.testing.assert_allclose(M[: first], P_t[: first] * L_COL, atol=1e-3 * MY)   # statics, inertia aside
    np.testing.assert_allclose(M[first:], MY, rtol=1e-10)
    rotation = sol.v[:, 0] - sol.v[:, 1]
    assert np.all(np.diff(rotation[first:]) > 0)        # the hinge keeps rotating under P > My / L
    tip = st.node_displacement(sol, 2, "ux")
    elastic_tip = MY * L_COL ** 2 / (3 * E_COL * I_COL)
    np.testing.assert_allclose(tip[first:], elastic_tip + rotation[first:] * L_COL, rtol=1e-6)


def test_hinge_hardening_is_relative_to_4EI_over_L_without_k():
    h = 0.5
    st = cantilever(hardening=h)
    P = 1.5 * MY / L_COL
    sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=2, ux=P), dt=0.01, t_end=12.0, method="modal")
    rotation = sol.v[-1, 0] - sol.v[-1, 1]
    assert rotation == pytest.approx((P * L_COL - MY) / (h * 4 * E_COL * I_COL / L_COL), rel=1e-3)


def test_hinge_at_end_j_of_a_beam_drawn_the_other_way_gives_the_same_response():
    P = 1.5 * MY / L_COL
    runs = []
    for downwards in (False, True):
        st = cantilever(k=800.0, hardening=0.1, downwards=downwards)
        sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=2, ux=P), dt=0.01, t_end=10.0, method="cq")
        runs.append((st.node_displacement(sol, 2, "ux"), sol.v))
    np.testing.assert_allclose(runs[1][0], runs[0][0], rtol=0, atol=1e-12 * np.abs(runs[0][0]).max())
    np.testing.assert_allclose(runs[1][1], runs[0][1], rtol=0, atol=1e-12 * np.abs(runs[0][1]).max())
    assert runs[0][1][-1, 0] > 0


@pytest.mark.parametrize("k", [None, 300.0, 5000.0])
def test_elastic_tip_stiffness_is_the_beam_in_series_with_the_hinge_spring(k):
    st = cantilever(k=k)
    model = st.to_model()
    f = st.nodal_load(2, ux=1.0)
    u = np.linalg.solve(model.K.toarray(), f)
    flexibility = L_COL ** 3 / (3 * E_COL * I_COL) + (0.0 if k is None else L_COL ** 2 / k)
    assert u[st.dofs.index(2, "ux")] == pytest.approx(flexibility, rel=1e-12)


def test_elastic_plastic_hinge_yields_at_My():
    st = cantilever(k=500.0)
    P = 1.5 * MY / L_COL
    sol = ul.solve(st.to_model(), ramp_load(st, 10.0, node=2, ux=P), dt=0.01, t_end=10.0, method="direct")
    M = forces(st, sol)[:, 0]
    first = np.argmax(sol.v[:, 0] > 0)
    assert M.max() == pytest.approx(MY, rel=1e-10)
    assert P * sol.t[first - 1] / 10.0 * L_COL < MY
    np.testing.assert_allclose(M[first:], MY, rtol=1e-10)


# ---------------------------------------------------------------------- friction on contacts
MASS, G, MU = 1.0, 10.0, 0.5


def block_on_soil(**kw):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.mass(1, MASS)
    fr.soil("s", 1, 1e4, mu=MU, kt=1e3, **kw)
    fr.rayleigh(a0=20.0)
    return fr.build()


def test_soil_with_friction_slides_once_H_exceeds_mu_N_and_not_before():
    st = block_on_soil()
    assert st.constraint_names == ("s", "s.slip+", "s.slip-")
    assert st.strain_names == ("s", "s.tangential")
    model = st.to_model()
    assert model.law.kinds == ("contact", "friction", "friction")
    H = 2 * MU * MASS * G
    sol = ul.solve(model, ramp_load(st, 20.0, st.gravity(G), node=1, ux=H), dt=0.01, t_end=20.0, method="cq")
    N, T = -forces(st, sol)[:, 0], forces(st, sol)[:, 1]
    slip = sol.v[:, 1] - sol.v[:, 2]
    H_t = H * sol.t / 20.0
    np.testing.assert_allclose(N, MASS * G, rtol=1e-9)
    assert np.all(slip[H_t <= MU * MASS * G] == 0.0)                 # sticks
    assert np.all(np.abs(T) <= MU * N * (1 + 1e-12))
    slides = yielding(sol.v, 1)
    assert H_t[np.argmax(slides)] == pytest.approx(MU * MASS * G, rel=1e-2)   # T lags H by the damping
    np.testing.assert_allclose(T[slides], MU * N[slides], rtol=1e-10)
    assert slip[-1] > 0 and not yielding(sol.v, 2).any()


def test_soil_lifted_off_carries_no_tangential_force():
    st = block_on_soil(c=50.0)
    load = ul.LoadHistory(st.gravity(G), [(st.nodal_load(1, ux=0.3 * MU * MASS * G), RAMP(0.5, 1.0)),
                                          (st.nodal_load(1, uy=3 * MASS * G), ul.loads.Rectangular(1.0, t_start=1.0,
                                                                                                   t_end=1.2))])
    sol = ul.solve(st.to_model(), load, dt=1e-3, t_end=2.0, method="modal")
    vdot = F.rates(sol.v, ul.rules.get_rule("bdf2"), 1e-3)[0]
    T = st.element_forces(sol.t, sol.u, sol.v, sol.udot, vdot)[:, 1]
    lifted = sol.v[:, 0] > 0
    assert lifted.sum() > 50
    assert np.abs(T[lifted]).max() <= 1e-9 * MU * MASS * G
    assert np.abs(T[~lifted]).max() > 0.1 * MU * MASS * G


def test_gap_with_friction_transmits_shear_only_when_closed():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 1.0)
    fr.support(1)
    fr.mass(2, MASS)
    fr.spring("hold", 2, 50.0, direction="uy")
    fr.gap("g", 1, 2, 1e4, mu=MU, kt=1e3)                   # direction from 1 to 2: uy; tangent ux
    fr.rayleigh(a0=20.0)
    st = fr.build()
    load = ul.LoadHistory(np.zeros(st.n), [(st.nodal_load(2, uy=-MASS * G), ul.loads.Rectangular(1.0, t_end=2.0)),
                                           (st.nodal_load(2, ux=0.2 * MASS * G), RAMP(1.0, 1.0))])
    sol = ul.solve(st.to_model(), load, dt=1e-3, t_end=4.0, method="cq")
    T = forces(st, sol)[:, 1]
    N = -forces(st, sol)[:, 0]
    closed = sol.v[:, 0] == 0
    assert closed.any() and (~closed).any()
    assert np.abs(T[~closed]).max() <= 1e-9 * MASS * G
    assert np.all(np.abs(T) <= MU * np.maximum(N, 0.0) + 1e-9 * MASS * G)
    assert T[1900] == pytest.approx(0.2 * MASS * G, rel=2e-2)                 # sticks under the compression


def test_slider_equals_a_yield_link_with_Fy_mu_N_and_reports_friction():
    def run(kind):
        fr = Frame2D()
        fr.node(1, 0.0, 0.0)
        fr.support(1, ux=False, uy=True)
        fr.mass(1, MASS)
        if kind == "slider":
            fr.slider("b", 1, mu=0.1, N=40.0, k=500.0)
        else:
            fr.yield_link("b", 1, k=500.0, Fy=0.1 * 40.0)
        st = fr.build()
        load = ul.LoadHistory(np.zeros(st.n), [(st.nodal_load(1, ux=10.0), ul.loads.HalfSine(1.0, duration=1.0))])
        model = st.to_model()
        return st, model, ul.solve(model, load, dt=1e-3, t_end=2.0, method="cq")
    (st_s, slider, a), (_, link, b) = run("slider"), run("yield")
    assert st_s.constraint_names == ("b.slip+", "b.slip-")
    assert slider.law.kinds == ("friction", "friction") and link.law.kinds == ("yield", "yield")
    assert isinstance(slider.families[0], Friction) and slider.families[0].normal.tolist() == [-1, -1]
    assert yielding(a.v, 0).any()
    np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-14)
    np.testing.assert_allclose(a.v, b.v, rtol=0, atol=1e-14)


# ---------------------------------------------------------------------- a frame with everything
def frame_load(st):
    return ul.LoadHistory(st.gravity(10.0), [(st.nodal_load(2, ux=160.0), ul.loads.HalfSine(1.0, duration=0.5)),
                                             (st.nodal_load(3, ux=-120.0), ul.loads.HalfSine(1.0, t_start=0.6,
                                                                                            duration=0.4))])


@pytest.fixture(scope="module")
def framed():
    st = frame()
    return st, st.to_model(), frame_load(st)


def test_frame_families_and_names(framed):
    st, model, _ = framed
    names = st.constraint_names                        # element order: c1 (h1), c2 (h3), g (h2), s1, b4, br
    assert names == ("h1.plastic+", "h1.plastic-", "h3.plastic+", "h3.plastic-", "h2.plastic+", "h2.plastic-",
                     "s1", "s1.slip+", "s1.slip-", "b4.slip+", "b4.slip-", "br.plastic+", "br.plastic-")
    kinds = dict(zip(names, model.law.kinds))
    assert kinds["s1"] == "contact" and kinds["s1.slip-"] == kinds["b4.slip+"] == "friction"
    assert kinds["h2.plastic+"] == kinds["br.plastic-"] == "yield"
    friction = next(f for f in model.families if isinstance(f, Friction))
    normal = dict(zip([names[i] for i in friction.indices], friction.normal))
    assert names[normal["s1.slip+"]] == "s1" and normal["b4.slip-"] == -1
    assert {type(f) for f in model.families} == {Contact, Yield, Friction}
    strains = dict(zip(names, st.constraint_strains))
    assert st.strain_names[strains["h1.plastic-"]] == "c1.rot_j"
    assert st.strain_names[strains["s1.slip+"]] == "s1.tangential"


def test_cq_modal_and_direct_agree_on_a_frame_with_hinges_and_friction(framed):
    st, model, load = framed
    kw = dict(dt=2e-3, t_end=1.2, rule="bdf2")
    ref = ul.solve(model, load, method="direct", **kw)
    assert ref.success, ref.message
    inc = np.diff(ref.v, axis=0)
    names = st.constraint_names
    for name in ("h1.plastic+", "s1.slip+", "b4.slip+", "br.plastic+"):
        assert (inc[:, names.index(name)] > 0).any() or (inc[:, names.index(name) + 1] > 0).any(), name
    for method in ("cq", "modal"):
        sol = ul.solve(model, load, method=method, **kw)
        assert sol.success, sol.message
        assert np.abs(sol.u - ref.u).max() <= 1e-9 * np.abs(ref.u).max(), method
        assert np.abs(sol.v - ref.v).max() <= 1e-9 * np.abs(ref.v).max(), method


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_frame_results_balance_with_hinges_friction_and_yield_links(rule):
    """Reactions through the frictional soil, the slider and the ground balance inertia and loads;
    the base-force operator (Rayleigh a1 on hinged beams) equals them; the energy balances."""
    st = frame(rayleigh=(0.5, 1e-3))
    dt, N = 1e-3, 1200
    Q = frame_load(st).sample(dt * np.arange(N + 1))          # samples: the rates of the rule start as h's
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=N * dt, method="cq", rule=rule)
    h = F.Histories.from_solution(st, sol, rule, load0=Q[0])
    reaction = F.reactions(st, h)
    assert set(reaction["ground_elements"]) == {"s1", "b4"}
    base = F.base_forces(st, reaction, (1.0, -1.0))
    inertia = st.M @ (h.uddot + 0.5 * h.udot).T
    expected = st.influence("ux") @ inertia - Q @ st.influence("ux")
    drift = 1e-7 if rule == "bdf2" else 1e-6            # the trapezoidal rates' recursion drifts by round-off
    np.testing.assert_allclose(base["base_shear"], expected, atol=drift * np.abs(expected).max())
    fast = F.BaseForceOperator.of(st, (1.0, -1.0))(F.StateRows.of(h.u, h.udot, h.v, h.vdot))
    for key, value in base.items():
        np.testing.assert_allclose(fast[key], value, rtol=0, atol=1e-11 * np.abs(value).max(), err_msg=key)
    energy = energy_balance(st, h, Q)
    assert energy["plastic_work"][-1] > 0.01 * energy["input_work"].max() and energy["friction_work"][-1] > 0
    assert energy["max_relative_error"] < (1e-4 if rule == "bdf2" else 1e-9)      # trapezoidal: exact


def test_end_forces_of_a_soil_with_friction_are_N_and_minus_T():
    st = block_on_soil()
    sol = ul.solve(st.to_model(), ramp_load(st, 2.0, st.gravity(G), node=1, ux=0.3 * MU * MASS * G),
                   dt=0.01, t_end=2.0, method="cq")
    h = F.Histories.from_solution(st, sol, "bdf2")
    ends = F.end_forces(st, h)["s"]
    sigma = forces(st, sol)
    np.testing.assert_allclose(ends[:, 3], sigma[:, 0])
    np.testing.assert_allclose(ends[:, 4], -sigma[:, 1])              # t = x is minus the local y (d = y)
    f = F.reactions(st, h)["ground_elements"]["s"]
    np.testing.assert_allclose(f[:, :2], -sigma[:, [1, 0]])           # the ground pulls back along x, y


# ---------------------------------------------------------------------- model files



def document(**changes):
    """``PORTAL_TOML`` (0.1 s at dt 1e-3) as a dict, with entries of ``unilateral`` changed (index -> dict;
    None deletes a key)."""
    import tomllib

    data = tomllib.loads(PORTAL_TOML + "[analysis]\ndt = 1e-3\nt_end = 0.1\n")
    for index, change in changes.items():
        entry = data["unilateral"][int(index.lstrip("u"))]
        for key, value in change.items():
            if value is None:
                entry.pop(key, None)
            else:
                entry[key] = value
    return data


def dense(a):
    return a.toarray() if hasattr(a, "toarray") else np.asarray(a)


def test_model_file_builds_the_frame_of_the_builder(tmp_path):
    spec = build_model_spec(document(), tmp_path / "model.toml")
    st, model = frame(), spec.model
    reference = st.to_model()
    assert model.constraint_names == reference.constraint_names and model.dof_names == reference.dof_names
    for key in ("K", "M", "C", "F", "H", "F_v", "H_v"):
        np.testing.assert_array_equal(dense(getattr(model, key)), dense(getattr(reference, key)), err_msg=key)
    np.testing.assert_array_equal(model.g(0.0), reference.g(0.0))
    np.testing.assert_array_equal(model.law.rate, reference.law.rate)
    np.testing.assert_array_equal(model.law.P, reference.law.P)
    assert model.law.kinds == reference.law.kinds


@pytest.mark.parametrize("changes, message", [
    (dict(u3=dict(kt=None)), "unilateral[3].kt: missing key (friction, mu = 0.4, needs the stick stiffness kt"),
    (dict(u3=dict(mu=None)), "unilateral[3].kt = 50000.0: a friction parameter: give the friction coefficient mu"),
    (dict(u3=dict(mu=-0.1)), "unilateral[3].mu = -0.1: must be >= 0"),
    (dict(u3=dict(kt=0.0)), "unilateral[3].kt = 0.0: must be > 0"),
    (dict(u5=dict(Fy=10.0)), "unilateral[5].Fy_t = 30.0: give either Fy (both ways) or Fy_t and Fy_c, not both"),
    (dict(u5=dict(Fy_t=None)), "unilateral[5].Fy_t: missing key (Fy_t and Fy_c go together; or give Fy for both)"),
    (dict(u5=dict(Fy_t=None, Fy_c=None)), "unilateral[5].Fy: missing key (give the yield force Fy [F]"),
    (dict(u5=dict(Fy_c=-45.0)), "unilateral[5].Fy_c = -45.0: must be > 0"),
    (dict(u5=dict(hardening=-0.5)), "unilateral[5].hardening = -0.5: must be >= 0"),
    (dict(u5=dict(k=0.0)), "unilateral[5].k = 0.0: must be > 0"),
    (dict(u0=dict(beam="c3")), 'unilateral[0].beam = "c3": no beam "c3" in [[elements]] (beams are "c1", "c2", '
                               '"g")'),
    (dict(u0=dict(end="k")), 'unilateral[0].end = "k": '),
    (dict(u0=dict(My=0.0)), "unilateral[0].My = 0.0: must be > 0"),
    (dict(u2=dict(beam="c1", end="j")), 'unilateral[2].end = "j": beam "c1" already has a hinge at this end '
                                        "(unilateral[0].end); one per end"),
    (dict(u4=dict(mu=-0.3)), "unilateral[4].mu = -0.3: must be >= 0"),
    (dict(u4=dict(direction="rz")), "unilateral[4]: slider 'b4': direction='rz' is not a sliding direction"),
])
def test_model_file_errors_name_the_key(tmp_path, changes, message):
    with pytest.raises(ModelFileError, match=re.escape(message)):
        build_model_spec(document(**changes), tmp_path / "model.toml")


# ---------------------------------------------------------------------- Frame2D errors
def small_frame():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 3.0)
    fr.support(1, rz=True)
    fr.beam("col", 1, 2, 1.0, 1.0, 1.0)
    return fr


@pytest.mark.parametrize("call, message", [
    (lambda fr: fr.yield_link("y", 2, k=1.0, Fy=0.0), "yield_link 'y': Fy=0.0 must be > 0"),
    (lambda fr: fr.yield_link("y", 2, k=-1.0, Fy=1.0), "yield_link 'y': k=-1.0 must be > 0"),
    (lambda fr: fr.yield_link("y", 2, k=1.0, Fy_t=1.0), "yield_link 'y': Fy_c is missing; give the yield force Fy"),
    (lambda fr: fr.yield_link("y", 2, k=1.0), "yield_link 'y': Fy is missing"),
    (lambda fr: fr.yield_link("y", 2, k=1.0, Fy=1.0, Fy_c=2.0), "yield_link 'y': give either Fy (both ways) or Fy_t"),
    (lambda fr: fr.yield_link("y", 2, k=1.0, Fy_t=1.0, Fy_c=-2.0), "yield_link 'y': Fy_c=-2.0 must be > 0"),
    (lambda fr: fr.yield_link("y", 2, k=1.0, Fy=1.0, hardening=-1.0), "yield_link 'y': hardening=-1.0 must be >= 0"),
    (lambda fr: fr.hinge("h", "beam9", "i", My=1.0), "hinge 'h': beam='beam9' is not a beam of the frame "
                                                     "(beams: 'col')"),
    (lambda fr: fr.hinge("h", "col", "k", My=1.0), "hinge 'h': end='k' is not valid; use 'i' or 'j'"),
    (lambda fr: fr.hinge("h", "col", "i", My=-1.0), "hinge 'h': My=-1.0 must be > 0"),
    (lambda fr: fr.hinge("h", "col", "i", My=1.0, k=0.0), "hinge 'h': k=0.0 must be > 0"),
    (lambda fr: (fr.hinge("h", "col", "j", My=1.0), fr.hinge("h2", "col", "j", My=2.0)),
     "hinge 'h2': end 'j' of beam 'col' already has the hinge 'h'; one hinge per beam end"),
    (lambda fr: fr.soil("s", 2, 1.0, mu=0.3), "soil 's': friction (mu=0.3) needs the stick stiffness kt"),
    (lambda fr: fr.soil("s", 2, 1.0, mu=-0.3, kt=1.0), "soil 's': mu=-0.3 must be >= 0"),
    (lambda fr: fr.soil("s", 2, 1.0, mu=0.3, kt=0.0), "soil 's': kt=0.0 must be > 0"),
    (lambda fr: fr.soil("s", 2, 1.0, kt=1.0), "soil 's': kt is a friction parameter; give the friction coefficient mu"),
    (lambda fr: fr.soil("s", 2, 1.0, direction="rz", mu=0.3, kt=1.0), "soil 's': friction (mu) needs a translational"),
    (lambda fr: fr.gap("g", 1, 2, 1.0, mu=0.3), "gap 'g': friction (mu=0.3) needs the stick stiffness kt"),
    (lambda fr: fr.slider("b", 2, mu=-0.1, N=1.0, k=1.0), "slider 'b': mu=-0.1 must be >= 0"),
    (lambda fr: fr.slider("b", 2, mu=0.1, N=0.0, k=1.0), "slider 'b': N=0.0 must be > 0"),
    (lambda fr: fr.slider("b", 2, mu=0.1, N=1.0, k=0.0), "slider 'b': k=0.0 must be > 0"),
])
def test_frame_errors_name_the_element_and_the_argument(call, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        call(small_frame())
