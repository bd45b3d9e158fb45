"""Plastic hinges of 3-D beams (:meth:`Frame3D.hinge`): a polygonal yield surface in the plane of the
end moments ``(M_y', M_z')``.

Defining properties: a plane frame with hinges built in 3-D responds as the 2-D frame with
``Frame2D.hinge`` (rigid-plastic, and with a spring and hardening); a cantilever's base hinge pushed
along any direction in plan never leaves its polygon, yields on it, and flows along the normals of
the active facets (associated flow); a box is two uncoupled 2-D hinges; the ellipse's polygon
converges to the ellipse, with an overstrength within ``sec(pi/N) - 1``; every facet is
complementary at every step; bad input is refused naming the argument; a 3-D model file builds the
same hinges.
"""

from __future__ import annotations

import copy
import re

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.optimize import nnls

import unilateral as ul
from unilateral.modelfile import ModelFileError, load_model_file
from unilateral.structure import Frame2D, Frame3D

RAMP = ul.loads.Ramp


def dense(a):
    return a.toarray() if sp.issparse(a) else np.asarray(a)


def relative(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) - np.asarray(b))) / np.max(np.abs(b)))


def polygon(shape, N, My, Mz):
    """The polygon from its definition: unit normals (N, 2) on (M_y', M_z') and distances (N,)."""
    if shape == "diamond":
        g, c = np.array([[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]]), 1.0
    else:
        th = 2 * np.pi * np.arange(N) / N
        g, c = np.column_stack([np.cos(th), np.sin(th)]), 1.0
    scaled = g / [My, Mz]
    s = np.linalg.norm(scaled, axis=1)
    return scaled / s[:, None], c / s


# ---------------------------------------------------------------------- a plane portal, 2-D and 3-D
H, L = 3.0, 5.0
E, A, I, I_OUT, G, J = 3e7, 0.16, 2e-3, 1.5e-3, 1.2e7, 3e-3
MY, MASS = 60.0, 5.0
#: The portal's members (i, j) and its hinges (member, end).
MEMBERS = {"c1": (1, 3), "c2": (2, 4), "g": (3, 4)}
HINGES = (("c1", "i"), ("c2", "i"), ("g", "i"), ("g", "j"))
#: 2-D DOF -> (3-D DOF, sign): the 2-D counter-clockwise rz turns x towards z, a rotation about -y.
IN_PLANE = {"ux": ("ux", 1.0), "uy": ("uz", 1.0), "rz": ("ry", -1.0)}


