"""Contacts whose law double precision must carry: a clearance that never closes, and friction on an
open contact (issue "silent wrong answers").

- A gap's clearance is the paper's imposed strain ``theta = -gap``: an open contact carries
  ``v = e + gap`` and the structure sees ``F (v - gap)``, so the response moves by about
  ``eps gap k / K`` whether or not the gap ever closes. A clearance up to
  :data:`~unilateral.structure.elements.CLEARANCE_MAX_RATIO` times the frame's size gives the
  response without the gap to that round-off; a larger one is refused, naming ``gap``.
- A friction row of the step LCP adds ``mu`` times the contact's row: the round-off of an open
  contact reaches its tangential force ``mu`` times over (and the step LCP fails at mu = 100 on the
  frame below). Up to :data:`~unilateral.structure.elements.FRICTION_MU_MAX` an open gap carries no
  tangential force to round-off and the slip condition holds at every step; above, ``mu`` is refused.
"""

import re

import numpy as np
import pytest

import unilateral as ul
from unilateral.structure import Frame2D, Frame3D
from unilateral.structure.elements import CLEARANCE_MAX_RATIO, FRICTION_MU_MAX

EPS = np.finfo(float).eps
K_GAP, KT = 1e6, 1e5
EI = 3e7 * 2e-3
K_COLUMN = 3 * EI / 3.0 ** 3               # the lateral stiffness of a column, kN/m
SIZE = 3.0                                  # the span of the nodes, m


def columns(gap=None, **friction):
    """Two cantilever columns 1 m apart and 3 m high, masses on top, a gap link between the tops."""
    fr = Frame2D()
    for node, (x, y) in {1: (0.0, 0.0), 2: (0.0, 3.0), 3: (1.0, 0.0), 4: (1.0, 3.0)}.items():
        fr.node(node, x, y)
    fr.support(1, rz=True)
    fr.support(3, rz=True)
    fr.beam("a", 1, 2, E=3e7, A=0.16, I=2e-3)
    fr.beam("b", 3, 4, E=3e7, A=0.16, I=2e-3)
    fr.mass(2, 20.0)
    fr.mass(4, 30.0)
    if gap is not None:
        fr.gap("g", 2, 4, K_GAP, gap=gap, **friction)
    return fr.build()


def pulse(st, P=0.5):
    """Gravity and a half-sine push of the left column (peak drift 1.25e-4 m at P = 0.5 kN)."""
    return ul.LoadHistory(st.gravity(9.81), [(st.nodal_load(2, ux=P), ul.loads.HalfSine(1.0, duration=0.2))])


def run(st, method, P=0.5):
    sol = ul.solve(st.to_model(), pulse(st, P), dt=2e-3, t_end=1.0, method=method)
    assert sol.success, sol.message
    return sol


# ---------------------------------------------------------------------- clearances
@pytest.mark.parametrize("method", ["direct", "modal", "cq"])
def test_a_clearance_that_never_closes_leaves_the_response_of_the_frame_without_it(method):
    reference = run(columns(), method)
    assert np.abs(reference.u).max() < 2e-4
    for gap in [1e-3, 1e-1, 1.0, CLEARANCE_MAX_RATIO * SIZE]:
        sol = run(columns(gap), method)
        assert sol.v[:, 0].min() > 0                                  # never closes
        error = np.abs(sol.u - reference.u).max()
        assert error <= 50 * EPS * max(gap, 1.0) * K_GAP / K_COLUMN, (gap, error)


@pytest.mark.parametrize("gap", [1e6, 1e9, 1e15, -1e6])
def test_a_clearance_the_precision_cannot_carry_is_refused_naming_gap(gap):
    with pytest.raises(ValueError, match=r"gap 'g': gap = .* exceeds 10 times the size of the frame \(3, "):
        columns(gap)


def test_soil_and_3d_clearances_are_refused_beyond_the_bound():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 4.0, 0.0)
    fr.beam("b", 1, 2, E=3e7, A=0.16, I=2e-3)
    fr.soil("s1", 1, 1e4, gap=40.0)
    fr.soil("s2", 2, 1e4, gap=40.1)
    fr.mass(1, 1.0)
    fr.mass(2, 1.0)
    with pytest.raises(ValueError, match=r"soil 's2': gap = 40.1 exceeds 10 times .* give \|gap\| <= 40"):
        fr.build()
    f3 = Frame3D()
    f3.node(1, 0.0, 0.0, 0.0)
    f3.mass(1, 1.0)
    f3.soil("s", 1, 1e4, gap=1e9)
    with pytest.raises(ValueError, match=r"soil 's': gap = 1000000000.0 exceeds .*\(10000, a frame whose nodes"):
        f3.build()                                   # one node at the origin: no size of its own
    f3 = Frame3D()
    f3.node(1, 0.0, 0.0, 0.0)
    f3.mass(1, 1.0)
    f3.support(1, ux=True, uy=True, uz=False, rx=True, ry=True, rz=True)
    f3.soil("s", 1, 1e4, gap=2e4)                    # 20 m in mm: carried
    assert f3.build().m == 1


