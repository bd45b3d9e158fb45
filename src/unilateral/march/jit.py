"""When the compiled (numba) loops pay for themselves.

A fresh process pays about 0.3-0.5 s to import numba and 0.5-1 s to load the cached machine code of
the first compiled loop it calls; after that the compiled loops cost 1-5 us per step against
30-400 us for the Python loops. A library process (a notebook, a batch worker) calls them many
times, so by default every ``engine="auto"`` compiles where it applies. The command line runs one
analysis per process: it raises :data:`COMPILE_MIN_STEPS` so that a short run uses the Python loops
and never loads numba; a linear sweep (no LCP) is cheaper per step in Python, so it needs a longer
run (:data:`SWEEP_STEP_COST`).
"""

from __future__ import annotations

import sys

#: Runs of fewer steps use the Python loops when a method's engine is ``"auto"`` (0: always compiled).
COMPILE_MIN_STEPS = 0
#: Python cost of a step of a linear sweep (no LCP) relative to a step of a march with an LCP:
#: 30-40 us against 90-210 us, measured on the pounding example (n = 18, m = 1).
SWEEP_STEP_COST = 0.2


def compiled_pays(steps: int, step_cost: float = 1.0) -> bool:
    """True if a run of ``steps`` steps should use the compiled loops (engine ``"auto"``).

    ``step_cost``: the Python cost of one step relative to a march step with an LCP
    (:data:`SWEEP_STEP_COST` for a linear sweep), so that a cheap loop is compiled only when it
    is long enough to repay the loading of the compiled code. Once numba is imported (an earlier
    run of the process compiled), its import is paid and every run compiles.
    """
    return steps * step_cost >= COMPILE_MIN_STEPS or numba_loaded()


def numba_loaded() -> bool:
    """True once numba is imported in this process (its import is paid)."""
    return "numba" in sys.modules
