"""Shared test models."""

from __future__ import annotations

import os

# The engine of method "auto" by the size policy's steps rule, never by what numba's cache holds
# (unilateral.march.policy): a test's numbers and stats do not depend on the tests before it. Set
# before unilateral is imported (the default of SizePolicy.engine_choice), and for the CLI's
# subprocesses. tests/test_engine_cost.py tests the "cost" rule with policies of its own.
os.environ.setdefault("UNILATERAL_ENGINE_CHOICE", "steps")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
import scipy.linalg as sla  # noqa: E402

import unilateral as ul  # noqa: E402

#: The files of ``pytest -m smoke``: the README, the entry points, every method against direct,
#: stepping, the LCP solvers and the paper's example, in about a minute.
SMOKE_FILES = {"test_readme.py", "test_solve.py", "test_conformance.py", "test_simulation.py", "test_lcp.py",
               "test_size_policy.py", "test_architecture.py", "test_example_outputs.py"}


def pytest_collection_modifyitems(config, items):
    """Mark the tests of :data:`SMOKE_FILES` ``smoke``."""
    for item in items:
        if item.path.name in SMOKE_FILES:
            item.add_marker(pytest.mark.smoke)

# The paper's example (docs/theory.md, "The paper's example"), in kN, m, s.
MASS = 40.0            # kN s^2/m
K_SOIL = 200e3         # kN/m
C_SOIL = 10e3          # kN s/m
EI = 1e6 * 1e3         # kN m^2
HEIGHT = 10.0          # m
HALF_WIDTH = 5.0       # m
EA_RIGID = 1e12        # kN, axially rigid column
GRAVITY = 10.0         # m/s^2


def rocking_natural(kelvin=True, top_rotational_mass=0.0):
    """The paper's example entered by hand in natural form (G, E, B, E_v, M, C).

    ``kelvin=True``: the soil dashpots act in series with the contact (Kelvin elements, E_v).
    ``kelvin=False``: the same dashpots stay attached (they pull too), i.e. they are part of C.

    DOFs ``u = [x1, y1, r1, y2, r2]``: top node 1 (mass), foundation centre node 2 (x2 fixed),
    rigid foundation with edges at x = -5 (node 3) and x = +5 (node 4). Element strains: column
    elongation, column end rotations relative to the chord (nodes 2 and 1), and the extensions
    of the soil elements under nodes 3, 2, 4.
    """
    h, b = HEIGHT, HALF_WIDTH
    G = np.zeros((5, 6))
    # column from node 2 (bottom) to node 1 (top): e_axial = y1 - y2,
    # chord rotation beta = -(x1 - x2)/h, end rotations r2 - beta, r1 - beta.
    G[1, 0], G[3, 0] = 1.0, -1.0
    G[4, 1] = 1.0
    G[0, 1] = 1.0 / h
    G[2, 2] = 1.0
    G[0, 2] = 1.0 / h
    # soil elements: extension = vertical displacement of the foundation at x = -b, 0, +b
    for j, x in enumerate((-b, 0.0, b)):
        G[3, 3 + j] = 1.0
        G[4, 3 + j] = x
    E = sla.block_diag(EA_RIGID / h, EI / h * np.array([[4.0, 2.0], [2.0, 4.0]]), K_SOIL * np.eye(3))
    B = np.zeros((6, 3))
    B[3:, :] = np.eye(3)
    E_dash = sla.block_diag(np.zeros((3, 3)), C_SOIL * np.eye(3))
    M = np.diag([MASS, MASS, top_rotational_mass, 0.0, 0.0])
    if kelvin:
        return dict(G=G, E=E, B=B, E_v=E_dash, M=M, C=None)
    return dict(G=G, E=E, B=B, E_v=None, M=M, C=G @ E_dash @ G.T)


def rocking_model(kelvin=True, **kw):
    nat = rocking_natural(kelvin, **kw)
    return ul.Model.from_natural(nat["G"], nat["E"], nat["B"], M=nat["M"], E_v=nat["E_v"], C=nat["C"],
                                 dof_names=["x1", "y1", "r1", "y2", "r2"],
                                 constraint_names=["soil3", "soil2", "soil4"])


def rocking_load(P=200.0, t_pulse=0.1):
    """Gravity on the top mass plus a horizontal rectangular pulse P for 0 < t <= t_pulse."""
    def q(t):
        out = np.zeros(5)
        out[1] = -MASS * GRAVITY
        if 0.0 < t <= t_pulse + 1e-12:
            out[0] = P
        return out
    return q


def bouncing_exact(t, m, k, g, V0):
    """Mass on a tensionless spring under gravity, thrown up with V0 from its static position.

    Returns the displacement u(t) (up positive, 0 = spring unloaded). Contact: harmonic arcs of
    amplitude V0/omega about -g/omega^2; flight: parabolas.
    """
    w = np.sqrt(k / m)
    ds = m * g / k
    A = V0 / w
    th1 = np.arcsin(ds / A)
    t_up = th1 / w                                  # first lift-off
    V1 = np.sqrt(V0 ** 2 - (ds * w) ** 2)
    T_flight = 2 * V1 / g
    T_contact = (np.pi + 2 * th1) / w
    T = T_flight + T_contact
    t = np.asarray(t, dtype=float)
    out = np.empty_like(t)
    first = t <= t_up
    out[first] = -ds + A * np.sin(w * t[first])
    tau = np.mod(t[~first] - t_up, T)
    flying = tau <= T_flight
    ft = tau[flying]
    res = np.empty_like(tau)
    res[flying] = V1 * ft - 0.5 * g * ft ** 2
    ct = tau[~flying] - T_flight                     # time since landing; phase pi - th1 at landing
    res[~flying] = -ds + A * np.sin(np.pi - th1 + w * ct)
    out[~first] = res
    return out, {"period": T, "peak_uplift": V1 ** 2 / (2 * g), "t_liftoff": t_up}


@pytest.fixture
def rocking():
    return rocking_model(kelvin=True)
