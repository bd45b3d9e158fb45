"""Compiled stepping of large sparse models: envelope Cholesky and the full-space LCP in machine code.

The compiled engine performs the operations of the Python full-space march
(:mod:`unilateral.march.active_set`), which equals the condensed LCP; here both are checked against
it for every rule, with Kelvin dashpots, with gaps whose constraints span two DOFs, and the static
state solved in the full space against the condensed static LCP. The memory test checks that no
dense n x m (or n x n) array is formed.
"""

import tracemalloc

import numpy as np
import pytest
import scipy.sparse as sp

import unilateral as ul
from unilateral.march import envelope
from unilateral.methods import Direct
from unilateral.structure import Frame2D, winkler_beam


def _solve(model, q, engine, **kw):
    kw = {"dt": 2e-3, "t_end": 0.4, "rule": "trapezoidal", **kw}
    return ul.solve(model, q, method=Direct(engine=engine), **kw)


def _every(model, step):
    """The model with only every ``step``-th contact (a sparse model with n >> m, sparse F)."""
    keep = np.arange(0, model.m, step)
    return ul.Model(M=model.M, K=model.K, F=sp.csc_matrix(model.F)[:, keep], H=model.H[np.ix_(keep, keep)], C=model.C,
                    g=model.g(0.0)[keep])


def _close(a, b, rtol):
    np.testing.assert_allclose(a, b, rtol=0, atol=rtol * max(1.0, np.max(np.abs(b))))


# ---------------------------------------------------------------------- the factorisation
def test_envelope_cholesky_solves_and_refactorises_from_a_row():
    rng = np.random.default_rng(4)
    n = 120
    B = sp.random(n, n, density=0.03, random_state=5) + sp.eye(n)
    A = (B @ B.T + n * sp.eye(n)).tocsr()
    env = envelope.Envelope(A)
    base = env.values(A)
    L = np.zeros_like(base)
    assert envelope.cholesky_rows(env.ptr, env.first, base, L, 0) == -1
    b = rng.standard_normal(n)
    x = np.empty(n)
    envelope.solve(env.ptr, env.first, L, b[env.perm], x)
    u = np.empty(n)
    u[env.perm] = x
    np.testing.assert_allclose(A @ u, b, rtol=0, atol=1e-12 * np.abs(b).max() * n)
    # change the rows from r0 on (a diagonal entry), factorise only them: the full factor
    r0 = 70
    changed = base.copy()
    changed[env.position(np.array([r0]), np.array([r0]))] += 3.0
    partial, full = L.copy(), np.zeros_like(L)
    envelope.cholesky_rows(env.ptr, env.first, changed, partial, r0)
    envelope.cholesky_rows(env.ptr, env.first, changed, full, 0)
    np.testing.assert_allclose(partial, full, rtol=1e-14, atol=0)
    # an indefinite matrix is reported at its first bad pivot
    bad = base.copy()
    bad[env.position(np.array([r0]), np.array([r0]))] = -1.0
    assert envelope.cholesky_rows(env.ptr, env.first, bad, np.zeros_like(L), 0) == r0


def test_envelope_keeps_a_beam_banded():
    st, _, _ = winkler_beam(200)
    model = st.to_model()
    env = envelope.Envelope(abs(model.K) + abs(model.M))
    assert env.size <= 4 * model.n          # three nodal DOFs: at most 3 entries below the diagonal


# ---------------------------------------------------------------------- the march
@pytest.mark.parametrize("rule", ["bdf1", "bdf2", "trapezoidal", "hht"])
def test_compiled_full_space_equals_python(rule):
    st, q, _ = winkler_beam(80, load="moving")
    model = st.to_model()
    python = _solve(model, q, "python", rule=rule)
    compiled = _solve(model, q, "compiled", rule=rule)
    assert compiled.stats["engine"] == "compiled" and python.stats["engine"] == "python"
    assert compiled.stats["lcp_space"] == python.stats["lcp_space"] == "full"
    assert compiled.success and python.success
    assert compiled.stats["contact_changes"] == python.stats["contact_changes"] > 10
    _close(compiled.u, python.u, 1e-10)
    _close(compiled.v, python.v, 1e-10)
    _close(compiled.psi, python.psi, 1e-10)
    _close(compiled.udot, python.udot, 1e-9)
    # factorised again only where the contact set changed, and then only from its rows on
    assert compiled.stats["factorizations"] <= compiled.stats["lcp_iterations"]


def test_compiled_full_space_with_kelvin_dashpots_equals_condensed_lcp():
    st, q, _ = winkler_beam(70, load="moving", c_soil=20.0, P=2000.0)
    model = st.to_model()
    assert model.viscous
    compiled = _solve(model, q, "compiled")
    condensed = _solve(model, q, "python", lcp="lemke")
    assert condensed.stats["lcp_space"] == "condensed" and compiled.stats["lcp_space"] == "full"
    assert compiled.stats["contact_changes"] == condensed.stats["contact_changes"] > 5
    _close(compiled.u, condensed.u, 1e-9)
    _close(compiled.v, condensed.v, 1e-9)
    _close(compiled.psi, condensed.psi, 1e-9)


