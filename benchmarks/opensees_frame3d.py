"""3-D frames on compression-only supports against OpenSees: the same model, rule and dt.

Asymmetric space frames of elastic beam-columns whose column bases stand on compression-only
vertical springs, loaded by gravity (the static state) and then by two horizontal components of
ground acceleration. Each frame is described once (:func:`layout`: nodes, supports, beams with
their sections and ``vecxz``, rigid diaphragms and links, springs, lumped masses) and built twice:

* with :class:`unilateral.structure.Frame3D` (``Frame3D.soil(name, node, k)``: a tensionless
  spring along ``uz``, one unilateral unknown) and solved by ``method="direct"`` with the
  trapezoidal rule (Newmark's average acceleration) on point samples of the load
  ``q(t) = gravity - M (r_x a_x(t) + r_y a_y(t))`` (``Structure3D.ground_motion``), from the
  static state under ``q(0)`` (``initial="static"``; both records are zero at ``t = 0``);
* in OpenSees (``model basic -ndm 3 -ndf 6``; ``elasticBeamColumn`` with ``geomTransf Linear``
  and the same ``vecxz``; a ``zeroLength`` element with an ``ENT`` (elastic no-tension) material
  in direction 3 from a fixed ground node to each spring node; ``rigidDiaphragm 3`` and
  ``rigidLink beam`` with the ``Transformation`` constraint handler; a static gravity analysis,
  ``loadConst -time 0``, then ``rayleigh a0 0 0 0``, two ``UniformExcitation`` patterns (directions
  1 and 2) of ``Path`` series of the same samples, ``Newmark 0.5 0.25``, ``Newton``,
  ``NormDispIncr 1e-12``).

Damping is mass-proportional only (``a0 M``), for the reason given in ``opensees_frames.py``.
Masses are lumped on the translations of the frame's nodes (no rotary inertia): a node in a rigid
diaphragm carries its mass to the master through ``T^T M T`` in both codes, and gravity acts on the
same nodal masses.

The frames:

* ``2-storey``: 2 x 1 bays (6 m x 5 m), storeys 3.5 m; rectangular columns (unequal: the line
  ``x = 0`` is stiffer) and beams with ``Iy != Iz`` so that the local axes matter (columns
  ``vecxz = (1, 0, 0)``, except those on the line ``x = 12`` with ``vecxz = (0, 1, 0)``; beams
  ``vecxz = (0, 0, 1)``); floor masses of 1 t/m^2 lumped at the nodes by tributary area plus 20 t at
  the corner ``(12, 5)`` of each floor (eccentric); no diaphragm. Each column base
  node holds ``ux, uy, rx, ry, rz`` and stands on one tensionless spring (6 contacts, 78 DOFs).
* ``building`` (the example building): 3 storeys, 3 x 2 bays (6 m x 5 m), a rigid diaphragm per
  floor (master at the centre of the plan, holding ``uz, rx, ry``; no mass on it); columns
  0.4 x 0.5 m (the line ``x = 0``: 0.5 x 0.6 m), beams, local axes (the last column line
  ``vecxz = (0, 1, 0)``) and masses as in the 2-storey frame (30 t at the corner of each floor).
  The 10 perimeter columns stand on rigid square footings (1.6 m): the base node is tied by
  ``rigid_link`` / ``rigidLink beam`` to four corner nodes, each on a tensionless spring, and held
  by linear springs along ``ux``, ``uy`` and about ``rz`` (``Frame3D.spring`` / ``zeroLength``
  ``Elastic``); the 2 interior columns stand on one spring each, base ``ux, uy, rx, ry, rz`` held
  (42 contacts, 179 DOFs).

Why the footings are held by springs and not by supports: with ``constraints Transformation`` a
``fix`` on the retained node of a ``rigidLink`` gives OpenSees a different transient response
(3e-5 of the displacement at the first step, of the order of the peak within two seconds)
although its static gravity state agrees to round-off; ``constraints Lagrange`` on the same model agrees with the
project to round-off (but fails on ``rigidDiaphragm``), and so does ``Transformation`` once the
retained node carries no ``fix``. The ``fix`` on a diaphragm's master (``uz, rx, ry``, not among
the retained DOFs) is harmless.

Rocking on tensionless springs amplifies small perturbations, the more so the stronger the shaking
and the stiffer the springs under the massless footings. The column ``1e-13 sensitivity`` of the
table measures it for each run: the project against itself with the x record scaled by
``1 + 1e-13``. The difference between the two codes (whose round-off differs) is to be read against
it, and the records are scaled so that it stays well below 1e-8 (measured over 20 s): at 6 and
5 m/s^2 the 2-storey frame turns 1e-13 into 1.6e-7 of its peak, and the codes then differ by 1.1e-7
although they agree to 1e-12 over the first 3 s; the building at 5 and 4 m/s^2 turns 1e-15 into
2e-8 (and differs from OpenSees by 4.5e-8), with springs of 5e5 kN/m into 5e-3. Hence 5 and 4 m/s^2
for the 2-storey frame (sensitivity 4e-10) and 3 and 2.5 m/s^2 for the building (3e-11); springs
still open in 40 to 65 % of the steps.

``python benchmarks/opensees_frame3d.py`` prints a table (end-to-end times: build + solve; the
roof-corner ``ux``, ``uy``, ``rz`` differences over their peaks; the steps with an open spring) and
writes ``benchmarks/results/opensees_frame3d.json``. OpenSees runs in a subprocess with its
library path (:func:`opensees_frames.opensees_environment`), BLAS in one thread in both.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

if __name__ == "__main__":                  # before numpy is imported: BLAS in one thread in both codes
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from opensees_frames import opensees_environment, record, record_samples  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
DOFS = ("ux", "uy", "uz", "rx", "ry", "rz")
#: The roof-corner histories compared.
COMPARED = ("ux", "uy", "rz")
#: The constraint handler and the system of equations of the OpenSees analyses. BandSPD was the
#: fastest on the example building (400 steps: BandSPD 1.7 s, BandGeneral 2.0 s, UmfPack 2.2 s,
#: FullGeneral 2.4 s, SparseGeneral 2.6 s, ProfileSPD 4.7 s; SparseSYM fails the gravity analysis);
#: the time goes to OpenSees's element loop and constraint handling rather than the solver.
CONSTRAINTS = ("Transformation",)
SYSTEM = "BandSPD"


def rect(b, h, E=30e6, nu=0.25):
    """Section of a b x h rectangle (b along the local y', h along the local z'): E, A, Iy, Iz, G, J."""
    a, c = max(b, h), min(b, h)
    J = a * c ** 3 * (1 / 3 - 0.21 * c / a * (1 - c ** 4 / (12 * a ** 4)))
    return {"E": E, "A": b * h, "Iy": b * h ** 3 / 12, "Iz": h * b ** 3 / 12, "G": E / (2 * (1 + nu)), "J": J}


@dataclass(frozen=True)
class Frame3DSpec:
    """A regular space frame on tensionless springs (kN, m, s, t); see the module docstring."""

    name: str = "2-storey"
    storeys: int = 2
    bays_x: int = 2
    bays_y: int = 1
    span_x: float = 6.0
    span_y: float = 5.0
    height: float = 3.5
    column: tuple = (0.35, 0.5)             # b, h (m): along local y', z'
    column_stiff: tuple = (0.45, 0.6)       # the columns of the line x = 0 (unequal columns)
    beam: tuple = (0.3, 0.5)
    floor_mass: float = 1.0                 # t per m^2 of plan, lumped at the floor's nodes by tributary area
    corner_mass: float = 20.0               # t added at the floor corner (x_max, y_max): the eccentricity
    k_soil: float = 1.5e5                   # kN/m per spring
    diaphragm: bool = False
    footing: float = 0.0                    # width (m) of the square footings of the perimeter columns (0: none)
    k_horizontal: float = 1e6               # kN/m of a footing's linear springs along ux, uy (rz: k b^2 / 6)
    zeta: float = 0.05                      # a0 = 2 zeta w with w = 2 pi / period
    period: float = 0.4
    pga: tuple = (5.0, 4.0)                 # m/s^2 of the components along x and y
    seeds: tuple = (3, 7)
    gravity: float = 9.81


FRAMES = (
    Frame3DSpec(),
    Frame3DSpec(name="building", storeys=3, bays_x=3, bays_y=2, column=(0.4, 0.5), column_stiff=(0.5, 0.6),
                corner_mass=30.0, diaphragm=True, footing=1.6, k_soil=2e5, period=0.5, pga=(3.0, 2.5)),
)


@dataclass
class Layout:
    """A frame described once, for both codes."""

    coords: dict = field(default_factory=dict)          # node -> (x, y, z)
    fixes: dict = field(default_factory=dict)           # node -> 6 flags (ux, uy, uz, rx, ry, rz)
    beams: list = field(default_factory=list)           # (name, i, j, section, vecxz)
    diaphragms: list = field(default_factory=list)      # (master, slaves)
    links: list = field(default_factory=list)           # (master, slave)
    springs: list = field(default_factory=list)         # (name, node, k)
    linear: list = field(default_factory=list)          # (name, node, k, dof): linear springs to the ground
    masses: dict = field(default_factory=dict)          # node -> m (translations)
    roof: int = 0                                       # the roof corner compared


def node_id(floor, ix, iy):
    return 10_000 * floor + 100 * ix + iy


def layout(spec: Frame3DSpec) -> Layout:
    """Nodes, supports, members, springs and masses of ``spec`` (see the module docstring)."""
    lay = Layout()
    nx, ny = spec.bays_x + 1, spec.bays_y + 1
    xs, ys = spec.span_x * np.arange(nx), spec.span_y * np.arange(ny)
    for f in range(spec.storeys + 1):
        for ix in range(nx):
            for iy in range(ny):
                lay.coords[node_id(f, ix, iy)] = (float(xs[ix]), float(ys[iy]), f * spec.height)
    beam_section = rect(*spec.beam)
    for f in range(1, spec.storeys + 1):
        for ix in range(nx):
            for iy in range(ny):
                stiff = ix == 0
                section = rect(*(spec.column_stiff if stiff else spec.column))
                vecxz = (0.0, 1.0, 0.0) if ix == nx - 1 else (1.0, 0.0, 0.0)
                lay.beams.append((f"C{f}_{ix}{iy}", node_id(f - 1, ix, iy), node_id(f, ix, iy), section, vecxz))
                if ix + 1 < nx:
                    lay.beams.append((f"BX{f}_{ix}{iy}", node_id(f, ix, iy), node_id(f, ix + 1, iy), beam_section,
                                      (0.0, 0.0, 1.0)))
                if iy + 1 < ny:
                    lay.beams.append((f"BY{f}_{ix}{iy}", node_id(f, ix, iy), node_id(f, ix, iy + 1), beam_section,
                                      (0.0, 0.0, 1.0)))
                wx = spec.span_x * (0.5 if ix in (0, nx - 1) else 1.0)
                wy = spec.span_y * (0.5 if iy in (0, ny - 1) else 1.0)
                lay.masses[node_id(f, ix, iy)] = spec.floor_mass * wx * wy
        lay.masses[node_id(f, nx - 1, ny - 1)] += spec.corner_mass
        if spec.diaphragm:
            master = 900_000 + f
            lay.coords[master] = (float(xs[-1]) / 2, float(ys[-1]) / 2, f * spec.height)
            lay.fixes[master] = (False, False, True, True, True, False)
            lay.diaphragms.append((master, [node_id(f, ix, iy) for ix in range(nx) for iy in range(ny)]))
    corner = 0
    for ix in range(nx):
        for iy in range(ny):
            base = node_id(0, ix, iy)
            perimeter = ix in (0, nx - 1) or iy in (0, ny - 1)
            if not (spec.footing and perimeter):
                lay.fixes[base] = (True, True, False, True, True, True)
                lay.springs.append((f"S{ix}{iy}", base, spec.k_soil))
                continue
            # a rigid square footing: its node free in all six DOFs, on linear springs along ux, uy
            # and about rz (no support on the retained node of a rigid link, see the docstring)
            h = spec.footing / 2
            lay.linear += [(f"H{ix}{iy}{d}", base, spec.k_horizontal, d) for d in ("ux", "uy")]
            lay.linear.append((f"H{ix}{iy}rz", base, spec.k_horizontal * spec.footing ** 2 / 6, "rz"))
            x, y, _ = lay.coords[base]
            for k, (dx, dy) in enumerate([(-h, -h), (h, -h), (-h, h), (h, h)]):
                corner += 1
                node = 800_000 + corner
                lay.coords[node] = (x + dx, y + dy, 0.0)
                lay.links.append((base, node))
                lay.springs.append((f"S{ix}{iy}_{k}", node, spec.k_soil))
    lay.roof = node_id(spec.storeys, nx - 1, ny - 1)
    return lay


def rayleigh_a0(spec):
    return 2 * spec.zeta * 2 * np.pi / spec.period


def records(spec, dt, t_end):
    """The two ground-acceleration records (x, y) of ``spec``."""
    return [record(duration=t_end, dt=dt, pga=pga, seed=seed) for pga, seed in zip(spec.pga, spec.seeds)]


# ---------------------------------------------------------------------- the project
def frame3d(spec: Frame3DSpec):
    """The :class:`~unilateral.structure.Structure3D` of ``spec`` and its layout."""
    from unilateral.structure import Frame3D

    lay = layout(spec)
    fr = Frame3D()
    for node, xyz in lay.coords.items():
        fr.node(node, *xyz)
    for node, flags in lay.fixes.items():
        fr.support(node, **dict(zip(DOFS, flags)))
    for master, slaves in lay.diaphragms:
        fr.rigid_diaphragm(master, slaves)
    for master, slave in lay.links:
        fr.rigid_link(master, slave)
    for name, i, j, section, vecxz in lay.beams:
        fr.beam(name, i, j, vecxz=vecxz, **section)
    for name, node, k in lay.springs:
        fr.soil(name, node, k)
    for name, node, k, dof in lay.linear:
        fr.spring(name, node, k, direction=dof)
    for node, m in lay.masses.items():
        fr.mass(node, m)
    fr.rayleigh(rayleigh_a0(spec), 0.0)
    return fr.build(), lay


def run_unilateral(spec, gms, dt, t_end):
    """Roof-corner histories {dof: (N+1,)}, wall time (build + solve) and the solution."""
    import unilateral as ul

    start = time.perf_counter()
    st, lay = frame3d(spec)
    model = st.to_model()
    N = int(round(t_end / dt))
    t = np.arange(N + 1) * dt
    q = np.repeat(st.gravity(spec.gravity)[None, :], N + 1, axis=0)
    for gm, direction in zip(gms, ("ux", "uy")):
        p, a_g = st.ground_motion(gm, direction)         # (-M r, a_g)
        q += np.outer(a_g(t), p)
    sol = ul.solve(model, q, dt=dt, t_end=t_end, method="direct", rule="trapezoidal", initial="static")
    elapsed = time.perf_counter() - start
    if not sol.success:
        raise RuntimeError(sol.message)
    roof = {dof: st.node_displacement(sol, lay.roof, dof) for dof in COMPARED}
    return roof, elapsed, sol


# ---------------------------------------------------------------------- OpenSees
def build_opensees(ops, spec):
    """The frame of ``spec`` in OpenSees (``ops``: the ``openseespy.opensees`` module), fresh, with
    gravity on its nodal masses; returns the layout."""
    lay = layout(spec)
    ops.wipe()
    ops.model("basic", "-ndm", 3, "-ndf", 6)
    for node, xyz in lay.coords.items():
        ops.node(node, *xyz)
    for node, flags in lay.fixes.items():
        ops.fix(node, *map(int, flags))
    for master, slaves in lay.diaphragms:
        ops.rigidDiaphragm(3, master, *slaves)
    for master, slave in lay.links:
        ops.rigidLink("beam", master, slave)
    ops.uniaxialMaterial("ENT", 1, spec.k_soil)             # every spring has k_soil
    tag = 0
    for name, i, j, s, vecxz in lay.beams:
        tag += 1
        ops.geomTransf("Linear", tag, *vecxz)
        ops.element("elasticBeamColumn", tag, i, j, s["A"], s["E"], s["G"], s["J"], s["Iy"], s["Iz"], tag)
    for name, node, k in lay.springs:
        assert k == spec.k_soil
        tag += 1
        ground = 700_000 + tag
        ops.node(ground, *lay.coords[node])
        ops.fix(ground, 1, 1, 1, 1, 1, 1)
        ops.element("zeroLength", tag, ground, node, "-mat", 1, "-dir", 3)
    for name, node, k, dof in lay.linear:
        tag += 1
        ground = 700_000 + tag
        ops.node(ground, *lay.coords[node])
        ops.fix(ground, 1, 1, 1, 1, 1, 1)
        ops.uniaxialMaterial("Elastic", tag, k)
        ops.element("zeroLength", tag, ground, node, "-mat", tag, "-dir", DOFS.index(dof) + 1)
    for node, m in lay.masses.items():
        ops.mass(node, m, m, m, 0.0, 0.0, 0.0)
    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for node, m in lay.masses.items():
        ops.load(node, 0.0, 0.0, -m * spec.gravity, 0.0, 0.0, 0.0)
    return lay


def _analysis(ops, kind):
    ops.wipeAnalysis()
    ops.constraints(*CONSTRAINTS)
    ops.numberer("RCM")
    ops.system(SYSTEM)
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    if kind == "Static":
        ops.integrator("LoadControl", 1.0)
    else:
        ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis(kind)


def run_opensees(spec, samples, dt, t_end):
    """Roof-corner histories {dof: (N+1,)}, wall time (build + solve), the first failed step (0: none)
    and the number of steps with an open spring (its node above the ground); in this process."""
    import openseespy.opensees as ops

    start = time.perf_counter()
    lay = build_opensees(ops, spec)
    _analysis(ops, "Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees: the gravity analysis failed")
    ops.loadConst("-time", 0.0)
    ops.rayleigh(rayleigh_a0(spec), 0.0, 0.0, 0.0)
    for direction, values in enumerate(samples, start=1):
        ops.timeSeries("Path", 10 + direction, "-dt", dt, "-values", *values)
        ops.pattern("UniformExcitation", 10 + direction, direction, "-accel", 10 + direction)
    _analysis(ops, "Transient")
    N = int(round(t_end / dt))
    columns = [DOFS.index(d) + 1 for d in COMPARED]
    springs = [node for _, node, _ in lay.springs]
    roof = np.zeros((N + 1, len(COMPARED)))
    roof[0] = [ops.nodeDisp(lay.roof, c) for c in columns]
    failed = open_steps = 0
    counting = 0.0                                      # the uplift count is not OpenSees's work: not timed
    for k in range(1, N + 1):
        if ops.analyze(1, dt) != 0:
            failed = k
            break
        roof[k] = [ops.nodeDisp(lay.roof, c) for c in columns]
        tic = time.perf_counter()
        open_steps += max(ops.nodeDisp(node, 3) for node in springs) > 0.0
        counting += time.perf_counter() - tic
    elapsed = time.perf_counter() - start - counting
    ops.wipe()
    return dict(zip(COMPARED, roof.T)), elapsed, failed, open_steps


def _tuples(value):
    return tuple(_tuples(v) for v in value) if isinstance(value, list) else value


def opensees_in_subprocess(spec, samples, dt, t_end):
    """:func:`run_opensees` in a fresh process with the library path it needs; None without OpenSees."""
    env = opensees_environment()
    if env is None:
        return None
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); import opensees_frame3d as b; "
            "a = json.loads(sys.stdin.read()); "
            "spec = b.Frame3DSpec(**{k: b._tuples(v) for k, v in a['spec'].items()}); "
            "r, t, f, o = b.run_opensees(spec, a['samples'], a['dt'], a['t_end']); "
            "print(json.dumps({'roof': {k: v.tolist() for k, v in r.items()}, 'time': t, 'failed': f, 'open': o}))")
    payload = json.dumps({"spec": asdict(spec), "samples": [list(map(float, s)) for s in samples], "dt": dt,
                          "t_end": t_end})
    proc = subprocess.run([sys.executable, "-c", code, str(Path(__file__).resolve().parent)], input=payload,
                          capture_output=True, text=True, env=env, timeout=3600)
    if proc.returncode:
        raise RuntimeError(f"OpenSees run failed:\n{proc.stderr[-2000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    return {k: np.array(v) for k, v in out["roof"].items()}, out["time"], out["failed"], out["open"]


# ---------------------------------------------------------------------- comparison
def open_steps(sol, tol=0.0):
    """Steps (after t = 0) at which at least one spring is open (``v > tol``)."""
    return int(np.count_nonzero((sol.v[1:] > tol).any(axis=1)))


class Scaled:
    """A ground motion times ``factor`` (a perturbation of the record)."""

    def __init__(self, gm, factor):
        self.gm, self.factor = gm, factor

    def __call__(self, t):
        return self.factor * self.gm(t)


def sensitivity(spec, gms, dt, t_end, ours, eps=1e-13):
    """Max difference over the peak between ``ours`` and the project's run on the x record scaled by
    ``1 + eps``: how much the response amplifies a perturbation of the size of round-off (a bound
    below which two correct codes need not agree; the rocking response is chaotic enough to grow it)."""
    perturbed, _, _ = run_unilateral(spec, [Scaled(gms[0], 1.0 + eps)] + list(gms[1:]), dt, t_end)
    return max(differences(perturbed, ours).values())


def differences(ours, theirs):
    """{dof: max |ours - theirs| / max |theirs|} of the roof-corner histories."""
    return {d: float(np.abs(ours[d] - theirs[d]).max() / np.abs(theirs[d]).max()) for d in COMPARED}


def compare(spec, *, t_end, dt, repeat=1):
    """Both runs on the same samples: median timings of ``repeat`` runs, differences over the peaks."""
    gms = records(spec, dt, t_end)
    samples = [record_samples(gm, dt, t_end) for gm in gms]
    N = int(round(t_end / dt))
    ours = [run_unilateral(spec, gms, dt, t_end) for _ in range(repeat)]
    roof, _, sol = ours[0]
    row = {"frame": spec.name, "storeys": spec.storeys, "bays": f"{spec.bays_x}x{spec.bays_y}",
           "n": int(sol.stats["n"]), "m": int(sol.stats["m"]), "steps": N, "dt": dt,
           "unilateral_s": float(np.median([o[1] for o in ours])),
           "uplift_steps": open_steps(sol), "contact_changes": int(sol.stats["contact_changes"]),
           "peak_roof": {d: float(np.abs(roof[d]).max()) for d in COMPARED}}
    row["unilateral_us_per_step"] = 1e6 * row["unilateral_s"] / N
    row["sensitivity_1e-13"] = sensitivity(spec, gms, dt, t_end, roof)
    theirs = [opensees_in_subprocess(spec, samples, dt, t_end) for _ in range(repeat)]
    if theirs[0] is not None:
        r_os, _, failed, opened = theirs[0]
        row["opensees_s"] = float(np.median([t[1] for t in theirs]))
        row["opensees_failed_step"] = int(failed)
        row["opensees_uplift_steps"] = int(opened)
        row["ratio"] = row["unilateral_s"] / row["opensees_s"]
        row["difference_over_peak"] = differences(roof, r_os)
        row["max_difference_over_peak"] = max(row["difference_over_peak"].values())
    return row


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="short records (a smoke test)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--dt", type=float, default=0.005)
    parser.add_argument("--out", type=Path, default=RESULTS / "opensees_frame3d.json")
    args = parser.parse_args(argv)
    t_end = 2.0 if args.quick else 20.0
    run_unilateral(FRAMES[0], records(FRAMES[0], args.dt, 0.5), args.dt, 0.5)   # warm-up: the compiled code
    rows = [compare(spec, t_end=t_end, dt=args.dt, repeat=args.repeat) for spec in FRAMES]
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print(f"{'frame':>9} {'DOFs':>5} {'m':>3} {'steps':>6} {'unilateral s':>12} {'us/step':>8} {'OpenSees s':>10} "
          f"{'ratio':>6} {'speed-up':>8} {'max diff/peak':>13} {'uplift steps':>12} {'OS uplift':>9} "
          f"{'1e-13 sensitivity':>17}")
    nan = float("nan")
    for r in rows:
        print(f"{r['frame']:>9} {r['n']:>5} {r['m']:>3} {r['steps']:>6} {r['unilateral_s']:12.3f} "
              f"{r['unilateral_us_per_step']:8.1f} {r.get('opensees_s', nan):10.3f} {r.get('ratio', nan):6.3f} "
              f"{1 / r.get('ratio', nan):8.1f} {r.get('max_difference_over_peak', nan):13.2e} "
              f"{r['uplift_steps']:>12} {r.get('opensees_uplift_steps', -1):>9} {r['sensitivity_1e-13']:17.2e}")
        if "difference_over_peak" in r:
            print("          roof corner " + ", ".join(f"{d} {v:.2e}" for d, v in r["difference_over_peak"].items()))
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"load_average": load, "quick": args.quick, "repeat": args.repeat, "rows": rows},
                              indent=1))
    tmp.replace(args.out)


if __name__ == "__main__":
    main()