def test_a_gap_that_closes_carries_k_times_the_overlap():
    gap = 1e-4
    st = columns(gap)
    sol = run(st, "cq", P=5.0)
    e, _ = st.element_deformations(sol.u, sol.v)
    force = -sol.psi[:, 0]
    assert (force > 0).sum() > 10
    np.testing.assert_allclose(force, K_GAP * np.maximum(0.0, -(gap + e[:, 0])), rtol=0, atol=1e-9 * force.max())


# ---------------------------------------------------------------------- friction on an open gap
@pytest.mark.parametrize("method", ["direct", "modal", "cq"])
@pytest.mark.parametrize("mu", [0.1, 1.0, FRICTION_MU_MAX])
def test_an_open_gap_carries_no_tangential_force_and_keeps_the_slip_condition(method, mu):
    gap = 0.5
    st = columns(gap, mu=mu, kt=KT)
    sol = run(st, method)
    assert sol.v[:, 0].min() > 0
    _, eps = st.element_deformations(sol.u, sol.v)
    T = KT * eps[:, 1]
    scale = K_GAP * gap                   # the scale of the contact row: its round-off reaches T mu times
    assert np.abs(T).max() <= 1e-14 * (1 + mu) * scale, np.abs(T).max()
    slip = sol.psi[:, 1:3]                # +-T - mu N <= 0 at every step
    assert slip.max() <= 1e-14 * (1 + mu) * scale, slip.max()


@pytest.mark.parametrize("mu", [10.5, 1e4, 1e30])
def test_friction_coefficients_above_the_bound_are_refused(mu):
    with pytest.raises(ValueError, match=rf"gap .g.: mu = {re.escape(repr(mu))} is above 10: .* Give mu <= 10"):
        columns(0.5, mu=mu, kt=KT)
    f3 = Frame3D()
    f3.node(1, 0.0, 0.0, 0.0)
    with pytest.raises(ValueError, match=r"soil 's': mu = .* is above 10"):
        f3.soil("s", 1, 1e4, mu=mu, kt=1e3)


# ---------------------------------------------------------------------- cq's history of a stiff stick spring
def sliding_block(kt):
    """Newmark's sliding block (mass 1 on a contact of k = 1e8, stick spring kt, mu = 0.2) under a
    base pulse: it slides, then sticks on a stick spring of frequency sqrt(kt)."""
    model = ul.Model.from_natural(
        G=np.eye(2), E=np.diag([kt, 1e8]), B=[[0.0, 1.0, -1.0], [1.0, 0.0, 0.0]], M=np.eye(2),
        C=np.diag([0.0, 2 * 0.05 * 1e4]),
        families=[ul.constraints.Contact([0]), ul.constraints.Friction([1, 2], normal=[0, 0], mu=0.2)])
    load = ul.LoadHistory([0.0, -9.81], [([-1.0, 0.0], ul.loads.Rectangular(4.0, t_end=0.5))])
    return model, load


@pytest.mark.parametrize("rule, kt, warns", [("trapezoidal", 1e10, True), ("bdf2", 1e10, False),
                                             ("trapezoidal", 1e6, False)])
def test_cq_warns_when_its_history_of_a_stiff_stick_spring_loses_the_friction_force(rule, kt, warns):
    """The history sums kt x slip (2.6e9 times the friction force at kt = 1e10): with the
    trapezoidal rule the stick spring's memory does not decay and the round-off estimate
    (``stats['history_round_off']``) exceeds 1e-6 and bounds the measured difference from direct
    (2.4e-7 of the slip against 3.9e-6); else cq stays within 1e-6 of direct (8e-8 with BDF2)."""
    model, load = sliding_block(kt)
    kw = dict(dt=1e-3, t_end=1.3, rule=rule)
    direct = ul.solve(model, load, method="direct", **kw)
    cq = ul.solve(model, load, method="cq", **kw)
    assert direct.success and cq.success
    slip_d, slip_c = direct.v[:, 2] - direct.v[:, 1], cq.v[:, 2] - cq.v[:, 1]
    assert slip_d[-1] > 0.5
    estimate = cq.stats["history_round_off"]
    assert np.abs(slip_c - slip_d).max() <= max(estimate, 1e-6) * slip_d[-1]
    assert (estimate > 1e-6) is warns
    assert ("history of the slips" in cq.message) is warns
    assert "history of the slips" not in direct.message


