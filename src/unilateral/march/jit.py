"""When the compiled (numba) loops pay for themselves.

A fresh process pays about 0.3-0.5 s to import numba and 0.5-1 s to load the cached machine code of
the first compiled loop it calls; after that the compiled loops cost 1-5 us per step against
30-400 us for the Python loops. A library process (a notebook, a batch worker) calls them many
times, so by default every ``engine="auto"`` compiles where it applies. The command line runs one
analysis per process: it raises :data:`COMPILE_MIN_STEPS` so that a short run uses the Python loops
and never loads numba.
"""

from __future__ import annotations

#: Runs of fewer steps use the Python loops when a method's engine is ``"auto"`` (0: always compiled).
COMPILE_MIN_STEPS = 0


def compiled_pays(steps: int) -> bool:
    """True if a run of ``steps`` steps should use the compiled loops (engine ``"auto"``)."""
    return steps >= COMPILE_MIN_STEPS
