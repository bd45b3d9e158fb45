"""Benchmark suite: every method of :func:`unilateral.solve` on problems small to large.

``python -m unilateral.bench [--quick]`` runs the problems of :mod:`~unilateral.bench.problems`
with ``method="cq"`` (naive and FFT-blocked history), ``"modal"`` (where :func:`unilateral.solve`
offers it), ``"direct"`` (compiled, and its Python loop) and ``"event"`` (the exact reference,
where the load has an exact form), each in its own subprocess (:mod:`~unilateral.bench.suite`), prints
a table of time per step, peak memory and error against a converged reference, writes the
results as JSON and draws the scaling figure (:mod:`~unilateral.bench.report`).
"""

from .problems import PROBLEMS, Problem, build
from .suite import METHODS, Limits, ScalingConfig, run_one, run_scaling, run_suite

# The table and the figure are in :mod:`unilateral.bench.report` (``format_table``,
# ``scaling_figure``, ``save_scaling_figure``), not imported here: each run of the suite is a
# subprocess that imports this package, and the report imports matplotlib (0.4 s of 1.3 s per run).

__all__ = ["METHODS", "PROBLEMS", "Limits", "Problem", "ScalingConfig", "build", "run_one", "run_scaling",
           "run_suite"]
