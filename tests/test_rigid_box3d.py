"""The rigid box on four corners in 3-D (structure/rigid3d.py, Frame3D.contact, Frame3D.rigid_box),
run by method="moreau-jean" (docs/rocking.md, "A rigid box in 3-D").

The box: height 2h = 1.2 m, m = 1 t (kN, m, s), plan 2bx x 2by; released at rest from a tilt of
0.05 rad on an edge or a corner. Its base moves by uz, rx, ry; a corner (x, y) of the base rises
by uz + rx y - ry x; the weight adds -W h on rx and ry to K.
"""

import math

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import block_results, energy_balance, one_sine_pulse
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, Frame3D, rigid, rigid3d

THETA0 = 0.05


def _box(width_x=0.4, width_y=0.7, **kw):
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, 0.6)
    box = fr.rigid_box("B", "c", width_x=width_x, width_y=width_y, height=1.2, mass=1.0, **kw)
    st = fr.build()
    return st, st.to_model(), box


def _tilted(st, **dofs):
    u0 = np.zeros(st.n)
    for dof, value in dofs.items():
        u0[st.dofs.index("B.base", dof)] = value
    return u0


def _run(st, model, box, u0, dt=5e-4, t_end=1.2, extra=()):
    load = LoadHistory(st.gravity(box.g), list(extra))
    sol = ul.solve(model, load, dt=dt, t_end=t_end, method="moreau-jean", rule="trapezoidal",
                   initial="rest" if u0 is None else {"u0": u0})
    assert sol.success, sol.message
    return sol


def _ratios(sol, axis):
    """omega+ / omega- of each located impact along the tilt ``axis`` (2,) in (rx, ry)."""
    axis = np.asarray(axis, dtype=float)
    return [float(axis @ np.array(ev["udot_after"])[1:] / (axis @ np.array(ev["udot_before"])[1:]))
            for ev in sol.stats["impacts"]]


# ---------------------------------------------------------------------- the model
def test_box_model_is_the_linearised_rocking_in_both_planes():
    st, model, box = _box()
    bx, by, h, m, g = 0.2, 0.35, 0.6, 1.0, box.g
    assert model.dof_names == ["B.base.uz", "B.base.rx", "B.base.ry"]
    assert model.constraint_names == ["B.sw", "B.se", "B.ne", "B.nw"]
    Jx, Jy = m * (by * by + h * h) / 3, m * (bx * bx + h * h) / 3
    assert (box.Jx, box.Jy, box.Jz) == pytest.approx((Jx, Jy, m * (bx * bx + by * by) / 3))
    np.testing.assert_allclose(model.M.toarray(), np.diag([m, Jx + m * h * h, Jy + m * h * h]))
    np.testing.assert_allclose(model.K.toarray(), np.diag([0.0, -m * g * h, -m * g * h]), atol=1e-15)
    # corner (x, y) rises by uz + rx y - ry x: sw, se, ne, nw
    np.testing.assert_allclose(model.F, [[1, 1, 1, 1], [-by, -by, by, by], [bx, -bx, -bx, bx]])
    assert not model.H.any() and not model.g(0.0).any()
    assert box.plane("y").restitution == pytest.approx(1 - 2 * m * bx ** 2 / (Jy + m * (bx * bx + h * h)))
    assert box.plane("x").b == by and box.plane("x").J == Jx
    assert box.uplift_acceleration == pytest.approx((g * bx / h, g * by / h))
    with pytest.raises(ValueError, match="not planar"):
        box.diagonal()
    for helper in (rigid.block_rotation, rigid.block_energy, rigid.impacts):      # the 2-D block's
        with pytest.raises(TypeError, match="3-D rigid box"):
            helper(st, None, "B")


