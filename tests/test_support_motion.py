"""Multiple-support excitation (``Frame2D.support_motion``): the total motion of a structure whose
supports move, checked against a closed form, an exact identity and OpenSees's MultipleSupport."""

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.loads import Constant, Tabulated
from unilateral.structure import Frame2D, Frame3D

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from opensees_frames import opensees_environment  # noqa: E402


def simply_supported(nel=6, L=6.0):
    fr = Frame2D()
    for k in range(nel + 1):
        fr.node(k, L * k / nel, 0.0)
    fr.support(0, ux=True, uy=True)
    fr.support(nel, ux=False, uy=True)
    for k in range(nel):
        fr.beam(f"b{k}", k, k + 1, E=2e8, A=0.01, I=1e-4)
    for k in range(1, nel):
        fr.mass(k, 1.0)
    return fr


def test_a_support_moved_slowly_gives_the_rigid_rotation():
    """Quasi-static: the beam follows the rigid rotation ``uy = D x / L``, ``rz = D / L``, unbent."""
    nel, L, D, T = 6, 6.0, 0.01, 20.0
    fr = simply_supported(nel, L)
    t = np.linspace(0.0, T, 401)
    fr.support_motion(nel, "uy", Tabulated(t, D * (t / T) ** 2 * (3 - 2 * t / T)))
    st = fr.build()
    sol = ul.solve(st.to_model(), t_end=T, dt=0.005)
    assert sol.success
    uy = np.array([st.node_displacement(sol, k, "uy")[-1] for k in range(nel + 1)])
    assert uy[-1] == D                                              # the imposed motion itself
    np.testing.assert_allclose(uy, D * np.arange(nel + 1) / nel, rtol=0, atol=1e-4 * D)    # measured 6e-6 D
    np.testing.assert_allclose(st.node_displacement(sol, 0, "rz")[-1], D / L, rtol=1e-4)


def portal(*, hinges=True):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0); fr.node(2, 6.0, 0.0); fr.node(3, 0.0, 4.0); fr.node(4, 6.0, 4.0)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.support(2, ux=True, uy=True, rz=True)
    fr.beam("c1", 1, 3, E=2e8, A=0.02, I=2e-4)
    fr.beam("c2", 2, 4, E=2e8, A=0.02, I=2e-4)
    fr.beam("g", 3, 4, E=2e8, A=0.02, I=4e-4)
    fr.mass(3, 20.0); fr.mass(4, 20.0)
    if hinges:
        fr.hinge("h1", "c1", "i", My=60.0)
        fr.hinge("h2", "c2", "i", My=60.0)
    return fr


@pytest.mark.parametrize("rule", ["trapezoidal", "bdf2"])
def test_supports_moving_alike_equal_a_ground_motion_plus_the_translation(rule):
    """``u_total = y + r u_g`` exactly, ``y`` the response relative to the ground under ``a_g``: both
    rules are exact for the quadratic ``u_g = a t^2 / 2`` of a constant ``a_g``; the hinges yield."""
    a, T, dt = 4.0, 1.5, 0.005
    moving = portal()
    for node in (1, 2):
        moving.support_motion(node, "ux", lambda t: 0.5 * a * np.asarray(t) ** 2)
    st = moving.build()
    total = ul.solve(st.to_model(), t_end=T, dt=dt, rule=rule, method="direct")
    fixed = portal().build()
    relative = ul.solve(fixed.to_model(), ul.loads.LoadHistory(np.zeros(fixed.n), [fixed.ground_motion(Constant(a))]),
                        t_end=T, dt=dt, rule=rule, method="direct", initial="rest")
    assert total.success and relative.success
    assert np.abs(relative.v).max() > 1e-3                          # the hinges yielded
    ug = 0.5 * a * total.t ** 2
    r = fixed.influence("ux")
    peak = np.abs(relative.u).max()
    assert np.abs(total.u - (relative.u + np.outer(ug, r))).max() <= 1e-9 * ug[-1]
    assert np.abs(total.v - relative.v).max() <= 1e-9 * np.abs(relative.v).max()
    assert peak > 1e-3
    np.testing.assert_allclose(st.node_displacement(total, 1, "ux"), ug)


def pounding_on_a_moving_abutment():
    """A cantilever whose base moves, pounding on an abutment that moves otherwise (both in ux)."""
    dt, steps = 0.005, 600
    t = dt * np.arange(steps + 1)
    base = 0.02 * np.sin(2 * np.pi * t / 0.7) * np.exp(-0.5 * t)
    abutment = 0.03 * np.sin(2 * np.pi * (t - 0.1) / 0.9) * (t > 0.1)
    return dt, steps, t, base, abutment


