"""A beam on tensionless Winkler springs against OpenSees: the same model, the same rule, the same dt.

The Winkler scale table. A free beam of ``nodes`` nodes along ``x`` (50 m, elastic Euler-Bernoulli
beam-columns ``EI = 2e6``, ``EA = 2e7``, lumped masses 2 t/m, node 0 held in ``ux``) rests on ``m``
compression-only soil springs spread evenly along it (tributary stiffness of 5e3 kN/m per metre, so
that the total soil stiffness is the same whatever ``m``); gravity (9.81) presses it onto the soil
(the static state, contacts included, is the start), then a downward force ``P = 500`` kN moves
from the left end at 40 m/s (shared linearly between the two nodes of the element under it, as
:func:`unilateral.structure.winkler_beam`), so that parts of the beam lift off and land again.
``n = 3 nodes - 1`` DOFs. It is built twice:

* with :class:`unilateral.structure.Frame2D`, its nodes, beams, masses and soil springs given as
  arrays (``Frame2D.nodes``, ``beams``, ``masses``, ``soils``: the elements of a loop of
  ``Frame2D.beam``... without a Python call per element; the separations are the unknowns of one
  LCP per step) and solved by ``method="auto"`` and ``method="direct"`` with the
  trapezoidal rule (Newmark's average acceleration) on point samples of the load;
* in OpenSees (``elasticBeamColumn``, ``zeroLength`` elements of an ``ENT`` material, elastic
  no-tension, from a fixed ground node to the beam node in ``uy``: compression when the beam
  moves down; a static gravity step, then ``Newmark 0.5 0.25``, ``Newton``, ``NormDispIncr``
  1e-12, and the moving load as one ``Path`` series per node with that node's load samples at
  ``k dt``, the same numbers as the project's load function).

Damping is mass-proportional (``a0 M``, ``a0`` of 2 % at 1 and 50 Hz as ``winkler_beam``'s
Rayleigh pair): then both codes solve the same discrete problem (see ``opensees_frames.py``) and
the displacement of the middle node agrees to round-off: 1e-13 of the peak at n = 98, but the
beam's stiffness over the soil's grows like ``nodes^3`` (``cond(K + 4/dt^2 M)`` about 1e5 at
n = 998, 1e8 at n = 9998) and the trapezoidal rule does not damp the round-off of each step, so
any two codes differ by about ``eps cond steps``: 1e-9 to 1e-8 of the peak at n = 998, 1e-6 at
n = 9998. The column ``linear diff`` shows that scale on a problem that is the same by
construction: the beam with its springs bonded in OpenSees (``Elastic`` springs) against the
banded recursion below.

A further column is the reference of the speed target "within 5x of a compiled banded recursion of
the same size": the *linear* beam (springs bonded, no contact) stepped by the same rule with
numba, ``K + 4/dt^2 M + 2/dt C`` factorised once by ``scipy.linalg.cholesky_banded`` (set-up not
counted) and a compiled banded forward and back substitution per step; ``march/banded`` is the
project's march time per step over it.

``python benchmarks/opensees_winkler.py`` prints a table with the machine's load average and
writes ``benchmarks/results/opensees_winkler.json``. Columns: ``n``, ``m``, steps (dt = 1.5 ms:
1000 steps in every cell, 1.5 s, in which the load crosses the beam), contact changes, ``auto s`` end to end (model built
and solved), ``build s`` (``Frame2D`` to ``Model``), the set-up (the build and every lap of
``stats["time"]`` before ``steps``) and its share, the march per step (the ``steps`` lap),
``direct s``, ``OpenSees s`` end to end and its set-up (built, gravity step, load patterns),
``ratio`` = auto / OpenSees (target 0.2), the largest difference of the middle node's ``uy`` over
its peak, the linear one (above) and the banded recursion. ``--quick``: two small cells in seconds
(CI); ``--opensees-system``, ``--opensees-tol`` change OpenSees's solver and its test. OpenSees
runs in a subprocess with its library path (:func:`opensees_frames.opensees_environment`); without
it the table has the project's rows only. BLAS runs in one thread in both codes. Medians of
``--repeats`` runs after a warm-up that loads the compiled code (the engine by the size policy's
steps rule; the first run after a fresh install and in a new process: ``cold_start.py``).

The tower row (a second table, ``"tower"`` in the JSON) is the benchmark suite's tower
(``unilateral.bench.problems.tower``: five storeys of 3 m, 40 t each on ``ux`` and ``uy``, a column
of ``EI = 1e9``, ``EA = 1e12``, the base held in ``ux`` and rigidly linked to two footing nodes at
+-3 m, gravity 10, the synthetic record of seed 1, pga 4 m/s2, 10 s, 10^4 steps) with two changes
that make it one model in both codes: its three soil elements are plain tensionless springs
(``Frame2D.soil(name, node, 200e3)``, no dashpot: OpenSees has no Kelvin element in series with a
contact) and its damping is mass-proportional, ``a0 M`` with 5 % at the first mode (2.13 Hz, the
springs bonded), in place of the dashpots. The load is ``gravity + ground_motion(record, "ux")``
sampled at ``k dt`` (an array, not the hat averages a :class:`~unilateral.loads.LoadHistory`
gives), in OpenSees a ``UniformExcitation`` of a ``Path -dt`` series of the same samples after the
static gravity step (``loadConst -time 0``). In OpenSees the rigid footing is not a ``rigidLink``:
with the ``Transformation`` handler a retained node fixed in some of its DOFs (the base, held in
``ux``) loses its constrained nodes after the first step (OpenSees PR #1785: here the footing nodes
follow only the increments after the gravity step, so the edge springs lose their static
compression), and with the ``Lagrange`` handler Newton stalls at ``NormDispIncr`` 1.3e-12 a few
hundred steps in (its multipliers, forces of 1e3 kN, carry round-off above 1e-12). The
edge springs are instead ``twoNodeLink`` elements from a fixed ground node at +-3 m to the base
node, ``-dir 2 -shearDist 0``: their deformation is the edge's ``uy_base -+ 3 rz_base``, exactly
the rigid link's; the right one sees it with the opposite sign (its local ``y`` points down), so
its material is the mirrored no-tension spring ``Elastic k 0 0`` (stiff in positive strain only)
while the left and middle ones are ``ENT``. The top's ``ux`` then agrees to 3.5e-9 of its peak
(``direct`` 1e-9), growing with ``EA`` (5e-11 at ``EA = 2e8``): the round-off of the axially
"rigid" column, not a model difference. ``--tower-steps``: its number of steps; ``--no-tower``.
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
    # the warm figures of the compiled loops (the engine by the steps rule): the first run of a
    # fresh install or of a new process, where the cost rule may step in Python, is cold_start.py's
    os.environ.setdefault("UNILATERAL_ENGINE_CHOICE", "steps")

import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
if str(HERE) not in sys.path:
    sys.path.insert(0, str(HERE))

from opensees_frames import opensees_environment  # noqa: E402

RESULTS = HERE / "results"
DT = 1.5e-3                                 # s: the benchmark suite's winkler<m> at 1000 steps
OPENSEES_SYSTEM = "BandSPD"                 # the fastest that works here, with ProfileSPD
OPENSEES_TOL = 1e-12                        # NormDispIncr, m


@dataclass(frozen=True)
class BeamSpec:
    """A free beam on ``springs`` tensionless Winkler springs (kN, m, s, t)."""

    nodes: int = 33
    springs: int = 10
    length: float = 50.0
    EI: float = 2e6
    EA: float = 2e7
    mass_per_length: float = 2.0
    k_soil: float = 5e3                     # kN/m per metre of beam
    P: float = 500.0                        # kN, downward
    speed: float = 40.0                     # m/s
    zeta: float = 0.02                      # mass-proportional: a0 of Rayleigh's pair at f1, f2
    f1: float = 1.0
    f2: float = 50.0
    gravity: float = 9.81

    @property
    def n(self):
        return 3 * self.nodes - 1

    @property
    def a0(self):
        w1, w2 = 2 * np.pi * self.f1, 2 * np.pi * self.f2
        return 2 * self.zeta * w1 * w2 / (w1 + w2)


#: The cells of the table: (nodes, springs, steps) at dt = DT. m = springs.
CELLS = ((33, 11, 1000), (333, 10, 1000), (333, 100, 1000), (3333, 10, 1000), (3333, 100, 1000),
         (3333, 1000, 1000))
QUICK_CELLS = ((33, 11, 200), (333, 10, 100))


def x_of(spec):
    return np.linspace(0.0, spec.length, spec.nodes)


def masses(spec):
    """Lumped mass of each node (tributary length)."""
    h = spec.length / (spec.nodes - 1)
    trib = np.full(spec.nodes, h)
    trib[[0, -1]] = h / 2
    return spec.mass_per_length * trib


def springs(spec):
    """``(nodes, k)``: the spring nodes, evenly spread (both ends included), and their tributary
    stiffness (the total is ``k_soil * length`` whatever their number)."""
    if spec.springs < 2:
        raise ValueError(f"springs={spec.springs!r}: at least 2 (the two ends)")
    where = np.unique(np.round(np.linspace(0, spec.nodes - 1, min(spec.springs, spec.nodes))).astype(int))
    x = x_of(spec)[where]
    trib = np.empty(len(where))
    trib[1:-1] = (x[2:] - x[:-2]) / 2
    trib[0], trib[-1] = (x[1] - x[0]) / 2, (x[-1] - x[-2]) / 2
    return where, spec.k_soil * trib


def load_position(spec, t):
    """``(i, f)``: the load acts on node ``i`` with ``1 - f`` and on ``i + 1`` with ``f``; ``i = -1``
    when it is off the beam (``t <= 0`` or past its end), as ``winkler_beam``'s moving load."""
    h = spec.length / (spec.nodes - 1)
    x = spec.speed * t / h
    i = int(np.floor(x))
    if t <= 0.0 or i >= spec.nodes - 1:
        return -1, 0.0
    return i, x - i


