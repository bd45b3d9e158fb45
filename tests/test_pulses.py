"""Load time functions: values, boundary convention, vectorization, validation, CSV tables."""

from pathlib import Path

import numpy as np
import pytest

from unilateral.loads import (
    Constant,
    HalfSine,
    Ramp,
    RecordFormatError,
    Rectangular,
    Tabulated,
    TimeFunction,
    Triangular,
)

DATA = Path(__file__).parent / "data" / "records"

FUNCTIONS = [
    Rectangular(2.0, t_start=0.1, t_end=0.3),
    Triangular(1.0, t_start=0.1, t_peak=0.2, t_end=0.4),
    HalfSine(3.0, duration=0.2),
    Constant(4.0),
    Ramp(0.5, 2.0),
    Tabulated([0.0, 1.0, 2.0], [0.0, 1.0, 0.0]),
]


def test_rectangular():
    f = Rectangular(2.0, t_start=0.1, t_end=0.3)
    assert [f(t) for t in (0.0, 0.1, 0.1000001, 0.2, 0.3, 0.3000001)] == [0.0, 0.0, 2.0, 2.0, 2.0, 0.0]
    assert Rectangular(5.0, t_end=1.0)(0.0) == 0.0  # zero at t = 0: the solver starts unloaded


def test_triangular():
    f = Triangular(1.0, t_start=0.1, t_peak=0.2, t_end=0.4)
    np.testing.assert_allclose(f([0.0, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5]), [0, 0, 0.5, 1, 0.5, 0, 0], atol=1e-12)
    blast = Triangular(-2.0, t_peak=0.0, t_end=1.0)  # instantaneous rise
    assert blast(0.0) == 0.0
    assert blast(1e-12) == pytest.approx(-2.0)
    assert blast(0.75) == pytest.approx(-0.5)
    sawtooth = Triangular(1.0, t_peak=1.0, t_end=1.0)
    assert sawtooth(1.0) == 1.0 and sawtooth(1.0 + 1e-12) == 0.0


def test_half_sine():
    f = HalfSine(3.0, t_start=0.5, duration=0.2)
    np.testing.assert_allclose(f([0.5, 0.55, 0.6, 0.7, 0.8]), [0, 3 * np.sin(np.pi / 4), 3, 0, 0], atol=1e-12)


def test_constant_and_ramp():
    assert Constant(4.0)(0.0) == 4.0
    np.testing.assert_array_equal(Constant(-1.5)([0.0, 10.0]), [-1.5, -1.5])
    np.testing.assert_allclose(Ramp(0.5, 2.0)([-1.0, 0.0, 0.25, 0.5, 3.0]), [0, 0, 1, 2, 2])


def test_tabulated_outside_options():
    zero = Tabulated([1.0, 2.0, 3.0], [1.0, 3.0, 2.0])
    hold = Tabulated([1.0, 2.0, 3.0], [1.0, 3.0, 2.0], outside="HOLD")
    np.testing.assert_allclose(zero([0.5, 1.0, 1.5, 3.0, 3.5]), [0, 1, 2, 2, 0])
    np.testing.assert_allclose(hold([0.5, 1.0, 1.5, 3.0, 3.5]), [1, 1, 2, 2, 2])
    assert hold.outside == "hold"
    assert not zero.t.flags.writeable


@pytest.mark.parametrize("f", FUNCTIONS, ids=lambda f: type(f).__name__)
def test_vectorized(f):
    rng = np.random.default_rng(7)
    t = rng.uniform(-0.5, 2.5, size=(4, 5))
    values = f(t)
    assert isinstance(f, TimeFunction)
    assert isinstance(values, np.ndarray) and values.shape == (4, 5)
    np.testing.assert_array_equal(values, [[f(x) for x in row] for row in t])
    assert isinstance(f(0.3), float)
    assert f([0.3]).shape == (1,)


