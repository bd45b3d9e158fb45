"""The fast paths of the frame builder give the matrices of a straightforward assembly.

The builder gathers the compatibility ``G``, the block-diagonal ``E`` and the DOF map with array
operations over groups of elements, and the model's checks skip the work a diagonal or exactly
symmetric matrix does not need. These tests hold them against references written out here, element
by element (dense ``K = sum a^T k a``, ``L`` row by row with :meth:`DofMap.full_index`, ``T`` row by
row), and check that the argument checks still refuse bad input with the same messages. No test
here measures time.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.linalg import block_diag

from unilateral import Model, _validate as V
from unilateral.structure import DofMap, Frame2D
from unilateral.structure import elements as el
from unilateral.structure.dofs import csr_of_entries
from unilateral.structure.frame import _block_diagonal, _compatibility, _groups, _lumped_mass, _real


def dense(a):
    return a.toarray() if sp.issparse(a) else np.asarray(a)


def random_frame(seed=0, *, rayleigh=(0.2, 1e-3)):
    """A small random frame: beams (one with two hinges), a bar, a cable, springs, dashpots, soil
    contacts (one with friction), a gap with friction, a yield link, a slider and a rigid link."""
    rng = np.random.default_rng(seed)
    fr = Frame2D()
    xy = {k: (float(x), float(y)) for k, (x, y) in enumerate(rng.uniform(-5.0, 5.0, size=(9, 2)))}
    xy[9] = (xy[8][0] + 0.5, xy[8][1])                 # axis-aligned beam 8 -> 9
    xy[10] = (xy[8][0], xy[8][1] + 2.0)
    for node, (x, y) in xy.items():
        fr.node(node, x, y)
    fr.node("s", xy[3][0] + 0.3, xy[3][1] - 0.2)
    fr.rigid_link(3, "s")
    fr.support(0, ux=True, uy=False)
    fr.support(10)
    for k in range(8):
        fr.beam(f"b{k}", k, k + 1, E=float(rng.uniform(1e6, 3e7)), A=float(rng.uniform(0.05, 0.3)),
                I=float(rng.uniform(1e-4, 1e-2)), axial_strain=float(rng.normal(0, 1e-5)),
                curvature=float(rng.normal(0, 1e-4)), rho=float(rng.uniform(1.0, 3.0)))
    fr.beam("b8", 8, 9, E=2e7, A=0.1, I=1e-3)
    fr.hinge("h1", "b2", "i", My=50.0)
    fr.hinge("h2", "b2", "j", My=60.0, k=2e4, hardening=0.05)
    fr.bar("bar", 0, 5, E=2e8, A=1e-3, axial_strain=1e-5)
    fr.cable("cab", 1, 6, 2e8, 5e-4, slack=1e-3)
    fr.spring("sp", 2, 1e4, direction=(1.0, 0.3))
    fr.spring("sp2", 4, 2e3, j=7, direction="ux")
    fr.spring("rot", 5, 1e3, direction="rz")
    fr.dashpot("dp", 6, 30.0, direction="uy")
    fr.soil("s0", 0, 2e5, c=1e3, gap=1e-4, capacity=1.0)
    fr.soil("s1", "s", 1e5, mu=0.4, kt=5e4, ct=10.0)
    fr.soil("s2", 9, 1e5, direction=(0.2, 1.0))
    fr.gap("gp", 7, 10, 1e6, gap=2e-3, mu=0.3, kt=1e5)
    fr.yield_link("yl", 1, 4, k=1e4, Fy=30.0, hardening=0.1)
    fr.slider("sl", 9, mu=0.3, N=50.0, k=2e3)
    for node in range(10):
        fr.mass(node, float(rng.uniform(1.0, 5.0)), J=float(rng.uniform(0.0, 0.5)))
    fr.rayleigh(*rayleigh)
    return fr


def reference_T(st) -> np.ndarray:
    """``T`` (full, n) row by row: 1 on each free DOF, the rigid-body rows of a slave."""
    dofs = st.dofs
    T = np.zeros((3 * len(dofs.nodes), dofs.n))
    index = {key: k for k, key in enumerate(dofs.free)}
    for p, node in enumerate(dofs.nodes):
        if node in dofs.masters:
            m = dofs.masters[node]
            dx, dy = st.coords[node] - st.coords[m]
            terms = [(0, "ux", 1.0), (0, "rz", -dy), (1, "uy", 1.0), (1, "rz", dx), (2, "rz", 1.0)]
            owner = m
        else:
            terms = [(d, dof, 1.0) for d, dof in enumerate(el.DOF_NAMES)]
            owner = node
        for d, dof, value in terms:
            if (owner, dof) in index:
                T[3 * p + d, index[(owner, dof)]] += value
    return T


def reference_L(elements, dofs) -> np.ndarray:
    """``L`` (ne, full): each element's ``a`` on the rows of its DOFs."""
    blocks = []
    for e in elements:
        L = np.zeros((e.a.shape[0], dofs.T.shape[0]))
        for col, (node, dof) in enumerate(e.dofs):
            L[:, dofs.full_index(node, dof)] += e.a[:, col]
        blocks.append(L)
    return np.vstack(blocks)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_assembled_matrices_are_those_of_an_element_by_element_assembly(seed):
    st = random_frame(seed).build()
    T = reference_T(st)
    np.testing.assert_array_equal(dense(st.dofs.T), T)
    L = reference_L(st.elements, st.dofs)
    G = T.T @ L.T
    np.testing.assert_allclose(dense(st.natural.G), G, rtol=0, atol=1e-15 * np.abs(G).max())
    E = block_diag(*[e.E for e in st.elements])
    np.testing.assert_array_equal(dense(st.natural.E), E)
    K = np.zeros((st.n, st.n))
    for e in st.elements:                               # K = sum a^T k a on the free DOFs
        a = reference_L([e], st.dofs) @ T
        K += a.T @ e.E @ a
    scale = np.abs(K).max()
    np.testing.assert_allclose(dense(st.natural.G @ st.natural.E @ st.natural.G.T), K, rtol=0, atol=1e-14 * scale)
    model = st.to_model()
    np.testing.assert_allclose(dense(model.K), K, rtol=0, atol=1e-14 * scale)
    kelvin = [np.zeros_like(e.E) if e.E_v is None else e.E_v for e in st.elements]
    np.testing.assert_array_equal(dense(st.natural.E_v), block_diag(*kelvin))
    with_unknowns = [e.interaction for e in st.elements if e.unknowns]
    np.testing.assert_array_equal(st.natural.A, block_diag(*with_unknowns))
    np.testing.assert_array_equal(st.natural.theta(0.0), np.concatenate([e.theta for e in st.elements]))
    H = st.natural.A + dense(st.natural.B.T @ st.natural.E @ st.natural.B)
    np.testing.assert_allclose(model.H, H, rtol=0, atol=1e-15 * np.abs(H).max())
    a0, a1 = st.rayleigh
    bilateral = [e for e in st.elements if not e.unilateral]
    Lb = reference_L(bilateral, st.dofs) @ T
    dashpot = reference_L(st.dashpots, st.dofs) @ T
    C = a0 * dense(st.M) + a1 * Lb.T @ block_diag(*[e.E for e in bilateral]) @ Lb
    C += dashpot.T @ block_diag(*[d.E for d in st.dashpots]) @ dashpot
    np.testing.assert_allclose(dense(st.C), C, rtol=0, atol=1e-14 * np.abs(C).max())


