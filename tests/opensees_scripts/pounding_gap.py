"""(5) Two cantilevers of different periods pounding through ElasticPPGap gap elements.

A compression gap (gap < 0) and a tension gap (gap > 0) act between the tips; their yield forces
are not reached (an elastic gap).
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 600
ag = [0.0] + [4.0 * math.sin(2 * math.pi * k * dt / 0.6) * math.exp(-0.5 * k * dt) for k in range(1, 401)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0)
ops.node(2, 0.0, 3.0)
ops.node(3, 0.0, 0.0)
ops.node(4, 0.0, 3.0)
ops.fix(1, 1, 1, 1)
ops.fix(3, 1, 1, 1)
ops.mass(2, 10.0, 10.0, 0.0)
ops.mass(4, 25.0, 25.0, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 2, 0.09, 30e6, 6.75e-4, 1)
ops.element('elasticBeamColumn', 2, 3, 4, 0.09, 30e6, 2.0e-4, 1)
ops.uniaxialMaterial('ElasticPPGap', 1, 5e4, -1e9, -0.01)
ops.uniaxialMaterial('ElasticPPGap', 2, 2e4, 1e9, 0.015, 0.0, 'damage')
ops.element('zeroLength', 51, 2, 4, '-mat', 1, '-dir', 1)
ops.element('zeroLength', 52, 2, 4, '-mat', 2, '-dir', 1)
ops.rayleigh(0.2, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.constraints('Plain')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('ux2', 'ux4', 'vx4', 'gap51', 'force51', 'gap52', 'force52', 'eleForce52')}
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['ux2'].append(ops.nodeDisp(2, 1))
    out['ux4'].append(ops.nodeDisp(4, 1))
    out['vx4'].append(ops.nodeVel(4, 1))
    out['gap51'].extend(ops.eleResponse(51, 'deformation'))
    out['force51'].extend(ops.eleResponse(51, 'basicForce'))
    out['gap52'].extend(ops.eleResponse(52, 'deformation'))
    out['force52'].extend(ops.eleResponse(52, 'basicForce'))
    out['eleForce52'].extend(ops.eleForce(52))
print(json.dumps(out))
