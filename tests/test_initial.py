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
