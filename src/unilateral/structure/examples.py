"""The numerical example of Liolios (1990), built with :class:`~unilateral.structure.Frame2D`.

The paper's Fig. 1 is lost; this is the reconstruction adopted in docs/theory.md ("The paper's example") (kN, m, s):
a mass M on top of a column of height 10 m, standing on a rigid massless foundation 10 m wide
that rests on three tensionless soil elements (spring k and dashpot c in parallel, acting only in
contact) under its edges and centre. Gravity first, then a horizontal rectangular pulse rocks the
structure and the left edge (node 3) lifts off.
"""

from __future__ import annotations

import numpy as np

from ..loads import LoadHistory, Rectangular
from .frame import Frame2D

MASS = 40.0          # kN s^2/m
K_SOIL = 200e3       # kN/m   (200 MN/m)
C_SOIL = 10e3        # kN s/m (10 MN s/m)
EI = 1e9             # kN m^2 (10^6 MN m^2)
EA_RIGID = 1e12      # kN: the column is axially practically rigid
HEIGHT = 10.0        # m
HALF_WIDTH = 5.0     # m
GRAVITY = 10.0       # m/s^2
PULSE = 200.0        # kN, half the weight
T_PULSE = 0.1        # s


def liolios1990(kelvin=True):
    """Build the paper's example: the structure, its load and a description.

    Nodes: 1 top of the column (0, 10) carrying the mass (both translations); 2 foundation centre
    (0, 0), restrained horizontally; 3 and 4 foundation edges (-5, 0) and (+5, 0), rigidly linked
    to node 2. Column: beam 2 -> 1 with ``EI = 1e9`` kN m^2 and ``EA = 1e12`` kN. Soil elements
    ``"soil3"``, ``"soil2"``, ``"soil4"`` under nodes 3, 2, 4 (vertical, ``k = 200e3`` kN/m).

    Parameters
    ----------
    kelvin : bool
        True (the paper's model): the soil dashpots ``c = 10e3`` kN s/m are in parallel with the
        springs and act only in contact (Kelvin elements). False: the dashpots stay attached to
        the foundation (they pull too) and go into ``C``.

    Returns
    -------
    structure : Structure
        DOFs ``1.ux, 1.uy, 1.rz, 2.uy, 2.rz``.
    load : LoadHistory
        ``q(t) -> (5,)``, sampled at all steps at once by :func:`unilateral.solve`.
        Gravity ``g = 10`` m/s^2 downwards plus ``P = 200`` kN at node 1 towards +x for
        ``0 < t <= 0.1`` s (zero at ``t = 0``: the static state is under gravity alone).
    info : dict
        ``units``; ``static_displacement`` ``-M g / (3 k)`` of the foundation (m);
        ``figure2``: the node, DOF and label of the quantity of the paper's Fig. 2 (the
        vertical displacement of node 3, for :meth:`Structure.node_displacement`).
    """
    fr = Frame2D()
    fr.node(1, 0.0, HEIGHT)
    fr.node(2, 0.0, 0.0)
    fr.node(3, -HALF_WIDTH, 0.0)
    fr.node(4, HALF_WIDTH, 0.0)
    fr.support(2, ux=True, uy=False)
    fr.rigid_link(2, 3)
    fr.rigid_link(2, 4)
    fr.beam("column", 2, 1, E=1.0, A=EA_RIGID, I=EI)
    fr.mass(1, MASS)
    for node in (3, 2, 4):
        fr.soil(f"soil{node}", node, K_SOIL, c=C_SOIL if kelvin else 0.0)
        if not kelvin:
            fr.dashpot(f"dashpot{node}", node, C_SOIL)
    structure = fr.build()
    weight = structure.gravity(GRAVITY)
    push = structure.nodal_load(1, ux=1.0)
    load = LoadHistory(weight, [(push, Rectangular(PULSE, t_end=T_PULSE))])

    info = {
        "units": "kN, m, s",
        "static_displacement": -MASS * GRAVITY / (3 * K_SOIL),
        "figure2": {"node": 3, "dof": "uy", "label": "vertical displacement of node 3 (m)"},
    }
    return structure, load, info


def winkler_beam(n_elements=100, *, length=50.0, EI=2e6, EA=2e7, mass_per_length=2.0,
                 k_soil=5e3, c_soil=0.0, zeta=0.02, load="impact", P=500.0, speed=40.0):
    """A free beam on a tensionless Winkler foundation (kN, m, s): large sparse models.

    Nodes ``0 .. n_elements`` along ``x`` at ``y = 0``; beam elements between them; lumped
    masses; one compression-only soil element (``"s0"``, ``"s1"``, ...) per node with the
    tributary stiffness ``k_soil`` per metre (and dashpot ``c_soil`` per metre); node 0 held
    horizontally; Rayleigh damping ``zeta`` at the first two frequencies of about 1 and 50 Hz.
    Gravity (g = 9.81) presses the beam onto the soil; then

    * ``load="impact"``: a downward half-sine impact ``P`` of 20 ms at the left quarter point,
    * ``load="moving"``: a downward force ``P`` moving from the left end at ``speed`` m/s,

    so that parts of the beam lift off and land again.

    Returns
    -------
    structure : Structure (``n = 3 (n_elements + 1) - 1`` DOFs, ``m = n_elements + 1``)
    load : callable ``q(t) -> (n,)``
    info : dict (units, the loaded node for figures)
    """
    from ..loads import HalfSine

    if load not in ("impact", "moving"):
        raise ValueError(f"load={load!r} is not valid; valid: 'impact', 'moving'")
    fr = Frame2D()
    h = length / n_elements
    for i in range(n_elements + 1):
        fr.node(i, i * h, 0.0)
    for i in range(n_elements):
        fr.beam(f"b{i}", i, i + 1, E=1.0, A=EA, I=EI)
    for i in range(n_elements + 1):
        trib = h if 0 < i < n_elements else h / 2
        fr.mass(i, mass_per_length * trib)
        fr.soil(f"s{i}", i, k_soil * trib, c=c_soil * trib)
    fr.support(0, ux=True, uy=False)
    if zeta:
        fr.rayleigh_from_ratios(zeta, 1.0, 50.0)
    structure = fr.build()
    weight = structure.gravity(9.81)
    if load == "impact":
        node = n_elements // 4
        q = LoadHistory(weight, [(structure.nodal_load(node, uy=-P), HalfSine(1.0, duration=0.02))])
    else:
        node = n_elements // 2
        unit = [structure.nodal_load(i, uy=-P) for i in range(n_elements + 1)]

        def q(t):
            x = speed * t / h                   # position in elements; linear between nodes
            i = int(np.floor(x))
            if t <= 0.0 or i >= n_elements:
                return weight
            f = x - i
            return weight + (1.0 - f) * unit[i] + f * unit[i + 1]
    info = {"units": "kN, m, s", "node": node,
            "figure": {"node": node, "dof": "uy", "label": f"vertical displacement of node {node} (m)"}}
    return structure, q, info