def test_the_beam_element_is_that_of_the_textbook_arrays():
    """The beam's ``a``, ``E`` and ``theta`` are those of ``np.eye``/``np.vstack`` (bit for bit)."""
    rng = np.random.default_rng(5)
    for xi, xj in [((0.0, 0.0), (2.5, 0.0)), ((1.0, 1.0), (1.0, -3.0)), *rng.normal(size=(20, 2, 2))]:
        xi, xj = np.asarray(xi, float), np.asarray(xj, float)
        E, A, I, eps, kappa = rng.uniform(0.5, 2.0, 5)
        e = el.beam("b", 1, xi, 2, xj, E=E, A=A, I=I, axial_strain=eps, curvature=kappa)
        d = xj - xi
        L = float(np.hypot(d[0], d[1]))
        c, s = d / L
        beta = np.array([s, -c, 0.0, -s, c, 0.0]) / L
        a = np.vstack([np.array([-c, -s, 0.0, c, s, 0.0]), np.eye(6)[2] - beta, np.eye(6)[5] - beta])
        stiffness = np.array([[E * A / L, 0, 0], [0, 4 * E * I / L, 2 * E * I / L], [0, 2 * E * I / L, 4 * E * I / L]])
        np.testing.assert_array_equal(e.a, a)
        np.testing.assert_array_equal(e.E, stiffness)
        np.testing.assert_array_equal(e.theta, [eps * L, -kappa * L / 2, kappa * L / 2])
        assert e.dofs == ((1, "ux"), (1, "uy"), (1, "rz"), (2, "ux"), (2, "uy"), (2, "rz"))
        L2, (c2, s2) = el.chord("b", 1, xi, 2, xj)
        assert (L2, c2, s2) == (L, c, s)


