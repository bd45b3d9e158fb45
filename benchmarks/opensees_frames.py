"""Yielding moment frames against OpenSees: the same model, the same rule, the same dt.

A regular moment frame (``storeys`` x ``bays``) of elastic beam-columns with an elastic-perfectly
plastic rotational spring at every beam end and column base, lumped masses at the floor nodes,
Rayleigh damping, gravity, then a ground acceleration record. It is built twice:

* with :class:`unilateral.structure.Frame2D` (``Frame2D.hinge(..., My=, k=)``: the plastic
  rotations are rate-type constraints of the CLCP) and solved by ``method="direct"`` with the
  trapezoidal rule (Newmark's average acceleration) on point samples of the record;
* in OpenSees (``elasticBeamColumn``, ``zeroLength`` rotational springs of an ``ElasticPP``
  material between the beam end and the joint, ``equalDOF`` in ux and uy, ``Newmark 0.5 0.25``,
  Newton iterations, ``UniformExcitation`` of the same samples).

Damping is mass-proportional (``a0 M``): with it both codes solve the same discrete problem and the
roof drifts agree to round-off, plastic phases included. Stiffness-proportional damping is not
the same model in the two: OpenSees leaves ``zeroLength`` springs undamped unless
``-doRayleigh 1``, and where it does damp them it damps their plastic rotation rate with the
spring's stiffness, while ``Frame2D`` damps the beam with its hinge spring in series
(``stiffness_damping=True`` shows the difference, 1e-3 of the peak on the elastic frame).

``python benchmarks/opensees_frames.py`` prints a table (time per run, per step and the ratio;
the roof-drift difference over the peak) and writes ``benchmarks/results/opensees_frames.json``.
OpenSees comes from the ``openseespy`` package (``pip install openseespy``); its Linux wheel needs
its own ``lib`` folder on ``LD_LIBRARY_PATH``, which :func:`opensees_environment` gives to a
subprocess. Without OpenSees the table has the project's rows only. BLAS runs in one thread in
both (on a shared 2-core machine a multi-threaded BLAS call on the project's small matrices can
cost a hundred times more than the call itself).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path

if __name__ == "__main__":                  # before numpy is imported: BLAS in one thread in both codes
    for _name in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(_name, "1")

import numpy as np  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"


@dataclass(frozen=True)
class FrameSpec:
    """A regular moment frame with plastic hinges (kN, m, s, t)."""

    storeys: int = 3
    bays: int = 2
    height: float = 3.5
    span: float = 6.0
    E: float = 30e6
    column: tuple = (0.16, 2.133e-3)        # A (m^2), I (m^4): 400 x 400 mm
    beam: tuple = (0.15, 2.813e-3)          # 300 x 500 mm
    My_column: float = 260.0                # kN m
    My_beam: float = 180.0
    hinge_factor: float = 20.0              # hinge stiffness over 6 EI / L of its member
    floor_mass: float = 60.0                # t per floor, split over the floor's nodes
    zeta: float = 0.05                      # Rayleigh at the first two periods (approximately)
    stiffness_damping: bool = False         # True: a1 K as well (the codes then differ, see below)
    gravity: float = 9.81


#: The frames of the table: 3 x 2 (the example's frame), 6 x 3, 9 x 3 (about 60 hinges), 12 x 4.
FRAMES = (
    FrameSpec(storeys=3, bays=2),
    FrameSpec(storeys=6, bays=3, column=(0.25, 5.21e-3), beam=(0.18, 3.75e-3), My_column=500.0,
              My_beam=300.0, floor_mass=90.0),
    FrameSpec(storeys=9, bays=3, column=(0.36, 1.08e-2), beam=(0.24, 7.2e-3), My_column=900.0,
              My_beam=500.0, floor_mass=120.0),
    FrameSpec(storeys=12, bays=4, column=(0.49, 2.0e-2), beam=(0.3, 1.25e-2), My_column=1400.0,
              My_beam=700.0, floor_mass=160.0),
)


def node_id(floor, line):
    return 100 * floor + line


def frame2d(spec: FrameSpec):
    """The :class:`~unilateral.structure.Structure` of ``spec`` and its roof node."""
    from unilateral.structure import Frame2D

    fr = Frame2D()
    for f in range(spec.storeys + 1):
        for c in range(spec.bays + 1):
            fr.node(node_id(f, c), c * spec.span, f * spec.height)
    for c in range(spec.bays + 1):
        fr.support(node_id(0, c), ux=True, uy=True, rz=True)
    Ac, Ic = spec.column
    Ab, Ib = spec.beam
    for f in range(1, spec.storeys + 1):
        for c in range(spec.bays + 1):
            name = f"C{f}_{c}"
            fr.beam(name, node_id(f - 1, c), node_id(f, c), E=spec.E, A=Ac, I=Ic)
            if f == 1:
                fr.hinge(f"{name}.base", name, "i", My=spec.My_column, k=_hinge_k(spec, "column"))
            fr.mass(node_id(f, c), spec.floor_mass / (spec.bays + 1))
        for b in range(spec.bays):
            name = f"B{f}_{b}"
            fr.beam(name, node_id(f, b), node_id(f, b + 1), E=spec.E, A=Ab, I=Ib)
            for end in ("i", "j"):
                fr.hinge(f"{name}.{end}", name, end, My=spec.My_beam, k=_hinge_k(spec, "beam"))
    a0, a1 = _rayleigh(spec)
    fr.rayleigh(a0, a1)
    return fr.build(), node_id(spec.storeys, 0)


def _hinge_k(spec, member):
    A, I = spec.column if member == "column" else spec.beam
    L = spec.height if member == "column" else spec.span
    return spec.hinge_factor * 6.0 * spec.E * I / L


def _rayleigh(spec):
    """Mass and stiffness factors for ``zeta`` at the circular frequencies of a shear building
    estimate (fixed from the spec, so that both codes get the same numbers)."""
    w1, w2 = 2 * np.pi / (0.1 * spec.storeys), 3 * 2 * np.pi / (0.1 * spec.storeys)
    a1 = 2 * spec.zeta / (w1 + w2) if spec.stiffness_damping else 0.0
    return 2 * spec.zeta * w1 * w2 / (w1 + w2), a1


def record(duration=20.0, dt=0.005, pga=4.0, seed=3):
    from unilateral.loads import synthetic_accelerogram

    return synthetic_accelerogram(duration=duration, dt=dt, pga=pga, seed=seed)


def run_unilateral(spec, ag, dt, t_end, rule="trapezoidal"):
    """Roof drift (N+1,) of the project's run and its wall time (model built and solved)."""
    import unilateral as ul

    start = time.perf_counter()
    st, roof = frame2d(spec)
    model = st.to_model()
    N = int(round(t_end / dt))
    t = np.arange(N + 1) * dt
    r = st.influence("ux")
    q = st.gravity(spec.gravity)[None, :] - np.outer(ag(t), st.M @ r)
    sol = ul.solve(model, q, dt=dt, t_end=t_end, method="direct", rule=rule)
    elapsed = time.perf_counter() - start
    if not sol.success:
        raise RuntimeError(sol.message)
    drift = st.node_displacement(sol, roof, "ux")
    return drift, elapsed, sol


