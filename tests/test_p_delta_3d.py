"""P-Delta of 3-D frames (``Frame3D.p_delta``): the consistent geometric stiffness of both bending
planes of each beam (:mod:`unilateral.structure.geometric`), checked against the 2-D frames
(whose P-Delta is verified in tests/test_frame_engineering.py), second-order beam-column theory,
the buckling refusal and the energy balance."""

from dataclasses import replace

import json
import subprocess
import sys

import numpy as np
import pytest
import scipy.sparse.linalg as spl
from test_opensees_module import ENV

import unilateral as ul
from unilateral.analysis.energy import energy_balance
from unilateral.structure import Frame2D, Frame3D
from unilateral.structure import forces3d as F3
from unilateral.structure.geometric import string

E, A, G, J = 3e7, 0.1, 1.2e7, 2e-3
IX, IY = 1e-3, 2.5e-3               # the column's second moments bending in x (Iy) and in y (Iz)
H, N_EL, GRAV = 4.0, 4, 9.81


def euler(I):
    return np.pi**2 * E * I / (4 * H**2)


def column_3d(mass, p_delta=True):
    """A cantilever along z of ``N_EL`` beams, the top mass ``mass``; local z' = X, y' = -Y, so
    bending in x uses ``Iy`` and bending in y ``Iz``."""
    fr = Frame3D()
    for k in range(N_EL + 1):
        fr.node(k, 0.0, 0.0, H * k / N_EL)
    fr.support(0, rx=True, ry=True, rz=True)
    for k in range(N_EL):
        fr.beam(f"c{k}", k, k + 1, E=E, A=A, Iy=IX, Iz=IY, G=G, J=J)
    fr.mass(N_EL, mass)
    if p_delta:
        fr.p_delta(g=GRAV)
    return fr.build()


def column_2d(mass, I):
    fr = Frame2D()
    for k in range(N_EL + 1):
        fr.node(k, 0.0, H * k / N_EL)
    fr.support(0, ux=True, uy=True, rz=True)
    for k in range(N_EL):
        fr.beam(f"c{k}", k, k + 1, E=E, A=A, I=I)
    fr.mass(N_EL, mass)
    fr.p_delta(g=GRAV)
    return fr.build()


def static(st, f):
    return spl.spsolve(st.to_model().K.tocsc(), f)


def beam_column(P, I, lateral=1.0):
    """The top drift of a cantilever under the axial load P and the lateral load: (tan kL - kL)/kL."""
    kL = np.sqrt(P / (E * I)) * H
    return lateral / (P / H) * (np.tan(kL) - kL) / kL


@pytest.mark.parametrize("angle", [0.0, 90.0, 30.0])
def test_a_3d_cantilever_drifts_as_the_2d_one_along_x_y_and_a_skew_direction(angle):
    P = 0.3 * euler(IX)
    st = column_3d(P / GRAV)
    assert st.axial_forces["c0"] == pytest.approx(-P, rel=1e-12)
    c, s = np.cos(np.radians(angle)), np.sin(np.radians(angle))
    u = static(st, st.nodal_load(N_EL, ux=c, uy=s))
    dx, dy = u[st.dofs.index(N_EL, "ux")], u[st.dofs.index(N_EL, "uy")]
    plane_x, plane_y = column_2d(P / GRAV, IX), column_2d(P / GRAV, IY)
    ref_x = static(plane_x, plane_x.nodal_load(N_EL, ux=c))[plane_x.dofs.index(N_EL, "ux")]
    ref_y = static(plane_y, plane_y.nodal_load(N_EL, ux=s))[plane_y.dofs.index(N_EL, "ux")]
    scale = max(abs(ref_x), abs(ref_y))
    assert abs(dx - ref_x) <= 1e-12 * scale and abs(dy - ref_y) <= 1e-12 * scale
    # second-order beam-column theory (the consistent cubic of 4 elements: 2e-6 off)
    assert dx == pytest.approx(c * beam_column(P, IX), rel=1e-5, abs=1e-12 * scale)
    assert dy == pytest.approx(s * beam_column(P, IY), rel=1e-5, abs=1e-12 * scale)