def test_the_dof_map_of_links_and_supports_is_that_of_the_rows_one_by_one():
    coords = {k: np.array([float(k), float(k % 3)]) for k in range(8)}
    restrained = {(0, "ux"), (0, "uy"), (4, "uy"), (6, "rz"), ("ghost", "ux")}
    links = {5: 4, 7: 5, 2: 1}
    dofs = DofMap(coords, restrained, rotated={0, 1, 3, 6, 7}, links=links)
    masters = {5: 4, 7: 4, 2: 1}
    assert dofs.masters == masters
    rotating = {0, 1, 3, 6} | {4, 1}                    # masters of offset slaves rotate
    free = [(node, dof) for node in coords if node not in masters for dof in el.DOF_NAMES
            if (node, dof) not in restrained and (dof != "rz" or node in rotating)]
    assert dofs.free == free
    T = np.zeros((24, len(free)))
    index = {key: k for k, key in enumerate(free)}
    for p, node in enumerate(coords):
        owner = masters.get(node, node)
        dx, dy = coords[node] - coords[owner]
        rows = ([(0, "ux", 1.0), (0, "rz", -dy), (1, "uy", 1.0), (1, "rz", dx), (2, "rz", 1.0)] if node in masters
                else [(d, dof, 1.0) for d, dof in enumerate(el.DOF_NAMES)])
        for d, dof, value in rows:
            if (owner, dof) in index and value != 0.0:
                T[3 * p + d, index[(owner, dof)]] = value
    np.testing.assert_array_equal(dofs.T.toarray(), T)
    assert dofs.T.has_canonical_format


def test_grouped_block_diagonals_and_compatibility_match_the_element_loop():
    rng = np.random.default_rng(3)
    blocks = [rng.normal(size=(k, k)) for k in rng.integers(0, 4, size=40)]
    np.testing.assert_array_equal(_block_diagonal(blocks).toarray(), block_diag(*blocks))
    assert _block_diagonal([]).shape == (0, 0)
    st = random_frame(4).build()
    L = reference_L(st.elements, st.dofs)
    np.testing.assert_array_equal(_compatibility(list(st.elements), st.dofs).toarray(), reference_T(st).T @ L.T)
    assert _compatibility([], st.dofs).shape == (st.n, 0)


