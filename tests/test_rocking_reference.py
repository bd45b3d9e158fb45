"""The rocking block's reference (``unilateral.analysis.rocking_reference``: Housner's equation by
``solve_ivp``) against the closed forms, and ``method="moreau-jean"`` against the reference.

Measured (the block of ``examples/overturning_map.py``, 0.5 x 2.5 m, ``rule="trapezoidal"``, the
lift-off and the end of the pulse on the grid, ``dt = T / n``): the rotation history and the impact
times of the linearised block equal the linearised reference's with errors ``C dt^2``, fitted order
2.0 (n = 64 ... 1024; ``C = 0.96-0.99`` rad/s^2 and 2.7 s^-1 under ``a_p = sqrt(2) g tan(alpha)``,
``omega_p = 4 p``, 0.64-0.72 and 1.9-2.1 under Zhang & Makris' pulse ``a_p = 2 g tan(alpha)``,
``omega_p = 6 p``). The tests take n = 64, 128, 256. A lift-off inside a step costs the same order with a constant that depends on
where it falls (no clean fit).
"""

from __future__ import annotations

import math
import runpy
from pathlib import Path

import numpy as np
import pytest

import unilateral as ul
from unilateral.analysis.rigid import block_results, one_sine_pulse, rocking_onset_phase
from unilateral.analysis.rocking_reference import ReferenceBlock, one_sine_class, rocking_response
from unilateral.loads import LoadHistory
from unilateral.structure import Frame2D, rigid

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def _block():
    fr = Frame2D()
    fr.node("c", 0.0, 1.25)
    block = fr.rigid_block("B", "c", width=0.5, height=2.5, mass=1.0)
    st = fr.build()
    return st, st.to_model(), block, ReferenceBlock(block.b, block.h, block.g, i0=block.I0 / block.mass)


def test_the_reference_block_is_the_rigid_block_of_the_frame():
    _, _, block, ref = _block()
    assert ref.p_linear == pytest.approx(block.p, rel=1e-15)
    assert ref.p == pytest.approx(math.sqrt(3 * block.g / (4 * ref.R)), rel=1e-15)
    assert ref.restitution == pytest.approx(block.restitution, rel=1e-15)
    assert ref.restitution == pytest.approx(1 - 1.5 * math.sin(ref.alpha) ** 2, rel=1e-14)
    assert ref.uplift_acceleration == pytest.approx(block.uplift_acceleration, rel=1e-15)


@pytest.mark.parametrize("psi", [False, True])
def test_linearised_reference_equals_the_closed_form_of_the_first_rocking_phase(psi):
    """Under a_p sin(omega_p t + psi) from the lift-off t_s to the first impact or the end of the
    pulse: theta = a - C sin(w t + psi) + A cosh(q tau) + B sinh(q tau), tau = t - t_s,
    C = q^2 a_p / (g (q^2 + w^2)), from rest (q = p sqrt(cos alpha), a = tan alpha; derived here,
    the kind of solution Dimitrakopoulos & DeJong 2012 build their spectra on, not checked against
    their text)."""
    _, _, _, ref = _block()
    q, a = ref.p_linear, math.tan(ref.alpha)
    for amplitude, frequency in [(1.5, 1.0), (3.0, 4.0), (6.0, 2.0)]:
        wp, a_p = frequency * q, amplitude * ref.uplift_acceleration
        phase = rocking_onset_phase(a_p, ref.uplift_acceleration) if psi else 0.0
        end = 2 * math.pi / wp
        res = rocking_response(ref, one_sine_pulse(a_p, wp, psi=phase), end + 1.0, linear=True, pulse_end=end)
        ts = res.start
        assert ts == pytest.approx(0.0 if psi else math.asin(1 / amplitude) / wp, abs=1e-12)
        t1 = min([end] + [t for t in (res.overturn_time,) if t] + list(res.impact_times))
        t = np.linspace(ts, t1, 400)
        C = q ** 2 * a_p / (ref.g * (q ** 2 + wp ** 2))
        A, B = -(a - C * math.sin(wp * ts + phase)), C * wp * math.cos(wp * ts + phase) / q
        exact = a - C * np.sin(wp * t + phase) + A * np.cosh(q * (t - ts)) + B * np.sinh(q * (t - ts))
        np.testing.assert_allclose(res.state(t)[0], exact, rtol=0, atol=1e-10)


def test_free_rocking_impacts_equal_housners_sequence():
    """Released from rest at theta0: the impact times of the linearised reference are
    RigidBlock.impact_times (the closed form), each impact r times the velocity; the nonlinear
    reference conserves Housner's energy between impacts."""
    _, _, block, ref = _block()
    theta0 = 0.1
    lin = rocking_response(ref, lambda t: 0.0, 8.0, linear=True, theta0=theta0, settle=False)
    exact = block.impact_times(theta0, 6)
    np.testing.assert_allclose(lin.impact_times[:6], exact, rtol=0, atol=1e-9)
    for _, before, after in lin.impacts:
        assert after == pytest.approx(ref.restitution * before, rel=1e-15)
    non = rocking_response(ref, lambda t: 0.0, 4.0, theta0=theta0, settle=False)
    t = np.linspace(0.0, non.impact_times[0] * 0.999, 200)
    theta, omega = non.state(t)
    energy = 0.5 * omega ** 2 + ref.p ** 2 * np.cos(ref.alpha - theta)
    np.testing.assert_allclose(energy, ref.p ** 2 * math.cos(ref.alpha - theta0), rtol=1e-10)
    # the nonlinear block takes longer to its first impact (the exact restoring moment is smaller)
    assert non.impact_times[0] > lin.impact_times[0]


