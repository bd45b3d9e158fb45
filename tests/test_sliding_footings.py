"""Footings that rock, lift and slide: horizontal soil forces limited by Coulomb friction.

Each patch of a footing with ``horizontal="soil"`` carries a horizontal force ``f`` through the
soil's horizontal (and horizontal-vertical) flexibility, a free unknown eliminated from each step's
LCP, and a slip pair whose friction rows take the normal force from the contact's unknown
(:class:`unilateral.constraints.SoilFriction`). Checked against the paper's primal form (Kelvin
soil elements, springs in series with friction sliders, stepped directly), the bilateral run
(``mu`` large, no uplift), and the friction law itself: ``|h| <= mu c``, slip only where
``|h| = mu c`` and against the force, and the slip equal to the relative motion of footing and
soil surface (the soil's own equation integrated independently).
"""

import numpy as np
import pytest

import unilateral as ul
from unilateral.constraints import Contact, SoilContact, SoilFriction, SoilShear, step_law
from unilateral.lcp import get_lcp_solver
from unilateral.soil import FoundationModel
from unilateral.structure import Frame2D

KELVIN = {"model": "winkler-kelvin", "k": 2e5, "c": 2e3, "kx": 1.5e5, "cx": 1.5e3}


def rel(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


def tower(soil, mu, *, amplitude=8.0, patches=4):
    """A column with a top mass on a rigid footing that may slide, under a horizontal pulse."""
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, 6.0)
    fr.beam("col", "base", "top", E=3e7, A=0.5, I=0.05)
    fr.mass("top", 40.0, J=10.0)
    fr.foundation("F", "base", width=4.0, length=4.0, soil=soil, patches=patches, horizontal="soil", mu=mu,
                  mass=20.0, J=30.0)
    st = fr.build()
    x = st.influence("ux")
    gravity = -9.81 * (st.M @ st.influence("uy"))

    def load(t):
        return gravity - st.M @ x * (amplitude * np.sin(2 * np.pi * t) * (t < 1.0))

    return st, load


# ---------------------------------------------------------------------- the law
def test_soil_friction_couples_to_the_contact_force_and_shears_are_free():
    law = step_law([SoilContact([0]), SoilShear([1]), SoilFriction([2, 3], normal=[0, 0], mu=0.4)], 4)
    assert law.free.tolist() == [False, True, False, False] and law.rate.tolist() == [False, False, True, True]
    assert law.Q[2, 0] == law.Q[3, 0] == 0.4 and np.count_nonzero(law.Q) == 2
    assert law.partner.tolist() == [-1, -1, 3, 2] and not law.compiled_ok and not law.symmetric
    W0 = np.diag([1.0, 2.0, 3.0, 4.0])
    assert np.array_equal(law.matrix(W0), law.P @ W0 + law.Q)
    with pytest.raises(ValueError, match="not the force of a soil contact"):
        step_law([Contact([0]), SoilShear([1]), SoilFriction([2, 3], normal=[0, 0], mu=0.4)], 4)


def test_free_unknowns_are_eliminated_exactly():
    """The condensed step LCP solves the mixed problem: ``w_F = 0``, complementarity on the rest."""
    rng = np.random.default_rng(3)
    A = rng.normal(size=(6, 6))
    M = A @ A.T + 6 * np.eye(6)
    free = np.array([False, True, False, False, True, False])
    law = step_law([Contact([0, 2, 3, 5]), SoilShear([1, 4])], 6)
    step = law.step_solver(get_lcp_solver("bpp"), M)
    for _ in range(20):
        q = rng.normal(size=6)
        res = step.solve(M, q)
        w = M @ res.v + q
        assert res.success
        assert np.abs(w[free]).max() < 1e-12 and np.abs(res.w - np.where(free, 0.0, w)).max() < 1e-12
        assert res.v[~free].min() >= 0 and w[~free].min() > -1e-12 and abs(res.v[~free] @ w[~free]) < 1e-12


