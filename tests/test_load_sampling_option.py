"""``[analysis] load_sampling``: the steps sample the loads as hat averages ("average", the default) or at
the step times ("point", as OpenSees reads a Path series). With "point" a model file reproduces an
OpenSees run of the same structure and record to round-off; every derived quantity takes the same samples."""

import json
import subprocess
import sys

import numpy as np
import pytest
from test_opensees_module import ENV, needs_opensees

import unilateral as ul
from unilateral.modelfile import ModelFileError, load_model_file

DT, STEPS, H, E, A, I, MASS = 0.01, 300, 3.0, 3.0e7, 0.16, 2.1333e-3, 20.0


def record(n=STEPS + 2):
    t = DT * np.arange(n)
    return 2.0 * np.sin(2 * np.pi * 1.7 * t) * np.exp(-0.3 * t) + 0.8 * np.sign(np.sin(2 * np.pi * 0.9 * t))


def model_file(tmp_path, sampling, method="direct"):
    np.savetxt(tmp_path / "rec.txt", record())
    (tmp_path / "model.toml").write_text(f"""
units = {{ length = "m", force = "kN", time = "s" }}
nodes = [{{ id = 1, x = 0.0, y = 0.0 }}, {{ id = 2, x = 0.0, y = {H} }}]
supports = [{{ node = 1, ux = true, uy = true, rz = true }}]
elements = [{{ type = "beam", name = "C", node_i = 1, node_j = 2, E = {E}, A = {A}, I = {I} }}]
unilateral = [{{ type = "hinge", name = "C.j", beam = "C", end = "j", My = 1e9 }}]
masses = [{{ node = 2, m = {MASS} }}]
[[loads.ground_motion]]
file = "rec.txt"
units = "m/s2"
dt = {DT}
direction = "ux"
[analysis]
dt = {DT}
t_end = {DT * STEPS}
method = "{method}"
rule = "trapezoidal"
initial = "rest"
load_sampling = "{sampling}"
""")
    return tmp_path / "model.toml"


def top_ux(spec):
    sol = ul.solve(spec.model, spec.load, dt=spec.analysis["dt"], t_end=spec.analysis["t_end"],
                   method=spec.analysis["method"], rule=spec.analysis["rule"], initial=spec.analysis["initial"])
    assert sol.success, sol.message
    return sol, sol.u[:, spec.structure.dofs.index(2, "ux")]


OPENSEES = """
import json, sys
import numpy as np
import openseespy.opensees as ops
H, E, A, I, MASS, DT, STEPS = {H}, {E}, {A}, {I}, {MASS}, {DT}, {STEPS}
values = np.loadtxt(sys.argv[1])
ops.model("basic", "-ndm", 2, "-ndf", 3)
ops.node(1, 0.0, 0.0)
ops.node(2, 0.0, H)
ops.fix(1, 1, 1, 1)
ops.mass(2, MASS, 0.0, 0.0)
ops.geomTransf("Linear", 1)
ops.element("elasticBeamColumn", 1, 1, 2, A, E, I, 1)
ops.timeSeries("Path", 1, "-dt", DT, "-values", *values)
ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
ops.constraints("Plain")
ops.numberer("Plain")
ops.system("FullGeneral")
ops.algorithm("Linear")
ops.integrator("Newmark", 0.5, 0.25)
ops.analysis("Transient")
out = [0.0]
for _ in range(STEPS):
    assert ops.analyze(1, DT) == 0
    out.append(ops.nodeDisp(2, 1))
print(json.dumps(out))
"""


def opensees_top_ux(folder):
    """The top's ux of the same column and record in OpenSees (Path series, Newmark 1/2 1/4), in a subprocess."""
    script = OPENSEES.format(H=H, E=E, A=A, I=I, MASS=MASS, DT=DT, STEPS=STEPS)
    proc = subprocess.run([sys.executable, "-c", script, str(folder / "rec.txt")], capture_output=True, text=True,
                          env=ENV, timeout=600)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return np.array(json.loads(proc.stdout.strip().splitlines()[-1]))


@needs_opensees
def test_point_sampling_reproduces_opensees_path_series(tmp_path):
    _, point = top_ux(load_model_file(model_file(tmp_path, "point")))
    theirs = opensees_top_ux(tmp_path)
    _, average = top_ux(load_model_file(model_file(tmp_path, "average")))
    peak = np.abs(theirs).max()          # (the record runs one step past t_end: at its last point, a jump
    # to zero, "point" takes the mean of both sides where OpenSees takes the last value)
    assert np.abs(point - theirs).max() <= 1e-9 * peak
    assert np.abs(average - theirs).max() >= 1e-3 * peak        # the averages are another load


def test_derived_quantities_take_the_run_samples(tmp_path):
    """results.nc's ground acceleration is the record at the step times, and the base shear equals the mass
    times the absolute acceleration at every step (no damping): the hand check closes with "point" too."""
    spec = load_model_file(model_file(tmp_path, "point"))
    assert spec.load.sampling == "point"
    ds = ul.run(model_file(tmp_path, "point"), figures=()).dataset.sel(case="unilateral")
    a_g = ds.ground_acceleration.values[:, 0]
    assert np.abs(a_g - record()[:-1]).max() <= 1e-14 * np.abs(record()).max()
    base_shear = ds.base_shear.values
    inertia = MASS * ds.absolute_acceleration.sel(dof="2.ux").values
    assert np.abs(base_shear - inertia).max() <= 1e-9 * np.abs(base_shear).max()


def test_point_sampling_refused_by_the_event_method(tmp_path):
    with pytest.raises(ModelFileError, match="load_sampling"):
        load_model_file(model_file(tmp_path, "point", method="event"))


def test_unknown_sampling_is_named(tmp_path):
    with pytest.raises(ModelFileError, match="load_sampling"):
        load_model_file(model_file(tmp_path, "midpoint"))
    with pytest.raises(ValueError, match="sampling='x' is not valid; valid: 'hat', 'box', 'point'"):
        ul.loads.LoadHistory([0.0], [], sampling="x")
