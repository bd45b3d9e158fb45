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

The first run after a fresh install: numba's cache is empty and the compiled loops of a march
compile, 5-20 s (the full-space march of a 998-DOF beam 4.9-6 s on a quiet 2-core machine, the
condensed direct march with its face-rule LCP solver about 20 s of CPU). With
:attr:`SizePolicy.engine_choice` ``"cost"`` (the default) a direct march weighs, for engine
``"auto"``, the Python loops of the run (:meth:`SizePolicy.python_seconds`) against the compiled
ones plus what it costs to make them ready (:meth:`SizePolicy.engine_cost`): nothing once this
process has run them, :attr:`SizePolicy.load_s` to load them from numba's cache,
:attr:`SizePolicy.compile_s` to compile them; ``stats["engine_reason"]`` says what was weighed. The
cache is read only when the answer depends on it (:func:`unilateral.march.loops.cache_state`), so a
short run never imports numba. ``"steps"`` keeps the rule of :attr:`SizePolicy.compile_min_steps`
alone: the engine never depends on the cache (the test suite runs so:
``UNILATERAL_ENGINE_CHOICE=steps`` sets the default of this field). Both engines give the same
solution to round-off (1e-13); pass ``engine=`` to a method, or a policy, to pin one.
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import os
import threading
from dataclasses import dataclass

__all__ = ["COMMAND_LINE", "ENGINE_CHOICES", "LIBRARY", "SizePolicy", "current_policy", "size_policy"]

