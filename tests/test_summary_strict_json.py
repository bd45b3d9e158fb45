"""summary.json is strict JSON: non-finite numbers are null and listed under "non_finite"."""

import json
import math

import numpy as np
import pytest

from unilateral.io.atomic import NON_FINITE_KEY, strict_jsonable, write_json_atomic


def strict_load(path):
    """json.load that refuses NaN, Infinity and -Infinity as a strict parser does."""
    def refuse(constant):
        raise ValueError(f"non-standard JSON constant {constant}")
    return json.loads(path.read_text(), parse_constant=refuse)


def test_non_finite_values_become_null_and_are_listed(tmp_path):
    summary = {"results": {"uplift": {"periods": np.array([0.5, np.inf]), "ductility": {"value": float("nan")},
                                      "peak": -np.inf, "ok": 1.5}}, "title": "t"}
    path = write_json_atomic(tmp_path / "summary.json", summary)
    data = strict_load(path)
    assert data["results"]["uplift"]["periods"] == [0.5, None]
    assert data["results"]["uplift"]["ductility"]["value"] is None
    assert data["results"]["uplift"]["peak"] is None
    assert data["results"]["uplift"]["ok"] == 1.5
    assert data[NON_FINITE_KEY] == ["results.uplift.periods[1]", "results.uplift.ductility.value",
                                    "results.uplift.peak"]


def test_finite_summary_has_no_non_finite_key(tmp_path):
    data = strict_load(write_json_atomic(tmp_path / "s.json", {"a": [1.0, 2], "b": np.float64(3.0)}))
    assert data == {"a": [1.0, 2], "b": 3.0}


def test_strict_jsonable_dumps_with_allow_nan_false():
    data, paths = strict_jsonable([np.nan, {"x": np.float32("inf")}, 2.0])
    assert json.loads(json.dumps(data, allow_nan=False)) == [None, {"x": None}, 2.0]
    assert paths == ["[0]", "[1].x"]
    with pytest.raises(ValueError):
        json.dumps([math.nan], allow_nan=False)


def test_a_run_with_infinite_periods_writes_strict_json(tmp_path, monkeypatch):
    """E = 1.18e21 once gave infinite periods: forced here, summary.json stays strict."""
    from pathlib import Path

    import unilateral.analysis.results as results
    from unilateral.analysis.run import run_model_file

    original = results.modes

    def infinite(*args, **kwargs):
        info = original(*args, **kwargs)
        info["period"] = np.full_like(info["period"], np.inf)
        return info

    monkeypatch.setattr(results, "modes", infinite)
    example = Path(__file__).resolve().parents[1] / "examples" / "liolios1990.toml"
    model_file = tmp_path / "m.toml"
    model_file.write_text(example.read_text().replace("t_end = 1.0", "t_end = 0.01"))
    run_model_file(model_file, out=tmp_path / "out", figures=())
    data = strict_load(tmp_path / "out" / "summary.json")
    assert "results.unilateral.periods[0]" in data[NON_FINITE_KEY]
    assert data["results"]["unilateral"]["periods"][0] is None