# ---------------------------------------------------------------------- against the primal form
@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_a_footing_that_rocks_lifts_and_slides_equals_the_papers_kelvin_elements(rule):
    """Kelvin soil: the mixed CLCP (cq, shears eliminated) equals direct stepping of the primal form
    (springs in series with friction sliders whose normal force is the contact's reaction)."""
    st, load = tower(KELVIN, 0.2)
    model = st.to_model()
    assert isinstance(model, FoundationModel) and model.sliding and model.m == 16
    kw = dict(dt=2e-3, t_end=2.0, rule=rule)
    dual = ul.solve(model, load, method="cq", **kw)
    primal = ul.solve(model.kelvin_model(), load, method="direct", **kw)
    assert dual.success and primal.success, dual.message
    from unilateral.methods.foundation_solve import primal_columns

    v, psi = primal_columns(model, primal.v, primal.psi)
    assert rel(dual.u, primal.u) < 1e-8
    assert rel(dual.psi, psi) < 1e-7 and rel(dual.v, v) < 1e-7
    fnd = st.foundation
    assert np.abs(fnd.slips(dual)[-1]).min() > 0.1           # it slid
    assert dual.v[:, :4].max() > 1e-3                          # and lifted


def test_modal_takes_the_kelvin_route_with_the_same_columns():
    st, load = tower(KELVIN, 0.2)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=1.5)
    cq = ul.solve(model, load, method="cq", **kw)
    modal = ul.solve(model, load, method="modal", **kw)
    assert modal.success and modal.constraint_names == cq.constraint_names
    assert rel(modal.u, cq.u) < 1e-8 and rel(modal.psi, cq.psi) < 1e-7 and rel(modal.psiL, cq.psiL) < 1e-7


def test_another_pivoting_solver_gets_one_face_of_each_slip_pair(monkeypatch):
    """The semismooth Newton solver leaves both faces of an open patch's slip pair active at some
    steps; the step is solved again from the basis that carries their net value on one face: the
    run equals the compiled pivoting one to the solver's tolerance."""
    from unilateral.constraints import law

    netted = []
    original = law.FreeCondensation._net_pairs

    def counting(self, res, q_R):
        out = original(self, res, q_R)
        netted.append(out is not res)
        return out

    st, load = tower(KELVIN, 0.2)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=2.0)
    reference = ul.solve(model, load, method="cq", **kw)
    monkeypatch.setattr(law.FreeCondensation, "_net_pairs", counting)
    newton = ul.solve(model, load, method="cq", lcp="newton", **kw)
    assert newton.success and any(netted)
    assert rel(newton.u, reference.u) < 1e-5


# ---------------------------------------------------------------------- the friction law
def test_slip_only_at_the_friction_limit_and_equal_to_the_relative_motion():
    """mu = 0.2 under a strong pulse: |h| <= mu c; the slip grows only where |h| = mu c, against h;
    and the slip equals footing minus soil-surface displacement, with the soil's horizontal
    Kelvin equation ``kx x + cx x' = -h`` integrated here by BDF2 from the computed forces."""
    mu, dt = 0.2, 2e-3
    st, load = tower(KELVIN, mu)
    sol = ul.solve(st.to_model(), load, method="cq", dt=dt, t_end=2.0, rule="bdf2")
    assert sol.success
    fnd = st.foundation
    c, h, slip = fnd.contact_forces(sol), fnd.shear_forces(sol), fnd.slips(sol)
    scale = c.max()
    assert (np.abs(h) - mu * c).max() < 1e-9 * scale
    assert np.abs(h[c <= 0]).max(initial=0.0) < 1e-9 * scale        # an open patch carries no shear
    ds = np.diff(slip, axis=0)
    sliding = (np.abs(ds) > 1e-12) & (c[1:] > 1e-9 * scale)
    assert sliding.sum() > 50
    assert np.abs(np.abs(h[1:][sliding]) - mu * c[1:][sliding]).max() < 1e-8 * scale
    assert np.all(np.sign(ds[sliding]) == -np.sign(h[1:][sliding]))
    kx, cx = KELVIN["kx"], KELVIN["cx"]
    f = -h                                                     # the force on the soil
    x = np.zeros_like(f)
    for n in range(1, f.shape[0]):
        x2 = x[n - 2] if n >= 2 else 0.0
        x[n] = (f[n] + cx / dt * (2 * x[n - 1] - 0.5 * x2)) / (kx + 1.5 * cx / dt)
    footing = sol.u @ fnd.Tx(st.dofs)
    relative = footing - x
    assert np.abs((relative - relative[0]) - (slip - slip[0])).max() < 1e-9 * np.abs(relative).max()