# ---------------------------------------------------------------------- (a), (b): rocking on an edge
def test_rocking_about_an_edge_parallel_to_y_is_the_2d_block():
    """Tilted in the x-z plane (ry) on its +x edge and released: the rotation history equals the
    2-D block's of the same b, h, m, J (3-D ry = -2-D rz) to 1e-12 (measured 3.5e-18), the box does
    not tilt about x (|rx| < 1e-15, measured 1.3e-18), and Housner's ratio and impact times hold as
    in 2-D."""
    st, model, box = _box()
    block = box.plane("y")
    sol = _run(st, model, box, _tilted(st, uz=box.bx * THETA0, ry=THETA0))
    fr = Frame2D()
    fr.node("c", 0.0, 0.6)
    flat = fr.rigid_block("B", "c", width=0.4, height=1.2, mass=1.0)
    st2 = fr.build()
    sol2 = ul.solve(st2.to_model(), LoadHistory(st2.gravity(flat.g)), dt=5e-4, t_end=1.2, method="moreau-jean",
                    rule="trapezoidal", initial={"u0": np.array([flat.b * THETA0, -THETA0])})
    assert (flat.b, flat.h, flat.J) == (block.b, block.h, block.J)
    np.testing.assert_allclose(sol.dof("B.base.ry"), -sol2.dof("B.base.rz"), rtol=0, atol=1e-12)
    assert np.abs(sol.dof("B.base.rx")).max() < 1e-15
    times = [ev["time"] for ev in sol.stats["impacts"]]
    np.testing.assert_allclose(times, [ev["time"] for ev in sol2.stats["impacts"]], rtol=0, atol=1e-12)
    first = _check_housner(sol, block, (0.0, 1.0), tol_time=3e-7)
    assert sol.stats["impacts"][0]["contacts"] == ["B.sw", "B.nw"]            # the -x edge lands
    # the impact times converge at second order (the trapezoidal rule between located impacts)
    half = _check_housner(_run(st, model, box, _tilted(st, uz=box.bx * THETA0, ry=THETA0), dt=2.5e-4), block,
                          (0.0, 1.0), tol_time=8e-8)
    assert first / half == pytest.approx(4.0, rel=0.02)


def test_rocking_about_an_edge_parallel_to_x_has_its_own_p_and_r():
    """Tilted in the y-z plane (rx) on its +y edge, width_y = 0.5 != width_x: Housner's closed forms
    with by = 0.25, I0 = Jx + m (by^2 + h^2) (another p and r than about y)."""
    st, model, box = _box(width_x=0.3, width_y=0.5)
    block = box.plane("x")
    assert block.p != pytest.approx(box.plane("y").p) and block.restitution != pytest.approx(
        box.plane("y").restitution)
    sol = _run(st, model, box, _tilted(st, uz=box.by * THETA0, rx=-THETA0))
    assert np.abs(sol.dof("B.base.ry")).max() < 1e-15
    _check_housner(sol, block, (1.0, 0.0), tol_time=3e-7)
    assert sol.stats["impacts"][0]["contacts"] == ["B.sw", "B.se"]            # the -y edge lands


def _check_housner(sol, block, axis, tol_time) -> float:
    """Housner's ratio 1 - 2 m b^2 / I0 at every located impact (1e-12, measured 1.1e-16), the impact
    times of the closed form and the times between impacts 2 atanh(|w| / (p b / h)) / p to
    ``tol_time``: the trapezoidal rule's second-order error, measured at dt = 5e-4 (2.5e-4) 2.1e-7
    (5.2e-8) at the fourth impact in the x-z plane, 1.6e-7 (3.9e-8) in the y-z plane, the times
    between impacts 6.7e-8 (1.7e-8) and 5.2e-8 (1.3e-8). Returns the error of the first impact time."""
    ratios = _ratios(sol, axis)
    assert len(ratios) >= 4
    np.testing.assert_allclose(ratios, block.restitution, rtol=0, atol=1e-12)
    times = np.array([ev["time"] for ev in sol.stats["impacts"]])
    np.testing.assert_allclose(times[:4], block.impact_times(THETA0, 4), rtol=0, atol=tol_time)
    a, p = block.b / block.h, block.p
    omega = p * math.sqrt(2 * a * THETA0 - THETA0 ** 2) * block.restitution
    for k in range(3):
        assert times[k + 1] - times[k] == pytest.approx(2 * math.atanh(omega / (p * a)) / p, abs=tol_time)
        omega *= block.restitution
    assert sol.stats["unlocated_steps"] == 0 and (-sol.psi).min() > -1e-15
    return abs(times[0] - block.first_impact_time(THETA0))


