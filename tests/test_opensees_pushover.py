"""``integrator('DisplacementControl', node, dof, incr)``: a static pushover after gravity, by the
path following of :mod:`unilateral.pushover`, against openseespy (``pushover_dc.py``: every
history to 1e-8 of its peak, measured 9e-14 .. 9e-13), and its refusals."""

import numpy as np
import pytest

from test_opensees_module import assert_equal_histories, needs_opensees

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


@needs_opensees
def test_displacement_control_pushover_equals_openseespy():
    theirs, _ = assert_equal_histories("pushover_dc.py")
    u5 = theirs["u5"].reshape(-1, 3)[:, 0]
    assert np.allclose(np.diff(u5[:120]), 0.002) and np.allclose(np.diff(u5[120:]), 0.005)
    assert np.isclose(theirs["hinge101"].min(), -90.0)               # the ElasticPP hinge yields
    assert theirs["ent31"].max() == 0.0 and theirs["uy1"].max() > 0.1  # the left footing lifts off


def cantilever(k=100.0, Fy=5.0):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0, 1, 1)
    ops.uniaxialMaterial('ElasticPP', 1, k, Fy / k)
    ops.element('zeroLength', 1, 1, 2, '-mat', 1, '-dir', 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, 1.0, 0.0, 0.0)
    ops.integrator('DisplacementControl', 2, 1, 0.01)
    ops.analysis('Static')


def test_load_factor_is_the_elastic_plastic_force():
    cantilever()
    lam = []
    for _ in range(10):
        assert ops.analyze(1) == 0
        lam.append(ops.getTime())
    u = 0.01 * np.arange(1, 11)
    assert np.allclose(lam, np.minimum(100.0 * u, 5.0), rtol=1e-12)   # k u up to Fy, then Fy


def test_reversal_and_time_following_loads_are_refused():
    cantilever()
    ops.analyze(3)
    ops.integrator('DisplacementControl', 2, 1, -0.01)
    with pytest.raises(OpenSeesRefused, match="unloading"):
        ops.analyze(1)
    cantilever()
    ops.timeSeries('Path', 2, '-dt', 1.0, '-values', 0.0, 1.0, 2.0)
    ops.pattern('Plain', 2, 2)
    ops.load(2, 1.0, 0.0, 0.0)
    with pytest.raises(OpenSeesRefused, match="Plain patterns of Linear series"):
        ops.analyze(1)
    with pytest.raises(OpenSeesRefused, match="incr = 0"):
        ops.integrator('DisplacementControl', 2, 1, 0.0)
    with pytest.raises(OpenSeesRefused, match="automatic increment"):
        ops.integrator('DisplacementControl', 2, 1, 0.01, 1, 0.001, 0.02)
