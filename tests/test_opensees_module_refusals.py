"""``unilateral.opensees`` refuses what it cannot represent, at once, by name, with the reason and the
nearest alternative (:class:`OpenSeesRefused`, a ``ValueError``); and the commands it accepts."""

import math

import numpy as np
import pytest

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


def portal(ag0=0.0):
    """A small elastic portal with a UniformExcitation, ready to analyze."""
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    for tag, x, y in ((1, 0.0, 0.0), (2, 4.0, 0.0), (3, 0.0, 3.0), (4, 4.0, 3.0)):
        ops.node(tag, x, y)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 1)
    ops.mass(3, 10.0, 10.0, 0.0)
    ops.mass(4, 10.0, 10.0, 0.0)
    ops.geomTransf('Linear', 1)
    for tag, i, j in ((1, 1, 3), (2, 2, 4), (3, 3, 4)):
        ops.element('elasticBeamColumn', tag, i, j, 0.1, 30e6, 1e-3, 1)
    ops.timeSeries('Path', 1, '-dt', 0.01, '-values', ag0, 1.0, -1.0, 0.5, 0.0)
    ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')


def refused(call, *words):
    with pytest.raises(OpenSeesRefused) as info:
        call()
    message = str(info.value)
    assert isinstance(info.value, ValueError) and not isinstance(info.value, NotImplementedError)
    assert "Nearest alternative:" in message and info.value.why and info.value.instead
    for word in words:
        assert word in message, (word, message)
    return message


REFUSED_CALLS = [
    (lambda: ops.uniaxialMaterial('Steel02', 9, 400.0, 2e5, 0.01), "Steel02", "smooth"),
    (lambda: ops.uniaxialMaterial('Concrete02', 9, -30.0, -0.002, -6.0, -0.006), "Concrete02", "softening"),
    (lambda: ops.uniaxialMaterial('Hysteretic', 9, 1.0, 0.1), "Hysteretic"),
    (lambda: ops.uniaxialMaterial('Steel01', 9, 400.0, 2e5, 0.01, 0.05, 1.0, 0.0, 1.0), "Steel01", "isotropic"),
    (lambda: ops.uniaxialMaterial('MinMax', 9, 1), "MinMax", "ElasticPP"),
    (lambda: ops.uniaxialMaterial('Elastic', 9, 100.0, 0.0, 50.0), "Eneg", "ENT"),
    (lambda: ops.uniaxialMaterial('ElasticPPGap', 9, 100.0, -5.0, -0.01, 0.1), "ElasticPPGap", "hardening"),
    (lambda: ops.uniaxialMaterial('ElasticPPGap', 9, 100.0, -5.0, 0.01), "one sign"),
    (lambda: ops.element('forceBeamColumn', 9, 1, 3, 1, 1), "forceBeamColumn", "fibre"),
    (lambda: ops.element('dispBeamColumn', 9, 1, 3, 1, 1), "dispBeamColumn"),
    (lambda: ops.element('corotTruss', 9, 1, 3, 1.0, 1), "corotTruss", "corotational"),
    (lambda: ops.element('quad', 9, 1, 2, 4, 3, 1.0, 'PlaneStress', 1), "quad"),
    (lambda: ops.element('elasticBeamColumn', 9, 1, 3, 0.1, 30e6, 1e-3, 1, '-cMass'), "-cMass", "lumped"),
    (lambda: ops.element('elasticBeamColumn', 9, 1, 3, 0.1, 30e6, 1e-3, 1, '-release', 1), "-release"),
    (lambda: ops.element('elasticBeamColumn', 9, 1, 3, 0.1, 30e6, 1e-3, 1, '-mass', 0.9), "-mass", "nodal masses"),
    (lambda: ops.element('zeroLength', 9, 1, 3, '-mat', 1, '-dir', 1, '-orient', 0, 1, 0, -1, 0, 0), "-orient"),
    (lambda: ops.element('zeroLength', 9, 1, 3, '-mat', 2, '-dir', 2, '-doRayleigh', 1), "-doRayleigh", "ENT"),
    (lambda: ops.geomTransf('Corotational', 7), "Corotational", "linear structure"),
    (lambda: ops.geomTransf('Linear', 7, '-jntOffset', 0.1, 0.0, 0.0, 0.0), "joint offsets"),
    (lambda: ops.timeSeries('Trig', 7, 0.0, 1.0, 0.5), "Trig", "Path"),
    (lambda: ops.pattern('MultipleSupport', 7), "MultipleSupport"),
    (lambda: ops.pattern('UniformExcitation', 7, 1, '-disp', 1), "-disp", "'-accel'"),
    (lambda: ops.pattern('UniformExcitation', 7, 3, '-accel', 1), "direction 3", "rotation"),
    (lambda: ops.integrator('HHT', 0.9), "HHT", "Newmark"),
    (lambda: ops.integrator('Newmark', 0.5, 0.1), "unconditionally stable"),
    (lambda: ops.integrator('ArcLength', 1.0, 1.0), "ArcLength", "DisplacementControl"),
    (lambda: ops.integrator('LoadControl', 0.1, 1, 0.01, 0.2), "automatic load increment"),
    (lambda: ops.analysis('VariableTransient'), "VariableTransient"),
    (lambda: ops.reactions('-dynamic'), "-dynamic"),
    (lambda: ops.eleResponse(1, 'stiffness'), "stiffness"),
    (lambda: ops.section('Fiber', 1), "section()", "fibre"),
    (lambda: ops.fiber(0.0, 0.0, 0.01, 1), "fiber()"),
    (lambda: ops.patch('rect', 1, 4, 4, 0, 0, 1, 1), "patch()"),
    (lambda: ops.recorder('Drift', '-file', 'x.out', '-iNode', 1, '-jNode', 3), "recorder('Drift')", "Node"),
    (lambda: ops.eigen(2), "eigen()"),
    (lambda: ops.sp(3, 1, 0.01), "sp()"),
    (lambda: ops.eleLoad('-ele', 3, '-type', '-beamPoint', -10.0, 0.5), "eleLoad(", "Plain pattern"),
    (lambda: ops.rigidLink('joint', 3, 4), "rigidLink('joint', 3, 4)", "'beam' or 'bar'"),
    (lambda: ops.rigidDiaphragm(3, 3, 4), "rigidDiaphragm(3, 3, ...)", "perpDirn 3", "2-D"),
    (lambda: ops.geomTransf('Linear', 8, 0.0, 0.0, 1.0), "geomTransf('Linear', 8) 0.0", "joint offsets"),
    (lambda: ops.beamIntegration('Lobatto', 1, 1, 5), "beamIntegration()"),
    (lambda: ops.analyze(10, 0.01, 0.001, 0.02, 10), "variable time steps"),
]


