"""Axial yield of bars and braces (``Frame2D.bar(..., Fy=...)``, ``Frame3D.bar``) and multi-linear
backbones of yielding links (``yield_link(backbone=...)``).

A diagonal brace pushed along x yields at its axial force ``Fy`` (the load factor ``Fy c``, ``c``
the chord's x component) and hardens at ``k h / (1 + h)`` along the chord; a cyclic push unloads
with ``EA/L`` and reloads at the kinematic hardening's shifted surface (closed form); a 3-D truss in
a plane equals the 2-D one; a link's backbone passes through its points and equals, under a ground
motion, the same springs given as parallel elastic-perfectly-plastic links (the Iwan construction)
to round-off; bad input is refused naming the argument."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.pushover import pushover
from unilateral.structure import Frame2D, Frame3D

E, A, FY, LX, LY = 2e8, 1e-3, 100.0, 3.0, 4.0
L, C = np.hypot(LX, LY), LX / np.hypot(LX, LY)
KAX = E * A / L


def brace(hardening=0.0, **yield_forces):
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", LX, LY)
    fr.support("a", ux=True, uy=True, rz=True)
    fr.support("b", ux=False, uy=True, rz=True)
    fr.bar("br", "a", "b", E=E, A=A, hardening=hardening, **(yield_forces or {"Fy": FY}))
    fr.mass("b", 1.0)
    return fr.build()


def test_a_brace_yields_at_its_axial_force_and_hardens_along_its_chord():
    h = 0.05
    st = brace(hardening=h)
    r = pushover(st, st.nodal_load("b", ux=1.0), node="b", dof="ux", target=0.02)
    assert r.success, r.message
    assert [(e.name, e.kind) for e in r.events] == [("br.plastic+", "yield")]
    at = r.events[0].point
    assert abs(r.load_factor[at] - FY * C) <= 1e-9 * FY                  # N = Fy: the push is Fy c
    assert abs(r.displacement[at] - FY / KAX / C) <= 1e-9 * FY / KAX / C
    slope = np.diff(r.load_factor[at:]) / np.diff(r.displacement[at:])
    np.testing.assert_allclose(slope, KAX * h / (1 + h) * C * C, rtol=1e-9)  # hardening along the chord
    N = r.load_factor[-1] / C
    plastic = r.v[-1] @ np.array([1.0, -1.0])
    assert abs(N - (FY + h * KAX * plastic)) <= 1e-9 * FY                # the surface moved by Hk v


def test_a_cyclic_push_unloads_elastically_and_yields_in_compression_at_Fy_c():
    st = brace(Fy_t=FY, Fy_c=0.5 * FY)                                   # a weak strut
    r = pushover(st, st.nodal_load("b", ux=1.0), node="b", dof="ux", target=[0.01, -0.01])
    assert r.success, r.message
    names = [e.name for e in r.events if e.kind == "yield"]
    assert names[:2] == ["br.plastic+", "br.plastic-"]
    N = r.load_factor / C
    assert N.max() <= FY * (1 + 1e-9) and N.min() >= -0.5 * FY * (1 + 1e-9)
    assert abs(N.max() - FY) <= 1e-9 * FY and abs(N.min() + 0.5 * FY) <= 1e-9 * FY
    # unloading from the tension plateau is elastic with EA/L along the chord until N = -Fy_c
    top = int(np.argmax(r.displacement))
    u_back = r.displacement[top] - (FY + 0.5 * FY) / (KAX * C)
    onset = [e.point for e in r.events if e.kind == "yield"][1]
    assert abs(r.displacement[onset] - u_back) <= 1e-9 * abs(u_back)


def test_a_3d_truss_in_a_plane_is_the_2d_one():
    fr = Frame3D()
    fr.node("a", 0.0, 0.0, 0.0)
    fr.node("b", LX, 0.0, LY)
    fr.support("a", ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.support("b", ux=False, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.bar("br", "a", "b", E=E, A=A, Fy=FY, hardening=0.05)
    fr.mass("b", 1.0)
    st3, st2 = fr.build(), brace(hardening=0.05)
    r3 = pushover(st3, st3.nodal_load("b", ux=1.0), node="b", dof="ux", target=0.02)
    r2 = pushover(st2, st2.nodal_load("b", ux=1.0), node="b", dof="ux", target=0.02)
    assert r3.success and r2.success
    np.testing.assert_allclose(r3.load_factor, r2.load_factor, rtol=0, atol=1e-10 * FY)
    np.testing.assert_allclose(r3.displacement, r2.displacement, rtol=0, atol=1e-12)


BACKBONE = [(0.002, 100.0), (0.006, 140.0), (0.02, 160.0)]


def link_frame(parallel: bool):
    """A mass on a link to the ground along x: one link with ``BACKBONE``, or the same as three
    elastic-perfectly-plastic links in parallel (stiffnesses ``S_s - S_{s+1}``, yield at the points)."""
    fr = Frame2D()
    fr.node("m", 0.0, 0.0)
    fr.support("m", ux=False, uy=True, rz=True)
    fr.mass("m", 2.0)
    if not parallel:
        fr.yield_link("L", "m", backbone=BACKBONE, direction="ux")
        return fr.build()
    points = np.array(BACKBONE)
    slopes = np.diff(np.vstack([[0.0, 0.0], points]), axis=0)
    slopes = slopes[:, 1] / slopes[:, 0]
    for s, (d, k) in enumerate(zip(points[:, 0], -np.diff(np.append(slopes, 0.0)))):
        fr.yield_link(f"L{s}", "m", k=k, Fy=k * d, direction="ux")
    return fr.build()


def test_a_link_backbone_passes_through_its_points():
    st = link_frame(parallel=False)
    r = pushover(st, st.nodal_load("m", ux=1.0), node="m", dof="ux", target=0.05)
    assert r.success, r.message
    assert [e.name for e in r.events] == ["L.plastic+", "L.plastic2+", "L.plastic3+"]
    for event, (d, F) in zip(r.events, BACKBONE):
        assert abs(r.load_factor[event.point] - F) <= 1e-9 * F
        assert abs(r.displacement[event.point] - d) <= 1e-9 * d


def test_a_link_backbone_equals_parallel_elastic_plastic_links_under_a_ground_motion():
    one, many = link_frame(False), link_frame(True)
    runs = []
    for st in (one, many):
        load = ul.LoadHistory(np.zeros(st.n), [(-(st.M @ st.influence("ux")),
                                                lambda t: 120.0 * np.sin(2 * np.pi * 1.5 * t) * (t < 3.0))])
        sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=4.0, method="direct", rule="trapezoidal")
        assert sol.success, sol.message
        runs.append((sol, load, st))
    (a, load_a, _), (b, _, _) = runs
    assert np.abs(a.u).max() > 3 * BACKBONE[-1][0]                       # beyond the last point, both ways
    np.testing.assert_allclose(a.u, b.u, rtol=0, atol=1e-10 * np.abs(b.u).max())
    ds = ul.results_dataset(a, one, load=load_a)
    assert float(np.abs(ds["energy_relative_error"]).max()) <= 1e-9
    assert float(ds["energy_plastic_work"][-1]) > 0.05 * float(np.abs(ds["energy_input_work"]).max())


@pytest.mark.parametrize("kwargs, words", [
    (dict(backbone=BACKBONE, k=5e4), "k cannot go with a backbone"),
    (dict(backbone=[(0.002, 100.0), (0.001, 140.0)]), "backbone"),
    (dict(backbone=[(0.002, 100.0), (0.004, 300.0)]), "decrease"),
    (dict(Fy=10.0), "k is missing"),
])
def test_bad_link_backbones_are_refused(kwargs, words):
    fr = Frame2D()
    fr.node("m", 0.0, 0.0)
    with pytest.raises(ValueError, match=words):
        fr.yield_link("L", "m", direction="ux", **kwargs)


@pytest.mark.parametrize("kwargs, words", [
    (dict(Fy=-1.0), "Fy"), (dict(Fy=10.0, Fy_t=5.0), "not both"), (dict(Fy_t=5.0), "Fy_c is missing"),
    (dict(hardening=0.1), "needs a yield force"),
])
def test_bad_bar_yield_forces_are_refused(kwargs, words):
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", 1.0, 0.0)
    with pytest.raises(ValueError, match=words):
        fr.bar("br", "a", "b", E=E, A=A, **kwargs)


MODEL_FILE = """
[units]
length = "m"
force = "kN"
time = "s"

