"""One analysis of a study, as run by a worker: build (cached), solve, collect the peaks.

:func:`run_analysis` takes the payload of an :class:`~unilateral.batch.study.Analysis` (a small
JSON-able dict), the source of its model variant (:func:`unilateral.batch.inputs.variant_source`:
the model text, the changed values, the files it refers to) and its record's samples, and returns
the result, failures included; the process that runs the study writes it. A worker reads no file
of the study, so a cluster needs no file system shared with that process. The built model
variants are cached per process (a Dask worker process runs many analyses), keyed by the hash of
their source: a worker builds each variant once, whatever the number of its analyses.
"""

from __future__ import annotations

import copy
import functools
import math
import os
import socket
import time
import tomllib
import traceback
from pathlib import Path

import numpy as np

_MODEL_CACHE: dict = {}
_VECTOR_CACHE: dict = {}
_CACHE_STATS = {"model_builds": 0}
_FILES: dict = {}
NOTES = {
    "base_shear": "not available: the model is not a frame (no elements to take the ground forces from)",
    "energy_error": "not available: the model is not a frame (no elements to take the energies from)",
}


class AnalysisTimeout(Exception):
    """An analysis that did not finish within its time limit."""


def cache_stats() -> dict:
    """How many model variants this process has built (``model_builds``), and its ``pid``."""
    return dict(_CACHE_STATS, pid=os.getpid())


def clear_caches() -> None:
    """Forget the model variants built by this process."""
    _MODEL_CACHE.clear()
    _VECTOR_CACHE.clear()


# ---------------------------------------------------------------------- cached inputs
def variant_data(text: str, overrides) -> dict:
    """The parsed model file ``text`` with the changed values ``[(key path, value), ...]`` applied in order."""
    from .keypath import set_key_path

    data = tomllib.loads(text)
    for key_path, value in overrides:
        set_key_path(data, key_path, copy.deepcopy(value))
    return data


def file_references(data) -> list:
    """The file names of a parsed model file: the ``file`` keys and the strings of ``[matrices]``."""
    found = []

    def walk(node, in_matrices=False):
        if isinstance(node, dict):
            for key, value in node.items():
                if isinstance(value, str) and (key == "file" or in_matrices):
                    found.append(value)
                else:
                    walk(value, in_matrices or key == "matrices")
        elif isinstance(node, list):
            for value in node:
                walk(value, in_matrices)

    walk(data)
    return found


def localize_files(data, files: dict) -> None:
    """Point the file names of ``data`` that ``files`` holds (``{name: bytes}``) at copies of
    theirs in a folder of this process (written once per content), in place."""
    def local(name):
        return str(_local_copy(name, files[name])) if name in files else name

    def walk(node, in_matrices=False):
        items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
        for key, value in list(items):
            if isinstance(value, str) and (key == "file" or in_matrices):
                node[key] = local(value)
            else:
                walk(value, in_matrices or key == "matrices")

    walk(data)


def _local_copy(name: str, content: bytes) -> Path:
    """A file of this process' temporary folder holding ``content`` (named by its hash, suffix kept)."""
    import hashlib
    import tempfile

    if "folder" not in _FILES:
        _FILES["folder"] = tempfile.TemporaryDirectory(prefix="unilateral-batch-")     # removed at exit
    path = Path(_FILES["folder"].name) / f"{hashlib.sha256(content).hexdigest()[:24]}{Path(name).suffix}"
    if not path.exists():
        path.write_bytes(content)
    return path


def model_variant(source: dict):
    """``(spec, ground-motion vector or None, node y coordinates, FrameOperators or None)`` of a
    model variant, built once per process (cached by ``source["digest"]``).

    Parameters
    ----------
    source : dict
        :func:`unilateral.batch.inputs.variant_source` of the variant.
    """
    from ..modelfile import build_model_spec

    hit = _MODEL_CACHE.get(source["digest"])
    if hit is not None:
        return hit
    data = variant_data(source["text"], source["overrides"])
    localize_files(data, source["files"])
    spec = build_model_spec(data, Path(source["path"]))
    vector = _ground_vector(spec, source["ground_motion"], source["influence"])
    # elevations (of the drift ratios): y in a plane frame, z in a space frame
    ys = {node.id: getattr(node, "z", node.y) for node in spec.document.nodes}
    _CACHE_STATS["model_builds"] += 1
    frame = None if spec.structure is None else FrameOperators(spec.structure)
    _MODEL_CACHE[source["digest"]] = (spec, vector, ys, frame)
    return _MODEL_CACHE[source["digest"]]


