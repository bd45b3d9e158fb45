"""The extensions of ``unilateral.opensees`` (``footing``, ``springFooting``, ``kelvinContact``,
``bilateral``): each script's response is that of the same model built with Frame2D and solved by
:func:`unilateral.solve` (to round-off), and bad input is refused by name."""

import numpy as np
import pytest

import unilateral.opensees as ops
from unilateral import solve
from unilateral.opensees import OpenSeesRefused
from unilateral.structure import Frame2D, Frame3D

DT = 0.005
PULSE = ((0.0, 0.01, 0.1, 0.11, 100.0), (0.0, 1.0, 1.0, 0.0, 0.0))


def pulse(t):
    """The pulse's factor at ``t`` (the Path series of the scripts)."""
    return np.interp(t, *PULSE)


def _transient(steps, record):
    """Hold the static loads, add the pulse (pattern 2 of the caller's loads) and step ``steps`` times,
    returning ``record()`` after each step (the first row: the static state)."""
    rows = [record()]
    ops.analysis("Transient")
    ops.integrator("Newmark", 0.5, 0.25)
    for _ in range(steps):
        assert ops.analyze(1, DT) == 0
        rows.append(record())
    return np.array(rows)


def _static_then_pulse(loads):
    """Gravity (pattern 1) by a static analysis, then the pulse ``loads`` (node, values) from t = 0."""
    ops.analysis("Static")
    assert ops.analyze(1) == 0
    ops.loadConst("-time", 0.0)
    ops.timeSeries("Path", 2, "-time", *PULSE[0], "-values", *PULSE[1])
    ops.pattern("Plain", 2, 2)
    for node, values in loads:
        ops.load(node, *values)


def _load_history(st, steps, gravity, pulses):
    """The Frame2D model's load (steps+1, n): ``gravity`` plus the pulse times ``pulses``."""
    t = DT * np.arange(steps + 1)
    return gravity[None, :] + pulse(t)[:, None] * pulses[None, :]


def _close(a, b, rtol=1e-9):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape
    scale = max(np.abs(b).max(), 1e-300)
    assert np.abs(a - b).max() <= rtol * scale, (np.abs(a - b).max(), scale)


