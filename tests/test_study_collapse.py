"""Collapse is not non-convergence (issue 33, item 5): a study records per analysis ``collapse``
(a limit of ``[collapse]`` exceeded, or a mechanism under gravity) apart from ``status`` ``failed``
(the LCP of a step failed); IDA curves go flat at a collapse and mark failures apart; fragility
counts a collapse as an exceedance and leaves failures out."""

from __future__ import annotations

import numpy as np
import pytest

from test_batch import record_files
from unilateral.batch import StudyFileError, load_study, run_study
from unilateral.batch.collapse import mechanism
from unilateral.modelfile import load_model_file

W, H = 100.0, 3.0          # the column's weight [kN] and height [m]

# A cantilever column of 3 m with a 10 t mass on top, an elastic-plastic hinge at its base (My = 30 kN m)
# and P-Delta: once the hinge yields the static tangent is K - W/h < 0 sideways (a mechanism under gravity)
# and the drift runs away; elastic (a weak record) it sways by millimetres.
COLUMN = """\
units = { length = "m", force = "kN", time = "s" }
nodes = [ { id = 1, x = 0.0, y = 3.0 }, { id = 2, x = 0.0, y = 0.0 } ]
supports = [ { node = 2, ux = true, uy = true, rz = true } ]
elements = [ { type = "beam", name = "col", node_i = 2, node_j = 1, E = 3e6, A = 1.0, I = 1e-3 } ]
unilateral = [ { type = "hinge", name = "base", beam = "col", end = "i", My = 30.0, k = 2000.0 } ]
masses = [ { node = 1, m = 10.0 } ]
[loads.gravity]
g = 10.0
[analysis]
dt = 0.01
t_end = 6.0
method = "direct"
p_delta = true
bilateral_reference = false
"""


def study(folder, limit=0.1, mechanism=True):
    """Two variants of the column under one record at PGA 0.02 g and 1 g, with the LCP solvers held to one
    solve (lcp_options max_iter = 1): the block principal pivoting of variant ``column`` fails at the
    hinge's first yield (a step that needs a second solve), the Gauss-Seidel sweep of variant ``pgs``
    solves the one-pair LCP in its one sweep, and its column collapses."""
    folder.mkdir(exist_ok=True)
    (folder / "column.toml").write_text(COLUMN)
    record = record_files(1)[0].as_posix()
    path = folder / f"study_{limit}_{mechanism}.toml"
    path.write_text(f"""
[[models]]
file = "column.toml"
[[models]]
file = "column.toml"
name = "pgs"
set = {{ "analysis.lcp" = "pgs" }}
[records]
files = ["{record}"]
direction = "ux"
[scaling]
measure = "pga"
values = [0.02, 1.0]
[analysis]
lcp_options = {{ max_iter = 1 }}
[[quantities]]
name = "drift"
type = "drift"
pairs = [[1, 2]]
[collapse]
quantity = "drift"
limit = {limit!r}
mechanism = {str(mechanism).lower()}
[[limit_states]]
name = "drift 2%"
quantity = "drift"
threshold = 0.02
""")
    return path


def rows(table) -> dict:
    return {(str(m), float(x)): i for i, (m, x) in enumerate(zip(table["model"].values, table["intensity"].values))}


@pytest.fixture(scope="module")
def ran(tmp_path_factory):
    folder = tmp_path_factory.mktemp("collapse")
    return folder, run_study(study(folder), folder / "out", synchronous=True, progress=False)


def test_a_collapse_and_a_failure_are_told_apart(ran):
    _, result = ran
    t, at = result.table, rows(result.table)
    weak = [at["column", 0.02], at["pgs", 0.02]]
    assert list(t["status"].values[weak]) == ["ok", "ok"] and list(t["collapse"].values[weak]) == [0, 0]
    assert np.all(t["drift"].values[weak] < 0.01)
    failed, fell = at["column", 1.0], at["pgs", 1.0]
    assert t["status"].values[failed] == "failed" and "the LCP of step" in t["message"].values[failed]
    assert t["collapse"].values[failed] == 0 and t["collapse_reason"].values[failed] == ""
    assert t["status"].values[fell] == "ok" and t["collapse"].values[fell] == 1
    reason = t["collapse_reason"].values[fell]
    assert "> 0.1 (collapse.limit)" in reason and "a mechanism under gravity" in reason and "base.plastic" in reason
    assert t["drift"].values[fell] > 10.0                                      # the drift runs away
    assert result.counts["failed"] == 1 and t.attrs["counts"].endswith('"collapse": 1}')