def ours_pounding(method="direct", *, rule="trapezoidal", c=0.0):
    st = pounding_structure(c=c)
    dt, steps = pounding_on_a_moving_abutment()[:2]
    sol = ul.solve(st.to_model(), t_end=steps * dt, dt=dt, rule=rule, method=method)
    assert sol.success
    return st, sol


def pounding_structure(*, c=0.0):
    dt, steps, t, base, abutment = pounding_on_a_moving_abutment()
    fr = Frame2D()
    fr.node(1, 0.0, 0.0); fr.node(2, 0.0, 3.0); fr.node(3, 0.0, 3.0)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.support(3, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=30e6, A=0.09, I=6.75e-4)
    fr.mass(2, 10.0)
    fr.gap("gap", 2, 3, 5e4, gap=0.01, direction="ux", c=c)
    fr.rayleigh(a0=0.2)
    fr.support_motion(1, "ux", Tabulated(t, base))
    fr.support_motion(3, "ux", Tabulated(t, abutment))
    return fr.build()


@pytest.mark.parametrize("rule", ["trapezoidal", "bdf2", "bdf1"])
@pytest.mark.parametrize("c", [0.0, 300.0])
def test_energy_balance_with_moving_supports_closes(rule, c):
    """``W_in + W_s = dT + dU + D`` with the work of the moving supports ``W_s = -int theta'^T sigma dt``
    (paired as the rule, ``theta`` at each step's time): an exact identity of the discrete equations,
    also with a Kelvin gap (``c``) on the moving abutment (``sigma`` then has ``-E_v theta'``)."""
    from unilateral.analysis.energy import energy_balance
    from unilateral.structure import forces as F

    st, sol = ours_pounding(rule=rule, c=c)
    assert sol.stats["contact_changes"] >= 4
    h = F.Histories.from_solution(st, sol, rule)
    e = energy_balance(st, h, np.zeros((len(sol.t), st.n)), rule=rule)
    assert e["exact"] and np.all(e["input_work"] == 0.0)           # no load: the supports do all the work
    assert e["support_work"][-1] > 1.0                              # measured 3.8-4.3 (c=0)
    assert np.abs(e["balance_error"]).max() <= 1e-9 * np.abs(e["support_work"]).max()      # measured <= 2e-13
    if c:
        assert e["contact_dissipated"][-1] > 0.1                   # the gap's dashpot dissipates
    with pytest.raises(ValueError, match="t: the energy balance with support motions needs the 601 times"):
        energy_balance(st, F.Histories(sol.t[:-1], *(getattr(h, k) for k in ("u", "udot", "uddot", "v", "vdot"))),
                       np.zeros((len(sol.t), st.n)), rule=rule)


OPENSEES = """
import json, sys
import openseespy.opensees as ops
a = json.loads(sys.stdin.read())
ops.wipe(); ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0); ops.node(2, 0.0, 3.0); ops.node(3, 0.0, 3.0)
ops.fix(1, 1, 1, 1); ops.fix(3, 1, 1, 1)
ops.mass(2, 10.0, 10.0, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 2, 0.09, 30e6, 6.75e-4, 1)
ops.uniaxialMaterial('ElasticPPGap', 1, 5e4, -1e12, -0.01)
ops.element('zeroLength', 2, 2, 3, '-mat', 1, '-dir', 1)
ops.rayleigh(0.2, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 10, '-dt', a['dt'], '-values', *a['base'])
ops.timeSeries('Path', 11, '-dt', a['dt'], '-values', *a['abutment'])
ops.pattern('MultipleSupport', 1)
ops.groundMotion(1, 'Plain', '-disp', 10)
ops.groundMotion(2, 'Plain', '-disp', 11)
ops.imposedMotion(1, 1, 1)
ops.imposedMotion(3, 1, 2)
ops.constraints('Transformation'); ops.numberer('RCM'); ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100); ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25); ops.analysis('Transient')
ux, force = [0.0], [0.0]
for k in range(a['steps']):
    assert ops.analyze(1, a['dt']) == 0
    ux.append(ops.nodeDisp(2, 1)); force.append(ops.eleResponse(2, 'basicForce')[0])
print(json.dumps({'ux': ux, 'force': force}))
"""