def test_real_still_refuses_bad_numbers_naming_the_argument():
    assert _real("w", "k", 3) == 3.0 and type(_real("w", "k", 3)) is float
    assert _real("w", "k", np.float64(2.5), ">0") == 2.5
    assert _real("w", "k", 0.0, ">=0") == 0.0
    with pytest.raises(TypeError, match=r"^w: k must be a real number, got True$"):
        _real("w", "k", True)
    with pytest.raises(TypeError, match=r"^w: k must be a real number, got '1'$"):
        _real("w", "k", "1")
    with pytest.raises(ValueError, match=r"^w: k=nan must be finite$"):
        _real("w", "k", float("nan"))
    with pytest.raises(ValueError, match=r"^w: k=inf must be finite$"):
        _real("w", "k", float("inf"), ">0")
    with pytest.raises(ValueError, match=r"^w: k=-1 must be > 0$"):
        _real("w", "k", -1, ">0")
    with pytest.raises(ValueError, match=r"^w: k=0.0 must be > 0$"):
        _real("w", "k", 0.0, ">0")
    with pytest.raises(ValueError, match=r"^w: k=-0.5 must be >= 0$"):
        _real("w", "k", -0.5, ">=0")
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 1.0, 0.0)
    with pytest.raises(TypeError, match=r"beam 'b': E must be a real number, got False"):
        fr.beam("b", 1, 2, E=False, A=1.0, I=1.0)
    with pytest.raises(ValueError, match=r"beam 'b': I=-2.0 must be > 0"):
        fr.beam("b", 1, 2, E=1.0, A=1.0, I=-2.0)
    with pytest.raises(ValueError, match=r"node 3: y=inf must be finite"):
        fr.node(3, 0.0, float("inf"))
    with pytest.raises(ValueError, match=r"mass at node 1: m=-1.0 must be >= 0"):
        fr.mass(1, -1.0)
    with pytest.raises(ValueError, match=r"soil 's': k=nan must be finite"):
        fr.soil("s", 1, float("nan"))
    with pytest.raises(ValueError, match=r"soil 's': kt is a friction parameter"):
        fr.soil("s", 1, 1.0, kt=1.0)
    with pytest.raises(ValueError, match=r"soil 's': ct is a friction parameter"):
        fr.soil("s", 1, 1.0, ct=2.0)


def test_masses_add_up_and_a_first_mass_is_the_sum_with_zero():
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.mass(1, 2.0, J=0.5)
    fr.mass(1, 1.5)
    np.testing.assert_array_equal(fr._mass[1], [3.5, 3.5, 0.5])


def large_diagonal(m, value=2.0):
    H = np.zeros((m, m))
    H[np.arange(m), np.arange(m)] = value
    return H


def test_the_cheap_symmetry_and_definiteness_checks_decide_as_the_full_ones():
    m = 200
    H = large_diagonal(m)
    V.check_symmetric("H", H)
    V.check_psd("H", H)
    V.check_psd("H", np.zeros((m, m)))
    with pytest.raises(ValueError, match="H must be symmetric positive definite; its smallest eigenvalue is 0"):
        V.check_psd("H", np.zeros((m, m)), strict=True)
    H[5, 5] = -1.0
    with pytest.raises(ValueError, match=r"H must be symmetric positive semidefinite; its smallest eigenvalue is -1"):
        V.check_psd("H", H)
    B = large_diagonal(m)
    B[3, 4] = B[4, 3] = 3.0                             # a 2 x 2 block with eigenvalues -1 and 5
    with pytest.raises(ValueError, match=r"smallest eigenvalue is -1 \(largest 5\)"):
        V.check_psd("B", B)
    B[3, 4] = 3.0 + 1e-6                                # not symmetric
    with pytest.raises(ValueError, match=r"B must be symmetric; max \|B - B\^T\| = 1e-06"):
        V.check_symmetric("B", B)
    S = sp.csr_matrix(B)
    with pytest.raises(ValueError, match=r"B must be symmetric; max \|B - B\^T\| = 1e-06"):
        V.check_symmetric("B", S)
    B[3, 4] = 3.0
    V.check_symmetric("B", sp.csr_matrix(B))
    unsorted = sp.csr_matrix(B)[:, ::-1][:, ::-1]         # same matrix, other index order
    V.check_symmetric("B", unsorted)
    with pytest.raises(ValueError, match="K contains nan at index"):
        V.check_finite("K", np.full((100, 100), np.nan))