def _ground_vector(spec, ground: dict, influence: bytes | None):
    """``-M r`` of the study's ground motion, as the model file builds it (``influence``: the
    Matrix Market file of ``r`` of a matrix-level model)."""
    if not ground or "pairs" in ground:      # the vectors of a pair: pair_vectors, per analysis
        return None
    model = spec.model
    if "direction" in ground:
        r = np.array([1.0 if dof == ground["direction"] else 0.0 for _, dof in spec.structure.dofs.free])
    else:
        from ..modelfile.errors import Problems
        from ..modelfile.matrices import read_vector

        path = _local_copy(ground["influence"], influence)
        try:      # the header checked first (a real vector of n entries), as the model files' matrices
            r = read_vector(("ground", "influence"), path.name, path.parent, model.n)
        except Problems as exc:
            raise ValueError(str(exc)) from None
    return -np.asarray(model.M @ r).ravel()


def plan_direction(direction: str, angle: float):
    """The ground motion direction ``direction`` of a 3-D frame rotated in plan by ``angle`` degrees:
    ``"ux"`` -> ``(cos a, sin a, 0)``, ``"uy"`` -> ``(-sin a, cos a, 0)``, ``"uz"`` (and any direction
    at a zero angle) itself. The cosine and sine of a multiple of 90 degrees are exact (0, 1, -1)."""
    if direction == "uz" or angle == 0:
        return direction
    quarter, rest = divmod(float(angle), 90.0)
    if rest == 0:
        c, s = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[int(quarter) % 4]
    else:
        a = math.radians(angle)
        c, s = math.cos(a), math.sin(a)
    return (c, s, 0.0) if direction == "ux" else (-s, c, 0.0)


def pair_vectors(spec, digest: str, ground: dict) -> list:
    """``[-M r_i]`` of the components of a pair (``ground``: ``{"directions", "angle"}``), each ``r_i``
    as a model file's ``[[loads.ground_motion]]`` along that direction builds it (a 3-D frame:
    ``Frame3D.influence``, of the direction rotated by the angle, :func:`plan_direction`; a 2-D
    frame: 1 on the free DOFs along it). Cached per model variant (``digest``), directions and angle."""
    key = (digest, tuple(ground["directions"]), float(ground["angle"]))
    hit = _VECTOR_CACHE.get(key)
    if hit is not None:
        return hit
    structure, model = spec.structure, spec.model
    if structure is None:
        raise ValueError("a pair of records needs a frame (a matrix-level model has no directions)")
    vectors = []
    for direction in ground["directions"]:
        if len(structure.dofs.dof_names) == 6:
            r = structure.influence(plan_direction(direction, ground["angle"]))
        else:
            r = np.array([1.0 if dof == direction else 0.0 for _, dof in structure.dofs.free])
        vectors.append(-np.asarray(model.M @ r).ravel())
    _VECTOR_CACHE[key] = vectors
    return vectors


def analysis_load(spec, vector, record, scale: float):
    """The model's load with the record ``record`` (m/s^2) times ``scale`` as its ground motion.

    The same arithmetic as a model file's ``[[loads.ground_motion]]`` with ``scale``: a study's
    analysis equals the model file run with that record, bit for bit. A pair: ``vector`` the list
    of the components' vectors (:func:`pair_vectors`), ``record`` the tuple of their records, each a
    term of its own in their order, as the ``[[loads.ground_motion]]`` entries of a model file.
    """
    from ..loads import LoadHistory, Tabulated, length_factor
    from ..modelfile.schema import TIME_UNITS

    if vector is None:
        return spec.load
    seconds = TIME_UNITS[spec.units["time"]]
    to_model = seconds ** 2 / length_factor(spec.units["length"])
    pairs = zip(vector, record, strict=True) if isinstance(vector, list) else [(vector, record)]
    terms = tuple((v, Tabulated(r.time / seconds, r.acceleration * (scale * to_model))) for v, r in pairs)
    return LoadHistory(spec.load.constant, tuple(spec.load.terms) + terms, sampling=spec.load.sampling)