def load_samples(spec, steps, dt):
    """The moving load's vertical nodal forces at ``t_k = k dt``, ``k = 0 .. steps + 1`` (one past
    the end: OpenSees's time, a sum of steps, may round past the last sample): ``{node: (steps+2,)}``."""
    t = dt * np.arange(steps + 2)
    out = {}
    for k, tk in enumerate(t):
        i, f = load_position(spec, tk)
        if i < 0:
            continue
        for node, share in ((i, 1.0 - f), (i + 1, f)):
            out.setdefault(node, np.zeros(len(t)))[k] -= share * spec.P
    return out


# --------------------------------------------------------------------------- the project's model

def frame2d(spec):
    """The :class:`~unilateral.structure.Structure`, the load ``q(t)`` and the middle node."""
    from unilateral.structure import Frame2D

    fr = Frame2D()                  # the nodes and elements from arrays (a loop of fr.beam(...): the same model)
    nodes = np.arange(spec.nodes)
    fr.nodes(nodes, x_of(spec), 0.0)
    fr.beams([f"b{i}" for i in range(spec.nodes - 1)], nodes[:-1], nodes[1:], E=1.0, A=spec.EA, I=spec.EI)
    fr.masses(nodes, masses(spec))
    on_soil, k = springs(spec)
    fr.soils([f"s{node}" for node in on_soil], on_soil, k)
    fr.support(0, ux=True, uy=False)
    fr.rayleigh(spec.a0, 0.0)
    st = fr.build()
    weight = st.gravity(spec.gravity)
    uy = uy_dofs(st, spec.nodes)

    def q(t):
        i, f = load_position(spec, t)
        if i < 0:
            return weight
        out = weight.copy()
        out[uy[i]] -= (1.0 - f) * spec.P
        out[uy[i + 1]] -= f * spec.P
        return out
    return st, q, spec.nodes // 2


