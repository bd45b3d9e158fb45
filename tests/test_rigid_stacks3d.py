"""Rigid boxes on a 3-D frame's floor and on other boxes (stacks): ``Frame3D.contact(..., on=)``,
``Frame3D.rigid_box(..., on=)`` (:mod:`unilateral.structure.stacks`, ``docs/rocking.md``).

What is checked: a 3-D stack rocking in the x-z plane is the 2-D stack to round-off; a two-box stack
released from a tilt about the diagonal is Housner's monolith box of twice the height until the
first impact (second order in dt); at rest the ground corners carry both weights and the interface
the upper one (the monolith's second-order terms about x and y); a box on the floor of a stiff 3-D
frame tends to the box on the shaken ground as the frame stiffens; Newton for the frame with a box
on its floor (its base forces); the energy balance of a stack shaken in both plan directions; bad
input."""

import math

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import energy_balance
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, Frame3D, rigid, rigid3d

G = 9.80665


def _stack3d(widths=((0.4, 0.4), (0.4, 0.4)), heights=(1.2, 1.2), masses=(1.0, 1.0), **kw):
    fr = Frame3D()
    fr.node("c1", 0.0, 0.0, heights[0] / 2)
    fr.node("c2", 0.0, 0.0, heights[0] + heights[1] / 2)
    lower = fr.rigid_box("L", "c1", width_x=widths[0][0], width_y=widths[0][1], height=heights[0], mass=masses[0],
                         **kw)
    upper = fr.rigid_box("U", "c2", width_x=widths[1][0], width_y=widths[1][1], height=heights[1], mass=masses[1],
                         on="L", **kw)
    return fr.build(), lower, upper


def _u0(st, **values):
    """``u0`` (n,) with ``values`` ``{"L_uz": ...}`` on the bases' free DOFs."""
    u0 = np.zeros(st.n)
    for key, value in values.items():
        box, dof = key.split("_")
        u0[st.dofs.index(f"{box}.base", dof)] = value
    return u0


def _run(st, load, *, dt, t_end, initial):
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=t_end, method="moreau-jean", rule="trapezoidal",
                   initial=initial)
    assert sol.success, sol.message
    return sol


def test_a_3d_stack_rocking_in_the_x_z_plane_is_the_2d_stack():
    """A 0.4 x 0.4 x 1.2 m box on a 1.2 x 1.2 x 1.0 m box shaken along x above the upper's uplift
    (the 2-D stack of tests/test_rigid_stacks.py): the bases' uz, ry of the 3-D stack are the 2-D
    stack's uy, -rz to round-off through its impacts (measured 2.7e-14 m and 1.4e-13 rad apart over
    1.5 s, the upper's peak tilt 0.159 rad), rx stays at the static start's round-off (1.4e-14) and
    the two located impacts are at the same times (to 1.5e-13 s)."""
    st3, _, upper = _stack3d(widths=((1.2, 1.2), (0.4, 0.4)), heights=(1.0, 1.2))
    fr = Frame2D()
    fr.node("c1", 0.0, 0.5)
    fr.node("c2", 0.0, 1.6)
    fr.rigid_block("L", "c1", width=1.2, height=1.0, mass=1.0)
    fr.rigid_block("U", "c2", width=0.4, height=1.2, mass=1.0, on="L")
    st2 = fr.build()
    a_g = _sine(1.5 * upper.uplift_acceleration[0])
    sol2 = _run(st2, LoadHistory(st2.gravity(G), [rigid.ground_motion(st2, a_g)]), dt=1e-3, t_end=1.5,
                initial="static")
    sol3, _ = _shaken(st3, a_g, "ux")
    assert len(sol2.stats["impacts"]) >= 2 and np.abs(sol2.dof("U.base.rz")).max() > 0.1
    for box in ("L", "U"):
        assert np.abs(sol3.dof(f"{box}.base.uz") - sol2.dof(f"{box}.base.uy")).max() <= 1e-13
        assert np.abs(sol3.dof(f"{box}.base.ry") + sol2.dof(f"{box}.base.rz")).max() <= 1e-12
        assert np.abs(sol3.dof(f"{box}.base.rx")).max() <= 1e-13          # the static start's round-off
    t2 = [ev["time"] for ev in sol2.stats["impacts"]]
    t3 = [ev["time"] for ev in sol3.stats["impacts"]]
    np.testing.assert_allclose(t3, t2, rtol=0, atol=1e-12)


