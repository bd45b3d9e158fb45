"""``unilateral opensees model.tcl``: OpenSees Tcl scripts through Python's Tcl interpreter.

Each script of ``tests/opensees_scripts/tcl`` is the Tcl version of the OpenSeesPy script of the
same name; it is run by ``python -m unilateral opensees`` (our commands registered in
``tkinter.Tcl()``) and compared with openseespy's run of the Python script: every history to 1e-8
of its peak. The Tcl parsing (numbers, list arguments, pattern bodies, inline series, returned
values, ``exit``, refusals by name) is checked on small scripts without openseespy.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from test_opensees_module import SRC, errors, needs_opensees, run

tkinter = pytest.importorskip("tkinter")

TCL = Path(__file__).resolve().parent / "opensees_scripts" / "tcl"


def run_tcl_cli(script, cwd):
    """``python -m unilateral opensees script`` in ``cwd``: (returncode, stdout, stderr)."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(SRC), env.get("PYTHONPATH")) if p)
    env.setdefault("OPENBLAS_NUM_THREADS", "1")
    proc = subprocess.run([sys.executable, "-m", "unilateral", "opensees", str(script)], capture_output=True,
                          text=True, env=env, cwd=cwd, timeout=900)
    return proc.returncode, proc.stdout, proc.stderr


def tcl_histories(name, tmp_path):
    code, _, err = run_tcl_cli(TCL / f"{name}.tcl", tmp_path)
    assert code == 0, err[-3000:]
    out = {}
    for line in (tmp_path / "results.txt").read_text().splitlines():
        key, *values = line.split()
        out[key] = np.array([float(v) for v in values])
    return out


@needs_opensees
@pytest.mark.parametrize("name", ["portal_hinges", "frame_on_ent", "gravity_then_transient", "frame3d_asymmetric"])
def test_tcl_script_equals_openseespy(name, tmp_path):
    theirs = run(f"{name}.py", "opensees")
    ours = tcl_histories(name, tmp_path)
    assert set(ours) <= set(theirs) and len(ours) >= 5
    theirs = {key: theirs[key] for key in ours}
    bad = {k: e for k, e in errors(theirs, ours).items() if not e <= 1e-8}
    assert not bad, f"{name}.tcl: histories off by more than 1e-8 of their peak: {bad}"


def session():
    from unilateral.opensees.tcl import TclSession

    return TclSession()


def test_words_are_parsed_as_opensees_tcl_parses_them():
    s = session()
    s.eval("model basic -ndm 2 -ndf 3; node 1 0 0; node 2 1.5 0; fix 1 1 1 1")
    s.eval("set v {0.0 1.0 2.0}; timeSeries Path 7 -dt 0.5 -values $v -factor 2")
    series = s.session.domain.series[7]
    assert np.array_equal(series.values, [0.0, 1.0, 2.0]) and series.factor == 2.0 and series.dt == 0.5
    assert s.session.domain.nodes[2] == (1.5, 0.0) and s.session.domain.fixes[1] == (1, 1, 1)
    assert s.eval("nodeCoord 2 1") == "1.5" and s.tcl.splitlist(s.eval("getNodeTags")) == ("1", "2")


def test_pattern_body_and_inline_series():
    s = session()
    s.eval("model basic -ndm 2 -ndf 3; node 1 0 0; node 2 0 3")
    s.eval("pattern Plain 3 Linear { load 2 1.0 [expr {-2.0 * 3}] 0.5 }")
    s.eval('pattern UniformExcitation 4 1 -accel "Series -dt 0.01 -values {0 1 0} -factor 9.81"')
    d = s.session.domain
    (node, values), = d.patterns[3].loads
    assert node == 2 and np.array_equal(values, [1.0, -6.0, 0.5])
    assert d.series[d.patterns[3].series].kind == "Linear"
    inline = d.series[d.patterns[4].series]
    assert inline.kind == "Path" and inline.factor == 9.81 and np.array_equal(inline.values, [0, 1, 0])


