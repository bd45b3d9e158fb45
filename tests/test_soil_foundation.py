"""A foundation lifting off a soil given in the Laplace domain (unilateral.soil.FoundationModel).

The dual CLCP in the contact forces, ``opening = openingL + (T^T D^-1 T + Phi) * c``, against:
the paper's Kelvin soil elements (the primal form, direct stepping and CQ), a Wolf cone with
trapped mass stepped as an explicit spring-dashpot-mass network with a rigid contact, AAA fits of
the rigorous half-space, and its own convergence order.
"""

from __future__ import annotations

import numpy as np
import pytest

import unilateral as ul
from unilateral.lcp import solve_lcp
from unilateral.loads import HalfSine, LoadHistory
from unilateral.march.stepper import StructureStepper
from unilateral.soil import (FoundationModel, HalfSpace, SoilFlexibility, cone, fit_rational,
                             strips)
from unilateral.structure import Frame2D
from unilateral.structure.examples import C_SOIL, K_SOIL, liolios1990


def rel(a, b):
    return float(np.abs(a - b).max() / np.abs(b).max())


# ---------------------------------------------------------------------- the paper's example
def paper_foundation():
    """The paper's example as a FoundationModel: the bare structure, T from the soil elements."""
    structure, load, _ = liolios1990()
    nat = structure.natural
    G, E = nat.G.toarray(), nat.E.toarray()
    rows = structure.constraint_strains
    structure_rows = [i for i in range(G.shape[1]) if i not in set(rows.tolist())]
    Gs = G[:, structure_rows]
    K = Gs @ E[np.ix_(structure_rows, structure_rows)] @ Gs.T      # without the soil springs
    T = G[:, rows]                       # the soil elements' strain: upward displacement of the node
    soil = SoilFlexibility.kelvin([K_SOIL] * 3, [C_SOIL] * 3)
    model = FoundationModel(structure.M.toarray(), K, T, soil, dof_names=structure.dofs.names,
                            contact_names=list(structure.constraint_names))
    return model, structure.to_model(), load


@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_kelvin_soil_equals_the_papers_kelvin_elements(rule):
    model, kelvin, load = paper_foundation()
    assert np.linalg.matrix_rank(model.K) == model.n - 2          # rests only on its soil
    kw = dict(dt=1e-3, t_end=1.0, rule=rule)
    direct = ul.solve(kelvin, load, method="direct", **kw)
    primal_cq = ul.solve(kelvin, load, method="cq", **kw)
    dual = ul.solve(model, load, method="cq", **kw)
    assert direct.success and dual.success, dual.message
    assert direct.v.max() > 2e-3 and direct.stats["contact_changes"] >= 8      # it lifts off
    assert dual.stats["contact_changes"] == direct.stats["contact_changes"]
    # measured: u 7.5e-11 / 9.8e-11, v 5.6e-11 / 5.4e-11, psi 1.8e-9 / 3.5e-9 (bdf2 / trapezoidal);
    # the primal cq itself is 4.4e-9 / 8.4e-9 off direct in psi
    assert rel(dual.u, direct.u) < 1e-9
    assert rel(dual.v, direct.v) < 1e-9
    assert rel(dual.psi, direct.psi) < 2e-8
    assert rel(dual.psiL, primal_cq.psiL) < 1e-9
    # the static state: the whole weight on three equal springs
    assert dual.u[0, model.dof_names.index("2.uy")] == pytest.approx(-40.0 * 10.0 / (3 * K_SOIL), rel=1e-9)
    # modal: the rigid footing goes through the equivalent Kelvin model, the same discrete problem
    modal = ul.solve(model, load, method="modal", **kw)
    assert rel(modal.u, direct.u) < 1e-9 and rel(modal.psi, direct.psi) < 2e-8


def test_kelvin_soil_bilateral_equals_the_papers_bilateral_case():
    model, kelvin, load = paper_foundation()
    kw = dict(dt=1e-3, t_end=0.5, bilateral=True)
    ref = ul.solve(kelvin, load, method="direct", **kw)
    sol = ul.solve(model, load, method="cq", **kw)
    assert np.all(sol.v == sol.v[0]) and np.all(sol.v == 0.0)
    assert sol.psi.max() > 0                          # held contacts pull (no uplift allowed)
    assert rel(sol.u, ref.u) < 1e-9 and rel(sol.psi, ref.psi) < 1e-8
    assert np.array_equal(sol.psi, sol.psiL)


