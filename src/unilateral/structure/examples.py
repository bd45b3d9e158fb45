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
        vertical displacement of node 3, for :meth:`Structure.node_displacement`); ``left_edge``
        ``(x, y)`` of the foundation's left edge (m), the point the README's overturning moments
        are taken about.
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
        "left_edge": (-HALF_WIDTH, 0.0),
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
        index = [structure.dofs.index(i, "uy") for i in range(n_elements + 1)]   # one number per node

        def q(t):
            x = speed * t / h                   # position in elements; linear between nodes
            i = int(np.floor(x))
            if t <= 0.0 or i >= n_elements:
                return weight
            f = x - i
            out = weight.copy()
            out[index[i]] -= (1.0 - f) * P
            out[index[i + 1]] -= f * P
            return out
    info = {"units": "kN, m, s", "node": node,
            "figure": {"node": node, "dof": "uy", "label": f"vertical displacement of node {node} (m)"}}
    return structure, q, info


#: The footing of :func:`halfspace_tower` (m): 10 m wide (the paper's), 10 m long out of plane.
FOOTING_WIDTH = 10.0
FOOTING_LENGTH = 10.0
#: The half-space of :func:`halfspace_tower` (kN, m, s): rho in t/m^3, Vs in m/s. With nu = 1/3 its
#: static vertical stiffness under the rigid 10 m x 10 m footing on 4 strips is 6.09e5 kN/m, the
#: paper's 3 x 200 MN/m (rocking 1.22e7 kN m/rad against the paper's 1.0e7; the cones: 6.37e5 and
#: 4.98e6, a Winkler bed's rocking).
SOIL_RHO = 2.0
SOIL_NU = 1.0 / 3.0
SOIL_VS = 97.0
HALFSPACE_SOILS = ("winkler-kelvin", "cones", "halfspace")


def halfspace_tower(soil="halfspace", *, load="pulse", patches=4, record=None, pulse=PULSE):
    """The paper's tower on a rigid footing resting on a soil medium (kN, m, s).

    Node 1: the mass ``M = 40`` on top of a 10 m column (``EI = 1e9``, axially practically rigid);
    node 2: the footing's centre, restrained horizontally, with the footing's ``uy`` and ``rz``.
    The footing (``Frame2D.foundation``, rigid, massless) rests on

    * ``"winkler-kelvin"``: the paper's three tensionless soil elements (``k = 200e3`` kN/m,
      ``c = 10e3`` kN s/m) under ``x = -5, 0, +5`` (three strips of a 15 m x 6.67 m footing, so that
      the contacts sit where the paper's are and the footing's area is 100 m^2);
    * ``"cones"``: Wolf's vertical cone of the 10 m x 10 m footing spread over ``patches`` strips
      by area (uncoupled spring, dashpot per strip; :mod:`unilateral.structure.foundation`);
    * ``"halfspace"``: the rigorous elastic half-space under the same strips.

    The medium of the cones and the half-space: ``rho = 2`` t/m^3, ``nu = 1/3``, ``Vs = 97`` m/s
    (``G = 18.8`` MPa), chosen so that the static vertical stiffness of the footing is the paper's
    ``3 x 200`` MN/m (see ``info["static_stiffness"]``).

    Parameters
    ----------
    soil : {"winkler-kelvin", "cones", "halfspace"}
    load : {"pulse", "earthquake"}
        Gravity (g = 10 m/s^2) and either the paper's horizontal pulse (``pulse`` kN at node 1 for
        ``0 < t <= 0.1`` s) or a horizontal ground acceleration ``record`` (default: the synthetic
        record of :func:`unilateral.loads.synthetic_accelerogram`, 8 s, PGA 5 m/s^2, f_g = 4 Hz,
        seed 1)
        acting as ``-M r a_g`` (displacements relative to the free field, ``docs/theory.md`` 12).
    patches : int
        Strips of the 10 m footing (cones, half-space).
    record : GroundMotion or time function, optional
        The ground acceleration (m/s^2) of ``load="earthquake"``.
    pulse : float
        Magnitude of the pulse (kN).

    Returns
    -------
    structure : Structure (``structure.to_model()`` is the FoundationModel)
    load : LoadHistory
    info : dict ``units``, ``soil``, ``load``, ``edge`` (x of the left edge), ``static_stiffness``
        (vertical, kN/m, from the soil's ``Phi(0)``), ``figure`` (rocking of node 2).
    """
    from ..loads import synthetic_accelerogram

    if soil not in HALFSPACE_SOILS:
        raise ValueError(f"soil={soil!r} is not valid; valid: {', '.join(map(repr, HALFSPACE_SOILS))}")
    if load not in ("pulse", "earthquake"):
        raise ValueError(f"load={load!r} is not valid; valid: 'pulse', 'earthquake'")
    fr = Frame2D()
    fr.node(1, 0.0, HEIGHT)
    fr.node(2, 0.0, 0.0)
    fr.beam("column", 2, 1, E=1.0, A=EA_RIGID, I=EI)
    fr.mass(1, MASS)
    if soil == "winkler-kelvin":
        width, length, m = 3 * HALF_WIDTH, FOOTING_WIDTH * FOOTING_LENGTH / (3 * HALF_WIDTH), 3
        spec = {"model": "winkler-kelvin", "k": K_SOIL, "c": C_SOIL}
    else:
        width, length, m = FOOTING_WIDTH, FOOTING_LENGTH, patches
        spec = {"model": soil, "Vs": SOIL_VS, "nu": SOIL_NU, "rho": SOIL_RHO}
    fr.foundation("footing", 2, width=width, length=length, patches=m, soil=spec)
    structure = fr.build()
    weight = structure.gravity(GRAVITY)
    if load == "pulse":
        history = LoadHistory(weight, [(structure.nodal_load(1, ux=1.0), Rectangular(pulse, t_end=T_PULSE))])
    else:
        a_g = record if record is not None else synthetic_accelerogram(8.0, 0.01, 5.0, seed=1, f_g=4.0)
        history = LoadHistory(weight, [structure.ground_motion(a_g, "ux")])
    fnd = structure.foundation
    ones = np.ones(fnd.m)
    info = {"units": "kN, m, s", "soil": soil, "load": load, "edge": -0.5 * FOOTING_WIDTH,
            "static_stiffness": float(ones @ np.linalg.solve(fnd.soil.static(), ones)),
            "figure": {"node": 2, "dof": "rz", "label": "rocking of the footing (rad)"}}
    return structure, history, info


