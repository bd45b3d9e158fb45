"""A 2-D hinge with a convex multi-linear backbone (``Frame2D.hinge(backbone=...)``): parallel
elastic-perfectly-plastic springs. A cantilever's pushover passes through the backbone's points, a
cyclic one unloads with the initial stiffness and reloads by Masing's rule, a dynamic run balances
its energy and equals OpenSees' ``Parallel`` of ``ElasticPP`` materials in a ``zeroLength`` spring."""

import json
import subprocess
import sys

import numpy as np
import pytest
from test_opensees_module import ENV, needs_opensees

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.pushover import pushover
from unilateral.structure import Frame2D
from unilateral.structure import forces as F

H, E, A, I = 3.0, 30e6, 0.02, 6.75e-4
BACKBONE = [(0.002, 100.0), (0.006, 140.0), (0.02, 160.0)]
K = 100.0 / 0.002


def cantilever(backbone=BACKBONE, hardening=0.0, a0=0.0):
    """A column fixed at its base (node 1) with the hinge at its foot, a mass on its top (node 2)."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, H)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=E, A=A, I=I)
    fr.hinge("h", "col", "i", backbone=backbone, hardening=hardening)
    fr.mass(2, 10.0)
    if a0:
        fr.rayleigh(a0=a0)
    return fr.build()


def hinge_curve(st, r):
    """The hinge's moment (on the beam at its foot: ``P H``) and its rotation ``M/K + sum_s (v_s+ - v_s-)``
    at every point of the pushover ``r``."""
    sign = np.array([1.0 if name.endswith("+") else -1.0 for name in st.constraint_names])
    M = r.load_factor * H
    return M, M / K + r.v @ sign


def test_monotonic_pushover_passes_through_every_point_of_the_backbone():
    st = cantilever()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.12)
    assert r.success, r.message
    assert [(e.name, e.kind) for e in r.events] == [("h.plastic+", "yield"), ("h.plastic2+", "yield"),
                                                    ("h.plastic3+", "yield")]
    M, theta = hinge_curve(st, r)
    for event, (theta_b, M_b) in zip(r.events, BACKBONE):
        assert abs(M[event.point] - M_b) <= 1e-9 * M_b and abs(theta[event.point] - theta_b) <= 1e-9 * theta_b
    assert abs(M[-1] - 160.0) <= 1e-9 * 160.0                              # flat beyond the last point
    # between the points the hinge follows the segments: the tip is the beam in series with the spring
    EI = E * I
    for (t0, m0), (t1, m1) in zip(BACKBONE, BACKBONE[1:]):
        slope = (m1 - m0) / (t1 - t0)
        tip = 1 / (H ** 3 / (3 * EI) + H ** 2 / slope)
        p0, p1 = (e.point for e in r.events if abs(M[e.point] - m0) < 1e-6 or abs(M[e.point] - m1) < 1e-6)
        assert (r.load_factor[p1] - r.load_factor[p0]) / (r.displacement[p1] - r.displacement[p0]) == \
            pytest.approx(tip, rel=1e-9)


def test_cyclic_pushover_unloads_with_the_initial_stiffness_and_reloads_by_masing():
    st = cantilever()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=[0.1, -0.1, 0.1])
    assert r.success, r.message
    M, theta = hinge_curve(st, r)
    turn = next(e.point for e in r.events if e.kind == "unload")
    M0, theta0 = M[turn], theta[turn]
    assert abs(M0 - 160.0) < 1e-9 * 160.0
    reverse = [e.point for e in r.events if e.kind == "yield" and e.name.endswith("-")]
    # Masing: the reverse branch is the backbone doubled, from the turning point: the first spring
    # yields back at (theta0 - 2 theta1, M0 - 2 M1), the second at (theta0 - 2 theta2, M0 - 2 M2)
    for point, (theta_b, M_b) in zip(reverse[:2], BACKBONE):
        assert abs(M[point] - (M0 - 2 * M_b)) <= 1e-9 * M0
        assert abs(theta[point] - (theta0 - 2 * theta_b)) <= 1e-9 * theta0
    assert (M0 - M[reverse[0]]) / (theta0 - theta[reverse[0]]) == pytest.approx(K, rel=1e-9)   # elastic, K
    assert [r.events[k].name for k in range(len(r.events)) if r.events[k].point == reverse[0]] == ["h.plastic-"]


def test_an_asymmetric_backbone_and_hardening_beyond_the_last_point():
    backbone = [(0.002, 100.0), (0.006, 140.0), (-0.003, -150.0), (-0.007, -190.0)]
    st = cantilever(backbone, hardening=0.01)
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=[0.05, -0.05])
    assert r.success, r.message
    M, theta = hinge_curve(st, r)
    first = [e.point for e in r.events if e.kind == "yield" and e.name.endswith("+")]
    assert M[first[0]] == pytest.approx(100.0, rel=1e-12) and M[first[1]] == pytest.approx(140.0, rel=1e-12)
    # beyond 0.006 rad the slope is 0.01 K
    end = np.argmax(r.displacement)
    assert (M[end] - 140.0) / (theta[end] - 0.006) == pytest.approx(0.01 * K, rel=1e-9)


@pytest.mark.parametrize("backbone, message", [
    ([(0.002, 100.0), (0.006, 90.0)], "softening or stiffening segment is not convex"),
    ([(0.002, 100.0), (0.004, 200.0)], "must decrease strictly"),
    ([(0.002, 100.0), (0.001, 120.0)], "must grow in magnitude"),
    ([(0.002, -100.0)], "of one sign"),
    ([(0.002, 100.0), (-0.002, -100.0), (-0.004, -130.0)], "differ from the positive branch"),
])
def test_a_backbone_that_is_not_convex_is_refused_with_the_reason(backbone, message):
    with pytest.raises(ValueError, match=message):
        cantilever(backbone)


def test_a_backbone_goes_without_My_and_k():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, H)
    fr.beam("col", 1, 2, E=E, A=A, I=I)
    with pytest.raises(ValueError, match="hinge 'h': My cannot go with a backbone"):
        fr.hinge("h", "col", "i", backbone=BACKBONE, My=100.0)


def load_history(st, dt, steps):
    t = dt * np.arange(steps + 1)
    force = 80.0 * np.sin(2 * np.pi * t / 0.4) * (t < 1.2)
    return force[:, None] * st.nodal_load(2, ux=1.0)[None, :]


def test_a_dynamic_run_balances_its_energy():
    st = cantilever(a0=0.5)
    dt, steps = 2e-3, 1000
    Q = load_history(st, dt, steps)
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=steps * dt, method="direct", rule="trapezoidal")
    assert sol.success, sol.message
    assert np.max(sol.v[:, 4]) > 0                                         # the third segment yields
    h = F.Histories.from_solution(st, sol, "trapezoidal", load0=Q[0])
    energy = energy_balance(st, h, Q)
    assert energy["plastic_work"][-1] > 0.05 * energy["input_work"].max()
    assert energy["max_relative_error"] < 1e-9


OPENSEES = """
import json, sys
import openseespy.opensees as ops
H, E, A, I, dt, a0 = {H!r}, {E!r}, {A!r}, {I!r}, {dt!r}, {a0!r}
springs, forces = {springs!r}, {forces!r}
ops.wipe(); ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0); ops.node(11, 0.0, 0.0); ops.node(2, 0.0, H)
ops.fix(1, 1, 1, 1); ops.equalDOF(1, 11, 1, 2)
ops.mass(2, 10.0, 10.0, 0.0)
for tag, (k, theta) in enumerate(springs, start=1):
    ops.uniaxialMaterial('ElasticPP', tag, k, theta)
