"""Rigid blocks on a frame's floor and on other blocks (stacks): ``Frame2D.contact(..., on=)``,
``Frame2D.rigid_block(..., on=)`` (:mod:`unilateral.structure.stacks`, ``docs/rocking.md``).

What is checked: a block on the floor of a stiff frame tends to the block on the shaken ground as
the frame stiffens; a two-block stack released from a tilt is Housner's monolith of twice the
height until the first impact (the second-order term of the upper weight carried by the lower
block included), its interface in compression; at rest the ground corners carry both weights; under
a base shaking below both uplift accelerations nothing lifts, above the upper one the upper block
rocks on the lower, and the energy balance closes with the impact losses alone; a block on a
flexible frame's floor is in the frame's base shear (Newton for the whole system); bad input."""

import math

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import energy_balance
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, rigid
from unilateral.structure.rigid import RigidBlock

G = 9.80665


def _frame_with_block(stiffness, *, m_floor=5.0, J_floor=1.0):
    """A cantilever column 3 m tall, its top the floor node "f" (mass ``m_floor``, rotary inertia
    ``J_floor``), the 0.4 x 1.2 m block "B" (1 t) standing on it; ``stiffness`` scales E."""
    fr = Frame2D()
    fr.node("g", 0.0, 0.0)
    fr.node("f", 0.0, 3.0)
    fr.support("g", ux=True, uy=True, rz=True)
    fr.beam("col", "g", "f", E=3e7 * stiffness, A=0.25, I=0.25 ** 4 / 12)
    fr.mass("f", m_floor, J=J_floor)
    fr.node("c", 0.0, 3.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, on="f")
    return fr.build(), block


def _ground_block():
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    block = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    return fr.build(), block


def _shaken(st, a_g, *, dt=1e-3, t_end=1.5, initial="static"):
    load = LoadHistory(st.gravity(G), [rigid.ground_motion(st, a_g)])
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=t_end, method="moreau-jean", rule="trapezoidal",
                   initial=initial)
    assert sol.success, sol.message
    return sol


def _sine(amplitude, f=2.0, duration=0.5):
    """``a_g(t) = amplitude sin(2 pi f t)`` for ``t < duration``, 0 after (scalars or arrays)."""
    return lambda t: np.where(np.asarray(t) < duration, amplitude * np.sin(2 * math.pi * f * np.asarray(t)), 0.0)


def test_a_block_on_a_stiff_frames_floor_tends_to_the_block_on_the_ground():
    a_g = _sine(1.5 * G / 3)                    # 1.5 times the uplift acceleration g b / h
    st0, _ = _ground_block()
    s0 = _shaken(st0, a_g)
    theta0 = st0.node_displacement(s0, "B.base", "rz")
    first = s0.stats["impacts"][0]["time"]
    k = np.searchsorted(s0.t, first)            # to the first impact (after it the floor's mass recoils)
    assert np.abs(theta0[:k]).max() > 0.01      # it lifts and rocks (0.020 rad)
    errors, impacts = [], []
    for stiffness in (1e2, 1e4, 1e6):
        st, _ = _frame_with_block(stiffness)
        sol = _shaken(st, a_g)
        theta = st.node_displacement(sol, "B.base", "rz")
        errors.append(np.abs(theta[:k] - theta0[:k]).max())
        impacts.append(abs(sol.stats["impacts"][0]["time"] - first))
    # measured 2.0e-3, 3.1e-5, 2.1e-8 rad; first impact times 3.8e-3, 5.7e-5, 5.5e-8 s off (after the
    # first impact the floor's mass recoils and the corner chatters on it: 1e-4 rad apart at any stiffness)
    assert errors[0] > 30 * errors[1] > 900 * errors[2], errors
    assert errors[2] < 1e-7 and impacts[2] < 1e-7 and impacts[0] > impacts[1] > impacts[2], impacts


def test_a_relative_contact_is_the_difference_of_the_two_nodes_columns():
    st, block = _frame_with_block(1.0)
    dofs, N = st.dofs, st.rigid.N.toarray()
    for j, contact in enumerate(st.rigid.contacts):
        assert contact.on == f"B.on.{contact.name.split('.')[1]}"
        expected = (dofs.T[dofs.full_index(contact.node, "uy")] - dofs.T[dofs.full_index(contact.on, "uy")]).toarray()
        assert np.array_equal(N[:, j], expected.ravel())
    x = dict(left=-block.b, right=block.b)
    for j, side in enumerate(("left", "right")):     # uy_B + x theta_B - (uy_f + x rz_f)
        col = dict(zip(dofs.names, N[:, j]))
        assert col == {"f.ux": 0.0, "f.uy": -1.0, "f.rz": -x[side], "B.base.uy": 1.0, "B.base.rz": x[side]}
    tied = dofs.T[dofs.full_index("B.base", "ux")].toarray().ravel()
    assert np.array_equal(tied, dofs.T[dofs.full_index("f", "ux")].toarray().ravel())   # no slip on the floor