[[nodes]]
id = "a"
x = 0.0
y = 0.0
[[nodes]]
id = "b"
x = 3.0
y = 4.0
[[nodes]]
id = "m"
x = 10.0
y = 0.0

[[supports]]
node = "a"
ux = true
uy = true
rz = true
[[supports]]
node = "b"
ux = false
uy = true
rz = true
[[supports]]
node = "m"
ux = false
uy = true
rz = true

[[elements]]
type = "bar"
name = "br"
node_i = "a"
node_j = "b"
E = 2e8
A = 1e-3
Fy_t = 100.0
Fy_c = 50.0
hardening = 0.05

[[unilateral]]
type = "yield"
name = "L"
node = "m"
direction = "ux"
backbone = [[0.002, 100.0], [0.006, 140.0], [0.02, 160.0]]

[[masses]]
node = "b"
m = 1.0
[[masses]]
node = "m"
m = 2.0

[analysis]
dt = 0.01
t_end = 0.1
"""


def test_a_model_file_takes_axial_yield_and_link_backbones(tmp_path):
    from unilateral.modelfile import load_model_file

    path = tmp_path / "m.toml"
    path.write_text(MODEL_FILE)
    spec = load_model_file(path)
    fr = Frame2D()
    for node, x, y in (("a", 0.0, 0.0), ("b", LX, LY), ("m", 10.0, 0.0)):
        fr.node(node, x, y)
    fr.support("a", ux=True, uy=True, rz=True)
    fr.support("b", ux=False, uy=True, rz=True)
    fr.support("m", ux=False, uy=True, rz=True)
    fr.bar("br", "a", "b", E=E, A=A, Fy_t=FY, Fy_c=0.5 * FY, hardening=0.05)
    fr.yield_link("L", "m", backbone=BACKBONE, direction="ux")
    fr.mass("b", 1.0)
    fr.mass("m", 2.0)
    model = fr.build().to_model()
    assert spec.model.constraint_names == model.constraint_names
    for key in ("K", "M"):
        np.testing.assert_array_equal(getattr(spec.model, key).toarray(), getattr(model, key).toarray())
    np.testing.assert_array_equal(spec.model.H, model.H)
    np.testing.assert_array_equal(np.asarray(spec.model.F), np.asarray(model.F))
    np.testing.assert_array_equal(spec.model.g(0.0), model.g(0.0))               # the yield forces
    bad = MODEL_FILE.replace('backbone = [[0.002, 100.0], [0.006, 140.0], [0.02, 160.0]]',
                             'k = 5e4\nbackbone = [[0.002, 100.0]]')
    path.write_text(bad)
    with pytest.raises(ValueError, match=r"unilateral\[0\]\.k .*cannot go with a backbone"):
        load_model_file(path)
