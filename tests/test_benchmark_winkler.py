"""The Winkler scale table of ``benchmarks/opensees_winkler.py``: its smallest configuration.

A beam of 33 nodes (n = 98) on 11 tensionless Winkler springs under gravity and a moving load,
solved by ``method="auto"`` with the trapezoidal rule and by OpenSees (``ENT`` springs, Newmark
average acceleration, Newton) in a subprocess. What is checked could fail without being slow: the
rows and the JSON have their keys, contacts open and close, and the two codes give the same
displacement history (an equivalence check; no time is asserted). OpenSees comes with the ``test``
extra (``openseespy``); without it the OpenSees checks are skipped.

The tower row (the benchmark suite's tower on plain tensionless springs, mass-proportional damping)
is checked the same way at a short record (1 s in 400 steps): the model is the suite's, the two
codes give the same histories and the footing lifts off.
"""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
import opensees_winkler as bench  # noqa: E402

HAVE_OPENSEES = bench.opensees_environment() is not None
needs_opensees = pytest.mark.skipif(not HAVE_OPENSEES, reason="openseespy is not installed (pip install '.[test]')")

SMALL = bench.BeamSpec(nodes=33, springs=11)
STEPS = 200


def test_springs_carry_the_same_total_stiffness_whatever_their_number():
    for m in (2, 10, 11, 33):
        where, k = bench.springs(bench.BeamSpec(nodes=33, springs=m))
        assert len(where) == m and where[0] == 0 and where[-1] == 32
        assert k.sum() == pytest.approx(SMALL.k_soil * SMALL.length)


def test_load_samples_are_the_projects_load():
    st, q, _ = bench.frame2d(SMALL)
    weight = q(0.0)
    uy = bench.uy_dofs(st, SMALL.nodes)
    samples = bench.load_samples(SMALL, STEPS, bench.DT)
    for k in (0, 1, 57, STEPS):
        expected = weight.copy()
        for node, values in samples.items():
            expected[uy[node]] += values[k]
        assert np.array_equal(q(k * bench.DT), expected)              # the same numbers, bit for bit
        assert sum(v[k] for v in samples.values()) == (0.0 if k == 0 else pytest.approx(-SMALL.P))


def test_banded_recursion_is_the_bilateral_run():
    """The compiled banded recursion steps the beam with its springs bonded: the project's run with
    every contact held (``bilateral=True``) is the same discrete problem."""
    ub, per_step, _ = bench.banded_reference(SMALL, STEPS, bench.DT)
    held, _, _, _ = bench.run_unilateral(SMALL, STEPS, bench.DT, method="direct", bilateral=True)
    assert per_step > 0
    assert np.abs(ub - held).max() <= 1e-10 * np.abs(held).max()          # measured 3.7e-13 (1000 steps)


def test_smallest_table(tmp_path):
    """``main(["--quick", ...])`` restricted to its smallest cell: the rows and the JSON have their
    keys; with OpenSees, the middle node's history equals OpenSees's to round-off."""
    out = tmp_path / "winkler.json"
    cells = bench.QUICK_CELLS
    bench.QUICK_CELLS = cells[:1]
    try:
        rows = bench.main(["--quick", "--repeats", "1", "--out", str(out)])
    finally:
        bench.QUICK_CELLS = cells
    data = json.loads(out.read_text())
    assert len(data["load_average"]) == 3 and data["quick"] and data["dt"] == bench.DT
    assert data["rows"] == json.loads(json.dumps(rows))
    (row,) = data["rows"]
    tower = data["tower"]
    for key in ("n", "m", "steps", "contact_changes", "auto_s", "setup_s", "setup_share", "march_us_per_step",
                "direct_s", "direct_difference_over_peak", "banded_us_per_step", "march_over_banded",
                "auto_laps", "auto_method"):
        assert key in row, key
    assert (row["n"], row["m"], row["steps"]) == (98, 11, cells[0][2])
    assert row["contact_changes"] > 10                                   # the beam lifts off and lands
    assert 0 < row["setup_s"] < row["auto_s"] and row["march_us_per_step"] > 0
    assert row["direct_difference_over_peak"] <= 1e-10
    if HAVE_OPENSEES:
        assert row["opensees_failed_step"] == 0
        assert row["difference_over_peak"] <= 1e-9                      # measured 7.6e-14 (6.9e-13 at 1000 steps)
        assert row["linear_difference_over_peak"] <= 1e-9               # measured 1.3e-13
        assert row["ratio"] > 0
    _check_tower_row(tower)


