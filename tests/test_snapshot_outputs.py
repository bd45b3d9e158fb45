"""Every example's outputs equal to 1e-12 to those frozen in ``tests/data/snapshot_outputs.json``
(written by ``python tests/snapshot_outputs.py --write`` from the code before the solver's redesign):
each variable of ``results.nc`` and each number of ``summary.json``, relative to the variable's peak."""

import json
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from snapshot_outputs import CASES, STORE, digest, run_case  # noqa: E402

RTOL = 1e-12
SLOW = {"yielding_frame.toml", "building3d.toml", "example-footings"}


def _numbers(d):
    """The numbers of one variable's digest, by name (NaN/inf kept as their strings)."""
    found = {k: d[k] for k in ("n_nan", "max", "min", "sum_abs")}
    found.update({f"picks[{i}]": v for i, v in d["picks"].items()})
    return found


def _compare(where, now, then, scale):
    """Mismatches of number ``now`` against ``then`` to RTOL times ``scale`` (1e-300 at zero scale)."""
    if isinstance(now, str) or isinstance(then, str) or now is None or then is None:
        return [] if now == then else [f"{where}: now {now!r}, stored {then!r}"]
    tol = RTOL * scale if scale > 0 else 1e-300
    return [] if abs(now - then) <= tol else [f"{where}: now {now!r}, stored {then!r} (tol {tol:.3g})"]


def _peak(d):
    values = [abs(v) for v in (d["max"], d["min"]) if isinstance(v, float | int)]
    return max(values, default=0.0)


def mismatches(case, now, then):
    """Every difference between digest ``now`` and stored digest ``then`` of ``case``, as messages."""
    out = []
    for part in ("variables", "summary"):
        if set(now[part]) != set(then[part]):
            out.append(f"{case} {part}: keys differ, new {sorted(set(now[part]) - set(then[part]))}, "
                       f"missing {sorted(set(then[part]) - set(now[part]))}")
    for name in sorted(set(now["variables"]) & set(then["variables"])):
        a, b = now["variables"][name], then["variables"][name]
        if a["shape"] != b["shape"] or set(a["picks"]) != set(b["picks"]):
            out.append(f"{case} variable {name}: shape now {a['shape']}, stored {b['shape']}")
            continue
        na, nb = _numbers(a), _numbers(b)
        scale = _peak(b)
        for key in na:
            s = abs(nb[key]) if key == "sum_abs" and isinstance(nb[key], float) else scale
            out += _compare(f"{case} variable {name} {key}", na[key], nb[key], s)
    for key in sorted(set(now["summary"]) & set(then["summary"])):
        a, b = now["summary"][key], then["summary"][key]
        scale = abs(b) if isinstance(b, float | int) else 0.0
        out += _compare(f"{case} summary {key}", a, b, scale)
    return out


@pytest.fixture(scope="module")
def stored():
    return json.loads(STORE.read_text())["cases"]


@pytest.mark.parametrize(
    "case", [pytest.param(c, marks=pytest.mark.slow) if c in SLOW else c for c in CASES])
def test_the_outputs_equal_the_frozen_ones(case, stored, tmp_path):
    run_case(case, tmp_path / "out")
    bad = mismatches(case, digest(tmp_path / "out"), stored[case])
    assert not bad, f"{len(bad)} numbers differ from the snapshot:\n" + "\n".join(bad[:30])


def test_a_perturbed_number_is_caught(stored):
    """The comparison itself: 1e-9 relative on one value of one variable is reported by name."""
    case = "liolios1990.toml"
    then = stored[case]
    now = json.loads(json.dumps(then))
    name = next(n for n, d in now["variables"].items() if isinstance(d["max"], float) and d["max"] != 0)
    now["variables"][name]["max"] *= 1 + 1e-9
    bad = mismatches(case, now, then)
    assert len(bad) == 1 and name in bad[0] and case in bad[0]