# ---------------------------------------------------------------------- kelvinContact
def _bouncing_script(*, bilateral=False, friction=False):
    """A mass of 10 on a Kelvin contact on the ground, gravity, then an upward (and sideways) pulse."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0 if friction else 1, 0, 1)
    ops.mass(2, 10.0, 10.0, 0.0)
    extra = ("-mu", 0.3, "-kt", 5e3) if friction else ()
    ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", 1e4, "-c", 20.0, "-gap", 0.0, *extra)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -98.1, 0.0)
    _static_then_pulse([(2, (100.0 if friction else 0.0, 500.0, 0.0))])
    if bilateral:
        ops.bilateral(1)
    return _transient(100, lambda: [*ops.nodeDisp(2)[:2], *ops.eleResponse(5, "basicForce"),
                                    ops.eleResponse(5, "opening")[0], *ops.eleForce(5)])


def _bouncing_frame(*, friction=False, bilateral_spring=False):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 0.0)
    fr.support(1, ux=True, uy=True)
    if not friction:
        fr.support(2, ux=True, uy=False)
    fr.mass(2, 10.0)
    if bilateral_spring:
        fr.spring("k", 1, 1e4, j=2, direction="uy")
        fr.dashpot("c", 1, 20.0, j=2, direction="uy")
    else:
        fr.gap("x5", 1, 2, 1e4, gap=0.0, c=20.0, direction="uy", **({"mu": 0.3, "kt": 5e3} if friction else {}))
    st = fr.build()
    f = st.nodal_load(2, ux=100.0 if friction else 0.0, uy=500.0)
    return st, st.to_model(), _load_history(st, 100, st.nodal_load(2, uy=-98.1), f)


def test_kelvin_contact_is_the_frame2d_gap_with_its_dashpot():
    got = _bouncing_script()
    st, model, q = _bouncing_frame()
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="direct", rule="trapezoidal", initial="static")
    uy = sol.u[:, model.dof_names.index("2.uy")]
    k = model.constraint_names.index("x5")
    _close(got[:, 1], uy)
    _close(got[:, 2], sol.psi[:, k])                     # the force with its dashpot's part (psi)
    _close(got[:, 3], sol.v[:, k])
    assert got[:, 3].max() > 1e-2                        # it lifts off: the test sees the contact open
    assert np.all(got[:, 2] <= 1e-9)                     # compression only
    _close(got[:, 4:7], -got[:, 7:10])                   # eleForce: -f at i, +f at j
    _close(got[:, 8], got[:, 2])


def test_kelvin_contact_with_friction():
    got = _bouncing_script(friction=True)
    st, model, q = _bouncing_frame(friction=True)
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="direct", rule="trapezoidal", initial="static")
    names = model.constraint_names
    ux = sol.u[:, model.dof_names.index("2.ux")]
    slip = sol.v[:, names.index("x5.slip+")] - sol.v[:, names.index("x5.slip-")]
    _close(got[:, 0], ux)
    _close(got[:, 1], sol.u[:, model.dof_names.index("2.uy")])
    _close(got[:, 2], sol.psi[:, names.index("x5")])
    # the stick spring's force (tangent of uy: the direction turned clockwise, +x)
    _close(got[:, 3], 5e3 * (ux - slip), rtol=1e-8)
    assert np.all(np.abs(got[:, 3]) <= 0.3 * np.abs(got[:, 2]) * (1 + 1e-9) + 1e-9)   # Coulomb's cone
    assert np.abs(slip).max() > 1e-3


def test_bilateral_reference_is_the_bilateral_spring():
    got = _bouncing_script(bilateral=True)
    st, model, q = _bouncing_frame(bilateral_spring=True)
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="direct", rule="trapezoidal", initial="static")
    _close(got[:, 1], sol.u[:, model.dof_names.index("2.uy")])
    assert np.all(got[:, 3] == 0)                        # held closed
    assert got[:, 2].max() > 1.0                         # it carries tension: the bilateral spring's
    free = _bouncing_script()
    assert free[:, 3].max() > 1e-2                       # the unilateral case lifts off
    ops.bilateral(1)
    ops.wipe()                                           # wipe switches it off
    assert ops._session.analysis.bilateral is False


def test_kelvin_contact_in_3d_is_the_frame3d_gap():
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.0, 0.0, 0.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.fix(2, 1, 1, 0, 1, 1, 1)
    ops.mass(2, 10.0, 10.0, 10.0, 0.0, 0.0, 0.0)
    ops.kelvinContact(5, 1, 2, "-dir", 3, "-k", 1e4, "-c", 20.0, "-gap", 1e-3)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, 0.0, -98.1, 0.0, 0.0, 0.0)
    _static_then_pulse([(2, (0.0, 0.0, 500.0, 0.0, 0.0, 0.0))])
    got = _transient(100, lambda: [ops.nodeDisp(2, 3), *ops.eleResponse(5, "basicForce"),
                                   *ops.eleResponse(5, "opening")])
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, 0.0)
    fr.support(1, ux=True, uy=True, uz=True)
    fr.support(2, ux=True, uy=True, uz=False)
    fr.mass(2, 10.0)
    fr.gap("x5", 1, 2, 1e4, gap=1e-3, c=20.0, direction="uz")
    st = fr.build()
    model = st.to_model()
    q = _load_history(st, 100, st.nodal_load(2, uz=-98.1), st.nodal_load(2, uz=500.0))
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="direct", rule="trapezoidal", initial="static")
    k = model.constraint_names.index("x5")
    _close(got[:, 0], sol.u[:, model.dof_names.index("2.uz")])
    _close(got[:, 1], sol.psi[:, k])
    _close(got[:, 2], sol.v[:, k])
    assert got[0, 0] < -1e-3 and got[:, 2].max() > 1e-2          # closed under gravity (past its gap), then open


def test_rigid_contact_is_frame2d_contact_by_moreau_jean():
    """A mass on a spring resting on a rigid stop 0.05 below (Newton's e = 0.5), thrown up by a pulse:
    the script is Frame2D.contact solved by method='moreau-jean' (theta = 1/2) step for step."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 0, 1)
    ops.mass(2, 0.0, 10.0, 0.0)
    ops.uniaxialMaterial("Elastic", 1, 1e3)
    ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 2)
    ops.rigidContact(5, 2, "-dir", 2, "-gap", 0.05, "-e", 0.5)
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -98.1, 0.0)
    _static_then_pulse([(2, (0.0, 700.0, 0.0))])
    got = _transient(200, lambda: [ops.nodeDisp(2, 2), *ops.eleResponse(5, "contactForce"),
                                   *ops.eleResponse(5, "opening"), *ops.eleForce(5)])
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 0.0)
    fr.support(1, ux=True, uy=True)
    fr.support(2, ux=True, uy=False)
    fr.mass(2, 10.0)
    fr.spring("k", 1, 1e3, j=2, direction="uy")
    fr.contact("x5", 2, direction="uy", gap=0.05, restitution=0.5)
    st = fr.build()
    model = st.to_model()
    q = _load_history(st, 200, st.nodal_load(2, uy=-98.1), st.nodal_load(2, uy=700.0))
    sol = solve(model, q, dt=DT, t_end=200 * DT, method="moreau-jean", rule="trapezoidal", initial="static")
    uy = sol.u[:, model.dof_names.index("2.uy")]
    _close(got[:, 0], uy)
    _close(got[:, 1], sol.v[:, model.constraint_names.index("x5")])
    _close(got[:, 2], uy + 0.05)                                   # the opening
    _close(got[:, 4], -got[:, 1])                                  # eleForce: minus the ground's force
    assert got[0, 1] == pytest.approx(98.1 - 50.0)                 # resting on the stop under gravity
    opened = np.flatnonzero(got[:, 2] > 1e-2)
    assert opened.size and np.any(got[opened[0]:, 1] > 0), got[opened[0]:, 1:3]   # it lifts off and lands again


