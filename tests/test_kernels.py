"""Laplace-domain kernels: the sign of eq. (23), Kelvin elements, the load transfer."""

import numpy as np
import pytest
import scipy.sparse as sp

import unilateral as ul
from conftest import rocking_model

S = np.array([0.3 + 2.0j, 1.0, 7.0j, 40.0 - 3.0j, 1e3 + 1e3j])


@pytest.mark.parametrize("sparse", [False, True])
def test_one_spring_kernel_pins_the_sign(sparse):
    k, m = 200.0, 4.0
    wrap = sp.csr_matrix if sparse else np.array
    model = ul.Model(M=wrap([[m]]), K=wrap([[k]]), F=[[k]], H=[[k]])
    got = ul.MatrixKernel(model)(S)[:, 0, 0]
    np.testing.assert_allclose(got, k * m * S**2 / (m * S**2 + k), rtol=1e-13)
    # an uplifted free mass needs no force; an instantaneous gap opening meets the spring alone
    assert abs(ul.MatrixKernel(model)(0.0)[0, 0]) < 1e-12
    np.testing.assert_allclose(ul.MatrixKernel(model)(1e9)[0, 0], k, rtol=1e-9)


def test_kelvin_element_uses_E_plus_s_Ev():
    k, c, m = 200.0, 10.0, 4.0
    model = ul.Model.from_natural(G=[[1.0]], E=[[k]], B=[[1.0]], M=[[m]], E_v=[[c]])
    ks = k + c * S
    expected = ks - ks**2 / (m * S**2 + ks)
    np.testing.assert_allclose(ul.MatrixKernel(model)(S)[:, 0, 0], expected, rtol=1e-13)


@pytest.mark.parametrize("sparse", [False, True])
def test_matrix_kernel_equals_definition_and_is_symmetric(sparse):
    model = rocking_model(kelvin=True, top_rotational_mass=1.0)
    if sparse:
        model = ul.Model(M=sp.csr_matrix(model.M), K=sp.csr_matrix(model.K), F=model.F, H=model.H,
                         C=sp.csr_matrix(model.C), F_v=model.F_v, H_v=model.H_v)
    got = ul.MatrixKernel(model)(S)
    for sk, Lk in zip(S, got):
        D = model.D(sk)
        D = D.toarray() if sp.issparse(D) else D
        Fs = model.F_of(sk)
        expected = model.H_of(sk) - Fs.T @ np.linalg.solve(D, Fs)
        np.testing.assert_allclose(Lk, expected, rtol=1e-10, atol=1e-6)
        np.testing.assert_allclose(Lk, Lk.T, rtol=1e-10, atol=1e-6)
    # real kernel: Lambda(conj s) = conj Lambda(s)
    np.testing.assert_allclose(ul.MatrixKernel(model)(np.conj(S)), np.conj(got), rtol=1e-12)


def test_transfer_is_FT_Dinv_d():
    model = rocking_model(kelvin=False, top_rotational_mass=1.0)
    rng = np.random.default_rng(0)
    d = rng.standard_normal((S.size, model.n)) + 1j * rng.standard_normal((S.size, model.n))
    got = ul.MatrixKernel(model).transfer(S, d)
    for k, sk in enumerate(S):
        np.testing.assert_allclose(got[k], model.F.T @ np.linalg.solve(model.D(sk), d[k]), rtol=1e-10)
    with pytest.raises(ValueError, match=r"d must have shape \(5, 5\)"):
        ul.MatrixKernel(model).transfer(S, d[:, :2])


def test_callable_kernel_checks_its_output():
    kern = ul.CallableKernel(lambda s: np.eye(3) * s, m=2)
    with pytest.raises(ValueError, match=r"Lambda\(s\) must return shape \(2, 2\)"):
        kern(np.array([1.0 + 1j]))
    with pytest.raises(TypeError, match="Lambda must be callable"):
        ul.CallableKernel(np.eye(2), m=2)