@pytest.mark.skipif(opensees_environment() is None, reason="openseespy is not installed (pip install '.[test]')")
def test_pounding_on_a_moving_abutment_equals_opensees_multiple_support():
    dt, steps, t, base, abutment = pounding_on_a_moving_abutment()
    payload = json.dumps({"dt": dt, "steps": steps, "base": base.tolist(), "abutment": abutment.tolist()})
    proc = subprocess.run([sys.executable, "-c", OPENSEES], input=payload, capture_output=True, text=True,
                          env=opensees_environment(), timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    theirs = json.loads(proc.stdout.strip().splitlines()[-1])
    st, sol = ours_pounding()
    ux = st.node_displacement(sol, 2, "ux")
    force = -st.element_forces(sol.t, sol.u, sol.v)[:, 0]          # compression positive, as ElasticPPGap's
    assert sol.stats["contact_changes"] >= 4                        # it pounds, and the abutment moves away
    assert np.abs(ux - theirs["ux"]).max() <= 1e-8 * np.abs(theirs["ux"]).max()
    assert np.abs(force - np.abs(theirs["force"])).max() <= 1e-8 * np.abs(theirs["force"]).max()


@pytest.mark.parametrize("method", ["cq", "modal"])
def test_every_method_solves_a_moving_support(method):
    _, reference = ours_pounding("direct")
    _, sol = ours_pounding(method)
    assert np.abs(sol.u - reference.u).max() <= 1e-8 * np.abs(reference.u).max()


def test_frame3d_moving_base():
    """3-D: a column whose base moves in x follows it quasi-statically when the motion is slow."""
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0); fr.node(2, 0.0, 0.0, 3.0)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("col", 1, 2, E=2e8, G=8e7, A=0.01, Iy=1e-4, Iz=1e-4, J=1e-4, vecxz=(1.0, 0.0, 0.0))
    fr.mass(2, 1.0)
    T = 20.0
    t = np.linspace(0.0, T, 401)
    fr.support_motion(1, "ux", Tabulated(t, 0.01 * (t / T) ** 2 * (3 - 2 * t / T)))
    st = fr.build()
    sol = ul.solve(st.to_model(), t_end=T, dt=0.01)
    assert abs(st.node_displacement(sol, 2, "ux")[-1] - 0.01) <= 1e-5


def test_bad_support_motions_are_refused_by_name():
    fr = portal(hinges=False)
    with pytest.raises(ValueError, match="free DOF"):
        fr.support_motion(3, "ux", lambda t: 0.0)
    with pytest.raises(ValueError, match="dof='uz' is not a DOF"):
        fr.support_motion(1, "uz", lambda t: 0.0)
    with pytest.raises(TypeError, match="displacement must be a time function"):
        fr.support_motion(1, "ux", 0.1)
    fr.support_motion(1, "ux", lambda t: 0.0)
    with pytest.raises(ValueError, match="already has a support motion"):
        fr.support_motion(1, "ux", lambda t: 0.0)
    fr.rayleigh(a0=0.1, a1=0.01)
    with pytest.raises(ValueError, match="stiffness-proportional Rayleigh"):
        fr.build()


@pytest.mark.parametrize("c", [0.0, 300.0])
def test_base_force_operator_with_moving_supports_equals_the_reactions(c):
    """``X x + X_d x' + c(t)`` with ``c(t) = -P^T (E theta(t) + E_v theta'(t))`` equals the summed
    reactions (:func:`base_forces` of :func:`reactions`) at every step, moments about a point off the
    supports; the pounding model (with a Kelvin gap on the moving abutment for ``c > 0``) and the
    portal whose hinges yield as one support sways and the other settles."""
    from unilateral.structure import forces as F

    runs = [ours_pounding(c=c)]
    fr = portal()
    fr.support_motion(1, "ux", lambda t: 0.01 * np.sin(8.0 * np.asarray(t)))
    fr.support_motion(2, "uy", lambda t: -0.02 * np.asarray(t))
    st = fr.build()
    runs.append((st, ul.solve(st.to_model(), t_end=0.6, dt=0.005, rule="trapezoidal", method="direct")))
    for st, sol in runs:
        assert sol.success
        h = F.Histories.from_solution(st, sol, "trapezoidal")
        point = (1.5, -2.0)
        reference = F.base_forces(st, F.reactions(st, h), point)
        operator = F.BaseForceOperator.of(st, point)
        ours = operator(F.StateRows.of_solution(sol, "trapezoidal"))
        assert np.abs(reference["base_shear"]).max() > 1.0
        for key, value in reference.items():
            scale = max(np.abs(value).max(), 1.0)
            assert np.abs(ours[key] - value).max() <= 1e-11 * scale, key
        np.testing.assert_allclose(operator.base_shear(F.StateRows.of_solution(sol, "trapezoidal")),
                                   reference["base_shear"], rtol=0, atol=1e-11 * np.abs(reference["base_shear"]).max())
    with pytest.raises(ValueError, match="state: the base forces with support motions need the"):
        operator(F.StateRows.of(h.u, h.udot, h.v, h.vdot))


