"""Friction polygons of more than four facets: the compiled and the Python engines solve every step alike.

A polygon's facet columns are linearly dependent (more than two facets on two tangential strains),
so the step LCP is not a P-matrix and block principal pivoting may meet a singular principal
submatrix or cycle. Both engines solve each step with :func:`unilateral.lcp.pivoting.solve_step`
(the face rules, Lemke's method where they fail; ``stats["lcp_fallbacks"]`` counts those steps).
Before, the compiled engine stopped where the Python one went on and the other way round (a 3-D
frame on four contacts with 12 facets and mu = 0.1; a footing sliding in plan with 8 facets).
Checked: both engines finish, agree to 1e-10 of the peak, and every step meets the LCP conditions.
"""

from __future__ import annotations

import numpy as np
import pytest

import unilateral as ul
from unilateral.lcp import Lemke
from unilateral.lcp.faces import FaceSetPivoting
from unilateral.methods.direct import Direct
from unilateral.structure import Frame3D

COLUMN = dict(E=3e7, A=0.25, Iy=5e-3, Iz=5e-3, G=1.2e7, J=8e-3)
KELVIN = {"model": "winkler-kelvin", "k": 2e5, "c": 2e3, "kx": 1.5e5, "cx": 1.5e3}
TOWER = dict(E=3e7, A=0.5, Iy=0.05, Iz=0.05, G=1.2e7, J=0.08)


def frame(facets, mu):
    """A one-storey 3-D frame (4 columns, 4 beams, unequal masses) on four soil contacts with
    friction polygons of ``facets`` facets."""
    fr = Frame3D()
    for i, (x, y) in enumerate([(0, 0), (4, 0), (0, 4), (4, 4)]):
        fr.node(f"b{i}", x, y, 0.0)
        fr.node(f"t{i}", x, y, 3.0)
        fr.beam(f"c{i}", f"b{i}", f"t{i}", **COLUMN)
        fr.mass(f"b{i}", 1.0)
        fr.mass(f"t{i}", 10.0 + 3 * i)
        fr.soil(f"s{i}", f"b{i}", 1e6, mu=mu, kt=2e5, facets=facets)
        fr.support(f"b{i}", ux=False, uy=False, uz=False, rx=True, ry=True, rz=True)
    for a, b in ((0, 1), (1, 3), (3, 2), (2, 0)):
        fr.beam(f"g{a}{b}", f"t{a}", f"t{b}", **COLUMN)
    fr.rayleigh(a0=0.5)
    return fr.build()


def shake(st, amplitude, angle=0.3):
    gravity = st.gravity(9.81)
    d = np.cos(angle) * st.influence("ux") + np.sin(angle) * st.influence("uy")
    return lambda t: gravity - st.M @ d * (amplitude * np.sin(2 * np.pi * 1.3 * t))


def tower(facets, mu):
    """A column with a top mass on a rigid footing (2 x 2 patches on Kelvin soil) that slides in plan."""
    fr = Frame3D()
    fr.node("base", 0.0, 0.0, 0.0)
    fr.node("top", 0.0, 0.0, 6.0)
    fr.beam("col", "base", "top", **TOWER)
    fr.mass("top", 40.0, Jz=10.0)
    fr.foundation("F", "base", width=4.0, length=4.0, soil=KELVIN, patches=(2, 2), horizontal="soil", mu=mu,
                  facets=facets, mass=20.0, Jx=30.0, Jy=30.0, Jz=30.0)
    st = fr.build()
    gravity = st.gravity(9.81)
    d = np.cos(0.5) * st.influence("ux") + np.sin(0.5) * st.influence("uy")
    return st, lambda t: gravity - st.M @ d * (8.0 * np.sin(2 * np.pi * t) * (t < 1.0))


def strains(st):
    """``B`` (strains, m): the strains of the constraint unknowns (openings, net slips in plan)."""
    return st.natural.B.toarray()


def both(model, load, **kw):
    runs = {e: ul.solve(model, load, method=Direct(engine=e), rule="trapezoidal", **kw) for e in ("compiled", "python")}
    assert runs["compiled"].stats["engine"] == "compiled" and runs["python"].stats["engine"] == "python"
    return runs["compiled"], runs["python"]