# ---------------------------------------------------------------------- (c): on a corner, both planes
def test_a_square_box_rocking_about_a_corner_is_housners_block_of_the_diagonal():
    """A square box (Jx = Jy) on its ne corner, tilted about the axis perpendicular to the diagonal:
    it stays in that plane (off-plane tilt < 1e-15, measured 2.1e-18) and follows Housner's closed forms with the
    half-width d = sqrt(bx^2 + by^2): the ratio exactly at every located impact (the flat landing
    onto the opposite corner), the impact times to 2e-7 at dt = 5e-4 (measured 1.6e-7 at the sixth,
    second order); the energy balance closes (measured 2e-14) and the box comes to rest."""
    st, model, box = _box(width_x=0.4, width_y=0.4)
    block = box.diagonal()
    d = block.b
    axis = np.array([-box.by, box.bx]) / d
    sol = _run(st, model, box, _tilted(st, uz=THETA0 * d, rx=THETA0 * axis[0], ry=THETA0 * axis[1]), t_end=3.0)
    tilt = sol.u[:, 1:]
    assert np.abs(tilt @ np.array([box.bx, box.by]) / d).max() < 1e-15
    np.testing.assert_allclose(_ratios(sol, axis)[:6], block.restitution, rtol=0, atol=1e-12)
    times = np.array([ev["time"] for ev in sol.stats["impacts"]][:6])
    np.testing.assert_allclose(times, block.impact_times(THETA0, 6), rtol=0, atol=2e-7)
    assert sol.stats["impacts"][0]["contacts"][:1] == ["B.sw"]
    assert energy_balance(model, sol)["relative_error"] < 1e-9
    _rests(sol)


def test_a_box_rocking_on_a_corner_in_both_planes_loses_energy_only_at_impacts_and_rests():
    """A rectangular box (Jx != Jy) released from a tilt about both axes on its ne corner: the
    linearised motion couples rx and ry (no closed form of the rocking); the energy balance closes
    with the impact losses alone (measured 1.4e-14; some 670 located impacts, the last at 1.98 s), the
    losses add up to the initial energy above the rest, and with restitution 0 the box comes to rest."""
    st, model, box = _box(width_x=0.4, width_y=0.7)
    rx, ry = -0.03, 0.04
    sol = _run(st, model, box, _tilted(st, uz=ry * box.bx - rx * box.by, rx=rx, ry=ry), dt=1e-3, t_end=3.0)
    energy = energy_balance(model, sol)
    assert energy["relative_error"] < 1e-9 and np.abs(energy["numerical_dissipation"]).max() == 0.0
    e0 = rigid3d.box_energy(st, sol, "B")
    assert energy["impact_loss"][-1] == pytest.approx(e0[0] - e0[-1], rel=1e-9)
    assert np.abs(sol.dof("B.base.rx")).max() > 0.02 and len(sol.stats["impacts"]) > 5
    _rests(sol)
    res = block_results(st, sol, "B")
    assert res["peak_rotation"] == pytest.approx(math.hypot(rx, ry), rel=1e-12) and not res["overturned"]
    assert res["peak_uplift"] == pytest.approx(box.bx * 2 * ry - box.by * 2 * rx, rel=1e-9)   # the sw corner


def _rests(sol):
    """At rest at the end: no velocity (< 1e-12) and the tilt within the velocity-level law's drift
    of the positions at the accumulation of impacts (< 1e-5 rad; measured 2e-7, as in 2-D)."""
    assert np.abs(sol.udot[-100:]).max() < 1e-12
    assert np.abs(sol.u[-1]).max() < 1e-5
    assert sol.stats["impacts"][-1]["time"] < sol.t[-1] - 0.5


# ---------------------------------------------------------------------- (d): a shaking base
@pytest.mark.parametrize("direction, factor, lifts", [("ux", 0.98, False), ("ux", 1.05, True),
                                                      ("uy", 0.98, False), ("uy", 1.05, True)])
def test_a_box_on_a_shaking_base_lifts_only_above_g_b_over_h(direction, factor, lifts):
    """A one-sine pulse a_g along x (y): below g bx / h (g by / h) nothing moves (|u| < 1e-12,
    measured 5e-18), the corners carry the weight (1.3e-15) and none unloads or changes; above it
    the box rocks in that plane only (the other tilt measured below 4e-18)."""
    st, model, box = _box()
    threshold = box.uplift_acceleration[0 if direction == "ux" else 1]
    block = box.plane("y" if direction == "ux" else "x")
    wp = 4.0 * block.p
    term = rigid3d.ground_motion(st, one_sine_pulse(factor * threshold, wp), direction)
    sol = _run(st, model, box, None, dt=1e-3, t_end=2 * math.pi / wp + 0.5, extra=[term])
    res = block_results(st, sol, "B")
    if lifts:
        assert res["peak_uplift"] > 1e-5 and not res["overturned"]
        other = "B.base.rx" if direction == "ux" else "B.base.ry"
        assert np.abs(sol.dof(other)).max() < 1e-15
    else:
        assert np.abs(sol.u).max() < 1e-12 and res["peak_uplift"] < 1e-12
        assert sol.v.min() > 0.0 and sol.stats["contact_changes"] == 0     # every corner carries (no chatter)
        np.testing.assert_allclose(sol.v.sum(axis=1), box.W, rtol=1e-12)