def test_a_large_mu_without_uplift_is_the_bilateral_run():
    """mu = 1000 and a load that lifts no patch: no slip, and the run equals the bilateral one
    (contacts and shears held) to round-off."""
    st, load = tower(KELVIN, 1e3, amplitude=0.5)
    model = st.to_model()
    kw = dict(dt=2e-3, t_end=1.5)
    sol = ul.solve(model, load, method="cq", **kw)
    held = ul.solve(model, load, method="cq", bilateral=True, **kw)
    assert sol.success and held.success
    assert sol.v[:, :4].max() == 0.0 and np.abs(st.foundation.slips(sol)).max() == 0.0
    assert rel(sol.u, held.u) < 1e-10
    assert rel(st.foundation.shear_forces(sol), st.foundation.shear_forces(held)) < 1e-9


def test_a_footing_sliding_on_the_half_space():
    """The x-z Green's tensor of the half-space under a footing that rocks, lifts and slides: the
    friction law holds patch by patch, and with mu = 0 the footing carries no shear at all."""
    half = {"model": "halfspace", "G": 4e4, "nu": 1 / 3, "rho": 2.0}
    for mu in (0.3, 0.0):
        st, load = tower(half, mu, patches=3)
        sol = ul.solve(st.to_model(), load, method="cq", dt=4e-3, t_end=1.2)
        assert sol.success, sol.message
        fnd = st.foundation
        c, h = fnd.contact_forces(sol), fnd.shear_forces(sol)
        assert (np.abs(h) - mu * c).max() < 1e-9 * c.max()
        if mu:
            assert np.abs(fnd.slips(sol)[-1]).min() > 1e-3 and sol.v[:, :3].max() > 0
        else:
            assert np.abs(h).max() < 1e-9 * c.max()


# ---------------------------------------------------------------------- several footings
def test_two_footings_that_slide_beside_a_gap_and_a_yielding_brace():
    """A portal frame on two Kelvin footings that slide, with a pounding gap and a yielding brace: the
    mixed CLCP equals direct stepping of the primal form."""
    fr = Frame2D()
    for name, x, y in (("a", 0.0, 0.0), ("b", 8.0, 0.0), ("c", 0.0, 4.0), ("d", 8.0, 4.0), ("stop", 8.5, 4.0)):
        fr.node(name, x, y)
    for name, i, j in (("colL", "a", "c"), ("colR", "b", "d"), ("beam", "c", "d")):
        fr.beam(name, i, j, E=3e7, A=0.2, I=2e-3)
    fr.mass("c", 20.0)
    fr.mass("d", 20.0)
    soil = {"model": "winkler-kelvin", "k": 4e4, "c": 4e2, "kx": 3e4, "cx": 3e2}
    for name, node in (("left", "a"), ("right", "b")):
        fr.foundation(name, node, width=2.0, length=2.0, soil=soil, patches=2, mass=2.0, J=1.0,
                      horizontal="soil", mu=0.25)
    fr.support("stop")
    fr.gap("pound", "d", "stop", k=2e5, gap=0.002)
    fr.yield_link("brace", "a", "d", k=5e4, Fy=60.0)
    st = fr.build()
    x = st.influence("ux")
    gravity = -9.81 * (st.M @ st.influence("uy"))

    def load(t):
        return gravity - st.M @ x * (6.0 * np.sin(2 * np.pi * 1.5 * t) * (t < 2.0))

    model = st.to_model()
    assert model.mixed and model.sliding and model.ms == 4 and model.m == model.mp + 16
    kw = dict(dt=2e-3, t_end=3.0)
    dual = ul.solve(model, load, method="cq", **kw)
    primal = ul.solve(model.kelvin_model(), load, method="direct", **kw)
    assert dual.success and primal.success, dual.message
    assert rel(dual.u, primal.u) < 1e-8
    assert np.abs(st.foundation.slips(dual)).max() > 1e-3