def test_a_large_model_of_many_contacts_has_the_offsets_of_the_dense_products():
    """``g = B^T E theta + r`` from the sparse product (many contacts) equals the dense one."""
    fr = Frame2D()
    n = 900
    for k in range(n):
        fr.node(k, 0.1 * k, 0.0)
    for k in range(n - 1):
        fr.beam(f"b{k}", k, k + 1, E=1.0, A=2e7, I=2e6, curvature=1e-4 * (k % 3))
    for k in range(n):
        fr.mass(k, 1.0)
        fr.soil(f"s{k}", k, 1e3 * (1 + k % 5), gap=1e-3 * (k % 4), capacity=0.5 * (k % 2), c=1.0 + k % 3)
    fr.support(0, ux=True, uy=False)
    st = fr.build()
    nat = st.natural
    assert nat.B.shape[1] * nat.E.shape[0] > 2_000_000      # the sparse route
    model = st.to_model()
    theta = nat.theta(0.0)
    g = dense(nat.B.T @ nat.E) @ theta + nat.r
    np.testing.assert_allclose(model.g(0.0), g, rtol=1e-15, atol=1e-15 * np.abs(g).max())
    H = nat.A + dense(nat.B.T @ nat.E @ nat.B)
    np.testing.assert_array_equal(model.H, H)
    assert isinstance(model.H, np.ndarray) and model.H.flags.c_contiguous
    q = np.asarray(nat.G @ nat.E @ theta).ravel()
    np.testing.assert_allclose(model.q_imposed(0.0), q, rtol=0, atol=1e-15 * np.abs(q).max())


def test_a_model_refuses_a_nonsymmetric_or_indefinite_matrix_as_before():
    n = 80
    K = large_diagonal(n)
    M = large_diagonal(n, 1.0)
    F = np.zeros((n, 70))
    H = large_diagonal(70)
    Model(M, K, F, H)
    Kb = K.copy()
    Kb[0, 1] = 1e-3
    with pytest.raises(ValueError, match="K must be symmetric"):
        Model(M, Kb, F, H)
    Hb = H.copy()
    Hb[0, 0] = -1.0
    with pytest.raises(ValueError, match="H must be symmetric positive semidefinite"):
        Model(M, K, F, Hb)
    with pytest.raises(ValueError, match="constraint_names has the name 'a' twice"):
        Model(M, K, F, H, constraint_names=["a"] * 70)


def test_the_builders_elements_are_the_frozen_dataclass_with_every_field():
    """The elements made without the dataclass's ``__init__`` have its fields and stay frozen."""
    import dataclasses

    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 3.0, 4.0)
    fr.beam("b", 1, 2, E=1.0, A=2.0, I=3.0)
    fr.soil("s", 2, 1e3, c=5.0)
    fr.spring("k", 1, 10.0, j=2, direction="ux")
    for e in fr._elements:
        assert type(e) is el.Element
        assert list(vars(e)) == [f.name for f in dataclasses.fields(el.Element)]
        again = el.Element(**{f.name: getattr(e, f.name) for f in dataclasses.fields(el.Element)})
        assert vars(again).keys() == vars(e).keys()
        assert repr(again) == repr(e)
        with pytest.raises(dataclasses.FrozenInstanceError):
            e.name = "other"
        assert dataclasses.replace(e, name="copy").name == "copy"
    beam, soil, spring = fr._elements
    assert beam.E_v is None and beam.unknowns == () and beam.A is None
    np.testing.assert_array_equal(soil.E_v, [[5.0]])
    assert soil.unknowns == (el.Unknown("s", 0, 1.0, 0.0),)
    assert spring.dofs == ((1, "ux"), (2, "ux")) and spring.a.tolist() == [[-1.0, 1.0]]


