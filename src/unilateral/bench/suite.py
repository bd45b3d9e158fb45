"""Run benchmark problems with every method, each run in its own subprocess.

A run (:func:`run_one`, in the child ``python -m unilateral.bench --run-one PROBLEM METHOD``)
builds its problem, warms up (a solve of a few steps, so that numba compilation and caches are
not timed), solves once more with timing and prints one JSON line: the phase times of
``sol.stats["time"]``, the peak resident memory of the child (``ru_maxrss``) and the solver's
counters; the key output goes to an ``.npz`` file. The parent (:func:`run_suite`) compares it
with a converged reference (``method="direct"``, BDF2, ``dt/4``, also a subprocess), and skips
combinations whose estimated memory or time exceeds the :class:`Limits`.
"""

from __future__ import annotations

import json
import math
import os
import platform
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from datetime import datetime, timezone
from importlib import metadata
from pathlib import Path

import numpy as np

from ..methods import Direct
from ..solve import solve
from .problems import build, refined

METHODS = {
    "cq naive": {"method": "cq", "cq_options": {"history": "naive", "engine": "auto"}},
    "cq fft": {"method": "cq", "cq_options": {"history": "fft", "engine": "auto"}},
    "modal": {"method": "modal"},
    "direct": {"method": "direct"},
    "direct python": {"method": Direct(engine="python")},
    "event": {"method": "event"},
}
"""Benchmarked methods: name -> keyword arguments of :func:`unilateral.solve`.

``"direct"`` is what ``method="direct"`` does (compiled where it applies, see
:class:`~unilateral.methods.Direct`), ``"direct python"`` its Python loop (the same operations);
``"event"`` the exact event-driven reference (loads with an exact piecewise form only: the Winkler
problems' moving load is a plain function, and the run is skipped with the reason)."""

REFERENCE = "reference"
REFERENCE_ATTEMPTS = ({"method": "direct", "rule": "bdf2"},
                      {"method": "direct", "rule": "bdf2", "lcp": "lemke"})
"""The reference: the default LCP solver, or Lemke's if that fails."""
REFERENCE_REFINEMENT = 4
WARMUP_STEPS = 20

# Rough cost model of method="cq", measured on a 2-core x86-64 machine: the kernel sampled on the
# circle, its FFT and the weights peak at about 24 (N+1) m^2 doubles; a sample of a sparse kernel
# costs about 1e-8 n m^2 s; the history sum 5e-10 N^2 m^2 s (naive, compiled) or
# 1e-9 N log2(N)^2 m^2 s (FFT-blocked); every step about 1e-4 s more.
CQ_DOUBLES_PER_WEIGHT = 24
BASE_MEMORY_BYTES = 200 * 2**20
KERNEL_SAMPLE_S = 1e-8
NAIVE_TERM_S = 5e-10
FFT_TERM_S = 1e-9
STEP_S = 1e-4


@dataclass(frozen=True)
class Limits:
    """Limits of one run.

    Attributes
    ----------
    memory_gib : float
        Skip a run whose estimated peak memory exceeds this.
    minutes : float
        Skip a run whose estimated time exceeds this.
    timeout : float
        Stop a run after this many seconds (it is then reported as skipped).
    """

    memory_gib: float = 4.0
    minutes: float = 10.0
    timeout: float = 900.0

    @classmethod
    def default(cls, quick: bool) -> Limits:
        """4 GiB; an estimated 10 min and a 15 min timeout (quick: 2 min both)."""
        return cls(minutes=2.0, timeout=120.0) if quick else cls()