def assert_lcp_conditions(model, sol):
    """Every step: ``psi <= tol``; contacts ``v >= -tol``, ``|psi v|`` small; rate unknowns (slips)
    the same on their increments."""
    rate = model.law.rate
    v, psi = sol.v, sol.psi
    tol_psi = 1e-9 * np.abs(psi).max()
    tol_v = 1e-9 * max(np.abs(v).max(), 1e-300)
    assert psi.max() <= tol_psi
    z = np.where(rate, np.diff(v, axis=0, prepend=v[:1]), v)[1:]
    assert z.min() >= -tol_v
    assert np.abs(psi[1:] * z).max() <= 1e-9 * np.abs(psi).max() * np.abs(z).max()


def assert_agree(a, b, B, rel=1e-10):
    """``u``, ``psi`` and the strains of the unknowns ``B v`` (the openings and the net slips) agree:
    the facet multipliers themselves are not unique where a contact is open (its slip is free, and
    two facets other than the adjacent ones may carry it)."""
    for x, y in ((a.u, b.u), (a.psi, b.psi), (a.v @ B.T, b.v @ B.T)):
        assert x.shape == y.shape
        np.testing.assert_allclose(x, y, rtol=0, atol=rel * np.abs(y).max())


@pytest.mark.parametrize("facets, mu, amplitude", [(4, 0.5, 3.0), (6, 0.5, 3.0), (8, 0.5, 3.0), (12, 0.1, 3.0),
                                                   (12, 0.1, 8.0)])
def test_a_frame_on_polygonal_contacts_is_solved_alike_by_both_engines(facets, mu, amplitude):
    st = frame(facets, mu)
    model = st.to_model()
    compiled, python = both(model, shake(st, amplitude), dt=2e-3, t_end=1.0)
    assert compiled.success and python.success, (compiled.message, python.message)
    assert len(compiled.t) == len(python.t) == 501
    assert python.v[:, 1:].max() > 1e-3 * np.abs(python.u).max()          # it slides
    assert_agree(compiled, python, strains(st))
    for sol in (compiled, python):
        assert_lcp_conditions(model, sol)
        assert sol.stats["lcp_fallbacks"] >= 0
    if facets == 4:                                 # pairs only: block principal pivoting suffices
        assert compiled.stats["lcp_fallbacks"] == python.stats["lcp_fallbacks"] == 0


def test_the_hard_case_needs_the_fallback_in_both_engines_and_they_count_it():
    """12 facets, mu = 0.1 under a strong shaking: before, the compiled engine stopped at step 314."""
    st = frame(12, 0.1)
    compiled, python = both(st.to_model(), shake(st, 8.0), dt=2e-3, t_end=1.0)
    assert compiled.success and python.success
    assert compiled.stats["lcp_fallbacks"] > 0 and python.stats["lcp_fallbacks"] > 0
    assert_agree(compiled, python, strains(st))


@pytest.mark.parametrize("facets, mu", [(4, 0.2), (8, 0.2), (8, 0.3), (12, 0.2)])
def test_a_footing_sliding_in_plan_is_solved_alike_by_both_engines(facets, mu):
    """The primal (Kelvin) form of a footing sliding in plan: before, the Python engine stopped at
    step 118 (8 facets, mu 0.3) and both stopped with 8 facets, mu 0.2."""
    st, load = tower(facets, mu)
    model = st.to_model().kelvin_model()
    compiled, python = both(model, load, dt=2e-3, t_end=2.0)
    assert compiled.success and python.success, (compiled.message, python.message)
    assert len(compiled.t) == 1001
    # u to 1e-10 of its peak (measured 1.0e-11 .. 2.3e-11); psi to 1e-7 (measured 9e-10 .. 1.3e-8:
    # the Kelvin dashpots' forces alternate step to step under the trapezoidal rule, which amplifies
    # round-off); the multipliers are not unique (several facet splits give one slip)
    np.testing.assert_allclose(compiled.u, python.u, rtol=0, atol=1e-10 * np.abs(python.u).max())
    np.testing.assert_allclose(compiled.psi, python.psi, rtol=0, atol=1e-7 * np.abs(python.psi).max())
    for sol in (compiled, python):
        assert_lcp_conditions(model, sol)
    if facets > 4 and mu == 0.2:                    # the steps that failed before need the fallback
        assert compiled.stats["lcp_fallbacks"] > 0 and python.stats["lcp_fallbacks"] > 0