# ---------------------------------------------------------------------- the second round of fast paths
def same_arrays(X, Y):
    """The same sparse matrix stored the same way (class, shape, index order, values bit for bit)."""
    return (type(X) is type(Y) and X.shape == Y.shape and np.array_equal(X.indptr, Y.indptr)
            and np.array_equal(X.indices, Y.indices) and np.array_equal(X.data, Y.data))


def test_csr_of_entries_is_the_coo_route_and_refuses_as_it_does():
    rng = np.random.default_rng(7)
    for _ in range(50):
        shape = tuple(int(x) for x in rng.integers(1, 12, 2))
        count = int(rng.integers(0, shape[0] * shape[1] + 1))
        flat = rng.choice(shape[0] * shape[1], size=count, replace=False)
        rows, cols = np.divmod(flat, shape[1])
        vals = rng.normal(size=count)
        vals[rng.uniform(size=count) < 0.2] = 0.0         # explicit zeros are kept, as there
        assert same_arrays(csr_of_entries(vals, rows, cols, shape), sp.csr_matrix((vals, (rows, cols)), shape=shape))
    rows, cols, vals = np.array([0, 1, 0]), np.array([2, 0, 2]), np.array([1.0, 2.0, 3.0])   # a repeated entry
    assert same_arrays(csr_of_entries(vals, rows, cols, (2, 3)), sp.csr_matrix((vals, (rows, cols)), shape=(2, 3)))
    with pytest.raises(ValueError) as ours:
        csr_of_entries(vals, rows, np.array([2, 0, 5]), (2, 3))
    with pytest.raises(ValueError) as theirs:
        sp.csr_matrix((vals, (rows, np.array([2, 0, 5]))), shape=(2, 3))
    assert str(ours.value) == str(theirs.value)


def test_groups_of_few_and_of_many_rows_are_the_same():
    rng = np.random.default_rng(1)
    keys = rng.integers(0, 4, size=(500, 2))
    many = _groups(keys)
    few = [(key, members) for start in (0,) for key, members in _groups(keys[:60])]
    expected: dict = {}
    for p, key in enumerate(map(tuple, keys.tolist())):
        expected.setdefault(key, []).append(p)
    assert [(key, members.tolist()) for key, members in many] == list(expected.items())
    expected_few: dict = {}
    for p, key in enumerate(map(tuple, keys[:60].tolist())):
        expected_few.setdefault(key, []).append(p)
    assert [(key, members.tolist()) for key, members in few] == list(expected_few.items())


def test_the_lumped_mass_is_the_product_of_the_transformation():
    """Without links ``M`` is made as a diagonal (zero masses not stored); it is the product's."""
    fr = Frame2D()
    for k in range(6):
        fr.node(k, float(k), 0.0)
    for k in range(5):
        fr.beam(f"b{k}", k, k + 1, E=1.0, A=1.0, I=1.0)
    fr.support(0)
    fr.mass(2, 3.0, J=0.5)
    fr.mass(4, 0.0)
    fr.mass(5, 1.5)
    st = fr.build()
    product = (st.dofs.T.T @ sp.diags(st.nodal_mass.ravel()) @ st.dofs.T).tocsr()
    assert same_arrays(st.M, product)
    assert same_arrays(_lumped_mass(st.dofs, st.nodal_mass), product)
    model = st.to_model()                               # no Kelvin element, no contact
    nat = st.natural
    assert same_arrays(model.K, nat.G @ nat.E @ nat.G.T) and model.F.shape == (st.n, 0)
    assert model.dof_names == st.dofs.names
    linked = random_frame(2).build()                    # with a rigid link: the product itself
    product = (linked.dofs.T.T @ sp.diags(linked.nodal_mass.ravel()) @ linked.dofs.T).tocsr()
    assert same_arrays(linked.M, product)