# ---------------------------------------------------------------------- peaks
def contact_names(model, names=None) -> list:
    """The names of the contact unknowns of ``model`` (the family kind ``"contact"``: soil and gap
    elements, cables, footing patches): the default elements of the quantities ``uplift`` and
    ``contact_force``, whose ``v`` is an opening and ``psi`` minus a contact force. Plastic multipliers
    (``yield``), slips (``friction``) and a sliding footing's shears (``shear``) are left out.

    Parameters
    ----------
    model : Model or FoundationModel (its step law's ``kinds``, one per unknown)
    names : the unknowns' names (default ``model.constraint_names``)

    Returns
    -------
    list of str, in the model's order (every name if the model states no kinds)
    """
    names = list(model.constraint_names if names is None else names)
    kinds = getattr(getattr(model, "law", None), "kinds", None)
    if kinds is None or len(kinds) != len(names):
        return names
    return [n for n, kind in zip(names, kinds) if kind == "contact"]


def _peak(x) -> float:
    x = np.asarray(x, dtype=float)
    return float(np.max(np.abs(x))) if x.size else math.nan


def collect(quantity: dict, sol, spec, ys: dict, frame: FrameResults | None = None) -> tuple[dict, list]:
    """``({column: value}, notes)`` of one ``[[quantities]]`` entry for the solution ``sol``.

    ``frame`` gives ``base_shear`` and ``energy_error`` (None: not a frame, NaN with a note).
    """
    kind, name = quantity["type"], quantity["name"]
    notes = []
    if kind == "footing":
        from .footing_quantity import collect_footing

        return collect_footing(quantity, sol, spec.structure)
    if kind in ("uplift", "contact_force"):
        names = quantity["elements"] or contact_names(spec.model, sol.constraint_names)
        if not names:
            return {name: math.nan} if quantity["over"] != "each" else {}, [
                f"{name}: not available: the model has no contact unknowns (its unknowns are plastic "
                "multipliers, slips or shears; name them in elements to take their peaks)"]
        missing = [n for n in names if n not in sol.constraint_names]
        if missing:
            raise KeyError(f"quantity {name}: no unilateral element {missing[0]!r} "
                           f"(elements: {', '.join(sol.constraint_names)})")
        cols = [sol.constraint_names.index(n) for n in names]
        series = (sol.v if kind == "uplift" else sol.psi)[:, cols]       # a copy by columns: fast reductions
        if not series.shape[0]:
            peaks = np.full(len(cols), math.nan)
        else:                                          # the contact force is -psi: its peak -min(psi)
            peaks = series.max(axis=0) if kind == "uplift" else -series.min(axis=0)
        if quantity["over"] == "each":
            return {f"{name}.{n}": float(p) for n, p in zip(names, peaks)}, notes
        return {name: float(np.max(peaks)) if peaks.size else math.nan}, notes
    if kind in ("displacement", "residual"):
        u = _dof_history(sol, spec, quantity["node"], quantity["dof"])
        return {name: _peak(u) if kind == "displacement" else abs(float(u[-1] - u[0]))}, notes
    if kind == "drift":
        dof = quantity["dof"] or "ux"
        values = []
        for upper, lower in quantity["pairs"]:
            d = _dof_history(sol, spec, upper, dof) - _dof_history(sol, spec, lower, dof)
            if quantity["ratio"]:
                d = d / (ys[upper] - ys[lower])
            values.append(_peak(d))
        return {name: max(values)}, notes
    if kind in ("base_shear", "energy_error"):
        if frame is None:
            return {name: math.nan}, [f"{name}: {NOTES[kind]}"]
        try:
            return {name: frame.peak_base_shear() if kind == "base_shear" else frame.energy_error()}, notes
        except (ValueError, TypeError) as exc:     # refused with its reason, not 0
            return {name: math.nan}, [f"{name}: not available: {exc}"]
    raise ValueError(f"unknown quantity type {kind!r}")


class FrameOperators:
    """The matrices :class:`FrameResults` needs of one model variant, built on first use and
    cached with the variant (a worker builds them once, whatever the number of its analyses).

    Parameters
    ----------
    structure : Structure of the model variant
    """

    def __init__(self, structure):
        self.structure = structure

    @functools.cached_property
    def base_forces(self):
        """:class:`~unilateral.structure.forces.BaseForceOperator` of the structure."""
        from ..structure.forces import BaseForceOperator

        return BaseForceOperator.of(self.structure)

    @functools.cached_property
    def energy_balance(self):
        """:class:`~unilateral.analysis.energy.EnergyBalance` of the structure."""
        from ..analysis.energy import EnergyBalance

        return EnergyBalance(self.structure)