def test_a_body_on_rigid_contacts_only_falls_from_rest_and_has_no_static_state():
    """A mass 0.1 above a rigid contact, nothing else holding it: a static analysis is refused by name;
    from rest it falls freely (the trapezoidal rule's discrete free fall) until it lands, and then rests
    on the contact, which carries its weight."""
    def model():
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(1, 0.0, 0.0)
        ops.fix(1, 1, 0, 1)
        ops.mass(1, 0.0, 10.0, 0.0)
        ops.rigidContact(5, 1, "-dir", 2, "-gap", 0.1)
        ops.timeSeries("Constant", 2)
        ops.pattern("Plain", 1, 2)
        ops.load(1, 0.0, -98.1, 0.0)
    model()
    ops.analysis("Static")
    with pytest.raises(OpenSeesRefused, match=r"analyze \(Static\) with a rigid contact.*no static state"):
        ops.analyze(1)
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.fix(1, 1, 0, 1)
    ops.mass(1, 0.0, 10.0, 0.0)
    ops.rigidContact(5, 1, "-dir", 2, "-gap", 0.1)
    ops.timeSeries("Path", 1, "-time", 0.0, 1e-9, 100.0, "-values", 0.0, 1.0, 1.0)
    ops.pattern("Plain", 1, 1)
    ops.load(1, 0.0, -98.1, 0.0)
    ops.analysis("Transient")
    ops.integrator("Newmark", 0.5, 0.25)
    u = []
    for _ in range(40):
        assert ops.analyze(1, 0.01) == 0
        u.append(ops.nodeDisp(1, 2))
    # the trapezoidal rule's free fall with the weight switched on just after t = 0 (the accelerations
    # 0, then -g): v_k = -g dt (k - 1/2), u_k = -g dt^2 (k (k - 1) / 2 + 1/4)
    k = np.arange(1, 41)
    fall = -9.81 * 0.01 ** 2 * (k * (k - 1) / 2 + 0.25)
    free = fall > -0.1
    free[np.flatnonzero(free)[-1]] = False                  # (kept clear of the step of the impact)
    _close(np.array(u)[free], fall[free], rtol=1e-9)
    assert u[-1] == pytest.approx(-0.1, abs=1e-12)
    assert ops.eleResponse(5, "contactForce")[0] == pytest.approx(98.1, rel=1e-6)


def test_a_script_with_extensions_is_not_converted(tmp_path):
    from unilateral.opensees.convert import convert_script
    from unilateral.opensees.convert_frame import NotConvertible

    script = tmp_path / "model.py"
    script.write_text("import openseespy.opensees as ops\n"
                      "ops.model('basic', '-ndm', 2, '-ndf', 3)\n"
                      "ops.node(1, 0.0, 0.0); ops.node(2, 0.0, 0.0); ops.fix(1, 1, 1, 1); ops.fix(2, 1, 0, 1)\n"
                      "ops.mass(2, 0.0, 10.0, 0.0)\n"
                      "ops.kelvinContact(5, 1, 2, '-dir', 2, '-k', 1e4, '-c', 20.0)\n"
                      "ops.analysis('Transient'); ops.analyze(10, 0.01)\n")
    with pytest.raises(NotConvertible, match=r"extension elements \[5\]"):
        convert_script(script, tmp_path / "model.toml")


