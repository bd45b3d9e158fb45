"""Results of a solved 3-D frame (``unilateral.structure.forces3d``): reactions, base forces and
moments, storey drifts at the corners.

The identity tested for the base forces: the forces of the ground on the structure (supports,
soil, springs and dashpots to the ground, the soil under footings) balance the inertia of the
masses, the mass-proportional damping and the applied loads at every step,

    base . r = r^T (M (u'' + a0 u') - q)

for every rigid-body motion ``r`` of the structure: the translations along x, y, z give ``Fx``,
``Fy``, ``Fz``, the rotations about the axes through the point give ``Mx``, ``My``, ``Mz``.
"""

import numpy as np
import pytest
from test_frame3d import ECC, building, dense, portal

import unilateral as ul
from unilateral.loads import LoadHistory
from unilateral.structure import Frame3D
from unilateral.structure import forces as F
from unilateral.structure import forces3d as F3

E, A, I, G, J = 3e7, 0.16, 2e-3, 1.2e7, 3e-3
SECTION = dict(E=E, A=A, Iy=I, Iz=1.5e-3, G=G, J=J)
GRAVITY = 9.81


def rigid(st, point, translation=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Free-DOF vector of the rigid motion ``u = t + w x (x - p)``, rotation ``w``."""
    t, w, p = (np.asarray(a, dtype=float) for a in (translation, rotation, point))
    r = np.zeros(st.n)
    names = ("ux", "uy", "uz", "rx", "ry", "rz")
    for k, (node, dof) in enumerate(st.dofs.free):
        u = t + np.cross(w, np.asarray(st.coords[node], dtype=float) - p)
        r[k] = np.concatenate([u, w])[names.index(dof)]
    return r


def unit(k) -> tuple:
    out = [0.0, 0.0, 0.0]
    out[k] = 1.0
    return tuple(out)


def motions(st, point) -> dict:
    """``component -> r`` of the six rigid motions of the base forces."""
    out = {f"F{axis}": rigid(st, point, translation=unit(k)) for k, axis in enumerate("xyz")}
    out |= {f"M{axis}": rigid(st, point, rotation=unit(k)) for k, axis in enumerate("xyz")}
    return out


# ---------------------------------------------------------------------- a plane frame in 3-D
def test_a_plane_frame_in_3d_has_the_base_forces_of_the_2d_frame():
    st2, st3 = portal(2), portal(3)
    a_g = lambda t: 6.0 * np.sin(2 * np.pi * 2.0 * t)          # noqa: E731
    options = dict(dt=2e-3, t_end=0.5, method="direct", rule="trapezoidal")
    loads = [LoadHistory(st.gravity(GRAVITY), [st.ground_motion(a_g, "ux")]) for st in (st2, st3)]
    sols = [ul.solve(st.to_model(), load, **options) for st, load in zip((st2, st3), loads)]
    assert sols[1].v[:, :2].max() > 1e-3                         # a base uplifts
    h2, h3 = (F.Histories.from_solution(st, sol, "trapezoidal", load0=load.sample(sol.t[:1])[0])
              for st, sol, load in zip((st2, st3), sols, loads))
    x0, z0 = 1.5, -0.5
    b2 = F.base_forces(st2, F.reactions(st2, h2), (x0, z0))
    b3 = F3.base_forces(st3, F3.reactions(st3, h3), (x0, 0.0, z0))
    assert set(b3) == set(F3.BASE_COMPONENTS)
    for key3, key2, sign in (("Fx", "base_shear", 1.0), ("Fz", "base_vertical", 1.0),
                             ("My", "overturning_moment", -1.0)):      # ry = -rz of the plane x-y
        scale = np.abs(b2[key2]).max()
        assert scale > 1.0
        np.testing.assert_allclose(b3[key3], sign * b2[key2], rtol=0, atol=1e-9 * scale, err_msg=key3)
    scale = max(np.abs(b3[key]).max() for key in ("Fx", "Fz", "My"))
    for key in ("Fy", "Mx", "Mz"):
        assert np.abs(b3[key]).max() <= 1e-9 * scale, key
    # the out-of-plane supports carry nothing; the in-plane ones carry what the 2-D ones carry
    support3 = F3.reactions(st3, h3)["support"]
    np.testing.assert_allclose(support3["w.uz"], F.reactions(st2, h2)["support"]["w.uy"], rtol=0,
                               atol=1e-9 * scale)
    for label in ("1.uy", "1.rx", "1.rz", "2.uy", "w.uy"):
        assert np.abs(support3[label]).max() <= 1e-9 * scale, label


# ---------------------------------------------------------------------- dynamic equilibrium in 3-D
A0, A1 = 0.4, 2e-3
PLAN = {1: (0.0, 0.0), 2: (5.0, 0.0), 3: (5.0, 4.0), 4: (0.0, 4.0)}
TOP_MASS = {1: 30.0, 2: 20.0, 3: 45.0, 4: 25.0}


def table(base="columns"):
    """Four columns on tensionless soil (Kelvin) under their bases, beams around the top, unequal
    masses with rotary inertias, a horizontal spring and a dashpot to the ground at the top.

    ``base="columns"``: each column base held in plan and against rotation, free to lift;
    ``"mat"``: the column bases rigidly linked to a mat's node below the plan's centre, held in
    ``ux``, ``uy``, ``rz`` and ``rx`` (the mat lifts and rocks about y on the soil under the bases,
    whose forces reach the mat's supports through the links)."""
    fr = Frame3D()
    if base == "mat":
        fr.node("mat", 2.5, 2.0, -0.5)
        fr.support("mat", ux=True, uy=True, uz=False, rx=True, ry=False, rz=True)
    for node, (x, y) in PLAN.items():
        fr.node(f"b{node}", x, y, 0.0)
        fr.node(f"t{node}", x, y, 3.0)
        if base == "mat":
            fr.rigid_link("mat", f"b{node}")
        else:
            fr.support(f"b{node}", ux=True, uy=True, uz=False, rx=True, ry=True, rz=True)
        fr.soil(f"soil{node}", f"b{node}", 2e4, c=300.0, direction=(0.0, 0.3, 1.0) if base == "mat" else "uz")
        fr.beam(f"c{node}", f"b{node}", f"t{node}", **SECTION)
        fr.mass(f"t{node}", TOP_MASS[node], Jx=2.0, Jy=3.0, Jz=4.0)
    for i, j in ((1, 2), (2, 3), (3, 4), (4, 1)):
        fr.beam(f"g{i}{j}", f"t{i}", f"t{j}", **SECTION, rho=2.5)
    fr.spring("hold", "t3", 5e2, direction=(1.0, 1.0, 0.0))
    fr.dashpot("damper", "t1", 40.0, direction="uy")
    fr.rayleigh(a0=A0, a1=A1)
    return fr.build()


@pytest.mark.parametrize("base", ["columns", "mat"])
def test_the_ground_balances_gravity_inertia_and_damping_in_3d_at_every_step(base):
    st = table(base)
    a_x = lambda t: 9.0 * np.sin(2 * np.pi * 2.5 * t)                 # noqa: E731
    a_y = lambda t: 7.0 * np.sin(2 * np.pi * 3.5 * t) * (t > 0)       # noqa: E731
    ground = [("ux", a_x), ("uy", a_y)]
    gravity = st.gravity(GRAVITY)
    load = LoadHistory(gravity, [st.ground_motion(a, d) for d, a in ground])
    sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=0.8, method="direct", rule="trapezoidal")
    assert sol.success and sol.v[:, :4].max() > 1e-4 and sol.stats["contact_changes"] > 0   # uplift
    q = load.sample(sol.t)
    h = F3.histories(st, sol, "trapezoidal", load0=q[0])
    reaction = F3.reactions(st, h)
    assert set(reaction["ground_elements"]) == {"soil1", "soil2", "soil3", "soil4", "hold", "damper"}
    assert reaction["footings"] == {}
    point = (2.0, 1.0, 0.0)
    base = F3.base_forces(st, reaction, point)
    absolute = F3.absolute_acceleration(st, h, ground)
    inertia = st.M @ (absolute + A0 * h.udot).T                         # (n, N+1)
    errors = {}
    for key, r in motions(st, point).items():
        expected = r @ inertia - gravity @ r
        scale = np.abs(expected).max()
        assert scale > 1.0, key
        np.testing.assert_allclose(r @ st.M @ (h.uddot + A0 * h.udot).T - q @ r, expected, rtol=0,
                                   atol=1e-12 * scale)                  # the same identity in q
        errors[key] = np.abs(base[key] - expected).max() / scale
    assert max(errors.values()) < 1e-8, errors


# ---------------------------------------------------------------------- torsion on a rigid diaphragm
@pytest.mark.parametrize("mass_at", ["master", "slave"])
def test_the_base_torque_of_an_eccentric_floor_is_the_torque_of_its_inertia(mass_at):
    st = building(mass_at, tops_fixed=False)
    a_y = lambda t: 5.0 * np.sin(2 * np.pi * 2.0 * t)                 # noqa: E731
    load = LoadHistory(np.zeros(st.n), [st.ground_motion(a_y, "uy")])
    sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=0.5, method="direct", rule="trapezoidal")
    h = F3.histories(st, sol, "trapezoidal")
    reaction = F3.reactions(st, h)
    # the tops' ux, uy, rz follow the master: the columns' forces reach the supports through the ties
    nodal = st.dofs.nodal(F3.absolute_acceleration(st, h, [("uy", a_y)]))          # (N+1, nodes, 6)
    xyz = np.array([st.coords[node] for node in st.dofs.nodes], dtype=float)
    m = st.nodal_mass
    for point in ((0.0, 0.0, 0.0), (1.3, -2.1, 0.7)):
        base = F3.base_forces(st, reaction, point)
        dx, dy = (xyz[:, :2] - np.asarray(point[:2])).T
        # inertia forces m a, their torque about the vertical through the point, the rotary inertia
        torque = (m[:, 0] * (dx * nodal[:, :, 1] - dy * nodal[:, :, 0]) + m[:, 5] * nodal[:, :, 5]).sum(axis=1)
        scale = np.abs(torque).max()
        assert scale > 10.0                                       # nonzero: the eccentric mass twists
        np.testing.assert_allclose(base["Mz"], torque, rtol=0, atol=1e-8 * scale)
        force_y = (m[:, 1] * nodal[:, :, 1]).sum(axis=1)
        np.testing.assert_allclose(base["Fy"], force_y, rtol=0, atol=1e-8 * np.abs(force_y).max())
    # about the floor's mass centre the torque is the rotary inertia's alone: Jz times the twist
    base = F3.base_forces(st, reaction, (ECC, 0.0, 0.0))
    twist = st.dofs.nodal(h.uddot)[:, st.dofs.nodes.index("m"), 5]
    np.testing.assert_allclose(base["Mz"], m[:, 5].sum() * twist, rtol=0, atol=1e-8 * np.abs(base["Mz"]).max())