def portal(dim, *, k=None, hardening=0.0):
    """A fixed-base portal in x-y (2-D) or x-z (3-D) with hinges at the column bases and the girder
    ends; in 3-D the hinges are ellipses of 8 facets with ``Mz = 0.7 My`` out of the plane."""
    fr = Frame2D() if dim == 2 else Frame3D()
    for node, (x, y) in {1: (0.0, 0.0), 2: (L, 0.0), 3: (0.0, H), 4: (L, H)}.items():
        fr.node(node, x, y) if dim == 2 else fr.node(node, x, 0.0, y)
    for base in (1, 2):
        if dim == 2:
            fr.support(base, ux=True, uy=True, rz=True)
        else:
            fr.support(base, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    for name, (i, j) in MEMBERS.items():
        if dim == 2:
            fr.beam(name, i, j, E, A, I)
        else:
            fr.beam(name, i, j, E=E, A=A, Iy=I, Iz=I_OUT, G=G, J=J)
    for beam, end in HINGES:
        if dim == 2:
            fr.hinge(f"{beam}.{end}", beam, end, My=MY, k=k, hardening=hardening)
        else:
            fr.hinge(f"{beam}.{end}", beam, end, My=MY, Mz=0.7 * MY, shape="ellipse", facets=8, k=k,
                     hardening=hardening)
    for node in (3, 4):
        fr.mass(node, MASS)
    fr.rayleigh(a0=2.0)
    return fr.build()


def in_plane_map(st2, st3) -> np.ndarray:
    """``P`` (n2, n3) with ``u2 = P u3`` on the in-plane DOFs."""
    P = np.zeros((st2.n, st3.n))
    for row, (node, dof) in enumerate(st2.dofs.free):
        dof3, sign = IN_PLANE[dof]
        P[row, st3.dofs.index(node, dof3)] = sign
    return P


def hinge_map(st2, st3):
    """``(Q (m2, m3), rest)``: the 2-D pair ``plastic+``, ``plastic-`` of each hinge from the 3-D facets
    normal to ``y'`` (facet0 along ``+M_y'``, facet4 along ``-M_y'``), with the sign of ``y'`` against
    the plane's normal ``-Y`` (columns: ``y' = -Y``; the girder: ``y' = +Y``); ``rest``: the other facets."""
    names3 = list(st3.constraint_names)
    Q = np.zeros((st2.m, st3.m))
    for beam, end in HINGES:
        sign = -1.0 if beam == "g" else 1.0
        plus, minus = ("facet0", "facet4") if sign > 0 else ("facet4", "facet0")
        Q[st2.constraint_names.index(f"{beam}.{end}.plastic+"), names3.index(f"{beam}.{end}.{plus}")] = 1.0
        Q[st2.constraint_names.index(f"{beam}.{end}.plastic-"), names3.index(f"{beam}.{end}.{minus}")] = 1.0
    rest = np.flatnonzero(~Q.any(axis=0))
    return Q, rest


@pytest.mark.parametrize("k, hardening", [(None, 0.0), (4e3, 0.05)], ids=["rigid-plastic", "spring+hardening"])
@pytest.mark.parametrize("loading", ["pulse", "push"])
def test_a_plane_portal_with_hinges_in_3d_responds_as_the_2d_portal(k, hardening, loading):
    st2, st3 = portal(2, k=k, hardening=hardening), portal(3, k=k, hardening=hardening)
    assert st3.m == 4 * 8 and st2.m == 4 * 2
    P = in_plane_map(st2, st3)
    Q, rest = hinge_map(st2, st3)
    collapse = 4 * MY / H                                       # the sway mechanism
    runs = []
    for st in (st2, st3):
        push = st.nodal_load(3, ux=1.0)
        if loading == "pulse":                                  # a dynamic run, beyond yield and back
            load = (lambda t, push=push: 1.5 * collapse * (0.0 < t <= 0.25) * push)
            options = dict(dt=2e-3, t_end=1.0)
        else:                                                   # slowly, beyond the first yield
            load = ul.LoadHistory(np.zeros(st.n), [(push, RAMP(4.0, (0.97 if k is None else 1.3) * collapse))])
            options = dict(dt=5e-3, t_end=4.0)
        runs.append(ul.solve(st.to_model(), load, method="direct", rule="trapezoidal", **options))
    two, three = runs
    assert two.success and three.success
    assert two.v.max() > 1e-4 and np.count_nonzero(two.v[-1] > 0) >= 2        # several hinges yield
    assert relative(three.u @ P.T, two.u) < 1e-9
    assert relative(three.v @ Q.T, two.v) < 1e-9
    assert relative(three.psi @ Q.T, two.psi) < 1e-9
    assert np.abs(three.v[:, rest]).max() <= 1e-12 * two.v.max()              # the oblique facets never flow
    assert three.psi[:, rest].max() < -0.1 * MY                                # and stay off the moments
    out = np.flatnonzero(~P.any(axis=0))
    assert np.abs(three.u[:, out]).max() <= 1e-12 * np.abs(three.u).max()      # nothing leaves the plane


# ---------------------------------------------------------------------- a cantilever pushed in plan
HC, EC, IY, IZ = 2.0, 1e4, 1.0, 0.8
PY, PZ = 100.0, 60.0


def column(*, shape="ellipse", facets=None, k=None, hardening=0.0, downwards=False):
    """A column along z fixed at node 1 (base), tip node 2; a hinge at the base. Local axes of the
    beam 1 -> 2 (default vecxz = X): ``y' = -Y``, ``z' = X``; the beam 2 -> 1 with vecxz = X:
    ``y' = Y``, ``z' = X``."""
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, HC)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    section = dict(E=EC, A=1.0, Iy=IY, Iz=IZ, G=4e3, J=1.0)
    if downwards:
        fr.beam("col", 2, 1, vecxz=(1.0, 0.0, 0.0), **section)
    else:
        fr.beam("col", 1, 2, **section)
    fr.hinge("H", "col", "j" if downwards else "i", My=PY, Mz=PZ, shape=shape, facets=facets, k=k,
             hardening=hardening)
    fr.mass(2, 1e-3)
    fr.rayleigh(a0=50.0)
    return fr.build()