# ---------------------------------------------------------------------- bad input
@pytest.mark.parametrize("kwargs, match", [
    (dict(horizontal="soil"), "needs mu"),
    (dict(horizontal="support", mu=0.3), "mu=0.3 is for a footing that slides"),
    (dict(horizontal="soil", mu=-1.0), "needs mu"),
    (dict(horizontal="soil", mu=0.3, soil={"model": "winkler-kelvin", "k": 1e5}), "needs kx"),
    (dict(horizontal="soil", mu=0.3, soil={"model": "halfspace", "G": 4e4, "nu": 0.3, "rho": 2.0, "kx": 1.0}),
     "kx and cx are for model='winkler-kelvin'"),
    (dict(horizontal="support", soil={"model": "winkler-kelvin", "k": 1e5, "kx": 1e5}), "kx and cx are for a footing"),
])
def test_bad_sliding_footings_are_refused(kwargs, match):
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.node("b", 0.0, 3.0)
    fr.beam("col", "a", "b", E=3e7, A=0.2, I=2e-3)
    args = dict(width=2.0, length=2.0, soil=KELVIN, patches=2) | kwargs
    with pytest.raises(ValueError, match=match):
        fr.foundation("F", "a", **args)


def test_sliding_and_held_footings_are_not_mixed_and_a_supported_ux_cannot_slide():
    fr = Frame2D()
    for name, x in (("a", 0.0), ("b", 6.0)):
        fr.node(name, x, 0.0)
    fr.node("c", 0.0, 3.0)
    fr.node("d", 6.0, 3.0)
    for name, i, j in (("colL", "a", "c"), ("colR", "b", "d"), ("beam", "c", "d")):
        fr.beam(name, i, j, E=3e7, A=0.2, I=2e-3)
    fr.foundation("L", "a", width=2.0, length=2.0, soil=KELVIN, patches=2, horizontal="soil", mu=0.3)
    fr.foundation("R", "b", width=2.0, length=2.0, soil={"model": "winkler-kelvin", "k": 2e5}, patches=2)
    with pytest.raises(ValueError, match="cannot be mixed"):
        fr.build()
    fr = Frame2D()
    fr.node("a", 0.0, 0.0)
    fr.support("a", ux=True, uy=False, rz=False)
    with pytest.raises(ValueError, match="ux of node 'a' is supported"):
        fr.foundation("F", "a", width=2.0, length=2.0, soil=KELVIN, patches=2, horizontal="soil", mu=0.3)


MODEL_FILE = """
[units]
length = "m"
force = "kN"
time = "s"
[[nodes]]
id = 1
x = 0.0
y = 0.0
[[nodes]]
id = 2
x = 0.0
y = 6.0
[[elements]]
type = "beam"
name = "col"
node_i = 1
node_j = 2
E = 3e7
A = 0.5
I = 0.05
[[masses]]
node = 2
m = 40.0
J = 10.0
[[foundations]]
name = "F"
node = 1
width = 4.0
length = 4.0
patches = 4
horizontal = "soil"
mu = 0.3
mass = 20.0
J = 30.0
soil = { model = "winkler-kelvin", k = 2e5, c = 2e3, kx = 1.5e5, cx = 1.5e3 }
[loads.gravity]
g = "standard"
[[loads.nodal]]
node = 2
ux = 250.0
time_function = { type = "half_sine", duration = 1.0 }
[analysis]
dt = 0.004
t_end = 1.0
"""


def test_model_file_footing_that_slides(tmp_path):
    from unilateral.modelfile import ModelFileError, load_model_file

    path = tmp_path / "slide.toml"
    path.write_text(MODEL_FILE)
    spec = load_model_file(path)
    fnd = spec.structure.foundation
    assert fnd.sliding and np.all(fnd.mu == 0.3) and spec.model.m == 16
    sol = ul.solve(spec.model, spec.load, method="cq", dt=0.004, t_end=1.0)
    assert sol.success and np.abs(fnd.slips(sol)).max() > 1e-3
    for old, new, match in (("mu = 0.3\n", "", "mu: missing key"),
                            ('horizontal = "soil"\n', "", "mu = 0.3: only for horizontal"),
                            ("kx = 1.5e5, ", "", "kx: missing key")):
        path.write_text(MODEL_FILE.replace(old, new, 1))
        with pytest.raises(ModelFileError, match=match):
            load_model_file(path)
