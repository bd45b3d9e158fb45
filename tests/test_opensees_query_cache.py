"""The queries' cache and the recorders' blocks change no number: the springs' responses computed
once per state for all elements (:func:`unilateral.opensees.queries.spring_state`) equal, bit for
bit, those of one material at a time (:func:`~unilateral.opensees.queries.material_forces`), a
query after a step is that of a fresh computation, and a recorder file written from the blocks of
whole ``analyze`` calls is, byte for byte, the file written one line per step from the queries."""

from pathlib import Path

import numpy as np
import pytest

import unilateral.opensees as ops
from unilateral.opensees import queries, recorders
from unilateral.opensees.elements import Truss
from unilateral.opensees.recorders import Recorder, _write_lines

SCRIPTS = Path(__file__).resolve().parent / "opensees_scripts"
IMPORT = "import openseespy.opensees as ops"


def bits(values):
    """The exact bits of floats (``-0.0`` differs from ``0.0``)."""
    return [float(x).hex() for x in np.atleast_1d(values)]


def reference(analysis, tag, name):
    """``eleResponse`` / ``eleForce`` of the spring ``tag`` from :func:`queries.material_forces`."""
    b, e = analysis.built, analysis.domain.elements[tag]
    pairs = queries.material_forces(analysis, tag)
    kind = queries.spring_kind(e, name)
    if kind == "e":
        return [de for de, _ in pairs]
    if kind == "f":
        return [f for _, f in pairs]
    out = np.zeros(2 * b.ndf)
    for (_, direction, *_), (_, f) in zip(b.springs[tag], pairs):
        out[:b.ndf] -= f * direction
        out[b.ndf:] += f * direction
    if isinstance(e, Truss) and e.rho:
        out += queries._truss_inertia_load(analysis, b, e)
    return list(out)


def run(script, monkeypatch, folder, checked=None):
    """Run a script of ``tests/opensees_scripts`` on the module in ``folder``; with ``checked``, every
    spring query is compared with :func:`reference` (the count of comparisons is added to it)."""
    monkeypatch.chdir(folder)
    if checked is not None:
        session = ops._session
        response, force = session.eleResponse, session.eleForce

        def eleResponse(tag, *args):
            ours = response(tag, *args)
            if int(tag) in session.analysis.built.springs:
                assert bits(ours) == bits(reference(session.analysis, int(tag), args[0])), (tag, args)
                checked.append(tag)
            return ours

        def eleForce(tag, dof=-1):
            ours = force(tag, dof)
            if int(tag) in session.analysis.built.springs:
                theirs = reference(session.analysis, int(tag), "force")
                assert bits(ours) == bits(theirs if dof == -1 else theirs[dof - 1]), tag
                checked.append(tag)
            return ours

        monkeypatch.setattr(ops, "eleResponse", eleResponse)
        monkeypatch.setattr(ops, "eleForce", eleForce)
    text = (SCRIPTS / script).read_text().replace(IMPORT, "import unilateral.opensees as ops")
    exec(compile(text, script, "exec"), {"__name__": "__main__"})


@pytest.mark.parametrize("script", ["materials_cyclic.py", "braced_truss.py", "pounding_gap.py"])
def test_spring_queries_equal_one_material_at_a_time(script, monkeypatch, tmp_path, capsys):
    checked = []
    run(script, monkeypatch, tmp_path, checked)
    assert len(checked) > 1000                  # every step's queries of composites, trusses, gaps
    ops.wipe()


def portal():
    """A portal on two yielding base hinges (ElasticPP zeroLength), an Elastic spring with a
    viscosity and Rayleigh damping (-doRayleigh) between its top nodes, in a ground motion."""
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0), (3, 0.0, 3.5), (4, 6.0, 3.5),
                      (5, 6.0, 3.5)):
        ops.node(tag, x, y)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 1)
    ops.equalDOF(1, 11, 1, 2)
    ops.equalDOF(2, 12, 1, 2)
    ops.equalDOF(4, 5, 2, 3)
    ops.mass(3, 30.0, 30.0, 0.0)
    ops.mass(4, 30.0, 30.0, 0.0)
    ops.mass(5, 1.0, 0.0, 0.0)
    ops.uniaxialMaterial('ElasticPP', 1, 4e5, 130.0 / 4e5)
    ops.uniaxialMaterial('Elastic', 2, 1e4, 50.0)
    ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
    ops.element('zeroLength', 102, 2, 12, '-mat', 1, '-dir', 3)
    ops.element('zeroLength', 103, 4, 5, '-mat', 2, '-dir', 1, '-doRayleigh', 1)
    ops.geomTransf('Linear', 1)
    ops.element('elasticBeamColumn', 1, 11, 3, 0.16, 30e6, 2.1e-3, 1)
    ops.element('elasticBeamColumn', 2, 12, 4, 0.16, 30e6, 2.1e-3, 1)
    ops.element('elasticBeamColumn', 3, 3, 5, 0.15, 30e6, 2.8e-3, 1)
    ops.rayleigh(0.3, 0.001, 0.0, 0.0)
    ag = [0.0] + [5.0 * np.sin(2 * np.pi * k * 0.005 / 0.5) for k in range(1, 301)]
    ops.timeSeries('Path', 2, '-dt', 0.005, '-values', *ag)
    ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')