@pytest.mark.parametrize("call_and_words", REFUSED_CALLS, ids=[w[1] for w in REFUSED_CALLS])
def test_refused_at_once_with_reason_and_alternative(call_and_words):
    portal()
    ops.uniaxialMaterial('Elastic', 1, 1e4)
    ops.uniaxialMaterial('ENT', 2, 1e4)
    call, *words = call_and_words
    refused(call, *words)


def test_models_without_rotations_are_refused():
    ops.wipe()
    refused(lambda: ops.model('basic', '-ndm', 3, '-ndf', 3), "rotations", "'-ndf', 6")
    refused(lambda: ops.model('basic', '-ndm', 2, '-ndf', 2), "rotations", "'-ndf', 3")
    refused(lambda: ops.node(1, 0.0, 0.0), "no model")


def test_accepted_commands_have_no_effect_and_analyze_returns_zero():
    portal()
    for call in (lambda: ops.constraints('Transformation'), lambda: ops.numberer('RCM'),
                 lambda: ops.system('BandGeneral'), lambda: ops.test('NormDispIncr', 1e-12, 10),
                 lambda: ops.algorithm('Newton')):
        assert call() == 0
    assert ops.analyze(5, 0.01) == 0
    assert math.isclose(ops.getTime(), 0.05)
    assert ops.nodeDisp(3, 1) != 0 and len(ops.nodeDisp(3)) == 3 and len(ops.eleForce(1)) == 6
    ops.setTime(0.02)               # a jump in time: the load there is not in equilibrium with the state
    refused(lambda: ops.analyze(1, 0.01), "acceleration")
    ops.wipe()
    assert ops.getTime() == 0.0 and ops.getNodeTags() == []


def test_a_ground_motion_that_starts_off_equilibrium_is_refused():
    portal(ag0=2.0)
    refused(lambda: ops.analyze(1, 0.01), "acceleration", "-prependZero")


def test_a_gap_that_reaches_its_yield_force_is_refused():
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    for tag in (1, 2, 3):
        ops.node(tag, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(3, 1, 1, 1)
    ops.mass(2, 1.0, 1.0, 0.0)
    ops.uniaxialMaterial('Elastic', 1, 100.0)
    ops.uniaxialMaterial('ElasticPPGap', 2, 1e4, -5.0, -0.001)
    ops.element('zeroLength', 1, 1, 2, '-mat', 1, 1, 1, '-dir', 1, 2, 3)
    ops.element('zeroLength', 2, 3, 2, '-mat', 2, '-dir', 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, -100.0, 0.0, 0.0)
    ops.integrator('LoadControl', 0.01)
    ops.analysis('Static')
    assert ops.analyze(1) == 0                           # -1: below the gap
    refused(lambda: ops.analyze(100), "ElasticPPGap of element 2", "yield force", "ENT")


def test_a_static_analysis_that_yields_is_refused():
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.uniaxialMaterial('Elastic', 1, 100.0)
    ops.uniaxialMaterial('ElasticPP', 2, 100.0, 0.01)
    ops.element('zeroLength', 1, 1, 2, '-mat', 1, 1, 1, '-dir', 1, 2, 3)
    ops.element('zeroLength', 2, 1, 2, '-mat', 2, '-dir', 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, 3.0, 0.0, 0.0)
    ops.analysis('Static')
    refused(lambda: ops.analyze(1), "yields", "transient")


def test_equal_dof_ties_and_static_reactions():
    """A column on a rotational spring, tied to its support in ux, uy: the reaction at the support is
    the spring's moment, and the tied node moves with its master."""
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.node(3, 0.0, 2.0)
    ops.fix(1, 1, 1, 1)
    ops.equalDOF(1, 2, 1, 2)
    ops.uniaxialMaterial('Elastic', 1, 1e3)
    ops.element('zeroLength', 1, 1, 2, '-mat', 1, '-dir', 3)
    ops.geomTransf('Linear', 1)
    ops.element('elasticBeamColumn', 2, 2, 3, 0.01, 2e8, 1e-4, 1)
    ops.timeSeries('Constant', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(3, 1.0, 0.0, 0.0)
    ops.analysis('Static')
    assert ops.analyze(1) == 0
    assert ops.nodeDisp(2, 1) == 0.0 and ops.nodeDisp(2, 2) == 0.0
    assert math.isclose(ops.nodeDisp(2, 3), -2.0 / 1e3)                # M = 2 kN m (clockwise) on k = 1000
    assert math.isclose(ops.eleResponse(1, 'basicForce')[0], -2.0)
    ops.reactions()
    assert np.allclose(ops.nodeReaction(1), [0.0, 0.0, 2.0])
    assert np.allclose(ops.nodeReaction(3), [0.0, 0.0, 0.0], atol=1e-12)
