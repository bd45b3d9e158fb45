"""Coulomb friction in the tangent plane of a 3-D contact as a polygonal friction cone of N facets.

The polygon circumscribes Coulomb's circle ``|T| <= mu N``: facet ``k`` (outward normal
``d_k = (cos th_k, sin th_k)``, ``th_k = 2 pi k / N`` from ``t1``) keeps ``d_k . T <= mu N``. Its
strength along ``phi`` is ``mu N / cos(phi - th_k)`` (``th_k`` the nearest facet normal), at most
``sec(pi/N)`` times Coulomb's (along the vertices); in steady sliding under a push ``P`` the slip
runs along ``P - proj(P)`` (``proj``: the projection on the polygon), at most ``pi/N`` away from
``P``. ``facets=4`` is the four-sided pyramid the contacts had before. Checked on a block (a unit
mass on a friction contact) pushed in plan.
"""

from __future__ import annotations

import numpy as np
import pytest

import unilateral as ul
from unilateral.structure import Frame2D, Frame3D
from unilateral.structure import elements as el
from unilateral.structure import elements3d as el3

MU, GRAVITY, KT = 0.5, 10.0, 1e5
#: The compression of the block on its contact, and Coulomb's strength.
WEIGHT = 1.0 * GRAVITY
COULOMB = MU * WEIGHT
FACETS = (4, 8, 16, 32)


def block(facets=4, *, kt=KT, **friction):
    """A unit mass on a tensionless soil contact along z with friction (a polygon of ``facets``),
    with a drag (mass-proportional damping) that makes its sliding steady."""
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.mass(1, 1.0)
    fr.soil("s", 1, 1e6, mu=MU, kt=kt, facets=facets, **friction)
    fr.rayleigh(a0=20.0)
    return fr.build()


def push(st, P, alpha, *, ramp, t_end, dt=0.005, start=0.0, method="direct", lcp="bpp"):
    """The block under its weight and a push in plan at the angle ``alpha`` from x, ramped from
    ``start`` (at t = 0: the static state under it is the initial state) to ``P`` over ``ramp``,
    then held."""
    weight = st.gravity(GRAVITY, (0.0, 0.0, -1.0))
    unit = st.nodal_load(1, ux=np.cos(alpha), uy=np.sin(alpha))

    def load(t):
        return weight + (start + (P - start) * min(t / ramp, 1.0)) * unit

    return ul.solve(st.to_model(), load, dt=dt, t_end=t_end, method=method, rule="trapezoidal", lcp=lcp)


def strength(alpha, N):
    """The polygon's strength along ``alpha``: ``mu N / cos(alpha - th_k)``, ``th_k`` the nearest
    facet normal."""
    gap = (alpha + np.pi / N) % (2 * np.pi / N) - np.pi / N
    return COULOMB / np.cos(gap)