def test_a_two_box_stack_tilted_about_the_diagonal_is_the_monolith_until_the_first_impact():
    """Two equal square boxes 0.4 x 0.4 x 1.2 m tilted on the lower's ne corner about the axis
    perpendicular to the diagonal: Housner's block of half-width d = sqrt(bx^2 + by^2) and height
    2.4 m (the monolith box's :meth:`~unilateral.structure.rigid3d.RigidBox.diagonal`), the tilt to
    0.1 dt^2 before the first impact (measured 2.0e-7, 5.1e-8, 1.3e-8 rad at dt = 2e-3, 1e-3,
    5e-4), its time second order in dt (-5.8e-7, -1.4e-7, -3.6e-8 s off t1 = 0.29710 s, fitted
    order 2.00), the upper box turning with the lower and the interface in compression (at least
    9.42 of W = 9.81 kN); the landing strikes L.sw and three of the interface's corners."""
    st, lower, upper = _stack3d()
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, 1.2)
    tall = fr.rigid_box("T", "c", width_x=0.4, width_y=0.4, height=2.4, mass=2.0).diagonal()
    theta0, d = 0.05, tall.b
    axis = np.array([-lower.by, lower.bx]) / d
    rx, ry = theta0 * axis
    u0 = _u0(st, L_uz=theta0 * d, L_rx=rx, L_ry=ry, U_uz=theta0 * d, U_rx=rx, U_ry=ry)
    t1 = tall.first_impact_time(theta0)
    names = list(st.to_model().constraint_names)
    interface = [names.index(f"U.{c}") for c in ("sw", "se", "ne", "nw")]
    dts, errors = (2e-3, 1e-3, 5e-4), []
    for dt in dts:
        sol = _run(st, LoadHistory(st.gravity(G)), dt=dt, t_end=0.45, initial={"u0": u0})
        first = sol.stats["impacts"][0]
        assert "L.sw" in first["contacts"]                                       # the landing on L's sw
        errors.append(first["time"] - t1)
        k = np.searchsorted(sol.t, first["time"])
        tilt = sol.dof("L.base.rx")[:k] * axis[0] + sol.dof("L.base.ry")[:k] * axis[1]
        assert np.abs(tilt - tall.tilt(sol.t[:k], theta0)).max() <= 0.1 * dt ** 2
        for dof in ("rx", "ry", "uz"):
            assert np.abs(sol.dof(f"U.base.{dof}")[:k] - sol.dof(f"L.base.{dof}")[:k]).max() <= 1e-15
        assert sol.v[1:k, interface].sum(axis=1).min() > 0.9 * upper.W
        assert np.abs(sol.v[1:k, names.index("L.sw")]).max() == 0.0             # it pivots on L.ne
    errors = np.abs(errors)
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert 1.9 < order < 2.1 and errors[0] < 0.2 * dts[0] ** 2, (errors, order)


def test_at_rest_the_ground_corners_carry_both_weights():
    """A 0.4 x 0.4 x 1.2 m box (1 t) on a 1.2 x 0.8 x 1.0 m box (3 t), off the lower's centre: the
    second-order terms are the monolith's, -sum W_i z_i about x and about y; at rest (static start)
    the lower's corners carry both weights, the interface the upper's, each with its resultant
    under the weight's centre (the four-corner split itself is statically indeterminate)."""
    fr = Frame3D()
    fr.node("c1", 0.0, 0.0, 0.5)
    fr.node("c2", 0.3, -0.1, 1.6)
    lower = fr.rigid_box("L", "c1", width_x=1.2, width_y=0.8, height=1.0, mass=3.0)
    upper = fr.rigid_box("U", "c2", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="L")
    st = fr.build()
    K = st.rigid.geometric.toarray()
    for dof in ("rx", "ry"):
        turn = _u0(st, **{f"L_{dof}": 1.0, f"U_{dof}": 1.0})                # held together, turned by 1 rad
        assert turn @ K @ turn == pytest.approx(-(lower.W * 0.5 + upper.W * (1.0 + 0.6)), rel=1e-14)
    model = st.to_model()
    sol = _run(st, LoadHistory(st.gravity(G)), dt=1e-3, t_end=0.1, initial="static")
    names = list(model.constraint_names)
    for box, carried, centre in ((lower, lower.W + upper.W, (0.3 * upper.W) / (lower.W + upper.W)), (upper, upper.W, 0.3)):
        cols = [names.index(c) for c in box.corners]
        x = np.array([st.coords[c][0] for c in box.corners])
        force = sol.v[:, cols]
        assert np.abs(force.sum(axis=1) - carried).max() <= 1e-13 * carried
        assert np.abs(force @ x / force.sum(axis=1) - centre).max() <= 1e-12
    assert np.abs(sol.u).max() <= 1e-13                 # round-off of the static state (measured 6.7e-15)