def uy_dofs(st, nodes):
    """The index of each node's ``uy`` among the free DOFs."""
    index = {key: k for k, key in enumerate(st.dofs.free)}
    return np.array([index[(i, "uy")] for i in range(nodes)])


def run_unilateral(spec, steps, dt, method="auto", bilateral=False):
    """Middle node's ``uy`` (steps+1,), the wall time (model built and solved), the build time and
    the solution."""
    import unilateral as ul

    start = time.perf_counter()
    st, q, mid = frame2d(spec)
    model = st.to_model()
    built = time.perf_counter() - start
    sol = ul.solve(model, q, dt=dt, t_end=steps * dt, method=method, rule="trapezoidal", bilateral=bilateral)
    elapsed = time.perf_counter() - start
    if not sol.success:
        raise RuntimeError(sol.message)
    return st.node_displacement(sol, mid, "uy"), elapsed, built, sol


def kept(run):
    """A run without its :class:`~unilateral.Solution`: the output, the times and the statistics with
    ``open_steps`` (the steps with a constraint open). The solutions are not kept alive: a user's
    process holds one model, and the histories and name lists of earlier runs would be scanned by
    Python's garbage collector while the next run builds its model (20-30 ms at n = 9998)."""
    out, elapsed, built, sol = run
    open_steps = int(np.count_nonzero(np.asarray(sol.v).max(axis=1) > 0))
    return out, elapsed, built, dict(sol.stats, open_steps=open_steps)


def split(elapsed, built, laps):
    """``(setup, march, after)`` seconds of an end-to-end run: the march is the ``steps`` lap, the
    results after it (``recover``...) what follows it, the set-up the rest (build included)."""
    laps = dict(laps)
    march = laps.get("steps", 0.0)
    names = [k for k in laps if k != "total"]
    after = sum(laps[k] for k in names[names.index("steps") + 1:]) if "steps" in names else 0.0
    return elapsed - march - after, march, after


# --------------------------------------------------------------------------- OpenSees

def run_opensees(spec, steps, dt, system=OPENSEES_SYSTEM, tol=OPENSEES_TOL, material="ENT"):
    """Middle node's ``uy`` by OpenSees, wall time (built and solved), the first failed step (0:
    none), the Newton iterations in all and the set-up time (built, gravity step, patterns); in
    this process. ``material="Elastic"``: the springs bonded (a check of the linear beam)."""
    import openseespy.opensees as ops

    start = time.perf_counter()
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.geomTransf("Linear", 1)
    for i, (x, mass) in enumerate(zip(x_of(spec), masses(spec))):
        ops.node(i + 1, float(x), 0.0)
        ops.mass(i + 1, float(mass), float(mass), 0.0)
    ops.fix(1, 1, 0, 0)
    for i in range(spec.nodes - 1):
        ops.element("elasticBeamColumn", i + 1, i + 1, i + 2, spec.EA, 1.0, spec.EI, 1)
    ground = 10 * spec.nodes
    for j, (node, k) in enumerate(zip(*springs(spec))):
        ops.uniaxialMaterial(material, j + 1, float(k))
        ops.node(ground + j, float(x_of(spec)[node]), 0.0)
        ops.fix(ground + j, 1, 1, 1)
        # strain = u(beam) - u(ground): negative (compression) as the beam moves down
        ops.element("zeroLength", ground + j, ground + j, int(node) + 1, "-mat", j + 1, "-dir", 2)

    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for i, mass in enumerate(masses(spec)):
        ops.load(i + 1, 0.0, -float(mass) * spec.gravity, 0.0)

    analysis = _gravity_first(ops, system, tol, spec.a0)
    for tag, (node, values) in enumerate(sorted(load_samples(spec, steps, dt).items()), start=2):
        ops.timeSeries("Path", tag, "-dt", dt, "-values", *map(float, values))
        ops.pattern("Plain", tag, tag)
        ops.load(node + 1, 0.0, 1.0, 0.0)
    analysis("Transient")
    setup = time.perf_counter() - start
    mid = spec.nodes // 2 + 1
    uy = np.zeros(steps + 1)
    uy[0] = ops.nodeDisp(mid, 2)
    failed, iterations = 0, 0
    for k in range(1, steps + 1):
        if ops.analyze(1, dt) != 0:
            failed = k
            break
        iterations += ops.testIter()
        uy[k] = ops.nodeDisp(mid, 2)
    elapsed = time.perf_counter() - start
    ops.wipe()
    return uy, elapsed, failed, iterations, setup