# ---------------------------------------------------------------------- (e): refusals
def test_refusals():
    fr = Frame3D()
    fr.node("c", 0.0, 0.0, 0.6)
    for kw, message in [(dict(width_x=0.0), "width_x=0.0 must be finite and > 0"),
                        (dict(width_y=-1.0), "width_y=-1.0"), (dict(height=0.0), "height=0.0"),
                        (dict(restitution=1.5), r"restitution=1.5 must lie in \[0, 1\]"),
                        (dict(restitution=-0.1), "restitution=-0.1"),
                        (dict(mu=-0.5), "mu=-0.5 must be finite and >= 0"),
                        (dict(mu=0.5, facets=3), "facets=3 is not valid"),
                        (dict(facets=8), "facets=8 is a friction parameter")]:
        args = dict(width_x=0.4, width_y=0.4, height=1.2, mass=1.0) | kw
        with pytest.raises(ValueError, match=message):
            fr.rigid_box("B", "c", **args)
    fr.node(1, 0.0, 0.0, 0.0)
    fr.mass(1, 1.0)
    with pytest.raises(ValueError, match="restitution=2"):
        fr.contact("k", 1, restitution=2)
    with pytest.raises(ValueError, match="mu=-0.3 must be finite and >= 0"):
        fr.contact("k", 1, mu=-0.3)
    with pytest.raises(ValueError, match="not a normal"):
        fr.contact("k", 1, direction="rx")
    fr2 = Frame3D()
    fr2.node("c", 0.0, 0.0, 0.6)
    fr2.rigid_box("B", "c", width_x=0.4, width_y=0.4, height=1.2, mass=1.0)
    fr2.p_delta()
    with pytest.raises(ValueError, match="p_delta with rigid contacts"):
        fr2.build()


def test_methods_without_an_impact_law_are_refused():
    st, model, box = _box()
    load = LoadHistory(st.gravity(box.g))
    with pytest.raises(ValueError, match="no impact law.*moreau-jean"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="event", initial="rest")
    for method in ("cq", "modal"):
        with pytest.raises(ValueError, match="not stable by itself"):
            ul.solve(model, load, dt=1e-3, t_end=0.01, method=method, initial="rest")
    with pytest.warns(UserWarning, match="reverses the velocity"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="direct", rule="trapezoidal", initial="rest")


def test_a_ball_on_a_3d_floor_bounces_by_newtons_law():
    """Frame3D.contact: a mass dropped from H on a rigid floor along uz, e = 0.5: the first impact at
    sqrt(2 H / g), the velocity reversed times e (1e-9)."""
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.support(1, ux=True, uy=True, uz=False)
    fr.mass(1, 2.0)
    fr.contact("floor", 1, gap=1.0, restitution=0.5)
    st = fr.build()
    sol = ul.solve(st.to_model(), LoadHistory(st.gravity(9.81)), dt=1e-3, t_end=0.8, method="moreau-jean",
                   rule="trapezoidal", initial="rest")
    first = sol.stats["impacts"][0]
    assert first["time"] == pytest.approx(math.sqrt(2 / 9.81), abs=1e-9)
    assert first["after"][0] == pytest.approx(-0.5 * first["before"][0], rel=1e-9)
    assert rigid.RigidContact("x", 1, (("uz", 1.0),), 0.0).restitution == 0.0


# ---------------------------------------------------------------------- model files
EXAMPLES = __import__("pathlib").Path(__file__).resolve().parents[1] / "examples"