#: The values of :attr:`SizePolicy.engine_choice`.
ENGINE_CHOICES = ("cost", "steps")
#: Its default: the environment's ``UNILATERAL_ENGINE_CHOICE``, else ``"cost"``.
DEFAULT_ENGINE_CHOICE = os.environ.get("UNILATERAL_ENGINE_CHOICE", "cost")
if DEFAULT_ENGINE_CHOICE not in ENGINE_CHOICES:
    raise ValueError(f"the environment variable UNILATERAL_ENGINE_CHOICE={DEFAULT_ENGINE_CHOICE!r} is not valid: "
                     f"set it to {' or '.join(map(repr, ENGINE_CHOICES))}, or unset it (the default is 'cost')")


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
    engine_choice : str
        ``"cost"``: engine ``"auto"`` of a direct march weighs the estimated seconds of both engines,
        the compiled one with its compile or load (see the module); ``"steps"``: by
        :attr:`compile_min_steps` alone, whatever the cache holds.
    compile_s, load_s : float
        Seconds to make a compiled march ready on a cold cache (compile) and from numba's cache in a
        fresh process (numba's start-up and the machine code: 0.4-0.8 s measured).
    python_step_s : tuple of 3 floats
        ``(base, per DOF, per constraint)`` seconds of a Python step: measured 0.14 ms (17 DOFs,
        3 contacts), 0.38 ms (98, 11), 0.6-0.7 ms (998, 10), 3.1 ms (998, 100: the full space),
        2.3 ms (9998, 10).
    compiled_step_s : tuple of 2 floats
        ``(base, per DOF)`` seconds of a compiled step (1 us at 17 DOFs, 60 us at 998).
    """

    compile_min_steps: int = 0
    sweep_step_cost: float = 0.2
    compiled_max_n: int = 400
    full_space_min_m: int = 64
    dense_stepping_max_n: int = 64
    blas_one_thread_max_n: int = 2000
    engine_choice: str = DEFAULT_ENGINE_CHOICE
    compile_s: float = 6.0
    load_s: float = 0.5
    python_step_s: tuple = (1.2e-4, 2.2e-7, 2.5e-5)
    compiled_step_s: tuple = (1e-6, 6e-8)

    def __post_init__(self):
        if self.engine_choice not in ENGINE_CHOICES:
            raise ValueError(f"SizePolicy engine_choice must be one of {', '.join(map(repr, ENGINE_CHOICES))}, "
                             f"got {self.engine_choice!r}")
        for name, size in (("python_step_s", 3), ("compiled_step_s", 2)):
            value = getattr(self, name)
            if not (isinstance(value, tuple) and len(value) == size
                    and all(isinstance(c, (int, float)) and not isinstance(c, bool) and 0 <= c < float("inf")
                            for c in value)):
                raise ValueError(f"SizePolicy {name} must be a tuple of {size} finite numbers >= 0, got {value!r}")
        for f in dataclasses.fields(self):
            if f.name in ("engine_choice", "python_step_s", "compiled_step_s"):
                continue
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

    def python_seconds(self, steps: int, n: int, m: int) -> float:
        """Estimated seconds of ``steps`` Python steps of a model of ``n`` DOFs and ``m`` constraints."""
        base, per_dof, per_constraint = self.python_step_s
        return steps * (base + per_dof * n + per_constraint * m)

    def compiled_seconds(self, steps: int, n: int) -> float:
        """Estimated seconds of ``steps`` compiled steps of a model of ``n`` DOFs, once ready."""
        base, per_dof = self.compiled_step_s
        return steps * (base + per_dof * n)

    def engine_cost(self, steps: int, n: int, m: int, cache, *, cheap: bool = False) -> tuple[bool, str, str | None]:
        """Whether the compiled loops pay for a run of ``steps`` steps (engine ``"auto"``, a direct
        march, :attr:`engine_choice` ``"cost"``), why, and the cache state read.

        The compiled loops pay if making them ready and running them costs less than the Python
        loops, or, as in the ski-rental problem, once the Python seconds that this process spent
        for lack of them (:func:`python_seconds_spent`) reach the cost of making them ready: a
        process that runs many short analyses (a batch worker, a notebook) pays at most twice the
        better of the two. ``cache()`` returns the state of the march's loops
        (:data:`unilateral.march.loops.STATES`); it is called if reading it is ``cheap`` (numba is
        imported already) or if the choice depends on it, so that a short run in a fresh process
        does not import numba. Returns ``(compiled, reason, state)``, ``state`` None if the cache
        was not read; a run that goes to Python adds its estimate to :func:`python_seconds_spent`.
        """
        python = self.python_seconds(steps, n, m)
        run = self.compiled_seconds(steps, n)
        spent = python_seconds_spent()
        estimate = f"the Python loops of {steps} steps take about {python:.2g} s"
        if spent:
            estimate += f" ({spent:.2g} s spent in Python by earlier runs of this process)"
        if not cheap and python <= run + self.load_s and python + spent < self.load_s:
            return _rented(python), f"{estimate}, less than loading the compiled loops (about {self.load_s:.2g} s)", None
        if not cheap and python > run + self.compile_s:
            return True, f"{estimate}, more than compiling the compiled loops (about {self.compile_s:.2g} s)", None
        state = cache()
        ready = {"loaded": 0.0, "cold": self.compile_s}.get(state, self.load_s)
        how = {"loaded": "already in this process", "cold": f"to compile (a cold numba cache), about "
               f"{self.compile_s:.2g} s"}.get(state, f"in numba's cache, loaded in about {self.load_s:.2g} s")
        compiled = run + ready < python or (ready > 0.0 and spent + python >= ready)
        return compiled or _rented(python), (f"{estimate}; the compiled loops are {how}, then {run:.2g} s: "
                                             f"{'compiled' if compiled else 'Python'}"), state

    def replace(self, **changes) -> SizePolicy:
        """A copy with ``changes`` (field names of :class:`SizePolicy`)."""
        unknown = sorted(set(changes) - {f.name for f in dataclasses.fields(self)})
        if unknown:
            raise ValueError(f"SizePolicy has no field {', '.join(map(repr, unknown))}; valid: "
                             + ", ".join(f.name for f in dataclasses.fields(self)))
        return dataclasses.replace(self, **changes)


_SPENT = [0.0]                              # estimated Python seconds of runs that chose Python by cost
_SPENT_LOCK = threading.Lock()


def python_seconds_spent() -> float:
    """Estimated seconds that runs of this process spent in the Python loops because the compiled
    ones cost more to make ready (:meth:`SizePolicy.engine_cost`)."""
    return _SPENT[0]


def _rented(python: float) -> bool:
    """Count ``python`` seconds as spent in Python for lack of compiled loops; False (the engine)."""
    with _SPENT_LOCK:
        _SPENT[0] += python
    return False


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