# ---------------------------------------------------------------------- footings on a half-space
HALF = {"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0}
FOOT_MASS = 8.0


def on_footings():
    """The table's four columns each on a square footing on one half-space, symmetric in plan
    about (2.5, 2), equal top masses."""
    fr = Frame3D()
    for node, (x, y) in PLAN.items():
        fr.node(f"b{node}", x, y, 0.0)
        fr.node(f"t{node}", x, y, 3.0)
        fr.foundation(f"f{node}", f"b{node}", width=1.6, length=1.6, patches=(2, 2), soil=HALF, mass=FOOT_MASS,
                      Jx=1.0, Jy=1.0)
        fr.beam(f"c{node}", f"b{node}", f"t{node}", E=E, A=1.0, Iy=0.05, Iz=0.05, G=G, J=0.08)
        fr.mass(f"t{node}", 30.0)
    for i, j in ((1, 2), (2, 3), (3, 4), (4, 1)):
        fr.beam(f"g{i}{j}", f"t{i}", f"t{j}", E=E, A=1.0, Iy=0.05, Iz=0.05, G=G, J=0.08)
    return fr.build()


def test_footings_carry_the_weight_and_no_moment_about_their_centre_in_the_static_state():
    st = on_footings()
    gravity = st.gravity(GRAVITY)
    push = st.nodal_load("t3", ux=60.0, uy=-40.0)
    load = LoadHistory(gravity, [(push, lambda t: np.sin(np.pi * t / 0.05) * (t < 0.05))])
    sol = ul.solve(st.to_model(), load, dt=2e-3, t_end=0.06, method="cq")
    assert sol.success
    q = load.sample(sol.t)
    h = F3.histories(st, sol, "bdf2", load0=q[0])
    reaction = F3.reactions(st, h, sol)
    assert len(reaction["footings"]) == 16 and reaction["at"]["f3.4"] == "b3"
    centre = (2.5, 2.0, 0.0)
    assert F3.base_point(st) == centre
    base = F3.base_forces(st, reaction, centre)
    weight = GRAVITY * (4 * 30.0 + 4 * FOOT_MASS)
    assert base["Fz"][0] == pytest.approx(weight, rel=1e-9)
    assert np.abs(-sol.psi[0]).sum() == pytest.approx(weight, rel=1e-9)     # the soil carries it all
    for key in ("Mx", "My", "Mz", "Fx", "Fy"):
        assert abs(base[key][0]) <= 1e-9 * weight, key
    # and at every step of the push: the ground balances the loads and the inertia
    for key, r in motions(st, centre).items():
        expected = r @ st.M @ h.uddot.T - q @ r
        scale = max(np.abs(expected).max(), weight)
        np.testing.assert_allclose(base[key], expected, rtol=0, atol=1e-8 * scale, err_msg=key)
    assert np.abs(base["My"]).max() > 1.0 and np.abs(base["Mx"]).max() > 1.0
    with pytest.raises(ValueError, match="give sol"):
        F3.reactions(st, h)


# ---------------------------------------------------------------------- drifts at the corners
def two_floors():
    """Floor 1 at z = 3.5 on four columns at (+-3, +-2); floor 2 at z = 7 on four columns leaning in
    to (+-2.5, +-1.75): its corners have no node of floor 1 below them. Rigid diaphragms with their
    masters at (ECC, 0)."""
    fr = Frame3D()
    low = {"a": (3.0, 2.0), "b": (-3.0, 2.0), "c": (-3.0, -2.0), "d": (3.0, -2.0)}
    for name, (x, y) in low.items():
        fr.node(f"{name}0", x, y, 0.0)
        fr.node(f"{name}1", x, y, 3.5)
        fr.node(f"{name}2", 5 * x / 6, 7 * y / 8, 7.0)
        fr.support(f"{name}0", rx=True, ry=True, rz=True)
        fr.beam(f"col1_{name}", f"{name}0", f"{name}1", **SECTION)
        fr.beam(f"col2_{name}", f"{name}1", f"{name}2", **SECTION)
    for floor, z in ((1, 3.5), (2, 7.0)):
        fr.node(f"m{floor}", ECC, 0.0, z)
        fr.support(f"m{floor}", ux=False, uy=False, uz=True, rx=True, ry=True)
        fr.rigid_diaphragm(f"m{floor}", [f"{name}{floor}" for name in low])
    return fr.build()


def test_corner_drifts_of_a_twisting_floor_differ_from_the_centre_by_the_twist_times_the_arm():
    st = two_floors()
    f = st.nodal_load("m1", ux=30.0, uy=-20.0, rz=80.0) + st.nodal_load("m2", ux=10.0, uy=25.0, rz=-150.0)
    u = np.linalg.solve(dense(st.to_model().K), f)
    h = F.Histories(t=np.zeros(1), u=u[None], udot=np.zeros((1, st.n)), uddot=np.zeros((1, st.n)),
                    v=np.zeros((1, st.m)), vdot=np.zeros((1, st.m)))
    drifts = F3.storey_drifts(st, h)
    assert list(drifts) == ["0-3.5", "3.5-7"]
    nodal = st.dofs.nodal(u)
    at = {node: p for p, node in enumerate(st.dofs.nodes)}
    master = {floor: nodal[at[f"m{floor}"]] for floor in (0, 1, 2) if f"m{floor}" in at}
    master[0] = np.zeros(6)
    twists = []
    for floor, label in ((1, "0-3.5"), (2, "3.5-7")):
        d = drifts[label]
        assert d["nodes"] == tuple(f"{name}{floor}" for name in "cdab")      # the bounding box's corners
        assert d["height"] == 3.5
        centre = master[floor] - master[floor - 1]              # the drift at the masters' (ECC, 0)
        twist = centre[5]
        twists.append(twist)
        arm = np.array([st.coords[node][:2] for node in d["nodes"]]) - (ECC, 0.0)
        scale = np.abs(centre[:2]).max()
        np.testing.assert_allclose(d["x"][0], centre[0] - twist * arm[:, 1], rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(d["y"][0], centre[1] + twist * arm[:, 0], rtol=0, atol=1e-12 * scale)
        np.testing.assert_allclose(d["ratio_x"], d["x"] / 3.5, rtol=1e-15)
        assert d["max_ratio_y"][0] == pytest.approx(np.abs(d["y"][0]).max() / 3.5, rel=1e-15)
        assert np.ptp(d["x"][0]) > 0.1 * scale                 # the corners differ: the floor twists
    assert abs(twists[1]) > 1e-3 * abs(twists[0]) and abs(twists[0]) > 0
    # corners=False: the drift of the floors' mean displacements
    mean = F3.storey_drifts(st, h, corners=False)["3.5-7"]
    floor1 = [at[n] for n in ("a1", "b1", "c1", "d1", "m1")]
    floor2 = [at[n] for n in ("a2", "b2", "c2", "d2", "m2")]
    expected = nodal[floor2, :2].mean(axis=0) - nodal[floor1, :2].mean(axis=0)
    np.testing.assert_allclose([mean["x"][0, 0], mean["y"][0, 0]], expected, rtol=1e-12)
    assert mean["nodes"] == ()


def test_the_extreme_nodes_are_the_corners_of_a_plan_without_box_corners():
    """A triangular floor: no node at two corners of its bounding box; the extreme nodes in x and y."""
    fr = Frame3D()
    plan = {"p": (0.0, 0.0), "q": (4.0, 1.0), "r": (1.0, 3.0)}
    for name, (x, y) in plan.items():
        fr.node(f"{name}0", x, y, 0.0)
        fr.node(name, x, y, 3.0)
        fr.support(f"{name}0", rx=True, ry=True, rz=True)
        fr.beam(f"col_{name}", f"{name}0", name, **SECTION)
    fr.node("m", 1.5, 1.0, 3.0)
    fr.support("m", ux=False, uy=False, uz=True, rx=True, ry=True)
    fr.rigid_diaphragm("m", list(plan))
    st = fr.build()
    u = np.linalg.solve(dense(st.to_model().K), st.nodal_load("m", ux=5.0, rz=20.0))
    h = F.Histories(t=np.zeros(1), u=u[None], udot=np.zeros((1, st.n)), uddot=np.zeros((1, st.n)),
                    v=np.zeros((1, st.m)), vdot=np.zeros((1, st.m)))
    d = F3.storey_drifts(st, h)["0-3"]
    assert d["nodes"] == ("p", "q", "r")                        # min x and min y, max x, max y
    nodal = st.dofs.nodal(u)
    idx = [st.dofs.nodes.index(n) for n in d["nodes"]]
    np.testing.assert_allclose(d["x"][0], nodal[idx, 0], rtol=1e-14)     # the ground does not move
    np.testing.assert_allclose(d["y"][0], nodal[idx, 1], rtol=1e-14)