#: The site of :func:`two_bay_on_footings`: a soft layer over stiffer ground (kN, m, s; rho in t/m^3).
FOOTINGS_SITE = {"model": "layered", "layers": [{"thickness": 4.0, "Vs": 120.0, "nu": 0.35, "rho": 1.8}],
                 "Vs": 300.0, "nu": 0.3, "rho": 2.0}


def two_bay_on_footings(*, soil=None, record=None, pga=4.0, duration=6.0, mu=None):
    """A two-storey, two-bay frame on two footings on one soil, under a ground motion (kN, m, s).

    Bays 6 m, storeys 3.5 m; columns 400 x 400 mm, beams 300 x 500 mm, E = 30 GPa; floor masses
    60 t (15, 30, 15 t at the joints); rigid-plastic hinges (My = 180 kN m) at both ends of the
    first-floor beams; mass-proportional damping, 5 % at the first period (0.48 s on the soil's
    static springs). The left and middle columns stand on one rigid footing ``"A"`` (8 m wide,
    3 m long, 20 t, centred at x = 3 m, node 10, rigidly linked to the column bases 1 and 2), the
    right column on footing ``"B"`` (3 m wide, 8 t, node 3); 3.5 m of ground between them. Both
    rest on the same soil (default :data:`FOOTINGS_SITE`: a 4 m layer with Vs = 120 m/s over a
    half-space with Vs = 300 m/s), 8 and 3 strips: the footings interact through the ground.
    Horizontally each footing is held at its node (no sliding), or with ``mu`` rests on the soil
    and slides (``horizontal="soil"``). Gravity (g = 9.81 m/s^2) and a horizontal ground motion
    ``-M r a_g``.

    Parameters
    ----------
    soil : dict, optional
        The soil of both footings (:class:`~unilateral.structure.foundation.SoilSpec` fields).
    mu : float, optional
        The footings' friction coefficient on the soil: they slide (default: held horizontally).
    record : GroundMotion or time function, optional
        Ground acceleration (m/s^2); default the synthetic record of
        :func:`unilateral.loads.synthetic_accelerogram` (``duration`` s, PGA ``pga`` m/s^2,
        f_g = 3 Hz, seed 7).

    Returns
    -------
    structure, load, info : info has ``units``, ``figure`` (roof ux), ``edges``
        ``{footing: (x_left, x_right)}``.
    """
    from ..loads import synthetic_accelerogram

    fr = Frame2D()
    for node, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (3, 12.0, 0.0), (10, 3.0, 0.0)):
        fr.node(node, x, y)
    for level, y in ((1, 3.5), (2, 7.0)):
        for k, x in enumerate((0.0, 6.0, 12.0)):
            fr.node(10 * level + k + 1, x, y)
    fr.rigid_link(10, 1)
    fr.rigid_link(10, 2)
    column, beam = dict(E=30e6, A=0.16, I=0.4 ** 4 / 12), dict(E=30e6, A=0.15, I=0.3 * 0.5 ** 3 / 12)
    for k in (1, 2, 3):
        fr.beam(f"C{k}_1", k, 10 + k, **column)
        fr.beam(f"C{k}_2", 10 + k, 20 + k, **column)
    for level in (1, 2):
        for bay in (1, 2):
            fr.beam(f"B{level}_{bay}", 10 * level + bay, 10 * level + bay + 1, **beam)
    for bay in (1, 2):
        fr.hinge(f"B1_{bay}.i", f"B1_{bay}", "i", My=180.0)
        fr.hinge(f"B1_{bay}.j", f"B1_{bay}", "j", My=180.0)
    for level in (1, 2):
        for k, m in enumerate((15.0, 30.0, 15.0)):
            fr.mass(10 * level + k + 1, m)
    fr.rayleigh(a0=1.3)                   # mass-proportional: 5 % at the first period, 0.48 s
    spec = dict(FOOTINGS_SITE if soil is None else soil)
    slide = {} if mu is None else dict(horizontal="soil", mu=mu)
    fr.foundation("A", 10, width=8.0, length=3.0, patches=8, soil=spec, mass=20.0, J=20.0 * 8.0 ** 2 / 12, **slide)
    fr.foundation("B", 3, width=3.0, length=3.0, patches=3, soil=spec, mass=8.0, J=8.0 * 3.0 ** 2 / 12, **slide)
    structure = fr.build()
    a_g = record if record is not None else synthetic_accelerogram(duration, 0.01, pga, seed=7, f_g=3.0)
    load = LoadHistory(structure.gravity(9.81), [structure.ground_motion(a_g, "ux")])
    info = {"units": "kN, m, s", "figure": {"node": 21, "dof": "ux", "label": "roof displacement ux of node 21 (m)"},
            "edges": {"A": (-1.0, 7.0), "B": (10.5, 13.5)}}
    return structure, load, info