@pytest.mark.parametrize("factor, lifts", [(0.98, False), (1.05, True)])
def test_the_reference_lifts_only_above_g_tan_alpha(factor, lifts):
    _, _, _, ref = _block()
    for linear in (True, False):
        res = one_sine_class(ref, factor, 4.0, linear=linear)
        assert (res.start is not None) is lifts and res.mode == ("rocks" if lifts else "rest")


def test_zhang_makris_pulse_lifts_at_zero_and_brings_the_ground_velocity_back():
    a_p, wp, uplift = 3.0, 5.0, 1.2
    psi = rocking_onset_phase(a_p, uplift)
    pulse = one_sine_pulse(a_p, wp, psi=psi)
    assert pulse(0.0) == pytest.approx(uplift, rel=1e-15) and pulse(2 * math.pi / wp + 1e-9) == 0.0
    t = np.linspace(0.0, 2 * math.pi / wp, 20001)
    velocity = np.trapezoid([pulse(x) for x in t], t)
    assert abs(velocity) < 1e-8
    with pytest.raises(ValueError, match="at least the uplift acceleration"):
        rocking_onset_phase(1.0, uplift)


def _moreau_jean_errors(amplitude, frequency, psi, steps):
    st, model, block, ref = _block()
    wp, a_p = frequency * block.p, amplitude * block.uplift_acceleration
    phase = rocking_onset_phase(a_p, block.uplift_acceleration) if psi else 0.0
    a_g, T = one_sine_pulse(a_p, wp, psi=phase), 2 * math.pi / wp
    res = rocking_response(ref, a_g, 3 * T, linear=True, pulse_end=T, settle=False)
    errors = []
    for n in steps:
        load = LoadHistory(st.gravity(block.g), [rigid.ground_motion(st, a_g)])
        sol = ul.solve(model, load, dt=T / n, t_end=3 * T, method="moreau-jean", rule="trapezoidal")
        out = block_results(st, sol, "B")
        times = np.array([i["time"] for i in out["impacts"]])
        assert len(times) == len(res.impacts) == 2
        errors.append((np.max(np.abs(out["rotation"] - res.state(sol.t)[0])), np.max(np.abs(times - res.impact_times))))
    return T, np.array(errors)


@pytest.mark.parametrize("amplitude, frequency, psi, C_theta, C_time",
                         [(math.sqrt(2), 4.0, False, 1.2, 3.2), (2.0, 6.0, True, 0.8, 2.3)])
def test_moreau_jean_converges_to_the_linearised_reference_at_second_order(amplitude, frequency, psi, C_theta,
                                                                           C_time):
    """The linearised block rocking under a one-sine pulse (two impacts in 3 T): its rotation and
    impact times tend to the reference's as dt^2 (sqrt(2): the lift-off at T / 8, on the grid)."""
    steps = np.array([64, 128, 256])
    T, errors = _moreau_jean_errors(amplitude, frequency, psi, steps)
    dt = T / steps
    for k, C in enumerate((C_theta, C_time)):
        assert np.all(errors[:, k] < C * dt ** 2), (errors[:, k] / dt ** 2)
        order = np.polyfit(np.log(dt), np.log(errors[:, k]), 1)[0]
        assert 1.85 < order < 2.15, order


def test_the_reference_map_has_a_safe_region_between_the_modes_only_when_the_block_is_followed():
    """At omega_p / p = 6, a_p / (g tan alpha) = 8.5, 9, 10: mode 1, no overturning, mode 2 when the
    overturn is decided once the pulse is over (criterion "free"), for the linearised and the
    nonlinear block, with either pulse; with the first passing of the equilibrium (criterion
    "tilt") the block 'overturns' without impact at 9 and the safe region is gone."""
    _, _, _, ref = _block()
    for linear in (True, False):
        for psi in (False, True):
            modes = [one_sine_class(ref, a, 6.0, linear=linear, psi=psi, criterion="free").mode for a in (8.5, 9.0, 10)]
            assert modes == ["mode 1", "rocks", "mode 2"], (linear, psi, modes)
            assert one_sine_class(ref, 9.0, 6.0, linear=linear, psi=psi, criterion="tilt").mode == "mode 2"


def test_the_example_classifies_as_the_reference():
    """examples/overturning_map.py's classify (moreau-jean, dt = 2e-3) and the linearised reference
    agree on points of each class, the safe region included (omega_p / p = 5, a_p = 7)."""
    module = runpy.run_path(str(EXAMPLES / "overturning_map.py"))
    st, model, block = module["build"]()
    ref = ReferenceBlock(block.b, block.h, block.g, i0=block.I0 / block.mass)
    points = {(5.0, 6.5): "mode 1", (5.0, 7.0): "rocks", (5.0, 7.5): "mode 2", (4.0, 1.5): "rocks",
              (2.0, 8.0): "mode 2", (3.0, 0.9): "rest"}
    for (frequency, amplitude), expected in points.items():
        got = module["classify"](st, model, block, frequency, amplitude)
        assert got == one_sine_class(ref, amplitude, frequency, linear=True, criterion="free").mode == expected
    assert module["classify"](st, model, block, 5.0, 7.0, criterion="tilt") == "mode 2"