# ---------------------------------------------------------------------- springFooting
def _column_script(footing, steps=100, pulse_force=300.0):
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 10.0)
    ops.node(2, 0.0, 0.0)
    ops.mass(1, 40.0, 40.0, 0.0)
    ops.geomTransf("Linear", 1)
    ops.element("elasticBeamColumn", 1, 2, 1, 1e12, 1.0, 1e9, 1)
    footing()
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(1, 0.0, -400.0, 0.0)
    _static_then_pulse([(1, (pulse_force, 0.0, 0.0))])
    return _transient(steps, lambda: [*ops.nodeDisp(1), *ops.nodeDisp(2)[1:], *ops.eleForce(7),
                                      *ops.eleResponse(7, "uplift"), *ops.eleResponse(7, "contactForce")])


def _column_frame(add):
    fr = Frame2D()
    fr.node(1, 0.0, 10.0)
    fr.node(2, 0.0, 0.0)
    fr.beam("column", 2, 1, E=1.0, A=1e12, I=1e9)
    fr.mass(1, 40.0)
    add(fr)
    return fr.build()


def test_spring_footing_is_frame2d_spring_footing():
    def script():
        ops.fix(2, 1, 0, 0)
        ops.springFooting(7, 2, 4.0, 2.5e4, "-length", 1.0, "-c", 500.0, "-springs", 4, "-qult", 250.0)
    got = _column_script(script, pulse_force=150.0)

    def frame(fr):
        fr.support(2, ux=True, uy=False)
        fr.spring_footing("x7", 2, width=4.0, k=2.5e4, length=1.0, c=500.0, springs=4, q_ult=250.0)
    st = _column_frame(frame)
    model = st.to_model()
    q = _load_history(st, 100, st.nodal_load(1, uy=-400.0), st.nodal_load(1, ux=150.0))
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="direct", rule="trapezoidal", initial="static")
    names = model.constraint_names
    for col, dof in enumerate(("1.ux", "1.uy", "1.rz", "2.uy", "2.rz")):
        _close(got[:, col], sol.u[:, model.dof_names.index(dof)])
    sigma = sol.psi[:, [names.index(f"x7.{j}") for j in range(1, 5)]]
    x = np.array([-1.5, -0.5, 0.5, 1.5])
    _close(got[:, 12:16], -sigma)                        # contactForce: the springs' compressions
    _close(got[:, 5:8], np.c_[0 * x[0] * sigma[:, 0], sigma.sum(axis=1), sigma @ x])   # eleForce
    _close(got[:, 8:12], sol.v[:, [names.index(f"x7.{j}") for j in range(1, 5)]])
    assert got[:, 8:12].max() > 1e-4                     # an edge lifts off
    assert sol.v[:, [names.index(f"x7.{j}.plastic-") for j in range(1, 5)]].max() > 0   # and the soil yields


# ---------------------------------------------------------------------- footing on a soil medium
def _soil_case(soil_args, spec, *, steps=100, pulse_force=300.0, sliding=False, pieces=None):
    extra = ("-mu", 0.3) if sliding else ()

    def script():
        ops.footing(7, 2, 10.0, 10.0, *soil_args, "-patches", 4, *extra)
        if sliding:                                      # the footing's own mass (its rigid-body slide)
            ops.mass(2, 5.0, 5.0, 5.0)
    got = _column_script(script, steps=steps, pulse_force=pulse_force) if pieces is None else pieces(script)

    def frame(fr):
        fr.foundation("x7", 2, width=10.0, length=10.0, patches=4, soil=spec,
                      **({"horizontal": "soil", "mu": 0.3} if sliding else {}))
        if sliding:
            fr.mass(2, 5.0, J=5.0)
    st = _column_frame(frame)
    model = st.to_model()
    q = _load_history(st, steps, st.nodal_load(1, uy=-400.0), st.nodal_load(1, ux=pulse_force))
    sol = solve(model, q, dt=DT, t_end=steps * DT, method="auto", rule="trapezoidal", initial="static")
    return got, model, sol


