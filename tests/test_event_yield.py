"""The event-driven march with rate-type unknowns: plastic multipliers (Yield) and slips (Friction).

The reference is the closed form of an elastic-perfectly-plastic SDOF under a pulse: elastic
phases are damped harmonic motions, plastic phases have the constant spring force +-Fy
(``m u'' + c u' = P(t) -+ Fy``), and the yield and unloading instants are roots of these
analytic expressions (brentq).
"""

import numpy as np
import pytest
from scipy.optimize import brentq

import unilateral as ul
from unilateral.constraints import Contact, Friction, Yield
from unilateral.loads import HalfSine, LoadHistory, Rectangular
from unilateral.march.event import march_event

MASS, STIFFNESS, YIELD_FORCE = 1.0, 100.0, 5.0
PULSES = {"rectangular": ("rect", 12.0, 0.3), "half-sine": ("sine", 12.0, 0.4)}
T_END = 2.0


# ---------------------------------------------------------------------- the closed form
def linear_piece(m, c, k, F0, A, Om, t0, y0, yd0):
    """``t -> (y, y')`` of ``m y'' + c y' + k y = F0 + A sin(Om t)`` from ``(y0, yd0)`` at ``t0``.

    ``k > 0``: underdamped; ``k = 0``: the plastic phase (free mass, with or without damping).
    """
    if A:
        D = np.array([[k - m * Om ** 2, c * Om], [-c * Om, k - m * Om ** 2]])
        a, b = np.linalg.solve(D, [0.0, A])
    else:
        a = b = 0.0
    if k > 0:
        const = lambda s: (F0 / k + 0 * s, 0 * s)
        sig = c / (2 * m)
        wd = np.sqrt(k / m - sig ** 2)
        basis = lambda s: (np.exp(-sig * s) * np.cos(wd * s), np.exp(-sig * s) * np.sin(wd * s),
                           np.exp(-sig * s) * (-sig * np.cos(wd * s) - wd * np.sin(wd * s)),
                           np.exp(-sig * s) * (-sig * np.sin(wd * s) + wd * np.cos(wd * s)))
    elif c > 0:
        const = lambda s: (F0 / c * s, F0 / c + 0 * s)
        basis = lambda s: (1.0 + 0 * s, np.exp(-c / m * s), 0 * s, -c / m * np.exp(-c / m * s))
    else:
        const = lambda s: (F0 / (2 * m) * s ** 2, F0 / m * s)
        basis = lambda s: (1.0 + 0 * s, s, 0 * s, 1.0 + 0 * s)

    def particular(t):
        y, yd = const(t - t0)
        return (y + a * np.cos(Om * t) + b * np.sin(Om * t),
                yd + Om * (b * np.cos(Om * t) - a * np.sin(Om * t)))

    p1, p2, d1, d2 = basis(0.0)
    yp, ypd = particular(t0)
    C1, C2 = np.linalg.solve([[p1, p2], [d1, d2]], [y0 - yp, yd0 - ypd])

    def y(t):
        p1, p2, d1, d2 = basis(t - t0)
        yp, ypd = particular(t)
        return C1 * p1 + C2 * p2 + yp, C1 * d1 + C2 * d2 + ypd
    return y


def first_crossing(f, ta, tb, zero, samples=4000):
    """The first time in ``(ta, tb]`` where ``f`` crosses from below 0 to above ``zero``, or None."""
    ts = np.linspace(ta, tb, samples + 1)
    hit = np.flatnonzero(f(ts[1:]) > zero)
    if not hit.size:
        return None
    j = hit[0]
    return brentq(f, ts[j], ts[j + 1], xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200)


