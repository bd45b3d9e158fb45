"""The compiled CQ weights of the structure equal the impulse responses of the Python sweeps.

:func:`unilateral.soil.structure_weights.structure_weights` steps all impulses together in compiled
code; the reference is the existing code path of ``FoundationModel.weights``: one
:func:`~unilateral.march.direct.sweep_direct` with a fresh
:class:`~unilateral.march.stepper.StructureStepper` per column of the impulse basis. A defining
property is checked too: the generating function of the weights is ``T^T D(delta(zeta)/dt)^-1 T``.
"""

import numpy as np
import pytest
import scipy.sparse as sp

from unilateral.linalg import dense
from unilateral.march.direct import sweep_direct
from unilateral.march.stepper import StructureStepper
from unilateral.rules import get_rule
from unilateral.soil.flexibility import SoilFlexibility
from unilateral.soil.foundation_model import FoundationModel
from unilateral.soil.structure_weights import structure_weights

RULES = ("bdf1", "bdf2", "trapezoidal")
TOL = 1e-12


def rel(a, b):
    return np.abs(a - b).max() / max(np.abs(b).max(), 1e-300)


def reference(model, rule, dt, N, basis, *, compiled=False):
    """The loop of ``FoundationModel.weights`` (structure part): one sweep per basis column."""
    rule = get_rule(rule, cq=True)
    n, m = model.n, model.m
    free = model.stepping_model()
    zeros_n, zeros_m = np.zeros((N + 2, n)), np.zeros((N + 2, m))
    W = np.empty((N + 1, m, basis.shape[1]))
    for j in range(basis.shape[1]):
        stepper = StructureStepper(free, rule, dt, zeros_n, zeros_m, None, condensed=False)
        impulse = np.zeros((N + 2, m))
        impulse[1] = basis[:, j]
        _, _, _, opening, _ = sweep_direct(stepper, N + 1, np.zeros(m), np.zeros(m), impulse,
                                           compiled=compiled)
        W[:, :, j] = opening[1:]
    return W


def chain_model(n, m, *, singular, damped, sparse, footing=False, massless=False, seed=0):
    """A chain of ``n`` masses and springs on ``m`` contacts (kN, m, s; t).

    ``singular``: no spring to the ground, ``K`` has a rigid translation (a structure resting only
    on the soil). ``footing``: the contacts sit on a rigid footing (DOFs 0, 1: ``uy``, ``rz``), so
    ``T`` has rank 2 and the impulse basis has ``r = 2 < m`` columns; otherwise contact ``j`` acts
    on DOFs ``j`` and ``j + 1``. ``massless``: the last DOF has no mass (as under a foundation).
    """
    rng = np.random.default_rng(seed)
    k = rng.uniform(1e3, 1e4, n)
    main = k + np.r_[k[1:], 0.0]
    if singular:
        main[0] -= k[0]
    K = sp.diags([main, -k[1:], -k[1:]], [0, 1, -1], format="csr")
    masses = rng.uniform(1.0, 3.0, n)
    if massless:
        masses[-1] = 0.0
    M = sp.diags(masses, format="csr")
    C = (2e-3 * K + 0.3 * M).tocsr() if damped else None
    T = np.zeros((n, m))
    if footing:
        T[0, :] = 1.0
        T[1, :] = np.linspace(-5.0, 5.0, m)
    else:
        for j in range(m):
            T[j % n, j] += 1.0
            T[(j + 1) % n, j] += 0.5
    if not sparse:
        M, K = M.toarray(), K.toarray()
        C = None if C is None else C.toarray()
    soil = SoilFlexibility.kelvin(np.full(m, 1e4), 10.0)
    return FoundationModel(M, K, T, soil, C=C)