def test_kelvin_model_is_the_papers_model():
    model, kelvin, _ = paper_foundation()
    mine = model.kelvin_model()
    for name in ("K", "F", "H", "F_v", "H_v"):
        a, b = getattr(mine, name), getattr(kelvin, name)
        a, b = (x.toarray() if hasattr(x, "toarray") else np.asarray(x) for x in (a, b))
        assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max()), name


# ---------------------------------------------------------------------- a cone with trapped mass
def block_on_cone(with_soil_node):
    """Foundation block (node 1) under a tower mass (node 2), vertical DOFs; optionally the soil
    node 3 of a vertical cone (mass dM, spring K, dashpot C to the ground)."""
    G, nu, rho, r0 = 5e4, 0.45, 2.0, 1.5
    c = cone("vertical", G, nu, rho, r0)
    assert c.dM > 0                                             # nu > 1/3: trapped mass
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, 4.0)
    for node in (1, 2):
        fr.support(node, ux=True, uy=False)
    fr.bar("tower", 1, 2, E=2e6, A=1.0)
    fr.mass(1, 30.0)
    fr.mass(2, 20.0)
    if with_soil_node:
        fr.node(3, 0.0, -1.0)
        fr.support(3, ux=True, uy=False)
        fr.mass(3, c.dM)
        fr.spring("cone_K", 3, c.K)
        fr.dashpot("cone_C", 3, c.C)
    st = fr.build()
    nat = st.natural
    K = (nat.G @ nat.E @ nat.G.T).toarray()
    C = None if st.C is None else st.C.toarray()
    return st, st.M.toarray(), K, C, c


def step_rigid_contact(M, K, C, a, q, rule, dt):
    """Direct stepping with the rule of a structure with one rigid unilateral contact of opening
    ``a^T u``, contact force ``c >= 0`` acting as ``a c``: one LCP per step (test reference)."""
    n, N = M.shape[0], q.shape[0] - 1
    # static state in contact: [K -a; a^T 0] (u, c) = (q0, 0)
    S = np.block([[K, -a[:, None]], [a[None, :], np.zeros((1, 1))]])
    x = np.linalg.solve(S, np.concatenate([q[0], [0.0]]))
    u_b, c_b = x[:n], x[n:]
    assert c_b[0] > 0
    rigid = FoundationModel(M, K, a[:, None], SoilFlexibility.callable(lambda s: np.zeros((len(s), 1, 1)), 1), C=C)
    stepper = StructureStepper(rigid.stepping_model(), ul.get_rule(rule), dt, q - q[0], np.zeros((N + 1, 1)),
                               None, condensed=True)
    W = -stepper.W0                                   # a^T D_eff^-1 a
    u, c, opening = np.zeros((N + 1, n)), np.zeros(N + 1), np.zeros(N + 1)
    u[0], c[0] = u_b, c_b[0]
    for k in range(1, N + 1):
        _, free = stepper.predict()
        res = solve_lcp(W, free - W @ c_b, tol=1e-14)
        assert res.success
        du, _ = stepper.correct(res.v - c_b)
        u[k], c[k], opening[k] = u_b + du, res.v[0], (free + W @ (res.v - c_b))[0]
    return u, c, opening