def _check_footing(got, model, sol, rtol=1e-8):
    for col, dof in enumerate(("1.ux", "1.uy", "1.rz", "2.uy", "2.rz")):
        _close(got[:, col], sol.u[:, model.dof_names.index(dof)], rtol=rtol)
    contacts = model.contacts
    c = -sol.psi[:, contacts]
    x = np.array([-3.75, -1.25, 1.25, 3.75])
    _close(got[:, 8:12], sol.v[:, contacts], rtol=rtol)           # uplift of each patch
    _close(got[:, 12:16], c, rtol=rtol)                           # the contact forces
    _close(got[:, 6:8], -np.c_[c.sum(axis=1), c @ x], rtol=rtol)  # eleForce: minus the soil's resultant
    assert got[:, 8:12].max() > 1e-5                              # the footing lifts off


CONES = (["cones", 97.0, 1 / 3, 2.0], {"model": "cones", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0})


def test_footing_on_cones_is_frame2d_foundation():
    _check_footing(*_soil_case(*CONES))


def test_footing_on_winkler_kelvin_patches():
    _check_footing(*_soil_case(["winkler", 150e3, 5e3], {"model": "winkler-kelvin", "k": 150e3, "c": 5e3},
                               pulse_force=400.0))


def test_footing_analysed_in_pieces_past_its_horizon():
    """30 steps, then 70 single steps: the simulation is solved again from its start when its
    horizon is used up, and the steps agree with one solve of 100 steps."""
    def pieces(script):
        rows = []

        def record():
            return [*ops.nodeDisp(1), *ops.nodeDisp(2)[1:], *ops.eleForce(7), *ops.eleResponse(7, "uplift"),
                    *ops.eleResponse(7, "contactForce")]
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(1, 0.0, 10.0)
        ops.node(2, 0.0, 0.0)
        ops.mass(1, 40.0, 40.0, 0.0)
        ops.geomTransf("Linear", 1)
        ops.element("elasticBeamColumn", 1, 2, 1, 1e12, 1.0, 1e9, 1)
        script()
        ops.timeSeries("Constant", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(1, 0.0, -400.0, 0.0)
        _static_then_pulse([(1, (300.0, 0.0, 0.0))])
        rows.append(record())
        ops.analysis("Transient")
        ops.integrator("Newmark", 0.5, 0.25)
        assert ops.analyze(30, DT) == 0
        for _ in range(70):
            assert ops.analyze(1, DT) == 0
        rows.append(record())
        return np.array(rows)
    got, model, sol = _soil_case(*CONES, pieces=pieces)
    for col, dof in enumerate(("1.ux", "1.uy", "1.rz")):
        _close(got[-1, col], sol.u[-1, model.dof_names.index(dof)], rtol=1e-8)


def test_footing_sliding_on_cones():
    got, model, sol = _soil_case(*CONES, sliding=True, pulse_force=600.0)
    _check_footing(got, model, sol)
    ux = sol.u[:, model.dof_names.index("2.ux")] if "2.ux" in model.dof_names else None
    assert ux is not None and np.abs(ux).max() > 0
    h = sol.psi[:, model.shears]
    _close(got[:, 5], -h.sum(axis=1), rtol=1e-8)                  # the soil's horizontal force


def test_footing_bilateral_reference():
    def script():
        ops.footing(7, 2, 10.0, 10.0, *CONES[0], "-patches", 4)
        ops.bilateral(1)
    got = _column_script(script)

    def frame(fr):
        fr.foundation("x7", 2, width=10.0, length=10.0, patches=4, soil=CONES[1])
    st = _column_frame(frame)
    model = st.to_model()
    q = _load_history(st, 100, st.nodal_load(1, uy=-400.0), st.nodal_load(1, ux=300.0))
    sol = solve(model, q, dt=DT, t_end=100 * DT, method="auto", rule="trapezoidal", initial="static",
                bilateral=True)
    _close(got[:, 0], sol.u[:, model.dof_names.index("1.ux")], rtol=1e-8)
    assert np.all(got[:, 8:12] == 0)                              # no uplift
    assert got[:, 12:16].min() < 0                                # the held contacts pull


@pytest.mark.slow
def test_footing_on_a_halfspace_is_frame2d_foundation():
    """60 steps of analyze(1, dt): the script's simulation is solved again over the horizons 1, 3, 9,
    27, 81 (:mod:`unilateral.opensees.soil_analysis`), the reference once over 60 steps; the half-space's
    convolution-quadrature weights of those horizons differ in the last digits (measured: the contact
    forces by 1.8e-7 of their peak, the displacements by less than 1e-8)."""
    args = (["halfspace", 97.0, 1 / 3, 2.0], {"model": "halfspace", "Vs": 97.0, "nu": 1 / 3, "rho": 2.0})
    _check_footing(*_soil_case(*args, steps=60, pulse_force=400.0), rtol=1e-6)


@pytest.mark.slow
def test_footing_on_a_layered_soil_is_frame2d_foundation():
    """A 4 m layer over a half-space ('-layer'); 40 steps of analyze(1, dt), as the half-space's test
    (measured: the contact forces by 1.3e-7 of their peak)."""
    args = (["layered", 300.0, 0.3, 2.0, "-layer", 4.0, 120.0, 0.35, 1.8],
            {"model": "layered", "Vs": 300.0, "nu": 0.3, "rho": 2.0,
             "layers": [{"thickness": 4.0, "Vs": 120.0, "nu": 0.35, "rho": 1.8, "damping": 0.0}]})
    _check_footing(*_soil_case(*args, steps=40, pulse_force=400.0), rtol=1e-6)


# ---------------------------------------------------------------------- bad input
def _model():
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 1.0)