def test_the_pounding_file_refuses_a_clearance_and_a_friction_it_cannot_carry():
    """The issue's runs: ``examples/pounding.toml`` with ``gap = 1e6`` (the response moved by 5e-9 m,
    1.5 m at 1e15) or with ``mu = 1e4, kt = 1e5`` on the joint (2.7e-5 kN across the open joint)."""
    import tomllib
    from pathlib import Path

    from unilateral.modelfile import build_model_spec
    from unilateral.modelfile.errors import ModelFileError

    source = Path(__file__).resolve().parents[1] / "examples" / "pounding.toml"
    document = tomllib.loads(source.read_text())
    for change, message in [({"gap": 1e6}, r"gap 'joint': gap = 1000000.0 exceeds 10 times .* <= 120.4"),
                            ({"mu": 1e4, "kt": 1e5}, r"gap 'joint': mu = 10000.0 is above 10")]:
        data = {**document, "unilateral": [{**document["unilateral"][0], **change}]}
        with pytest.raises(ModelFileError, match=message):
            build_model_spec(data, source)
    data = {**document, "unilateral": [{**document["unilateral"][0], "gap": 120.0}]}
    assert build_model_spec(data, source).model.m == 1


# ---------------------------------------------------------------------- footing patches and Model(gap=)
CONES = {"model": "cones", "G": 2e4, "nu": 0.3, "rho": 2.0}


def portal_on_footings(gap):
    """A portal 6 m wide on two footings on cones; patch 2 of footing B open by ``gap`` (it never
    touches the soil for gap >= 1 m)."""
    fr = Frame2D()
    for node, x, y in (("a", 0, 0), ("b", 6, 0), ("c", 0, 3), ("d", 6, 3)):
        fr.node(node, x, y)
    for name, i, j in (("c1", "a", "c"), ("c2", "b", "d"), ("bm", "c", "d")):
        fr.beam(name, i, j, E=3e7, A=0.2, I=2e-3)
    fr.mass("c", 20.0)
    fr.mass("d", 20.0)
    fr.foundation("A", "a", width=2.0, length=2.0, soil=CONES, patches=2, mass=2.0, J=0.5)
    fr.foundation("B", "b", width=2.0, length=2.0, soil=CONES, patches=2, mass=2.0, J=0.5, gap=[0.0, gap])
    st = fr.build()
    x, gravity = st.influence("ux"), -9.81 * (st.M @ st.influence("uy"))
    sol = ul.solve(st.to_model(), lambda t: gravity - st.M @ x * (4.0 * np.sin(2 * np.pi * t)), dt=5e-3, t_end=1.0)
    assert sol.success, sol.message
    return sol.u


def test_a_footing_patch_gap_within_the_bound_leaves_the_response_and_beyond_is_refused():
    """Before the bound, a patch open by 1e9 m moved the response by 3.9 % of its peak (76 times at 1e15)."""
    ref, far = portal_on_footings(1.0), portal_on_footings(10 * 6.0)
    assert np.abs(far - ref).max() <= 1e-11 * np.abs(ref).max()
    with pytest.raises(ValueError, match=r"foundation 'B': gap = 1000000000.0 \(patch 2\) exceeds 10 times.*<= 60"):
        portal_on_footings(1e9)


def gap_model(gap):
    """Two DOFs in series, the second on a gap spring k = 1e4 to the ground (the natural form's
    ``F = G E B``, ``H = B^T E B``), under a sine force: the gap never closes for gap >= 1."""
    k = 1e4
    model = ul.Model(np.eye(2), np.array([[2e3, -1e3], [-1e3, 1e3 + k]]), np.array([[0.0], [k]]), np.array([[k]]),
                     gap=[gap])
    sol = ul.solve(model, lambda t: np.array([0.0, 50.0 * np.sin(2 * np.pi * t)]), method="direct", dt=5e-3,
                   t_end=2.0)
    assert sol.success, sol.message
    return sol.u


def test_a_model_gap_within_gap_max_leaves_the_response_and_beyond_is_refused():
    """Without the bound a gap of 1e12 moved the response by 2.8 % of its peak, 1e15 by 35 times."""
    from unilateral.model import GAP_MAX

    ref, far = gap_model(100.0), gap_model(GAP_MAX)
    assert np.abs(far - ref).max() <= 1e-7 * np.abs(ref).max()
    with pytest.raises(ValueError, match=r"gap\[0\] = 1000000000000.0 exceeds 100000 .*give gap <= 100000"):
        gap_model(1e12)