def test_a_compatibility_with_a_repeated_dof_is_that_of_the_element_loop():
    """An element naming one DOF twice (``L`` with a repeated entry) takes the summing route."""
    st = random_frame(1).build()
    odd = el.Element("odd", "spring", ((1, "ux"), (1, "ux"), (2, "uy")), np.array([[1.0, 2.0, -1.0]]),
                     np.array([[5.0]]), np.zeros(1))
    elements = list(st.elements) + [odd]
    L = reference_L(elements, st.dofs)
    np.testing.assert_allclose(_compatibility(elements, st.dofs).toarray(), reference_T(st).T @ L.T,
                               rtol=0, atol=1e-15 * np.abs(L).max())


def test_the_model_keeps_what_it_computes_and_copies_what_it_is_given():
    st = random_frame(0).build()
    nat = st.natural
    model = st.to_model()
    H = nat.A + dense(nat.B.T @ nat.E @ nat.B)
    np.testing.assert_allclose(model.H, H, rtol=0, atol=1e-15 * np.abs(H).max())
    assert not np.shares_memory(model.natural.A, nat.A)       # the given A is copied
    again = st.to_model()                                     # (computes K again: the same arrays)
    assert same_arrays(again.K, model.K)
    assert again.K is not model.K
    # a public Model gets copies of every dense matrix it is given
    n, m = 30, 4
    K, M, F, Hd = 2.0 * np.eye(n), np.eye(n), np.zeros((n, m)), np.eye(m)
    public = Model(M, K, F, Hd)
    for mine, given in ((public.K, K), (public.M, M), (public.F, F), (public.H, Hd)):
        assert not np.shares_memory(mine, given)
    Hd[0, 0] = 5.0
    assert public.H[0, 0] == 1.0
    # from_natural: a zero A given or left out, the same model
    G = sp.csr_matrix(np.eye(3))
    E = sp.csr_matrix(np.diag([1.0, 2.0, 3.0]))
    B = sp.csr_matrix(np.array([[1.0], [0.0], [0.0]]))
    left_out = Model.from_natural(G, E, B, M=np.eye(3))
    given = Model.from_natural(G, E, B, M=np.eye(3), A=np.zeros((1, 1)))
    np.testing.assert_array_equal(left_out.H, given.H)
    np.testing.assert_array_equal(left_out.natural.A, given.natural.A)
    with pytest.raises(ValueError, match="A must be symmetric positive semidefinite"):
        Model.from_natural(G, E, B, M=np.eye(3), A=-np.ones((1, 1)))


def test_a_replaced_or_copied_structure_builds_the_same_model():
    import copy
    import dataclasses

    st = random_frame(3).build()
    first, second, third = st.to_model(), dataclasses.replace(st).to_model(), copy.copy(st).to_model()
    assert third.K is not first.K
    for other in (second, third):
        for name in ("K", "M", "C", "F"):
            a, b = getattr(first, name), getattr(other, name)
            if sp.issparse(a):
                assert same_arrays(a, b)
            else:
                np.testing.assert_array_equal(a, b)
        np.testing.assert_array_equal(first.H, other.H)


def test_small_symmetry_checks_still_refuse_with_the_same_message():
    A = np.array([[1.0, 2.0], [2.0 + 1e-3, 1.0]])
    with pytest.raises(ValueError, match=r"^A must be symmetric; max \|A - A\^T\| = 0.001"):
        V.check_symmetric("A", A)
    with pytest.raises(ValueError, match=r"^A must be symmetric; max \|A - A\^T\| = 0.001"):
        V.check_symmetric("A", sp.csr_matrix(A))
    V.check_symmetric("A", np.array([[1.0, 2.0], [2.0, 1.0]]))
    V.check_symmetric("A", np.array([[1.0, 2.0], [2.0 + 1e-12, 1.0]]))     # within the tolerance
    with pytest.raises(ValueError, match="A contains nan"):
        V.as_matrix("A", np.array([[np.nan]]), (1, 1))