@pytest.mark.parametrize("rule", ["bdf1", "bdf2"])
def test_cone_with_trapped_mass_equals_its_network(rule):
    """BDF only: a rigid contact between two masses (the block and the trapped soil mass) is an
    index-3 problem on which the trapezoidal rule's contact forces chatter (125 contact changes
    against 10 for BDF2 here), and round-off then decides the contact sets."""
    st, M, K, C, c = block_on_cone(with_soil_node=False)
    model = FoundationModel(M, K, np.array([[1.0], [0.0]]), SoilFlexibility.impedances([c]),
                            dof_names=st.dofs.names, contact_names=["cone"])
    dt, N = 1e-3, 600
    t = np.arange(N + 1) * dt
    weight = st.gravity(10.0)
    lift = 3.0 * 500.0 * np.sin(np.pi * t / 0.06) * (t < 0.06)           # 3x the weight, upward
    q = weight[None, :] + np.outer(lift, st.nodal_load(1, uy=1.0))
    sol = ul.solve(model, q, dt=dt, t_end=N * dt, method="cq", rule=rule)
    assert sol.success and sol.stats["contact_changes"] >= 2 and sol.v.max() > 1e-3
    # the network: the same structure plus the soil node, a rigid contact between nodes 1 and 3
    stn, Mn, Kn, Cn, _ = block_on_cone(with_soil_node=True)
    a = np.zeros(stn.n)
    a[stn.dofs.index(1, "uy")], a[stn.dofs.index(3, "uy")] = 1.0, -1.0
    qn = np.zeros((N + 1, stn.n))
    for node in (1, 2):
        qn[:, stn.dofs.index(node, "uy")] = q[:, st.dofs.index(node, "uy")]
    u, force, opening = step_rigid_contact(Mn, Kn, Cn, a, qn, rule, dt)
    idx = [stn.dofs.index(node, "uy") for node in (1, 2)]
    # measured (bdf1 / bdf2): u 3.3e-12 / 1.4e-11, v 3.5e-13 / 7.6e-13, c 2.4e-11 / 4.6e-11
    assert rel(sol.u, u[:, idx]) < 1e-9
    assert rel(sol.v[:, 0], opening) < 1e-9
    assert rel(-sol.psi[:, 0], force) < 1e-9
    # the soil node is not in the foundation model: its cone impedance carries it
    assert c.dM / (M[0, 0]) > 0.1


def test_a_rigid_footing_on_a_non_kelvin_rational_soil_is_refused_by_modal_and_auto_uses_cq():
    st, M, K, C, c = block_on_cone(with_soil_node=False)
    model = FoundationModel(M, K, np.array([[1.0], [0.0]]), SoilFlexibility.impedances([c]))
    q = np.tile(st.gravity(10.0), (101, 1))
    with pytest.raises(ValueError, match="pole at s = 0.*method='cq'"):
        ul.solve(model, q, dt=1e-3, t_end=0.1, method="modal")
    sol = ul.solve(model, q, dt=1e-3, t_end=0.1)
    assert sol.stats["method"] == "cq" and "modal refused" in sol.stats["method_reason"]
    # at rest under its weight: nothing moves, the soil carries the weight
    assert np.allclose(sol.u, sol.u[0], atol=1e-12 * np.abs(sol.u).max())
    assert -sol.psi[:, 0] == pytest.approx(np.full(101, 500.0), rel=1e-10)


# ---------------------------------------------------------------------- the rigorous half-space
HALF_WIDTH = 2.0


def footing_on_halfspace(soil=None, *, piles=False, m=3):
    """A rigid footing (node 2: uy, rz) carrying a tower (node 1 at 6 m) on ``m`` strips of a
    4 m x 4 m footing on a half-space (kN, m, s). ``piles``: springs under node 2 (K definite)."""
    fr = Frame2D()
    fr.node(1, 0.0, 6.0)
    fr.node(2, 0.0, 0.0)
    fr.support(2, ux=True, uy=False)
    fr.beam("tower", 2, 1, E=3e7, A=0.5, I=0.05)
    fr.mass(1, 40.0)
    fr.mass(2, 20.0, J=30.0)
    if piles:
        fr.spring("pile", 2, 2e5)
        fr.spring("pile_rz", 2, 5e5, direction="rz")
    st = fr.build()
    nat = st.natural
    K = (nat.G @ nat.E @ nat.G.T).toarray()
    patches = strips(2 * HALF_WIDTH, 2 * HALF_WIDTH, m)
    T = np.zeros((st.n, m))
    T[st.dofs.index(2, "uy")] = 1.0
    T[st.dofs.index(2, "rz")] = patches.centres[:, 0]         # z = u_y + x theta
    if soil is None:
        soil = SoilFlexibility.halfspace(HalfSpace(1e5, 0.3, 2.0), patches)
    model = FoundationModel(st.M.toarray(), K, T, soil, dof_names=st.dofs.names,
                            contact_names=[f"strip{j}" for j in range(m)])
    return st, model, patches


def rocking_load(st, push):
    return LoadHistory(st.gravity(10.0), [(st.nodal_load(1, ux=1.0), HalfSine(push, duration=0.2))])


