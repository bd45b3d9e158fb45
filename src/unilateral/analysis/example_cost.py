"""What a built-in example with several runs will cost, said (or refused) before anything is solved.

The examples ``halfspace`` (twelve solves: three soils, two loads, two cases) and ``footings`` (four
solves on a soil of patches) march every run with ``cq`` on a soil kernel: their time grows with the
steps ``t_end / dt`` of each run (as ``N log N``: the soil's weights by FFT, the FFT-blocked history).
``example halfspace --dt 1e-6`` asked for 5.7e7 steps (about eight hours) and printed nothing for
minutes. :func:`check_example_cost` estimates the time from the steps and a rough cost per step
measured at the examples' default time steps, and refuses an example estimated above
:data:`MAX_EXAMPLE_SECONDS`, naming ``dt`` (or ``t_end``), the estimate, the limit and a time step
that fits; the memory of each run is checked by ``unilateral.solve`` as for any run.
"""

from __future__ import annotations

import math

MAX_EXAMPLE_SECONDS = 3600.0
"""Longest estimated time of a built-in example (an hour: an example is a demonstration)."""
SECONDS_PER_STEP = {"halfspace": 6e-4, "footings": 2.5e-2}
"""Rough seconds per step of a run of each example at its default time step, the soil's weights
included (their frequencies grow with the steps); measured on a loaded 2-core machine: ``halfspace``
1.0-2.5 s per 4000-step earthquake run, ``footings`` 27-30 s per 1200-step run on the layered soil."""
REFERENCE_STEPS = {"halfspace": 4000, "footings": 1200}
"""The steps of the runs those costs were measured on (the cost per step grows as ``log N`` beyond)."""


def example_seconds(name: str, steps: list[int]) -> float:
    """Rough seconds of the example ``name`` whose runs take ``steps`` (one entry per solve)."""
    ref = REFERENCE_STEPS[name]
    return sum(SECONDS_PER_STEP[name] * n * max(1.0, math.log2(max(n, 2)) / math.log2(ref)) for n in steps)


def check_example_cost(name: str, steps: list[int], dt: float | None, t_end: float | None) -> float:
    """The estimated seconds of the example; a ValueError above :data:`MAX_EXAMPLE_SECONDS`.

    Parameters
    ----------
    name : ``"halfspace"`` or ``"footings"``
    steps : the steps of each solve the example will run
    dt, t_end : the values given (None: the example's defaults), named in the refusal
    """
    seconds = example_seconds(name, steps)
    if seconds <= MAX_EXAMPLE_SECONDS:
        return seconds
    scale = seconds / MAX_EXAMPLE_SECONDS
    given = f"--dt {dt:g}" if dt is not None else f"--t-end {t_end:g}"
    fits = (f"--dt {dt * scale * 1.1:.2g} or more" if dt is not None else f"--t-end {t_end / scale / 1.1:.2g} or less")
    raise ValueError(f"{given}: the {name} example would take about {_clock(seconds)} ({len(steps)} solves, "
                     f"{sum(steps):.3g} steps, roughly {SECONDS_PER_STEP[name] * 1e3:g} ms per step): more than the "
                     f"{_clock(MAX_EXAMPLE_SECONDS)} allowed for an example; give {fits}, or run the model "
                     "yourself (unilateral.structure.examples) with the runs you need")


def _clock(seconds: float) -> str:
    if seconds >= 86400:
        return f"{seconds / 86400:.3g} days"
    return f"{seconds / 3600:.3g} h" if seconds >= 3600 else f"{seconds / 60:.3g} min"