def test_fragility_counts_collapse_never_failure(ran):
    folder, result = ran
    import json

    fits = {(f["limit_state"], f["label"]): f for f in json.loads((folder / "out" / "fragility.json").read_text())}
    column, pgs = fits["drift 2%", "column"], fits["drift 2%", "pgs"]
    assert (column["levels"], column["n"], column["z"]) == ([0.02], [1], [0])     # the failure is left out ...
    assert "1 failed analyses left out (not counted as collapse)" in column["note"]
    assert (pgs["n"], pgs["z"]) == ([1, 1], [0, 1])                # ... the collapse exceeds the limit state
    assert (fits["collapse", "pgs"]["n"], fits["collapse", "pgs"]["z"]) == ([1, 1], [0, 1])
    assert (fits["collapse", "column"]["n"], fits["collapse", "column"]["z"]) == ([1], [0])
    assert {p.name for p in result.figures} == {"ida.png", "fragility.png"}


def test_a_limit_passed_before_the_failure_is_a_collapse_and_the_limit_needs_no_new_run(ran):
    """The peaks of a failed run over the steps it computed (``values_computed``): a drift of 2.4 % before
    the failed step exceeds a limit of 1 %; a changed [collapse] reruns nothing (it is not in the keys)."""
    folder, _ = ran
    again = run_study(study(folder, limit=0.01, mechanism=False), folder / "out", synchronous=True, progress=False)
    t, at = again.table, rows(again.table)
    assert again.ran == 0 and again.skipped == 4
    failed = at["column", 1.0]
    assert t["status"].values[failed] == "failed" and t["collapse"].values[failed] == 1
    assert t["collapse_reason"].values[failed].startswith("drift = 0.02") and "mechanism" not in "".join(
        t["collapse_reason"].values)


def test_the_mechanism_is_the_static_tangent_with_p_delta_and_the_yielding_hinge_released(tmp_path):
    """At the end of the collapsing run the tangent's smallest eigenvalue is near -W/h (the pinned column's
    P-Delta stiffness); the column held elastic (no P-Delta either) is no mechanism."""
    import unilateral as ul

    path = tmp_path / "column.toml"
    path.write_text(COLUMN.replace('method = "direct"', 'method = "direct"\nlcp = "pgs"')
                    + '[[loads.ground_motion]]\nfile = "' + record_files(1)[0].as_posix()
                    + '"\ndirection = "ux"\nscale = 3.0\n')
    spec = load_model_file(path)
    a = spec.analysis
    sol = ul.solve(spec.model, spec.load, dt=a["dt"], t_end=a["t_end"], method="direct", lcp="pgs",
                   lcp_options={"max_iter": 1})
    why = mechanism(spec.model, sol)
    lowest = float(why.split("smallest eigenvalue ")[1].split(",")[0])
    assert why.startswith("a mechanism under gravity at t = 6") and -1.1 * W / H < lowest < -0.9 * W / H
    assert mechanism(spec.model, ul.solve(spec.model, spec.load, dt=a["dt"], t_end=0.2, method="direct")) == ""


def test_collapse_keys_are_checked(tmp_path):
    path = study(tmp_path)
    text = path.read_text()
    path.write_text(text.replace('quantity = "drift"\nlimit', 'quantity = "drfit"\nlimit'))
    with pytest.raises(StudyFileError, match=r'collapse\.quantity = "drfit": no such quantity \(valid: drift\); '
                                             r'did you mean "drift"\?'):
        load_study(path)
    path.write_text(text.replace("limit = 0.1\n", ""))
    with pytest.raises(StudyFileError, match=r"collapse\.limit: missing key \(collapse\.quantity is given"):
        load_study(path)