def opensees_environment():
    """The environment in which openseespy imports (its wheel's ``lib`` on LD_LIBRARY_PATH), or None."""
    import importlib.util

    spec = importlib.util.find_spec("openseespylinux")
    if spec is None or not spec.submodule_search_locations:
        return None
    lib = Path(list(spec.submodule_search_locations)[0]) / "lib"
    env = dict(os.environ)
    env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (str(lib), env.get("LD_LIBRARY_PATH")) if p)
    return env


def run_opensees(spec, ag_samples, dt, t_end):
    """Roof drift (N+1,) by OpenSees and its wall time (model built and solved); in this process."""
    import openseespy.opensees as ops

    start = time.perf_counter()
    build_opensees(ops, spec)
    m_node = spec.floor_mass / (spec.bays + 1)

    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for f in range(1, spec.storeys + 1):
        for c in range(spec.bays + 1):
            ops.load(node_id(f, c), 0.0, -m_node * spec.gravity, 0.0)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    ops.analyze(1)
    ops.loadConst("-time", 0.0)
    a0, a1 = _rayleigh(spec)
    ops.rayleigh(a0, 0.0, a1, 0.0)                    # a1 on the initial stiffness, as the project's K
    ops.timeSeries("Path", 2, "-dt", dt, "-values", *ag_samples)
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    ops.wipeAnalysis()
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    roof = node_id(spec.storeys, 0)
    N = int(round(t_end / dt))
    drift = np.zeros(N + 1)
    drift[0] = ops.nodeDisp(roof, 1)
    failed = 0
    for k in range(1, N + 1):
        if ops.analyze(1, dt) != 0:
            failed = k
            break
        drift[k] = ops.nodeDisp(roof, 1)
    elapsed = time.perf_counter() - start
    ops.wipe()
    return drift, elapsed, failed


