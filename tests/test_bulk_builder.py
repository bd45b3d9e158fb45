"""Many nodes and elements at once (``Frame2D.nodes``, ``beams``, ``masses``, ``soils``) are the
loops of the one-at-a-time calls: the same matrices bit for bit, the same names; a call that fails
adds nothing and names the argument and the row. And the banded definiteness check of a model's
``K`` decides as the sparse LU's inertia does. No test here measures time."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp

from unilateral.model import DEFINITENESS_BANDED_MAX, check_definite
from unilateral.structure import Frame2D


def frame_by_loop(xy, beams, masses, soils, bulk_extra=None):
    """The frame of the rows, built one call per node and element."""
    fr = Frame2D()
    for node, (x, y) in xy.items():
        fr.node(node, float(x), float(y))
    for name, i, j, E, A, I, strain, curvature in beams:
        fr.beam(name, i, j, E=float(E), A=float(A), I=float(I), axial_strain=float(strain),
                curvature=float(curvature))
    for node, m, J in masses:
        fr.mass(node, float(m), J=float(J))
    for name, node, k, c, gap, capacity, direction in soils:
        fr.soil(name, node, float(k), c=float(c), gap=float(gap), capacity=float(capacity), direction=direction)
    return fr


def rows(seed=0):
    """Random rows: node ids of both kinds, inclined and axis-aligned beams, imposed strains,
    repeated masses, soil contacts with and without dashpots, gaps and capacities."""
    rng = np.random.default_rng(seed)
    ids = [0, 1, 2, 3, 4, "a", "b", 7]
    xy = {node: rng.uniform(-5.0, 5.0, 2) for node in ids}
    xy["b"] = np.array([xy["a"][0] + 2.0, xy["a"][1]])                 # horizontal beam a -> b
    xy[7] = np.array([xy[4][0], xy[4][1] + 1.5])                        # vertical beam 4 -> 7
    chain = [(0, 1), (1, 2), (2, 3), (3, 4), ("a", "b"), (4, 7), (2, "a")]
    beams = [(f"b{k}", i, j, rng.uniform(1e6, 3e7), rng.uniform(0.05, 0.3), rng.uniform(1e-4, 1e-2),
              rng.normal(0, 1e-5), rng.normal(0, 1e-4)) for k, (i, j) in enumerate(chain)]
    masses = [(node, rng.uniform(0.5, 2.0), rng.uniform(0.0, 0.3)) for node in (0, 1, 2, 3, 4, "a", "b", 7, 2)]
    soils = [(f"s{k}", node, rng.uniform(1e4, 1e5), c, gap, cap, "uy")
             for k, (node, c, gap, cap) in enumerate([(0, 0.0, 0.0, 0.0), (3, 50.0, 1e-3, 0.0),
                                                      ("b", 0.0, -2e-4, 10.0), (7, 20.0, 0.0, 0.0)])]
    return xy, beams, masses, soils


def frame_by_arrays(xy, beams, masses, soils):
    """The same frame, one call per kind of row."""
    fr = Frame2D()
    coords = np.array(list(xy.values()))
    fr.nodes(list(xy), coords[:, 0], coords[:, 1])
    name, i, j, E, A, I, strain, curvature = zip(*beams)
    fr.beams(name, i, j, np.array(E), np.array(A), np.array(I), axial_strain=np.array(strain),
             curvature=np.array(curvature))
    node, m, J = zip(*masses)
    fr.masses(node, np.array(m), J=np.array(J))
    name, node, k, c, gap, capacity, _ = zip(*soils)
    fr.soils(name, node, np.array(k), c=np.array(c), gap=np.array(gap), capacity=np.array(capacity))
    return fr


def same(a, b):
    """The same array or sparse matrix, bit for bit (signs of zeros included)."""
    a = a.toarray() if sp.issparse(a) else np.asarray(a)
    b = b.toarray() if sp.issparse(b) else np.asarray(b)
    return a.shape == b.shape and np.array_equal(a, b) and np.array_equal(np.signbit(a), np.signbit(b))


def finish(fr):
    fr.support(0)
    fr.rayleigh(0.3, 2e-3)
    return fr.build()


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_arrays_build_the_frame_of_the_loop_bit_for_bit(seed):
    data = rows(seed)
    loop, arrays = finish(frame_by_loop(*data)), finish(frame_by_arrays(*data))
    for name in ("G", "E", "B", "A", "r", "E_v"):
        x, y = getattr(loop.natural, name), getattr(arrays.natural, name)
        assert (x is None) == (y is None)
        if x is not None:
            assert same(x, y), name
    assert same(loop.natural.theta(0.0), arrays.natural.theta(0.0))
    assert same(loop.M, arrays.M) and same(loop.C, arrays.C) and same(loop.nodal_mass, arrays.nodal_mass)
    assert loop.element_names == arrays.element_names and loop.strain_names == arrays.strain_names
    assert loop.constraint_names == arrays.constraint_names and loop.dofs.free == arrays.dofs.free
    for a, b in zip(loop.elements, arrays.elements):
        assert repr(a) == repr(b)
    m1, m2 = loop.to_model(), arrays.to_model()
    for name in ("K", "M", "C", "F", "H", "F_v", "H_v"):
        x, y = getattr(m1, name), getattr(m2, name)
        assert (x is None) == (y is None) and (x is None or same(x, y)), name
    assert same(m1.g(0.0), m2.g(0.0)) and same(m1.q_imposed(0.0), m2.q_imposed(0.0))
    assert m1.dof_names == m2.dof_names and m1.constraint_names == m2.constraint_names


def test_soils_along_a_vector_or_ux_and_numbers_for_all_rows():
    fr1, fr2 = Frame2D(), Frame2D()
    for fr in (fr1, fr2):
        fr.nodes([1, 2, 3], [0.0, 1.0, 2.0], 0.0)
        fr.beams(["b1", "b2"], [1, 2], [2, 3], E=2e7, A=0.1, I=1e-3)
    for direction in ((0.3, 1.0), "ux"):
        names = [f"{direction}{k}" for k in (1, 2, 3)]
        for name, node in zip(names, (1, 2, 3)):
            fr1.soil(name, node, 5e4, c=10.0, direction=direction)
        fr2.soils(names, [1, 2, 3], 5e4, c=10.0, direction=direction)
    for fr in (fr1, fr2):
        fr.support(1)
    s1, s2 = fr1.build(), fr2.build()
    for name in ("G", "E", "B", "E_v"):
        assert same(getattr(s1.natural, name), getattr(s2.natural, name)), name
    assert [e.dofs for e in s1.elements] == [e.dofs for e in s2.elements]


def test_numpy_integer_ids_and_one_number_for_all():
    fr = Frame2D()
    nodes = np.arange(5)
    fr.nodes(nodes, np.linspace(0.0, 4.0, 5), 0.0)
    fr.beams([f"b{k}" for k in range(4)], nodes[:-1], nodes[1:], E=1.0, A=2.0, I=3.0)
    fr.masses(nodes, 1.5)
    fr.nodes(np.array(["p", "q"]), [9.0, 10.0], [1.0, 1.0])               # numpy strings: plain strs
    fr.beams(np.array(["bp"]), np.array(["p"]), ["q"], E=1.0, A=2.0, I=3.0)
    assert all(type(node) in (int, str) for node in fr._coords) and type(fr._elements[-1].name) is str
    assert fr._elements[-1].dofs[0] == ("p", "ux") and type(fr._elements[-1].dofs[0][0]) is str
    st = fr.build()
    assert st.dofs.free[0] == (0, "ux") and type(st.dofs.free[0][0]) is int
    np.testing.assert_array_equal(st.nodal_mass[:5, :2], 1.5)


def snapshot(fr):
    """What a frame holds, to see that a failed call changed nothing."""
    return (dict(fr._coords), list(fr._elements), set(fr._names), {k: v.copy() for k, v in fr._mass.items()},
            dict(fr._beams))


def base_frame():
    fr = Frame2D()
    fr.nodes([1, 2, 3], [0.0, 1.0, 1.0], 0.0)              # 2 and 3 at the same place
    fr.beam("old", 1, 2, E=1.0, A=1.0, I=1.0)
    return fr


@pytest.mark.parametrize("call, error, message", [
    (lambda fr: fr.nodes([4, 5], [0.0, 1.0], [0.0, np.nan]), ValueError, r"^nodes: y\[1\] = nan must be finite$"),
    (lambda fr: fr.nodes([4, 1], [0.0, 1.0], 0.0), ValueError, r"^nodes: ids\[1\] = 1: node 1 is already defined$"),
    (lambda fr: fr.nodes([4, 4], [0.0, 1.0], 0.0), ValueError, r"^nodes: ids\[1\] = 4: node 4 is already defined$"),
    (lambda fr: fr.nodes([4, 2.5], [0.0, 1.0], 0.0), TypeError, r"^nodes: ids\[1\] = 2.5 must be an int or a str$"),
    (lambda fr: fr.nodes([4, 5], [0.0, 1.0, 2.0], 0.0), ValueError,
     r"^nodes: x must be a number or 2 numbers \(one per row\), got shape \(3,\)$"),
    (lambda fr: fr.beams(["a", "b"], [1, 2], [2, 1], E=[1.0, -1.0], A=1.0, I=1.0), ValueError,
     r"^beams: E\[1\] = -1.0 must be > 0$"),
    (lambda fr: fr.beams(["a", "b"], [1, 2], [2, 9], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: j\[1\] = 9 is not defined \(nodes: 1, 2, 3\)$"),
    (lambda fr: fr.beams(["a", "a"], [1, 2], [2, 1], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: names\[1\] = 'a' is already used by another element$"),
    (lambda fr: fr.beams(["a", "old"], [1, 2], [2, 1], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: names\[1\] = 'old' is already used by another element$"),
    (lambda fr: fr.beams(["a", "b"], [1, 2], [2, 2], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: i\[1\] and j\[1\] are the same node 2 \(beam 'b'\)$"),
    (lambda fr: fr.beams(["a", "b"], [1, 2], [2, 3], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beam 'b': nodes i=2 and j=3 are both at \(1, 0\): zero-length element$"),
    (lambda fr: fr.beams(["a"], [1, 2], [2, 3], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: 1 names for 2 rows; give one name per row$"),
    (lambda fr: fr.beams(["a", "b"], [1, 2], [2], E=1.0, A=1.0, I=1.0), ValueError,
     r"^beams: i has 2 nodes and j 1; give one of each per beam$"),
    (lambda fr: fr.beams(["a"], [1], [2], E=True, A=1.0, I=1.0), TypeError, r"^beams: E must be a real number"),
    (lambda fr: fr.beams(["a"], [1], [2], E="1", A=1.0, I=1.0), TypeError, r"^beams: E must be a real number"),
    (lambda fr: fr.masses([1, 7], [1.0, 2.0]), ValueError, r"^masses: nodes\[1\] = 7 is not defined"),
    (lambda fr: fr.masses([1, 2], [1.0, 2.0], J=[0.0, -1.0]), ValueError, r"^masses: J\[1\] = -1.0 must be >= 0$"),
    (lambda fr: fr.soils(["s1", ""], [1, 2], 1e3), TypeError, r"^soils: names\[1\] must be a non-empty str"),
    (lambda fr: fr.soils(["s1", "s2"], [1, 2], [1e3, 0.0]), ValueError, r"^soils: k\[1\] = 0.0 must be > 0$"),
    (lambda fr: fr.soils(["s1", "s2"], [1, 2], 1e3, capacity=-1.0), ValueError,
     r"^soils: capacity\[0\] = -1.0 must be >= 0$"),
    (lambda fr: fr.soils(["s1"], [1], 1e3, direction="uz"), ValueError, r"^soils: direction='uz' is not valid"),
])
def test_a_call_that_fails_names_the_row_and_adds_nothing(call, error, message):
    fr = base_frame()
    before = snapshot(fr)
    with pytest.raises(error, match=message):
        call(fr)
    after = snapshot(fr)
    assert after[0].keys() == before[0].keys() and after[1] == before[1] and after[2] == before[2]
    assert after[3].keys() == before[3].keys() and after[4] == before[4]


def test_masses_of_a_node_given_twice_add_up_as_repeated_calls():
    fr1, fr2 = Frame2D(), Frame2D()
    for fr in (fr1, fr2):
        fr.nodes([1, 2], [0.0, 1.0], 0.0)
        fr.mass(1, 0.25, J=0.5)
    fr1.mass(1, 1.0)
    fr1.mass(2, 2.0, J=0.1)
    fr1.mass(1, 3.0, J=0.2)
    fr2.masses([1, 2, 1], [1.0, 2.0, 3.0], J=[0.0, 0.1, 0.2])
    for node in (1, 2):
        assert same(fr1._mass[node], fr2._mass[node])


def banded_spd(n, b, rng):
    """A random symmetric positive definite matrix of half-bandwidth ``b`` (diagonally dominant)."""
    offsets = list(range(-b, b + 1))
    diagonals = [rng.uniform(-1.0, 1.0, n - abs(k)) for k in offsets]
    A = sp.diags(diagonals, offsets).tocsr()
    A = (A + A.T) / 2
    return (A + sp.diags(np.abs(A).sum(axis=1).A1 + 0.1)).tocsr()


@pytest.mark.parametrize("b", [1, 4, DEFINITENESS_BANDED_MAX, DEFINITENESS_BANDED_MAX + 1])
def test_the_banded_definiteness_check_decides_as_the_inertia(b):
    """Definite passes; one negative pivot (a shifted diagonal) is refused with the message of the
    path taken (the banded Cholesky within the limit, the LU's inertia beyond it)."""
    rng = np.random.default_rng(b)
    A = banded_spd(60, b, rng)
    check_definite("K", A, strict=True)
    check_definite("K", sp.coo_matrix(A), strict=True)                   # any sparse format
    eig = np.linalg.eigvalsh(A.toarray())
    shifted = (A - sp.identity(60) * (eig[0] + 0.5 * (eig[1] - eig[0]))).tocsr()   # one eigenvalue < 0
    assert np.sum(np.linalg.eigvalsh(shifted.toarray()) < 0) == 1
    expected = ("Cholesky factorisation fails" if b <= DEFINITENESS_BANDED_MAX
                else "LDL\\^T factorisation has 1 nonpositive")
    with pytest.raises(ValueError, match=f"^K must be symmetric positive definite; its {expected}"):
        check_definite("K", shifted, strict=True)
