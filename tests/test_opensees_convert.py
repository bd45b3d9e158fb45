"""``unilateral convert``: an OpenSees script's model as a model file.

The defining property: the response of the converted file (``unilateral.run``, the model-file
pipeline of ``unilateral run``) equals the response of the script run through
:mod:`unilateral.opensees`, step by step, DOF by DOF and constraint by constraint (by name), to
about 1e-12 of the peak. The script's states are recorded at each committed step of its main
analysis by a :class:`~unilateral.opensees.convert.CaptureSession` of the conversion itself.
What the model file cannot express is refused, naming the command.
"""

import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

import unilateral as ul
from unilateral.cli import main
from unilateral.modelfile import load_model_file
from unilateral.opensees import OpenSeesRefused
from unilateral.opensees import convert
from unilateral.opensees.convert_frame import NotConvertible
from unilateral.opensees.toml_writer import dumps

HERE = Path(__file__).resolve().parent
SCRIPTS = HERE / "opensees_scripts"


class Recording(convert.CaptureSession):
    """A capture session that keeps the state of every committed step of the main analysis."""

    last = None

    def __init__(self):
        super().__init__()
        self.history = []
        commit = self.analysis.on_commit
        Recording.last = self

        def on_commit(t):
            commit(t)
            if self.stage is not None:
                a = self.analysis
                model = a.built.model
                self.history.append((t, dict(zip(model.dof_names, a.u)), dict(zip(model.constraint_names, a.v))))
        self.analysis.on_commit = on_commit


def converted(script, folder, monkeypatch):
    """Convert ``script`` into ``folder``: the model file's path and the script's recorded history."""
    monkeypatch.setattr(convert, "CaptureSession", Recording)
    monkeypatch.chdir(folder)                                   # the files a script writes go there
    out = folder / (Path(script).stem + ".toml")
    result = convert.convert_script(script, out)
    assert result["path"] == out and out.exists()
    tomllib.loads(out.read_text())                              # the writer's TOML reads back
    return out, Recording.last


def relative_errors(history, names, u, constraint_names, v):
    """``(max |u - u_script| / peak, max |v - v_script| / peak)`` over the recorded steps (k = 1..N)."""
    at = {name: k for k, name in enumerate(names)}
    vat = {name: k for k, name in enumerate(constraint_names)}
    theirs_u = np.array([[state[name] for name in state] for _, state, _ in history])
    ours_u = np.array([[u[k + 1, at[name]] for name in state] for k, (_, state, _) in enumerate(history)])
    e_u = float(np.abs(ours_u - theirs_u).max() / np.abs(theirs_u).max())
    e_v = 0.0
    if vat:
        theirs_v = np.array([[c[name] for name in c] for _, _, c in history])
        ours_v = np.array([[v[k + 1, vat[name]] for name in c] for k, (_, _, c) in enumerate(history)])
        peak = np.abs(theirs_v).max()
        e_v = float(np.abs(ours_v - theirs_v).max() / peak) if peak else float(np.abs(ours_v).max())
    return e_u, e_v


TRANSIENT = {   # script -> the largest relative error allowed (u and v), measured figures in the comments
    "portal_path_dt.py": 1e-12,            # elastic portal, Path -dt ground motion, Rayleigh alphaM, betaK
    "portal_path_time.py": 1e-12,          # Path -time, betaKinit, betaKcomm
    "portal_hinges.py": 1e-12,             # zeroLength ElasticPP base hinges (equalDOF to the support)
    "frame_on_ent.py": 1e-10,              # ENT springs: gravity by LoadControl, uplift and landing
    "pounding_gap.py": 1e-9,               # ElasticPPGap gaps (pounding amplifies the round-off of the start)
    "materials_cyclic.py": 1e-12,          # Steel01, Hardening, ElasticBilin, Parallel
    "beam_uniform.py": 1e-12,              # eleLoad -beamUniform Wy, Wx
    "convert/beam_rayleigh_springs.py": 1e-12,   # eleLoad, masses, betaK with -doRayleigh, truss -rho, Linear
    "convert/frame3d_diaphragm.py": 1e-12,       # 3-D: vecxz, rigidDiaphragm, zeroLength, two components
    "convert/frame_hinges_equaldof.py": 1e-10,   # ElasticPP beam-end hinges tied to free joints by equalDOF 1 2
    "tcl/portal_hinges.tcl": 1e-12,        # the Tcl front
    "tcl/frame_on_ent.tcl": 1e-10,
}