def test_halfspace_uplift_satisfies_the_lcp_at_every_step():
    st, model, _ = footing_on_halfspace()
    sol = ul.solve(model, rocking_load(st, 200.0), dt=2e-3, t_end=0.6, method="cq")
    assert sol.success, sol.message
    v, c = sol.v, -sol.psi
    scale_v, scale_c = v.max(), c.max()
    assert scale_v > 1e-4 and sol.stats["contact_changes"] >= 2      # the edges lift off
    assert v.min() >= -1e-12 * scale_v and c.min() >= -1e-12 * scale_c
    assert np.abs(v * c).max() <= 1e-10 * scale_v * scale_c
    assert sol.stats["max_lcp_error"] < 1e-12
    # the openings of the LCPs are the definition's v = T^T u + Phi * c + gap, with u recovered
    # by stepping the structure and the soil's convolution computed independently by CQ
    Wphi = ul.cq_weights(model.soil.evaluate, len(sol.t) - 1, 2e-3, ul.get_rule("bdf2"))
    dc = c - c[0]
    conv = np.array([np.einsum("jab,jb->a", Wphi[: k + 1], dc[k::-1]) for k in range(len(sol.t))])
    v_def = sol.u @ model.T + conv + model.soil.static() @ c[0] + model.gap
    assert np.abs(v_def - v).max() < 1e-9 * scale_v               # measured ~1e-12 of the peak
    # static state: the contact forces carry the weight, the footing is level and on the soil
    assert c[0].sum() == pytest.approx(600.0, rel=1e-10)
    assert np.all(v[0] == 0)
    # the held (bilateral) contact forces: psiL at t = 0 is the static state too
    assert np.allclose(sol.psiL[0], sol.psi[0])


def test_halfspace_cq_converges_at_order_two_bdf2():
    st, model, _ = footing_on_halfspace()
    load = rocking_load(st, 30.0)                              # smooth, no contact change
    t_end, dts = 0.4, [4e-3, 2e-3, 1e-3, 5e-4]
    sols = [ul.solve(model, load, dt=dt, t_end=t_end, method="cq", rule="bdf2") for dt in dts]
    assert all(s.stats["contact_changes"] == 0 and s.v.max() < 1e-15 for s in sols)
    # differences of successive runs, u and psi = -c at the coarser grid: ~ C dt^p
    errors = []
    for coarse, fine in zip(sols[:-1], sols[1:]):
        errors.append(max(rel(coarse.u, fine.u[::2]), rel(coarse.psi, fine.psi[::2])))
    slope = np.polyfit(np.log(dts[:-1]), np.log(errors), 1)[0]
    # measured: differences 9.8e-3, 2.5e-3, 6.5e-4 (u) and 3.3e-3, 8.5e-4, 2.1e-4 (psi); slope 1.96
    assert slope >= 1.9, (errors, slope)


def aaa_soil(hs, patches, fmax=500.0, samples=150):
    """Entry-by-entry AAA fits of the rigorous flexibility on the imaginary axis.

    Returns the soil and the fit's matrix-relative error ``max ||Phi_fit - Phi|| / ||Phi||`` on
    the samples and on a 4x denser grid over the same band (between the samples).
    """
    f = np.concatenate([[0.0], np.geomspace(0.05, fmax, samples)])
    Phi = hs.surface_flexibility(patches, 2j * np.pi * f)
    m = patches.m
    fits = [[None] * m for _ in range(m)]
    for i in range(m):
        for j in range(i, m):
            fits[i][j] = fits[j][i] = fit_rational(f, Phi[:, i, j], linear=False, rtol=1e-7, max_terms=30)
    soil = SoilFlexibility.rational(fits)

    def error(freq, exact):
        fitted = soil.evaluate(2j * np.pi * freq)
        return float(np.max(np.linalg.norm(fitted - exact, axis=(1, 2)) / np.linalg.norm(exact, axis=(1, 2))))

    dense = np.concatenate([[0.0], np.geomspace(0.01, fmax, 4 * samples)])
    return soil, error(f, Phi), error(dense, hs.surface_flexibility(patches, 2j * np.pi * dense))