class FrameResults:
    """Base shear and energy error of one solved frame, from the state the two need only.

    The state is the solution's ``u``, ``u'``, ``v`` and the rule's ``v'`` as
    :class:`~unilateral.structure.forces.StateRows` (no accelerations, no element forces); the
    base shear is its product with the variant's
    :class:`~unilateral.structure.forces.BaseForceOperator`, the energies those of its
    :class:`~unilateral.analysis.energy.EnergyBalance`. A footing on a soil medium is handled as
    :func:`unilateral.analysis.results.structure_results` does: the frame alone, loaded by the
    contact forces too, whose work went into the soil; the soil's forces on the footings are
    ground reactions (the horizontal ones of footings that slide are in the base shear). Both
    numbers equal those of ``structure_results`` to round-off (``tests/test_batch.py``).

    Parameters
    ----------
    sol : Solution of ``spec.model``;  operators : FrameOperators of the variant;  load : the
    analysis' load;  rule : the time rule of the run (name or Rule)
    """

    def __init__(self, sol, operators: FrameOperators, load, rule):
        self.sol, self.operators, self.load, self.rule = sol, operators, load, rule
        self.foundation = operators.structure.foundation

    @functools.cached_property
    def state(self):
        """:class:`~unilateral.structure.forces.StateRows` of the run (of the frame alone with a foundation)."""
        from ..structure.forces import StateRows

        sol = self.sol
        if self.foundation is not None:
            from ..structure.foundation import structural_solution

            sol = structural_solution(sol, self.foundation.first)
        return StateRows.of_solution(sol, self.rule)

    @property
    def three_d(self) -> bool:
        """Whether the frame is a 3-D one (six DOFs per node)."""
        return len(self.operators.structure.dofs.dof_names) == 6

    def peak_base_shear(self) -> float:
        """Peak |sum of the x forces of the ground| (force unit of the model); of a 3-D frame, the
        peak of the horizontal resultant ``sqrt(Fx^2 + Fy^2)``
        (:func:`unilateral.structure.forces3d.base_forces`)."""
        if not self.three_d:
            shear = self.operators.base_forces.base_shear(self.state)
            if self.foundation is not None:         # the soil's forces on the footings (horizontal: sliding)
                forces, _ = self.foundation.ground_reactions(self.operators.structure, self.sol)
                shear = shear + sum(f[:, 0] for f in forces.values())
            return _peak(shear)
        from ..structure import forces3d as F3

        structure, sol = self.operators.structure, self.sol
        h = F3.histories(structure, sol, self.rule, load0=self.initial_load())
        base = F3.base_forces(structure, F3.reactions(structure, h, sol), F3.base_point(structure))
        return _peak(np.hypot(base["Fx"], base["Fy"]))

    def initial_load(self):
        """The load (n,) the run used at ``t = 0+`` (row 0 of its samples, :func:`_load_samples`: the
        hat-function average of a LoadHistory), for the initial acceleration; None without a load."""
        sol = self.sol
        if self.load is None or len(sol.t) < 2:
            return None
        q = _load_samples(self.load, sol.u.shape[1], len(sol.t) - 1, float(sol.t[1] - sol.t[0]))
        if isinstance(q, np.ndarray):
            return q[0]
        return q.constant + q.factors[0] @ q.vectors

    def energy_error(self) -> float:
        """Largest relative error of the energy balance over the run."""
        sol = self.sol
        q = _load_samples(self.load, sol.u.shape[1], len(sol.t) - 1, float(sol.t[1] - sol.t[0]))
        contact = None if self.foundation is None else self.foundation.contact_load(self.operators.structure, sol)
        energy = self.operators.energy_balance(self.state, q, rule=self.rule, dt=float(sol.t[1] - sol.t[0]),
                                               contact=contact, t=sol.t)     # contact: its work went into the soil
        return float(energy["max_relative_error"])


def _load_samples(load, n, N, dt):
    """The load samples a run on ``t_k = k dt`` used: (N+1, n), or the
    :class:`~unilateral.analysis.energy.LoadFactors` of a LoadHistory's hat averages."""
    from ..analysis.energy import LoadFactors

    if hasattr(load, "grid_factors"):
        return LoadFactors(load.constant, load.vectors(), load.grid_factors(dt, N)[0])
    if isinstance(load, np.ndarray):
        return np.asarray(load, dtype=float)[: N + 1]
    if load is None:
        return np.zeros((N + 1, n))
    return np.array([load(k * dt) for k in range(N + 1)], dtype=float)