def test_query_after_a_step_equals_a_fresh_computation():
    portal()
    analysis = ops._session.analysis
    for _ in range(40):
        assert ops.analyze(1, 0.005) == 0
        cached = [ops.eleResponse(t, name) for t in (101, 102, 103) for name in ('basicForce', 'deformation', 'force')]
        cached.append(ops.eleForce(102, 3))
        again = [ops.eleResponse(t, name) for t in (101, 102, 103) for name in ('basicForce', 'deformation', 'force')]
        again.append(ops.eleForce(102, 3))                       # the fast path: the lookup in the cache
        analysis._query_cache = None                             # forget the state: computed afresh
        fresh = [ops.eleResponse(t, name) for t in (101, 102, 103) for name in ('basicForce', 'deformation', 'force')]
        fresh.append(ops.eleForce(102, 3))
        assert bits(np.hstack(cached)) == bits(np.hstack(again)) == bits(np.hstack(fresh))
        theirs = [reference(analysis, t, name) for t in (101, 102, 103) for name in ('basicForce', 'deformation', 'force')]
        assert bits(np.hstack(cached[:-1])) == bits(np.hstack(theirs))
    assert abs(ops.eleResponse(101, 'basicForce')[0]) == pytest.approx(130.0)      # the hinge yields
    with pytest.raises(ops.OpenSeesRefused, match="DOF 7"):
        ops.eleForce(101, 7)                                     # (past the fast path: refused as before)
    ops.wipe()


def recorded(tmp_path, monkeypatch, pieces, blocks=True):
    """The text of the recorder files of :func:`portal` analysed in ``pieces`` (steps per analyze),
    from blocks or (``blocks=False``) one line per step from the queries."""
    if not blocks:
        monkeypatch.setattr(recorders, "_block_plan", lambda rec, b, domain: None)
    monkeypatch.chdir(tmp_path)
    portal()
    ops.recorder('Node', '-file', 'disp.out', '-time', '-precision', 16, '-node', 3, 5, '-dof', 1, 2, 3, 'disp')
    ops.recorder('Node', '-file', 'va.out', '-dT', 0.0125, '-node', 4, '-dof', 1, 'vel', '-precision', 17)
    ops.recorder('Node', '-file', 'acc.out', '-precision', 12, '-node', 4, '-dof', 1, 2, 'accel')
    ops.recorder('Element', '-file', 'hinges.out', '-time', '-precision', 16, '-ele', 101, 102, 103, 'basicForce')
    ops.recorder('Element', '-file', 'def.out', '-ele', 103, 101, 'deformation')
    ops.recorder('Element', '-file', 'force.out', '-precision', 16, '-ele', 102, 103, 'force')
    ops.recorder('Element', '-file', 'beams.out', '-precision', 16, '-ele', 1, 3, 'localForce')
    ops.recorder('EnvelopeElement', '-file', 'env.out', '-time', '-precision', 16, '-ele', 101, 102, 'basicForce')
    ops.recorder('EnvelopeNode', '-file', 'envnode.out', '-precision', 16, '-node', 3, 4, '-dof', 1, 3, 'disp')
    for n in pieces:
        assert ops.analyze(n, 0.005) == 0
    ops.record()
    ops.wipe()
    return {p.name: p.read_text() for p in sorted(tmp_path.glob("*.out"))}


def test_recorder_files_from_blocks_equal_one_line_per_step(tmp_path, monkeypatch):
    (tmp_path / "a").mkdir(), (tmp_path / "b").mkdir(), (tmp_path / "c").mkdir()
    blocks = recorded(tmp_path / "a", monkeypatch, [250])
    pieces = recorded(tmp_path / "b", monkeypatch, [1, 7, 100, 1, 1, 140])
    with monkeypatch.context() as m:
        lines = recorded(tmp_path / "c", m, [250], blocks=False)
    assert len(blocks) == 9 and blocks.keys() == lines.keys()
    for name in blocks:
        assert blocks[name] == lines[name] == pieces[name], name
    assert len(blocks["disp.out"].splitlines()) == 251 and len(blocks["va.out"].splitlines()) == 84   # every 3rd step (dT 2.5 dt)
    assert len(blocks["env.out"].splitlines()) == 3


def test_vectorised_writer_formats_as_python():
    rng = np.random.default_rng(1)
    values = np.r_[rng.standard_normal(499) * 10.0 ** rng.integers(-300, 300, 499), 0.0, -0.0, np.inf, -np.inf,
                   np.nan, 5e-324, 0.1, 123456789.0].reshape(-1, 3)

    class Stream(list):
        write = list.append

    for p in (1, 6, 12, 16, 17):
        stream = Stream()
        _write_lines(stream, values, p, rows=50)
        assert "".join(stream) == "".join(" ".join(f"{float(x):.{p}g}" for x in row) + "\n" for row in values)


@pytest.mark.parametrize("nan", [False, True])
def test_envelope_of_a_block_equals_row_by_row(nan):
    rng = np.random.default_rng(2)
    t = np.arange(60) * 0.01
    values = np.round(rng.standard_normal((60, 4)), 1)          # ties: the first time an extreme is reached
    if nan:
        values[5, 2] = np.nan
    one, block = Recorder("EnvelopeNode", "x", [1], ("disp",)), Recorder("EnvelopeNode", "x", [1], ("disp",))
    for k in range(60):
        one._envelope(float(t[k]), values[k].tolist())
    block._envelope_block(t[:25], values[:25])
    block._envelope_block(t[25:], values[25:])
    assert repr(one.envelope) == repr(block.envelope)
