"""The natural form (eqs. 1-16): imposed strains, resistances, the interaction matrix, Kelvin parts."""

import numpy as np
import pytest
import scipy.sparse as sp

import unilateral as ul


def random_natural(seed=0, n=6, ne=9, m=3):
    rng = np.random.default_rng(seed)
    G = rng.standard_normal((n, ne))
    R = rng.standard_normal((ne, ne))
    E = R @ R.T + ne * np.eye(ne)
    Rv = rng.standard_normal((ne, ne))
    E_v = 0.1 * (Rv @ Rv.T)
    B = rng.standard_normal((ne, m))
    Ra = rng.standard_normal((m, m))
    A = Ra @ Ra.T
    r = rng.uniform(0.0, 1.0, m)
    return G, E, E_v, B, A, r, rng


def test_from_natural_performs_eqs_13_to_16():
    G, E, E_v, B, A, r, rng = random_natural()
    theta0 = rng.standard_normal(G.shape[1])
    rate = rng.standard_normal(G.shape[1])
    theta = lambda t: theta0 + t * rate
    M = np.diag(rng.uniform(1.0, 2.0, G.shape[0]))
    model = ul.Model.from_natural(G, E, B, M=M, A=A, r=r, theta=theta, E_v=E_v, theta_rate=lambda t: rate)
    np.testing.assert_allclose(model.K, G @ E @ G.T, rtol=1e-12)                       # (13)
    np.testing.assert_allclose(model.F, G @ E @ B, rtol=1e-12)                         # (15)
    np.testing.assert_allclose(model.H, A + B.T @ E @ B, rtol=1e-12)                   # (16)
    np.testing.assert_allclose(model.C, G @ E_v @ G.T, rtol=1e-12)
    np.testing.assert_allclose(model.F_v, G @ E_v @ B, rtol=1e-12)
    np.testing.assert_allclose(model.H_v, B.T @ E_v @ B, rtol=1e-12)
    t = 0.7
    np.testing.assert_allclose(model.g(t), B.T @ E @ theta(t) + B.T @ E_v @ rate + r, rtol=1e-12)
    np.testing.assert_allclose(model.q_imposed(t), G @ E @ theta(t) + G @ E_v @ rate, rtol=1e-12)  # (14)


def test_stresses_recover_sigma_and_psi():
    """psi = B^T sigma - A v - r (eq. 4) with sigma = E (G^T u - B v - theta) (eqs. 1-3, 9)."""
    G, E, _, B, A, r, rng = random_natural(1)
    theta = rng.standard_normal(G.shape[1])
    model = ul.Model.from_natural(G, E, B, M=np.eye(G.shape[0]), A=A, r=r, theta=theta)
    u = rng.standard_normal((4, G.shape[0]))
    v = rng.uniform(0, 1, (4, B.shape[1]))
    sigma = model.natural.stresses(np.zeros(4), u, v)
    psi = u @ model.F - v @ model.H.T - model.g(0.0)
    np.testing.assert_allclose(sigma @ B - v @ A.T - r, psi, rtol=1e-10, atol=1e-10)


def test_an_imposed_strain_closes_a_gap():
    """A bar heated against a wall: the thermal elongation theta closes the gap g0 and presses."""
    k, g0 = 1000.0, 0.002
    # DOF u: the bar end; strain 0: the bar (stiffness k_bar) from ground to u; strain 1: the
    # contact (stiffness k) between u and the wall, compression-only, with initial gap g0
    k_bar = 500.0
    G = np.array([[1.0, -1.0]])          # e_bar = u, e_contact = -u (the gap closes as u grows)
    E = np.diag([k_bar, k])
    B = np.array([[0.0], [1.0]])
    for elongation, expect_contact in ((0.001, False), (0.005, True)):
        theta = np.array([elongation, -g0])
        model = ul.Model.from_natural(G, E, B, M=[[1.0]], theta=theta)
        sol = ul.solve(model, None, dt=0.01, t_end=0.01)
        v, psi = sol.v[0, 0], sol.psi[0, 0]
        if expect_contact:
            # compatibility: u = elongation - force/k_bar, penetration of the spring = u - g0
            u = (k_bar * elongation + k * g0) / (k_bar + k)
            assert v == 0.0
            np.testing.assert_allclose(psi, -k * (u - g0), rtol=1e-10)
            np.testing.assert_allclose(sol.u[0, 0], u, rtol=1e-10)
        else:
            assert psi == 0.0 or abs(psi) < 1e-12
            np.testing.assert_allclose(v, g0 - elongation, rtol=1e-10)
            np.testing.assert_allclose(sol.u[0, 0], elongation, rtol=1e-10)


