"""Frozen outputs of every example: the cases, a compact digest of a run folder, and its writer.

Each case is a model file of ``examples/`` run by ``unilateral run FILE --figures none`` or a built-in
example run by ``unilateral example NAME --figures none``. :func:`digest` reduces the folder's
``results.nc`` (every numeric variable: shape, max, min, sum of |x|, values at fixed flat indices) and
``summary.json`` (every number, by key path, timings and paths left out) to a small dict, so that a
change of the solver's internals can be shown to leave every number unchanged (``--write`` stores
the digest of all cases in ``tests/data/snapshot_outputs.json``; ``test_snapshot_outputs.py`` compares).
"""

import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
STORE = ROOT / "tests" / "data" / "snapshot_outputs.json"
N_PICKS = 8
#: Every case runs with one BLAS thread: the threads change the order of a product's sums (by 5e-11
#: of the peak on the 3-D building), and the snapshot is to show the code's changes, not the pool's.
ONE_THREAD = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
#: ... and with the engine chosen by the policy's steps rule, never by what numba's cache holds
#: (:mod:`unilateral.march.policy`): the two engines agree to round-off, not bit for bit.
PINNED = {**ONE_THREAD, "UNILATERAL_ENGINE_CHOICE": "steps"}
SKIP_WORDS = ("time", "timing", "wall", "elapsed", "seconds", "version", "path", "file", "dir", "date",
              "output")                  # summary.json's "output": what was written, not a result

CASES = {
    "liolios1990.toml": ["run", str(EXAMPLES / "liolios1990.toml")],
    "pounding.toml": ["run", str(EXAMPLES / "pounding.toml")],
    "winkler_beam.toml": ["run", str(EXAMPLES / "winkler_beam.toml")],
    "yielding_frame.toml": ["run", str(EXAMPLES / "yielding_frame.toml")],
    "building3d.toml": ["run", str(EXAMPLES / "building3d.toml")],
    "example-liolios1990": ["example", "liolios1990"],
    "example-halfspace": ["example", "halfspace"],
    "example-footings": ["example", "footings"],
}


def run_case(name, out):
    """Run case ``name`` of :data:`CASES` into folder ``out`` with the CLI; return the wall time [s]."""
    if name not in CASES:
        raise ValueError(f"case={name!r} is not a snapshot case; valid: {sorted(CASES)}")
    full = ["--histories", "full"] if CASES[name][0] == "run" else []     # every history, whatever its size
    cmd = [sys.executable, "-m", "unilateral", *CASES[name], *full, "--out", str(out), "--figures", "none"]
    start = time.perf_counter()
    done = subprocess.run(cmd, capture_output=True, text=True, env={**os.environ, **PINNED})
    if done.returncode != 0:
        raise RuntimeError(f"case {name!r} failed ({' '.join(cmd)}):\n{done.stdout}\n{done.stderr}")
    return time.perf_counter() - start


def _num(x):
    """A float for JSON: NaN and infinities as strings."""
    x = float(x)
    return x if math.isfinite(x) else repr(x)


def array_digest(a):
    """Shape, NaN count, max, min, sum of |x| and the values at :data:`N_PICKS` fixed flat indices."""
    a = np.asarray(a)
    if a.dtype == bool:
        a = a.astype(np.int8)
    flat = a.astype(np.float64).ravel()
    finite = flat[np.isfinite(flat)]
    picks = sorted({int(i) for i in np.linspace(0, flat.size - 1, N_PICKS)}) if flat.size else []
    return {
        "shape": list(a.shape),
        "n_nan": int(np.isnan(flat).sum()),
        "max": _num(finite.max()) if finite.size else None,
        "min": _num(finite.min()) if finite.size else None,
        "sum_abs": _num(np.abs(finite).sum()),
        "picks": {str(i): _num(flat[i]) for i in picks},
    }


def _skipped(key):
    low = key.lower()
    return any(word in low for word in SKIP_WORDS)


def flatten_numbers(obj, prefix=""):
    """Every number of a JSON object by key path (``a/b/0``), keys naming timings or paths skipped."""
    found = {}
    if isinstance(obj, dict):
        for key, value in obj.items():
            if not _skipped(str(key)):
                found.update(flatten_numbers(value, f"{prefix}{key}/"))
    elif isinstance(obj, list):
        for i, value in enumerate(obj):
            found.update(flatten_numbers(value, f"{prefix}{i}/"))
    elif isinstance(obj, bool):
        found[prefix.rstrip("/")] = int(obj)
    elif isinstance(obj, (int, float)):
        found[prefix.rstrip("/")] = _num(obj)
    return found


def digest(folder):
    """The digest of a run folder: every numeric variable and coordinate of ``results.nc`` and every
    number of ``summary.json``."""
    folder = Path(folder)
    variables = {}
    with xr.open_dataset(folder / "results.nc") as ds:
        for name in sorted(list(ds.data_vars) + list(ds.coords), key=str):
            values = ds[name].values
            if values.dtype.kind in "biuf" and not str(name).startswith("time_"):  # time_*: timings
                variables[str(name)] = array_digest(values)
    summary = json.loads((folder / "summary.json").read_text())
    return {"variables": variables, "summary": flatten_numbers(summary)}


def main(argv=None):
    """``--write``: run every case and store the digests in :data:`STORE`, with each case's runtime."""
    import tempfile

    import unilateral

    argv = sys.argv[1:] if argv is None else argv
    if argv != ["--write"]:
        raise SystemExit("usage: python tests/snapshot_outputs.py --write")
    print("unilateral from", unilateral.__file__)
    store = {"cases": {}}
    with tempfile.TemporaryDirectory() as tmp:
        # a cache of compiled code of its own: numba's cache does not see a change in a function that
        # a cached one calls from another module, so an old cache could freeze an old build's numbers
        os.environ["NUMBA_CACHE_DIR"] = str(Path(tmp) / "numba-cache")
        for name in CASES:
            seconds = run_case(name, Path(tmp) / name)
            store["cases"][name] = digest(Path(tmp) / name)
            print(f"{name}: {seconds:.1f} s")
    STORE.write_text(json.dumps(store, indent=1, sort_keys=True) + "\n")
    print(f"wrote {STORE} ({STORE.stat().st_size} bytes)")


if __name__ == "__main__":
    main()
