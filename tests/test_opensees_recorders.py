"""Recorders write the files OpenSees writes: ``recorders.py`` run by both codes, its files read
back: the same shapes (rows: every committed step, static and transient, or every ``-dT``;
columns: the time, then the values), the values to 1e-8 of their peak at 16 and 12 digits and to
the printed digits at the default precision of 6."""

import numpy as np
import pytest

from test_opensees_module import both, needs_opensees

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused


@needs_opensees
def test_recorder_files_equal_openseespy():
    theirs, ours = both("recorders.py")
    for key in theirs:
        if key.endswith(".shape"):
            assert np.array_equal(theirs[key], ours[key]), key
            continue
        tol = 1e-5 if key == "local" else 1e-8                        # 'local' is written with 6 digits
        assert np.abs(theirs[key] - ours[key]).max() <= tol * np.abs(theirs[key]).max(), key
    assert list(theirs["disp.shape"]) == [4 + 300, 1 + 6]            # 4 static + 300 transient steps
    assert list(theirs["accel.shape"]) == [29, 3]                     # -dT 0.02 on 0.005 steps
    hinges = theirs["hinges"].reshape(-1, 3)
    assert np.isclose(np.abs(hinges[:, 1:]).max(), 130.0)             # the hinges yield
    assert np.array_equal(hinges[:4, 0], [0.25, 0.5, 0.75, 1.0])      # the static steps' times
    assert list(theirs["envnode.shape"]) == [3, 8] and list(theirs["envele.shape"]) == [3, 4]
    env = theirs["envnode"].reshape(3, 8)                             # min, max, absmax; (time, value) pairs
    assert np.allclose(env[2, 1::2], np.maximum(-env[0, 1::2], env[1, 1::2]))


def test_recorder_writes_lines_and_closes_on_wipe(tmp_path):
    path = tmp_path / "u.out"
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0, 1, 1)
    ops.uniaxialMaterial('Elastic', 1, 100.0)
    ops.element('zeroLength', 1, 1, 2, '-mat', 1, '-dir', 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(2, 1.0, 0.0, 0.0)
    assert ops.recorder('Node', '-file', str(path), '-time', '-node', 2, '-dof', 1, 'disp') == 0
    ops.integrator('LoadControl', 0.5)
    ops.analysis('Static')
    ops.analyze(3)
    ops.wipe()
    assert path.read_text() == "0.5 0.005\n1 0.01\n1.5 0.015\n"    # %g with 6 digits, as C++ streams


@pytest.mark.parametrize("args, words", [
    (('Drift', '-file', 'x.out', '-iNode', 1, '-jNode', 1), ("Drift",)),
    (('Node', '-xml', 'x.xml', '-node', 1, '-dof', 1, 'disp'), ("'-xml'", "text only")),
    (('Node', '-node', 1, '-dof', 1, 'disp'), ("to a file",)),
    (('Node', '-file', 'x.out', '-node', 7, '-dof', 1, 'disp'), ("[7] are not defined",)),
    (('Node', '-file', 'x.out', '-node', 1, '-dof', 4, 'disp'), ("1..3",)),
    (('Node', '-file', 'x.out', '-node', 1, '-dof', 1, 'eigen', 1), ("'eigen'",)),
])
def test_recorders_outside_the_subset_are_refused(tmp_path, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    with pytest.raises(OpenSeesRefused) as info:
        ops.recorder(*args)
    for word in words:
        assert word in str(info.value)