def _frame_with_box(stiffness):
    """A cantilever column 3 m tall (0.25 m square), its top the floor node "f" (5 t), the box "B"
    0.4 x 0.6 x 1.2 m (1 t) standing on it; ``stiffness`` scales E."""
    fr = Frame3D()
    fr.node("g", 0.0, 0.0, 0.0)
    fr.node("f", 0.0, 0.0, 3.0)
    fr.support("g", ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    a, E = 0.25, 3e7 * stiffness
    fr.beam("col", "g", "f", E=E, A=a * a, Iy=a ** 4 / 12, Iz=a ** 4 / 12, G=E / 2.4, J=0.141 * a ** 4)
    fr.mass("f", 5.0, Jx=1.0, Jy=1.0, Jz=1.0)
    fr.node("c", 0.0, 0.0, 3.6)
    box = fr.rigid_box("B", "c", width_x=0.4, width_y=0.6, height=1.2, mass=1.0, on="f")
    return fr.build(), box


def _shaken(st, a_g, direction, *, dt=1e-3, t_end=1.5):
    load = LoadHistory(st.gravity(G), [rigid3d.ground_motion(st, a_g, direction)])
    return _run(st, load, dt=dt, t_end=t_end, initial="static"), load


def _sine(amplitude, f=2.0, duration=0.5):
    return lambda t: np.where(np.asarray(t) < duration, amplitude * np.sin(2 * math.pi * f * np.asarray(t)), 0.0)


def test_a_box_on_a_stiff_frames_floor_tends_to_the_box_on_the_ground():
    """A skew shaking (1, 0.5, 0) at 1.5 g bx / h: the floor box's tilts tend to the ground box's up
    to its first impact (0.271 s; peak tilt 3.7e-3 rad) as the column stiffens (E x 1e2, 1e4, 1e6):
    measured 1.8e-3, 8.6e-6, 9.6e-9 rad apart, at least 1/stiffness."""
    direction = (1.0, 0.5, 0.0)
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, 0.6)
    fr.rigid_box("B", "c", width_x=0.4, width_y=0.6, height=1.2, mass=1.0)
    st0 = fr.build()
    a_g = _sine(1.5 * G * 0.2 / 0.6 / math.hypot(*direction))
    s0, _ = _shaken(st0, a_g, direction)
    first = s0.stats["impacts"][0]["time"]
    k = np.searchsorted(s0.t, first)
    tilt0 = np.column_stack([s0.dof("B.base.rx"), s0.dof("B.base.ry")])[:k]
    assert np.abs(tilt0).max() > 0.003                  # it lifts (3.7e-3 rad before its first impact)
    errors = []
    for stiffness in (1e2, 1e4, 1e6):
        st, _ = _frame_with_box(stiffness)
        sol, _ = _shaken(st, a_g, direction)
        tilt = np.column_stack([sol.dof("B.base.rx"), sol.dof("B.base.ry")])[:k]
        errors.append(np.abs(tilt - tilt0).max())
    assert errors[0] > 100 * errors[1] > 1e4 * errors[2] and errors[2] < 1e-7, errors


