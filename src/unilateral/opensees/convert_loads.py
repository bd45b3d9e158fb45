"""The loads and the analysis of a script's main analysis as the ``[loads]``, ``[analysis]`` and
``[pushover]`` tables of a model file.

A transient analysis (``Newmark 0.5 0.25``, ``n`` steps of ``dt`` from the time ``t0`` the analysis
starts at) becomes ``[analysis]`` with ``method = "direct"``, ``rule = "trapezoidal"``,
``load_sampling = "point"`` (the loads at the step times, as OpenSees reads them) and
``initial = "static"``; the model file's time is ``t - t0``. A ``Plain`` pattern held by
``loadConst`` or of a ``Constant`` series is a constant load; one that follows a ``Linear`` or
``Path`` series gets a table of its factor at the step times the script reaches (``t += dt``), and
a ``UniformExcitation`` a record of its acceleration at those times (one sample a step, plus one
past the end): point sampling reads them back exactly. A ``DisplacementControl`` analysis becomes
``[analysis] type = "pushover"`` with the forces of its ``Linear`` patterns as the pattern and the
displacement the control DOF reached as the target.
"""

from __future__ import annotations

import numpy as np

from .convert_frame import not_convertible
from .eleloads import pattern_forces
from .materials import DIRECTIONS

__all__ = ["transient_tables", "pushover_tables"]


def _dof_names(ndf):
    return tuple(DIRECTIONS[ndf].values())


def _column(values) -> str:
    return "".join(f"{float(x)!r}\n" for x in values)


def _plain_time_function(d, tag, p, times, grid, stem):
    """``(time_function, scale, files)`` of the Plain pattern ``p``: the model file's time function, the
    factor on its loads and the table file it needs."""
    series = d.series[p.series]
    if p.frozen is not None:
        return {"type": "constant"}, p.frozen, {}
    if series.kind == "Constant":
        return {"type": "constant"}, p.factor * series.factor, {}
    values = p.factor * series(times)
    name = f"{stem}.pattern{tag}.txt"
    rows = [f"{float(t)!r} {float(v)!r}\n" for t, v in zip(grid, np.r_[values[0], values])]
    text = f"# time, factor of pattern {tag} at the steps of the analysis (timeSeries {series.kind!r})\n"
    return {"type": "table", "file": name}, 1.0, {name: text + "".join(rows)}


def _nodal(d, p, scale, tf) -> list:
    names = _dof_names(d.ndf)
    out = []
    for node, values in p.loads:
        components = {n: float(v * scale) for n, v in zip(names, values) if v}
        if components:
            out.append({"node": node, **components, "time_function": tf})
    return out


def _distributed(d, p, scale, tf) -> list:
    out = []
    for tag, wy, wx in p.element_loads:
        e = d.elements[tag]
        c, s = np.subtract(d.nodes[e.j], d.nodes[e.i]) / float(np.hypot(*np.subtract(d.nodes[e.j], d.nodes[e.i])))
        out.append({"beam": f"e{tag}", "wx": float((c * wx - s * wy) * scale), "wy": float((s * wx + c * wy) * scale),
                    "time_function": tf})
    return out


def transient_tables(stage, stem, length="m") -> tuple[dict, dict, dict]:
    """``(loads, analysis, files)`` of a transient stage (see the module): the ``[loads]`` and
    ``[analysis]`` tables and ``{file name: text}`` of the tables and records they name."""
    d, N, dt, t0 = stage.domain, stage.steps, stage.dt, stage.t0
    times = np.cumsum(np.r_[t0, np.full(N + 1, dt)])            # t_0 ... t_{N+1} as the script reaches them
    grid = dt * np.arange(-1, N + 2)                              # the model file's times, -dt ... (N+1) dt
    loads, files = {"nodal": [], "distributed": [], "ground_motion": []}, {}
    for tag, p in d.patterns.items():
        if p.kind == "Plain":
            tf, scale, more = _plain_time_function(d, tag, p, times, grid, stem)
            files.update(more)
            loads["nodal"] += _nodal(d, p, scale, tf)
            loads["distributed"] += _distributed(d, p, scale, tf)
            continue
        a = p.factor * d.series[p.series](times)
        if a[0] != 0.0:
            not_convertible(f"pattern('UniformExcitation', {tag}, {p.direction}, ...)", f"its acceleration is "
                            f"{a[0]:.6g} at the start of the transient analysis (t = {t0:g}): the model file's "
                            "analysis starts from the static state without the ground motion", "a record that "
                            "starts at zero ('-prependZero')")
        name = f"{stem}.ground{tag}.txt"
        files[name] = (f"# the ground acceleration of pattern {tag} at the steps of the analysis, dt = {dt!r} "
                       f"(in the length unit of the model per s^2)\n" + _column(a))
        loads["ground_motion"].append({"file": name, "direction": _dof_names(d.ndf)[p.direction - 1],
                                       "units": f"{length}/s2", "dt": float(dt)})
    analysis = {"type": "transient", "dt": float(dt), "t_end": float(N * dt), "method": "direct",
                "rule": "trapezoidal", "lcp": "bpp", "initial": "static", "load_sampling": "point",
                "bilateral_reference": False}
    return {k: v for k, v in loads.items() if v}, analysis, files