def test_the_drift_is_amplified_by_about_1_over_1_minus_P_over_Pcr():
    P = 0.05 * euler(IX)
    linear, pd = column_3d(P / GRAV, p_delta=False), column_3d(P / GRAV)
    assert linear.geometric is None and linear.axial_forces is None
    f = linear.nodal_load(N_EL, ux=1.0)
    ratio = static(pd, f)[pd.dofs.index(N_EL, "ux")] / static(linear, f)[linear.dofs.index(N_EL, "ux")]
    assert ratio == pytest.approx(1 / (1 - P / euler(IX)), rel=1e-3)          # 6.6e-4: the amplifier's own error


def test_gravity_at_the_buckling_load_is_refused():
    st = column_3d(1.05 * euler(IX) / GRAV)                # above the weaker plane's (x) buckling load only
    with pytest.raises(ValueError, match="p_delta: K - K_G is not positive definite: the gravity load reaches "
                                         "the buckling load"):
        st.to_model()
    column_3d(0.95 * euler(IX) / GRAV).to_model()


def test_p_delta_arguments_are_checked():
    fr = Frame3D()
    with pytest.raises(ValueError, match="p_delta: direction=.*is not a direction of gravity"):
        fr.p_delta(direction="rz")
    with pytest.raises(ValueError, match="p_delta: g="):
        fr.p_delta(g=-1.0)
    fr.node(1, 0, 0, 0)
    fr.node(2, 0, 0, 3)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("c", 1, 2, E=E, A=A, Iy=IX, Iz=IY, G=G, J=J)
    fr.mass(2, 1.0)
    assert fr.build(p_delta=True).axial_forces["c"] == pytest.approx(-9.80665)
    assert fr.build(p_delta=False).geometric is None


def portal_2d(*, soil=True):
    fr = Frame2D()
    for node, x, y in ((1, 0, 0), (2, 0, 4), (3, 6, 0), (4, 6, 4)):
        fr.node(node, x, y)
    for base in (1, 3):
        fr.support(base, ux=True, uy=not soil, rz=True)
        if soil:
            fr.soil(f"s{base}", base, 4e5, c=2e3)
    fr.beam("c1", 1, 2, E=E, A=0.2, I=2e-3)
    fr.beam("c2", 3, 4, E=E, A=0.2, I=2e-3)
    fr.beam("b", 2, 4, E=E, A=0.2, I=3e-3)
    fr.mass(2, 400.0)
    fr.mass(4, 400.0)
    fr.rayleigh(a0=0.2)
    fr.p_delta(g=GRAV)
    return fr.build()


def portal_3d(*, soil=True):
    """The portal of :func:`portal_2d` in the x-z plane (2-D y -> z, rz -> -ry), out of plane held."""
    fr = Frame3D()
    for node, x, z in ((1, 0, 0), (2, 0, 4), (3, 6, 0), (4, 6, 4)):
        fr.node(node, x, 0.0, z)
    for node in (2, 4):
        fr.support(node, ux=False, uy=True, uz=False, rx=True, ry=False, rz=True)
    for base in (1, 3):
        fr.support(base, ux=True, uy=True, uz=not soil, rx=True, ry=True, rz=True)
        if soil:
            fr.soil(f"s{base}", base, 4e5, c=2e3)
    section = dict(E=E, A=0.2, G=G, J=J)
    fr.beam("c1", 1, 2, Iy=2e-3, Iz=1e-3, **section)
    fr.beam("c2", 3, 4, Iy=2e-3, Iz=1e-3, **section)
    fr.beam("b", 2, 4, Iy=3e-3, Iz=1e-3, vecxz=(0.0, 0.0, 1.0), **section)    # y' = Y: bending in x-z uses Iy
    fr.mass(2, 400.0)
    fr.mass(4, 400.0)
    fr.rayleigh(a0=0.2)
    fr.p_delta(g=GRAV)
    return fr.build()


def ground_motion_load(st, vertical, t):
    """Samples (N+1, n) of the gravity along ``vertical`` and a 12 sin(2 pi t) ground acceleration along x."""
    gravity = -GRAV * (st.M @ st.influence(vertical))
    return gravity + np.outer(12.0 * np.sin(2 * np.pi * t), -(st.M @ st.influence("ux")))


def run(st, vertical, dt=5e-3, t_end=2.0):
    t = dt * np.arange(int(round(t_end / dt)) + 1)
    q = ground_motion_load(st, vertical, t)
    sol = ul.solve(st.to_model(), q, method="direct", rule="trapezoidal", dt=dt, t_end=t_end)
    assert sol.success, sol.message
    return sol, q