def test_the_frames_base_forces_are_newton_with_the_box_on_its_floor():
    """The frame with a box rocking on its floor, shaken along x and y: on the steps without a
    located impact, the base forces are sum m a_abs of every node, the box's centre included (its
    part is more than a tenth of the base shear), and the box's corners are internal."""
    st, box = _frame_with_box(1.0)
    a_g = _sine(1.5 * G * 0.2 / 0.6)
    load = LoadHistory(st.gravity(G), [rigid3d.ground_motion(st, a_g, "ux"),
                                       rigid3d.ground_motion(st, _sine(0.5 * G * 0.3 / 0.6, f=1.5), "uy")])
    dt = 1e-3
    sol = _run(st, load, dt=dt, t_end=1.0, initial="static")
    assert len(sol.stats["impacts"]) > 2
    ds = ul.results_dataset(sol, st, load=load)
    mid = lambda x: 0.5 * (x[1:] + x[:-1])
    base = {c: mid(ds[f"base_F{c}"].values.ravel()) for c in "xyz"}
    mass = st.nodal_mass[:, 0]
    a = st.dofs.nodal(np.diff(sol.udot, axis=0) / dt)
    t_mid = sol.t[:-1] + dt / 2
    ground = {"x": a_g(t_mid), "y": _sine(0.5 * G * 0.3 / 0.6, f=1.5)(t_mid), "z": 0.0 * t_mid}
    struck = np.searchsorted(sol.t, [ev["time"] for ev in sol.stats["impacts"]]) - 1
    smooth = np.ones(len(t_mid), dtype=bool)
    smooth[struck] = False
    centre = list(st.dofs.nodes).index(box.node)
    for k, c in enumerate("xyz"):
        momentum = (mass * (a[:, :, k] + ground[c][:, None])).sum(axis=1) + (mass.sum() * G if c == "z" else 0.0)
        scale = np.abs(base[c]).max()
        assert np.abs(base[c] - momentum)[smooth].max() <= 1e-11 * scale, c
    box_x = box.mass * (a[:, centre, 0] + ground["x"])
    assert np.abs(box_x).max() > 0.1 * np.abs(base["x"]).max()
    assert "ground_element" not in ds.coords


def test_a_stack_shaken_in_both_directions_balances_its_energy():
    """A 0.4 x 0.4 x 1.2 m box on a 1.2 x 1.2 x 1.0 m box, shaken along x and y above the upper's
    uplift: the upper rocks on the lower (which stays put), and the energy balance of the march
    closes with the impact losses (measured 1.6e-14; 132 located impacts, peak tilt 0.159 rad)."""
    st, lower, upper = _stack3d(widths=((1.2, 1.2), (0.4, 0.4)), heights=(1.0, 1.2))
    model = st.to_model()
    amp = 1.5 * upper.uplift_acceleration[0]
    load = LoadHistory(st.gravity(G), [rigid3d.ground_motion(st, _sine(amp), "ux"),
                                       rigid3d.ground_motion(st, _sine(0.7 * amp, f=1.5), "uy")])
    sol = _run(st, load, dt=1e-3, t_end=1.5, initial="static")
    assert np.hypot(sol.dof("U.base.rx"), sol.dof("U.base.ry")).max() > 0.02 and len(sol.stats["impacts"]) > 2
    assert np.abs(sol.dof("L.base.rx")).max() <= 1e-13 and np.abs(sol.dof("L.base.ry")).max() <= 1e-13
    balance = energy_balance(model, sol)
    assert balance["relative_error"] <= 1e-12, balance["relative_error"]
    assert balance["impact_loss"][-1] > 0