def test_the_model_file_of_a_rocking_box_is_the_api_box_and_runs(tmp_path):
    """examples/rocking_box.toml ([[rigid_blocks]] of a 3-D frame: width, width_y) builds the box of
    Frame3D.rigid_box and runs through unilateral.run with moreau-jean: the rocking in the summary,
    the energy balance closed (measured 6e-14), the corners' forces in the vertical base force."""
    import json

    from unilateral.analysis.run import run_model_file
    from unilateral.modelfile import load_model_file

    spec = load_model_file(EXAMPLES / "rocking_box.toml")
    box = spec.structure.rigid.blocks["cabinet"]
    assert (box.bx, box.by, box.h, box.mass) == (0.3, 0.45, 0.9, 2.0)
    fr = Frame3D()
    fr.node("centre", 0.0, 0.0, 0.9)
    fr.rigid_box("cabinet", "centre", width_x=0.6, width_y=0.9, height=1.8, mass=2.0)
    model = fr.build().to_model()
    assert spec.model.constraint_names == model.constraint_names == [f"cabinet.{c}" for c in ("sw", "se", "ne", "nw")]
    for key in ("M", "K"):
        np.testing.assert_allclose(getattr(spec.model, key).toarray(), getattr(model, key).toarray(), rtol=1e-15)
    np.testing.assert_array_equal(spec.model.F, model.F)
    run_model_file(EXAMPLES / "rocking_box.toml", tmp_path / "out", figures=(), t_end=2.5)
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert summary["method"] == "moreau-jean" and summary["success"]
    results = summary["results"]["unilateral"]
    rocking = results["rigid_contacts"]["blocks"]["cabinet"]
    assert 0.05 < rocking["peak_rotation"] < box.bx / box.h and not rocking["overturned"]
    assert rocking["impacts"] > 2 and rocking["impact_loss"] > 0
    assert results["energy"]["max_relative_error"] < 1e-10
    assert results["energy"]["contact_dissipated"] == pytest.approx(rocking["impact_loss"], rel=1e-9)
    assert results["base_forces"]["Fz"]["max"] > box.W > results["base_forces"]["Fz"]["min"] > 0


def _box_file(tmp_path, table):
    text = ('[units]\nlength = "m"\nforce = "kN"\ntime = "s"\n\n[frame]\ndimensions = 3\n\n'
            '[[nodes]]\nid = 1\nx = 0.0\ny = 0.0\nz = 0.6\n\n' + table
            + '\n[loads.gravity]\ng = 9.81\n\n[analysis]\ndt = 0.001\nt_end = 0.5\nbilateral_reference = false\n'
            'initial = "rest"\nmethod = "moreau-jean"\nrule = "trapezoidal"\n')
    path = tmp_path / "m.toml"
    path.write_text(text)
    return path


BOX = '[[rigid_blocks]]\nname = "B"\nnode = 1\nwidth = 0.4\nwidth_y = 0.6\nheight = 1.2\nmass = 1.0\n'


@pytest.mark.parametrize("table, message", [
    (BOX.replace("width_y = 0.6", "width_y = 0.0"), "rigid_blocks[0].width_y"),
    (BOX + "restitution = 1.5\n", "rigid_blocks[0].restitution"),
    (BOX + "mu = -0.3\n", "rigid_blocks[0].mu"),
    (BOX + "mu = 0.3\nfacets = 5\n", "rigid_blocks[0]: rigid_box 'B': facets=5 is not valid"),
    (BOX.replace("width_y = 0.6\n", ""), "rigid_blocks[0].width_y"),
    ('[[contacts]]\nname = "c"\nnode = 1\nfacets = 8\n', "contacts[0]: contact 'c': facets=8 is a friction"),
    ('[[contacts]]\nname = "c"\nnode = 9\n', "no node 9"),
])
def test_model_file_bad_3d_rigid_tables_are_named(tmp_path, table, message):
    from unilateral.modelfile import ModelFileError, load_model_file

    with pytest.raises(ModelFileError, match=__import__("re").escape(message)):
        load_model_file(_box_file(tmp_path, table))


def test_a_3d_model_file_contact_bounces_by_its_restitution(tmp_path):
    from unilateral.modelfile import load_model_file

    spec = load_model_file(_box_file(tmp_path, '[[supports]]\nnode = 1\nuz = false\n[[masses]]\nnode = 1\nm = 1.0\n'
                                               '[[contacts]]\nname = "floor"\nnode = 1\ngap = 0.2\nrestitution = 0.5\n'))
    sol = ul.solve(spec.model, spec.load, dt=1e-3, t_end=0.5, method="moreau-jean", rule="trapezoidal",
                   initial="rest")
    first = sol.stats["impacts"][0]
    assert first["time"] == pytest.approx(math.sqrt(2 * 0.2 / 9.81), abs=1e-12)
    assert first["after"][0] == pytest.approx(-0.5 * first["before"][0], rel=1e-12)


def test_a_3d_model_file_box_needs_vertical_gravity(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file

    path = _box_file(tmp_path, BOX)
    path.write_text(path.read_text().replace("g = 9.81\n", "g = 9.81\ndirection = [0.0, -1.0, 0.0]\n"))
    with pytest.raises(ModelFileError, match=r"rigid_blocks\[0\]: a rigid box needs gravity along -z"):
        load_model_file(path)