_ROWS: dict = {}


def _dof_history(sol, spec, node, dof):
    """History of a node's DOF (frames; as ``Structure.node_displacement``) or of a named DOF."""
    if spec.structure is None:
        return sol.dof(dof)
    if node is None:
        raise KeyError(f"a frame needs the node of dof {dof!r}")
    dofs = spec.structure.dofs
    key = (id(dofs), node, dof)
    row = _ROWS.get(key)
    if row is None or row[0] is not dofs:
        sparse = dofs.T[dofs.full_index(node, dof)]
        dense = np.asarray(sparse.todense()).ravel()
        nonzero = np.flatnonzero(dense)
        row = _ROWS[key] = (dofs, nonzero, dense[nonzero], sparse)
    _, nonzero, weights, sparse = row
    if sol.u is None or sol.u.shape[1] != spec.structure.n:
        return spec.structure.node_displacement(sol, node, dof)       # its error message
    if nonzero.size == 1 and weights[0] == 1.0:       # a DOF of u itself: its column
        return sol.u[:, nonzero[0]]
    # a combination (a slave node): node_displacement's own product, rounded as it is (a dense
    # product may fuse a multiply-add and differ in the last place)
    return np.asarray(sparse @ sol.u.T).ravel() if nonzero.size else np.zeros(len(sol.t))


# ---------------------------------------------------------------------- one analysis
def run_analysis(payload: dict, source: dict, record=None, run_id: str = "") -> dict:
    """Run one analysis and return its result (the process that runs the study writes it).

    Reads no file: the model variant is built from ``source`` (once per process) and the record
    is given. Never raises for a problem of the analysis itself: an LCP failure
    (``success=False``), an exception or a timeout is the result, with its message.

    Parameters
    ----------
    payload : dict
        ``Analysis.payload``: ``key``, ``scale``, ``settings``, ``quantities``.
    source : dict
        :func:`unilateral.batch.inputs.variant_source` of the analysis' model variant.
    record : GroundMotion, optional
        The record (None: the model's own loads).
    run_id : str
        The run that asked for it, recorded in the result.

    Returns
    -------
    dict
        The result: ``key``, ``status`` (``"ok"``, ``"failed"``, ``"error"``, ``"timeout"``),
        ``message``, ``values`` (the peak quantities; NaN for a failed run, whose peaks over the
        steps it computed are ``values_computed``), ``mechanism`` (why the last state computed is a
        mechanism under gravity, or ``""``: :func:`unilateral.batch.collapse.mechanism`), ``notes``, ``stats`` (steps, method,
        max_lcp_error, contact_changes), ``solve_time``, ``quantities_time`` (collecting the
        peaks), ``task_time`` in seconds, ``worker``, ``host``, ``pid``, ``run_id``, ``cache``
        (``{"model": "hit" or "miss"}``), and ``restart_worker`` (True) after a timeout.
    """
    start = time.perf_counter()
    result = {"key": payload["key"], "status": "ok", "message": "", "values": {}, "notes": [], "stats": {},
              "solve_time": math.nan, "run_id": run_id, "pid": os.getpid(), "host": socket.gethostname(),
              "worker": _worker_address()}
    try:
        builds = _CACHE_STATS["model_builds"]
        spec, vector, ys, operators = model_variant(source)
        result["cache"] = {"model": "miss" if _CACHE_STATS["model_builds"] > builds else "hit"}
        if payload.get("ground") is not None:           # a pair of records: a vector per component
            vector = pair_vectors(spec, source["digest"], payload["ground"])
        _solve_and_collect(result, payload, spec, analysis_load(spec, vector, record, payload["scale"]),
                           (ys, operators))
    except AnalysisTimeout as exc:
        result.update(status="timeout", message=str(exc), restart_worker=True)
    except Exception as exc:                           # noqa: BLE001 - recorded, the study goes on
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" (at {Path(tb[-1].filename).name}:{tb[-1].lineno})" if tb else ""
        result.update(status="error", message=f"{type(exc).__name__}: {exc}{where}")
    result["task_time"] = time.perf_counter() - start
    return result