def _gravity_first(ops, system, tol, a0):
    """The static gravity step (load control, Newton), ``loadConst``, damping ``a0 M``; returns the
    function that sets up an analysis of a kind (``"Transient"``: Newmark 1/2, 1/4, Newton)."""
    def analysis(kind):
        ops.wipeAnalysis()
        ops.constraints("Plain")
        ops.numberer("RCM")
        ops.system(system)
        ops.test("NormDispIncr", tol, 50)
        ops.algorithm("Newton")
        if kind == "Static":
            ops.integrator("LoadControl", 1.0)
        else:
            ops.integrator("Newmark", 0.5, 0.25)
        ops.analysis(kind)

    analysis("Static")
    if ops.analyze(1) != 0:
        raise RuntimeError("OpenSees: the static gravity step failed")
    ops.loadConst("-time", 0.0)
    ops.rayleigh(a0, 0.0, 0.0, 0.0)
    return analysis


def opensees_in_subprocess(spec, steps, dt, system=OPENSEES_SYSTEM, tol=OPENSEES_TOL, material="ENT"):
    """:func:`run_opensees` in a fresh process with the library path it needs; None without OpenSees."""
    env = opensees_environment()
    if env is None:
        return None
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); import opensees_winkler as b; "
            "a = json.loads(sys.stdin.read()); "
            "u, t, f, it, s = b.run_opensees(b.BeamSpec(**a['spec']), a['steps'], a['dt'], a['system'], a['tol'], "
            "a['material']); print(json.dumps({'uy': u.tolist(), 'time': t, 'failed': f, 'iterations': it, "
            "'setup': s}))")
    payload = json.dumps({"spec": asdict(spec), "steps": steps, "dt": dt, "system": system, "tol": tol,
                          "material": material})
    proc = subprocess.run([sys.executable, "-c", code, str(HERE)], input=payload, capture_output=True, text=True,
                          env=env, timeout=3600)
    if proc.returncode:
        raise RuntimeError(f"OpenSees run failed:\n{proc.stderr[-2000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    return np.array(out["uy"]), out["time"], out["failed"], out["iterations"], out["setup"]


# --------------------------------------------------------------------------- the banded recursion

def banded_reference(spec, steps, dt, repeats=3):
    """The linear beam (every spring bonded) stepped by Newmark's average acceleration with a banded
    Cholesky factor and compiled substitutions: middle node's ``uy``, seconds per step of the
    march (median of ``repeats``), seconds of the set-up (assembly and factorisation, model build
    excluded)."""
    import scipy.sparse as sp
    from scipy.linalg import cholesky_banded

    st, _, mid = frame2d(spec)
    start = time.perf_counter()
    n = st.n
    uy = uy_dofs(st, spec.nodes)
    K = st.to_model().K.tocsr()             # the springs bonded (v = 0) are in the model's K
    M = st.M.diagonal()
    C = st.C.diagonal() if st.C is not None else np.zeros(n)
    if st.C is not None and (st.C - sp.diags(C)).count_nonzero() or (st.M - sp.diags(M)).count_nonzero():
        raise ValueError("the banded reference needs lumped M and C")
    c1, c2 = 4.0 / dt**2, 2.0 / dt
    Keff = (K + sp.diags(c1 * M + c2 * C)).tocoo()
    bw = int(np.max(np.abs(Keff.col - Keff.row)))
    ab = np.zeros((bw + 1, n))
    upper = Keff.row <= Keff.col
    ab[bw + Keff.row[upper] - Keff.col[upper], Keff.col[upper]] = Keff.data[upper]
    U = np.ascontiguousarray(cholesky_banded(ab, lower=False).T)          # (n, bw+1): U[j, r]
    weight = st.gravity(spec.gravity)
    u0 = _static(K, weight)
    node = np.full(steps + 1, -1, dtype=np.int64)
    frac = np.zeros(steps + 1)
    for s in range(1, steps + 1):
        node[s], frac[s] = load_position(spec, s * dt)
    setup = time.perf_counter() - start
    _banded_march(U, bw, M, C, weight, uy, node, frac, spec.P, u0, dt, 2, uy[mid])      # compiled before
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        out = _banded_march(U, bw, M, C, weight, uy, node, frac, spec.P, u0, dt, steps, uy[mid])
        times.append(time.perf_counter() - start)
    return out, float(np.median(times)) / steps, setup


def _static(K, f):
    import scipy.sparse.linalg as sla

    return sla.spsolve(K.tocsc(), f)


def _compiled():
    import numba

    @numba.njit(fastmath=False)         # no cache: nothing written next to the script
    def march(U, bw, M, C, weight, uy, node, frac, P, u0, dt, steps, out_dof):
        n = u0.shape[0]
        u = u0.copy()
        v = np.zeros(n)
        a = np.zeros(n)
        rhs = np.empty(n)
        rdiag = 1.0 / U[:, bw]
        out = np.empty(steps + 1)
        out[0] = u[out_dof]
        c1, c2, c3 = 4.0 / dt**2, 2.0 / dt, 4.0 / dt
        for s in range(1, steps + 1):
            for j in range(n):
                rhs[j] = weight[j] + M[j] * (c1 * u[j] + c3 * v[j] + a[j]) + C[j] * (c2 * u[j] + v[j])
            i = node[s]
            if i >= 0:
                rhs[uy[i]] -= (1.0 - frac[s]) * P
                rhs[uy[i + 1]] -= frac[s] * P
            for j in range(n):                      # U^T y = rhs, U[i, j] = Ub[j, bw + i - j]
                acc = rhs[j]
                for r in range(max(0, j - bw), j):
                    acc -= U[j, bw + r - j] * rhs[r]
                rhs[j] = acc * rdiag[j]
            for j in range(n - 1, -1, -1):          # U x = y, by columns (row j of Ub: column j of U)
                x = rhs[j] * rdiag[j]
                rhs[j] = x                          # rhs now holds the new u
                for r in range(max(0, j - bw), j):
                    rhs[r] -= U[j, bw + r - j] * x
            for j in range(n):
                du = rhs[j] - u[j]
                a_new = c1 * du - c3 * v[j] - a[j]
                v[j] = c2 * du - v[j]
                a[j] = a_new
                u[j] = rhs[j]
            out[s] = u[out_dof]
        return out
    return march


_MARCH = []


def _banded_march(*args):
    if not _MARCH:
        _MARCH.append(_compiled())
    return _MARCH[0](*args)


# --------------------------------------------------------------------------- the tower

@dataclass(frozen=True)
class TowerSpec:
    """The benchmark suite's tower (``unilateral.bench.problems``' constants; kN, m, s, t) on plain
    tensionless springs, mass-proportional damping ``a0 M`` (``zeta`` at ``f1``, its first mode
    with the springs bonded)."""

    storeys: int = 5
    storey_height: float = 3.0
    mass: float = 40.0                      # per storey, on ux and uy
    EI: float = 1e9
    EA: float = 1e12                        # axially practically rigid
    half_width: float = 3.0                 # the footing nodes at -+ half_width
    k_soil: float = 200e3                   # kN/m, each of the three springs
    gravity: float = 10.0
    duration: float = 10.0                  # s, the record
    pga: float = 4.0
    seed: int = 1
    zeta: float = 0.05
    f1: float = 2.13                        # Hz

    @property
    def a0(self):
        return 2 * self.zeta * 2 * np.pi * self.f1


TOWER_STEPS = 10_000                        # dt = 1 ms, as the suite's tower
QUICK_TOWER = (TowerSpec(duration=1.0), 400)


def tower_samples(spec, steps):
    """The record at ``k dt``, ``k = 0 .. steps + 1`` (``dt = duration / steps``; one past the end
    for OpenSees's time, a sum of steps)."""
    from unilateral.loads import synthetic_accelerogram

    record = synthetic_accelerogram(spec.duration, pga=spec.pga, seed=spec.seed)
    return np.asarray(record(np.arange(steps + 2) * (spec.duration / steps)), dtype=float)


def tower_frame2d(spec):
    """The :class:`~unilateral.structure.Structure` of ``problems.tower`` with ``c = 0`` and ``a0 M``."""
    from unilateral.structure import Frame2D

    fr = Frame2D()
    fr.node("base", 0.0, 0.0)
    fr.node("left", -spec.half_width, 0.0)
    fr.node("right", spec.half_width, 0.0)
    fr.support("base", ux=True, uy=False)
    fr.rigid_link("base", "left")
    fr.rigid_link("base", "right")
    below = "base"
    for storey in range(1, spec.storeys + 1):
        fr.node(storey, 0.0, storey * spec.storey_height)
        fr.beam(f"column{storey}", below, storey, E=1.0, A=spec.EA, I=spec.EI)
        fr.mass(storey, spec.mass)
        below = storey
    for node in ("left", "base", "right"):
        fr.soil(f"soil_{node}", node, spec.k_soil)
    fr.rayleigh(spec.a0, 0.0)
    return fr.build()


def tower_load(st, spec, samples, steps):
    """``gravity + ground_motion(record, "ux")`` at ``k dt`` (steps+1, n), as ``problems.tower``'s
    :class:`~unilateral.loads.LoadHistory` evaluates it at a time (``LoadHistory.sample``)."""
    inertia = -(st.M @ st.influence("ux"))
    load = np.multiply.outer(samples[:steps + 1], inertia)
    load += st.gravity(spec.gravity)
    return load


def run_tower_unilateral(spec, steps, samples, method="auto"):
    """``(ux of the top, uy of the base, rz of the base)`` (each steps+1), the wall time (model built,
    load formed and solved), the build time and the solution."""
    import unilateral as ul

    start = time.perf_counter()
    st = tower_frame2d(spec)
    model = st.to_model()
    q = tower_load(st, spec, samples, steps)
    built = time.perf_counter() - start
    sol = ul.solve(model, q, dt=spec.duration / steps, t_end=spec.duration, method=method, rule="trapezoidal")
    elapsed = time.perf_counter() - start
    if not sol.success:
        raise RuntimeError(sol.message)
    out = np.array([st.node_displacement(sol, spec.storeys, "ux"), st.node_displacement(sol, "base", "uy"),
                    st.node_displacement(sol, "base", "rz")])
    return out, elapsed, built, sol


def run_tower_opensees(spec, steps, samples, system=OPENSEES_SYSTEM, tol=OPENSEES_TOL):
    """The tower in OpenSees: ``(ux top, uy base, rz base)`` (3, steps+1), wall time (built and
    solved), the first failed step (0: none), the Newton iterations and the set-up time; in this
    process. The edge springs are ``twoNodeLink`` levers (see the module's docstring)."""
    import openseespy.opensees as ops

    start = time.perf_counter()
    dt = spec.duration / steps
    ops.wipe()
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.geomTransf("Linear", 1)
    base, top = 100, spec.storeys
    ops.node(base, 0.0, 0.0)
    ops.fix(base, 1, 0, 0)
    below = base
    for storey in range(1, spec.storeys + 1):
        ops.node(storey, 0.0, storey * spec.storey_height)
        ops.mass(storey, spec.mass, spec.mass, 0.0)
        ops.element("elasticBeamColumn", storey, below, storey, spec.EA, 1.0, spec.EI, 1)
        below = storey
    ops.uniaxialMaterial("ENT", 1, spec.k_soil)                 # no tension: stiff for strain < 0
    ops.uniaxialMaterial("Elastic", 2, spec.k_soil, 0.0, 0.0)   # no compression: the mirrored one
    for j, x in enumerate((-spec.half_width, 0.0, spec.half_width)):
        ops.node(200 + j, x, 0.0)
        ops.fix(200 + j, 1, 1, 1)
    ops.element("zeroLength", 201, 201, base, "-mat", 1, "-dir", 2)            # strain uy_base
    # from the ground node at the edge to the base, the spring at the ground node's end:
    # deformation uy_base - 3 rz (left), -(uy_base + 3 rz) (right: local y points down)
    ops.element("twoNodeLink", 200, 200, base, "-mat", 1, "-dir", 2, "-shearDist", 0.0)
    ops.element("twoNodeLink", 202, 202, base, "-mat", 2, "-dir", 2, "-shearDist", 0.0)

    ops.timeSeries("Linear", 1)
    ops.pattern("Plain", 1, 1)
    for storey in range(1, spec.storeys + 1):
        ops.load(storey, 0.0, -spec.mass * spec.gravity, 0.0)

    analysis = _gravity_first(ops, system, tol, spec.a0)
    ops.timeSeries("Path", 2, "-dt", dt, "-values", *map(float, samples))
    ops.pattern("UniformExcitation", 2, 1, "-accel", 2)
    analysis("Transient")
    setup = time.perf_counter() - start
    out = np.zeros((3, steps + 1))
    out[:, 0] = ops.nodeDisp(top, 1), ops.nodeDisp(base, 2), ops.nodeDisp(base, 3)
    failed, iterations = 0, 0
    for k in range(1, steps + 1):
        if ops.analyze(1, dt) != 0:
            failed = k
            break
        iterations += ops.testIter()
        out[:, k] = ops.nodeDisp(top, 1), ops.nodeDisp(base, 2), ops.nodeDisp(base, 3)
    elapsed = time.perf_counter() - start
    ops.wipe()
    return out, elapsed, failed, iterations, setup


def tower_opensees_in_subprocess(spec, steps, samples, system=OPENSEES_SYSTEM, tol=OPENSEES_TOL):
    """:func:`run_tower_opensees` in a fresh process with its library path; None without OpenSees."""
    env = opensees_environment()
    if env is None:
        return None
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); import opensees_winkler as b; "
            "a = json.loads(sys.stdin.read()); "
            "u, t, f, it, s = b.run_tower_opensees(b.TowerSpec(**a['spec']), a['steps'], a['samples'], a['system'], "
            "a['tol']); print(json.dumps({'u': u.tolist(), 'time': t, 'failed': f, 'iterations': it, 'setup': s}))")
    payload = json.dumps({"spec": asdict(spec), "steps": steps, "samples": list(map(float, samples)),
                          "system": system, "tol": tol})
    proc = subprocess.run([sys.executable, "-c", code, str(HERE)], input=payload, capture_output=True, text=True,
                          env=env, timeout=3600)
    if proc.returncode:
        raise RuntimeError(f"OpenSees run failed:\n{proc.stderr[-2000:]}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    return np.array(out["u"]), out["time"], out["failed"], out["iterations"], out["setup"]


def spring_uy(u, spec):
    """``uy`` under the left, middle and right springs (3, steps+1) from ``(ux top, uy base, rz
    base)``: a spring is open where its node is above the soil's unloaded level (``uy > 0``)."""
    return np.array([u[1] - spec.half_width * u[2], u[1], u[1] + spec.half_width * u[2]])


def compare_tower(spec, steps, *, repeats=3, opensees=True, system=OPENSEES_SYSTEM, tol=OPENSEES_TOL):
    """The tower row: medians of ``repeats`` runs of each code (after the caller's warm-up)."""
    samples = tower_samples(spec, steps)
    run_tower_unilateral(spec, steps, samples)          # untimed, as the Winkler cells
    runs = [kept(run_tower_unilateral(spec, steps, samples)) for _ in range(repeats)]
    u, _, _, stats = sorted(runs, key=lambda r: r[1])[(repeats - 1) // 2]
    parts = np.array([split(r[1], r[2], r[3]["time"]) for r in runs])
    open_steps = stats["open_steps"]
    row = {"problem": "tower", "spec": asdict(spec), "a0": spec.a0, "n": int(stats["n"]), "m": int(stats["m"]),
           "steps": steps, "dt": spec.duration / steps, "auto_method": stats["method"],
           "auto_engine": stats.get("engine"), "contact_changes": int(stats["contact_changes"]),
           "open_steps": open_steps, "peak_top_ux_m": float(np.abs(u[0]).max()),
           "auto_s": float(np.median([r[1] for r in runs])), "build_s": float(np.median([r[2] for r in runs])),
           "setup_s": float(np.median(parts[:, 0])), "march_s": float(np.median(parts[:, 1])),
           "after_march_s": float(np.median(parts[:, 2])),
           "auto_laps": {k: float(v) for k, v in stats["time"].items()}}
    row["setup_share"] = row["setup_s"] / row["auto_s"]
    row["march_us_per_step"] = 1e6 * row["march_s"] / steps
    direct = [kept(run_tower_unilateral(spec, steps, samples, method="direct")) for _ in range(repeats)]
    row["direct_s"] = float(np.median([d[1] for d in direct]))
    row["direct_difference_over_peak"] = float(np.abs(direct[0][0][0] - u[0]).max() / np.abs(u[0]).max())
    if opensees:
        theirs = [tower_opensees_in_subprocess(spec, steps, samples, system, tol) for _ in range(repeats)]
        if theirs[0] is not None:
            u_os, _, failed, iterations, _ = theirs[0]
            row["opensees_s"] = float(np.median([t[1] for t in theirs]))
            row["opensees_setup_s"] = float(np.median([t[4] for t in theirs]))
            row["opensees_failed_step"] = int(failed)
            row["opensees_newton_iterations"] = int(iterations)
            row["opensees_open_steps"] = int(np.count_nonzero(spring_uy(u_os, spec).max(axis=0) > 0))
            row["ratio"] = row["auto_s"] / row["opensees_s"]
            row["difference_over_peak"] = float(np.abs(u[0] - u_os[0]).max() / np.abs(u_os[0]).max())
            row["base_uy_difference_over_peak"] = float(np.abs(u[1] - u_os[1]).max() / np.abs(u_os[1]).max())
    return row


def print_tower(row, file=None):
    nan = float("nan")
    r = row
    print(f"{'tower':>5} {'n':>3} {'m':>2} {'steps':>6} {'changes':>7} {'open':>5} {'auto s':>7} {'build s':>7} "
          f"{'set-up s':>8} {'march us/step':>13} {'direct s':>8} {'OpenSees s':>10} {'OS set-up':>9} "
          f"{'OS open':>7} {'ratio':>6} {'diff/peak':>9} {'uy diff':>8}", file=file)
    print(f"{'':>5} {r['n']:>3} {r['m']:>2} {r['steps']:>6} {r['contact_changes']:>7} {r['open_steps']:>5} "
          f"{r['auto_s']:7.3f} {r['build_s']:7.3f} {r['setup_s']:8.3f} {r['march_us_per_step']:13.2f} "
          f"{r['direct_s']:8.3f} {r.get('opensees_s', nan):10.3f} {r.get('opensees_setup_s', nan):9.3f} "
          f"{r.get('opensees_open_steps', -1):>7} {r.get('ratio', nan):6.3f} {r.get('difference_over_peak', nan):9.1e} "
          f"{r.get('base_uy_difference_over_peak', nan):8.1e}", file=file)
    print(f"tower: dt = {r['dt']:g} s, EA = {r['spec']['EA']:g}, a0 = {r['a0']:.4g} 1/s (mass-proportional), "
          f"open = steps with a spring open; auto = {r['auto_method']}", file=file)


# --------------------------------------------------------------------------- the table

def compare(spec, steps, dt=DT, *, repeats=3, opensees=True, banded=True, roundoff=True, system=OPENSEES_SYSTEM,
            tol=OPENSEES_TOL):
    """One cell: medians of ``repeats`` runs of each code (after the caller's warm-up and one run of
    the project's at this size)."""
    run_unilateral(spec, steps, dt)         # untimed: the first run of a size is up to 2x slower (memory)
    runs = [kept(run_unilateral(spec, steps, dt)) for _ in range(repeats)]
    uy, _, _, stats = sorted(runs, key=lambda r: r[1])[(repeats - 1) // 2]     # the median run's laps
    parts = np.array([split(r[1], r[2], r[3]["time"]) for r in runs])
    row = {"nodes": spec.nodes, "n": int(stats["n"]), "m": int(stats["m"]), "steps": steps, "dt": dt,
           "auto_method": stats["method"], "auto_engine": stats.get("engine"),
           "lcp_space": stats.get("lcp_space"), "contact_changes": int(stats["contact_changes"]),
           "peak_uy_m": float(np.abs(uy).max()),
           "auto_s": float(np.median([r[1] for r in runs])), "build_s": float(np.median([r[2] for r in runs])),
           "setup_s": float(np.median(parts[:, 0])), "march_s": float(np.median(parts[:, 1])),
           "after_march_s": float(np.median(parts[:, 2])),
           "auto_laps": {k: float(v) for k, v in stats["time"].items()}}
    row["setup_share"] = row["setup_s"] / row["auto_s"]
    row["march_us_per_step"] = 1e6 * row["march_s"] / steps
    direct = [kept(run_unilateral(spec, steps, dt, method="direct")) for _ in range(repeats)]
    row["direct_s"] = float(np.median([d[1] for d in direct]))
    row["direct_difference_over_peak"] = float(np.abs(direct[0][0] - uy).max() / np.abs(uy).max())
    if banded:
        ub, per_step, setup = banded_reference(spec, steps, dt, repeats)
        row["banded_us_per_step"] = 1e6 * per_step
        row["banded_setup_s"] = setup
        row["march_over_banded"] = row["march_us_per_step"] / row["banded_us_per_step"]
        row["linear_over_peak"] = float(np.abs(ub - uy).max() / np.abs(uy).max())   # how far from linear
    if opensees:
        theirs = [opensees_in_subprocess(spec, steps, dt, system, tol) for _ in range(repeats)]
        if theirs[0] is not None:
            u_os, _, failed, iterations, _ = theirs[0]
            row["opensees_s"] = float(np.median([t[1] for t in theirs]))
            row["opensees_setup_s"] = float(np.median([t[4] for t in theirs]))
            row["opensees_failed_step"] = int(failed)
            row["opensees_newton_iterations"] = int(iterations)
            row["ratio"] = row["auto_s"] / row["opensees_s"]
            row["difference_over_peak"] = float(np.abs(uy - u_os).max() / np.abs(u_os).max())
            if roundoff and banded:     # the round-off scale: the linear beam in OpenSees and the recursion
                u_lin = opensees_in_subprocess(spec, steps, dt, system, tol, material="Elastic")[0]
                row["linear_difference_over_peak"] = float(np.abs(u_lin - ub).max() / np.abs(ub).max())
    return row


def print_table(rows, load, file=None):
    nan = float("nan")
    print(f"load average {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}", file=file)
    print(f"{'n':>5} {'m':>5} {'steps':>5} {'changes':>7} {'auto s':>7} {'build s':>7} {'set-up s':>8} "
          f"{'share':>6} "
          f"{'march us/step':>13} {'direct s':>8} {'OpenSees s':>10} {'OS set-up':>9} {'ratio':>6} "
          f"{'diff/peak':>9} {'linear diff':>11} {'banded us/step':>14} {'march/banded':>12}", file=file)
    for r in rows:
        print(f"{r['n']:>5} {r['m']:>5} {r['steps']:>5} {r['contact_changes']:>7} {r['auto_s']:7.3f} "
              f"{r['build_s']:7.3f} "
              f"{r['setup_s']:8.3f} {r['setup_share']:6.1%} {r['march_us_per_step']:13.1f} {r['direct_s']:8.3f} "
              f"{r.get('opensees_s', nan):10.3f} {r.get('opensees_setup_s', nan):9.3f} {r.get('ratio', nan):6.3f} "
              f"{r.get('difference_over_peak', nan):9.1e} {r.get('linear_difference_over_peak', nan):11.1e} "
              f"{r.get('banded_us_per_step', nan):14.2f} {r.get('march_over_banded', nan):12.1f}", file=file)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--quick", action="store_true", help="the two small cells, few steps (a smoke test)")
    parser.add_argument("--repeats", type=int, default=3, help="runs per code and cell (the median is shown)")
    parser.add_argument("--out", type=Path, default=RESULTS / "opensees_winkler.json")
    parser.add_argument("--no-opensees", action="store_true", help="the project's rows only")
    parser.add_argument("--opensees-system", default=OPENSEES_SYSTEM, help="OpenSees's linear system")
    parser.add_argument("--opensees-tol", type=float, default=OPENSEES_TOL, help="its NormDispIncr tolerance (m)")
    parser.add_argument("--no-tower", action="store_true", help="without the tower row")
    parser.add_argument("--tower-steps", type=int, default=None,
                        help=f"steps of the tower row (default {TOWER_STEPS}; --quick: a {QUICK_TOWER[0].duration:g} s "
                             f"record in {QUICK_TOWER[1]})")
    args = parser.parse_args(argv)
    cells = QUICK_CELLS if args.quick else CELLS
    start = time.perf_counter()
    warm = BeamSpec(nodes=33, springs=11)               # warm-up: loads the compiled code of every path
    for method in ("auto", "direct"):
        run_unilateral(warm, 20, DT, method=method)
        run_unilateral(BeamSpec(nodes=333, springs=100), 5, DT, method=method)
    banded_reference(warm, 5, DT)
    rows = [compare(BeamSpec(nodes=nodes, springs=m), steps, repeats=args.repeats, opensees=not args.no_opensees,
                    system=args.opensees_system, tol=args.opensees_tol) for nodes, m, steps in cells]
    tower = None
    if not args.no_tower:
        spec, steps = QUICK_TOWER if args.quick else (TowerSpec(), TOWER_STEPS)
        steps = args.tower_steps or steps
        for method in ("auto", "direct"):                # warm-up: the tower's compiled paths
            run_tower_unilateral(spec, steps, tower_samples(spec, steps), method=method)
        tower = compare_tower(spec, steps, repeats=args.repeats, opensees=not args.no_opensees,
                              system=args.opensees_system, tol=args.opensees_tol)
    load = os.getloadavg()
    print_table(rows, load)
    if tower is not None:
        print_tower(tower)
    wall = time.perf_counter() - start
    print(f"dt = {DT} s; OpenSees: system {args.opensees_system}, NormDispIncr {args.opensees_tol:g}, Newton; "
          f"{args.repeats} repeats; the table took {wall:.0f} s")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(json.dumps({"utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "load_average": load,
                               "cpus": os.cpu_count(), "dt": DT, "repeats": args.repeats, "quick": args.quick,
                               "opensees": {"system": args.opensees_system, "test": "NormDispIncr",
                                            "tol": args.opensees_tol, "algorithm": "Newton",
                                            "integrator": "Newmark 0.5 0.25"},
                               "wall_s": wall, "rows": rows, "tower": tower}, indent=1))
    tmp.replace(args.out)
    return rows


if __name__ == "__main__":
    main()