def _stack(widths=(0.4, 0.4), heights=(1.2, 1.2), masses=(1.0, 1.0)):
    fr = Frame2D()
    fr.node("c1", 0.0, heights[0] / 2)
    fr.node("c2", 0.0, heights[0] + heights[1] / 2)
    lower = fr.rigid_block("L", "c1", width=widths[0], height=heights[0], mass=masses[0])
    upper = fr.rigid_block("U", "c2", width=widths[1], height=heights[1], mass=masses[1], on="L")
    return fr.build(), lower, upper


def test_a_two_block_stack_released_from_a_tilt_rocks_as_the_monolith_until_the_first_impact():
    st, lower, upper = _stack()
    model = st.to_model()
    # the monolith: 0.4 x 2.4 m, 2 t, the uniform rectangle's J (the two uniform halves' together)
    tall = RigidBlock("tall", None, None, (), 0.2, 1.2, 2.0, 2.0 * (0.2 ** 2 + 1.2 ** 2) / 3, G)
    theta0 = 0.05
    u0 = np.array([lower.b * theta0, -theta0, lower.b * theta0, -theta0])   # on the right corner, no gap between
    t1 = tall.first_impact_time(theta0)
    names = list(model.constraint_names)
    dts, errors = (2e-3, 1e-3, 5e-4), []
    for dt in dts:
        sol = ul.solve(model, LoadHistory(st.gravity(G)), dt=dt, t_end=0.45, method="moreau-jean",
                       rule="trapezoidal", initial={"u0": u0})
        first = sol.stats["impacts"][0]
        assert set(first["contacts"]) == {"L.left", "U.left", "U.right"}         # the landing strikes all three
        errors.append(first["time"] - t1)
        k = np.searchsorted(sol.t, first["time"])
        tilt = -sol.u[:k, 1]
        assert np.abs(tilt - tall.tilt(sol.t[:k], theta0)).max() <= 0.1 * dt ** 2      # 2.1e-7 at dt = 2e-3
        assert np.abs(sol.u[:k, 3] - sol.u[:k, 1]).max() <= 1e-15                  # the upper turns with it
        assert np.abs(sol.u[:k, 2] - sol.u[:k, 0]).max() <= 1e-15
        interface = sol.v[1:k, [names.index("U.left"), names.index("U.right")]]
        assert interface.min() > 0.15 * upper.W                                    # compressive (1.79 of 9.8)
        assert np.abs(sol.v[1:k, names.index("L.left")]).max() == 0.0               # it pivots on L.right
    errors = np.abs(errors)                     # measured -7.3e-7, -1.8e-7, -4.6e-8 s
    order = np.polyfit(np.log(dts), np.log(errors), 1)[0]
    assert 1.95 < order < 2.05 and errors[0] < 0.2 * dts[0] ** 2, (errors, order)


def test_the_stack_has_the_monoliths_second_order_term_and_rests_on_its_ground_corners():
    st, lower, upper = _stack(widths=(1.2, 0.4), heights=(1.0, 1.2), masses=(3.0, 1.0))
    K = st.rigid.geometric.toarray()
    theta = np.array([0.0, 1.0, 0.0, 1.0])      # the two held together, turned by 1 rad
    # the potential of the weights, -sum W_i y_i theta^2 / 2, y_i the centres' heights above the ground
    assert theta @ K @ theta == pytest.approx(-(lower.W * 0.5 + upper.W * (1.0 + 0.6)), rel=1e-14)
    model = st.to_model()
    sol = ul.solve(model, LoadHistory(st.gravity(G)), dt=1e-3, t_end=0.2, method="moreau-jean",
                   rule="trapezoidal", initial="static")
    names = list(model.constraint_names)
    ground = sol.v[:, [names.index("L.left"), names.index("L.right")]]
    interface = sol.v[:, [names.index("U.left"), names.index("U.right")]]
    assert np.abs(ground.sum(axis=1) - (lower.W + upper.W)).max() <= 1e-13 * lower.W
    assert np.abs(interface.sum(axis=1) - upper.W).max() <= 1e-13 * upper.W
    assert np.abs(ground[:, 0] - ground[:, 1]).max() <= 1e-12 and np.abs(sol.u).max() <= 1e-15