@pytest.mark.parametrize("script", sorted(TRANSIENT))
def test_converted_transient_equals_the_script(script, tmp_path, monkeypatch):
    out, session = converted(SCRIPTS / script, tmp_path, monkeypatch)
    spec = load_model_file(out)
    sol = ul.run(spec, figures=()).solutions["unilateral"]
    assert sol.success, sol.message
    assert len(session.history) == sol.u.shape[0] - 1
    times = np.array([t for t, *_ in session.history]) - session.stage.t0
    assert np.allclose(times, sol.t[1:], rtol=0, atol=1e-9 * sol.t[-1])
    e_u, e_v = relative_errors(session.history, spec.model.dof_names, sol.u, spec.model.constraint_names, sol.v)
    print(f"{script}: u {e_u:.1e}, v {e_v:.1e} of the peak")
    assert e_u <= TRANSIENT[script] and e_v <= TRANSIENT[script], (e_u, e_v)


def test_converted_pushover_equals_the_script(tmp_path, monkeypatch):
    from unilateral.pushover import pushover
    from unilateral.pushover.files import _gravity, _pattern, run_file

    out, session = converted(SCRIPTS / "convert" / "pushover_portal.py", tmp_path, monkeypatch)
    spec = load_model_file(out)
    table = spec.document.pushover
    result = pushover(spec.structure, _pattern(spec.structure, table), node=table.node, dof=table.dof,
                      target=table.target, gravity=_gravity(spec, table), control=table.control)
    assert result.success, result.message
    names = spec.model.dof_names
    control = names.index("3.ux")
    theirs = np.array([[state[name] for name in names] for _, state, _ in session.history])
    lam = np.array([t for t, *_ in session.history])
    # the script's steps on the path: where the control DOF is the script's
    at = result.at(np.interp(theirs[:, control], result.u[:, control], result.parameter))
    e_u = float(np.abs(at["u"] - theirs).max() / np.abs(theirs).max())
    e_lam = float(np.abs(at["load_factor"] - lam).max() / np.abs(lam).max())
    print(f"pushover: u {e_u:.1e}, load factor {e_lam:.1e} of the peak")
    assert e_u <= 1e-12 and e_lam <= 1e-12
    summary = run_file(spec, tmp_path / "run", figures=())
    assert summary["success_all"] and not summary["not_applied"]


def test_pushover_pattern_pushing_the_other_way(tmp_path):
    """A pattern towards -x with increments towards +x: OpenSees's load factor is negative, the model
    file's pattern is turned to push towards its target (the same path)."""
    from unilateral.pushover.files import run_file

    text = (SCRIPTS / "convert" / "pushover_portal.py").read_text()
    script = tmp_path / "push.py"
    script.write_text(text.replace("ops.load(3, 1.0, 0.0, 0.0)", "ops.load(3, -1.0, 0.0, 0.0)")
                      .replace("ops.load(4, 1.0, 0.0, 0.0)", "ops.load(4, -1.0, 0.0, 0.0)"))
    out = tmp_path / "push.toml"
    convert.convert_script(script, out)
    spec = load_model_file(out)
    assert [f.ux for f in spec.document.pushover.pattern] == [1.0, 1.0]
    assert run_file(spec, tmp_path / "run", figures=())["success_all"]


