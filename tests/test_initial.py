"""Initial states: the static one, and given initial values made consistent or refused."""

from __future__ import annotations

import numpy as np
import pytest

import unilateral as ul
from unilateral.structure import Frame2D

M_, K_, G_ = 2.0, 2000.0, 10.0


def one_mass():
    """The README's mass on a tensionless spring: psi = k (u - v) is the spring force."""
    return ul.Model(M=[[M_]], K=[[K_]], F=[[K_]], H=[[K_]], constraint_names=["spring"])


def gravity(t):
    return np.array([-M_ * G_])


def test_u0_without_v0_gets_the_consistent_opening_and_the_drop_height_is_not_exceeded():
    sol = ul.solve(one_mass(), gravity, dt=1e-4, t_end=1.0, method="direct", initial={"u0": [1.0]})
    assert sol.success
    assert sol.v[0, 0] == pytest.approx(1.0, abs=1e-12) and sol.psi[0, 0] == pytest.approx(0.0, abs=1e-9)
    assert np.all(sol.psi <= 1e-9) and np.all(sol.v >= 0)
    # energy is conserved by the exact motion: the mass never rises above where it was dropped
    assert sol.u[:, 0].max() <= 1.0 + 1e-6


def test_a_given_v0_that_puts_a_constraint_in_tension_is_refused():
    with pytest.raises(ValueError, match=r"puts constraint 'spring' in tension: psi = 2000 > 0 with v0 = 0"):
        ul.solve(one_mass(), gravity, dt=1e-3, t_end=0.1, initial={"u0": [1.0], "v0": [0.0]})


def test_a_given_v0_that_is_open_under_load_is_refused():
    with pytest.raises(ValueError, match=r"has constraint 'spring' open \(v0 = 0.5 > 0\) while it carries"):
        ul.solve(one_mass(), gravity, dt=1e-3, t_end=0.1, initial={"u0": [-0.01], "v0": [0.5]})


def test_rest_on_an_open_gap_starts_with_the_gap_open():
    """A spring with a 5 mm gap: at rest (u = 0) the gap is open by 5 mm, not closed in tension."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=True, uy=False, rz=True)
    fr.mass(1, 1.0)
    fr.soil("soil", 1, k=1e4, gap=0.005)
    fr.spring("hold", 1, k=10.0, direction="uy")
    model = fr.build().to_model()
    sol = ul.solve(model, None, dt=1e-3, t_end=0.01, method="direct", initial="rest")
    assert sol.success and sol.v[0, 0] == pytest.approx(0.005, rel=1e-12)


def test_static_state_of_a_large_model_solves_in_blocks_without_a_dense_n_by_m(monkeypatch):
    """``K^-1 F`` is formed a block of columns at a time (bounded memory): the static state is the same,
    and no solve sees more than the block's columns; a diagonal ``H`` is checked per entry."""
    import unilateral.initial as initial
    from unilateral.linalg import Factorization
    from unilateral.structure.examples import winkler_beam

    structure, load, _ = winkler_beam(60)
    model = structure.to_model()
    q0 = np.asarray(load(0.0), dtype=float)
    from unilateral.lcp import get_lcp_solver

    solver = get_lcp_solver("bpp")
    reference = initial.static_state(model, q0, solver)
    widths = []
    solve = Factorization.solve

    def counting(self, rhs):
        widths.append(1 if np.ndim(rhs) == 1 else np.shape(rhs)[1])
        return solve(self, rhs)

    monkeypatch.setattr(Factorization, "solve", counting)
    monkeypatch.setattr(initial, "SOLVE_BLOCK_ENTRIES", 5 * model.n)
    blocked = initial.static_state(structure.to_model(), q0, solver)     # a new model: not the kept state
    assert max(widths) == 5 < model.m
    assert np.allclose(blocked.u, reference.u, rtol=0, atol=1e-12 * np.abs(reference.u).max())
    assert np.array_equal(blocked.v > 0, reference.v > 0)
