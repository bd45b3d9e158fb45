"""3-D OpenSeesPy scripts (``-ndm 3 -ndf 6``) on :mod:`unilateral.opensees`, against openseespy.

``frame3d_asymmetric.py``: elasticBeamColumn with vecxz (four transformations), rigidDiaphragm,
rigidLink beam and bar, 6-flag fix, 6-value mass (rotary inertia), 3-D zeroLength (ElasticPP about
4 and 5, Elastic in all six directions), equalDOF, gravity then two ground components: every
history to 1e-8 of its peak (measured 2e-13 .. 4e-12).
"""

import numpy as np
import pytest

from test_opensees_module import assert_equal_histories, needs_opensees

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


@needs_opensees
def test_asymmetric_space_frame_equals_openseespy():
    theirs, _ = assert_equal_histories("frame3d_asymmetric.py")
    hinge = theirs["hinge201"].reshape(-1, 2)
    assert np.isclose(np.abs(hinge[:, 0]).max(), 60.0) and np.isclose(np.abs(hinge[:, 1]).max(), 80.0)
    u13, u15 = theirs["u13"].reshape(-1, 6), theirs["u15"].reshape(-1, 6)
    assert np.abs(u15[:, 5]).max() > 1e-4                              # the floor twists (asymmetric)
    # the diaphragm: node 13 at (6, 4) follows the master at (3, 2): ux = ux_m - dy rz_m
    assert np.allclose(u13[:, 0], u15[:, 0] - 2.0 * u15[:, 5], atol=1e-12)


def space_cantilever():
    ops.wipe()
    ops.model('basic', '-ndm', 3, '-ndf', 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 1.0, 2.0, 3.0)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.geomTransf('Linear', 1, 1.0, 0.0, 0.0)
    ops.element('elasticBeamColumn', 1, 1, 2, 0.01, 2e8, 8e7, 2e-5, 1e-5, 3e-5, 1)


def test_static_space_cantilever_is_in_equilibrium_and_symmetric():
    """A tip load on an inclined 3-D cantilever: the end forces balance the load, and the
    displacement is the flexibility's (reciprocity: u_a(F_b) = u_b(F_a))."""
    def tip(load):
        space_cantilever()
        ops.timeSeries('Constant', 1)
        ops.pattern('Plain', 1, 1)
        ops.load(2, *load)
        ops.integrator('LoadControl', 1.0)
        ops.analysis('Static')
        assert ops.analyze(1) == 0
        return np.array(ops.nodeDisp(2)), np.array(ops.eleForce(1))

    ua, fa = tip((1.0, 0.0, 0.0, 0.0, 0.0, 0.0))
    ub, fb = tip((0.0, 0.0, 0.0, 0.0, 1.0, 0.0))
    assert np.isclose(ua[4], ub[0], rtol=1e-10)
    assert np.allclose(fa[6:], [1.0, 0, 0, 0, 0, 0], atol=1e-9)      # the node pushes the element by the load
    r = np.array([1.0, 2.0, 3.0])
    assert np.allclose(fa[:3] + fa[6:9], 0.0, atol=1e-9)
    assert np.allclose(fa[3:6] + fa[9:] + np.cross(r, fa[6:9]), 0.0, atol=1e-9)


@pytest.mark.parametrize("call, words", [
    (lambda: ops.geomTransf('Linear', 2), ("vecxz",)),
    (lambda: ops.geomTransf('Linear', 2, 1.0, 2.0, 3.0), None),
    (lambda: ops.fix(2, 1, 1, 1), ("6 0 or 1",)),
    (lambda: ops.mass(2, 1.0, 1.0, 1.0), ("6 DOFs",)),
    (lambda: ops.node(3, 0.0, 1.0), ("3 coordinates",)),
    (lambda: ops.rigidDiaphragm(2, 1, 2), ("perpDirn 3",)),
    (lambda: ops.element('zeroLength', 9, 1, 2, '-mat', 1, '-dir', 7), ("1..6",)),
    (lambda: ops.pattern('UniformExcitation', 5, 4, '-accel', 1), ("ground rotation", "3 (z)")),
])
def test_3d_input_errors_are_refused_by_name(call, words):
    space_cantilever()
    ops.uniaxialMaterial('Elastic', 1, 1.0)
    ops.timeSeries('Linear', 1)
    if words is None:                                  # vecxz parallel to the member: at the element
        call()
        with pytest.raises(OpenSeesRefused, match="parallel"):
            ops.element('elasticBeamColumn', 5, 1, 2, 0.01, 2e8, 8e7, 2e-5, 1e-5, 3e-5, 2)
        return
    with pytest.raises(OpenSeesRefused) as info:
        call()
    for word in words:
        assert word in str(info.value)