@pytest.mark.parametrize("call, words", [
    (lambda: ops.kelvinContact(5, 1, 2, "-dir", 2), ["kelvinContact(5", "'-k' is missing"]),
    (lambda: ops.kelvinContact(5, 1, 9, "-dir", 2, "-k", 1.0), ["jNode=9", "node 9 is not defined"]),
    (lambda: ops.kelvinContact(5, 1, 2, "-dir", 3, "-k", 1.0), ["'-dir'", "d=3.0", "translation 1..2"]),
    (lambda: ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", -1.0), ["k=-1.0", "> 0"]),
    (lambda: ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", 1.0, "-mu", 0.3), ["'-mu' and '-kt'"]),
    (lambda: ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", 1.0, "-eta", 1.0), ["'-eta'", "valid: '-dir'"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "clay", 1.0), ["footing(7", "soil 'clay'", "'halfspace'"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "halfspace", 97.0, 0.3), ["takes Vs, nu, rho"]),
    (lambda: ops.footing(7, 1, -1.0, 10.0, "cones", 97.0, 0.3, 2.0), ["width=-1.0", "> 0"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "cones", 97.0, 0.3, 2.0, "-patches", 2.5), ["n=2.5", "1..400"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "layered", 300.0, 0.3, 2.0), ["at least one '-layer'"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "cones", 97.0, 0.3, 2.0, "-horizontal", "glue"),
     ["'-horizontal'", "'glue'", "'support', 'cone', 'none'"]),
    (lambda: ops.springFooting(7, 1, 4.0, 1e4, "-springs", 0), ["n=0", "> 0"]),
    (lambda: ops.springFooting(7, 1, 4.0, "soft"), ["k='soft' is not a number"]),
    (lambda: ops.bilateral(2), ["bilateral(2)", "0 or 1"]),
    (lambda: ops.rigidContact(5, 1, "-dir", 2, "-e", 1.5), ["'-e'", "e=1.5", "[0, 1]"]),
    (lambda: ops.rigidContact(5, 1, "-dir", 3), ["'-dir'", "d=3.0"]),
    (lambda: ops.rigidContact(5, 1, "-dir", 2, "-gap", -0.1), ["g=-0.1", ">= 0"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "winkler", 1e5, 0.0, "-damping", 0.05), ["no material damping"]),
    (lambda: ops.footing(7, 1, 10.0, 10.0, "cones", 97.0, 0.3, 2.0, "-mu", 0.3, "-horizontal", "cone"),
     ["one of '-mu', mu or '-horizontal'"]),
])
def test_bad_input_is_refused_by_name(call, words):
    _model()
    with pytest.raises(OpenSeesRefused) as info:
        call()
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_a_tag_is_not_taken_twice_and_3d_footings_are_refused():
    _model()
    ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", 1.0)
    with pytest.raises(OpenSeesRefused, match="element 5 is already defined"):
        ops.springFooting(5, 1, 4.0, 1e4)
    assert ops.getEleTags() == [5]
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    ops.node(1, 0.0, 0.0, 0.0)
    with pytest.raises(OpenSeesRefused, match="2-D extension"):
        ops.footing(7, 1, 10.0, 10.0, "cones", 97.0, 0.3, 2.0)

