"""A 3-storey, 2 x 2-bay building with an eccentric mass on four footings on a half-space.

What it shows
-------------
A :class:`unilateral.structure.Frame3D` model of a reinforced-concrete space frame (units kN, m,
s, t; concrete E = 30 GPa, G = E / 2.4):

* 3 storeys of 3.5 m, 2 x 2 bays of 6 m (a 12 m x 12 m plan, 9 column lines); columns
  0.5 x 0.5 m, floor beams 0.3 x 0.6 m (b x h), elastic 3-D beams (:meth:`Frame3D.beam`);
* a rigid diaphragm per floor (:meth:`Frame3D.rigid_diaphragm`), its master node at the centre of
  the plan holding ``uz``, ``rx``, ``ry`` (the columns carry the vertical loads);
* floor masses of 1 t/m^2 lumped at the column nodes by tributary area (144 t per floor), plus an
  eccentric 30 % of a floor's mass (43.2 t) at the corner column ``(12, 12)`` of every floor: the
  centre of mass of the plan is 1.38 m off the centre along x and y, the centre of stiffness is at
  the centre (the frame is symmetric), so the building twists;
* four rigid footings 2.5 m x 2.5 m (1 m thick, 15.6 t) under the four corner columns, each on 3 x 3
  contact patches (36 unilateral contacts) on one elastic half-space (Vs = 200 m/s, nu = 1/3,
  rho = 2 t/m^3) that couples every patch of every footing to every other
  (:meth:`Frame3D.foundation`, ``horizontal="support"``: the footings do not slide or twist);
  the five inner column lines stand on a grid of grade beams 0.5 x 1.2 m at ground level that
  ties them to the corner footings (the foundation is four footings and a tie-beam grid; the
  grade beams' own mass, 2.5 t/m^3, is lumped at their ends). Under gravity alone the grade beams,
  carrying the inner columns, tilt the three lighter corner footings inwards: their outer corner
  patches are open by about 0.3 mm before the shaking starts;
* Rayleigh damping of 5 % at the first and the sixth period of the structure with its footings
  held (bilateral) on the static soil springs; the soil adds radiation damping of its own.

Gravity is the static state (``initial="static"``). Then two synthetic ground-acceleration
records (:func:`unilateral.loads.synthetic_accelerogram`, Kanai-Tajimi, seeds 11 and 12) act
together along x (PGA 4.5 m/s^2) and y (PGA 4.0 m/s^2), 12 s sampled at 0.01 s, solved with
``dt`` = 0.005 s. One CLCP per step (``method="cq"``: convolution quadrature of the half-space) gives
the uplift of every patch. The same building with every patch held at its static state
(``bilateral=True``: the soil then pulls on the patches, up to about 230 kN) shows what the uplift
changes: here little, a few per cent less peak twist and base torque (the building is squat: the
footings lift one at a time and briefly, while the twist comes from the eccentric mass).

What it prints
--------------
The periods of the bilateral building and their effective modal masses along x, y and in torsion
(the first and third modes couple the diagonal sway with the twist), the centres of mass and of
stiffness (the axis about which lateral floor forces leave the roof untwisted), the weight against
the static soil force, the static load on each footing, the peak opening of each footing and
whether it lifted off entirely (every patch open: the light corner F00, opposite the extra mass,
for about 0.3 s), the peak roof twist and roof displacements, the peak base torque (the torque of
the footings' horizontal supports about the plan's centre, ``-rho^T K u``) with and without
uplift, the run time (about 4 s for the 2400 steps, and as much again for the bilateral run), the
steps and the contact changes. It writes into ``--out`` (default ``building3d_out/``):

* ``building3d.png``: (a) the plan: beams, columns, footings with their patches coloured by
  their peak opening, the centres of mass and of stiffness; (b) the ground accelerations;
  (c) the base torque with and without uplift; (d) the opening of each corner footing (its most
  open patch) against time, shaded where the footing is off the ground entirely; (e) the roof's
  twist ``rz`` with and without uplift; (f), (g) the roof corners' ``ux`` and ``uy``;
* ``building3d.json``: the numbers printed.

Run: ``python examples/building3d.py [--out FOLDER] [--t-end T] [--dt DT] [--no-bilateral]`` (about
ten seconds; ``--t-end 3`` stops just after the first lift-off).
"""