def test_model_file_support_motions_equal_the_library(tmp_path):
    """examples/support_motion.toml ([[loads.support_motion]] with record tables) gives the run of
    :func:`ours_pounding` (its records are the same samples) to round-off, and its energy balance
    closes with the work of the moving supports."""
    import unilateral.modelfile as mf

    example = Path(__file__).resolve().parents[1] / "examples" / "support_motion.toml"
    spec = mf.load_model_file(example)
    st, sol = ours_pounding()
    ours = ul.solve(spec.structure.to_model(), t_end=3.0, dt=0.005, rule="trapezoidal", method="direct")
    assert np.abs(ours.u - sol.u).max() <= 1e-12 * np.abs(sol.u).max()
    summary = ul.run(example, tmp_path / "out", figures=())
    assert summary["success"], summary["message"]
    assert "support_work" in json.dumps(json.loads((tmp_path / "out" / "summary.json").read_text()))
    import tomllib

    data = tomllib.loads(example.read_text(encoding="utf-8"))
    data["loads"]["support_motion"][0]["dof"] = "uz"
    with pytest.raises(mf.ModelFileError, match=r"loads.support_motion\[0\]: .*dof='uz' is not a DOF"):
        mf.build_model_spec(data, example)
    data["loads"]["support_motion"][0].update(dof="ux", node=2)
    with pytest.raises(mf.ModelFileError, match=r"loads.support_motion\[0\]: .*ux is a free DOF"):
        mf.build_model_spec(data, example)


def test_study_worker_results_with_moving_supports():
    """The study worker's operators (energy error, peak base shear from StateRows) take support motions."""
    from unilateral.batch.worker import FrameOperators, FrameResults
    from unilateral.loads import LoadHistory
    from unilateral.structure import forces as F

    st, sol = ours_pounding()
    frame = FrameResults(sol, FrameOperators(st), LoadHistory(np.zeros(st.n), ()), "trapezoidal")
    shear = np.abs(F.base_forces(st, F.reactions(st, F.Histories.from_solution(st, sol, "trapezoidal")))["base_shear"])
    assert frame.energy_error() <= 1e-11                                # measured 4e-14
    assert frame.peak_base_shear() == pytest.approx(shear.max(), rel=1e-12)       # 724 kN


def test_model_file_3d_moving_base_follows_a_slow_ramp():
    """``[[loads.support_motion]]`` of a 3-D frame: a column whose base is ramped 10 mm along y over
    10 s (``type = "ramp"``, ``scale``) follows it quasi-statically."""
    import unilateral.modelfile as mf

    data = {"units": {"length": "m", "force": "kN", "time": "s"}, "frame": {"dimensions": 3},
            "nodes": [{"id": 1, "x": 0.0, "y": 0.0, "z": 0.0}, {"id": 2, "x": 0.0, "y": 0.0, "z": 3.0}],
            "supports": [{"node": 1, "ux": True, "uy": True, "uz": True, "rx": True, "ry": True, "rz": True}],
            "elements": [{"type": "beam", "name": "col", "node_i": 1, "node_j": 2, "E": 2e8, "G": 8e7, "A": 0.01,
                          "Iy": 1e-4, "Iz": 1e-4, "J": 1e-4, "vecxz": [1.0, 0.0, 0.0]}],
            "masses": [{"node": 2, "m": 1.0}],
            "loads": {"support_motion": [{"node": 1, "dof": "uy", "scale": 0.01,
                                          "displacement": {"type": "ramp", "t_ramp": 10.0}}]},
            "analysis": {"dt": 0.01, "t_end": 20.0}}
    spec = mf.build_model_spec(data, Path("column.toml"))
    sol = ul.solve(spec.structure.to_model(), t_end=20.0, dt=0.01)
    assert sol.success
    assert abs(spec.structure.node_displacement(sol, 2, "uy")[-1] - 0.01) <= 1e-5           # measured 5e-9