@pytest.mark.parametrize(
    "make, message",
    [
        (
            lambda: Rectangular(1.0, t_start=0.3, t_end=0.3),
            r"t_end must be > t_start, got t_end=0\.3 and t_start=0\.3",
        ),
        (lambda: Rectangular(np.nan, t_end=1.0), r"amplitude must be finite, got nan"),
        (lambda: Triangular(1.0, t_peak=2.0, t_end=1.0), r"t_end must be >= t_peak"),
        (lambda: Triangular(1.0, t_start=1.0, t_peak=0.5, t_end=2.0), r"t_peak must be >= t_start"),
        (lambda: HalfSine(1.0, duration=-0.1), r"duration must be a positive finite number, got -0\.1"),
        (lambda: Ramp(0.0, 1.0), r"t_ramp must be a positive finite number, got 0\.0"),
        (lambda: Constant(np.inf), r"value must be finite, got inf"),
        (
            lambda: Tabulated([0.0, 1.0, 1.0], [1.0, 2.0, 3.0]),
            r"t: times must increase strictly; t=1\.0 follows t=1\.0",
        ),
        (lambda: Tabulated([0.0], [1.0]), r"t: a table needs at least two times, got 1"),
        (lambda: Tabulated([0.0, 1.0], [1.0, 2.0, 3.0]), r"values must have shape \(2,\), got shape \(3,\)"),
        (
            lambda: Tabulated([0.0, 1.0], [1.0, 2.0], outside="extrapolate"),
            r"outside='extrapolate' is not valid",
        ),
    ],
)
def test_parameter_validation(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_non_numeric_parameter():
    with pytest.raises(TypeError, match=r"amplitude must be a real number, got 'big'"):
        Rectangular("big", t_end=1.0)


def test_tabulated_from_csv():
    f = Tabulated.from_csv(DATA / "load_table.csv")
    np.testing.assert_allclose(f.t, [0.0, 0.1, 0.3, 0.4])
    np.testing.assert_allclose(f([0.05, 0.2, 0.35, 0.5]), [5.0, 10.0, 2.5, 0.0])
    held = Tabulated.from_csv(DATA / "load_table.csv", skip_header=1, outside="hold")
    assert held(1.0) == -5.0


def test_tabulated_from_csv_errors():
    with pytest.raises(RecordFormatError, match=r"load_table_decreasing\.csv, line 4: times must increase"):
        Tabulated.from_csv(DATA / "load_table_decreasing.csv")
    with pytest.raises(RecordFormatError, match=r"load_table_bad_token\.csv, line 3: 'ten' is not a number"):
        Tabulated.from_csv(DATA / "load_table_bad_token.csv")
    with pytest.raises(ValueError, match=r"value_column=2 is out of range"):
        Tabulated.from_csv(DATA / "load_table.csv", value_column=2)
    with pytest.raises(FileNotFoundError):
        Tabulated.from_csv(DATA / "no_such_file.csv")


# ---------------------------------------------------------------------- LoadHistory
def test_load_history_sample_equals_calls():
    from unilateral.loads import GroundMotion, LoadHistory
    record = GroundMotion(0.01, np.sin(np.linspace(0.0, 3.0, 31)))
    q = LoadHistory([1.0, -2.0, 0.5], [([0.0, 1.0, 0.0], FUNCTIONS[0]), ([1.0, 0.0, -1.0], record),
                                       ([0.5, 0.5, 0.5], FUNCTIONS[2])])
    t = np.linspace(-0.1, 0.5, 61)
    sampled = q.sample(t)
    assert sampled.shape == (61, 3)
    np.testing.assert_allclose(sampled, np.array([q(s) for s in t]), rtol=1e-15, atol=1e-15)
    assert q.n == 3 and np.any(sampled[:, 0] != sampled[0, 0])


def test_load_history_errors():
    from unilateral.loads import LoadHistory
    with pytest.raises(ValueError, match=r"terms\[0\] vector must have shape \(2,\), got shape \(3,\)"):
        LoadHistory([0.0, 0.0], [([1.0, 2.0, 3.0], Constant(1.0))])
    with pytest.raises(TypeError, match=r"terms\[1\] must be a pair \(vector, f\) with f callable"):
        LoadHistory([0.0], [([1.0], Constant(1.0)), ([1.0], 2.0)])
    with pytest.raises(ValueError, match=r"constant contains nan"):
        LoadHistory([np.nan])
    scalar_only = LoadHistory([0.0], [([1.0], lambda t: 2.0)])
    assert scalar_only(0.5) == 2.0
    with pytest.raises(ValueError, match=r"terms\[0\]: f\(t\) of 3 times returned shape \(\).*accept arrays"):
        scalar_only.sample(np.zeros(3))