# ---------------------------------------------------------------------- the step solver
def polygon_lcp(facets=8, mu=0.3, seed=0):
    """A step LCP of one contact with a polygon of ``facets`` facets that has a solution: ``W = P W0``
    with ``W0`` the flexibility of a normal and two tangential strains, the facets' columns
    ``d_k . (t1, t2)``."""
    rng = np.random.default_rng(seed)
    th = 2 * np.pi * np.arange(facets) / facets
    B = np.zeros((3, 1 + facets))
    B[0, 0] = 1.0
    B[1, 1:], B[2, 1:] = np.cos(th), np.sin(th)
    A = rng.normal(size=(3, 3))
    W0 = B.T @ (A @ A.T + np.diag([1.0, 0.5, 0.5])) @ B
    P = np.eye(1 + facets)
    P[1:, 0] = mu
    v = np.zeros(1 + facets)                # a solution: the contact open, slipping on two adjacent facets
    k = int(rng.integers(facets))
    v[[0, 1 + k, 1 + (k + 1) % facets]] = rng.uniform(0.1, 1.0, size=3)
    w = np.where(v > 0, 0.0, rng.uniform(0.1, 1.0, size=1 + facets))
    q = w - P @ W0 @ v
    partner = np.array([-1] + [1 + (k + facets // 2) % facets for k in range(facets)])
    group = np.array([-1] + [0] * facets)
    return P @ W0, q, partner, group


@pytest.mark.parametrize("facets", [6, 8, 12])
def test_the_step_solver_solves_polygon_lcps_where_lemke_does(facets):
    solved = 0
    for seed in range(20):
        W, q, partner, group = polygon_lcp(facets, seed=seed)
        res = FaceSetPivoting(partner, group, symmetric=False).solve(W, q)
        ref = Lemke().solve(W, q)
        if ref.success:
            assert res.success, res.message
        if res.success:
            solved += 1
            assert res.v.min() >= 0.0 and res.w.min() >= -1e-10 * (1 + np.abs(q).max())
            assert abs(res.v @ res.w) <= 1e-10 * (1 + np.abs(q).max()) * (1 + res.v.max())
            assert np.count_nonzero(res.active[1:]) <= 2                 # at most two facets
            np.testing.assert_allclose(W @ res.v + q, res.w, atol=1e-10 * (1 + np.abs(q).max()))
    assert solved >= 15


def test_the_step_solver_counts_its_fallbacks_and_gives_v_0_for_q_nonnegative():
    W, q, partner, group = polygon_lcp(8)
    solver = FaceSetPivoting(partner, group, symmetric=False)
    res = solver.solve(W, np.abs(q))
    assert res.success and res.iterations == 0 and not res.v.any() and not res.fallback
    assert solver.fallbacks == 0


@pytest.mark.parametrize("kwargs, message", [
    (dict(partner=[0.5, -1], group=[-1, -1]), "partner must be a 1-D integer array"),
    (dict(partner=[-1, -1], group=[[-1, -1]]), "group must be a 1-D integer array"),
    (dict(partner=[-1, -1], group=[-1]), r"group must have the shape of partner \(2,\), got shape \(1,\)"),
    (dict(partner=[-1, 5], group=[-1, -1]), r"partner\[1\] = 5 is not an unknown: valid are -1 \(none\) and 0 .. 1"),
    (dict(partner=[-1, -1], group=[-1, -1], tol=0.0), "tol must be positive, got tol=0.0"),
    (dict(partner=[-1, -1], group=[-1, -1], max_iter=0), "max_iter must be a positive integer or None"),
])
def test_bad_faces_are_refused_naming_the_argument(kwargs, message):
    partner, group = np.asarray(kwargs.pop("partner")), np.asarray(kwargs.pop("group"))
    with pytest.raises(ValueError, match=message):
        FaceSetPivoting(partner, group, symmetric=False, **kwargs)


def test_a_problem_of_another_size_is_refused():
    solver = FaceSetPivoting(np.array([-1, -1]), np.array([-1, -1]), symmetric=True)
    with pytest.raises(ValueError, match="q has m = 3 unknowns but the faces"):
        solver.solve(np.eye(3), -np.ones(3))
