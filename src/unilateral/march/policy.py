"""The size thresholds of a run, in one object: :class:`SizePolicy`, and the policy in force.

Which march steps a model (dense or sparse arrays, the condensed LCP or the full sparse space,
compiled or Python loops) and how many BLAS threads it uses depend on the model's size and the
run's length, never on what a process happened to import before. Every threshold of that choice is
a field of one :class:`SizePolicy`; a run takes the policy in force when it starts
(:func:`current_policy`), a caller sets another for a block of code (:func:`size_policy`: the
command line runs in :data:`COMMAND_LINE`) or passes one to :class:`unilateral.Simulation`.

When compiled loops pay: a fresh process pays about 0.3-0.5 s to import numba and 0.5-1 s to load
the cached machine code of the first compiled loop it calls; after that the compiled loops cost
1-5 us per step against 30-400 us for the Python loops. A library process (a notebook, a batch
worker) calls them many times, so :data:`LIBRARY` compiles every run where a compiled loop applies.
The command line runs one analysis per process: :data:`COMMAND_LINE` runs fewer than 2000 steps in
the Python loops, which never load numba. A linear sweep (no LCP) is cheaper per step in Python,
so it needs a longer run (:attr:`SizePolicy.sweep_step_cost`).
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
from dataclasses import dataclass

__all__ = ["COMMAND_LINE", "LIBRARY", "SizePolicy", "current_policy", "size_policy"]


@dataclass(frozen=True)
class SizePolicy:
    """The thresholds that choose how a model is stepped.

    Attributes
    ----------
    compile_min_steps : int
        Runs of fewer steps use the Python loops when a method's engine is ``"auto"`` (0: compiled
        wherever a compiled loop applies).
    sweep_step_cost : float
        Python cost of a step of a linear sweep (no LCP) relative to a step of a march with an
        LCP: 30-40 us against 90-210 us, measured on the pounding example (n = 18, m = 1).
    compiled_max_n : int
        Models with at most this many DOFs may be stepped by compiled code with a dense LU of
        ``D_eff`` (the condensed LCP); larger sparse ones with contacts only, in the full space.
    full_space_min_m : int
        Sparse models with more constraints than this (contacts only, ``H`` without a zero on its
        diagonal) solve the step's LCP in the full sparse space instead of the condensed one.
    dense_stepping_max_n : int
        Models with at most this many DOFs are stepped with dense arrays (sparse products cost
        more than they save there).
    blas_one_thread_max_n : int
        Models with at most this many DOFs run with one BLAS thread: the products and
        factorisations of a small model's step are too small to share (on the 17-DOF tower, 2
        cores, OpenBLAS's threads made a run 2.4 times slower: 0.026 s against 0.011 s).
    """

    compile_min_steps: int = 0
    sweep_step_cost: float = 0.2
    compiled_max_n: int = 400
    full_space_min_m: int = 64
    dense_stepping_max_n: int = 64
    blas_one_thread_max_n: int = 2000

    def __post_init__(self):
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            numeric = isinstance(value, (int, float)) and not isinstance(value, bool)
            if not numeric or value != value or value < 0 or (f.type == "int" and value != int(value)):
                kind = "an integer" if f.type == "int" else "a number"
                raise ValueError(f"SizePolicy {f.name} must be {kind} >= 0, got {value!r}")

    def compiled_pays(self, steps: int, step_cost: float = 1.0) -> bool:
        """True if a run of ``steps`` steps should use the compiled loops (engine ``"auto"``).

        ``step_cost``: the Python cost of one step relative to a march step with an LCP
        (:attr:`sweep_step_cost` for a linear sweep), so that a cheap loop is compiled only when
        it is long enough to repay the loading of the compiled code.
        """
        return steps * step_cost >= self.compile_min_steps

    def replace(self, **changes) -> SizePolicy:
        """A copy with ``changes`` (field names of :class:`SizePolicy`)."""
        unknown = sorted(set(changes) - {f.name for f in dataclasses.fields(self)})
        if unknown:
            raise ValueError(f"SizePolicy has no field {', '.join(map(repr, unknown))}; valid: "
                             + ", ".join(f.name for f in dataclasses.fields(self)))
        return dataclasses.replace(self, **changes)


#: The policy of a library process (a notebook, a batch worker): compiled wherever it applies.
LIBRARY = SizePolicy()
#: The policy of the command line (one analysis per process): short runs in Python.
COMMAND_LINE = SizePolicy(compile_min_steps=2000)

_CURRENT = contextvars.ContextVar("unilateral_size_policy", default=LIBRARY)


def current_policy() -> SizePolicy:
    """The :class:`SizePolicy` in force (:data:`LIBRARY` unless :func:`size_policy` set another)."""
    return _CURRENT.get()


@contextlib.contextmanager
def size_policy(policy: SizePolicy):
    """A block of code in which ``policy`` is in force (restored on leaving, also on an error)."""
    if not isinstance(policy, SizePolicy):
        raise TypeError(f"policy must be a unilateral.SizePolicy, got {type(policy).__name__}")
    token = _CURRENT.set(policy)
    try:
        yield policy
    finally:
        _CURRENT.reset(token)
