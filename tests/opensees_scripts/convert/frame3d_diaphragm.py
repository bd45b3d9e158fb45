"""A one-storey 3-D frame for `unilateral convert`: four columns (two vecxz), a rigid floor
diaphragm, a yielding zeroLength (ElasticPP about x) and an Elastic zeroLength spring at column
feet, Rayleigh damping, two horizontal ground components (Path -dt and Path -time)."""
import math

import openseespy.opensees as ops

dt, steps = 0.01, 300
ax = [0.0] + [2.5 * math.sin(2 * math.pi * k * dt / 0.45) * math.exp(-0.8 * k * dt) for k in range(1, 201)]
ay = [0.0] + [1.5 * math.sin(2 * math.pi * k * dt / 0.3 + 0.4) * math.exp(-k * dt) for k in range(1, 151)]

ops.wipe()
ops.model('basic', '-ndm', 3, '-ndf', 6)
plan = [(0.0, 0.0), (5.0, 0.0), (5.0, 4.0), (0.0, 4.0)]
for k, (x, y) in enumerate(plan, 1):
    ops.node(k, x, y, 0.0)
    ops.node(10 + k, x, y, 0.0)
    ops.node(20 + k, x, y, 3.2)
    ops.fix(k, 1, 1, 1, 1, 1, 1)
ops.node(30, 2.5, 2.0, 3.2)
ops.fix(30, 0, 0, 1, 1, 1, 0)
for k in range(1, 5):
    ops.fix(10 + k, 1, 1, 1, 0, 1, 1)
ops.rigidDiaphragm(3, 30, 21, 22, 23, 24)
ops.mass(30, 40.0, 40.0, 0.0, 0.0, 0.0, 120.0)
ops.mass(23, 5.0, 5.0, 5.0, 0.0, 0.0, 0.0)
ops.geomTransf('Linear', 1, 1.0, 0.0, 0.0)
ops.geomTransf('Linear', 2, 0.0, 1.0, 0.0)
ops.geomTransf('Linear', 3, 0.0, 0.0, 1.0)
for k in range(1, 5):
    ops.element('elasticBeamColumn', k, 10 + k, 20 + k, 0.16, 30e6, 12.5e6, 3.6e-3, 2.133e-3, 2.133e-3, 1 if k % 2 else 2)
ops.element('elasticBeamColumn', 5, 21, 22, 0.12, 30e6, 12.5e6, 2.6e-3, 1.6e-3, 1.6e-3, 3)
ops.element('elasticBeamColumn', 6, 22, 23, 0.12, 30e6, 12.5e6, 2.6e-3, 1.6e-3, 1.6e-3, 3)
ops.element('elasticBeamColumn', 7, 23, 24, 0.12, 30e6, 12.5e6, 2.6e-3, 1.6e-3, 1.6e-3, 3)
ops.element('elasticBeamColumn', 8, 24, 21, 0.12, 30e6, 12.5e6, 2.6e-3, 1.6e-3, 1.6e-3, 3)
ops.uniaxialMaterial('ElasticPP', 1, 4.0e5, 2.0e-4)
ops.uniaxialMaterial('Elastic', 2, 6.0e5)
for k in range(1, 5):
    ops.element('zeroLength', 100 + k, k, 10 + k, '-mat', 1 if k % 2 else 2, '-dir', 4)
ops.rayleigh(0.3, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ax)
ops.timeSeries('Path', 2, '-time', *[k * dt for k in range(len(ay))], '-values', *ay)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.pattern('UniformExcitation', 2, 2, '-accel', 2, '-fact', 1.2)
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
ops.analyze(steps, dt)