ops.uniaxialMaterial('Parallel', 100, *range(1, len(springs) + 1))
ops.element('zeroLength', 101, 1, 11, '-mat', 100, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 2, A, E, I, 1)
ops.rayleigh(a0, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *forces)
ops.pattern('Plain', 1, 1); ops.load(2, 1.0, 0.0, 0.0)
ops.constraints('Transformation'); ops.numberer('RCM'); ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100); ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25); ops.analysis('Transient')
out = {{'ux': [0.0], 'M': [0.0]}}
for k in range(len(forces) - 1):
    assert ops.analyze(1, dt) == 0
    out['ux'].append(ops.nodeDisp(2, 1)); out['M'].append(ops.eleResponse(101, 'basicForce')[0])
print(json.dumps(out))
"""


@needs_opensees
def test_a_dynamic_run_equals_opensees_parallel_elastic_pp_springs():
    a0, dt, steps = 0.5, 2e-3, 1000
    st = cantilever(a0=a0)
    Q = load_history(st, dt, steps)
    sol = ul.solve(st.to_model(), Q, dt=dt, t_end=steps * dt, method="direct", rule="trapezoidal")
    assert sol.success, sol.message
    slopes = [100.0 / 0.002, 40.0 / 0.004, 20.0 / 0.014, 0.0]
    springs = [(s0 - s1, theta) for s0, s1, (theta, _) in zip(slopes, slopes[1:], BACKBONE)]
    script = OPENSEES.format(H=H, E=E, A=A, I=I, dt=dt, a0=a0, springs=springs,
                             forces=Q[:, int(np.flatnonzero(st.nodal_load(2, ux=1.0))[0])].tolist())
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=ENV, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    theirs = {key: np.array(value) for key, value in json.loads(proc.stdout.strip().splitlines()[-1]).items()}
    ux = sol.u[:, int(np.flatnonzero(st.nodal_load(2, ux=1.0))[0])]
    moment = st.element_forces(sol.t, sol.u, sol.v)[:, st.constraint_names.index("h.plastic+")]
    assert np.abs(ux - theirs["ux"]).max() <= 1e-9 * np.abs(theirs["ux"]).max()           # measured 2.1e-12
    # the spring's basic force is its moment on the node, minus the end moment on the beam
    assert np.abs(moment + theirs["M"]).max() <= 1e-9 * np.abs(theirs["M"]).max()          # measured 4.2e-12
    assert np.abs(moment).max() == pytest.approx(160.0, rel=1e-9)                          # the last segment