@pytest.mark.filterwarnings("ignore:AAA failed to converge")
def test_aaa_fit_of_the_halfspace_runs_modal_and_matches_the_rigorous_kernel():
    hs = HalfSpace(1e5, 0.3, 2.0)
    st, rigorous, patches = footing_on_halfspace(piles=True, m=2)
    soil, sample_error, error = aaa_soil(hs, patches)
    # measured: 3.4e-6 on the samples, 1.3e-3 between them (0 ... 500 Hz); 98 poles
    assert soil.is_rational and 0 < sample_error <= error < 1e-2
    _, fitted, _ = footing_on_halfspace(soil, piles=True, m=2)
    load = rocking_load(st, 400.0)
    kw = dict(dt=2e-3, t_end=0.5)                  # CQ samples Phi up to |s| = 4/dt (318 Hz)
    ref = ul.solve(rigorous, load, method="cq", **kw)
    cq = ul.solve(fitted, load, method="cq", **kw)
    modal = ul.solve(fitted, load, method="modal", **kw)
    assert ref.v.max() > 1e-3 and ref.stats["contact_changes"] >= 2
    # the same rational kernel: cq and the recursive history agree to round-off (measured 4e-13, 2e-12)
    assert rel(modal.u, cq.u) < 1e-9 and rel(modal.psi, cq.psi) < 1e-9
    assert modal.stats["modal"]["soil_poles"] > 0
    # the fit against the rigorous kernel, within the fit error (measured: u 3e-10, v 6e-9, psi 7e-7)
    for name in ("u", "v", "psi"):
        assert rel(getattr(cq, name), getattr(ref, name)) < error, name
    # auto picks the recursive history for a rational soil
    auto = ul.solve(fitted, load, **kw)
    assert auto.stats["method"] == "modal" and rel(auto.u, modal.u) < 1e-12


# ---------------------------------------------------------------------- bad input
def test_bad_input_is_refused_with_clear_messages():
    st, model, patches = footing_on_halfspace(SoilFlexibility.kelvin([1e5] * 3, 1e3))
    M, K, T = model.M, model.K, model.T
    soil = model.soil
    with pytest.raises(ValueError, match=r"T has shape \(4, 3\), expected \(5, any\)"):
        FoundationModel(M, K, T[:4], soil)
    with pytest.raises(ValueError, match="soil has m = 2 rows but T has 3 columns"):
        FoundationModel(M, K, T, SoilFlexibility.kelvin([1e5, 1e5]))
    with pytest.raises(TypeError, match="soil must be a SoilFlexibility"):
        FoundationModel(M, K, T, np.eye(3))
    with pytest.raises(ValueError, match=r"k must be > 0 \(soil springs\); k\[1\] = -1"):
        SoilFlexibility.kelvin([1e5, -1.0, 1e5])
    with pytest.raises(ValueError, match=r"c must be >= 0 \(soil dashpots\); c\[0\] = -2"):
        SoilFlexibility.kelvin([1e5], [-2.0])
    with pytest.raises(ValueError, match=r"gap must have shape \(3,\)"):
        FoundationModel(M, K, T, soil, gap=[0.0, 0.0])
    with pytest.raises(ValueError, match=r"K must be positive semidefinite; K\[0, 0\] = -9"):
        FoundationModel(M, K - 1e9 * np.eye(5), T, soil)
    indefinite = K.copy()
    indefinite[0, 3] = indefinite[3, 0] = 10 * np.sqrt(K[0, 0] * K[3, 3])
    with pytest.raises(ValueError, match="K must be symmetric positive semidefinite; its smallest eigenvalue"):
        FoundationModel(M, indefinite, T, soil)
    with pytest.raises(ValueError, match="zero-stiffness mode without mass or damping"):
        FoundationModel(np.zeros((5, 5)), K, T, soil)
    with pytest.raises(ValueError, match="impedances.1.: the dashpot c must be >= 0"):
        SoilFlexibility.impedances([(1e5, 1.0), (1e5, -1.0)])
    with pytest.raises(TypeError, match="one impedance per contact"):
        SoilFlexibility.impedances((1e5, 1e3))
    with pytest.raises(TypeError, match="patches must be RectangularPatches"):
        SoilFlexibility.halfspace(HalfSpace(1e5, 0.3, 2.0), [[0.0, 0.0]])
    load = rocking_load(st, 10.0)
    penetrating = FoundationModel(M, K, T, soil, gap=[-1e-3, 0.0, 0.0], contact_names=model.contact_names)
    for method in ("cq", "modal"):
        with pytest.raises(ValueError, match="penetrates the unloaded soil at contact 'strip0'"):
            ul.solve(penetrating, load, dt=1e-3, t_end=0.01, initial="rest", method=method)
    with pytest.raises(ValueError, match="initial for a FoundationModel takes 'u0' and 'udot0'"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, initial={"v0": [0.0] * 3})
    creeping = SoilFlexibility.halfspace(HalfSpace(1e5, 0.3, 2.0, damping=0.05), patches)
    _, creep_model, _ = footing_on_halfspace(creeping)
    with pytest.raises(ValueError, match="has no static flexibility Phi.0."):
        ul.solve(creep_model, load, dt=1e-3, t_end=0.01)
    _, hs_model, _ = footing_on_halfspace()
    with pytest.raises(ValueError, match="has no pole-residue form; use method='cq'"):
        ul.solve(hs_model, load, dt=1e-3, t_end=0.01, method="modal")
    with pytest.raises(ValueError, match="method='direct' solves a Model"):
        ul.solve(model, load, dt=1e-3, t_end=0.01, method="direct")
    bad = SoilFlexibility.callable(lambda s: np.ones((len(s), 2, 2)), 3)
    with pytest.raises(ValueError, match=r"returned shape \(\d+, 2, 2\) .* expected \(\d+, 3, 3\)"):
        ul.solve(FoundationModel(M, K, T, bad), load, dt=1e-3, t_end=0.01, initial="rest")