def _check_tower_row(tower):
    """The quick tower row: 1 s of the record in 400 steps (its uplift starts at 0.2 s)."""
    spec, steps = bench.QUICK_TOWER
    assert (tower["n"], tower["m"], tower["steps"]) == (17, 3, steps) and tower["dt"] == spec.duration / steps
    for key in ("auto_s", "build_s", "setup_s", "march_us_per_step", "direct_s", "auto_laps", "auto_method",
                "peak_top_ux_m", "a0"):
        assert key in tower, key
    assert tower["contact_changes"] >= 2 and tower["open_steps"] > 10             # measured 6 and 66
    assert tower["direct_difference_over_peak"] <= 1e-9                          # measured 3e-11
    if HAVE_OPENSEES:
        assert tower["opensees_failed_step"] == 0
        assert tower["opensees_newton_iterations"] >= 2 * steps
        assert tower["opensees_open_steps"] == tower["open_steps"]               # the same springs open
        assert tower["difference_over_peak"] <= 1e-9                             # measured 6.5e-11
        assert tower["base_uy_difference_over_peak"] <= 2e-9                     # measured 1.1e-10
        assert tower["ratio"] > 0


def test_tower_is_the_suites_tower_on_springs():
    """``TowerSpec`` is ``problems.tower``'s tower; with ``c = 0`` and ``a0 M`` its stiffness, mass and
    load at ``k dt`` are the suite's (the dashpots only enter ``C``)."""
    from unilateral.bench import problems

    spec = bench.TowerSpec()
    assert (spec.storeys, spec.storey_height, spec.mass, spec.EI, spec.EA, spec.half_width, spec.k_soil,
            spec.gravity, spec.duration, spec.pga, spec.seed) == (
        problems.TOWER_STOREYS, problems.TOWER_STOREY_HEIGHT, problems.TOWER_MASS, problems.TOWER_EI,
        problems.TOWER_EA, problems.TOWER_HALF_WIDTH, problems.TOWER_K_SOIL, problems.TOWER_GRAVITY,
        problems.TOWER_DURATION, problems.TOWER_PGA, problems.TOWER_SEED)
    suite = problems.build("tower", steps=bench.TOWER_STEPS)
    st = bench.tower_frame2d(spec)
    model = st.to_model()
    assert suite.dt == spec.duration / bench.TOWER_STEPS and model.n == suite.model.n == 17
    assert abs(model.K - suite.model.K).max() == 0 and abs(model.M - suite.model.M).max() == 0
    assert abs(st.C - spec.a0 * st.M).max() == 0                                   # mass-proportional only
    steps = 50
    samples = bench.tower_samples(spec, bench.TOWER_STEPS)[:steps + 2]
    q = bench.tower_load(st, spec, samples, steps)
    assert np.array_equal(q, suite.load.sample(np.arange(steps + 1) * suite.dt))   # point values, bit for bit
    # the first mode with the springs bonded is at f1 (a0 is 5 % there)
    import scipy.linalg as sl

    K, M = model.K.toarray(), st.M.toarray()
    heavy = np.diag(M) > 0
    Kc = K[np.ix_(heavy, heavy)] - K[np.ix_(heavy, ~heavy)] @ np.linalg.solve(K[np.ix_(~heavy, ~heavy)],
                                                                             K[np.ix_(~heavy, heavy)])
    f1 = np.sqrt(sl.eigvalsh(Kc, M[np.ix_(heavy, heavy)])[0]) / (2 * np.pi)
    assert f1 == pytest.approx(spec.f1, rel=1e-2)


@needs_opensees
def test_opensees_springs_act_in_compression_only():
    """The ENT springs of the OpenSees model: with them the response differs from the bonded beam
    by far more than round-off (the beam lifts off), and equals the project's."""
    ours, _, _, sol = bench.run_unilateral(SMALL, STEPS, bench.DT)
    theirs, _, failed, iterations, _ = bench.opensees_in_subprocess(SMALL, STEPS, bench.DT)
    linear, *_ = bench.opensees_in_subprocess(SMALL, STEPS, bench.DT, material="Elastic")
    assert failed == 0 and iterations >= STEPS
    peak = np.abs(theirs).max()
    assert np.abs(ours - theirs).max() <= 1e-9 * peak
    assert np.abs(linear - theirs).max() > 0.1 * peak
    assert np.max(sol.v) > 0                                             # some spring separates
