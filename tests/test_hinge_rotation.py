"""The total rotation of a hinge spring (``yield_total_deformation``) beside its plastic part, and its
sign against OpenSees's zeroLength deformation (docs/model-file.md, "Signs")."""

import numpy as np
import pytest

import unilateral
from unilateral.structure import Frame2D
from unilateral import results_dataset

E, A, I, H = 2e8, 0.01, 1e-4, 3.0          # kN/m^2, m^2, m^4, m


def _cantilever(k, hardening=0.1, My=50.0):
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, H)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=E, A=A, I=I)
    fr.hinge("hb", "col", "i", My=My, k=k, hardening=hardening)
    fr.mass(2, 1.0)
    return fr.build()


@pytest.mark.parametrize("P", [5.0, 25.0])          # below (M = 15 < 50) and past the yield moment (75)
def test_total_rotation_is_the_base_spring_rotation_of_a_pushed_cantilever(P):
    """A cantilever on a base spring (k) under a lateral force P at its top, statically: the top moves
    P H^3 / (3 E I) + theta H, theta the spring's total rotation, elastic M / k plus plastic; the moment
    on the column at its base is + P H (counter-clockwise) and theta has its sign."""
    st = _cantilever(k=2e4)
    model = st.to_model()
    q = st.nodal_load(2, ux=P)
    sol = unilateral.solve(model, lambda t: q, dt=0.01, t_end=0.02, initial="static")
    d = results_dataset(sol, st)
    theta = float(d["yield_total_deformation"].values[0, 0])
    plastic = float(d["plastic_deformation"].values[0, 0])
    M = float(d["yield_force"].values[0, 0])
    assert M == pytest.approx(P * H, rel=1e-9)
    assert theta == pytest.approx(M / 2e4 + plastic, rel=1e-12)
    assert (plastic > 0) == (P * H > 50.0)
    ux = st.node_displacement(sol, 2, "ux")[0]
    assert ux == pytest.approx(P * H ** 3 / (3 * E * I) + theta * H, rel=1e-9)
    assert d["yield_total_deformation"].attrs["units"]


def test_a_rigid_plastic_hinge_total_rotation_is_its_plastic_part():
    st = _cantilever(k=None, hardening=0.2)
    q = st.nodal_load(2, ux=25.0)
    sol = unilateral.solve(st.to_model(), lambda t: q, dt=0.01, t_end=0.02, initial="static")
    d = results_dataset(sol, st)
    np.testing.assert_array_equal(d["yield_total_deformation"].values, d["plastic_deformation"].values)
    assert d["plastic_deformation"].values[0, 0] > 0
