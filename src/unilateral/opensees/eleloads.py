"""``eleLoad('-ele', *tags | '-range', a, b, '-type', '-beamUniform', Wy[, Wx])`` on 2-D
``elasticBeamColumn`` elements.

A uniform load ``(Wx, Wy)`` along the element's local axes (``x`` from ``i`` to ``j``, ``y`` turned
90 degrees counter-clockwise) enters the equations of motion as its consistent nodal loads, the
fixed-end forces reversed: ``(Wx L/2, Wy L/2, Wy L^2/12)`` at ``i`` and ``(Wx L/2, Wy L/2,
-Wy L^2/12)`` at ``j`` (local axes, rotated to global ones), times the pattern's factor. For an
Euler-Bernoulli beam these give its exact nodal displacements. The element's end forces are those
of its displacements minus these loads (``K_e u_e - f_e``: the fixed-end forces included), as
OpenSees reports them (``eleForce``, ``localForce``, ``basicForce``) and sums them into
``reactions``.
"""

from __future__ import annotations

import numpy as np

from .elements import BeamColumn
from .refusals import refuse

__all__ = ["parse_element_load", "equivalent_loads", "pattern_forces", "element_load_forces"]

_FORM = "eleLoad('-ele', *tags, '-type', '-beamUniform', Wy, Wx)"


def parse_element_load(domain, args) -> list:
    """``[(tag, Wy, Wx), ...]`` of ``eleLoad(*args)``, checked against ``domain``."""
    what = f"eleLoad({', '.join(map(repr, args))})"
    args = list(args)
    tags = []
    while args and args[0] in ("-ele", "-range"):
        flag = args.pop(0)
        numbers = []
        while args and not isinstance(args[0], str):
            numbers.append(int(args.pop(0)))
        if flag == "-range":
            if len(numbers) != 2:
                refuse(what, "'-range' takes two element tags", "eleLoad('-range', first, last, ...)")
            numbers = [t for t in domain.elements if numbers[0] <= t <= numbers[1]]
        tags += numbers
    if len(args) < 3 or args[0] != "-type" or args[1] != "-beamUniform":
        kind = args[1] if len(args) > 1 and args[0] == "-type" else None
        refuse(what, f"only uniform beam loads (-beamUniform) are in this slice{f', not {kind}' if kind else ''}",
               f"{_FORM}, or nodal loads")
    values = args[2:]
    if len(values) not in (1, 2) or any(isinstance(v, str) for v in values):
        refuse(what, "'-beamUniform' takes Wy and optionally Wx (a partial or trapezoidal load is not in the "
               "subset)", _FORM)
    wy, wx = float(values[0]), float(values[1]) if len(values) > 1 else 0.0
    if not tags:
        refuse(what, "no element is named", _FORM)
    for tag in tags:
        e = domain.elements.get(tag)
        if not isinstance(e, BeamColumn):
            refuse(what, f"element {tag} is not a 2-D elasticBeamColumn", "uniform loads on 2-D elasticBeamColumn "
                   "elements; nodal loads on the others")
        if wx and domain.transforms[e.transf][0] == "PDelta":
            refuse(what, f"an axial load Wx on the PDelta element {tag}: its axial force varies along it, and "
                   "OpenSees's P-Delta takes the basic one (with -Wx L/2)", "Wx = 0, or nodal loads")
    return [(tag, wy, wx) for tag in tags]


def equivalent_loads(domain, tag, wy, wx) -> np.ndarray:
    """The consistent nodal loads (6,) of a uniform load on element ``tag``, global ``(Fx, Fy, Mz)`` at
    ``i`` then ``j``."""
    e = domain.elements[tag]
    d = np.subtract(domain.nodes[e.j], domain.nodes[e.i])
    L = float(np.hypot(*d))
    c, s = d / L
    fx, fy = c * wx - s * wy, s * wx + c * wy                       # the load per length, global axes
    m = wy * L * L / 12.0
    return np.array([fx * L / 2, fy * L / 2, m, fx * L / 2, fy * L / 2, -m])


def _factor(domain, p, time):
    return p.frozen if p.frozen is not None else p.factor * float(domain.series[p.series](np.array([time]))[0])


def pattern_forces(b, domain, p) -> np.ndarray:
    """The nodal forces (3 nodes,) of the Plain pattern ``p`` at factor 1: its nodal loads and the
    consistent nodal loads of its element loads."""
    f = np.zeros(b.mass.size)
    nf = b.ndf
    for node, values in p.loads:
        f[b.row[node]:b.row[node] + nf] += values
    for tag, wy, wx in p.element_loads:
        e = domain.elements[tag]
        q = equivalent_loads(domain, tag, wy, wx)
        f[b.row[e.i]:b.row[e.i] + 3] += q[:3]
        f[b.row[e.j]:b.row[e.j] + 3] += q[3:]
    return f


def element_load_forces(domain, tag, time) -> np.ndarray:
    """The consistent nodal loads (6,) of every element load on ``tag`` at ``time`` (patterns' factors)."""
    out = np.zeros(6)
    for p in domain.patterns.values():
        if p.kind != "Plain" or not p.element_loads:
            continue
        for t, wy, wx in p.element_loads:
            if t == tag:
                out += _factor(domain, p, time) * equivalent_loads(domain, tag, wy, wx)
    return out