def epp_exact(pulse, c, *, m=MASS, k=STIFFNESS, Fy=YIELD_FORCE, t_end=T_END):
    """The EPP SDOF from rest under ``pulse`` = ("rect", P0, t_p) or ("sine", A, t_d).

    Returns ``(pieces, events)``: pieces ``(t0, t1, state)`` with ``state(t) -> (u, u', drift)``,
    events ``(t, "yield"/"unload")``.
    """
    kind, amp, tp = pulse
    Om = np.pi / tp if kind == "sine" else 0.0
    t, u, ud, drift, phase = 0.0, 0.0, 0.0, 0.0, 0
    pieces, events = [], []
    while t < t_end:
        on = t < tp
        t1 = tp if on else t_end
        F0, A = ((amp, 0.0) if kind == "rect" else (0.0, amp)) if on else (0.0, 0.0)
        if phase == 0:
            y = linear_piece(m, c, k, F0, A, Om, t, u - drift, ud)
            state = lambda s, y=y, d=drift: (y(s)[0] + d, y(s)[1], d + 0 * s)
            crossings = [lambda s, y=y: k * y(s)[0] - Fy, lambda s, y=y: -k * y(s)[0] - Fy]
            zero = 1e-12 * Fy
        else:
            y = linear_piece(m, c, 0.0, F0 - phase * Fy, A, Om, t, u, ud)
            state = lambda s, y=y, p=phase: (y(s)[0], y(s)[1], y(s)[0] - p * Fy / k)
            crossings = [lambda s, y=y, p=phase: -p * y(s)[1]]
            zero = 1e-12 * Fy / np.sqrt(k * m)
        roots = [r for r in (first_crossing(f, t, t1, zero) for f in crossings) if r is not None]
        t_next = min(roots) if roots else t1
        pieces.append((t, t_next, state))
        u, ud, d = state(t_next)
        if roots and phase == 0:
            phase = 1 if u > drift else -1
            events.append((t_next, "yield"))
        elif roots:
            drift, phase = d, 0
            events.append((t_next, "unload"))
        t = t_next
    return pieces, events


def evaluate(pieces, t):
    """``(u, u', drift)`` (3, len(t)) of the closed form at the times ``t``."""
    out = np.empty((3, t.size))
    for t0, t1, state in pieces:
        sel = (t >= t0) & (t <= t1)
        out[:, sel] = state(t[sel])
    return out


# ---------------------------------------------------------------------- the models
def epp_model(c):
    """The EPP SDOF: two multipliers (+ face, - face) with opposite columns."""
    return ul.Model.from_natural(G=[[1.0]], E=[[STIFFNESS]], B=[[1.0, -1.0]], M=[[MASS]], C=[[c]],
                                 r=[YIELD_FORCE, YIELD_FORCE], families=[Yield([0, 1])])


def pulse_load(pulse, direction=(1.0,), constant=(0.0,)):
    kind, amp, tp = pulse
    f = Rectangular(amp, t_end=tp) if kind == "rect" else HalfSine(amp, duration=tp)
    return LoadHistory(list(constant), [(list(direction), f)])


def friction_block(mu, E_v=None):
    """A block (ux, uy) on a normal contact spring (0) with a tangential stick spring and slips
    (1, 2): under its weight the horizontal motion is the EPP SDOF with ``Fy = mu m g``."""
    B = [[0.0, 1.0, -1.0], [1.0, 0.0, 0.0]]
    return ul.Model.from_natural(G=np.eye(2), E=np.diag([STIFFNESS, 1e4]), B=B, M=MASS * np.eye(2), E_v=E_v,
                                 families=[Contact([0]), Friction([1, 2], normal=[0, 0], mu=mu)])