def pushover_tables(stage, masses, fixed) -> tuple[dict, dict, dict]:
    """``(loads, analysis, pushover)`` of a DisplacementControl stage: the pattern of its Linear
    patterns, the target the control DOF reached and, for the loads held when it started, a
    ``[loads.gravity]`` if they are ``g`` times the masses (``masses``: the ``[[masses]]`` entries;
    ``fixed``: the support flags of the nodes)."""
    d, b = stage.domain, stage.built
    held, reference = np.zeros(b.mass.size), np.zeros(b.mass.size)
    for tag, p in d.patterns.items():
        if p.kind != "Plain":
            not_convertible(f"pattern('UniformExcitation', {tag}, ...) in a pushover", "a model file's pushover "
                            "takes no ground motion", "remove the pattern")
        f = pattern_forces(b, d, p)
        if p.frozen is not None:
            held += p.frozen * f
        else:
            reference += p.factor * d.series[p.series].factor * f
    held += stage.t0 * reference
    reference *= stage.sign                         # the pattern pushes the control DOF towards the target
    names, nf = _dof_names(d.ndf), d.ndf
    pattern = []
    for tag in d.nodes:
        row = reference[b.row[tag]:b.row[tag] + nf]
        if np.any(row):
            pattern.append({"node": tag, **{n: float(x) for n, x in zip(names, row) if x}})
    loads, gravity = {}, _gravity(d, b, held, masses, fixed)
    if gravity is not None:
        loads["gravity"] = {"g": gravity, "direction": [0.0, -1.0] if d.ndm == 2 else [0.0, 0.0, -1.0]}
    node, dof = stage.control
    table = {"pattern": pattern, "node": node, "dof": names[dof - 1], "target": float(stage.end),
             "control": "displacement", "gravity": gravity is not None, "max_events": 100_000}
    return loads, {"type": "pushover", "lcp": "bpp"}, table


def _gravity(d, b, held, masses, fixed):
    """``g`` if the held loads ``held`` (nodal, on the free DOFs) are ``-g m`` along the vertical of every
    mass ``m`` and nothing else, None if they are zero; otherwise refused."""
    nf, vertical = d.ndf, d.ndm - 1
    m = {entry["node"]: entry["m"] for entry in masses}
    g, expected = None, {}
    for tag in d.nodes:
        row = b.row[tag]
        for k in range(nf):
            if fixed[tag][k]:
                continue
            value = held[row + k]
            weight = m.get(tag, 0.0) if k == vertical else 0.0
            if weight and g is None and value:
                g = -float(value) / weight
            expected[(tag, k)] = (value, weight)
    if g is None and not np.any([v for v, _ in expected.values()]):
        return None
    scale = float(np.max(np.abs(held)))
    if g is not None and g > 0 and all(abs(v + g * w) <= 1e-12 * scale for v, w in expected.values()):
        return g
    not_convertible("a DisplacementControl after loadConst of its gravity loads", "a model file's pushover "
                    "starts from the static state under [loads.gravity], g times every mass, and these loads are "
                    "not g times the masses (nodal loads are not applied in a pushover)", "gravity loads -g m on "
                    "the vertical of every mass (mass and load from the same g), or no held loads")
