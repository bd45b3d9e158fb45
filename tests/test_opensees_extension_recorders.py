"""Element and EnvelopeElement recorders of the extension elements (``kelvinContact``, ``rigidContact``,
``springFooting``, ``footing`` on a soil medium): a script run once with recorders (its transient in
pieces of ``analyze(n)``, a footing on the soil past its horizon) writes, parsed back, the values the
queries ``eleForce`` / ``eleResponse`` return after each ``analyze(1)`` of a second run of the same
script (to round-off at 17 digits); ``-dT`` keeps every third step; the envelope is the min, max and
absolute max of those values at the first time each is reached; a recorder of an OpenSees element and
an extension writes both; an unknown response is refused by name."""

import numpy as np
import pytest

import unilateral.opensees as ops
from unilateral.opensees import OpenSeesRefused

DT = 0.005
PULSE = ((0.0, 0.01, 0.1, 0.11, 100.0), (0.0, 1.0, 1.0, 0.0, 0.0))


def _kelvin():
    """A mass of 10 on a Kelvin contact with friction on the ground; gravity, then a pulse up and sideways."""
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 0, 0, 1)
    ops.mass(2, 10.0, 10.0, 0.0)
    ops.kelvinContact(5, 1, 2, "-dir", 2, "-k", 1e4, "-c", 20.0, "-mu", 0.3, "-kt", 5e3)
    return [(2, (0.0, -98.1, 0.0))], [(2, (100.0, 500.0, 0.0))]


def _rigid():
    """A mass on a zeroLength spring resting on a rigid stop 0.05 below (e = 0.5), thrown up by a pulse."""
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 0, 1)
    ops.mass(2, 0.0, 10.0, 0.0)
    ops.uniaxialMaterial("Elastic", 1, 1e3)
    ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 2)
    ops.rigidContact(5, 2, "-dir", 2, "-gap", 0.05, "-e", 0.5)
    return [(2, (0.0, -98.1, 0.0))], [(2, (0.0, 700.0, 0.0))]


def _column(footing):
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 10.0)
    ops.node(2, 0.0, 0.0)
    ops.mass(1, 40.0, 40.0, 0.0)
    ops.geomTransf("Linear", 1)
    ops.element("elasticBeamColumn", 1, 2, 1, 1e12, 1.0, 1e9, 1)
    footing()
    return [(1, (0.0, -400.0, 0.0))]


def _spring_footing():
    """A column on a footing on 4 yielding tensionless springs, pushed sideways: it lifts and yields."""
    def footing():
        ops.fix(2, 1, 0, 0)
        ops.springFooting(5, 2, 4.0, 2.5e4, "-length", 1.0, "-c", 500.0, "-springs", 4, "-qult", 250.0)
    return _column(footing), [(1, (150.0, 0.0, 0.0))]


def _soil_footing():
    """A column on a footing sliding (mu = 0.3) on Wolf's cones, 4 patches, pushed sideways."""
    def footing():
        ops.footing(5, 2, 10.0, 10.0, "cones", 97.0, 1 / 3, 2.0, "-patches", 4, "-mu", 0.3)
        ops.mass(2, 5.0, 5.0, 5.0)
    return _column(footing), [(1, (600.0, 0.0, 0.0))]


def _halfspace_footing():
    """A column on a footing on the rigorous half-space (the convolution quadrature), 4 patches."""
    def footing():
        ops.footing(5, 2, 10.0, 10.0, "halfspace", 97.0, 1 / 3, 2.0, "-patches", 4)
    return _column(footing), [(1, (400.0, 0.0, 0.0))]


#: case: (script, responses of element 5, transient pieces of the recorded run)
CASES = {
    "kelvinContact": (_kelvin, ("force", "basicForce", "deformation", "opening"), (15, 25)),
    "rigidContact": (_rigid, ("force", "contactForce", "opening"), (120, 80)),
    "springFooting": (_spring_footing, ("force", "contactForce", "uplift", "settlement"), (40, 60)),
    "footing": (_soil_footing, ("force", "contactForce", "uplift", "slip"), (6, 14)),   # past the horizon of 6
}
HALFSPACE = (_halfspace_footing, ("force", "contactForce", "uplift"), (2, 4))