def test_a_soil_from_a_gap_starts_at_rest_and_falls_onto_the_soil():
    """initial='rest' with an open gap: the footing falls under gravity, lands, stays in contact."""
    st, model, _ = footing_on_halfspace(SoilFlexibility.kelvin([3e5] * 3, 2e3))
    gapped = FoundationModel(model.M, model.K, model.T, model.soil, gap=1e-3, dof_names=model.dof_names)
    load = LoadHistory(st.gravity(10.0), [])
    sol = ul.solve(gapped, load, dt=1e-3, t_end=0.3, initial="rest", method="cq")
    # modal takes the Kelvin model (the primal form): the same problem, but its start differs when
    # the load jumps at t = 0 on a footing with mass (BDF2 starts u from a quadratic, the opening
    # from rest): an O(dt^2) difference, measured 7.9e-5 (u)
    modal = ul.solve(gapped, load, dt=1e-3, t_end=0.3, initial="rest", method="modal")
    assert modal.stats["formulation"].startswith("primal") and "Kelvin model" in modal.stats["foundation_route"]
    assert rel(modal.u, sol.u) < 1e-3
    assert "chatter" not in sol.message
    uy = sol.dof("2.uy")
    first = int(np.argmax(sol.v[:, 1] == 0))
    assert first > 0 and np.all(sol.psi[:first] == 0)
    # free fall until the contact closes: u = -g t^2 / 2 (BDF2 is exact for a quadratic after
    # its start-up, to round-off)
    t = sol.t[:first]
    assert np.allclose(uy[:first], -5.0 * t ** 2, rtol=1e-9, atol=1e-15)
    assert sol.v[-1].max() < 1e-15 and -sol.psi[-1].sum() == pytest.approx(600.0, rel=2e-2)


def test_a_coupled_cone_model_that_would_create_energy_is_refused_and_the_half_space_is_passive():
    """The admittance i omega Phi(i omega) of a soil must have a positive semidefinite Hermitian part
    (it absorbs energy); the coupled cones' does not, the rigorous half-space's does."""
    from unilateral.soil import HalfSpace, strips
    from unilateral.soil.flexibility import SoilFlexibility, _check_passive

    patches = strips(10.0, 10.0, 2)
    with pytest.raises(ValueError, match=r"not passive: the Hermitian part of i omega Phi\(i omega\) has a negative eigenvalue \(-0\.\d+ of"):
        SoilFlexibility.cones(patches, 18.8e3, 1 / 3, 2.0)
    assert SoilFlexibility.cones(strips(10.0, 10.0, 1), 18.8e3, 1 / 3, 2.0).m == 1     # one cone: passive
    halfspace = HalfSpace(18.8e3, 1 / 3, 2.0)
    _check_passive(lambda s: halfspace.surface_flexibility(patches, s), patches, 18.8e3, 2.0)
