"""Steel01 (no isotropic hardening), Hardening (kinematic), ElasticBilin (stiffening) and Parallel
mapped exactly onto springs, contacts and elastic-plastic links in parallel, against openseespy
(``materials_cyclic.py``, every history to 1e-8 of its peak; measured 6e-15 .. 2e-12), and the
laws outside the subset refused by name."""

import numpy as np
import pytest

from test_opensees_module import assert_equal_histories, needs_opensees

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


@needs_opensees
def test_composite_materials_equal_openseespy_through_yielding():
    theirs, _ = assert_equal_histories("materials_cyclic.py")
    assert np.isclose(np.abs(theirs["f101"]).max(), 40.0)            # Steel01 b = 0: perfectly plastic
    assert np.abs(theirs["f100"]).max() > 50.0 * 1.3                 # Steel01 b = 0.05 hardens past Fy
    assert np.abs(theirs["f102"]).max() > 40.0 * 4                   # Hardening, H = E / 10
    assert theirs["u103"].max() > 0.004 and theirs["u103"].min() < -0.003   # ElasticBilin: both kinks crossed


def sdof(material_args, d):
    """The static force of a material at the deformation ``d`` (a displacement-loaded zeroLength)."""
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0, 1, 1)
    ops.uniaxialMaterial(*material_args)
    ops.uniaxialMaterial('Elastic', 99, 1e12)                        # a stiff spring imposes d
    ops.node(3, 0.0, 0.0)
    ops.fix(3, 0, 1, 1)
    ops.element('zeroLength', 1, 1, 2, '-mat', material_args[1], '-dir', 1)
    ops.element('zeroLength', 2, 2, 3, '-mat', 99, '-dir', 1)
    ops.uniaxialMaterial('Elastic', 98, 1.0)
    ops.element('zeroLength', 3, 1, 3, '-mat', 98, '-dir', 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(3, 1e12 * d, 0.0, 0.0)
    ops.integrator('LoadControl', 1.0)
    ops.analysis('Static')
    assert ops.analyze(1) == 0
    return ops.eleResponse(1, 'basicForce')[0], ops.eleResponse(1, 'deformation')[0]


@pytest.mark.parametrize("d", [-0.006, -0.002, 0.001, 0.003, 0.007])
def test_elastic_bilin_is_the_piecewise_linear_elastic_law(d):
    f, e = sdof(('ElasticBilin', 4, 1.0e4, 3.0e4, 0.004, 2.0e4, 5.0e4, -0.003), d)
    expected = (1e4 * e if 0 <= e <= 0.004 else 40.0 + 3e4 * (e - 0.004) if e > 0.004
                else 2e4 * e if e >= -0.003 else -60.0 + 5e4 * (e + 0.003))
    assert np.isclose(f, expected, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("args, words", [
    (('Steel01', 1, 250.0, 2e5, 0.02, 0.1, 1.0, 0.1, 1.0), ("isotropic hardening", "a1 = a3 = 0")),
    (('Hardening', 1, 2e5, 250.0, 100.0, 1000.0), ("H_iso", "kinematic")),
    (('Hardening', 1, 2e5, 250.0, 0.0, 1000.0, 5.0), ("viscoplastic",)),
    (('ElasticBilin', 1, 2e4, 1e4, 0.002), ("softening", "EP2 >= EP1")),
    (('Series', 1, 2, 3), ("Series", "internal deformation")),
    (('Steel01', 1, 250.0, 2e5, 1.2), ("0 <= b < 1",)),
    (('Steel02', 1, 250.0, 2e5, 0.02), ("Steel02", "Steel01 or Hardening")),
])
def test_laws_outside_the_subset_are_refused(args, words):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    with pytest.raises(OpenSeesRefused) as info:
        ops.uniaxialMaterial(*args)
    for word in words:
        assert word in str(info.value)


def test_parallel_refuses_a_gap_that_could_yield_and_undefined_parts():
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.uniaxialMaterial('ElasticPPGap', 1, 1e4, -50.0, -0.01)
    with pytest.raises(OpenSeesRefused, match="zeroLength element of its own"):
        ops.uniaxialMaterial('Parallel', 2, 1)
    with pytest.raises(OpenSeesRefused, match="uniaxialMaterial 7 is not defined"):
        ops.uniaxialMaterial('Parallel', 3, 7)
    with pytest.raises(OpenSeesRefused, match="scaled"):
        ops.uniaxialMaterial('Elastic', 4, 1.0)
        ops.uniaxialMaterial('Parallel', 5, 4, '-factors', 2.0)