def build_opensees(ops, spec):
    """The frame of ``spec`` in OpenSees (``ops``: the ``openseespy.opensees`` module), fresh."""
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.geomTransf("Linear", 1)
    ops.uniaxialMaterial("ElasticPP", 1, _hinge_k(spec, "column"), spec.My_column / _hinge_k(spec, "column"))
    ops.uniaxialMaterial("ElasticPP", 2, _hinge_k(spec, "beam"), spec.My_beam / _hinge_k(spec, "beam"))
    m_node = spec.floor_mass / (spec.bays + 1)
    for f in range(spec.storeys + 1):
        for c in range(spec.bays + 1):
            ops.node(node_id(f, c), c * spec.span, f * spec.height)
            if f:
                ops.mass(node_id(f, c), m_node, m_node, 0.0)
    for c in range(spec.bays + 1):
        ops.fix(node_id(0, c), 1, 1, 1)
    hidden, element = [10_000], [0]

    def new_element():
        element[0] += 1
        return element[0]

    def hinge(joint, mat):
        """A node at the joint, tied in ux, uy, and a rotational spring: the member end."""
        hidden[0] += 1
        x, y = ops.nodeCoord(joint)
        ops.node(hidden[0], x, y)
        ops.equalDOF(joint, hidden[0], 1, 2)
        ops.element("zeroLength", new_element(), joint, hidden[0], "-mat", mat, "-dir", 3)
        return hidden[0]

    Ac, Ic = spec.column
    Ab, Ib = spec.beam
    for f in range(1, spec.storeys + 1):
        for c in range(spec.bays + 1):
            bottom = hinge(node_id(0, c), 1) if f == 1 else node_id(f - 1, c)
            ops.element("elasticBeamColumn", new_element(), bottom, node_id(f, c), Ac, spec.E, Ic, 1)
        for b in range(spec.bays):
            left, right = hinge(node_id(f, b), 2), hinge(node_id(f, b + 1), 2)
            ops.element("elasticBeamColumn", new_element(), left, right, Ab, spec.E, Ib, 1)


def record_samples(gm, dt, t_end):
    """The samples of ``gm`` at ``k dt`` for OpenSees's Path series, one past ``t_end`` (its time,
    a sum of steps, may round past the last sample, where the series would give zero)."""
    return gm(np.arange(int(round(t_end / dt)) + 2) * dt)