def projection(P, N):
    """The point of the polygon nearest to ``P`` (2,) (``P`` outside): the force of steady sliding."""
    th = 2 * np.pi * np.arange(N) / N
    vertices = COULOMB / np.cos(np.pi / N) * np.column_stack([np.cos(th + np.pi / N), np.sin(th + np.pi / N)])
    best = None
    for a, b in zip(vertices, np.roll(vertices, -1, axis=0)):
        s = np.clip((P - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        x = a + s * (b - a)
        if best is None or np.linalg.norm(P - x) < np.linalg.norm(P - best):
            best = x
    return best


def slip_direction(sol, tail=0.5):
    """The direction (angle from x) of the block's motion over the last ``tail`` of the run."""
    k = int(round(tail / (sol.t[1] - sol.t[0])))
    du = sol.u[-1, :2] - sol.u[-1 - k, :2]
    return float(np.arctan2(du[1], du[0]))


def onset(sol):
    """The index of the first step with a slip."""
    slipping = np.flatnonzero(sol.v[:, 1:].max(axis=1) > 0.0)
    assert slipping.size, "the block never slides"
    return int(slipping[0])


def success(sol):
    assert sol.t[-1] == pytest.approx(sol.t[0] + (len(sol.t) - 1) * (sol.t[1] - sol.t[0]))
    assert "stopped" not in sol.message, sol.message


# ---------------------------------------------------------------------- facets=4: the pyramid
def old_pyramid(name, kt):
    """The unknowns of the four-sided pyramid as :func:`elements3d.frictional` built them before
    the polygon: two slip pairs on the tangential strains 1 and 2."""
    from dataclasses import replace

    second = tuple(replace(u, name=u.name.replace(".slip", ".slip2"))
                   for u in el.pair(name, 2, "friction", normal=name, mu=MU, k=kt))
    return (el.Unknown(name, 0, 1.0, 0.0), *el.pair(name, 1, "friction", normal=name, mu=MU, k=kt), *second)


def test_four_facets_are_the_pyramid_of_before():
    st = block(4)
    assert st.constraint_names == ("s", "s.slip+", "s.slip-", "s.slip2+", "s.slip2-")
    assert block(kt=KT).constraint_names == st.constraint_names        # the default is 4
    assert st.elements[0].unknowns == old_pyramid("s", KT)               # every field, no extra entry
    B = st.natural.B.toarray()
    np.testing.assert_array_equal(B, [[1, 0, 0, 0, 0], [0, 1, -1, 0, 0], [0, 0, 0, 1, -1]])
    assert st.natural.B.nnz == 5
    np.testing.assert_array_equal(st.constraint_strains, [0, 1, 1, 2, 2])
    # the results: a frame whose contact is the old pyramid, element by element
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.mass(1, 1.0)
    fr.soil("s", 1, 1e6, mu=MU, kt=KT)
    fr.rayleigh(a0=20.0)
    fr._elements[0] = el3.FrictionContact(**{**vars(fr._elements[0]), "unknowns": old_pyramid("s", KT)})
    old = fr.build()
    alpha = 0.4
    new_sol = push(st, 2 * COULOMB, alpha, ramp=1.0, t_end=1.5)
    old_sol = push(old, 2 * COULOMB, alpha, ramp=1.0, t_end=1.5)
    success(new_sol)
    for a, b in ((new_sol.u, old_sol.u), (new_sol.v, old_sol.v), (new_sol.psi, old_sol.psi)):
        np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max())
    # the pyramid: slides along t1 (x) under a push at 0.4 rad from it, as before
    assert new_sol.v[-1, 1] > 0.1 and new_sol.v[:, 2:].max() == 0.0
    assert abs(slip_direction(new_sol)) < 1e-6


def test_many_facets_enter_both_tangential_strains():
    st = block(8)
    names = st.constraint_names
    assert names == ("s", *(f"s.facet{k}" for k in (0, 4, 1, 5, 2, 6, 3, 7)))
    assert st.to_model().law.kinds == ("contact",) + ("friction",) * 8
    assert st.to_model().law.partner.tolist() == [-1, 2, 1, 4, 3, 6, 5, 8, 7]    # opposite facets
    B = st.natural.B.toarray()
    th = 2 * np.pi * np.array([0, 4, 1, 5, 2, 6, 3, 7]) / 8
    np.testing.assert_allclose(B[1:, 1:], np.vstack([np.cos(th), np.sin(th)]), atol=1e-15)
    np.testing.assert_array_equal(B[0], [1] + [0] * 8)
    assert st.natural.B.nnz == 1 + 8 + 4                      # facets 1, 3, 5, 7 have two entries
    facet1 = st.elements[0].unknowns[3]
    assert facet1.name == "s.facet1" and facet1.extra == ((2, pytest.approx(np.sqrt(0.5))),)
    assert facet1.normal == "s" and facet1.mu == MU and facet1.k == KT and facet1.kind == "friction"
    assert st.elements[0].unilateral


def test_a_push_along_a_facet_normal_slides_as_the_2d_block():
    """Exact along every facet normal: at 3 pi/4 with 8 facets, as the 2-D block along x."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.mass(1, 1.0)
    fr.soil("s", 1, 1e6, mu=MU, kt=KT, direction="uy")
    fr.rayleigh(a0=20.0)
    st2 = fr.build()
    weight = st2.gravity(GRAVITY, (0.0, -1.0))
    sol2 = ul.solve(st2.to_model(), lambda t: weight + min(t, 1.0) * st2.nodal_load(1, ux=2 * COULOMB), dt=0.005,
                    t_end=1.5, method="direct", rule="trapezoidal")
    alpha = 3 * np.pi / 4
    sol = push(block(8), 2 * COULOMB, alpha, ramp=1.0, t_end=1.5)
    success(sol)
    along = sol.u[:, :2] @ (np.cos(alpha), np.sin(alpha))
    np.testing.assert_allclose(along, sol2.u[:, 0], rtol=0, atol=1e-9 * np.abs(sol2.u[:, 0]).max())
    assert np.abs(sol.u[:, :2] @ (-np.sin(alpha), np.cos(alpha))).max() < 1e-9 * np.abs(along).max()
    assert sol.constraint_names[7] == "s.facet3"
    np.testing.assert_allclose(sol.v[:, 7], sol2.v[:, 1], atol=1e-9 * sol2.v[:, 1].max())   # facet 3 only
    assert np.delete(sol.v, [0, 7], axis=1).max() == 0.0


# ---------------------------------------------------------------------- strength and slip direction
@pytest.fixture(scope="module")
def vertex_onsets():
    """Per N: the push at which the block starts to slide along a vertex (at pi/N, the middle
    between facets 0 and 1), and the friction force then."""
    out = {}
    for N in FACETS:
        st = block(N)
        alpha = np.pi / N
        expected = strength(alpha, N)
        lo, hi = 0.99 * expected, 1.01 * expected                  # a slow ramp across the onset
        sol = push(st, hi, alpha, ramp=4.0, t_end=4.0, start=lo)
        success(sol)
        n = onset(sol)
        P = lo + (hi - lo) * sol.t[n] / 4.0
        T = st.natural.stresses(sol.t, sol.u, sol.v)[n, 1:3]       # (T1, T2)
        out[N] = P, T
    return out


def test_the_block_starts_sliding_at_the_polygons_strength(vertex_onsets):
    errors = []
    for N in FACETS:
        P, T = vertex_onsets[N]
        bound = 1 / np.cos(np.pi / N) - 1
        step = 0.02 * strength(np.pi / N, N) * 0.005 / 4.0           # the load's increment in a step
        assert P == pytest.approx(strength(np.pi / N, N), abs=2 * step)
        # the friction force at the onset: at the vertex, sec(pi/N) mu N along pi/N
        assert np.hypot(*T) == pytest.approx(COULOMB / np.cos(np.pi / N), rel=1e-8)
        assert np.arctan2(T[1], T[0]) == pytest.approx(np.pi / N, abs=1e-6)
        error = np.hypot(*T) / COULOMB - 1
        assert error == pytest.approx(bound, rel=1e-6)              # the bound is met along the vertex
        assert 0 < error <= bound * (1 + 1e-8)
        assert P / COULOMB - 1 <= bound + 2 * step / COULOMB
        errors.append(error)
    assert np.all(np.diff(errors) < 0)
    slope = np.polyfit(np.log(FACETS[1:]), np.log(errors[1:]), 1)[0]
    assert slope == pytest.approx(-2.0, abs=0.1)                    # sec(pi/N) - 1 ~ (pi/N)^2 / 2
    assert errors[-1] < 0.005


@pytest.mark.parametrize("force", [1.5, 4.0])
def test_the_block_slides_within_the_facet_error_of_the_push(force):
    """A push between facets 0 and 1 (at 0.3 of their angle) slides along ``P - proj(P)``: along
    facet 0's normal (1.5 mu N) or from the vertex (4 mu N), within pi/N of the push."""
    errors = []
    for N in FACETS:
        alpha = 0.3 * 2 * np.pi / N
        P = force * COULOMB
        sol = push(block(N), P, alpha, ramp=1.0, t_end=2.5)
        success(sol)
        direction = slip_direction(sol)
        load = P * np.array([np.cos(alpha), np.sin(alpha)])
        expected = load - projection(load, N)
        assert direction == pytest.approx(np.arctan2(expected[1], expected[0]), abs=1e-6)
        error = abs(direction - alpha)
        assert 0 < error < np.pi / N
        errors.append(error)
    assert np.all(np.diff(errors) < 0)
    assert errors[-1] < np.pi / 32
    if force == 1.5:                                # along facet 0: 0.3 of the facets' angle off, like pi/N
        np.testing.assert_allclose(errors, 0.6 * np.pi / np.array(FACETS), rtol=1e-5)


def test_the_push_at_a_vertex_slides_along_it_and_the_lemke_solver_agrees():
    """Along a vertex the slip is exact (two facets slip alike); the LCP solvers agree."""
    N = 8
    alpha = np.pi / N
    st = block(N)
    sol = push(st, 2 * COULOMB, alpha, ramp=1.0, t_end=2.0)
    lemke = push(st, 2 * COULOMB, alpha, ramp=1.0, t_end=2.0, lcp="lemke")
    success(sol)
    success(lemke)
    assert slip_direction(sol) == pytest.approx(alpha, abs=1e-9)
    np.testing.assert_allclose(sol.v[:, 1], sol.v[:, 3], atol=1e-12)       # facets 0 and 1
    assert np.delete(sol.v, [0, 1, 3], axis=1).max() == 0.0
    np.testing.assert_allclose(lemke.u, sol.u, atol=1e-8 * np.abs(sol.u).max())
    np.testing.assert_allclose(lemke.v, sol.v, atol=1e-8 * np.abs(sol.v).max())


@pytest.mark.parametrize("lcp", ["bpp", "lemke"])
def test_a_sudden_large_push_on_many_facets(lcp):
    """Many facets violated at once (a sudden push of 20 mu N, 16 facets): block principal pivoting
    (the default: at most two facets of a cone active, any three being dependent) and Lemke's
    method solve every step, and the block slides along ``P - proj(P)``."""
    N, alpha, P = 16, 0.37, 20 * COULOMB
    sol = push(block(N, kt=1e3), P, alpha, ramp=1e-9, t_end=3.0, dt=0.01, lcp=lcp)
    success(sol)
    load = P * np.array([np.cos(alpha), np.sin(alpha)])
    expected = load - projection(load, N)
    assert slip_direction(sol) == pytest.approx(np.arctan2(expected[1], expected[0]), abs=1e-6)


# ---------------------------------------------------------------------- sticking
@pytest.mark.parametrize("N", [4, 8, 16])
def test_a_push_below_the_strength_in_every_direction_sticks(N):
    """The polygon holds Coulomb's circle: 0.98 mu N in any direction sticks; along a vertex, just
    below its strength sticks and just above slides."""
    st = block(N)
    for alpha in np.linspace(0.0, 2 * np.pi, 7, endpoint=False) + 0.1:
        sol = push(st, 0.98 * COULOMB, alpha, ramp=1.0, t_end=1.5, dt=0.01)
        success(sol)
        assert sol.v[:, 1:].max() == 0.0
        np.testing.assert_allclose(sol.u[-1, :2], 0.98 * COULOMB / KT * np.array([np.cos(alpha), np.sin(alpha)]),
                                   rtol=1e-3)
    vertex = np.pi / N
    below = push(st, 0.995 * strength(vertex, N), vertex, ramp=1.0, t_end=1.5, dt=0.01)
    above = push(st, 1.005 * strength(vertex, N), vertex, ramp=1.0, t_end=1.5, dt=0.01)
    assert below.v[:, 1:].max() == 0.0
    assert above.v[:, 1:].max() > 0.0


# ---------------------------------------------------------------------- the argument
@pytest.mark.parametrize("call, error, message", [
    (lambda fr: fr.soil("s", 1, 1.0, mu=0.3, kt=1.0, facets=6.0), TypeError, "soil 's': facets must be an even int"),
    (lambda fr: fr.soil("s", 1, 1.0, mu=0.3, kt=1.0, facets=True), TypeError, "soil 's': facets must be an even int"),
    (lambda fr: fr.soil("s", 1, 1.0, mu=0.3, kt=1.0, facets=2), ValueError, "soil 's': facets=2 must be an even int"),
    (lambda fr: fr.soil("s", 1, 1.0, mu=0.3, kt=1.0, facets=7), ValueError, "soil 's': facets=7 must be an even int"),
    (lambda fr: fr.soil("s", 1, 1.0, facets=8), ValueError, "soil 's': facets is a friction parameter"),
    (lambda fr: fr.gap("g", 1, 2, 1.0, mu=0.3, kt=1.0, facets=5), ValueError, "gap 'g': facets=5 must be an even int"),
])
def test_a_bad_number_of_facets_is_refused_naming_the_argument(call, error, message):
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 1.0, 0.0, 0.0)
    with pytest.raises(error, match=message):
        call(fr)


def test_a_gap_takes_the_facets_too():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 1.0, 0.0, 0.0)
    fr.support(1, ux=True, uy=True, uz=True)
    fr.gap("g", 1, 2, 1e3, mu=0.3, kt=1e2, facets=6)
    fr.spring("k", 2, 1.0, direction="ux")
    fr.mass(2, 1.0)
    st = fr.build()
    assert st.constraint_names == ("g", *(f"g.facet{k}" for k in (0, 3, 1, 4, 2, 5)))
    B = st.natural.B.toarray()
    th = 2 * np.pi * np.array([0, 3, 1, 4, 2, 5]) / 6
    np.testing.assert_allclose(B[1:3, 1:], np.vstack([np.cos(th), np.sin(th)]), atol=1e-15)