def test_cli_convert_then_run(tmp_path):
    """``unilateral convert`` then ``unilateral run`` on the file: results.nc holds the script's response."""
    import xarray as xr

    runner = CliRunner()
    out = tmp_path / "portal.toml"
    result = runner.invoke(main, ["convert", str(SCRIPTS / "portal_hinges.py"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    assert "portal.toml" in result.output and out.exists() and (tmp_path / "portal.ground1.txt").exists()
    again = runner.invoke(main, ["convert", str(SCRIPTS / "portal_hinges.py"), "-o", str(out)])
    assert again.exit_code != 0 and "exists" in again.output and "--force" in again.output
    forced = runner.invoke(main, ["convert", str(SCRIPTS / "portal_hinges.py"), "-o", str(out), "--force"])
    assert forced.exit_code == 0, forced.output
    ran = runner.invoke(main, ["run", str(out), "--out", str(tmp_path / "res"), "--figures", "none"])
    assert ran.exit_code == 0, ran.output
    with xr.open_dataset(tmp_path / "res" / "results.nc") as ds:
        assert "unilateral" in [str(c) for c in ds["case"].values]


@pytest.mark.parametrize("args, message", [
    (["missing.py", "-o", "m.toml"], "does not exist"),
    (["{script}", "-o", "m.json"], ".toml"),
    (["{notes}", "-o", "m.toml"], ".py"),
])
def test_cli_errors(tmp_path, args, message):
    notes = tmp_path / "notes.txt"
    notes.write_text("x")
    args = [a.format(script=SCRIPTS / "portal_hinges.py", notes=notes) for a in args]
    result = CliRunner().invoke(main, ["convert", *args])
    assert result.exit_code != 0 and message in result.output, result.output


HEAD = """import openseespy.opensees as ops
ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0); ops.node(2, 0.0, 3.0); ops.node(3, 4.0, 3.0)
ops.fix(1, 1, 1, 1)
ops.mass(2, 10.0, 10.0, 0.0); ops.mass(3, 10.0, 10.0, 0.0)
"""
FRAME = """ops.geomTransf('{transf}', 1)
ops.element('elasticBeamColumn', 1, 1, 2, 0.1, 3e7, 1e-3, 1)
ops.element('elasticBeamColumn', 2, 2, 3, 0.1, 3e7, 1e-3, 1)
"""
MOTION = """ops.timeSeries('Path', 1, '-dt', 0.01, '-values', 0.0, 1.0, 0.5, 0.0)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.integrator('Newmark', {newmark})
ops.analysis('Transient')
ops.analyze(20, 0.01)
"""
REFUSED = {
    "equalDOF to a rigid link's slave": (HEAD + FRAME.format(transf="Linear") + "ops.node(4, 4.0, 3.0)\n"
                                         "ops.rigidLink('beam', 2, 4)\nops.equalDOF(4, 3, 1)\n"
                                         + MOTION.format(newmark="0.5, 0.25"), "equalDOF(4, 3, 1)"),
    "PDelta": (HEAD + FRAME.format(transf="PDelta") + MOTION.format(newmark="0.5, 0.25"), "geomTransf('PDelta', 1)"),
    "Newmark": (HEAD + FRAME.format(transf="Linear") + MOTION.format(newmark="0.6, 0.3025"),
                "integrator('Newmark', 0.6, 0.3025)"),
    "unequal masses": (HEAD + FRAME.format(transf="Linear") + "ops.mass(3, 10.0, 4.0, 0.0)\n"
                       + MOTION.format(newmark="0.5, 0.25"), "mass(3, 10, 4, 0)"),
    "betaK before an element": (HEAD + "ops.geomTransf('Linear', 1)\n"
                                "ops.element('elasticBeamColumn', 1, 1, 2, 0.1, 3e7, 1e-3, 1)\n"
                                "ops.rayleigh(0.0, 0.001, 0.0, 0.0)\n"
                                "ops.element('elasticBeamColumn', 2, 2, 3, 0.1, 3e7, 1e-3, 1)\n"
                                + MOTION.format(newmark="0.5, 0.25"), "rayleigh(0, 0.001, 0, 0)"),
    "no transient analysis": (HEAD + FRAME.format(transf="Linear") + "ops.analysis('Static')\nops.analyze(1)\n",
                              "runs no transient analysis"),
    "a second model": (HEAD + FRAME.format(transf="Linear") + MOTION.format(newmark="0.5, 0.25") + "ops.wipe()\n"
                       + HEAD + FRAME.format(transf="Linear") + MOTION.format(newmark="0.5, 0.25"), "wipe()"),
    "dt changed": (HEAD + FRAME.format(transf="Linear") + MOTION.format(newmark="0.5, 0.25")
                   + "ops.analyze(5, 0.02)\n", "the time step changed"),
    "loads changed": (HEAD + FRAME.format(transf="Linear") + MOTION.format(newmark="0.5, 0.25")
                      + "ops.timeSeries('Constant', 5)\nops.pattern('Plain', 5, 5)\nops.load(3, 1.0, 0.0, 0.0)\n"
                      + "ops.analyze(5, 0.01)\n", "the model or its loads changed"),
}


@pytest.mark.parametrize("tie", ["2, 3, 1", "3, 2, 1"])
def test_equal_dof_between_free_nodes_is_written(tie, tmp_path, monkeypatch):
    """equalDOF between free DOFs (formerly refused) becomes [[equal_dofs]], the node defined first the
    master (whose DOF names the pair, as in the module); the slave's DOF reads the master's."""
    script = tmp_path / "tied.py"
    script.write_text(HEAD + FRAME.format(transf="Linear") + f"ops.equalDOF({tie})\n" + MOTION.format(newmark="0.5, 0.25"))
    out, session = converted(script, tmp_path, monkeypatch)
    assert tomllib.loads(out.read_text())["equal_dofs"] == [{"master": 2, "slave": 3, "dofs": ["ux"]}]
    spec = load_model_file(out)
    assert "3.ux" not in spec.model.dof_names and "2.ux" in spec.model.dof_names
    sol = ul.run(spec, figures=()).solutions["unilateral"]
    nodal = spec.structure.dofs.nodal(sol.u)
    nodes = spec.structure.dofs.nodes
    assert np.abs(nodal[:, nodes.index(2), 0]).max() > 0
    assert np.array_equal(nodal[:, nodes.index(3), 0], nodal[:, nodes.index(2), 0])
    e_u, _ = relative_errors(session.history, spec.model.dof_names, sol.u, spec.model.constraint_names, sol.v)
    assert e_u <= 1e-10, e_u


@pytest.mark.parametrize("case", sorted(REFUSED))
def test_refusals_name_the_command(case, tmp_path):
    text, command = REFUSED[case]
    script = tmp_path / "model.py"
    script.write_text(text)
    out = tmp_path / "model.toml"
    with pytest.raises(NotConvertible) as info:
        convert.convert_script(script, out)
    message = str(info.value)
    assert message.startswith("unilateral convert cannot write") and command in message, message
    assert "Nearest:" in message
    assert not out.exists() and not list(tmp_path.glob("model.*.txt"))         # nothing written


def test_refused_eps0():
    """An ElasticPP's eps0 (an imposed strain) has no key in the model file's yield link."""
    from unilateral.opensees.commands import Session
    from unilateral.opensees.convert_frame import structure_tables

    session = Session()
    ops = session.commands()
    ops["model"]("basic", "-ndm", 2, "-ndf", 3)
    ops["node"](1, 0.0, 0.0)
    ops["node"](2, 0.0, 0.0)
    ops["fix"](1, 1, 1, 1)
    ops["fix"](2, 1, 1, 0)
    ops["uniaxialMaterial"]("ElasticPP", 1, 1e5, 0.01, -0.01, 0.001)
    ops["element"]("zeroLength", 9, 1, 2, "-mat", 1, "-dir", 3)
    with pytest.raises(NotConvertible, match=r"element 9 \(an ElasticPP with eps0\).*no imposed strain"):
        structure_tables(session.domain)


def test_a_command_outside_the_subset_is_the_module_refusal(tmp_path):
    script = tmp_path / "model.py"
    script.write_text(HEAD + "ops.uniaxialMaterial('Steel02', 1, 300.0, 2e5, 0.01)\n")
    with pytest.raises(OpenSeesRefused, match="Steel02"):
        convert.convert_script(script, tmp_path / "model.toml")


def test_toml_writer_reads_back():
    document = {"units": {"length": "m"}, "nodes": [{"id": 1, "x": 0.1, "y": 1e-300}, {"id": "a b", "x": -0.0,
                                                                                      "y": 1e16}],
                "flag": True, "list": [1.5, 2.0], "table": {"name": 'a "quoted" \\ name', "inline": {"k": 3}}}
    assert tomllib.loads(dumps(document, "a header\nof two lines")) == {
        **document, "list": [1.5, 2.0], "nodes": document["nodes"]}
    with pytest.raises(ValueError, match="finite"):
        dumps({"x": float("nan")})
