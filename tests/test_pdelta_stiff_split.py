"""P-Delta survives the stiff-coordinate split: a frame with a penalty-stiff beam (the split of
:mod:`unilateral.model.stiff` applies) keeps the geometric stiffness of its gravity load.

The split rebuilds ``K`` from the natural form ``G E G^T``, which has no geometric stiffness: before
``NaturalForm.K_geometric`` carried it, such a frame silently lost its P-Delta effect (the drift of
the frame without P-Delta, 8.6 % off here)."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.model.stiff import StiffCoordinates
from unilateral.structure import Frame2D


def portal(beam_factor, p_delta=True):
    """A portal with a heavy beam of ``beam_factor`` times the columns' E, a pounding gap at the top."""
    fr = Frame2D()
    for node, x, y in ((1, 0, 0), (2, 0, 4), (3, 6, 0), (4, 6, 4), (9, 6.5, 4)):
        fr.node(node, x, y)
    for node in (1, 3, 9):
        fr.support(node)
    fr.beam("c1", 1, 2, E=3e7, A=0.2, I=2e-3)
    fr.beam("c2", 3, 4, E=3e7, A=0.2, I=2e-3)
    fr.beam("b", 2, 4, E=3e7 * beam_factor, A=0.2, I=2e-3)
    fr.mass(2, 400.0)
    fr.mass(4, 400.0)
    fr.gap("g", 4, 9, k=1e5, gap=0.01)
    if p_delta:
        fr.p_delta()
    return fr.build()


def drift(st):
    x, gravity = st.influence("ux"), -9.81 * (st.M @ st.influence("uy"))
    sol = ul.solve(st.to_model(), lambda t: gravity - st.M @ x * (3.0 * np.sin(2 * np.pi * t)), method="direct",
                   dt=5e-3, t_end=2.0)
    assert sol.success, sol.message
    return sol.u[:, st.dofs.index(4, "ux")]


@pytest.mark.parametrize("p_delta", [True, False])
def test_a_penalty_stiff_beam_keeps_the_p_delta_effect(p_delta):
    stiff, soft = portal(1e12, p_delta), portal(1e7, p_delta)
    assert StiffCoordinates.of(stiff.to_model()) is not None, "the split must apply for this test to mean something"
    assert StiffCoordinates.of(soft.to_model()) is None
    a, b = drift(stiff), drift(soft)
    # the beams differ (1e12 against 1e7 times E): the drifts by 8e-8 of the peak, with or without P-Delta
    assert np.abs(a - b).max() <= 1e-6 * np.abs(b).max()


def test_the_p_delta_effect_is_there():
    with_pd, without = drift(portal(1e12, True)), drift(portal(1e12, False))
    assert np.abs(with_pd - without).max() >= 0.05 * np.abs(without).max()