@pytest.mark.parametrize("scale", [0.9, 1.5])
def test_a_stack_on_a_shaken_ground_lifts_only_above_the_upper_blocks_uplift(scale):
    # lower 1.2 x 1.0 m, upper 0.4 x 1.2 m, 1 t each: the upper lifts at g b/h = g/3; the stack as one
    # at g 2 (0.6) / (0.5 + 1.6) = 0.571 g, so at 1.5 g/3 = 0.5 g only the upper block rocks
    st, lower, upper = _stack(widths=(1.2, 0.4), heights=(1.0, 1.2))
    model = st.to_model()
    a_g = _sine(scale * upper.uplift_acceleration)
    sol = _shaken(st, a_g, t_end=2.0)
    names = list(model.constraint_names)
    ground = [names.index("L.left"), names.index("L.right")]
    opening = -sol.psi
    assert np.abs(opening[:, ground]).max() <= 1e-15 and sol.v[1:, ground].min() > 0.1 * lower.W
    assert np.abs(st.node_displacement(sol, "L.base", "rz")).max() <= 1e-15     # the lower block stays put
    balance = energy_balance(model, sol)
    assert balance["relative_error"] <= 1e-13, balance["relative_error"]          # 2e-14
    loss = np.diff(balance["impact_loss"])
    if scale < 1:                                # nothing lifts: at rest on the moving ground
        assert np.abs(sol.u).max() <= 1e-15 and np.abs(opening).max() <= 1e-15
        assert sol.v[1:].min() > 0.04 * upper.W and not sol.stats["impacts"]
        assert np.abs(sol.v[:, ground].sum(axis=1) - lower.W - upper.W).max() <= 1e-12 * lower.W
        assert np.abs(balance["impact_loss"]).max() <= 1e-15 * lower.W
        return
    theta = st.node_displacement(sol, "U.base", "rz")
    assert np.abs(theta).max() > 0.1                                               # it rocks (0.159 rad)
    assert opening[:, [names.index("U.left"), names.index("U.right")]].max() > 0.01
    # on a lower block that does not move, the upper block is the block on the ground
    st0, _ = _ground_block()
    theta0 = st0.node_displacement(_shaken(st0, a_g, t_end=2.0), "B.base", "rz")
    assert np.abs(theta - theta0).max() <= 1e-12
    # energy is lost only at the located impacts: their losses are the march's, step by step
    impacts = sol.stats["impacts"]
    assert len(impacts) >= 2 and all(ev["loss"] > 0 for ev in impacts)
    at = np.searchsorted(sol.t, [ev["time"] for ev in impacts]) - 1
    expected = np.zeros_like(loss)
    np.add.at(expected, at, [ev["loss"] for ev in impacts])
    assert np.abs(loss - expected).max() <= 1e-14 * balance["impact_loss"][-1]


def test_a_block_on_a_flexible_frames_floor_is_in_the_frames_base_shear():
    st, block = _frame_with_block(1.0)          # 3 EI / L^3 = 1.1e3 kN/m under 6 t: a sway period near 0.5 s
    a_g = _sine(1.5 * G / 3)
    load = LoadHistory(st.gravity(G), [rigid.ground_motion(st, a_g)])
    dt = 1e-3
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=1.5, method="moreau-jean", rule="trapezoidal", initial="static")
    assert sol.success and len(sol.stats["impacts"]) > 5
    ds = ul.results_dataset(sol, st, load=load)
    mid = lambda x: 0.5 * (x[1:] + x[:-1])      # the trapezoidal rule's mid-step values
    shear, vertical = mid(ds["base_shear"].values.ravel()), mid(ds["base_vertical"].values.ravel())
    nodes, mass = list(st.dofs.nodes), st.nodal_mass[:, 0]
    a = st.dofs.nodal(np.diff(sol.udot, axis=0) / dt)            # the steps' mean accelerations, every node
    a_th = a_g(sol.t[:-1] + dt / 2)
    momentum_x = (mass * (a[:, :, 0] + a_th[:, None])).sum(axis=1)   # sum m a_abs: the frame's and the block's
    momentum_y = (mass * a[:, :, 1]).sum(axis=1)
    # Newton for the whole system on the steps without a located impact (a step with one is taken in
    # pieces: its mean is not the mid-step state's)
    struck = np.searchsorted(sol.t, [ev["time"] for ev in sol.stats["impacts"]]) - 1
    smooth = np.ones(len(shear), dtype=bool)
    smooth[struck] = False
    scale = np.abs(shear).max()
    assert np.abs(shear - momentum_x)[smooth].max() <= 1e-12 * scale                 # 2.7e-12 of 85 kN
    assert np.abs(vertical - mass.sum() * G - momentum_y)[smooth].max() <= 1e-12 * np.abs(vertical).max()
    centre = nodes.index(block.node)
    block_x = block.mass * (a[:, centre, 0] + a_th)
    frame_x = momentum_x - block_x
    assert np.abs(shear - frame_x)[smooth].max() > 0.1 * scale                       # the block's part counts
    # the block's contacts and its base are internal: the ground acts through the column's support only
    assert "ground_element" not in ds.coords and list(ds.coords["support"].values) == ["g.ux", "g.uy", "g.rz"]


