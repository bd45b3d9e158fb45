"""Large sparse models: the full-space active-set LCP of method="direct"."""

import numpy as np
import pytest

import unilateral as ul
from unilateral.structure import winkler_beam


@pytest.mark.parametrize("load", ["impact", "moving"])
def test_full_space_lcp_equals_condensed_lcp(load):
    st, q, _ = winkler_beam(80, load=load)
    model = st.to_model()
    assert model.sparse and model.m == 81
    full = ul.solve(model, q, dt=2e-3, t_end=0.6, method="direct")
    condensed = ul.solve(model, q, dt=2e-3, t_end=0.6, method="direct", lcp="lemke")
    assert full.stats["lcp_space"] == "full" and condensed.stats["lcp_space"] == "condensed"
    assert full.success and condensed.success
    assert full.stats["contact_changes"] == condensed.stats["contact_changes"] > 20
    scale = np.max(np.abs(condensed.v))
    np.testing.assert_allclose(full.v, condensed.v, rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(full.psi, condensed.psi, rtol=0, atol=1e-9 * np.max(np.abs(condensed.psi)))
    np.testing.assert_allclose(full.u, condensed.u, rtol=0, atol=1e-9 * np.max(np.abs(condensed.u)))
    # factorisations are reused across steps with the same contact set
    assert full.stats["factorizations"] < full.stats["steps"]
    assert np.all(full.v >= 0) and np.all(full.psi <= 1e-9 * np.max(np.abs(full.psi)))


def test_winkler_beam_lifts_off_and_lands():
    st, q, info = winkler_beam(60, load="impact")
    sol = ul.solve(st.to_model(), q, dt=1e-3, t_end=0.5, method="direct")
    lifted = (sol.v > 0).sum(axis=1)
    assert lifted[0] == 0 and lifted.max() >= 3       # in full contact under gravity, then uplift
    assert st.node_displacement(sol, info["node"], "uy").min() < sol.u[0].min()