def test_a_3d_portal_in_the_xz_plane_moves_as_the_2d_portal_under_a_ground_motion():
    plane, space = portal_2d(), portal_3d()
    assert space.axial_forces == pytest.approx(plane.axial_forces, rel=1e-12)
    (a, _), (b, _) = run(plane, "uy"), run(space, "uz")
    roof_2d, roof_3d = a.u[:, plane.dofs.index(4, "ux")], b.u[:, space.dofs.index(4, "ux")]
    assert np.abs(roof_3d - roof_2d).max() <= 1e-10 * np.abs(roof_2d).max()
    assert np.abs(b.v - a.v).max() <= 1e-10 * np.abs(a.v).max()
    assert a.v.max() > 1e-3                                   # the footings uplift: the contacts are active
    without, _ = run(replace(space, geometric=None, axial_forces=None), "uz")
    assert np.abs(without.u[:, space.dofs.index(4, "ux")] - roof_3d).max() > 0.01 * np.abs(roof_3d).max()


def test_the_energy_balance_closes_with_p_delta_in_3d():
    st = portal_3d()
    sol, q = run(st, "uz")
    e = energy_balance(st, F3.histories(st, sol, "trapezoidal", load0=q[0]), q)
    assert e["max_relative_error"] < 1e-9
    geometric = e["geometric"] - e["geometric"][0]
    assert np.abs(geometric).max() > 1e-3 * np.abs(e["input_work"]).max()      # the term is there
    assert np.abs(e["balance_error"] + geometric).max() > 1e-3 * np.abs(e["input_work"]).max()


#: The 3-D cantilever of :func:`column_3d` in OpenSees (``geomTransf('PDelta')``: the string stiffness
#: of the committed axial force): gravity P by Newton, then the skew lateral load; the drift of the second.
OPENSEES_COLUMN = """
import json, sys
import openseespy.opensees as ops
E, A, G, J, Iy, Iz, H, n, P, c, s = map(float, sys.argv[1:])
n = int(n)
ops.model('basic', '-ndm', 3, '-ndf', 6)
for k in range(n + 1):
    ops.node(k, 0.0, 0.0, H * k / n)
ops.fix(0, 1, 1, 1, 1, 1, 1)
ops.geomTransf('PDelta', 1, 1.0, 0.0, 0.0)
for k in range(n):
    ops.element('elasticBeamColumn', k + 1, k, k + 1, A, E, G, J, Iy, Iz, 1)
ops.system('FullGeneral'); ops.numberer('Plain'); ops.constraints('Plain')
ops.test('NormDispIncr', 1e-14, 50); ops.algorithm('Newton'); ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
ops.timeSeries('Constant', 1); ops.pattern('Plain', 1, 1); ops.load(n, 0.0, 0.0, -P, 0.0, 0.0, 0.0)
ops.analyze(1); ops.loadConst('-time', 0.0)
before = [ops.nodeDisp(n, 1), ops.nodeDisp(n, 2)]
ops.timeSeries('Constant', 2); ops.pattern('Plain', 2, 2); ops.load(n, c, s, 0.0, 0.0, 0.0, 0.0)
ops.analyze(1)
print(json.dumps([ops.nodeDisp(n, 1) - before[0], ops.nodeDisp(n, 2) - before[1]]))
"""


@pytest.mark.skipif(ENV is None, reason="openseespy is not installed (pip install '.[test]')")
def test_the_string_form_is_opensees_p_delta_and_the_consistent_one_is_near():
    P, c, s = 0.3 * euler(IX), np.cos(np.radians(30.0)), np.sin(np.radians(30.0))
    args = [E, A, G, J, IX, IY, H, N_EL, P, c, s]
    out = subprocess.run([sys.executable, "-c", OPENSEES_COLUMN, *(repr(float(a)) for a in args)], env=ENV, capture_output=True,
                         text=True, timeout=120, check=True)
    theirs = np.array(json.loads(out.stdout.strip().splitlines()[-1]))
    st = column_3d(P / GRAV)
    f = st.nodal_load(N_EL, ux=c, uy=s)
    top = [st.dofs.index(N_EL, "ux"), st.dofs.index(N_EL, "uy")]
    strung = static(replace(st, geometric=string(st, st.axial_forces)), f)[top]
    np.testing.assert_allclose(strung, theirs, rtol=1e-9)          # measured: 2e-14
    consistent = static(st, f)[top]
    assert np.all(np.abs(consistent / theirs - 1) < 1e-2) and np.all(consistent > theirs)      # 0.5 %, 0.2 %