# ---------------------------------------------------------------------- child side
def run_one(problem_name: str, method: str, *, quick: bool = False, steps: int | None = None,
            output: str | os.PathLike | None = None) -> dict:
    """Solve one problem with one method, timed after a warm-up; return the record.

    Parameters
    ----------
    problem_name : str
        A name for :func:`~unilateral.bench.problems.build`.
    method : str
        A key of :data:`METHODS`, or ``"reference"`` (``method="direct"``, BDF2, ``dt/4``).
    quick : bool
        Quick number of steps.
    steps : int, optional
        Number of steps (before refinement), overriding the problem's default.
    output : path, optional
        Write the times ``t`` and the key output ``y`` of a successful run to this ``.npz``.

    Returns
    -------
    dict
        ``status`` ``"ok"``, ``"failed"`` (``sol.success`` is False) or ``"skipped"`` (``solve``
        rejected the method with a ``ValueError``); ``reason`` (the messages of failed
        attempts: a reference that failed with the default LCP solver is repeated with Lemke's);
        ``N``, ``n``, ``m``; the times ``steps_s``, ``total_s`` and ``phases`` (s) of the last
        attempt; ``peak_mib`` of the child process; the solver's counters.
    """
    problem = build(problem_name, quick=quick, steps=steps)
    if method == REFERENCE:
        problem = refined(problem, REFERENCE_REFINEMENT)
        attempts = REFERENCE_ATTEMPTS
    elif method in METHODS:
        attempts = (METHODS[method],)
    else:
        raise ValueError(f"method {method!r} is not known; valid: {', '.join(map(repr, METHODS))}, 'reference'")
    model = problem.model
    record = {"problem": problem_name, "method": method, "N": problem.N, "n": model.n, "m": model.m}
    failures = []
    for options in attempts:
        try:
            solve(model, problem.load, dt=problem.dt,
                  t_end=min(WARMUP_STEPS, problem.N) * problem.dt, **options)
        except ValueError as exc:
            return record | {"status": "skipped", "reason": f"solve rejects it: {exc}"}
        sol = solve(model, problem.load, dt=problem.dt, t_end=problem.N * problem.dt, **options)
        if sol.success:
            break
        failures.append(f"lcp={sol.stats['lcp_solver']}: {sol.message}")
    times = sol.stats["time"]
    record |= {
        "status": "ok" if sol.success else "failed",
        "reason": "; ".join(failures),
        "steps_s": times.get("steps", times["total"]), "total_s": times["total"], "phases": times,
        "peak_mib": peak_memory_mib(),
        **{key: sol.stats.get(key) for key in ("lcp_solver", "engine", "history", "lcp_space",
                                               "contact_changes", "max_lcp_error")},
    }
    if output is not None and sol.success:
        np.savez(output, t=sol.t, y=problem.output(sol))
    return record


def peak_memory_mib() -> float:
    """Peak resident memory of this process (``ru_maxrss``), MiB."""
    import resource                                  # POSIX only, like ru_maxrss itself

    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return rss / 2**20 if sys.platform == "darwin" else rss / 2**10     # bytes on macOS, else KiB


# ---------------------------------------------------------------------- parent side
def run_subprocess(problem_name: str, method: str, *, quick: bool, timeout: float,
                   steps: int | None = None, output: Path | None = None) -> dict:
    """:func:`run_one` in a fresh interpreter; a crash or a timeout becomes the record's status."""
    command = [sys.executable, "-m", "unilateral.bench", "--run-one", problem_name, method]
    command += ["--quick"] * quick + ["--steps", str(steps)] * (steps is not None)
    command += ["--output", str(output)] * (output is not None)
    start = time.perf_counter()
    try:
        proc = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"status": "skipped", "reason": f"timed out after {timeout:g} s (the run's timeout)"}
    lines = [line for line in proc.stdout.splitlines() if line.startswith("{")]
    if proc.returncode != 0 or not lines:
        last = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        return {"status": "failed", "reason": f"exit code {proc.returncode}: {last}"}
    return json.loads(lines[-1]) | {"process_s": time.perf_counter() - start}


def estimate(method: str, n: int, m: int, N: int) -> tuple[float, float] | None:
    """Estimated peak memory (bytes) and time (s) of a CQ run; None for the other methods."""
    history = METHODS[method].get("cq_options", {}).get("history")
    if history is None:
        return None
    memory = BASE_MEMORY_BYTES + 8.0 * CQ_DOUBLES_PER_WEIGHT * (N + 1) * m * m
    kernel = (4 * N + 5) * KERNEL_SAMPLE_S * n * m * m
    if history == "naive":
        summation = NAIVE_TERM_S * N * N * m * m
    else:
        summation = FFT_TERM_S * N * math.log2(N + 1) ** 2 * m * m
    return memory, kernel + summation + STEP_S * N


def infeasible(method: str, n: int, m: int, N: int, limits: Limits) -> str:
    """Why a run is skipped before it starts, or ``""``."""
    cost = estimate(method, n, m, N)
    if cost is None:
        return ""
    memory, seconds = cost[0] / 2**30, cost[1]
    if memory > limits.memory_gib:
        return (f"estimated {memory:.3g} GiB > {limits.memory_gib:g} GiB "
                f"({CQ_DOUBLES_PER_WEIGHT} (N+1) m^2 doubles of CQ weights and their transform)")
    if seconds > 60 * limits.minutes:
        return f"estimated {seconds / 60:.3g} min > {limits.minutes:g} min"
    return ""


