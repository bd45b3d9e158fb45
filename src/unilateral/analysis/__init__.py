"""A structural analysis from start to finish: the unilateral and bilateral cases, and every output.

:func:`run_cases` solves the cases; :func:`write_outputs` writes ``results.nc``, CSV tables,
``summary.json`` and the figures atomically; :func:`report` is the terminal summary. The command
line (``unilateral run``, ``unilateral example``) is these three calls.
"""

from .outputs import report, run_cases, write_outputs

__all__ = ["report", "run_cases", "write_outputs"]