# ---------------------------------------------------------------------- exact to round-off
@pytest.mark.parametrize("c", [0.0, 1.0])
@pytest.mark.parametrize("name", sorted(PULSES))
def test_epp_sdof_is_exact(name, c):
    pulse = PULSES[name]
    pieces, events = epp_exact(pulse, c)
    assert [kind for _, kind in events] == ["yield", "unload"]
    model, load = epp_model(c), pulse_load(pulse)
    sol = ul.solve(model, load, dt=1e-3, t_end=T_END, method="event", initial="rest")
    u, _, drift = evaluate(pieces, sol.t)
    scale = np.abs(u).max()
    # yield and unloading instants, the + face only
    np.testing.assert_allclose(sol.stats["event_times"], [t for t, _ in events], rtol=1e-10, atol=0)
    assert list(sol.stats["event_kinds"]) == ["yield", "unload"]
    assert list(sol.stats["event_constraints"]) == [0, 0]
    # the motion, its elastic part and the permanent set
    assert np.abs(sol.u[:, 0] - u).max() <= 1e-10 * scale
    plastic = sol.v[:, 0] - sol.v[:, 1]
    assert np.abs(plastic - drift).max() <= 1e-10 * scale
    assert abs(plastic[-1] - drift[-1]) <= 1e-10 * drift[-1]
    assert np.abs((sol.u[:, 0] - plastic) - (u - drift)).max() <= 1e-10 * scale
    # the peak, at the unloading instant
    t_unload = events[1][0]
    peak, _, _, _, _ = march_event(model, load, [0.0, t_unload], [0.0], [0.0], [0.0, 0.0])
    u_peak = evaluate(pieces, np.array([t_unload]))[0, 0]
    assert u_peak >= u.max()
    assert abs(peak[-1, 0] - u_peak) <= 1e-10 * u_peak
    # the law: yield functions <= 0, multipliers only grow
    assert sol.psi.max() <= 1e-12 * YIELD_FORCE
    assert np.all(np.diff(sol.v, axis=0) >= -1e-15)


@pytest.mark.parametrize("name", sorted(PULSES))
def test_friction_block_is_the_epp_sdof(name):
    """Friction rows (psi_slip + mu psi_normal) under a constant normal force: Fy = mu m g."""
    mu, g = 0.5, YIELD_FORCE / (0.5 * MASS)
    pulse = PULSES[name]
    pieces, events = epp_exact(pulse, 0.0, Fy=mu * MASS * g)
    sol = ul.solve(friction_block(mu), pulse_load(pulse, (1.0, 0.0), (0.0, -MASS * g)), dt=1e-3,
                   t_end=T_END, method="event")
    u, _, drift = evaluate(pieces, sol.t)
    np.testing.assert_allclose(sol.stats["event_times"], [t for t, _ in events], rtol=1e-10, atol=0)
    assert list(sol.stats["event_kinds"]) == ["slip", "stick"]
    assert np.abs(sol.u[:, 0] - u).max() <= 1e-10 * np.abs(u).max()
    assert np.abs(sol.v[:, 1] - sol.v[:, 2] - drift).max() <= 1e-10 * np.abs(u).max()
    # psi holds the constraint functions: +-T - mu N with N = m g
    T = STIFFNESS * (sol.u[:, 0] - sol.v[:, 1] + sol.v[:, 2])
    np.testing.assert_allclose(sol.psi[:, 0], -MASS * g, rtol=1e-12)
    np.testing.assert_allclose(sol.psi[:, 1:], np.c_[T, -T] - mu * MASS * g, atol=1e-10 * mu * MASS * g)


def test_friction_on_a_kelvin_contact_is_refused():
    model = friction_block(0.5, E_v=np.diag([0.0, 10.0]))
    load = pulse_load(PULSES["rectangular"], (1.0, 0.0), (0.0, -10.0))
    with pytest.raises(ValueError, match=r"friction on a Kelvin contact.*'cq', 'modal' or 'direct'"):
        ul.solve(model, load, dt=1e-3, t_end=0.1, method="event")


# ---------------------------------------------------------------------- the steppers converge
def convergence_slope(method, rule, pulse, c):
    """Fitted order of the max error of u against the closed form, dt halved 4 times."""
    pieces, _ = epp_exact(pulse, c)
    model, load = epp_model(c), pulse_load(pulse)
    steps = 2e-3 / 2.0 ** np.arange(5)
    errors = []
    for dt in steps:
        sol = ul.solve(model, load, dt=dt, t_end=T_END, method=method, rule=rule, initial="rest")
        errors.append(np.abs(sol.u[:, 0] - evaluate(pieces, sol.t)[0]).max())
    return np.polyfit(np.log(steps), np.log(errors), 1)[0], errors


