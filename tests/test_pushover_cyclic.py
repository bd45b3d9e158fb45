"""Pushover with P-Delta in its two forms (closed forms of the sway mechanism's slope) and cyclic
pushover (closed-form hysteresis of a bilinear SDOF, the portal's sway mechanism under cycles)."""

import numpy as np
import pytest
from pushover_frames import A, E, I_COL, MP_BEAM, MP_COL, H, L, portal, rocking_block, sdof

from unilateral.pushover import pushover

W = 2 * 10.0 * 9.81                     # the weight on the columns (10 t at each top node)
COLLAPSE = 2 * (MP_COL + MP_BEAM) / H   # the sway mechanism, 120 kN


def _mechanism(r, st):
    """``(slope against the mean roof drift, slope against the control DOF 2.ux, intercept)`` of
    the last segment (the four-hinge mechanism)."""
    i2, i3 = st.dofs.names.index("2.ux"), st.dofs.names.index("3.ux")
    mean = 0.5 * (r.u[:, i2] + r.u[:, i3])
    dlam = np.diff(r.load_factor)[-1]
    slope = dlam / np.diff(mean)[-1]
    return slope, dlam / np.diff(r.displacement)[-1], r.load_factor[-1] - slope * mean[-1]


def _column_slope(N, EI, h):
    """Tangent lateral stiffness of one column in the sway mechanism under the consistent geometric
    stiffness of its axial force ``N`` (tension positive): base moment fixed at Mp (hinge), top
    moment balancing the fixed beam-end moment and the matrix's rotational terms. With
    ``beta = N h^2 / (90 EI)`` the joint turns by ``(1 + 3 beta) / (1 + 4 beta)`` per unit chord
    rotation, and the column's shear changes by ``N (33 + that) / (30 h)`` per unit sway."""
    beta = N * h * h / (90.0 * EI)
    return N * (33.0 + (1.0 + 3.0 * beta) / (1.0 + 4.0 * beta)) / (30.0 * h)


def _against_control(s):
    """The slope against ``2.ux`` when each column softens by ``s`` per unit of its own sway: the beam
    (``k_b = E A / L``) shortens by the second column's shear, ``du3 = k_b / (k_b + s)``."""
    kb = E * A / L
    return s + kb * s / (kb + s)


def test_string_p_delta_softens_the_sway_mechanism_by_W_over_h():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81, p_delta="string")
    assert r.success and [e.kind for e in r.events] == ["yield"] * 4
    slope, at_control, intercept = _mechanism(r, st)
    assert slope == pytest.approx(-W / H, rel=1e-9)                 # found: 1e-12
    assert intercept == pytest.approx(COLLAPSE, rel=1e-9)           # lambda = 120 - W d / h
    assert at_control == pytest.approx(_against_control(-W / 2 / H), rel=1e-9)
    assert r.stats["max_residual"] < 1e-10 and r.stats["max_lcp_error"] < 1e-10


def test_consistent_p_delta_closed_form_of_the_mechanism_slope():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81, p_delta="consistent")
    slope, at_control, _ = _mechanism(r, st)
    s = _column_slope(-W / 2, E * I_COL, H)
    assert slope == pytest.approx(2 * s, rel=1e-9)                  # found: 9e-13
    assert at_control == pytest.approx(_against_control(s), rel=1e-9)
    assert slope / (-W / H) == pytest.approx(34 / 30, rel=2e-5)     # the nodal cubic: 34/30 of the string
    built = portal(p_delta=True)                                    # Frame2D.p_delta is the same form
    b = pushover(built, built.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81)
    assert b.load_factor == pytest.approx(r.load_factor, rel=1e-12)
    off = pushover(built, built.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81, p_delta=False)
    assert off.load_factor[-1] == pytest.approx(COLLAPSE, rel=1e-9)


@pytest.mark.parametrize("kwargs, words", [
    (dict(p_delta="exact", gravity=9.81), ["p_delta='exact'", "'consistent'", "'string'"]),
    (dict(p_delta="string"), ["p_delta='string'", "gravity"]),
    (dict(target=[0.1, 0.1]), ["target[1]=0.1", "repeats"]),
    (dict(target=[]), ["target=[]", "nonempty"]),
    (dict(target=[0.1, "x"]), ["target[1]='x'", "finite number"]),
    (dict(target=[-0.1, 0.1]), ["target=-0.1", "wrong sign"]),
])
def test_bad_p_delta_and_history(kwargs, words):
    st = portal()
    args = dict(node=2, dof="ux", target=0.1) | kwargs
    with pytest.raises(ValueError) as info:
        pushover(st, st.nodal_load(2, ux=1.0), **args)
    for word in words:
        assert word in str(info.value), (word, str(info.value))
    with pytest.raises(ValueError, match="p_delta='string' needs the beams' axial forces"):
        pushover(sdof().to_model(), [1.0], node=0, target=0.1, gravity=[-1.0], p_delta="string")


def _bilinear_kinematic(d, k, Fy, hardening):
    """Closed-form force of a bilinear SDOF with kinematic hardening along the displacements ``d``
    (from rest): the elastic trial bounded by the lines ``+-Fy + k2 (d -+ dy)``, ``k2 = k h / (1 + h)``
    (exact for any increments in 1-D)."""
    k2, dy = k * hardening / (1 + hardening), Fy / k
    force, out = 0.0, [0.0]
    for d0, d1 in zip(d[:-1], d[1:]):
        force = min(max(force + k * (d1 - d0), -Fy + k2 * (d1 + dy)), Fy + k2 * (d1 - dy))
        out.append(force)
    return np.array(out)