from __future__ import annotations

import argparse
import json
import os
import time
from pathlib import Path

import numpy as np

import unilateral as ul
from unilateral.loads import LoadHistory, synthetic_accelerogram
from unilateral.structure import Frame3D

# ---------------------------------------------------------------------- the model (kN, m, s, t)
STOREYS, HEIGHT = 3, 3.5                    # storeys, storey height (m)
BAYS, SPAN = 2, 6.0                         # bays along x and along y, span (m)
CONCRETE = {"E": 3.0e7, "nu": 0.2}          # kN/m^2
COLUMN, BEAM, GRADE_BEAM = (0.5, 0.5), (0.3, 0.6), (0.5, 1.2)    # b x h (m)
FLOOR_MASS = 1.0                            # t per m^2 of plan
ECCENTRIC = 0.3                             # extra mass at a corner, fraction of a floor's mass
FOOTING, FOOTING_DEPTH, PATCHES = 2.5, 1.0, (3, 3)               # m, m, patches along x and y
DENSITY = 2.5                               # t/m^3 of the footings and grade beams
SOIL = {"model": "halfspace", "Vs": 200.0, "nu": 1 / 3, "rho": 2.0}
ZETA, DAMPED_MODES = 0.05, (1, 6)           # Rayleigh: 5 % at these periods
GRAVITY = 9.81
RECORDS = {"ux": {"pga": 4.5, "seed": 11}, "uy": {"pga": 4.0, "seed": 12}}      # m/s^2
RECORD_DT, DT, T_END = 0.01, 0.005, 12.0    # s: the records' sampling, the time step, the end
#: Openings (m) below this count as closed (round-off of the LCP).
OPEN = 1e-9

NX = NY = BAYS + 1
CENTRE = (SPAN * BAYS / 2, SPAN * BAYS / 2)
ROOF = 1000 + STOREYS                       # the roof's master node
CORNERS = {"F00": (0, 0), "F20": (BAYS, 0), "F02": (0, BAYS), "F22": (BAYS, BAYS)}


def node(floor, ix, iy):
    """Node id of the column line ``(ix, iy)`` at floor ``floor`` (0: the ground)."""
    return 100 * floor + 10 * ix + iy


def master(floor):
    return 1000 + floor


def rect(b, h):
    """Elastic section of a b x h rectangle (b along the local y', h along z'): E, A, Iy, Iz, G, J."""
    E = CONCRETE["E"]
    a, c = max(b, h), min(b, h)
    J = a * c ** 3 * (1 / 3 - 0.21 * c / a * (1 - c ** 4 / (12 * a ** 4)))
    return {"E": E, "A": b * h, "Iy": b * h ** 3 / 12, "Iz": h * b ** 3 / 12, "G": E / (2 * (1 + CONCRETE["nu"])),
            "J": J}


