"""Ground-motion records: PEER .AT2 and text readers, GroundMotion, unit conversions."""

import re
from pathlib import Path

import numpy as np
import pytest

from unilateral.loads import (
    STANDARD_GRAVITY,
    GroundMotion,
    RecordFormatError,
    acceleration_factor,
    force_factor,
    length_factor,
    read_at2,
    read_record,
    read_table,
    read_text_record,
)

DATA = Path(__file__).parent / "data" / "records"

# The 12 values written (in various formats) in every well-formed .AT2 test file.
AT2_VALUES = np.array([
    0.001234567, -0.002345678, 0.003456789, -0.004567890, 0.005678901,
    0.1, -0.2, 0.3, -0.0004, 0.0005,
    -0.06, 0.07,
])


# ---------------------------------------------------------------- units

@pytest.mark.parametrize(
    "unit, factor",
    [
        ("g", 9.80665), ("G", 9.80665), ("m/s2", 1.0), ("m/s^2", 1.0), ("M/SEC/SEC", 1.0),
        ("cm/s2", 0.01), ("cm/s^2", 0.01), ("gal", 0.01), ("CM/S/S", 0.01), ("cm/sec/sec", 0.01),
        ("cm/sec^2", 0.01), (" cm / s / s ", 0.01), ("mm/s2", 1e-3), ("in/s2", 0.0254), ("ft/s2", 0.3048),
    ],
)
def test_acceleration_factor(unit, factor):
    assert acceleration_factor(unit) == pytest.approx(factor, rel=1e-15)


def test_length_and_force_factors():
    lengths = [length_factor(u) for u in ("m", "CM", "mm", "in", "ft")]
    assert lengths == pytest.approx([1, 0.01, 0.001, 0.0254, 0.3048])
    assert [force_factor(u) for u in ("N", "kN", "MN", "lbf", "KIP")] == pytest.approx(
        [1, 1e3, 1e6, 4.4482216152605, 4448.2216152605]
    )


@pytest.mark.parametrize(
    "function, unit, valid",
    [
        (acceleration_factor, "furlongs/fortnight^2", "cm/s2"),
        (length_factor, "yd", "ft"),
        (force_factor, "ton", "kip"),
    ],
)
def test_unknown_unit_names_it_and_lists_valid_ones(function, unit, valid):
    with pytest.raises(ValueError, match=rf"unknown .* unit '{re.escape(unit)}'.*valid units:.*{valid}"):
        function(unit)


# ---------------------------------------------------------------- AT2 header variants

@pytest.mark.parametrize(
    "name, dt",
    [
        ("standard.AT2", 0.01),  # NPTS=    12, DT=   .0100 SEC  (no leading zero)
        ("trailing_text.AT2", 0.01),  # ... SEC,  BAND-PASS FILTERED ...
        ("west2_no_space.AT2", 0.005),  # NPTS=12,    DT=0.0050SEC
        ("values_first.AT2", 0.005),  # 12 0.00500 NPTS, DT  (8 values per row)
        ("values_first_spaced.AT2", 0.005),  # "  12    .00500    NPTS, DT"
        ("leading_spaces.AT2", 0.02),
        ("lower_case.AT2", 0.01),
        ("no_comma.AT2", 0.01),  # NPTS= 12 DT= 0.01 SEC
        ("d_exponent.AT2", 0.01),  # 1.0D-01 values
    ],
)
def test_at2_header_variants(name, dt):
    gm = read_at2(DATA / name)
    assert gm.npts == 12
    assert gm.dt == dt
    np.testing.assert_allclose(gm.acceleration, AT2_VALUES * 9.80665, rtol=1e-14)
    assert gm.name == Path(name).stem
    assert len(gm.header) == 4
    assert gm.units.lower() == "g"


def test_at2_in_cm_per_s2_is_converted():
    gm = read_at2(DATA / "cms2.AT2")
    np.testing.assert_allclose(gm.acceleration, AT2_VALUES * 0.01, rtol=1e-14)
    assert gm.units == "CM/S/S"


def test_at2_units_argument():
    no_units = DATA / "no_units.AT2"
    np.testing.assert_allclose(read_at2(no_units).acceleration, AT2_VALUES * STANDARD_GRAVITY)
    np.testing.assert_allclose(read_at2(no_units, units="gal").acceleration, AT2_VALUES * 0.01)
    # Agreeing with the header (in another spelling) is fine.
    np.testing.assert_allclose(read_at2(DATA / "cms2.AT2", units="gal").acceleration, AT2_VALUES * 0.01)
    with pytest.raises(ValueError, match=r"standard\.AT2: units='cm/s2' disagrees with the units 'G'"):
        read_at2(DATA / "standard.AT2", units="cm/s2")


def test_at2_more_values_than_npts_warns_and_truncates():
    with pytest.warns(UserWarning, match=r"found 12 values .* NPTS=10; using the first 10"):
        gm = read_at2(DATA / "too_many_values.AT2")
    np.testing.assert_allclose(gm.acceleration, AT2_VALUES[:10] * STANDARD_GRAVITY)


@pytest.mark.parametrize(
    "name, message",
    [
        ("missing_npts.AT2", r"missing_npts\.AT2, line 4: missing NPTS in 'DT=   \.0100 SEC'"),
        ("missing_dt.AT2", r"missing_dt\.AT2, line 4: missing DT"),
        ("zero_dt.AT2", r"line 4: DT must be positive, got '\.0000'"),
        ("too_few_values.AT2", r"too_few_values\.AT2: found 12 values after the header, expected NPTS=15"),
        ("unknown_units.AT2", r"unknown_units\.AT2, line 3: .*unit 'FURLONGS'; valid units: g, m/s2, cm/s2"),
        ("bad_token.AT2", r"bad_token\.AT2, line 6: '0\.3000000E\+0O' is not a number"),
        ("empty.AT2", r"empty\.AT2: empty file"),
        ("short_header.AT2", r"only 2 line\(s\); a PEER \.AT2 file starts with 4 header lines"),
    ],
)
def test_broken_at2_files(name, message):
    with pytest.raises(RecordFormatError, match=message) as info:
        read_at2(DATA / name)
    assert info.value.path == str(DATA / name)
    assert isinstance(info.value, ValueError)


