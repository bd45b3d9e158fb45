"""geomTransf('PDelta') columns and a Linear girder (mixed): heavy gravity by LoadControl, then a
ground motion. OpenSees updates the columns' axial forces with the response (overturning); here
they stay those of the gravity: the histories differ by that (measured, not to round-off)."""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.01, 600
ag = [0.0] + [3.0 * math.sin(2 * math.pi * k * dt / 0.9) * math.exp(-0.3 * k * dt) for k in range(1, 401)]
E, H, Lb = 2e8, 3.5, 6.0
Ac, Ic, Ab, Ib = 0.01, 6e-5, 0.01, 4e-4
out = {}
for kind in ('PDelta', 'Linear'):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, Lb, 0.0)
    ops.node(3, 0.0, H)
    ops.node(4, Lb, H)
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 1)
    ops.mass(3, 40.0, 40.0, 0.0)
    ops.mass(4, 40.0, 40.0, 0.0)
    ops.geomTransf(kind, 1)
    ops.geomTransf('Linear', 2)
    ops.element('elasticBeamColumn', 1, 1, 3, Ac, E, Ic, 1)
    ops.element('elasticBeamColumn', 2, 2, 4, Ac, E, Ic, 1)
    ops.element('elasticBeamColumn', 3, 3, 4, Ab, E, Ib, 2)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    for node in (3, 4):
        ops.load(node, 0.0, -1500.0, 0.0)          # 0.3 of the sway buckling load (about 2 x 5000)
    ops.test('NormDispIncr', 1e-12, 100)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', 0.1)
    ops.analysis('Static')
    assert ops.analyze(10) == 0
    ops.loadConst('-time', 0.0)
    static = ops.nodeDisp(3) + ops.nodeDisp(4) + ops.eleResponse(1, 'basicForce')
    ops.wipeAnalysis()
    ops.rayleigh(0.4, 0.0, 0.0, 0.0)
    ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
    ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
    ops.test('NormDispIncr', 1e-12, 100)
    ops.algorithm('Newton')
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')
    drift, n1, n2 = [], [], []
    for k in range(steps):
        assert ops.analyze(1, dt) == 0
        drift.append(ops.nodeDisp(3, 1))
        n1.append(ops.eleResponse(1, 'basicForce')[0])
        n2.append(ops.eleResponse(2, 'basicForce')[0])
    out[f'static_{kind}'], out[f'drift_{kind}'] = static, drift
    out[f'N1_{kind}'], out[f'N2_{kind}'] = n1, n2
print(json.dumps(out))