# ---------------------------------------------------------------------- equality with the sweeps
@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("singular", [True, False], ids=["K-singular", "K-regular"])
@pytest.mark.parametrize("damped", [False, True], ids=["undamped", "damped"])
@pytest.mark.parametrize("n, sparse", [(10, False), (90, True)], ids=["dense", "sparse"])
def test_equal_to_the_sweeps(rule, singular, damped, n, sparse):
    model = chain_model(n, 4, singular=singular, damped=damped, sparse=sparse)
    N, dt = 300, 0.01
    basis = model.impulse_basis()
    assert basis.shape == (4, 4)
    expected = reference(model, rule, dt, N, basis=basis)
    compiled = reference(model, rule, dt, N, basis, compiled=True)
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis)
    assert W.shape == (N + 1, 4, 4)
    # The existing compiled and Python sweeps differ by ``floor`` themselves (the compiled sweep
    # writes the trapezoidal history differently): up to 1.5e-12 here, zero for most cases.
    floor = rel(compiled, expected)
    assert rel(W, expected) <= TOL + floor
    assert rel(W, compiled) <= TOL
    if singular:                                # the rigid drift is there: the weights grow
        assert np.abs(W[-1]).max() > 2 * np.abs(W[0]).max()


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("engine", ["small", "dense", "sparse"])
@pytest.mark.parametrize("sparse", [False, True], ids=["dense-input", "sparse-input"])
def test_every_engine_on_both_inputs(rule, engine, sparse):
    """Each compiled loop on dense or sparse matrices, damped, ``K`` singular, ``n > 64``."""
    model = chain_model(70, 3, singular=True, damped=True, sparse=sparse, seed=3)
    N, dt = 200, 0.005
    basis = model.impulse_basis()
    expected = reference(model, rule, dt, N, basis=basis)
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis, engine=engine)
    assert rel(W, expected) <= TOL


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("sparse", [False, True], ids=["dense", "sparse"])
def test_impulse_basis_of_a_rigid_footing(rule, sparse):
    """``r = 2 < m``: the responses to the basis, and the full weights ``W @ V.T``."""
    n = 8 if not sparse else 80
    model = chain_model(n, 12, singular=True, damped=not sparse, sparse=sparse, footing=True)
    N, dt = 250, 0.01
    basis = model.impulse_basis()
    assert basis.shape == (12, 2)
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis)
    assert W.shape == (N + 1, 12, 2)
    assert rel(W, reference(model, rule, dt, N, basis=basis)) <= TOL
    full = reference(model, rule, dt, N, np.eye(12))
    assert rel(W @ basis.T, full) <= TOL
    assert rel(structure_weights(model.M, model.K, model.C, model.T, rule, dt, N), full) <= TOL


@pytest.mark.parametrize("rule", RULES)
def test_equal_to_compiled_sweeps(rule):
    """The per-column compiled sweep (the default of ``sweep_direct`` up to 400 DOFs)."""
    model = chain_model(12, 5, singular=True, damped=True, sparse=False)
    N, dt = 400, 0.01
    basis = model.impulse_basis()
    expected = reference(model, rule, dt, N, basis, compiled=True)
    assert rel(structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis), expected) <= TOL


@pytest.mark.parametrize("rule", RULES)
def test_replaces_the_loop_of_foundation_model_weights(rule, monkeypatch):
    """How ``FoundationModel.weights`` calls it: its structure part, the soil's weights set to zero."""
    model = chain_model(9, 12, singular=True, damped=True, sparse=False, footing=True)
    N, dt = 150, 0.01
    monkeypatch.setattr(model.soil, "cq_weights", lambda N, dt, rule, **kw: np.zeros((N + 1, 12, 12)))
    expected = model.weights(N, dt, rule)
    basis = model.impulse_basis()
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis)
    if basis.shape[1] < model.m:
        W = W @ basis.T
    assert rel(W, expected) <= TOL


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("n, sparse", [(10, False), (90, True)], ids=["dense", "sparse"])
def test_massless_dof(rule, n, sparse):
    """A massless DOF (``M`` singular) and ``K`` singular: the existing compiled and Python sweeps
    differ by up to 3e-12 between themselves here, the new loops by as much from either."""
    model = chain_model(n, 4, singular=True, damped=True, sparse=sparse, massless=True)
    N, dt = 300, 0.01
    basis = model.impulse_basis()
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis)
    assert rel(W, reference(model, rule, dt, N, basis=basis)) <= 1e-11
    assert rel(W, reference(model, rule, dt, N, basis, compiled=True)) <= 1e-11