def _session(case, recorders=None, pieces=None):
    """Run the case's script: gravity by a static analysis, then the pulse from t = 0 stepped by
    ``pieces`` (recorded: ``recorders(stage)`` defines them, ``"start"`` before the static analysis,
    ``"pulse"`` after it) or by ``analyze(1)`` steps returning the rows (time, the queries of each
    response of element 5) of the static state and of each step."""
    script, names, steps = CASES.get(case) or HALFSPACE
    ops.wipe()
    gravity, pulse = script()
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for node, values in gravity:
        ops.load(node, *values)
    if recorders:
        recorders("start")

    def row():
        values = [ops.getTime()]
        for name in names:
            values.extend(ops.eleForce(5) if name == "force" else ops.eleResponse(5, name))
        return values
    ops.analysis("Static")
    assert ops.analyze(1) == 0
    rows = [row()]
    ops.loadConst("-time", 0.0)
    ops.timeSeries("Path", 2, "-time", *PULSE[0], "-values", *PULSE[1])
    ops.pattern("Plain", 2, 2)
    for node, values in pulse:
        ops.load(node, *values)
    if recorders:
        recorders("pulse")
    ops.analysis("Transient")
    ops.integrator("Newmark", 0.5, 0.25)
    if pieces:
        for n in pieces:
            assert ops.analyze(n, DT) == 0
        ops.wipe()                                        # closes the files
        return None
    for _ in range(sum(steps)):
        assert ops.analyze(1, DT) == 0
        rows.append(row())
    ops.wipe()
    return np.array(rows)


def _widths(case):
    """The number of columns of each response of element 5."""
    names = (CASES.get(case) or HALFSPACE)[1]
    widths = {"kelvinContact": dict(force=6, basicForce=2, deformation=1, opening=1),
              "rigidContact": dict(force=3, contactForce=1, opening=1)}.get(case)
    if widths is None:
        widths = dict(force=3, contactForce=4, uplift=4, settlement=4, slip=4)
    return [widths[name] for name in names]


def _read(path):
    return np.atleast_2d(np.loadtxt(path))


def _close(a, b, rtol):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    assert a.shape == b.shape, (a.shape, b.shape)
    scale = np.maximum(np.abs(b).max(axis=0), 1e-300)
    assert np.all(np.abs(a - b).max(axis=0) <= rtol * scale), (np.abs(a - b).max(axis=0) / scale)


#: The agreement of the recorded and the queried values: the same steps bit for bit, printed at 17
#: digits; the footing on the soil is solved again over other horizons (the first steps agree to round-off).
RTOL = {"footing": 1e-9}