def test_the_interaction_matrix_couples_the_constraints():
    """With A != 0 the opening of one constraint changes the reaction of the other (eq. 4)."""
    G = np.eye(2)
    E = np.diag([100.0, 100.0])
    B = np.eye(2)
    A = np.array([[50.0, 40.0], [40.0, 50.0]])
    model = ul.Model.from_natural(G, E, B, M=np.eye(2), A=A)
    sol = ul.solve(model, lambda t: np.array([30.0, -20.0]), dt=0.01, t_end=0.01)
    v, psi = sol.v[0], sol.psi[0]
    assert v[0] > 0 and v[1] == 0                       # the first opens, the second stays closed
    np.testing.assert_allclose(psi, model.F.T @ sol.u[0] - model.H @ v - model.g(0.0), atol=1e-9)
    free = ul.Model.from_natural(G, E, B, M=np.eye(2))
    sol_free = ul.solve(free, lambda t: np.array([30.0, -20.0]), dt=0.01, t_end=0.01)
    assert abs(sol_free.psi[0, 1] - psi[1]) > 1.0      # coupling through A changes psi_2
    assert np.all(sol.psi[0] <= 1e-12) and np.all(sol.v[0] >= 0) and abs(sol.v[0] @ sol.psi[0]) < 1e-10


def test_sparse_and_dense_models_agree():
    G, E, E_v, B, A, r, rng = random_natural(2)
    M = np.diag(rng.uniform(1.0, 2.0, G.shape[0]))
    dense = ul.Model.from_natural(G, E, B, M=M, A=A, r=r, E_v=E_v)
    sparse = ul.Model.from_natural(sp.csr_matrix(G), sp.csr_matrix(E), sp.csr_matrix(B), M=sp.csr_matrix(M),
                                   A=A, r=r, E_v=sp.csr_matrix(E_v))
    s = np.array([0.5 + 3j, 20.0])
    np.testing.assert_allclose(ul.MatrixKernel(sparse)(s), ul.MatrixKernel(dense)(s), rtol=1e-10)


def test_a_matrix_level_gap_equals_the_frame_gap_and_loads_the_structure_consistently():
    """``gap=`` sets g = -H gap and q_imposed = -F gap: the Frame2D soil element with the same gap."""
    from unilateral.structure import Frame2D

    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False, rz=True)
    fr.mass(1, 2.0)
    fr.soil("s", 1, k=2000.0, c=5.0, gap=0.01)
    fr.spring("h", 1, k=10.0)
    frame = fr.build().to_model()
    matrix = ul.Model(M=[[2.0]], K=[[2010.0]], F=[[2000.0]], H=[[2000.0]], C=[[5.0]], F_v=[[5.0]], H_v=[[5.0]],
                      gap=[0.01])
    assert np.allclose(matrix.g(0.0), frame.g(0.0), rtol=1e-15) and np.allclose(matrix.q_imposed(0.0),
                                                                              frame.q_imposed(0.0), rtol=1e-15)
    load = lambda t: np.array([-20.0 - 300.0 * np.sin(8.0 * t)])
    a, b = (ul.solve(m, load, dt=1e-3, t_end=1.5, method="direct") for m in (frame, matrix))
    assert a.success and b.success
    assert np.abs(a.v).max() > 1e-3 and np.abs(a.psi).max() > 1.0         # it opens and closes
    assert np.allclose(a.u, b.u, rtol=0, atol=1e-14) and np.allclose(a.psi, b.psi, rtol=0, atol=1e-10)
    # g alone (without the load of the imposed strain) is another model: a force g acts on the mass
    g_only = ul.Model(M=[[2.0]], K=[[2010.0]], F=[[2000.0]], H=[[2000.0]], C=[[5.0]], F_v=[[5.0]], H_v=[[5.0]],
                      g=matrix.g(0.0))
    c = ul.solve(g_only, load, dt=1e-3, t_end=1.5, method="direct")
    assert np.abs(c.u - a.u).max() > 1e-3


def test_a_negative_gap_is_refused_with_its_index():
    with pytest.raises(ValueError, match=r"gap\[1\] = -0.5 is negative"):
        ul.Model(M=np.eye(2), K=np.eye(2), F=np.eye(2), H=np.eye(2), gap=[0.0, -0.5])