def _solve_and_collect(result: dict, payload: dict, spec, load, variant_extras) -> None:
    """Solve the analysis and fill ``result`` (status, message, stats, peak values, times) in place."""
    ys, operators = variant_extras
    settings = payload["settings"]
    if not math.isfinite(settings["t_end"]):
        raise ValueError("no end time (the record could not be read)")
    t0 = time.perf_counter()
    sol, cpu = _solve(spec.model, load, settings)
    result["solve_time"] = time.perf_counter() - t0
    result["solve_cpu_time"] = cpu
    stats = sol.stats
    result["stats"] = {"steps": int(len(sol.t) - 1), "method": str(stats.get("method", "")),
                       "max_lcp_error": float(stats.get("max_lcp_error", math.nan)),
                       "contact_changes": int(stats.get("contact_changes", -1))}
    result["message"] = sol.message
    if not sol.success:
        result["status"] = "failed"
    values = {}
    t0 = time.perf_counter()
    frame = (FrameResults(sol, operators, load, settings["rule"])
             if operators is not None and sol.u is not None and len(sol.t) > 1 else None)
    for quantity in payload["quantities"]:
        got, notes = collect(quantity, sol, spec, ys, frame)
        values.update(got)
        result["notes"] += notes
    overflow = _non_finite(sol, values) if sol.success else ""
    if overflow:
        result.update(status="failed", message=overflow)
    from .collapse import mechanism

    result["mechanism"] = "" if overflow else mechanism(spec.model, sol)     # collapse, not failure
    if result["status"] == "failed":                   # peaks of a run that stopped half-way mislead
        result["values_computed"] = values             # ... but may show a collapse before the failure
        values = {name: math.nan for name in values}
    result["values"] = values
    result["quantities_time"] = time.perf_counter() - t0


def _non_finite(sol, values: dict) -> str:
    """Why a run that succeeded has no finite result (an overflow), or ``""``."""
    for name in ("u", "v"):
        history = getattr(sol, name, None)
        if history is not None and not np.all(np.isfinite(history)):
            return (f"the solution {name} is not finite (an overflow: is the load, e.g. the record's "
                    "scale, far too large?)")
    infinite = [name for name, value in values.items() if math.isinf(value)]
    if infinite:
        return f"the peak quantities {', '.join(infinite)} are infinite (an overflow)"
    return ""


def _solve(model, load, settings: dict):
    """``(solution, CPU seconds)`` of ``unilateral.solve`` with the study's settings (in a thread if
    there is a time limit)."""
    from .. import solve

    kwargs = dict(dt=settings["dt"], t_end=settings["t_end"], method=settings["method"], rule=settings["rule"],
                  lcp=settings["lcp"], initial=settings["initial"], lcp_options=settings["lcp_options"] or None)
    timeout = settings.get("timeout")
    if not timeout:
        cpu = time.thread_time()
        sol = solve(model, load, **kwargs)
        return sol, time.thread_time() - cpu
    future = _executor().submit(_timed_solve, solve, model, load, kwargs)
    try:
        return future.result(timeout)
    except TimeoutError:
        _abandon_executor()
        raise AnalysisTimeout(f"stopped after {timeout:g} s (analysis.timeout); the worker is restarted") from None


_EXECUTOR = None


def _executor():
    """A thread of this process that runs the solves with a time limit (started once)."""
    global _EXECUTOR
    if _EXECUTOR is None:
        from concurrent.futures import ThreadPoolExecutor

        _EXECUTOR = ThreadPoolExecutor(1, thread_name_prefix="unilateral-analysis")
    return _EXECUTOR


def _abandon_executor() -> None:
    """Leave the thread of a timed-out solve to finish on its own; the next solve gets a new one."""
    global _EXECUTOR
    if _EXECUTOR is not None:
        _EXECUTOR.shutdown(wait=False, cancel_futures=True)
    _EXECUTOR = None


def _timed_solve(solve, model, load, kwargs):
    cpu = time.thread_time()
    sol = solve(model, load, **kwargs)
    return sol, time.thread_time() - cpu


def _worker_address() -> str:
    import sys

    if "distributed" not in sys.modules:
        return ""
    try:
        return sys.modules["distributed"].get_worker().address
    except Exception:                                  # noqa: BLE001 - not in a Dask worker
        return ""


def warm_up() -> float:
    """Solve a tiny model once so that the compiled (numba) code is loaded; returns the seconds."""
    import unilateral as ul

    start = time.perf_counter()
    m, k = 1.0, 100.0
    model = ul.Model(M=[[m]], K=[[k]], F=[[k]], H=[[k]])
    for method in ("modal", "cq"):
        ul.solve(model, lambda t: np.array([-m * 10.0]), dt=1e-2, t_end=0.1, method=method)
    return time.perf_counter() - start