# ---------------------------------------------------------------- text records

def test_one_column_text_record():
    gm = read_text_record(DATA / "one_column.txt", dt=0.02, units="cm/s2")
    np.testing.assert_allclose(gm.acceleration, [0.015, -0.02, 0.0325, -0.045])
    assert gm.dt == 0.02
    assert gm.header == ("# Synthetic one-column record for tests", "# units: cm/s2, dt = 0.02 s")


def test_two_column_text_record_infers_dt():
    gm = read_text_record(DATA / "two_column.csv", units="g", skip_header=1)
    assert gm.dt == pytest.approx(0.01, rel=1e-12)
    np.testing.assert_allclose(gm.acceleration, np.array([0.01, -0.02, 0.03, -0.04, 0.05]) * STANDARD_GRAVITY)
    assert gm.header == ("time,acceleration",)


def test_text_record_value_column_and_dt_check():
    path = DATA / "three_column.txt"
    velocity = read_text_record(path, units="m/s2", value_column=2, dt=0.005)
    np.testing.assert_allclose(velocity.acceleration, [0.0, 1e-3, 2e-3, 3e-3])
    with pytest.raises(ValueError, match=r"dt=0\.01 disagrees with the time step 0\.005"):
        read_text_record(path, units="g", dt=0.01)
    with pytest.raises(ValueError, match=r"value_column=3 is out of range: .*three_column\.txt has 3 column"):
        read_text_record(path, units="g", value_column=3)


def test_text_record_errors():
    with pytest.raises(RecordFormatError, match=r"nonuniform\.txt, line 5: time 0\.04 follows 0\.02"):
        read_text_record(DATA / "nonuniform.txt", units="g")
    with pytest.raises(ValueError, match=r"one_column\.txt: units is required"):
        read_text_record(DATA / "one_column.txt", dt=0.02)
    with pytest.raises(ValueError, match=r"one-column record needs dt"):
        read_text_record(DATA / "one_column.txt", units="g")
    with pytest.raises(RecordFormatError, match=r"ragged\.txt, line 2: 3 column\(s\), expected 2"):
        read_text_record(DATA / "ragged.txt", units="g")
    with pytest.raises(RecordFormatError, match=r"two_column\.csv, line 1: 'time' is not a number"):
        read_text_record(DATA / "two_column.csv", units="g")


def test_text_record_starting_late_warns():
    with pytest.warns(UserWarning, match=r"starts at t=0\.01 s"):
        gm = read_text_record(DATA / "late_start.txt", units="g")
    assert gm.npts == 3


def test_read_table_auto_header():
    table = read_table(DATA / "two_column.csv", skip_header=None)
    assert table.values.shape == (5, 2)
    np.testing.assert_array_equal(table.line_numbers, [2, 3, 4, 5, 6])


def test_read_record_dispatches_on_suffix():
    assert read_record(DATA / "standard.AT2").npts == 12
    assert read_record(DATA / "one_column.txt", dt=0.02, units="gal").npts == 4


# ---------------------------------------------------------------- GroundMotion

@pytest.fixture
def motion():
    rng = np.random.default_rng(12345)
    return GroundMotion(0.01, rng.standard_normal(101), name="noise")


def test_ground_motion_properties(motion):
    assert motion.npts == 101
    assert motion.duration == pytest.approx(1.0)
    np.testing.assert_allclose(motion.time, np.arange(101) * 0.01)
    assert motion.pga == np.max(np.abs(motion.acceleration))
    assert not motion.acceleration.flags.writeable


def test_ground_motion_interpolation(motion):
    np.testing.assert_array_equal(motion(motion.time), motion.acceleration)
    a = motion.acceleration
    assert motion(0.015) == pytest.approx(0.5 * (a[1] + a[2]))
    assert motion(-0.001) == 0.0
    assert motion(motion.duration + 1e-9) == 0.0
    assert motion(motion.duration) == a[-1]
    assert isinstance(motion(0.5), float)
    assert motion(np.zeros((2, 3))).shape == (2, 3)


def test_ground_motion_scaled_and_resampled(motion):
    np.testing.assert_allclose(motion.scaled(-2.0).acceleration, -2.0 * motion.acceleration)
    assert motion.scaled(2.0).name == "noise"

    fine = motion.resampled(0.005)
    assert fine.npts == 201 and fine.dt == 0.005
    np.testing.assert_allclose(fine.acceleration[::2], motion.acceleration)
    midpoints = 0.5 * (motion.acceleration[:-1] + motion.acceleration[1:])
    np.testing.assert_allclose(fine.acceleration[1::2], midpoints)

    coarse = motion.resampled(0.03)
    assert coarse.npts == 34
    np.testing.assert_allclose(coarse.acceleration, motion.acceleration[::3])


def test_ground_motion_validation():
    with pytest.raises(ValueError, match="dt must be a positive"):
        GroundMotion(0.0, [1.0, 2.0])
    with pytest.raises(ValueError, match="at least one sample"):
        GroundMotion(0.01, [])
    with pytest.raises(ValueError, match="acceleration contains nan"):
        GroundMotion(0.01, [1.0, np.nan])
    with pytest.raises(ValueError, match="factor must be finite"):
        GroundMotion(0.01, [1.0]).scaled(np.inf)
