"""A study's checks: a drift quantity without pairs is refused before any analysis runs (every
analysis failed with ``max() arg is an empty sequence``), and the messages name the file's keys,
not pydantic's union members (``records.angle.list[float][0]``, ``scaling.period.literal['T1']``)."""

from __future__ import annotations

import pytest
from test_batch import record_files, write_study

from unilateral.batch import load_study

ANALYSIS = '[analysis]\nmethod = "modal"\ndt = 2e-3\nt_end = 2.0\n'


def _study(tmp_path, records="", rest=""):
    record = record_files(1)[0].as_posix()
    return write_study(tmp_path, f'[[models]]\nfile = "tower.toml"\n[records]\nfiles = ["{record}"]\n'
                                 f'direction = "ux"\n{records}{rest}{ANALYSIS}')


@pytest.mark.parametrize("records, rest, message", [
    ("", '[[quantities]]\nname = "d"\ntype = "drift"\npairs = []\n' + "", "quantities[0].pairs = []: needs at least 1"),
    ("", '[[quantities]]\nname = "d"\ntype = "drift"\npairs = [[1, 2, 3]]\n',
     "quantities[0].pairs[0] = [1, 2, 3]: takes at most 2 item(s), got 3"),
    ('angle = ["a"]\n', "", 'records.angle[0] = "a": expected a number'),
    ("", '[scaling]\nmeasure = "sa"\nperiod = 0.0\nvalues = [1.0]\n', "scaling.period = 0.0: must be > 0"),
])
def test_the_checks_refuse_with_the_files_keys(tmp_path, records, rest, message):
    with pytest.raises(ValueError) as info:
        load_study(_study(tmp_path, records, rest))
    text = str(info.value)
    assert message in text, text
    for leak in ("list[", "literal[", "constrained-", ".float", "valid: )", "after validation"):
        assert leak not in text, (leak, text)
    assert len(text.strip().splitlines()) == 1, text                 # one problem, said once


def test_a_drift_with_pairs_is_accepted(tmp_path):
    study = load_study(_study(tmp_path, rest='[[quantities]]\nname = "d"\ntype = "drift"\npairs = [[1, 2]]\n'))
    assert "d" in study.quantity_columns
