"""An inclined cantilever of two elastic beams with a tip mass (unequal mx, my and a rotational
mass) under a ground acceleration, mass-proportional Rayleigh damping, and a Newmark rule other
than 1/2, 1/4 (gamma = 0.6, beta = (gamma + 1/2)^2 / 4)."""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 300
ag = [0.0] + [2.0 * math.sin(2 * math.pi * k * dt / 0.3) for k in range(1, 201)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0)
ops.node(2, 0.5, 1.5)
ops.node(3, 1.0, 3.0)
ops.fix(1, 1, 1, 1)
ops.mass(3, 5.0, 8.0, 0.2)
ops.mass(2, 1.0, 1.0, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 2, 0.09, 30e6, 6.75e-4, 1)
ops.element('elasticBeamColumn', 2, 2, 3, 0.09, 30e6, 6.75e-4, 1)
ops.rayleigh(0.5, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.6, 0.3025)
ops.analysis('Transient')

out = {k: [] for k in ('u3', 'v2', 'a3', 'force1', 'local2', 'basic2')}
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['u3'].extend(ops.nodeDisp(3))
    out['v2'].extend(ops.nodeVel(2))
    out['a3'].extend(ops.nodeAccel(3))
    out['force1'].extend(ops.eleForce(1))
    out['local2'].extend(ops.eleResponse(2, 'localForce'))
    out['basic2'].extend(ops.eleResponse(2, 'basicForce'))
print(json.dumps(out))