def test_the_ground_carries_a_stack_through_its_lower_blocks_corners_and_base():
    st, lower, upper = _stack(widths=(1.2, 0.4), heights=(1.0, 1.2))
    a_g = _sine(1.5 * upper.uplift_acceleration)
    load = LoadHistory(st.gravity(G), [rigid.ground_motion(st, a_g)])
    dt = 1e-3
    sol = ul.solve(st.to_model(), load, dt=dt, t_end=1.5, method="moreau-jean", rule="trapezoidal", initial="static")
    ds = ul.results_dataset(sol, st, load=load)
    assert list(ds.coords["ground_element"].values) == ["L.left", "L.right", "L.base"]   # not U's: internal
    nodes = list(st.dofs.nodes)
    a = st.dofs.nodal(np.diff(sol.udot, axis=0) / dt)
    a_mean = ds["ground_acceleration"].values[1:, 0]            # moreau-jean: the steps' means
    centres = [nodes.index(lower.node), nodes.index(upper.node)]
    masses = np.array([lower.mass, upper.mass])
    fx, fy = ds["base_shear"].values[1:], ds["base_vertical"].values[1:]
    # Newton for the stack at every step, impacts included (the forces are the steps' impulses / dt)
    assert np.abs(fy - lower.W - upper.W - a[:, centres, 1] @ masses).max() <= 1e-12 * np.abs(fy).max()
    assert np.abs(fx - (a[:, centres, 0] + a_mean[:, None]) @ masses).max() <= 1e-12 * np.abs(fx).max()
    assert np.abs(a[:, centres[1], 1]).max() > 1.0              # the upper block's impacts are in them


def test_direct_takes_the_relative_contacts_too():
    st, lower, upper = _stack()
    model = st.to_model()
    tall = RigidBlock("tall", None, None, (), 0.2, 1.2, 2.0, 2.0 * (0.2 ** 2 + 1.2 ** 2) / 3, G)
    theta0, q = 0.05, st.gravity(G)
    u0 = np.array([lower.b * theta0, -theta0, lower.b * theta0, -theta0])
    v0 = rigid.initial_forces(model, u0, q)
    assert v0[0] == 0 and v0[2:].min() > 0     # the interface in compression from the start
    errors = []
    for dt in (1e-3, 5e-4):
        with pytest.warns(UserWarning, match="trapezoidal"):
            sol = ul.solve(model, LoadHistory(q), dt=dt, t_end=0.3, method="direct", rule="trapezoidal",
                           initial={"u0": u0, "v0": v0})
        assert np.abs(sol.u[:, 3] - sol.u[:, 1]).max() <= 1e-15
        errors.append(np.abs(-sol.u[:, 1] - tall.tilt(sol.t, theta0)).max())
    assert errors[1] < 0.3 * errors[0] and errors[1] < 2e-8, errors    # 5.2e-8, 1.3e-8: second order


def _floor(centre=True):
    fr = Frame2D()
    fr.node("g", 0.0, 0.0)
    fr.node("f", 0.0, 3.0)
    fr.support("g", ux=True, uy=True, rz=True)
    fr.beam("col", "g", "f", E=3e7, A=0.25, I=0.25 ** 4 / 12)
    fr.mass("f", 5.0, J=1.0)
    if centre:
        fr.node("c", 0.0, 3.6)
    return fr