def opensees_in_subprocess(spec, ag_samples, dt, t_end):
    """:func:`run_opensees` in a fresh process with the library path it needs; None without OpenSees."""
    env = opensees_environment()
    if env is None:
        return None
    code = ("import json, sys, numpy as np; sys.path.insert(0, sys.argv[1]); import opensees_frames as b; "
            "a = json.loads(sys.stdin.read()); spec = b.FrameSpec(**{k: tuple(v) if isinstance(v, list) else v "
            "for k, v in a['spec'].items()}); d, t, f = b.run_opensees(spec, a['ag'], a['dt'], a['t_end']); "
            "print(json.dumps({'drift': d.tolist(), 'time': t, 'failed': f}))")
    payload = json.dumps({"spec": asdict(spec), "ag": list(map(float, ag_samples)), "dt": dt, "t_end": t_end})
    proc = subprocess.run([sys.executable, "-c", code, str(Path(__file__).resolve().parent)], input=payload,
                          capture_output=True, text=True, env=env, timeout=3600)
    if proc.returncode:
        raise RuntimeError(f"OpenSees run failed:\n{proc.stderr[-2000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    return np.array(out["drift"]), out["time"], out["failed"]


def compare(spec, *, t_end, dt, repeat=1):
    """Both runs on the same samples: timings (best of ``repeat``), drift difference over the peak."""
    gm = record(duration=t_end, dt=dt)
    samples = record_samples(gm, dt, t_end)
    N = int(round(t_end / dt))
    ours = [run_unilateral(spec, gm, dt, t_end) for _ in range(repeat)]
    drift, sol = ours[0][0], ours[0][2]
    row = {"storeys": spec.storeys, "bays": spec.bays, "hinges": int(sol.stats["m"]) // 2, "steps": N, "dt": dt,
           "n": int(sol.stats["n"]), "unilateral_s": float(np.median([o[1] for o in ours])),
           "peak_roof_drift_m": float(np.abs(drift).max()),
           "yield_events": int(sol.stats["contact_changes"])}
    row["unilateral_us_per_step"] = 1e6 * row["unilateral_s"] / N
    theirs = [opensees_in_subprocess(spec, samples, dt, t_end) for _ in range(repeat)]
    if theirs[0] is not None:
        d_os, _, failed = theirs[0]
        row["opensees_s"] = float(np.median([t[1] for t in theirs]))
        row["opensees_failed_step"] = int(failed)
        row["ratio"] = row["unilateral_s"] / row["opensees_s"]
        row["drift_difference_over_peak"] = float(np.abs(drift - d_os).max() / np.abs(d_os).max())
    return row


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="short records (a smoke test)")
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--out", type=Path, default=RESULTS / "opensees_frames.json")
    args = parser.parse_args(argv)
    t_end = 2.0 if args.quick else 20.0
    run_unilateral(FRAMES[0], record(duration=0.5), 0.005, 0.5)     # warm-up: loads the compiled code
    rows = [compare(spec, t_end=t_end, dt=0.005, repeat=args.repeat) for spec in FRAMES]
    load = os.getloadavg()
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    print(f"{'frame':>6} {'n':>4} {'hinges':>6} {'m':>4} {'steps':>6} {'yield events':>12} {'ours s':>8} "
          f"{'us/step':>8} {'OpenSees s':>10} {'ratio':>6} {'OS failed':>9} {'drift diff/peak':>15}")
    for r in rows:
        print(f"{r['storeys']:>3}x{r['bays']:<2} {r['n']:>4} {r['hinges']:>6} {2 * r['hinges']:>4} {r['steps']:>6} "
              f"{r['yield_events']:>12} {r['unilateral_s']:8.3f} {r['unilateral_us_per_step']:8.1f} "
              f"{r.get('opensees_s', float('nan')):10.3f} {r.get('ratio', float('nan')):6.3f} "
              f"{r.get('opensees_failed_step', -1):>9} {r.get('drift_difference_over_peak', float('nan')):15.2e}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"load_average": load, "rows": rows}, indent=1))
    tmp.replace(args.out)


if __name__ == "__main__":
    main()