def run_suite(problems, methods, *, quick: bool, limits: Limits, progress=None) -> list[dict]:
    """Every problem with its reference and every method; one record per run.

    Parameters
    ----------
    problems : sequence of str
        Problem names.
    methods : sequence of str
        Keys of :data:`METHODS`.
    quick : bool
        Quick numbers of steps.
    limits : Limits
    progress : callable ``progress(record)``, optional
        Called after every run.

    Returns
    -------
    list of dict
        Records of :func:`run_one` plus ``error``: the relative maximum error of the key output
        against the reference (None without one).
    """
    _check_methods(methods)
    records = []
    with tempfile.TemporaryDirectory(prefix="unilateral-bench-") as tmp:
        for name in problems:
            problem = build(name, quick=quick)
            dims = {"problem": name, "N": problem.N, "n": problem.model.n, "m": problem.model.m}
            reasons = {method: infeasible(method, dims["n"], dims["m"], dims["N"], limits)
                       for method in methods}
            reference_file = Path(tmp) / f"{name}-reference.npz"
            runs = [(REFERENCE, "" if "" in reasons.values() else "no method to compare")]
            runs += list(reasons.items())
            for method, reason in runs:
                output = Path(tmp) / f"{name}-{method.replace(' ', '_')}.npz"
                if reason:
                    record = {"status": "skipped", "reason": reason}
                else:
                    record = run_subprocess(name, method, quick=quick, timeout=limits.timeout,
                                            output=output)
                record = dims | {"method": method} | record
                if method == REFERENCE:
                    record["N"] = dims["N"] * REFERENCE_REFINEMENT
                else:
                    record["error"] = output_error(output, reference_file)
                records.append(record)
                if progress is not None:
                    progress(record)
    return records


def _check_methods(methods) -> None:
    unknown = [method for method in methods if method not in METHODS]
    if unknown:
        raise ValueError(f"methods {unknown} are not known; valid: {', '.join(map(repr, METHODS))}")


def output_error(output: Path, reference: Path) -> float | None:
    """Relative maximum error ``max |y - y_ref| / max |y_ref|`` at the run's times, or None."""
    if not (output.exists() and reference.exists()):
        return None
    with np.load(output) as run, np.load(reference) as ref:
        y_ref = np.interp(run["t"], ref["t"], ref["y"])
        return float(np.max(np.abs(run["y"] - y_ref)) / np.max(np.abs(ref["y"])))


@dataclass(frozen=True)
class ScalingConfig:
    """Runs of the scaling figure.

    Attributes
    ----------
    steps : sequence of int
        Numbers of steps of the ``paper`` problem (time against N).
    steps_methods : sequence of str
    sizes : sequence of int
        Numbers of unilateral unknowns ``m`` of the Winkler beams (time against m).
    sizes_steps : int
        Number of steps of every Winkler run.
    sizes_methods : sequence of str
    """

    steps: tuple = tuple(2**k for k in range(9, 15))
    steps_methods: tuple = ("cq naive", "cq fft", "modal", "direct")
    sizes: tuple = (25, 50, 100, 200, 400, 1000)
    sizes_steps: int = 1000
    sizes_methods: tuple = ("direct", "modal")

    @classmethod
    def default(cls, quick: bool) -> ScalingConfig:
        """The full configuration, or N = 2^9 .. 2^11 and m = 25, 50, 100 with 200 steps."""
        if quick:
            return cls(steps=(2**9, 2**10, 2**11), sizes=(25, 50, 100), sizes_steps=200)
        return cls()


def run_scaling(config: ScalingConfig, *, limits: Limits, progress=None) -> list[dict]:
    """Time the ``paper`` problem against N and the Winkler beams against m.

    Returns
    -------
    list of dict
        Records of :func:`run_one` with ``sweep`` ``"N"`` or ``"m"``; infeasible runs skipped.
    """
    _check_methods([*config.steps_methods, *config.sizes_methods])
    runs = [("N", "paper", steps, method) for method in config.steps_methods for steps in config.steps]
    runs += [("m", f"winkler{size}", config.sizes_steps, method)
             for method in config.sizes_methods for size in config.sizes]
    records = []
    for sweep, name, steps, method in runs:
        model = build(name, steps=steps).model
        reason = infeasible(method, model.n, model.m, steps, limits)
        record = {"sweep": sweep, "problem": name, "method": method, "N": steps, "n": model.n,
                  "m": model.m}
        if reason:
            record |= {"status": "skipped", "reason": reason}
        else:
            record |= run_subprocess(name, method, quick=False, steps=steps, timeout=limits.timeout)
        records.append(record)
        if progress is not None:
            progress(record)
    return records


def machine_info() -> dict:
    """Platform, CPU count, Python and library versions, and the date (UTC)."""
    versions = {}
    for package in ("unilateral", "numpy", "scipy", "numba"):
        try:
            versions[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            versions[package] = None
    return {"platform": platform.platform(), "processor": platform.processor() or platform.machine(),
            "cpu_count": os.cpu_count(), "python": platform.python_version(), "versions": versions,
            "date": datetime.now(timezone.utc).isoformat(timespec="seconds")}

