"""Which compiled loops a march calls, and whether they are ready: compiled in this process, held by
numba's on-disk cache, or to be compiled (a cold cache, as after a fresh install).

The size policy (:meth:`unilateral.march.policy.SizePolicy.engine_cost`) weighs the Python loops
of a run against the compiled ones plus what it costs to make them ready: nothing in a process
that has run them, a load from the cache (numba's start-up and the machine code, about 0.5 s), or
a compile (seconds). :func:`cache_state` tells which, without compiling or loading anything: it
reads the index numba keeps of each loop (the source file's time stamp, the bytecode and the
machine of each cached specialisation). Importing this module imports numba.
"""

from __future__ import annotations

import hashlib
import os

from . import compiled, envelope, full_space

__all__ = ["CONDENSED", "FULL_SPACE", "STATES", "cache_state"]

#: The loops that the compiled condensed direct march calls from Python (their callees are compiled
#: into them and cached with them).
CONDENSED = (compiled.direct_start, compiled.direct_steps)
#: The loops of the compiled full-space direct march.
FULL_SPACE = (envelope.cholesky_rows, full_space.full_space_steps, full_space._columns_times)
#: The states of :func:`cache_state`, readiest first.
STATES = ("loaded", "cached", "cold", "unknown")


def cache_state(loops) -> str:
    """``"loaded"`` if every loop of ``loops`` (numba dispatchers) has machine code in this process,
    ``"cached"`` if numba's cache holds machine code of each for this machine and this source,
    ``"cold"`` if it lacks one (it will compile), ``"unknown"`` if the cache cannot be read (numba's
    internals changed: treated as ``"cached"``)."""
    if all(loop.overloads for loop in loops):
        return "loaded"
    try:
        return "cached" if all(_in_cache(loop) for loop in loops if not loop.overloads) else "cold"
    except Exception:                       # numba's private cache layout: never fail a run on it
        return "unknown"


def _in_cache(loop) -> bool:
    """Whether numba's cache index of ``loop`` lists machine code of this bytecode for this machine
    whose data file exists (the index is read as numba reads it: a stale time stamp gives none)."""
    from numba.core.registry import cpu_target

    cache = getattr(loop, "_cache", None)
    index_file = getattr(cache, "_cache_file", None)
    if index_file is None:                  # not cache=True
        return False
    magic = cpu_target.target_context.codegen().magic_tuple()
    code = hashlib.sha256(loop.py_func.__code__.co_code).hexdigest()
    for key, data_name in index_file._load_index().items():
        _, key_magic, (key_code, _) = key
        if key_magic == magic and key_code == code and os.path.exists(index_file._data_path(data_name)):
            return True
    return False