def _floor3d():
    fr = Frame3D()
    fr.node("g", 0.0, 0.0, 0.0)
    fr.node("f", 0.0, 0.0, 3.0)
    fr.support("g", ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("col", "g", "f", E=3e7, A=0.0625, Iy=3e-4, Iz=3e-4, G=1.25e7, J=5e-4)
    fr.mass("f", 5.0, Jx=1.0, Jy=1.0, Jz=1.0)
    fr.node("c", 0.0, 0.0, 3.6)
    fr.node("cL", 3.0, 0.0, 0.6)
    fr.rigid_box("L", "cL", width_x=0.4, width_y=0.4, height=1.2, mass=1.0)
    return fr


@pytest.mark.parametrize("on, match", [
    ("nowhere", "neither a defined node nor a rigid block"),
    ("B", "is the block itself"),
    ("c", "own centre node"),
    ("L.sw", "is a node of rigid block 'L'; to stand on that block give on='L'"),
    ("L.base", "is a node of rigid block 'L'"),
    ("g", "is supported"),
])
def test_a_box_on_what_cannot_carry_it_is_refused(on, match):
    fr = _floor3d()
    node = "c"
    if on == "g":
        fr.node("c2", 0.0, 0.0, 0.6)
        node = "c2"
    with pytest.raises(ValueError, match=match):
        fr.rigid_box("B", node, width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on=on)


def test_a_box_must_stand_where_it_is_put():
    fr = _floor3d()
    with pytest.raises(ValueError, match=r"base centre \(0, 0, 2.5\) must be at node on='f' \(0, 0, 3\)"):
        fr.rigid_box("B", "c", width_x=0.4, width_y=0.4, height=2.2, mass=1.0, on="f")
    fr.node("c3", 3.0, 0.0, 1.8)
    with pytest.raises(ValueError, match=r"base y in \[-0.3, 0.3\] must lie within the top face of rigid block "
                                         r"'L', \[-0.2, 0.2\] \(no overhang\)"):
        fr.rigid_box("U", "c3", width_x=0.4, width_y=0.6, height=1.2, mass=1.0, on="L")    # wider than L
    fr.node("c4", 3.1, 0.0, 1.8)
    with pytest.raises(ValueError, match=r"base x in \[2.9, 3.3\] must lie within"):
        fr.rigid_box("U", "c4", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="L")    # off its edge
    fr.node("c5", 3.0, 0.0, 2.0)
    with pytest.raises(ValueError, match="must lie on the top face of rigid block 'L', z = 1.2"):
        fr.rigid_box("U", "c5", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="L")


def test_a_cycle_of_stacks_and_bad_contacts_are_refused():
    fr = Frame3D()
    fr.node("x", 0.0, 0.0, 1.2)
    fr.node("cA", 0.0, 0.0, 1.8)
    fr.rigid_box("A", "cA", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="x")
    with pytest.raises(ValueError, match="closes a cycle of stacks: 'B' on 'A' on node 'x', the centre of 'B'"):
        fr.rigid_box("B", "x", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="A")
    with pytest.raises(ValueError, match="is the floor node of rigid block 'A'"):
        fr.rigid_box("B", "x", width_x=0.4, width_y=0.4, height=1.2, mass=1.0)
    with pytest.raises(ValueError, match="on='nowhere' is not defined"):
        fr.contact("k", "x", on="nowhere")
    with pytest.raises(ValueError, match="on='x' is the node itself"):
        fr.contact("k", "x", on="x")
    fr = Frame3D()
    fr.node("g", 0.0, 0.0, 0.0)
    fr.node("f", 0.0, 0.0, 3.0)
    fr.support("g", ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("col", "g", "f", E=3e7, A=0.0625, Iy=3e-4, Iz=3e-4, G=1.25e7, J=5e-4)
    fr.mass("f", 5.0)
    fr.contact("k", "f", on="g")
    with pytest.raises(ValueError, match=r"node on='g' is supported \(uz\): it is the ground; give on=None"):
        fr.build()


def test_a_relative_contact_with_friction_has_relative_tangent_columns():
    """``Frame3D.contact(..., on=, mu=)``: the normal and both tangent columns are the differences of
    the two nodes' (a ball on a free slab)."""
    fr = Frame3D()
    fr.node("s", 0.0, 0.0, 0.0)
    fr.node("p", 0.0, 0.0, 0.0)
    for node in ("s", "p"):
        fr.mass(node, 1.0)
    fr.contact("k", "p", on="s", mu=0.3)
    st = fr.build()
    T, dofs = st.dofs.T, st.dofs
    e = lambda node, dof: T[dofs.full_index(node, dof)].toarray().ravel()
    np.testing.assert_array_equal(st.rigid.N.toarray()[:, 0], e("p", "uz") - e("s", "uz"))
    for axis, dof in zip(st.rigid.tangent, ("ux", "uy")):
        np.testing.assert_array_equal(axis.toarray()[:, 0], e("p", dof) - e("s", dof))


def test_a_model_file_3d_stack_is_the_api_stack(tmp_path):
    from unilateral.modelfile import load_model_file

    text = ('[units]\nlength = "m"\nforce = "kN"\ntime = "s"\n\n[frame]\ndimensions = 3\n\n'
            '[[nodes]]\nid = 1\nx = 0.0\ny = 0.0\nz = 0.6\n\n[[nodes]]\nid = 2\nx = 0.0\ny = 0.0\nz = 1.8\n\n'
            '[[rigid_blocks]]\nname = "L"\nnode = 1\nwidth = 0.4\nwidth_y = 0.4\nheight = 1.2\nmass = 1.0\n\n'
            '[[rigid_blocks]]\nname = "U"\nnode = 2\nwidth = 0.4\nwidth_y = 0.4\nheight = 1.2\nmass = 1.0\n'
            'on = "L"\n\n[loads.gravity]\ng = 9.80665\n\n[analysis]\ndt = 0.001\nt_end = 0.1\n'
            'bilateral_reference = false\ninitial = "rest"\nmethod = "moreau-jean"\nrule = "trapezoidal"\n')
    path = tmp_path / "m.toml"
    path.write_text(text)
    spec = load_model_file(path)
    st, _, _ = _stack3d()
    model = st.to_model()
    np.testing.assert_allclose(spec.model.K.toarray(), model.K.toarray(), rtol=1e-14, atol=0)
    assert list(spec.model.constraint_names) == list(model.constraint_names)
    path.write_text(text.replace('on = "L"', 'on = "M"'))
    from unilateral.modelfile import ModelFileError

    with pytest.raises(ModelFileError, match="neither a defined node nor a rigid block"):
        load_model_file(path)


def test_the_ground_carries_a_3d_stack_through_its_lower_boxs_corners_and_base():
    """The stack of the at-rest test (the upper box 0.3 m east and 0.1 m south of the lower's
    centre) shaken along x and y above the upper's uplift: the ground's forces (the lower's corners
    and base; the upper's are internal) are Newton's for the two boxes at every step, impacts
    included: ``sum m a`` along x, y and z, and about the vertical through the base point
    ``sum m (dx a_y - dy a_x)`` (no twist without friction)."""
    fr = Frame3D()
    fr.node("c1", 0.0, 0.0, 0.5)
    fr.node("c2", 0.3, -0.1, 1.6)
    lower = fr.rigid_box("L", "c1", width_x=1.2, width_y=0.8, height=1.0, mass=3.0)
    upper = fr.rigid_box("U", "c2", width_x=0.4, width_y=0.4, height=1.2, mass=1.0, on="L")
    st = fr.build()
    ax, ay = _sine(1.5 * upper.uplift_acceleration[0]), _sine(0.8 * upper.uplift_acceleration[1], f=1.5)
    load = LoadHistory(st.gravity(G), [rigid3d.ground_motion(st, ax, "ux"), rigid3d.ground_motion(st, ay, "uy")])
    dt = 1e-3
    sol = _run(st, load, dt=dt, t_end=1.0, initial="static")
    assert np.hypot(sol.dof("U.base.rx"), sol.dof("U.base.ry")).max() > 0.02 and len(sol.stats["impacts"]) > 2
    ds = ul.results_dataset(sol, st, load=load)
    assert "U.base.ux" not in list(ds.coords["support"].values)             # the upper's base: tied, internal
    nodes = list(st.dofs.nodes)
    a = st.dofs.nodal(np.diff(sol.udot, axis=0) / dt)
    a_ground = ds["ground_acceleration"].values[1:]                         # the steps' means, (steps, 2)
    masses = np.array([lower.mass, upper.mass])
    centres = [nodes.index(lower.node), nodes.index(upper.node)]
    absolute = a[:, centres, :3].copy()
    absolute[:, :, 0] += a_ground[:, [0]]
    absolute[:, :, 1] += a_ground[:, [1]]
    for k, c in enumerate("xyz"):
        base = ds[f"base_F{c}"].values[1:]
        expected = absolute[:, :, k] @ masses + (masses.sum() * G if c == "z" else 0.0)
        assert np.abs(base - expected).max() <= 1e-12 * np.abs(base).max(), c
    xp, yp = np.asarray(ds.attrs["base_point"], dtype=float)[:2]
    dx = np.array([st.coords[lower.node][0], st.coords[upper.node][0]]) - xp
    dy = np.array([st.coords[lower.node][1], st.coords[upper.node][1]]) - yp
    mz = ds["base_Mz"].values[1:]
    expected = (absolute[:, :, 1] * dx - absolute[:, :, 0] * dy) @ masses
    assert np.abs(mz - expected).max() <= 1e-12 * np.abs(mz).max() and np.abs(mz).max() > 0.1