def test_tower_on_a_rigid_footing():
    """The half-space example's tower (n = 5, stiffness up to 2e11 kN/m against masses of 40 t,
    massless footing, two rigid modes of ``K``): its weights are determined by the float64 data
    only to about 1e-6 (solves refined in extended precision move them that much), and the two
    existing engines (compiled and Python sweeps) already differ by 3.5e-10 at N = 5000. The
    tolerances here are those of the problem, not of the method."""
    from unilateral.structure.examples import halfspace_tower

    structure, _, _ = halfspace_tower("halfspace", load="pulse", patches=12)
    model = structure.to_model()
    basis = model.impulse_basis()
    assert basis.shape[1] == 2
    N, dt = 2000, 1e-3
    for rule in RULES:
        W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N, basis=basis)
        assert rel(W, reference(model, rule, dt, N, basis=basis)) <= 1e-8, rule
        assert rel(W, reference(model, rule, dt, N, basis, compiled=True)) <= 1e-10, rule


# ---------------------------------------------------------------------- the CQ definition
@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("singular", [True, False], ids=["K-singular", "K-regular"])
@pytest.mark.parametrize("damped", [False, True], ids=["undamped", "damped"])
@pytest.mark.parametrize("sparse", [False, True], ids=["dense", "sparse"])
def test_generating_function(rule, singular, damped, sparse):
    """``sum_j W_j zeta^j = T^T D(delta(zeta)/dt)^-1 T`` on the circle ``|zeta| = 0.9``.

    400 weights: the neglected tail is below ``0.9^400 N ~ 1e-16`` of the sum even where the
    rigid drift makes the weights grow linearly.
    """
    model = chain_model(7 if not sparse else 70, 3, singular=singular, damped=damped, sparse=sparse)
    N, dt, rho = 400, 0.02, 0.9
    r = get_rule(rule, cq=True)
    W = structure_weights(model.M, model.K, model.C, model.T, rule, dt, N)
    M, K, T = dense(model.M), dense(model.K), dense(model.T)
    C = np.zeros_like(M) if model.C is None else dense(model.C)
    for theta in (0.3, 1.1, 2.0, 2.9, -1.7):
        zeta = rho * np.exp(1j * theta)
        s = r.delta(zeta) / dt
        exact = T.T @ np.linalg.solve(K + s * C + s * s * M, T.astype(complex))
        series = np.tensordot(zeta ** np.arange(N + 1), W, axes=1)
        assert rel(series, exact) <= 1e-10, theta


# ---------------------------------------------------------------------- arguments
def test_arguments_are_checked():
    model = chain_model(5, 2, singular=False, damped=False, sparse=False)
    args = (model.M, model.K, model.C, model.T)
    with pytest.raises(ValueError, match="convolution-quadrature"):
        structure_weights(*args, "hht", 0.01, 10)
    with pytest.raises(ValueError, match="dt"):
        structure_weights(*args, "bdf2", 0.0, 10)
    with pytest.raises(ValueError, match="N must be"):
        structure_weights(*args, "bdf2", 0.01, -1)
    with pytest.raises(ValueError, match="basis"):
        structure_weights(*args, "bdf2", 0.01, 10, basis=np.eye(3))
    with pytest.raises(ValueError, match="engine"):
        structure_weights(*args, "bdf2", 0.01, 10, engine="gpu")
    W = structure_weights(*args, "newmark", 0.01, 0)          # Newmark(1/2, 1/4) is the trapezoidal rule
    assert W.shape == (1, 2, 2)
    assert np.allclose(W[0], W[0].T)