@pytest.mark.parametrize("case", list(CASES))
def test_recorded_rows_are_the_queries_of_each_step(case, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    _, names, pieces = CASES[case]

    def recorders(stage):
        if stage == "start":
            for name in names:
                ops.recorder("Element", "-file", f"{name}.out", "-time", "-precision", 17, "-ele", 5, name)
            ops.recorder("EnvelopeElement", "-file", "env.out", "-time", "-precision", 17, "-ele", 5, *names[1:2])
        else:
            ops.recorder("Element", "-file", "dT.out", "-time", "-dT", 3 * DT, "-precision", 17, "-ele", 5, names[0])
    _session(case, recorders, pieces)
    rows = _session(case)
    assert rows.shape[0] == 1 + sum(pieces)
    rtol = RTOL.get(case, 1e-14)
    at = 1
    for name, width in zip(names, _widths(case)):
        got = _read(f"{name}.out")
        assert got.shape == (rows.shape[0], 1 + width), (name, got.shape)
        np.testing.assert_allclose(got[:, 0], rows[:, 0], rtol=1e-15, atol=1e-15)     # -time: the times
        _close(got[:, 1:], rows[:, at:at + width], rtol)
        at += width
    # -dT 3 dt from the pulse's start: the steps 1, 4, 7, ... (each the first one dT after the last record)
    got = _read("dT.out")
    expected = rows[1::3, :1 + _widths(case)[0]]
    assert got.shape == expected.shape
    _close(got, expected, rtol)
    # the envelope of the second response: min, max, absmax, each (time, value), the first time reached
    width = _widths(case)[1]
    values = rows[:, 1 + _widths(case)[0]:1 + _widths(case)[0] + width]
    env = _read("env.out")
    assert env.shape == (3, 2 * width)
    extremes = (values.min(axis=0), values.max(axis=0), np.abs(values).max(axis=0))
    for which, (line, extreme) in enumerate(zip(env, extremes)):
        _close(line[1::2], extreme, rtol)
        for k, t in enumerate(line[::2]):                 # the value at the time written is the extreme
            step = int(np.argmin(np.abs(rows[:, 0] - t)))
            assert abs(rows[step, 0] - t) <= 1e-12
            x = abs(values[step, k]) if which == 2 else values[step, k]
            assert abs(x - line[2 * k + 1]) <= rtol * max(np.abs(values[:, k]).max(), 1e-300)


def test_a_footing_on_a_halfspace_records_the_queries_of_its_steps(tmp_path, monkeypatch):
    """On the half-space each analyze(1) solves the simulation again from its start over one step more
    (:mod:`unilateral.opensees.soil_analysis`): the lines recorded in that session are its queries after
    each step, to the last digit; the run in pieces (2, 4) is solved over the horizons 2 and 6, whose
    convolution-quadrature weights differ in the last digits (measured: 2.9e-7 of a column's peak)."""
    monkeypatch.chdir(tmp_path)
    names = HALFSPACE[1]

    def recorders(stage):
        if stage == "start":
            for name in names:
                ops.recorder("Element", "-file", f"{name}.out", "-time", "-precision", 17, "-ele", 5, name)
    rows = _session("halfspace", recorders)
    assert rows[:, -4:].max() > 1e-4                      # the footing lifts off
    recorded = [_read(f"{name}.out") for name in names]
    at = 1
    for name, width, got in zip(names, _widths("halfspace"), recorded):
        _close(got, np.c_[rows[:, :1], rows[:, at:at + width]], 1e-15)
        at += width
    _session("halfspace", recorders, HALFSPACE[2])
    at = 1
    for name, width in zip(names, _widths("halfspace")):
        _close(_read(f"{name}.out")[:, 1:], rows[:, at:at + width], 1e-6)
        at += width


def test_the_responses_move(tmp_path, monkeypatch):
    """The recorded histories are not trivial: the contacts open and close, the springs yield, the
    footing lifts off and slips."""
    rows = {case: _session(case) for case in ("rigidContact", "springFooting", "footing")}
    opening = rows["rigidContact"][:, 5]
    assert opening.max() > 1e-2 and opening.min() == pytest.approx(0.0, abs=1e-12)
    settlement = rows["springFooting"][:, -4:]
    assert settlement.max() > 0
    uplift, slip = rows["footing"][:, 8:12], rows["footing"][:, 12:16]
    assert uplift.max() > 1e-5 and np.abs(slip).max() > 0


def test_a_recorder_of_an_opensees_element_and_an_extension(tmp_path, monkeypatch):
    """'-ele 1 5' and '-eleRange 1 5' of the zeroLength 1 and the rigid contact 5: its six end forces,
    then the contact's three, at each step; the zeroLength's forces equal its spring's e k."""
    monkeypatch.chdir(tmp_path)

    def recorders(stage):
        if stage == "start":
            ops.recorder("Element", "-file", "mixed.out", "-precision", 17, "-ele", 1, 5, "force")
            ops.recorder("Element", "-file", "range.out", "-precision", 17, "-eleRange", 1, 5, "force")
            ops.recorder("EnvelopeElement", "-file", "env.out", "-precision", 17, "-ele", 5, 1, "force")
    _session("rigidContact", recorders, (50,))
    ops.wipe()
    _rigid()
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    ops.load(2, 0.0, -98.1, 0.0)
    ops.analysis("Static")
    ops.analyze(1)
    rows = [ops.eleForce(1) + ops.eleForce(5)]
    ops.loadConst("-time", 0.0)
    ops.timeSeries("Path", 2, "-time", *PULSE[0], "-values", *PULSE[1])
    ops.pattern("Plain", 2, 2)
    ops.load(2, 0.0, 700.0, 0.0)
    ops.analysis("Transient")
    ops.integrator("Newmark", 0.5, 0.25)
    for _ in range(50):
        ops.analyze(1, DT)
        rows.append(ops.eleForce(1) + ops.eleForce(5))
    ops.wipe()
    rows = np.array(rows)
    got = _read("mixed.out")
    _close(got, rows, 1e-14)
    _close(_read("range.out"), rows, 1e-14)
    env = _read("env.out")                                # no -time: min, max, absmax of 5's, then 1's
    swapped = np.c_[rows[:, 6:], rows[:, :6]]
    _close(env, np.array([swapped.min(axis=0), swapped.max(axis=0), np.abs(swapped).max(axis=0)]), 1e-14)
    assert np.abs(rows[:, 4]).max() > 1.0 and np.abs(rows[:, 7]).max() > 1.0    # both elements carry force


@pytest.mark.parametrize("script, response, words", [
    (_kelvin, "uplift", ["recorder('Element') of kelvinContact(5) 'uplift'",
                         "'force', 'basicForce', 'deformation', 'opening'"]),
    (_rigid, "basicForce", ["rigidContact(5) 'basicForce'", "'force', 'contactForce', 'opening'"]),
    (lambda: _column(lambda: ops.springFooting(5, 2, 4.0, 2.5e4)), "settlement",
     ["springFooting(5) 'settlement'", "'force', 'contactForce', 'uplift'"]),
    (lambda: _column(lambda: ops.footing(5, 2, 10.0, 10.0, "cones", 97.0, 0.3, 2.0)), "slip",
     ["footing(5) 'slip'", "not one of a footing's", "'force', 'contactForce', 'uplift'"]),
])
def test_an_unknown_response_of_an_extension_is_refused_by_name(script, response, words, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    ops.wipe()
    script()
    for kind in ("Element", "EnvelopeElement"):
        with pytest.raises(OpenSeesRefused) as info:
            ops.recorder(kind, "-file", "x.out", "-ele", 5, response)
        for word in words:
            assert word.replace("'Element'", repr(kind)) in str(info.value), (word, str(info.value))
    with pytest.raises(OpenSeesRefused, match=f"eleResponse\\(5, '{response}'\\).*not one of"):
        ops.eleResponse(5, response)
    ops.wipe()