def test_queries_return_values_to_tcl_and_exit_ends_the_script(tmp_path):
    script = tmp_path / "m.tcl"
    script.write_text("""model basic -ndm 2 -ndf 3
node 1 0 0; node 2 0 2; fix 1 1 1 1
uniaxialMaterial Elastic 1 100.0
element zeroLength 1 1 2 -mat 1 1 -dir 1 2
pattern Plain 1 Linear { load 2 3.0 -5.0 0.0 }
integrator LoadControl 1.0
analysis Static
set ok [analyze 1]
set f [open out.txt w]
puts $f "$ok [nodeDisp 2 1] [nodeDisp 2] [eleResponse 1 basicForce]"
close $f
exit
puts "not reached"
""")
    code, out, err = run_tcl_cli(script, tmp_path)
    assert code == 0, err
    assert "not reached" not in out
    values = [float(x) for x in (tmp_path / "out.txt").read_text().split()]
    assert values == [0.0, 0.03, 0.03, -0.05, 0.0, 3.0, -5.0]      # u = F / k, forces tension positive


@pytest.mark.parametrize("line, named", [
    ("uniaxialMaterial Steel02 1 1 2 3", "uniaxialMaterial('Steel02')"),
    ("eigen 3", "eigen()"),
    ("someCommand 1 2", "someCommand()"),
    ("element forceBeamColumn 1 1 2 1 1", "element('forceBeamColumn')"),
])
def test_refusals_name_the_command_and_the_line(tmp_path, line, named):
    script = tmp_path / "bad.tcl"
    script.write_text(f"model basic -ndm 2 -ndf 3\nnode 1 0 0\nnode 2 1 0\n{line}\n")
    code, _, err = run_tcl_cli(script, tmp_path)
    assert code == 1
    assert f"refuses {named}" in err and "Nearest alternative" in err and "line 4" in err


def test_a_tcl_error_of_the_script_is_reported_with_its_line(tmp_path):
    script = tmp_path / "bad.tcl"
    script.write_text("set a 1\nputs [expr {$a +}]\n")
    code, _, err = run_tcl_cli(script, tmp_path)
    assert code == 1 and "Tcl error" in err and "line 2" in err and "Traceback" not in err


def test_no_tcl_interpreter_says_how_to_get_it(monkeypatch):
    import builtins

    from unilateral.opensees import tcl

    real = builtins.__import__

    def no_tkinter(name, *args, **kwargs):
        if name == "tkinter":
            raise ImportError("No module named 'tkinter'")
        return real(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tkinter)
    with pytest.raises(RuntimeError, match="python3-tk"):
        tcl.tcl_interpreter()


def test_python_script_runs_with_the_cli(tmp_path):
    script = tmp_path / "m.py"
    script.write_text("import openseespy.opensees as ops\nops.model('basic', '-ndm', 2, '-ndf', 3)\n"
                      "ops.node(1, 0.0, 0.0)\nops.node(2, 0.0, 2.0)\nprint(ops.nodeCoord(2, 2))\n")
    code, out, err = run_tcl_cli(script, tmp_path)
    assert code == 0, err
    assert out.strip() == "2.0"


@needs_opensees
def test_tcl_recorders_write_the_files_of_openseespy(tmp_path):
    theirs = run("recorders.py", "opensees")
    code, _, err = run_tcl_cli(TCL / "recorders.tcl", tmp_path)
    assert code == 0, err[-3000:]
    for name in ("disp", "accel", "react", "hinges", "local"):
        rows = [[float(x) for x in line.split()] for line in (tmp_path / f"{name}.out").read_text().splitlines()]
        assert [len(rows), len(rows[0])] == list(theirs[name + ".shape"]), name
        ours = np.array(rows).ravel()
        tol = 1e-5 if name == "local" else 1e-8                      # 'local': 6 digits
        assert np.abs(ours - theirs[name]).max() <= tol * np.abs(theirs[name]).max(), name
