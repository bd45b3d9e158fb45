"""P-Delta on footings on a soil medium: the gravity's axial forces of the static state on the soil's
static springs, their geometric stiffness in the frame's ``K``.

A rigid footing on Winkler-Kelvin patches is exactly the paper's Kelvin soil elements under a rigid
foundation (three soil elements linked rigidly to the footing's node): with P-Delta on both, the
frame on the footing (``FoundationModel``, cq) equals the frame on the soil elements (``Model``,
direct) to round-off, the axial forces are the same, the energy balance closes with the geometric
term, and the P-Delta effect is there. The frame alone (``K - K_G`` without the soil) is unstable in
rocking under its weight; ``FoundationModel`` checks ``K - K_geometric`` instead of ``K``."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.soil import FoundationModel
from unilateral.structure import Frame2D

K_PATCH, C_PATCH, WIDTH, H = 4e4, 4e2, 4.0, 8.0
XS = (-WIDTH / 3, 0.0, WIDTH / 3)           # the centres of three patches of a 4 m footing


def tower(on_footing: bool, p_delta=True):
    """A column of height H with a top mass on a rigid footing (``on_footing``) or on three Kelvin
    soil elements under a rigid foundation (the same springs, dashpots and masses)."""
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, H)
    fr.beam("col", "base", "top", E=3e7, A=0.5, I=0.02)
    fr.mass("top", 60.0, J=10.0)
    if on_footing:
        fr.foundation("F", "base", width=WIDTH, length=4.0, patches=3, mass=20.0, J=30.0,
                      soil={"model": "winkler-kelvin", "k": K_PATCH, "c": C_PATCH})
    else:
        fr.support("base", ux=True, uy=False)
        fr.mass("base", 20.0, J=30.0)
        for k, x in enumerate(XS):
            fr.node(f"s{k}", x, 0.0)
            fr.rigid_link("base", f"s{k}")
            fr.soil(f"F.{k + 1}", f"s{k}", K_PATCH, c=C_PATCH)
    if p_delta:
        fr.p_delta()
    return fr.build()


def run(st, method):
    x, gravity = st.influence("ux"), -ul.loads.STANDARD_GRAVITY * (st.M @ st.influence("uy"))
    load = ul.LoadHistory(gravity, [(-(st.M @ x), lambda t: 3.0 * np.sin(2 * np.pi * 1.2 * t) * (t < 2.0))])
    sol = ul.solve(st.to_model(), load, method=method, dt=5e-3, t_end=3.0, rule="trapezoidal")
    assert sol.success, sol.message
    return sol, load


def test_a_footing_with_p_delta_equals_the_kelvin_soil_elements_with_p_delta():
    footing, springs = tower(True), tower(False)
    assert isinstance(footing.to_model(), FoundationModel)
    assert footing.axial_forces["col"] == pytest.approx(springs.axial_forces["col"], rel=1e-12)
    assert footing.axial_forces["col"] == pytest.approx(-60.0 * ul.loads.STANDARD_GRAVITY, rel=1e-12)
    a, _ = run(footing, "cq")
    b, _ = run(springs, "direct")
    top_a = a.u[:, footing.dofs.index("top", "ux")]
    top_b = b.u[:, springs.dofs.index("top", "ux")]
    assert np.abs(top_a - top_b).max() <= 1e-9 * np.abs(top_b).max()
    assert a.v.max() > 1e-4, "the footing must lift for this test to mean something"


def test_the_p_delta_effect_on_a_footing_and_its_energy_balance():
    with_pd, load = run(tower(True), "cq")
    without, _ = run(tower(True, p_delta=False), "cq")
    st = tower(True)
    i = st.dofs.index("top", "ux")
    assert np.abs(with_pd.u[:, i] - without.u[:, i]).max() >= 0.05 * np.abs(without.u[:, i]).max()
    ds = ul.results_dataset(with_pd, st, load=load)
    assert float(np.abs(ds["energy_relative_error"]).max()) <= 1e-9
    assert float(np.abs(ds["energy_geometric"]).max()) > 0


def test_a_footing_frame_at_its_buckling_load_is_refused():
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, H)
    fr.beam("col", "base", "top", E=3e7, A=0.5, I=0.02)
    fr.mass("top", 1e4)
    fr.foundation("F", "base", width=WIDTH, length=4.0, patches=3, soil={"model": "winkler-kelvin", "k": K_PATCH})
    fr.p_delta()
    with pytest.raises(ValueError, match="p_delta: K - K_G is not positive definite"):
        fr.build().to_model()
