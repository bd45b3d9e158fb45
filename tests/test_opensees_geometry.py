"""``geomTransf('PDelta')`` (2-D and 3-D) against openseespy: the static P-Delta equilibrium to round-off,
and a transient response after gravity, where the axial forces kept constant here (OpenSees
follows them) make the histories differ by a measured amount; the combinations refused."""

import numpy as np
import pytest

from test_opensees_module import both, errors, needs_opensees

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


@needs_opensees
def test_pdelta_static_cantilever_equals_openseespy_to_round_off():
    theirs, ours = both("pdelta_cantilever.py")
    err = errors(theirs, ours)
    assert max(err.values()) <= 1e-12, err                          # measured 7.5e-15
    # the P-Delta effect is there: the tip drift is 45 % above the Linear transformation's
    assert theirs["u_PDelta"][-6] > 1.4 * theirs["u_Linear"][-6]


@needs_opensees
def test_pdelta_transient_after_gravity_within_the_measured_difference():
    theirs, ours = both("pdelta_portal.py")
    err = errors(theirs, ours)
    for key in ("static_PDelta", "static_Linear", "drift_Linear", "N1_Linear", "N2_Linear"):
        assert err[key] <= 1e-11, (key, err[key])                   # gravity and Linear: round-off
    # constant axial forces here, OpenSees's follow the overturning (+- 21 % of the gravity's)
    n1 = theirs["N1_PDelta"]
    assert np.abs(n1 + 1500.0).max() > 0.2 * 1500.0
    assert 1e-6 < err["drift_PDelta"] <= 3e-4, err["drift_PDelta"]   # measured 1.4e-4 of the peak
    peak_theirs, peak_ours = np.abs(theirs["drift_PDelta"]).max(), np.abs(ours["drift_PDelta"]).max()
    assert abs(peak_ours - peak_theirs) <= 2e-4 * peak_theirs       # peak drift: 1.4e-4
    # ... against the P-Delta effect itself: 41 % more drift than with Linear columns
    assert peak_theirs > 1.35 * np.abs(theirs["drift_Linear"]).max()


def cantilever(P, F, kind="PDelta", steps=1):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 4.0)
    ops.fix(1, 1, 1, 1)
    ops.geomTransf(kind, 1)
    ops.element('elasticBeamColumn', 1, 1, 2, 0.01, 2e8, 8e-5, 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, F, P, 0.0)
    ops.integrator('LoadControl', 1.0 / steps)
    ops.analysis('Static')
    return [ops.analyze(1) for _ in range(steps)]


def test_pdelta_static_is_the_string_pdelta_equilibrium():
    """One element: the fixed point solves ``(K + N/L t t^T) u = f`` with ``N`` the element's own
    axial force (``EA/L`` times its elongation)."""
    assert cantilever(-2000.0, 5.0) == [0]
    u = np.array(ops.nodeDisp(2))
    E, A, I, H = 2e8, 0.01, 8e-5, 4.0
    N = E * A / H * u[1]
    K = np.array([[12 * E * I / H**3 + N / H, 0, 6 * E * I / H**2], [0, E * A / H, 0],
                  [6 * E * I / H**2, 0, 4 * E * I / H]])                  # N < 0: compression softens
    assert np.allclose(K @ u, [5.0, -2000.0, 0.0], rtol=0, atol=1e-9 * 2000)
    assert np.isclose(ops.eleResponse(1, 'basicForce')[0], N, rtol=1e-12)


def test_pdelta_refused_where_not_mapped():
    cantilever(-2000.0, 5.0)
    ops.integrator('DisplacementControl', 2, 1, 0.001)
    with pytest.raises(OpenSeesRefused, match="follows the axial forces along the pushover"):
        ops.analyze(1)
    with pytest.raises(OpenSeesRefused, match="buckling"):
        cantilever(-1e6, 5.0)                                        # above the Euler load (2470)
    ops.wipe()
    ops.model('basic', '-ndm', 3, '-ndf', 6)
    with pytest.raises(OpenSeesRefused, match="needs its vecxz"):
        ops.geomTransf('PDelta', 1)


@needs_opensees
def test_pdelta_3d_equals_openseespy():
    """3-D (``PDeltaCrdTransf3d``: ``N/L`` on both transverse directions): an inclined two-element
    column, Iy != Iz, skew vecxz, static to round-off with its element forces and reactions; the
    transient after it to round-off on a vertical column (its axial forces stay constant in OpenSees
    too) and within the measured difference on the inclined one (OpenSees follows ``N``)."""
    theirs, ours = both("pdelta3d_cantilever.py")
    err = errors(theirs, ours)
    for key in ("u_PDelta", "force1", "basic2", "reaction1", "u_Linear", "tip_Linear", "u_PDelta_vertical",
                "tip_PDelta_vertical"):
        assert err[key] <= 1e-12, (key, err[key])                  # measured 4e-16 .. 1.7e-14
    assert 1e-6 < err["tip_PDelta"] <= 5e-4, err["tip_PDelta"]      # measured 1.8e-4 of the peak
    tip = np.abs(theirs["u_PDelta"][-6:-3]).max()
    assert tip > 1.3 * np.abs(theirs["u_Linear"][-6:-3]).max()      # the P-Delta effect: +34 %


