"""One OpenSeesPy script run end to end by openseespy and by ``unilateral.opensees``.

A 9-storey 3-bay moment frame (bays 6 m, storeys 3.5 m; the sections, yield moments and masses
of the 9-storey frame of ``opensees_frames.py``) of elastic beam-columns
with 58 zeroLength ElasticPP rotational hinges (both ends of every beam, every column base; each
tied to its joint by equalDOF 1 2), lumped floor masses, gravity by a static analysis, then 3000
steps (dt = 0.01 s) of a synthetic ground acceleration with mass-proportional Rayleigh damping. The
script is written as OpenSeesPy users write it, in two styles:

* ``loop``: ``for k in range(3000): ops.analyze(1, dt)``, reading each step the roof displacement,
  the base shear (``eleForce`` of the four base hinges) and every hinge's
  ``eleResponse(tag, 'basicForce')``;
* ``recorders``: one ``ops.analyze(3000, dt)`` with a Node recorder (roof) and an Element recorder
  (the hinges).

Where OpenSees's Newton fails to converge (it can cycle between the states of the hinges), the
script does what its users do: one step of ``ModifiedNewton -initial``, then Newton again (the
remaining steps in one ``analyze`` in the recorders style). ``unilateral.opensees`` never takes that
branch (each step is one LCP; ``algorithm`` and ``test`` have no effect).

Each style runs in a fresh interpreter with each code (the script's text, its import line changed,
nothing else), timed from the start of the process to its end (imports, building, gravity, the
analysis, the queries or the files). The roof histories of the two codes are compared (max
difference over the peak). ``python benchmarks/opensees_module_speed.py`` prints the table and
writes ``benchmarks/results/opensees_module_speed.json``. Timings on a shared machine are noisy.
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
SRC = HERE.parent / "src"
RESULTS = HERE / "results"
IMPORT = "import openseespy.opensees as ops"

SCRIPT = '''
import json, math, sys, time
import openseespy.opensees as ops

style, folder, steps, dt = sys.argv[1], sys.argv[2], int(sys.argv[3]), 0.01
storeys, bays, span = 9, 3, 6.0
heights = [3.5] * storeys
E = 30e6
col = (0.36, 1.08e-2)                # A, I of the columns
beam = (0.24, 7.2e-3)
mass_floor = 120.0
record = [0.0] + [2.5 * math.sin(2 * math.pi * k * dt / 0.9) * math.sin(math.pi * k * dt / 30.0)
                  + 1.0 * math.sin(2 * math.pi * k * dt / 0.37) * math.exp(-0.05 * k * dt) for k in range(1, steps + 1)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
def joint(f, l):
    return 1000 + 10 * f + l
y = 0.0
for f in range(storeys + 1):
    for l in range(bays + 1):
        ops.node(joint(f, l), l * span, y)
    if f < storeys:
        y += heights[f]
hinges, base = [], []
ops.uniaxialMaterial('ElasticPP', 1, 6 * E * col[1] / 3.5 * 20, 900.0 / (6 * E * col[1] / 3.5 * 20))
ops.uniaxialMaterial('ElasticPP', 2, 6 * E * beam[1] / span * 20, 500.0 / (6 * E * beam[1] / span * 20))
ops.geomTransf('Linear', 1)
tag = 1
for l in range(bays + 1):
    ops.fix(joint(0, l), 1, 1, 1)
    n = 5000 + l
    ops.node(n, l * span, 0.0)
    ops.equalDOF(joint(0, l), n, 1, 2)
    ops.element('zeroLength', 100000 + l, joint(0, l), n, '-mat', 1, '-dir', 3)
    hinges.append(100000 + l)
    base.append(100000 + l)
for f in range(storeys):
    for l in range(bays + 1):
        i = 5000 + l if f == 0 else joint(f, l)
        ops.element('elasticBeamColumn', tag, i, joint(f + 1, l), col[0], E, col[1], 1)
        tag += 1
for f in range(1, storeys + 1):
    for b in range(bays):
        ends = []
        for side, l in ((0, b), (1, b + 1)):
            n = 6000 + 100 * f + 10 * b + side
            ops.node(n, l * span, ops.nodeCoord(joint(f, l), 2))
            ops.equalDOF(joint(f, l), n, 1, 2)
            h = 200000 + 100 * f + 10 * b + side
            ops.element('zeroLength', h, joint(f, l), n, '-mat', 2, '-dir', 3)
            hinges.append(h)
            ends.append(n)
        ops.element('elasticBeamColumn', tag, ends[0], ends[1], beam[0], E, beam[1], 1)
        tag += 1
    for l in range(bays + 1):
        m = mass_floor / (bays + 1)
        ops.mass(joint(f, l), m, m, 0.0)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
for f in range(1, storeys + 1):
    for l in range(bays + 1):
        m = mass_floor / (bays + 1)
        ops.load(joint(f, l), 0.0, -9.81 * m, 0.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-10, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
assert ops.analyze(1) == 0
ops.loadConst('-time', 0.0)

ops.wipeAnalysis()
ops.rayleigh(0.3, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *record)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-10, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
roof = joint(storeys, 0)
t_end = steps * dt


def advance(n):
    # analyze n steps; where Newton fails (it can cycle between the states of the hinges), the
    # usual fallback: one step of ModifiedNewton -initial, then Newton again
    ok = ops.analyze(n, dt)
    while ok != 0:
        left = int(round((t_end - ops.getTime()) / dt)) if n > 1 else 1
        print(f'fallback at t = {ops.getTime():.4f}', file=sys.stderr)
        ops.algorithm('ModifiedNewton', '-initial')
        ops.test('NormDispIncr', 1e-10, 5000)
        ok = ops.analyze(1, dt)
        ops.algorithm('Newton')
        ops.test('NormDispIncr', 1e-10, 100)
        if ok != 0:
            raise RuntimeError(f'no convergence at t = {ops.getTime()}')
        if left > 1:
            ok = ops.analyze(left - 1, dt)


if style == 'loop':
    out = {'roof': [], 'shear': [], 'hinges': []}
    for k in range(steps):
        advance(1)
        out['roof'].append(ops.nodeDisp(roof, 1))
        out['shear'].append(sum(ops.eleForce(e, 3) for e in base))
        out['hinges'].append([ops.eleResponse(h, 'basicForce')[0] for h in hinges])
    roof_history = out['roof']
else:
    ops.recorder('Node', '-file', folder + '/roof.out', '-time', '-precision', 16, '-node', roof, '-dof', 1, 'disp')
    ops.recorder('Element', '-file', folder + '/hinges.out', '-precision', 16, '-ele', *hinges, 'basicForce')
    advance(steps)
    ops.wipe()
    roof_history = [float(line.split()[1]) for line in open(folder + '/roof.out')]
print(json.dumps({'roof': roof_history, 'hinges': len(hinges)}))
'''


def opensees_environment():
    """The environment in which openseespy imports (its wheel's ``lib`` on LD_LIBRARY_PATH), or None."""
    import importlib.util

    spec = importlib.util.find_spec("openseespylinux")
    if spec is None or not spec.submodule_search_locations:
        return None
    env = dict(os.environ)
    lib = Path(list(spec.submodule_search_locations)[0]) / "lib"
    env["LD_LIBRARY_PATH"] = os.pathsep.join(p for p in (str(lib), env.get("LD_LIBRARY_PATH")) if p)
    return env


def run(code, style, steps):
    """``(seconds end to end, roof history, Newton fallbacks taken)`` of the script with ``code`` ('openseespy' or 'unilateral')."""
    env = opensees_environment() if code == "openseespy" else dict(os.environ)
    if env is None:
        return None, None, None
    text = SCRIPT if code == "openseespy" else SCRIPT.replace(IMPORT, "import unilateral.opensees as ops")
    if code == "unilateral":
        env["PYTHONPATH"] = os.pathsep.join(p for p in (str(SRC), env.get("PYTHONPATH")) if p)
    env["OPENBLAS_NUM_THREADS"] = env["OMP_NUM_THREADS"] = "1"
    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "frame9.py"
        script.write_text(text)
        start = time.perf_counter()
        proc = subprocess.run([sys.executable, str(script), style, folder, str(steps)], capture_output=True,
                              text=True, env=env, timeout=3600)
        seconds = time.perf_counter() - start
    if proc.returncode:
        raise RuntimeError(f"{code} {style}: {proc.stderr[-2000:]}")
    fallbacks = proc.stderr.count("fallback at t")
    return seconds, json.loads(proc.stdout.strip().splitlines()[-1])["roof"], fallbacks


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=3000)
    parser.add_argument("--out", type=Path, default=RESULTS / "opensees_module_speed.json")
    args = parser.parse_args(argv)
    rows = []
    for style in ("loop", "recorders"):
        t_ops, roof_ops, fb_ops = run("openseespy", style, args.steps)
        t_uni, roof_uni, fb_uni = run("unilateral", style, args.steps)
        diff = None
        if roof_ops is not None:
            peak = max(abs(x) for x in roof_ops)
            diff = max(abs(a - b) for a, b in zip(roof_ops, roof_uni)) / peak
        rows.append({"style": style, "steps": args.steps, "openseespy_s": t_ops, "unilateral_s": t_uni,
                     "ratio": t_uni / t_ops if t_ops else None, "roof_difference_over_peak": diff,
                     "openseespy_fallbacks": fb_ops, "unilateral_fallbacks": fb_uni,
                     "roof_peak": max(abs(x) for x in roof_uni)})
    print(f"{'style':<10} {'steps':>6} {'openseespy [s]':>15} {'unilateral [s]':>15} {'ratio':>7} {'roof diff/peak':>15} "
          f"{'fallbacks':>10}")
    for r in rows:
        fmt = lambda x, f: format(x, f) if x is not None else "-"
        print(f"{r['style']:<10} {r['steps']:>6} {fmt(r['openseespy_s'], '15.2f')} {r['unilateral_s']:>15.2f} "
              f"{fmt(r['ratio'], '7.3f')} {fmt(r['roof_difference_over_peak'], '15.1e')} "
              f"{fmt(r['openseespy_fallbacks'], '10d')}")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else None
    args.out.write_text(json.dumps({"load_average": load, "rows": rows}, indent=1))


if __name__ == "__main__":
    main()