def test_the_fast_argument_paths_give_the_elements_of_the_checked_ones():
    """Python floats take the inline checks; numpy floats and ints the full ones: the same frame."""
    def frame(number):
        fr = Frame2D()
        for k in range(4):
            fr.node(k, number(1.5 * k), number(0.25 * k))
        for k in range(3):
            fr.beam(f"b{k}", k, k + 1, E=number(2.0), A=number(3.0), I=number(4.0),
                    axial_strain=number(1e-4), curvature=number(0.0))
        for k in range(4):
            fr.mass(k, number(1.0 + k), J=number(0.5))
        fr.soil("s", 3, number(1e3))
        fr.support(0)
        return fr.build()

    fast, checked = frame(float), frame(np.float64)
    for a, b in zip(fast.elements, checked.elements):
        for name in ("a", "E", "theta"):
            np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
        assert a.dofs == b.dofs and a.unknowns == b.unknowns
    np.testing.assert_array_equal(fast.nodal_mass, checked.nodal_mass)
    assert same_arrays(fast.M, checked.M) and same_arrays(fast.natural.G, checked.natural.G)
    assert fast.coords.keys() == checked.coords.keys()
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 1.0, 0.0)
    with pytest.raises(ValueError, match=r"^node 1 is already defined \(at \(0, 0\)\)$"):
        fr.node(1, 2.0, 2.0)
    with pytest.raises(ValueError, match=r"^node 3: x=nan must be finite$"):
        fr.node(3, float("nan"), 0.0)
    with pytest.raises(ValueError, match=r"^beam 'b': i and j are the same node 1$"):
        fr.beam("b", 1, 1, E=1.0, A=1.0, I=1.0)
    with pytest.raises(ValueError, match=r"^beam 'b': j=7 is not defined"):
        fr.beam("b", 1, 7, E=1.0, A=1.0, I=1.0)
    with pytest.raises(ValueError, match=r"^beam 'b': j=\[1\] is not defined"):
        fr.beam("b", 1, [1], E=1.0, A=1.0, I=1.0)
    with pytest.raises(ValueError, match=r"^beam 'b': A=inf must be finite$"):
        fr.beam("b", 1, 2, E=1.0, A=float("inf"), I=1.0)
    with pytest.raises(ValueError, match=r"^beam 'b': curvature=nan must be finite$"):
        fr.beam("b", 1, 2, E=1.0, A=1.0, I=1.0, curvature=float("nan"))
    with pytest.raises(ValueError, match=r"^mass at node 1: J=-0.5 must be >= 0$"):
        fr.mass(1, 1.0, J=-0.5)
    with pytest.raises(ValueError, match=r"^mass at node 9: node=9 is not defined"):
        fr.mass(9, 1.0)
    fr.beam("b", 1, 2, E=1.0, A=1.0, I=1.0)
    with pytest.raises(ValueError, match=r"^beam 'b': the name is already used by another element$"):
        fr.beam("b", 1, 2, E=1.0, A=1.0, I=1.0)
    fr.node(3, 1.0, 0.0)
    with pytest.raises(ValueError, match=r"^beam 'c': nodes i=2 and j=3 are both at \(1, 0\): zero-length element$"):
        fr.beam("c", 2, 3, E=1.0, A=1.0, I=1.0)
    fr.soil("s", 1, 1e3)
    assert fr._elements[-1].unknowns == (el.Unknown("s", 0, 1.0, 0.0),)
    assert list(vars(fr._elements[-1].unknowns[0])) == list(vars(el.Unknown("s", 0, 1.0, 0.0)))

