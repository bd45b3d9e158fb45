"""Benchmark problems: a model, its load, the time step and a key output to compare methods.

Every factory returns a :class:`Problem` ``(model, load, dt, N, output, description)``;
:func:`build` looks a problem up by name:

``paper``
    The seed's example (:func:`~unilateral.structure.liolios1990`), 0.5 s;
    ``10^5`` steps (quick: 2000). Output: vertical displacement of node 3 (the seed's Fig. 2).
``tower``
    A five-storey tower on a rigid foundation resting on three tensionless soil spring-dashpots,
    under gravity and a 10 s synthetic accelerogram in ``x``; ``10^4`` steps (quick: 1000).
    Output: horizontal displacement of the top relative to the ground.
``winkler<m>``
    :func:`~unilateral.structure.winkler_beam` with ``m`` nodes (``m - 1`` elements, so ``m``
    unilateral unknowns) under the moving load, 1.5 s; ``10^4`` steps (quick: 500 for
    ``m <= 100``, else 200). Output: vertical displacement of the middle node. The suite runs
    ``winkler100`` and ``winkler1000``.
"""

import re
from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from ..loads import LoadHistory
from ..loads.synthetic import synthetic_accelerogram
from ..structure import Frame2D, liolios1990, winkler_beam

PAPER_DURATION = 0.5        # s, as the command line's example
WINKLER_DURATION = 1.5      # s: the moving load crosses the 50 m beam at 40 m/s in 1.25 s

TOWER_STOREYS = 5
TOWER_STOREY_HEIGHT = 3.0   # m
TOWER_MASS = 40.0           # kN s^2/m per storey
TOWER_EI = 1e9              # kN m^2, the paper's column
TOWER_EA = 1e12             # kN, axially practically rigid
TOWER_HALF_WIDTH = 3.0      # m
TOWER_K_SOIL = 200e3        # kN/m, the paper's soil elements
TOWER_C_SOIL = 10e3         # kN s/m
TOWER_GRAVITY = 10.0        # m/s^2
TOWER_DURATION = 10.0       # s, the length of the accelerogram
TOWER_PGA = 4.0             # m/s^2
TOWER_SEED = 1

PROBLEMS = ("paper", "tower", "winkler100", "winkler1000")
"""The problems of the benchmark suite."""


class Problem(NamedTuple):
    """A benchmark problem.

    Attributes
    ----------
    model : Model
    load : callable ``q(t) -> (n,)``
    dt : float
        Time step.
    N : int
        Number of steps (``t_end = N dt``).
    output : callable ``output(sol) -> (N+1,)``
        The key output compared between methods.
    description : str
    """

    model: object
    load: Callable
    dt: float
    N: int
    output: Callable
    description: str


def build(name: str, *, quick: bool = False, steps: int | None = None) -> Problem:
    """Build problem ``name`` (``"paper"``, ``"tower"`` or ``"winkler<m>"``).

    Parameters
    ----------
    name : str
    quick : bool
        Use the quick number of steps.
    steps : int, optional
        Number of steps, overriding the default.

    Returns
    -------
    Problem
    """
    match = re.fullmatch(r"winkler(\d+)", name)
    if match:
        m = int(match.group(1))
        if m < 2:
            raise ValueError(f"problem {name!r}: a Winkler beam needs at least 2 nodes")
        return winkler(m, _steps(steps, quick, 10_000, 500 if m <= 100 else 200))
    if name == "paper":
        return paper(_steps(steps, quick, 100_000, 2000))
    if name == "tower":
        return tower(_steps(steps, quick, 10_000, 1000))
    raise ValueError(f"problem {name!r} is not known; valid: 'paper', 'tower', 'winkler<m>' "
                     f"(e.g. {', '.join(map(repr, PROBLEMS))})")


def _steps(steps, quick, full, short) -> int:
    """``steps`` checked, or the default number of steps (``short`` if ``quick``)."""
    if steps is None:
        return short if quick else full
    if isinstance(steps, bool) or not isinstance(steps, (int, np.integer)) or steps < 1:
        raise ValueError(f"steps must be a positive integer, got {steps!r}")
    return int(steps)


def refined(problem: Problem, factor: int) -> Problem:
    """The same problem with ``factor`` times smaller steps over the same time span."""
    return problem._replace(dt=problem.dt / factor, N=problem.N * factor,
                            description=f"{problem.description}, dt/{factor}")


def paper(steps: int) -> Problem:
    """The seed's example over 0.5 s in ``steps`` steps."""
    structure, load, info = liolios1990()
    node, dof = info["figure2"]["node"], info["figure2"]["dof"]
    return Problem(structure.to_model(), load, PAPER_DURATION / steps, steps,
                   lambda sol: structure.node_displacement(sol, node, dof),
                   "Liolios (1990) example: rocking column on 3 tensionless Kelvin soil elements, "
                   f"pulse; output {node}.{dof}")


def tower(steps: int) -> Problem:
    """A five-storey tower rocking on tensionless soil under a synthetic earthquake."""
    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("left", -TOWER_HALF_WIDTH, 0.0)
    fr.node("right", TOWER_HALF_WIDTH, 0.0)
    fr.support("base", ux=True, uy=False)       # moves with the ground horizontally
    fr.rigid_link("base", "left")
    fr.rigid_link("base", "right")
    below = "base"
    for storey in range(1, TOWER_STOREYS + 1):
        fr.node(storey, 0.0, storey * TOWER_STOREY_HEIGHT)
        fr.beam(f"column{storey}", below, storey, E=1.0, A=TOWER_EA, I=TOWER_EI)
        fr.mass(storey, TOWER_MASS)
        below = storey
    for node in ("left", "base", "right"):
        fr.soil(f"soil_{node}", node, TOWER_K_SOIL, c=TOWER_C_SOIL)
    structure = fr.build()
    # Relative coordinates: the effective load is -M r a_g(t), r = 1 on the free ux DOFs.
    r = np.array([dof == "ux" for _, dof in structure.dofs.free], dtype=float)
    inertia = -(structure.M @ r)
    weight = structure.gravity(TOWER_GRAVITY)
    record = synthetic_accelerogram(TOWER_DURATION, pga=TOWER_PGA, seed=TOWER_SEED)

    load = LoadHistory(weight, [(inertia, record)])
    top = TOWER_STOREYS
    return Problem(structure.to_model(), load, TOWER_DURATION / steps, steps,
                   lambda sol: structure.node_displacement(sol, top, "ux"),
                   f"{TOWER_STOREYS}-storey tower on 3 tensionless Kelvin soil elements, "
                   f"{record.name}, pga {TOWER_PGA:g} m/s2; output {top}.ux (relative)")


def winkler(m: int, steps: int) -> Problem:
    """A beam with ``m`` nodes on tensionless Winkler springs under a moving load."""
    structure, load, info = winkler_beam(m - 1, load="moving")
    node = info["node"]
    return Problem(structure.to_model(), load, WINKLER_DURATION / steps, steps,
                   lambda sol: structure.node_displacement(sol, node, "uy"),
                   f"beam on {m} tensionless Winkler springs, moving load; output {node}.uy")