def _two_beams_that_pound(n_el=40, gaps=70):
    """Two parallel cantilever beams 0.01 m apart, a gap link between them at ``gaps`` points."""
    fr = Frame2D()
    L = 10.0
    for k in range(n_el + 1):
        fr.node(f"a{k}", 0.0, L * k / n_el)
        fr.node(f"b{k}", 0.5, L * k / n_el)
    for s in "ab":
        fr.support(f"{s}0", ux=True, uy=True, rz=True)
        for k in range(n_el):
            fr.beam(f"{s}-{k}", f"{s}{k}", f"{s}{k + 1}", E=1.0, A=1e7, I=1e4 if s == "a" else 3e4)
        for k in range(1, n_el + 1):
            fr.mass(f"{s}{k}", 0.2)
    for g, k in enumerate(np.linspace(1, n_el, gaps).round().astype(int)):
        fr.gap(f"g{g}", f"a{k}", f"b{k}", 1e5, gap=0.01 + 1e-4 * g, direction="ux")
    fr.rayleigh(a0=0.3)
    st = fr.build()
    top = st.nodal_load(f"a{n_el}", ux=1.0)
    q = lambda t: 400.0 * np.sin(2 * np.pi * 2.0 * t) * top
    return st, q


def test_compiled_full_space_with_gaps_between_two_dofs():
    st, q = _two_beams_that_pound()
    model = st.to_model()
    assert model.m > 64 and model.sparse
    assert max(np.diff(sp.csc_matrix(model.F).indptr)) == 2     # each gap spans two DOFs
    # (up to 0.75 s: later, hundreds of poundings amplify round-off; at 1 s the condensed LCP
    # differs from the Python full space by 2e-9 of the peak, as the compiled one does)
    compiled = _solve(model, q, "compiled", t_end=0.75)
    python = _solve(model, q, "python", t_end=0.75)
    assert compiled.success and compiled.stats["contact_changes"] == python.stats["contact_changes"] > 10
    _close(compiled.u, python.u, 1e-9)
    # psi is k times a difference of displacements of metres: u's round-off times k = 1e5
    np.testing.assert_allclose(compiled.psi, python.psi, rtol=0, atol=1e-9 * 1e5 * np.max(np.abs(python.u)))


def test_medium_sparse_model_with_few_contacts_is_compiled():
    """n > COMPILED_MAX_N with m <= 64: stepped in the full space in compiled code by default."""
    st, q, _ = winkler_beam(150, load="impact")
    sub = _every(st.to_model(), 5)                           # 31 of the 151 contacts
    assert sub.n > 400 and sub.m <= 64
    auto = ul.solve(sub, q, dt=2e-3, t_end=0.3, method="direct", rule="bdf2")
    python = ul.solve(sub, q, dt=2e-3, t_end=0.3, method=Direct(engine="python"), rule="bdf2")
    assert auto.stats["engine"] == "compiled" and auto.stats["lcp_space"] == "full"
    assert python.stats["lcp_space"] == "condensed"
    assert auto.stats["contact_changes"] == python.stats["contact_changes"] > 0
    _close(auto.u, python.u, 1e-9)
    _close(auto.v, python.v, 1e-9)


def test_static_state_in_the_full_space_equals_the_condensed_one():
    st, _, _ = winkler_beam(90)
    model = st.to_model()
    from unilateral.initial import _static_full_space, static_state
    from unilateral.lcp import get_lcp_solver

    q0 = st.gravity(9.81) + 300.0 * st.nodal_load(30, uy=1.0) + 200.0 * st.nodal_load(80, rz=1.0)
    full = _static_full_space(model, q0, get_lcp_solver("bpp"))
    condensed = static_state(model, q0, get_lcp_solver("lemke"))
    assert full is not None and np.count_nonzero(full.v) > 0      # some springs open
    _close(full.u, condensed.u, 1e-10)
    _close(full.v, condensed.v, 1e-10)
    _close(full.psi, condensed.psi, 1e-10)


def test_large_sparse_model_forms_no_dense_n_by_m_array():
    st, q, _ = winkler_beam(1500, load="moving")
    build = lambda: _every(st.to_model(), 3)
    model = build()
    n, m = model.n, model.m                                     # n = 4502, m = 501
    Q = np.array([q(k * 1e-3) for k in range(6)])
    _solve(model, Q, "compiled", dt=1e-3, t_end=5e-3)          # compile and load the code first
    model = build()                                             # a fresh model: nothing remembered
    tracemalloc.start()
    sol = _solve(model, Q, "compiled", dt=1e-3, t_end=5e-3)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert sol.success and sol.stats["engine"] == "compiled" and sol.stats["lcp_space"] == "full"
    # what the solve allocates: O(n) vectors (histories, sparse operands, factors), O(m^2) for H
    assert peak < 0.5 * n * m * 8, f"peak {peak / 2**20:.2f} MiB against {n * m * 8 / 2**20:.2f} MiB for n x m"


def test_rigid_contacts_take_the_condensed_lcp():
    """``H = 0`` (rigid contacts): the full space would invert ``H_AA``; the condensed LCP is used."""
    st, q, _ = winkler_beam(80, load="moving")
    base = st.to_model()
    model = ul.Model(M=base.M, K=base.K, F=sp.csc_matrix(base.F), H=np.zeros((base.m, base.m)), C=base.C,
                     g=np.full(base.m, -1e-3))
    assert model.m > 64 and model.sparse
    sol = ul.solve(model, q, dt=2e-3, t_end=0.02, method="direct")
    assert sol.success and sol.stats["lcp_space"] == "condensed"
    assert np.all(np.isfinite(sol.u)) and np.all(sol.v >= 0)
    from unilateral.initial import _static_full_space
    from unilateral.lcp import get_lcp_solver

    assert _static_full_space(model, st.gravity(9.81), get_lcp_solver("bpp")) is None
