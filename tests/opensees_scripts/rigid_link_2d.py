"""(14) 2-D rigid links: a column carrying an eccentric mass on a rigidLink('beam') arm and tied to
a second column by a rigidLink('bar') strut, on an ElasticPP base hinge, shaken sideways."""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 500
ag = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.4) * math.exp(-0.6 * k * dt) for k in range(1, 401)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 4.0, 0.0), (11, 0.0, 0.0), (3, 0.0, 3.0), (4, 4.0, 3.0), (5, 1.5, 3.8)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.equalDOF(1, 11, 1, 2)
ops.uniaxialMaterial('ElasticPP', 1, 4e4, 50.0 / 4e4)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.1, 30e6, 1e-3, 1)
ops.element('elasticBeamColumn', 2, 2, 4, 0.1, 30e6, 6e-4, 1)
ops.rigidLink('beam', 3, 5)
ops.rigidLink('bar', 3, 4)
ops.mass(5, 10.0, 10.0, 2.0)
ops.mass(3, 2.0, 2.0, 0.0)
ops.mass(4, 3.0, 3.0, 0.1)
ops.rayleigh(0.2, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
out = {k: [] for k in ('u5', 'u4', 'hinge', 'col2')}
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['u5'].extend(ops.nodeDisp(5))
    out['u4'].extend(ops.nodeDisp(4))
    out['hinge'].extend(ops.eleResponse(101, 'basicForce'))
    out['col2'].extend(ops.eleForce(2))
print(json.dumps(out))