def build(extra_at="corner", rayleigh=None):
    """The building as a :class:`~unilateral.structure.Structure3D`.

    ``extra_at``: where the extra mass of every floor stands, ``"corner"`` (column line (2, 2): the
    eccentric building) or ``"centre"`` (column line (1, 1): a symmetric building).
    ``rayleigh``: the frequencies ``(f1, f2)`` (Hz) of 5 % Rayleigh damping, or None (undamped).
    """
    fr = Frame3D()
    for f in range(STOREYS + 1):
        for ix in range(NX):
            for iy in range(NY):
                fr.node(node(f, ix, iy), SPAN * ix, SPAN * iy, HEIGHT * f)
    for f in range(1, STOREYS + 1):
        fr.node(master(f), *CENTRE, HEIGHT * f)
        fr.support(master(f), ux=False, uy=False, uz=True, rx=True, ry=True, rz=False)
        fr.rigid_diaphragm(master(f), [node(f, ix, iy) for ix in range(NX) for iy in range(NY)])
    column, beam, grade = rect(*COLUMN), rect(*BEAM), rect(*GRADE_BEAM)
    for f in range(STOREYS + 1):
        section = grade if f == 0 else beam
        for ix in range(NX):
            for iy in range(NY):
                if f:
                    fr.beam(f"C{f}.{ix}{iy}", node(f - 1, ix, iy), node(f, ix, iy), vecxz=(1.0, 0.0, 0.0), **column)
                    tributary = (SPAN / 2 if ix in (0, NX - 1) else SPAN) * (SPAN / 2 if iy in (0, NY - 1) else SPAN)
                    fr.mass(node(f, ix, iy), FLOOR_MASS * tributary)
                if ix + 1 < NX:
                    fr.beam(f"BX{f}.{ix}{iy}", node(f, ix, iy), node(f, ix + 1, iy), vecxz=(0.0, 0.0, 1.0),
                            rho=DENSITY if f == 0 else None, **section)
                if iy + 1 < NY:
                    fr.beam(f"BY{f}.{ix}{iy}", node(f, ix, iy), node(f, ix, iy + 1), vecxz=(0.0, 0.0, 1.0),
                            rho=DENSITY if f == 0 else None, **section)
        if f:
            where = (BAYS, BAYS) if extra_at == "corner" else (BAYS // 2, BAYS // 2)
            fr.mass(node(f, *where), ECCENTRIC * FLOOR_MASS * (SPAN * BAYS) ** 2)
    m = DENSITY * FOOTING ** 2 * FOOTING_DEPTH
    J = m * (FOOTING ** 2 + FOOTING_DEPTH ** 2) / 12
    for name, (ix, iy) in CORNERS.items():
        fr.foundation(name, node(0, ix, iy), width=FOOTING, length=FOOTING, soil=SOIL, patches=PATCHES, mass=m,
                      Jx=J, Jy=J)
    if rayleigh is not None:
        fr.rayleigh_from_ratios(ZETA, *rayleigh)
    return fr.build()


# ---------------------------------------------------------------------- properties of the building
def _dense(A):
    return A.toarray() if hasattr(A, "toarray") else np.asarray(A, dtype=float)


def twist_vector(st, centre=CENTRE):
    """``rho`` (n,): the free DOFs of a unit rigid rotation of the building about the vertical axis
    through ``centre`` (``ux = -(y - yc)``, ``uy = x - xc``, ``rz = 1``)."""
    rho = np.zeros(st.n)
    for k, (nd, dof) in enumerate(st.dofs.free):
        x, y, _ = st.coords[nd]
        rho[k] = {"ux": -(y - centre[1]), "uy": x - centre[0], "rz": 1.0}.get(dof, 0.0)
    return rho


def modes(st, model, count=6):
    """Periods (s) of the bilateral building (every patch bonded, the soil's static springs) and the
    effective modal masses (fractions) along x, y and in torsion about the centre.

    The DOFs without mass are condensed statically; ``K`` is the structure's plus ``T Phi(0)^-1 T^T``
    (:meth:`FoundationModel.static_model`)."""
    from scipy.linalg import eigh

    K = _dense(model.static_model().K)
    M = _dense(st.M)
    mass = np.flatnonzero(np.abs(M).sum(axis=1) > 0)
    zero = np.setdiff1d(np.arange(st.n), mass)
    Kmm = K[np.ix_(mass, mass)] - K[np.ix_(mass, zero)] @ np.linalg.solve(K[np.ix_(zero, zero)], K[np.ix_(zero, mass)])
    Mmm = M[np.ix_(mass, mass)]
    w2, phi = eigh(0.5 * (Kmm + Kmm.T), Mmm)                # phi^T M phi = I
    periods = 2 * np.pi / np.sqrt(w2[:count])
    shares = {}
    for label, r in (("x", st.influence("ux")), ("y", st.influence("uy")), ("rz", twist_vector(st))):
        Mr = Mmm @ r[mass]
        shares[label] = (phi[:, :count].T @ Mr) ** 2 / (r[mass] @ Mr)
    return periods, shares


def centre_of_mass(st):
    """``(x, y)`` of the centre of the floors' masses (the same on every floor)."""
    nodes = [node(1, ix, iy) for ix in range(NX) for iy in range(NY)]
    at = {nd: p for p, nd in enumerate(st.dofs.nodes)}
    m = np.array([st.nodal_mass[at[nd], 0] for nd in nodes])
    xy = np.array([st.coords[nd][:2] for nd in nodes])
    return tuple(float(c) for c in m @ xy / m.sum())


def centre_of_stiffness(st, model):
    """``(x, y)`` of the vertical axis through which lateral floor forces (an inverted triangle, the
    floors' masses times their heights) twist the roof by nothing, on the bilateral building with the
    soil's static springs."""
    K = _dense(model.static_model().K)
    index = {key: k for k, key in enumerate(st.dofs.free)}
    floors = range(1, STOREYS + 1)
    P = np.array([f * HEIGHT for f in floors])              # equal floor masses: proportional to the height
    roof_rz = np.linalg.solve(K, np.eye(st.n)[index[master(STOREYS), "rz"]])   # row of K^-1 (K symmetric)
    at = lambda dof: np.array([roof_rz[index[master(f), dof]] for f in floors])
    rz_rz, rz_ux, rz_uy = at("rz") @ P, at("ux") @ P, at("uy") @ P
    return CENTRE[0] - rz_uy / rz_rz, CENTRE[1] + rz_ux / rz_rz


# ---------------------------------------------------------------------- the analysis
def records(t_end=T_END, components=("ux", "uy")):
    """The ground accelerations ``{direction: GroundMotion}`` (m/s^2), sampled at ``RECORD_DT`` whatever
    the time step, ``max(t_end, T_END)`` s long (a shorter run sees the start of the same records)."""
    duration = max(t_end, T_END)
    return {d: synthetic_accelerogram(duration=duration, dt=RECORD_DT, pga=RECORDS[d]["pga"], seed=RECORDS[d]["seed"])
            for d in components}


def loading(st, gms):
    """Gravity and the ground motions: ``LoadHistory``."""
    return LoadHistory(st.gravity(GRAVITY), [st.ground_motion(gm, d) for d, gm in gms.items()])


def analyse(t_end=T_END, dt=DT, extra_at="corner", components=("ux", "uy"), bilateral=True):
    """Build and solve the building; return a dict of the structure, model, solutions and timings."""
    start = time.perf_counter()
    plain = build(extra_at)
    periods, _ = modes(plain, plain.to_model(), count=max(DAMPED_MODES))
    f1, f2 = (1 / periods[k - 1] for k in DAMPED_MODES)
    st = build(extra_at, rayleigh=(f1, f2))
    model = st.to_model()
    gms = records(t_end, components)
    q = loading(st, gms)
    built = time.perf_counter()
    sol = ul.solve(model, q, dt=dt, t_end=t_end, method="cq", initial="static")
    solved = time.perf_counter()
    held = ul.solve(model, q, dt=dt, t_end=t_end, method="cq", initial="static", bilateral=True) if bilateral else None
    return {"structure": st, "model": model, "records": gms, "sol": sol, "bilateral": held,
            "rayleigh_hz": (f1, f2), "build_s": built - start, "solve_s": solved - built,
            "bilateral_s": time.perf_counter() - solved}


def footing_columns(st):
    """``{footing name: columns of its patches in sol.v}``."""
    first = st.foundation.first
    out, k = {}, first
    for fnd in st.foundation.footings:
        out[fnd.name] = np.arange(k, k + fnd.m)
        k += fnd.m
    return out


def base_torque(st, model, sol):
    """Torque (N+1,) about the vertical axis through the plan's centre that the footings' horizontal
    supports exert on the building, kN m: ``-rho^T K u`` (``rho``: :func:`twist_vector`; the elements
    do no work in a rigid rotation, and the soil's vertical forces none in a twist)."""
    return -np.asarray(_dense(model.K) @ sol.u.T).T @ twist_vector(st)


def summarise(run) -> dict:
    """The numbers printed and written to ``building3d.json``."""
    st, model, sol, held = run["structure"], run["model"], run["sol"], run["bilateral"]
    periods, shares = modes(st, model)
    cols = footing_columns(st)
    c0, v0 = -sol.psi[0], sol.v[0]
    openings = sol.v
    footings = {}
    for name, j in cols.items():
        v = openings[:, j]
        off = v.min(axis=1) > OPEN
        footings[name] = {"static_load_kN": float(c0[j].sum()),
                          "statically_open_patches": int(np.count_nonzero(v0[j] > OPEN)),
                          "peak_opening_mm": 1e3 * float(v.max()),
                          "peak_lift_off_mm": 1e3 * float(v.min(axis=1).max()),
                          "lift_off_s": float(np.count_nonzero(off[1:]) * (sol.t[1] - sol.t[0])),
                          "first_lift_off_s": float(sol.t[np.argmax(off)]) if off.any() else None}
    height = STOREYS * HEIGHT
    roof = {d: st.node_displacement(sol, ROOF, d) for d in ("ux", "uy", "rz")}
    corners = {f"{ix}{iy}": {d: st.node_displacement(sol, node(STOREYS, ix, iy), d) for d in ("ux", "uy")}
               for ix, iy in ((0, 0), (BAYS, BAYS))}
    out = {"model": {"storeys": STOREYS, "storey_height_m": HEIGHT, "bays": [BAYS, BAYS], "span_m": SPAN,
                     "column_m": COLUMN, "beam_m": BEAM, "grade_beam_m": GRADE_BEAM,
                     "floor_mass_t": FLOOR_MASS * (SPAN * BAYS) ** 2, "extra_mass_t": ECCENTRIC * FLOOR_MASS *
                     (SPAN * BAYS) ** 2, "footing_m": FOOTING, "patches": list(PATCHES), "soil": SOIL,
                     "records": RECORDS, "dt_s": float(sol.t[1] - sol.t[0]), "t_end_s": float(sol.t[-1]),
                     "n": int(st.n), "m": int(model.m), "rayleigh_hz": list(run["rayleigh_hz"])},
           "weight_kN": float(-st.gravity(GRAVITY) @ st.influence("uz")), "static_soil_force_kN": float(c0.sum()),
           "periods_s": periods.tolist(), "modal_mass": {k: v.tolist() for k, v in shares.items()},
           "centre_of_mass_m": list(centre_of_mass(st)), "centre_of_stiffness_m": list(centre_of_stiffness(st, model)),
           "success": bool(sol.success), "message": sol.message, "steps": int(len(sol.t) - 1),
           "contact_changes": int(sol.stats.get("contact_changes", 0)),
           "run_time_s": run["build_s"] + run["solve_s"], "solve_s": run["solve_s"],
           "footings": footings,
           "steps_with_an_open_patch": int(np.count_nonzero((sol.v[1:] > OPEN).any(axis=1))),
           "statically_open_patches": int(np.count_nonzero(v0 > OPEN)),
           "patches_that_open_in_the_shaking": int(np.count_nonzero((v0 <= OPEN) & (sol.v[1:] > OPEN).any(axis=0))),
           "peak_roof_twist_rad": float(np.abs(roof["rz"]).max()),
           "peak_roof_mm": {d: 1e3 * float(np.abs(roof[d]).max()) for d in ("ux", "uy")},
           "peak_roof_drift_ratio": {d: float(np.abs(roof[d]).max() / height) for d in ("ux", "uy")},
           "peak_roof_corner_mm": {k: {d: 1e3 * float(np.abs(h).max()) for d, h in c.items()}
                                   for k, c in corners.items()},
           "peak_base_torque_kNm": float(np.abs(base_torque(st, model, sol)).max())}
    if held is not None:
        out["bilateral"] = {"success": bool(held.success),
                            "peak_roof_twist_rad": float(np.abs(st.node_displacement(held, ROOF, "rz")).max()),
                            "peak_roof_mm": {d: 1e3 * float(np.abs(st.node_displacement(held, ROOF, d)).max())
                                             for d in ("ux", "uy")},
                            "peak_base_torque_kNm": float(np.abs(base_torque(st, model, held)).max()),
                            "peak_patch_tension_kN": float(max(0.0, held.psi.max())),
                            "solve_s": run["bilateral_s"]}
    return out


def report(s) -> str:
    """The text summary of :func:`summarise`'s dict."""
    lines = ["periods of the bilateral building (footings bonded, static soil springs), effective modal mass "
             "x / y / torsion:"]
    for k, T in enumerate(s["periods_s"]):
        shares = " / ".join(f"{100 * s['modal_mass'][d][k]:4.1f} %" for d in ("x", "y", "rz"))
        lines.append(f"  T{k + 1} = {T:.3f} s   {shares}")
    lines.append("centre of mass ({:.2f}, {:.2f}) m, centre of stiffness ({:.2f}, {:.2f}) m".format(
        *s["centre_of_mass_m"], *s["centre_of_stiffness_m"]))
    lines.append(f"weight {s['weight_kN']:.1f} kN, static soil force {s['static_soil_force_kN']:.1f} kN; "
                 f"{s['model']['m']} contact patches, {s['model']['n']} DOFs")
    lines.append(f"solve: {s['message']} (success {s['success']}), build + solve {s['run_time_s']:.2f} s")
    for name, f in s["footings"].items():
        off = (f"lifts off entirely for {f['lift_off_s']:.2f} s (first at t = {f['first_lift_off_s']:.2f} s, "
               f"by up to {f['peak_lift_off_mm']:.2f} mm)" if f["first_lift_off_s"] is not None
               else "never off the ground entirely")
        lines.append(f"footing {name}: static load {f['static_load_kN']:.0f} kN, peak opening "
                     f"{f['peak_opening_mm']:.2f} mm, {off}")
    lines.append(f"patches open under gravity alone: {s['statically_open_patches']} (the grade beams tilt the corner "
                 f"footings inwards); patches that open in the shaking: {s['patches_that_open_in_the_shaking']} of "
                 f"{s['model']['m']}")
    lines.append(f"peak roof twist rz: {1e3 * s['peak_roof_twist_rad']:.3f} mrad; peak roof ux "
                 f"{s['peak_roof_mm']['ux']:.1f} mm, uy {s['peak_roof_mm']['uy']:.1f} mm (drift ratios "
                 f"{100 * s['peak_roof_drift_ratio']['ux']:.2f} %, {100 * s['peak_roof_drift_ratio']['uy']:.2f} %)")
    lines.append(f"peak base torque: {s['peak_base_torque_kNm']:.0f} kN m")
    if "bilateral" in s:
        b = s["bilateral"]
        lines.append(f"footings held (bilateral): peak roof twist {1e3 * b['peak_roof_twist_rad']:.3f} mrad, roof ux "
                     f"{b['peak_roof_mm']['ux']:.1f} mm, uy {b['peak_roof_mm']['uy']:.1f} mm, base torque "
                     f"{b['peak_base_torque_kNm']:.0f} kN m, peak patch tension {b['peak_patch_tension_kN']:.0f} kN")
        twist = s["peak_roof_twist_rad"] / b["peak_roof_twist_rad"] - 1
        torque = s["peak_base_torque_kNm"] / b["peak_base_torque_kNm"] - 1
        lines.append(f"uplift changes the peak twist by {100 * twist:+.0f} % and the peak base torque by "
                     f"{100 * torque:+.0f} %")
    return "\n".join(lines)


# ---------------------------------------------------------------------- the figure
def draw(run, s, path):
    """``building3d.png`` (see the module docstring), written atomically."""
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib import cm, colors
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    st, model, sol, held = run["structure"], run["model"], run["sol"], run["bilateral"]
    t = sol.t
    fig = Figure(figsize=(13.0, 11.0), layout="constrained")
    grid = fig.add_gridspec(4, 2, width_ratios=(1.0, 1.35))
    plan = fig.add_subplot(grid[0:2, 0])
    ax_g, ax_T = fig.add_subplot(grid[2, 0]), fig.add_subplot(grid[3, 0])
    right = [fig.add_subplot(grid[k, 1]) for k in range(4)]
    for ax in [ax_T] + right[1:]:
        ax.sharex(ax_g)

    # (a) the plan
    cols = footing_columns(st)
    openings = sol.v
    peak = {name: openings[:, j].max(axis=0) for name, j in cols.items()}
    vmax = 1e3 * max(p.max() for p in peak.values()) or 1.0
    norm, cmap = colors.Normalize(0.0, vmax), matplotlib.colormaps["viridis"]
    L = SPAN * BAYS
    for k in range(NX):
        plan.plot([SPAN * k, SPAN * k], [0, L], color="0.55", lw=3, zorder=1)
        plan.plot([0, L], [SPAN * k, SPAN * k], color="0.55", lw=3, zorder=1)
    for fnd in st.foundation.footings:
        for (x, y), (a, b), v in zip(fnd.patches.centres, fnd.patches.sizes, peak[fnd.name]):
            plan.add_patch(Rectangle((x - a / 2, y - b / 2), a, b, facecolor=cmap(norm(1e3 * v)), edgecolor="k",
                                     lw=0.5, zorder=2))
        x0, y0 = st.coords[fnd.node][:2]
        plan.add_patch(Rectangle((x0 - fnd.width / 2, y0 - fnd.length / 2), fnd.width, fnd.length, fill=False,
                                 edgecolor="k", lw=1.5, zorder=3))
        f = s["footings"][fnd.name]
        dy = fnd.length / 2 + 0.25
        plan.text(x0, y0 - dy if y0 < CENTRE[1] else y0 + dy, f"{fnd.name}: peak {f['peak_opening_mm']:.1f} mm"
                  + (f"\noff {f['lift_off_s']:.2f} s" if f["first_lift_off_s"] is not None else ""),
                  ha="center", va="top" if y0 < CENTRE[1] else "bottom", fontsize=8)
    for ix in range(NX):
        for iy in range(NY):
            plan.add_patch(Rectangle((SPAN * ix - COLUMN[0] / 2, SPAN * iy - COLUMN[1] / 2), *COLUMN, color="0.2",
                                     zorder=4))
    xm, ym = s["centre_of_mass_m"]
    xs, ys = s["centre_of_stiffness_m"]
    plan.plot(xs, ys, "s", ms=9, mfc="none", mec="tab:blue", mew=2, zorder=5, label="centre of stiffness")
    plan.plot(xm, ym, "o", ms=9, color="tab:red", zorder=5, label="centre of mass")
    plan.plot(L, L, "*", ms=16, color="tab:orange", mec="k", zorder=5,
              label=f"extra mass {s['model']['extra_mass_t']:.0f} t per floor")
    plan.set(xlim=(-2.5, L + 2.5), ylim=(-3.2, L + 3.2), aspect="equal", xlabel="x [m]", ylabel="y [m]",
             title="(a) plan: footings, patches coloured by their peak opening")
    plan.legend(loc="center", fontsize=8, framealpha=0.9, bbox_to_anchor=(0.5, 0.72))
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=plan, shrink=0.7, label="peak opening of the patch [mm]")

    # (b) the ground motions
    for (d, gm), colour in zip(run["records"].items(), ("tab:blue", "tab:red")):
        ax_g.plot(t, gm(t), color=colour, lw=0.7, label=f"{d[-1]} (PGA {RECORDS[d]['pga']:g} m/s$^2$)")
    ax_g.set(ylabel="ground acceleration [m/s$^2$]", title="(b) ground accelerations")
    ax_g.legend(fontsize=8, loc="upper right")

    # (c) base torque
    ax_T.plot(t, 1e-3 * base_torque(st, model, sol), color="k", lw=0.8, label="with uplift")
    if held is not None:
        ax_T.plot(t, 1e-3 * base_torque(st, model, held), color="tab:orange", lw=0.8, ls="--",
                  label="footings held (bilateral)")
    ax_T.set(xlabel="time [s]", ylabel="base torque [MN m]", title="(c) torque of the footings on the building "
             "about the plan's centre")
    ax_T.legend(fontsize=8, loc="upper right")

    # (d) uplift of each footing
    ax = right[0]
    palette = dict(zip(CORNERS, ("tab:blue", "tab:green", "tab:purple", "tab:red")))
    for name, j in cols.items():
        v = 1e3 * openings[:, j]
        x0, y0 = st.coords[node(0, *CORNERS[name])][:2]
        ax.plot(t, v.max(axis=1), color=palette[name], lw=0.8, label=f"{name} at ({x0:g}, {y0:g}) m")
        off = openings[:, j].min(axis=1) > OPEN
        ax.fill_between(t, 0, v.max(axis=1), where=off, color=palette[name], alpha=0.3, lw=0)
    ax.set(ylabel="largest patch opening [mm]", title="(d) uplift of the corner footings (shaded: the whole "
           "footing off the ground)")
    ax.legend(fontsize=8, loc="upper right", ncol=2)

    # (e) roof twist
    ax = right[1]
    ax.plot(t, 1e3 * st.node_displacement(sol, ROOF, "rz"), color="k", lw=0.8, label="with uplift")
    if held is not None:
        ax.plot(t, 1e3 * st.node_displacement(held, ROOF, "rz"), color="tab:orange", lw=0.8, ls="--",
                label="footings held (bilateral)")
    ax.set(ylabel="roof twist rz [mrad]", title="(e) twist of the roof")
    ax.legend(fontsize=8, loc="upper right")

    # (f), (g) roof corners
    for ax, d, letter in ((right[2], "ux", "f"), (right[3], "uy", "g")):
        for (ix, iy), colour in (((0, 0), "tab:blue"), ((BAYS, BAYS), "tab:red")):
            ax.plot(t, 1e3 * st.node_displacement(sol, node(STOREYS, ix, iy), d), color=colour, lw=0.8,
                    label=f"corner ({SPAN * ix:g}, {SPAN * iy:g})")
        ax.plot(t, 1e3 * st.node_displacement(sol, ROOF, d), color="k", lw=0.6, ls=":", label="centre")
        ax.set(ylabel=f"roof {d} [mm]", title=f"({letter}) roof {d} relative to the ground, with uplift")
        ax.legend(fontsize=8, loc="upper right", ncol=3)
    right[3].set_xlabel("time [s]")
    for ax in [ax_g, ax_T] + right:
        ax.axhline(0.0, color="0.7", lw=0.5)
        ax.set_xlim(t[0], t[-1])
    fig.suptitle(f"3-storey 2 x 2-bay building, eccentric mass, 4 footings on a half-space (Vs = {SOIL['Vs']:g} m/s), "
                 "two horizontal ground motions", fontsize=11)
    _atomic(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))


def _atomic(path, write):
    """Write ``path`` through a temporary file in the same folder, then rename it into place."""
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        write(tmp)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def main(argv=None) -> dict:
    """Run the example: print the summary, write ``building3d.png`` and ``building3d.json`` to
    ``--out``; return the summary dict (with the paths under ``"files"``)."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path, default=Path("building3d_out"), help="output folder")
    parser.add_argument("--t-end", type=float, default=T_END, help=f"end time, s (default {T_END:g})")
    parser.add_argument("--dt", type=float, default=DT, help=f"time step, s (default {DT:g})")
    parser.add_argument("--no-bilateral", action="store_true", help="skip the run with the footings held")
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    run = analyse(args.t_end, args.dt, bilateral=not args.no_bilateral)
    s = summarise(run)
    print(report(s))
    png, js = args.out / "building3d.png", args.out / "building3d.json"
    draw(run, s, png)
    _atomic(js, lambda tmp: Path(tmp).write_text(json.dumps(s, indent=1) + "\n", encoding="utf-8"))
    print(f"wrote {png} and {js}")
    return s | {"files": [str(png), str(js)]}


if __name__ == "__main__":
    main()