@needs_opensees
def test_truss_braces_equal_openseespy():
    """Elastic braces (``-rho``, ``-doRayleigh 1``, a material ``eta``) and tension-only braces
    (``ElasticPPGap``) with an ``ENT`` strut: every history to 1e-11 of its peak (measured 3e-13)."""
    theirs, ours = both("braced_truss.py")
    err = errors(theirs, ours)
    assert max(err.values()) <= 1e-11, err
    axial = theirs["axial_tension_only"].reshape(-1, 3)
    for brace in (0, 1):                                            # each goes slack and taut in turn
        assert axial[:, brace].min() >= 0.0 and (axial[:, brace] == 0).mean() > 0.2
        assert axial[:, brace].max() > 500.0
    assert axial[:, 2].max() <= 0.0 and axial[:, 2].min() < -100.0  # the ENT strut: compression only
    assert (axial[:, 2] == 0).mean() > 0.2


def small_truss(*options, material=('Elastic', 1, 2e8), ndm=2):
    ops.wipe()
    ops.model('basic', '-ndm', ndm, '-ndf', 3 * (ndm - 1))
    ops.node(1, *[0.0] * ndm)
    ops.node(2, 3.0, 4.0, *[0.0] * (ndm - 2))
    ops.uniaxialMaterial(*material)
    ops.element('truss', 1, 1, 2, 1e-3, 1, *options)


@pytest.mark.parametrize("call, words", [
    (lambda: small_truss('-cMass', 1), ("-cMass 1", "lumped")),
    (lambda: small_truss('-doRayleigh', 1, material=('ENT', 1, 2e8)), ("-doRayleigh 1 with ENT",)),
    (lambda: small_truss(ndm=3), ("3-D",)),
    (lambda: small_truss('-section'), ("'-section'",)),
    (lambda: small_truss('-rho', -1.0), ("rho >= 0",)),
    (lambda: ops.element('corotTruss', 2, 1, 2, 1e-3, 1), ("corotational", "2e-4", "truss (the linear truss)")),
])
def test_truss_options_refused(call, words):
    small_truss()
    with pytest.raises(OpenSeesRefused) as info:
        call()
    for word in words:
        assert word in str(info.value), (word, str(info.value))


def test_truss_is_an_axial_spring_of_EA_over_L():
    small_truss('-rho', 2.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0, 1, 1)                                             # free along x only: k = EA/L c^2
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, 30.0, 0.0, 0.0)
    ops.integrator('LoadControl', 1.0)
    ops.analysis('Static')
    assert ops.analyze(1) == 0
    k = 2e8 * 1e-3 / 5.0
    assert np.isclose(ops.nodeDisp(2, 1), 30.0 / (k * 0.6**2), rtol=1e-13)
    assert np.isclose(ops.eleResponse(1, 'axialForce')[0], 50.0, rtol=1e-13)
    assert np.allclose(ops.eleForce(1), [-30.0, -40.0, 0.0, 30.0, 40.0, 0.0], rtol=1e-13)
    with pytest.raises(OpenSeesRefused, match="axialForce"):
        ops.eleResponse(1, 'localForce')


@needs_opensees
def test_beam_uniform_loads_equal_openseespy():
    """``eleLoad -beamUniform`` (Wy and Wx, inclined rafters, '-ele' and '-range'): the consistent
    nodal loads give the nodal displacements, and the end forces with the fixed-end forces give
    eleForce, localForce, basicForce and the reactions, to round-off (measured 1.6e-13)."""
    theirs, ours = both("beam_uniform.py")
    err = errors(theirs, ours)
    assert max(err.values()) <= 1e-11, err
    basic = theirs["basic"].reshape(4, 4, 3)[-1]
    assert abs(basic[1, 1]) < 1e-9 * np.abs(basic).max()            # the pinned base carries no moment


def loaded_beam(*ele_load):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 5.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 1)
    ops.geomTransf('Linear', 1)
    ops.geomTransf('PDelta', 2)
    ops.element('elasticBeamColumn', 1, 1, 2, 0.1, 3e7, 1e-3, 1)
    ops.node(3, 0.0, 3.0)
    ops.element('elasticBeamColumn', 2, 1, 3, 0.1, 3e7, 1e-3, 2)
    ops.uniaxialMaterial('Elastic', 1, 1e5)
    ops.element('zeroLength', 3, 1, 3, '-mat', 1, '-dir', 1)
    ops.timeSeries('Constant', 1)
    ops.pattern('Plain', 1, 1)
    ops.eleLoad(*ele_load)


def test_beam_uniform_fixed_end_forces():
    """A beam fixed at both ends: no displacement, and its end forces are the fixed-end forces."""
    loaded_beam('-ele', 1, '-type', '-beamUniform', -10.0, 4.0)
    ops.integrator('LoadControl', 1.0)
    ops.analysis('Static')
    assert ops.analyze(1) == 0
    assert np.allclose(ops.eleForce(1), [-10.0, 25.0, 125.0 / 6, -10.0, 25.0, -125.0 / 6], rtol=1e-13)
    assert np.allclose(ops.eleResponse(1, 'basicForce'), [-10.0, 125.0 / 6, -125.0 / 6], rtol=1e-13)


@pytest.mark.parametrize("args, words", [
    (('-ele', 1, '-type', '-beamPoint', -10.0, 0.5), ("-beamPoint", "-beamUniform")),
    (('-ele', 1, '-type', '-beamUniform', -10.0, 0.0, 0.2, 0.8), ("partial",)),
    (('-ele', 3, '-type', '-beamUniform', -10.0), ("element 3 is not a 2-D elasticBeamColumn",)),
    (('-ele', 2, '-type', '-beamUniform', -10.0, 1.0), ("PDelta element 2", "Wx = 0")),
    (('-type', '-beamUniform', -10.0), ("no element",)),
])
def test_element_loads_refused(args, words):
    with pytest.raises(OpenSeesRefused) as info:
        loaded_beam(*args)
    for word in words:
        assert word in str(info.value), (word, str(info.value))