@pytest.mark.parametrize("c", [0.0, 1.0])
@pytest.mark.parametrize("name", sorted(PULSES))
@pytest.mark.parametrize("rule", ["bdf2", "trapezoidal"])
def test_direct_stepping_is_second_order(rule, name, c):
    slope, errors = convergence_slope("direct", rule, PULSES[name], c)
    assert slope >= 1.9, (slope, errors)
    assert errors[-1] <= 1e-6


@pytest.mark.parametrize("name", sorted(PULSES))
def test_cq_is_second_order(name):
    slope, errors = convergence_slope("cq", "bdf2", PULSES[name], 0.0)
    assert slope >= 1.9, (slope, errors)


# ---------------------------------------------------------------------- mixed contact and yield
def contact_yield_model(seed, *, kelvin=False):
    """A random structure (n = 2..3) with 1-2 contacts and one hardening yield pair (m = 3..4)."""
    rng = np.random.default_rng(seed)
    n, mc = int(rng.integers(2, 4)), int(rng.integers(1, 3))
    ne, m = n + 2, mc + 2
    G = rng.normal(size=(n, ne))
    E = np.diag(rng.uniform(50.0, 150.0, ne))
    B = np.zeros((ne, m))
    B[np.arange(mc), np.arange(mc)] = 1.0
    B[mc, mc], B[mc, mc + 1] = 1.0, -1.0
    A = np.zeros((m, m))
    A[mc:, mc:] = 5.0 * np.array([[1.0, -1.0], [-1.0, 1.0]])          # kinematic hardening
    r = np.concatenate([np.zeros(mc), rng.uniform(3.0, 6.0, 2)])
    E_v = np.diag([2.0] * mc + [0.0] * (ne - mc)) if kelvin else None
    model = ul.Model.from_natural(G, E, B, M=np.diag(rng.uniform(0.5, 1.5, n)), A=A, r=r,
                                  C=0.01 * (G @ E @ G.T), E_v=E_v,
                                  families=[Contact(np.arange(mc)), Yield([mc, mc + 1])])
    shape = rng.normal(size=n)
    load = LoadHistory(-0.03 * (G[:, :mc] @ np.diag(E)[:mc]),      # presses the contacts
                       [(20.0 * shape, HalfSine(1.0, duration=0.4)),
                        (-15.0 * shape, Rectangular(1.0, t_start=0.5, t_end=0.7))])
    return model, load


@pytest.mark.parametrize("seed, kelvin", [(0, False), (4, False), (6, False), (0, True)])
def test_every_method_converges_to_the_event_march_on_contact_and_yield(seed, kelvin):
    model, load = contact_yield_model(seed, kelvin=kelvin)
    ref = ul.solve(model, load, dt=1e-3, t_end=1.0, method="event")
    kinds = set(ref.stats["event_kinds"])
    assert {"open", "close", "yield", "unload"} <= kinds and ref.stats["undecided"] == 0
    # the reference obeys both laws
    contact, rate = ~model.law.rate, model.law.rate
    scale_psi = np.abs(ref.psi).max()
    assert ref.psi.max() <= 1e-12 * scale_psi
    assert np.all(ref.v[:, contact] * ref.psi[:, contact] == 0.0)
    assert np.all(np.diff(ref.v[:, rate], axis=0) >= -1e-15)
    scale = np.abs(ref.u).max(), np.abs(ref.v).max()
    # the trapezoidal rule chatters at Kelvin contacts (test_event.py): BDF2 only there
    runs = ((("direct", "bdf2"), ("cq", "bdf2"), ("modal", "bdf2")) if kelvin else
            (("direct", "bdf2"), ("direct", "trapezoidal"), ("cq", "bdf2"), ("modal", "trapezoidal")))
    for method, rule in runs:
        errors = []
        for dt in (5e-4, 2.5e-4):
            sol = ul.solve(model, load, dt=dt, t_end=1.0, method=method, rule=rule)
            s = int(round(1e-3 / dt))
            errors.append(max(np.abs(sol.u[::s] - ref.u).max() / scale[0],
                              np.abs(sol.v[::s] - ref.v).max() / scale[1]))
        assert errors[1] <= 1e-4, (method, rule, errors)
        assert errors[0] / errors[1] >= 3.0, (method, rule, errors)