@pytest.mark.parametrize("hardening", [0.0, 0.1])
def test_cyclic_sdof_follows_the_closed_form_hysteresis(hardening):
    k, Fy = 100.0, 5.0
    st = sdof(k=k, Fy=Fy, hardening=hardening)
    history = [0.1, -0.1, 0.2, -0.15, 0.0]
    r = pushover(st, st.nodal_load(1, ux=1.0), node=1, dof="ux", target=history)
    assert r.success, r.message
    assert r.displacement[[0] + [i for i in range(len(r.parameter)) if r.parameter[i] in _ends(history)]] \
        == pytest.approx([0.0, *history], abs=1e-15)
    t = np.union1d(np.linspace(0.0, r.parameter[-1], 401), _ends(history))   # the reversals among them
    s = r.at(t)                                         # points between the events: linear, exact
    assert s["load_factor"] == pytest.approx(_bilinear_kinematic(s["displacement"], k, Fy, hardening), abs=1e-12)
    kinds = [(e.kind, e.name) for e in r.events]
    assert kinds[:4] == [("yield", "y.plastic+"), ("unload", "y.plastic+"), ("yield", "y.plastic-"),
                         ("unload", "y.plastic-")]
    assert np.all(np.diff(r.parameter) >= 0) and r.stats["max_lcp_error"] < 1e-12


def _ends(history):
    """The cumulative path parameters at the targets of ``history`` (from 0)."""
    return list(np.cumsum(np.abs(np.diff([0.0, *history]))))


def test_cyclic_sdof_under_load_control_reverses_the_load():
    st = sdof(hardening=0.1)
    r = pushover(st, st.nodal_load(1, ux=1.0), node=1, dof="ux", target=[6.0, -6.0, 0.0], control="load")
    assert r.success, r.message
    k2 = 100 / 11
    d1 = 0.05 + 1.0 / k2                                # hardening beyond Fy = 5 up to 6
    d2 = d1 - 10.0 / 100 - 2.0 / k2                     # elastic range 2 Fy, then 2 more on the other line
    assert r.displacement[-2] == pytest.approx(d2, rel=1e-12)
    assert r.displacement[-1] == pytest.approx(d2 + 6.0 / 100, rel=1e-12)
    assert r.load_factor[-1] == 0.0


def test_portal_sway_mechanism_under_cycles():
    st = portal()
    first = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.05)
    k0 = first.load_factor[1] / first.displacement[1]            # the elastic frame
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=[0.05, -0.05, 0.05])
    assert r.success, r.message
    lam, d = r.load_factor, r.displacement
    assert lam.max() == pytest.approx(COLLAPSE, rel=1e-9) and lam.min() == pytest.approx(-COLLAPSE, rel=1e-9)
    back = np.flatnonzero(np.isclose(d, 0.05, rtol=1e-12))[0]    # the first reversal
    unload = [e for e in r.events if e.kind == "unload"]
    assert [e.displacement for e in unload] == pytest.approx([0.05] * 4 + [-0.05] * 4, rel=1e-12)
    assert (lam[back + 1] - lam[back]) / (d[back + 1] - d[back]) == pytest.approx(k0, rel=1e-9)
    # every hinge is at +-Mp on the plateau and unloads elastically: the first hinge to form, at
    # P1 = min Mp / |m1| (m1 the elastic moment per unit load), reverses after a drop of 2 P1
    P1, name = first.events[0].load_factor, first.events[0].name
    reverse = [e for e in r.events if e.kind == "yield" and e.load_factor < 0]
    assert len(reverse) == 4 and reverse[0].load_factor == pytest.approx(COLLAPSE - 2 * P1, rel=1e-9)
    assert reverse[0].name == name.replace("-", "+")
    again = [e for e in r.events if e.kind == "yield" and e.displacement < 0 and e.load_factor > 0]
    assert len(again) == 4 and again[0].load_factor == pytest.approx(2 * P1 - COLLAPSE, rel=1e-9)
    assert r.stats["max_residual"] < 1e-10 and r.stats["max_lcp_error"] < 1e-10


def test_load_control_with_p_delta_stops_at_the_peak():
    st = portal()
    args = dict(node=2, dof="ux", gravity=9.81, p_delta="string")
    peak = pushover(st, st.nodal_load(2, ux=1.0), target=0.1, **args).load_factor.max()
    r = pushover(st, st.nodal_load(2, ux=1.0), target=200.0, control="load", **args)
    assert not r.success and r.stats["mechanism"]
    assert r.load_factor[-1] == pytest.approx(peak, rel=1e-12) and peak < COLLAPSE
    assert f"mechanism at load factor {peak:.10g}" in r.message and "softening branch" in r.message


def test_a_rocking_block_under_cycles_lifts_and_lands_on_either_side():
    b, height, mass, g = 1.0, 2.0, 50.0, 9.81
    st = rocking_block(b=b, height=height, mass=mass)
    r = pushover(st, st.nodal_load("t", ux=1.0), node="t", dof="ux", target=[0.05, -0.05, 0.02], gravity=g)
    assert r.success, r.message
    assert [(e.kind, e.name) for e in r.events] == [("uplift", "sl"), ("contact", "sl"), ("uplift", "sr"),
                                                     ("contact", "sr"), ("uplift", "sl")]
    rocking = mass * g * b / height                                  # P h = W b on either edge
    assert [e.load_factor for e in r.events] == pytest.approx([rocking, rocking, -rocking, -rocking, rocking],
                                                              rel=1e-12)
    d = r.events[0].displacement
    assert [e.displacement for e in r.events] == pytest.approx([d, d, -d, -d, d], rel=1e-12)
    assert [e.point for e in r.events] == [1, 3, 4, 6, 7]
    assert r.table().count("uplift") == 3 and r.table().count("contact") == 2     # each at its own point
    assert r.stats["max_lcp_error"] < 1e-12