@pytest.mark.parametrize("on, match", [
    ("nowhere", "neither a defined node nor a rigid block"),
    ("B", "is the block itself"),
    ("c", "own centre node"),
    ("L.left", "is a node of rigid block 'L'; to stand on that block give on='L'"),
    ("L.base", "is a node of rigid block 'L'"),
    ("g", "is supported"),
])
def test_a_block_on_what_cannot_carry_it_is_refused(on, match):
    fr = _floor()
    fr.node("cL", 3.0, 0.6)
    fr.rigid_block("L", "cL", width=0.4, height=1.2, mass=1.0)
    if on == "g":
        fr.node("c2", 0.0, 0.6)
        with pytest.raises(ValueError, match=match):
            fr.rigid_block("B", "c2", width=0.4, height=1.2, mass=1.0, on=on)
        return
    with pytest.raises(ValueError, match=match):
        fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, on=on)


def test_a_block_must_stand_where_it_is_put():
    fr = _floor()
    with pytest.raises(ValueError, match=r"base centre \(0, 2.5\) must be at node on='f' \(0, 3\)"):
        fr.rigid_block("B", "c", width=0.4, height=2.2, mass=1.0, on="f")
    fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0, on="f")
    fr.node("c2", 0.3, 4.8)
    with pytest.raises(ValueError, match="must lie within the top face of rigid block 'B'"):
        fr.rigid_block("U", "c2", width=0.4, height=1.2, mass=1.0, on="B")     # overhangs B's right edge
    fr.node("c3", 0.0, 5.0)
    with pytest.raises(ValueError, match="must lie on the top face of rigid block 'B', y = 4.2"):
        fr.rigid_block("U", "c3", width=0.4, height=1.2, mass=1.0, on="B")


def test_a_cycle_of_stacks_is_refused():
    fr = Frame2D()
    fr.node("x", 0.0, 1.2)
    fr.node("cA", 0.0, 1.8)
    fr.rigid_block("A", "cA", width=0.4, height=1.2, mass=1.0, on="x")    # A on the node x ...
    with pytest.raises(ValueError, match="closes a cycle of stacks: 'B' on 'A' on node 'x', the centre of 'B'"):
        fr.rigid_block("B", "x", width=0.4, height=1.2, mass=1.0, on="A")  # ... the centre of B, on A
    with pytest.raises(ValueError, match="is the floor node of rigid block 'A'"):
        fr.rigid_block("B", "x", width=0.4, height=1.2, mass=1.0)          # B would carry A by its centre


def test_a_contact_between_nodes_is_checked():
    fr = _floor(centre=False)
    with pytest.raises(ValueError, match="on='nowhere' is not defined"):
        fr.contact("k", "f", on="nowhere")
    with pytest.raises(ValueError, match="on='f' is the node itself"):
        fr.contact("k", "f", on="f")
    fr.node("s", 0.5, 3.0)
    fr.rigid_link("f", "s")
    fr.contact("k", "s", on="f")                # rigidly linked: they cannot move apart
    with pytest.raises(ValueError, match="nodes 's' and on='f' are rigidly linked together"):
        fr.build()
    fr = _floor(centre=False)
    fr.contact("k", "f", on="g")
    with pytest.raises(ValueError, match="node on='g' is supported \\(uy\\): it is the ground; give on=None"):
        fr.build()


def test_moreau_jean_refuses_a_relative_contact_on_a_massless_rotation():
    st, _ = _frame_with_block(1.0, J_floor=0.0)
    with pytest.raises(ValueError, match=r"rigid contacts move DOFs without mass \(f.rz\).*rotary inertia J"):
        _shaken(st, _sine(1.0))
    sol = ul.solve(st.to_model(), LoadHistory(st.gravity(G)), dt=1e-3, t_end=0.01, method="direct", rule="bdf1",
                   initial={"u0": np.zeros(st.n)})
    assert sol.success                          # the position-level direct method takes it


