"""P-Delta of a column on a footing on the elastic half-space, and the pushover of footings on a
soil medium (on the soil's static springs ``Phi(0)^-1``, the patches' openings as the unknowns).

A stiff column of height ``H`` carrying ``W`` on a rigid footing rocks on the soil's rotational
stiffness ``K_r``: under a lateral force ``F`` at its top the drift without P-Delta is ``d0 = F H^2
/ K_r`` and with P-Delta ``d0 / (1 - W H / K_r)`` (the rigid column: ``K_r theta = F H + W H
theta``), its buckling load ``W_cr = K_r / H``. ``K_r`` is read from the run without P-Delta; the
amplified drift is then a closed form, and a weight above ``W_cr`` is refused. A larger push lifts
the footing's heel: the pushover finds the patches opening one by one, the constraint laws hold
along the path, and it overturns below the rigid block's load."""

import numpy as np
import pytest

from unilateral.pushover import pushover
from unilateral.structure import Frame2D

HALF = {"model": "halfspace", "Vs": 150.0, "nu": 1 / 3, "rho": 2.0}
H, G, F = 8.0, 9.81, 10.0


def tower(W, p_delta=True):
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, H)
    fr.beam("col", "base", "top", E=3e7, A=1.0, I=1e6)           # stiff: its bending ~2e-7 of the rocking
    fr.mass("top", W / G)
    fr.foundation("F", "base", width=4.0, length=4.0, patches=8, soil=HALF, mass=10.0, J=10.0)
    if p_delta:
        fr.p_delta(g=G)
    return fr.build()


def drift(st, force=F, events=False):
    r = pushover(st, st.nodal_load("top", ux=1.0), node="top", dof="ux", target=force, gravity=G, control="load")
    assert r.success, r.message
    return r if events else r.displacement[-1] - r.displacement[0]


def test_the_drift_on_the_half_space_is_amplified_by_one_over_one_minus_W_over_W_cr():
    d0 = drift(tower(2000.0, p_delta=False))
    W_cr = F * H / d0                                              # K_r / H, K_r = F H^2 / d0
    for W in (2000.0, 8000.0, 0.5 * W_cr, 0.9 * W_cr):
        d = drift(tower(W))
        assert abs(d - d0 / (1 - W / W_cr)) <= 1e-6 * d, (W, d, d0 / (1 - W / W_cr))


def test_a_weight_above_the_buckling_load_on_the_half_space_is_refused():
    W_cr = F * H / drift(tower(2000.0, p_delta=False))
    drift(tower(0.98 * W_cr))
    with pytest.raises(ValueError, match="p_delta"):
        tower(1.02 * W_cr).to_model()


def test_a_pushover_lifts_the_footing_patch_by_patch_until_it_overturns():
    st = tower(2000.0)
    r = drift(st, force=400.0, events=True)
    opened = [e.name for e in r.events if e.kind == "uplift"]
    assert len(opened) >= 2 and opened[0].startswith("F.")
    assert r.stats["max_lcp_error"] <= 1e-9
    heel = r.v[:, list(r.constraint_names).index(opened[0])]
    assert heel[-1] > 0 and np.all(np.diff(heel) >= -1e-12)        # the heel opens and keeps opening
    # pushed further by load, it overturns on its toe below the rigid block's W (B/2) / H = 500
    over = pushover(st, st.nodal_load("top", ux=1.0), node="top", dof="ux", target=600.0, gravity=G,
                    control="load")
    assert not over.success and over.stats["mechanism"] and "mechanism" in over.message
    assert 0.8 * 500.0 < over.load_factor[-1] < 500.0


def test_a_squat_frame_on_sliding_footings_slides_at_mu_times_its_weight():
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("top", 0.0, 1.0)
    fr.beam("col", "base", "top", E=3e7, A=1.0, I=1.0)
    fr.mass("top", 200.0)
    fr.foundation("F", "base", width=4.0, length=4.0, patches=4, soil={"model": "winkler-kelvin", "k": 3e4, "kx": 2e4},
                  mass=10.0, J=10.0, horizontal="soil", mu=0.3)
    st = fr.build()
    r = pushover(st, st.nodal_load("top", ux=1.0), node="top", dof="ux", target=0.5, gravity=G)
    assert r.success, r.message
    assert [e.kind for e in r.events] == ["slip"] * 4                  # patch by patch, no uplift
    assert abs(r.load_factor[-1] - 0.3 * 210.0 * G) <= 1e-9 * 210.0 * G   # mu W, the footing's mass included


def test_the_pushover_p_delta_argument_on_footings_is_the_builders():
    """``pushover(p_delta="consistent")`` on a frame on footings takes the gravity's axial forces on
    the soil's static springs, as ``Frame2D.p_delta`` does."""
    built, plain = tower(8000.0), tower(8000.0, p_delta=False)
    r = pushover(plain, plain.nodal_load("top", ux=1.0), node="top", dof="ux", target=F, gravity=G,
                 control="load", p_delta="consistent")
    assert r.success, r.message
    d = r.displacement[-1] - r.displacement[0]
    assert abs(d - drift(built)) <= 1e-9 * d