def hinge_moments(st, sol):
    """``(M (N+1, 2), theta_p (N+1, 2))``: the end moments ``(M_y', M_z')`` at the base hinge from the
    stresses, and the plastic rotation from the kinematics, total end rotation minus elastic."""
    beam = st.elements[0]
    end = "j" if beam.dofs[0][0] == 2 else "i"
    rows = [st.strain_names.index(f"col.roty_{end}"), st.strain_names.index(f"col.rotz_{end}")]
    sigma = st.natural.stresses(sol.t, sol.u, sol.v)
    strains = np.asarray((st.natural.G.T @ sol.u.T).T)
    elastic = sigma @ np.linalg.inv(dense(st.natural.E)).T
    return sigma[:, rows], strains[:, rows] - elastic[:, rows]


def tip_push(st, phi, P):
    return st.nodal_load(2, ux=P * np.cos(phi), uy=P * np.sin(phi))


@pytest.mark.parametrize("shape, facets, phi_deg", [("ellipse", 8, 30.0), ("ellipse", 8, 112.5), ("ellipse", 6, 60.0),
                                                    ("diamond", None, 200.0), ("box", None, -50.0)])
def test_a_pushed_base_hinge_stays_on_its_polygon_and_flows_along_the_normals(shape, facets, phi_deg):
    st = column(shape=shape, facets=facets)
    N = facets or 4
    n, r = polygon(shape, N, PY, PZ)
    # the model's facets are the polygon's: the columns of B on (roty_i, rotz_i) and the resistances
    rows = [st.strain_names.index("col.roty_i"), st.strain_names.index("col.rotz_i")]
    B = dense(st.natural.B)[rows]
    order = [int(name.rpartition("facet")[2]) for name in st.constraint_names]
    assert order == [f for p in range(N // 2) for f in (p, p + N // 2)]         # opposite pairs
    np.testing.assert_allclose(B.T, n[order], atol=1e-15)
    np.testing.assert_allclose(st.natural.r, r[order], rtol=1e-14)
    if shape == "ellipse":                                      # every facet touches the ellipse
        np.testing.assert_allclose(np.hypot(PY * n[:, 0], PZ * n[:, 1]), r, rtol=1e-14)
    phi = np.radians(phi_deg)
    d = np.array([np.cos(phi), np.sin(phi)])
    strength = min(r[k] / (n[k] @ d) for k in range(N) if n[k] @ d > 0)     # |M| at which M along d reaches it
    push = ul.LoadHistory(np.zeros(st.n), [(tip_push(st, phi, 1.0), RAMP(10.0, 1.3 * strength / HC))])
    sol = ul.solve(st.to_model(), push, dt=0.01, t_end=10.0, method="direct")
    assert sol.success
    M, theta_p = hinge_moments(st, sol)
    f = M @ n.T - r                                             # the yield functions of the facets
    np.testing.assert_allclose(sol.psi, f[:, order], atol=1e-9 * PY)          # are the model's psi
    assert f.max() <= 1e-9 * PY                                 # the yield condition at every step
    flowing = np.diff(sol.v, axis=0).max(axis=1) > 1e-12
    first = int(np.argmax(flowing)) + 1
    assert flowing.any() and sol.t[first] > 5.0
    # elastic: the base moment is H times the push, (M_y', M_z') = H (Fx, Fy) (inertia aside)
    load = np.outer(1.3 * strength * sol.t / 10.0, d)
    np.testing.assert_allclose(M[:first], load[:first], atol=1e-3 * PY)
    # at yield: on the polygon (max_k psi_k = 0) at every step that flows
    np.testing.assert_allclose(f[1:][flowing].max(axis=1), 0.0, atol=1e-9 * PY)
    # associated flow: each plastic rotation increment is a nonnegative combination of the normals of
    # the facets on which the moment lies (one facet: along its normal; a vertex: in between)
    increments = np.diff(theta_p, axis=0)
    for step in np.flatnonzero(flowing):
        active = f[step + 1] > -1e-9 * PY
        weights, residual = nnls(n[active].T, increments[step])
        assert residual <= 1e-9 * np.linalg.norm(increments[step]), (step, active)
    # and it is the multipliers' sum lambda_k n_k, a plastic rotation in rad
    np.testing.assert_allclose(theta_p, sol.v @ n[order], atol=1e-12 * np.abs(theta_p).max())


@pytest.mark.parametrize("k, hardening", [(None, 0.05), (300.0, 0.1)], ids=["rigid-plastic", "spring"])
def test_a_box_is_two_uncoupled_2d_hinges(k, hardening):
    """An oblique push on a box hinge: about y' the 2-D cantilever of EIy and My under P cos(phi), about
    z' the 2-D cantilever of EIz and Mz under P sin(phi), to round-off; both yield at their own moment."""
    phi, P = np.radians(35.0), 1.6 * PY / HC
    st = column(shape="box", k=k, hardening=hardening)
    sol = ul.solve(st.to_model(), ul.LoadHistory(np.zeros(st.n), [(tip_push(st, phi, P), RAMP(10.0, 1.0))]),
                   dt=0.01, t_end=10.0, method="direct")
    M, theta_p = hinge_moments(st, sol)
    for axis, (inertia, moment, force) in enumerate([(IY, PY, P * np.cos(phi)), (IZ, PZ, P * np.sin(phi))]):
        fr = Frame2D()
        fr.node(1, 0.0, 0.0)
        fr.node(2, 0.0, HC)
        fr.support(1, ux=True, uy=True, rz=True)
        fr.beam("col", 1, 2, EC, 1.0, inertia)
        fr.hinge("H", "col", "i", My=moment, k=k, hardening=hardening)
        fr.mass(2, 1e-3)
        fr.rayleigh(a0=50.0)
        st2 = fr.build()
        push = ul.LoadHistory(np.zeros(st2.n), [(st2.nodal_load(2, ux=force), RAMP(10.0, 1.0))])
        two = ul.solve(st2.to_model(), push, dt=0.01, t_end=10.0, method="direct")
        moment2 = st2.element_forces(two.t, two.u, two.v)[:, 0]
        plastic2 = two.v[:, 0] - two.v[:, 1]
        assert plastic2[-1] > 1e-4                                              # it yields about this axis
        first = int(np.argmax(plastic2 > 0))
        applied = force * HC * sol.t / 10.0                                     # the moment of the push
        assert applied[first - 1] < moment * (1 + 1e-3) and moment <= applied[first] * (1 + 1e-3)
        np.testing.assert_allclose(M[:, axis], moment2, rtol=0, atol=1e-10 * moment)
        np.testing.assert_allclose(theta_p[:, axis], plastic2, rtol=0, atol=1e-10 * plastic2.max())


def collapse_load(N, phi):
    """The push ``P`` along ``phi`` in plan at which the rigid-plastic base hinge (an ellipse of ``N``
    facets) first yields, from a run: the zero of the largest yield function, linear in ``P`` while
    elastic, interpolated between the last two elastic steps."""
    st = column(shape="ellipse", facets=N)
    top = 2.0 * np.hypot(PY, PZ) / HC
    T = 10.0
    sol = ul.solve(st.to_model(), ul.LoadHistory(np.zeros(st.n), [(tip_push(st, phi, 1.0), RAMP(T, top))]),
                   dt=0.01, t_end=T, method="direct")
    assert sol.success
    f = sol.psi.max(axis=1)
    first = int(np.argmax(np.diff(sol.v, axis=0).max(axis=1) > 0)) + 1
    a, b = first - 2, first - 1
    t = sol.t[b] + (0.0 - f[b]) * (sol.t[b] - sol.t[a]) / (f[b] - f[a])
    assert sol.t[b] <= t <= sol.t[first]
    return top * t / T


def test_the_ellipse_polygon_converges_to_the_ellipse_within_sec_pi_over_N():
    """Along 45 degrees in plan the ellipse (My = 100, Mz = 60) yields at ``P_e = 1 / (H |(cos/My,
    sin/Mz)|)``; the circumscribed polygon of N facets yields at ``P_N``, with ``0 <= P_N/P_e - 1 <=
    sec(pi/N) - 1``, the error never growing with N (its facets are a superset) and vanishing."""
    phi = np.radians(45.0)
    ellipse = 1.0 / (HC * np.hypot(np.cos(phi) / PY, np.sin(phi) / PZ))
    errors = {}
    for N in (4, 8, 16, 32):
        errors[N] = collapse_load(N, phi) / ellipse - 1.0
        assert -1e-9 <= errors[N] <= 1.0 / np.cos(np.pi / N) - 1.0 + 1e-9, (N, errors[N])
        # the polygon's radial overstrength: sec of the angle to the nearest facet normal (normalised plane)
        alpha = np.arctan2(np.sin(phi) / PZ, np.cos(phi) / PY)
        nearest = min(abs(np.angle(np.exp(1j * (alpha - 2 * np.pi * k / N)))) for k in range(N))
        assert errors[N] == pytest.approx(1.0 / np.cos(nearest) - 1.0, abs=1e-4)
    values = [errors[N] for N in (4, 8, 16, 32)]
    assert all(b <= a + 1e-9 for a, b in zip(values, values[1:])), errors
    assert errors[32] < 0.005 and errors[4] > 0.1, errors


def test_a_hinge_at_end_j_of_a_beam_drawn_downwards_yields_at_the_same_push():
    """The same column drawn from the tip to the base (hinge at end j, y' = +Y): the base moments are
    the same but M_y' changes sign with y'; it yields under the same push."""
    phi = np.radians(30.0)
    runs = []
    for downwards in (False, True):
        st = column(shape="ellipse", facets=8, k=500.0, hardening=0.1, downwards=downwards)
        sol = ul.solve(st.to_model(), ul.LoadHistory(np.zeros(st.n), [(tip_push(st, phi, 1.6 * PY / HC),
                                                                         RAMP(10.0, 1.0))]),
                       dt=0.01, t_end=10.0, method="direct")
        M, theta_p = hinge_moments(st, sol)
        runs.append((st.node_displacement(sol, 2, "ux"), st.node_displacement(sol, 2, "uy"), M, theta_p))
    (ux0, uy0, M0, p0), (ux1, uy1, M1, p1) = runs
    assert np.abs(p0).max() > 1e-3
    np.testing.assert_allclose(ux1, ux0, rtol=0, atol=1e-10 * np.abs(ux0).max())
    np.testing.assert_allclose(uy1, uy0, rtol=0, atol=1e-10 * np.abs(uy0).max())
    # the polygon of end j is mirrored in M_y' (y' flipped): symmetric for the ellipse, so the same
    np.testing.assert_allclose(M1 * [-1.0, 1.0], M0, rtol=0, atol=1e-9 * PY)


# ---------------------------------------------------------------------- complementarity at every step
@pytest.mark.parametrize("k, hardening, facets", [(None, 0.1, 8), (300.0, 0.05, 8), (300.0, 0.05, 4)])
def test_every_facet_is_complementary_at_every_step_under_a_turning_push(k, hardening, facets):
    """A push of 1.4 times the strength turning round in plan, twice: the moment runs round the
    polygon, from facet to facet through the vertices. For every facet at every step: ``lambda >= 0``
    and never decreasing, ``psi <= 0``, ``psi d lambda = 0``."""
    st = column(shape="ellipse", facets=facets, k=k, hardening=hardening)
    fx, fy = st.nodal_load(2, ux=1.0), st.nodal_load(2, uy=1.0)
    P = 1.4 * PY / HC
    ramp = lambda t: min(t / 2.0, 1.0)                          # noqa: E731
    load = lambda t: P * ramp(t) * (np.cos(np.pi * t / 5.0) * fx + np.sin(np.pi * t / 5.0) * fy)  # noqa: E731
    sol = ul.solve(st.to_model(), load, dt=0.01, t_end=20.0, method="direct")
    assert sol.success
    dv = np.diff(sol.v, axis=0)
    scale = np.abs(sol.v).max()
    assert np.count_nonzero(dv.max(axis=0) > 1e-9 * scale) == facets          # every facet flows at some time
    assert sol.v.min() >= 0.0 and dv.min() >= -1e-12 * scale
    assert sol.psi.max() <= 1e-9 * PY
    assert np.abs(dv * sol.psi[1:]).max() <= 1e-9 * PY * scale
    two = (dv > 1e-9 * scale).sum(axis=1)
    assert two.max() == 2                                        # a vertex: two adjacent facets at once


@pytest.mark.parametrize("facets, k, factor", [(8, None, 3.0), (8, 4e3, 1.2), (16, None, 1.2), (16, 4e3, 3.0)])
def test_a_sudden_push_far_beyond_the_polygon_is_solved_by_block_pivoting(facets, k, factor):
    """A push of 1.2 or 3 times the strength at once, in several directions: three facets of one
    hinge have dependent columns, and block principal pivoting (the default) keeps at most two of a
    polygon active (the group rule; before it, these pushes stopped at a singular basis and needed
    ``lcp="lemke"``). The default solver runs every step and equals Lemke's method."""
    st = column(shape="ellipse", facets=facets, k=k)
    options = dict(dt=0.01, t_end=0.3, method="direct")
    for angle in (0.1, 0.5, 0.9, 2.3):
        push = tip_push(st, angle, factor * PY / HC)
        sol = ul.solve(st.to_model(), lambda t: (t > 0) * push, **options)
        assert sol.success, sol.message
        assert sol.v.max() > 0
        dv = np.diff(sol.v, axis=0)
        assert dv.min() >= 0.0 and sol.psi.max() <= 1e-9 * PY
        assert np.abs(dv * sol.psi[1:]).max() <= 1e-9 * PY * sol.v.max()
        lemke = ul.solve(st.to_model(), lambda t: (t > 0) * push, lcp="lemke", **options)
        np.testing.assert_allclose(sol.u, lemke.u, rtol=0, atol=1e-9 * np.abs(lemke.u).max())


# ---------------------------------------------------------------------- bad input
def _frame():
    fr = Frame3D()
    fr.node(1, 0.0, 0.0, 0.0)
    fr.node(2, 0.0, 0.0, 2.0)
    fr.support(1, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    fr.beam("col", 1, 2, E=1.0, A=1.0, Iy=1.0, Iz=1.0, G=1.0, J=1.0)
    fr.hinge("h1", "col", "j", My=1.0, Mz=1.0)
    return fr


BAD = {
    "shape": (dict(shape="circle"), ValueError, "hinge 'h': shape='circle' is not valid; use 'ellipse', 'diamond' or "
                                                "'box'"),
    "odd facets": (dict(facets=7), ValueError, "hinge 'h': facets=7 must be an even int >= 4"),
    "two facets": (dict(facets=2), ValueError, "hinge 'h': facets=2 must be an even int >= 4"),
    "float facets": (dict(facets=8.0), TypeError, "hinge 'h': facets must be an even int >= 4"),
    "box facets": (dict(shape="box", facets=8), ValueError, "hinge 'h': facets=8 is not valid for shape='box', "
                                                            "which has exactly 4 facets"),
    "diamond facets": (dict(shape="diamond", facets=6), ValueError, "facets=6 is not valid for shape='diamond'"),
    "My": (dict(My=0.0), ValueError, "hinge 'h': My=0.0 must be > 0"),
    "Mz": (dict(Mz=-1.0), ValueError, "hinge 'h': Mz=-1.0 must be > 0"),
    "My type": (dict(My="1"), TypeError, "hinge 'h': My must be a real number"),
    "k": (dict(k=0.0), ValueError, "hinge 'h': k=0.0 must be > 0"),
    "hardening": (dict(hardening=-0.1), ValueError, "hinge 'h': hardening=-0.1 must be >= 0"),
    "end": (dict(end="k"), ValueError, "hinge 'h': end='k' is not valid; use 'i' or 'j'"),
    "beam": (dict(beam="colm"), ValueError, "hinge 'h': beam='colm' is not a beam of the frame (beams: 'col')"),
    "twice": (dict(end="j"), ValueError, "hinge 'h': end 'j' of beam 'col' already has the hinge 'h1'; one hinge "
                                         "per beam end"),
    "name": (dict(name="h1"), ValueError, "hinge 'h1': the name is already used by another element"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_hinge_input_is_refused_naming_the_argument(case):
    changes, error, message = BAD[case]
    args = dict(name="h", beam="col", end="i", My=1.0, Mz=1.0) | changes
    fr = _frame()
    with pytest.raises(error, match=re.escape(message)):
        fr.hinge(args.pop("name"), args.pop("beam"), args.pop("end"), **args)
    assert fr.build().constraint_names == tuple(f"h1.facet{f}" for f in (0, 4, 1, 5, 2, 6, 3, 7))


def test_mz_is_required_and_diamond_and_box_default_to_4_facets():
    fr = _frame()
    with pytest.raises(TypeError, match="Mz"):
        fr.hinge("h", "col", "i", My=1.0)
    fr.hinge("h", "col", "i", My=2.0, Mz=1.0, shape="diamond", facets=4)
    st = fr.build()
    assert st.constraint_names[8:] == ("h.facet0", "h.facet2", "h.facet1", "h.facet3")


# ---------------------------------------------------------------------- model files
PORTAL_3D = {
    "units": {"length": "m", "force": "kN", "time": "s"},
    "frame": {"dimensions": 3},
    "nodes": [{"id": 1, "x": 0.0, "y": 0.0, "z": 0.0}, {"id": 2, "x": L, "y": 0.0, "z": 0.0},
              {"id": 3, "x": 0.0, "y": 0.0, "z": H}, {"id": 4, "x": L, "y": 0.0, "z": H}],
    "supports": [{"node": 1, "rx": True, "ry": True, "rz": True}, {"node": 2, "rx": True, "ry": True, "rz": True}],
    "elements": [{"type": "beam", "name": name, "node_i": i, "node_j": j, "E": E, "A": A, "Iy": I, "Iz": I_OUT,
                  "G": G, "J": J} for name, (i, j) in MEMBERS.items()],
    "unilateral": [{"type": "hinge", "name": "c1.i", "beam": "c1", "end": "i", "My": MY, "Mz": 0.7 * MY},
                   {"type": "hinge", "name": "c2.i", "beam": "c2", "end": "i", "My": MY, "Mz": 0.7 * MY,
                    "shape": "ellipse", "facets": 16, "k": 4e3, "hardening": 0.05},
                   {"type": "hinge", "name": "g.i", "beam": "g", "end": "i", "My": MY, "Mz": 0.5 * MY,
                    "shape": "box"},
                   {"type": "hinge", "name": "g.j", "beam": "g", "end": "j", "My": MY, "Mz": 0.5 * MY,
                    "shape": "diamond", "facets": 4, "hardening": 0.02}],
    "masses": [{"node": 3, "m": MASS}, {"node": 4, "m": MASS}],
    "damping": {"rayleigh": {"a0": 2.0}},
    "loads": {"nodal": [{"node": 3, "ux": 1.2 * 4 * MY / H, "uy": 0.5 * 4 * MY / H,
                         "time_function": {"type": "ramp", "t_ramp": 2.0}}]},
    "analysis": {"dt": 0.01, "t_end": 2.0, "method": "direct"},
}


def _inline(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_inline(x) for x in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {_inline(x)}" for k, x in value.items()) + "}"
    return repr(value)


def write(tmp_path, document, name="model.toml"):
    path = tmp_path / name
    path.write_text("".join(f"{key} = {_inline(value)}\n" for key, value in document.items()))
    return path


def portal_by_the_api():
    fr = Frame3D()
    for node in PORTAL_3D["nodes"]:
        fr.node(node["id"], node["x"], node["y"], node["z"])
    for base in (1, 2):
        fr.support(base, ux=True, uy=True, uz=True, rx=True, ry=True, rz=True)
    for name, (i, j) in MEMBERS.items():
        fr.beam(name, i, j, E=E, A=A, Iy=I, Iz=I_OUT, G=G, J=J)
    fr.hinge("c1.i", "c1", "i", My=MY, Mz=0.7 * MY)
    fr.hinge("c2.i", "c2", "i", My=MY, Mz=0.7 * MY, shape="ellipse", facets=16, k=4e3, hardening=0.05)
    fr.hinge("g.i", "g", "i", My=MY, Mz=0.5 * MY, shape="box")
    fr.hinge("g.j", "g", "j", My=MY, Mz=0.5 * MY, shape="diamond", facets=4, hardening=0.02)
    for node in (3, 4):
        fr.mass(node, MASS)
    fr.rayleigh(a0=2.0)
    return fr.build()


def test_a_3d_model_file_with_hinges_builds_the_api_frame_and_runs(tmp_path):
    spec = load_model_file(write(tmp_path, PORTAL_3D))
    st = portal_by_the_api()
    assert spec.structure.constraint_names == st.constraint_names
    assert len(st.constraint_names) == 8 + 16 + 4 + 4
    model = st.to_model()
    for name in ("K", "M", "C", "F", "H"):
        np.testing.assert_array_equal(dense(getattr(spec.model, name)), dense(getattr(model, name)), err_msg=name)
    np.testing.assert_array_equal(spec.model.g(0.0), model.g(0.0))
    sol = ul.solve(spec.model, spec.load, dt=0.01, t_end=2.0, method="direct")
    assert sol.success and sol.v.max() > 1e-4                    # the hinges yield
    assert sol.psi.max() <= 1e-9 * MY
    result = ul.run(write(tmp_path, PORTAL_3D, "run.toml"), tmp_path / "out", figures=())
    assert result["success_all"]
    # the facets' multipliers are plastic rotations and their rows moments, in the tables' headers
    header = (tmp_path / "out" / "constraints.csv").read_text().splitlines()[0]
    assert "v:c1.i.facet0 [rad]" in header and "psi:c1.i.facet0 [kN m]" in header


def _portal_2d():
    d = copy.deepcopy(PORTAL_3D)
    del d["frame"]
    d["nodes"] = [{"id": n["id"], "x": n["x"], "y": n["z"]} for n in d["nodes"]]
    d["supports"] = [{"node": 1, "rz": True}, {"node": 2, "rz": True}]
    d["elements"] = [{"type": "beam", "name": name, "node_i": i, "node_j": j, "E": E, "A": A, "I": I}
                     for name, (i, j) in MEMBERS.items()]
    d["unilateral"] = [{"type": "hinge", "name": "c1.i", "beam": "c1", "end": "i", "My": MY}]
    d["loads"] = {"nodal": [{"node": 3, "ux": 100.0, "time_function": {"type": "ramp", "t_ramp": 2.0}}]}
    return d


WRONG = {
    "Mz in 2-D": (2, lambda d: d["unilateral"][0].update(Mz=30.0),
                  "unilateral[0].Mz = 30.0: a key of 3-D frames only (declare [frame] dimensions = 3; valid keys of "
                  "a 2-D frame here: type, name, beam, end, My, k, hardening, backbone, interaction, Ny)"),
    "shape in 2-D": (2, lambda d: d["unilateral"][0].update(shape="box"),
                     'unilateral[0].shape = "box": a key of 3-D frames only'),
    "facets in 2-D": (2, lambda d: d["unilateral"][0].update(facets=8), "unilateral[0].facets = 8: a key of 3-D "
                                                                         "frames only"),
    "no Mz in 3-D": (3, lambda d: d["unilateral"][0].pop("Mz"),
                     "unilateral[0].Mz: missing key (required keys: type, name, beam, end, My, Mz)"),
    "odd facets": (3, lambda d: d["unilateral"][1].update(facets=9),
                   "unilateral[1].facets = 9: must be even (the facets of the hinge's polygon come in opposite pairs)"),
    "box facets": (3, lambda d: d["unilateral"][2].update(facets=8),
                   'unilateral[2].facets = 8: a box has exactly 4 facets: give facets = 4 or remove it (or use shape '
                   '= "ellipse")'),
    "shape": (3, lambda d: d["unilateral"][2].update(shape="circle"),
              'unilateral[2].shape = "circle": unknown hinge shape (valid: ellipse, diamond, box)'),
    "beam": (3, lambda d: d["unilateral"][3].update(beam="girder"), 'unilateral[3].beam = "girder": no beam "girder"'),
    "twice": (3, lambda d: d["unilateral"][3].update(end="i"), 'unilateral[3].end = "i": beam "g" already has a hinge '
                                                               "at this end (unilateral[2].end); one per end"),
}


@pytest.mark.parametrize("case", list(WRONG))
def test_a_wrong_hinge_in_a_model_file_names_the_key(tmp_path, case):
    dimensions, change, expected = WRONG[case]
    document = copy.deepcopy(PORTAL_3D) if dimensions == 3 else _portal_2d()
    change(document)
    path = write(tmp_path, document)
    with pytest.raises(ModelFileError) as info:
        load_model_file(path)
    assert f"{path}: {expected}" in str(info.value)