_MODEL = """
units = {{ length = "m", force = "kN", time = "s", mass = "t" }}
nodes = [{{ id = "g", x = 0.0, y = 0.0 }}, {{ id = "f", x = 0.0, y = 3.0 }},
         {{ id = "c1", x = 0.0, y = 3.5 }}, {{ id = "c2", x = 0.0, y = 4.6 }}]
supports = [{{ node = "g", ux = true, uy = true, rz = true }}]
elements = [{{ type = "beam", name = "col", node_i = "g", node_j = "f", E = 3e7, A = 0.25, I = 3.255e-4 }}]
masses = [{{ node = "f", m = 5.0, J = 1.0 }}]
{blocks}
[loads.gravity]
g = "standard"
[analysis]
dt = 0.001
t_end = 0.1
method = "moreau-jean"
rule = "trapezoidal"
"""
_LOWER = '[[rigid_blocks]]\nname = "L"\nnode = "c1"\nwidth = 1.2\nheight = 1.0\nmass = 3.0\non = "f"\n'
_UPPER = '[[rigid_blocks]]\nname = "U"\nnode = "c2"\nwidth = 0.4\nheight = 1.2\nmass = 1.0\non = "L"\n'


def test_a_model_file_stands_a_stack_on_a_floor(tmp_path):
    from unilateral.modelfile import load_model_file

    path = tmp_path / "stack.toml"
    path.write_text(_MODEL.format(blocks=_LOWER + _UPPER))
    spec = load_model_file(path)
    blocks = spec.structure.rigid.blocks
    assert (blocks["L"].on, blocks["L"].seat, blocks["U"].on, blocks["U"].seat) == ("f", "f", "L", "L.base")
    on = {c.name: c.on for c in spec.structure.rigid.contacts}
    assert on == {"L.left": "L.on.left", "L.right": "L.on.right", "U.left": "U.on.left", "U.right": "U.on.right"}
    # the upper weight on the lower block's top face (1 m above its base), the floor's at its level: none
    K = spec.structure.rigid.geometric.toarray()
    i = spec.structure.dofs.index("L.base", "rz")
    assert K[i, i] == pytest.approx(-blocks["L"].W * 0.5 - blocks["U"].W * 1.0, rel=1e-14)
    sol = ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.05, method="moreau-jean", rule="trapezoidal",
                   initial="static")
    names = list(spec.model.constraint_names)
    floor = sol.v[:, [names.index("L.left"), names.index("L.right")]].sum(axis=1)
    assert np.abs(floor - blocks["L"].W - blocks["U"].W).max() <= 1e-12 * floor.max()   # at rest on the floor


@pytest.mark.parametrize("blocks, match", [
    (_UPPER + _LOWER, r"rigid_blocks\[0\]: on = 'L' is a block listed after it"),
    (_LOWER.replace('on = "f"', 'on = "U"') + _UPPER,
     r"rigid_blocks\[0\]: on = 'U' closes a cycle of stacks: 'L' on 'U' on 'L'"),
    (_LOWER.replace('on = "f"', 'on = "roof"'), r"rigid_blocks\[0\].*on='roof' is neither a defined node nor a rigid"),
])
def test_a_model_file_with_a_bad_on_is_refused(tmp_path, blocks, match):
    from unilateral.modelfile import ModelFileError, load_model_file

    path = tmp_path / "bad.toml"
    path.write_text(_MODEL.format(blocks=blocks))
    with pytest.raises((ModelFileError, ValueError), match=match):
        load_model_file(path)


def test_a_tie_makes_a_dof_equal_to_another_nodes_and_a_cycle_of_ties_is_refused():
    from unilateral.structure import DofMap

    coords = {"m": np.array([0.0, 0.0]), "s": np.array([0.0, 2.0]), "b": np.array([0.0, 2.0]),
              "t": np.array([1.0, 2.0])}
    # s rigidly linked to m (2 above it), b's ux tied to s's, t rigidly linked to b
    dofs = DofMap(coords, set(), {"m", "b"}, {"s": "m", "t": "b"}, ties={("b", "ux"): "s"})
    assert dofs.names == ["m.ux", "m.uy", "m.rz", "b.uy", "b.rz"]
    row = lambda node, dof: dict(zip(dofs.names, dofs.T[dofs.full_index(node, dof)].toarray().ravel()))
    assert row("b", "ux") == row("s", "ux") == {"m.ux": 1.0, "m.uy": 0.0, "m.rz": -2.0, "b.uy": 0.0, "b.rz": 0.0}
    assert row("t", "ux") == row("b", "ux")            # b's slave follows the tie (offset along x only)
    with pytest.raises(ValueError, match="b.ux is not a free DOF: it is tied to the ux of node 's'"):
        dofs.index("b", "ux")
    with pytest.raises(ValueError, match="the ties form a cycle through"):
        DofMap(coords, set(), {"m", "b"}, {"s": "m", "t": "b"}, ties={("b", "ux"): "s", ("m", "ux"): "t"})
