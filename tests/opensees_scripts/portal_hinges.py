"""(3) A portal frame with zeroLength ElasticPP rotational hinges at the column bases (yielding).

Each column stands on a node of its own at the support, tied to it in ux, uy by equalDOF, with a
rotational ElasticPP spring (unequal yield moments in the two senses) between them.
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 600
ag = [0.0] + [6.0 * math.sin(2 * math.pi * k * dt / 0.5) * math.exp(-0.8 * k * dt) for k in range(1, 501)]
E, Ic, H = 30e6, 2.133e-3, 3.5
k_hinge = 20 * 6 * E * Ic / H

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0), (3, 0.0, H), (4, 6.0, H)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.equalDOF(1, 11, 1, 2)
ops.equalDOF(2, 12, 1, 2)
ops.mass(3, 30.0, 30.0, 0.0)
ops.mass(4, 30.0, 30.0, 0.0)
ops.uniaxialMaterial('ElasticPP', 1, k_hinge, 120.0 / k_hinge, -150.0 / k_hinge)
ops.uniaxialMaterial('ElasticPP', 2, k_hinge, 140.0 / k_hinge)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 102, 2, 12, '-mat', 2, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 2, 12, 4, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, E, 2.813e-3, 1)
ops.rayleigh(0.3, 0.001, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('ux3', 'ax4', 'rz11', 'def101', 'force101', 'basic102', 'force1', 'eleForce102')}
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['ux3'].append(ops.nodeDisp(3, 1))
    out['ax4'].append(ops.nodeAccel(4, 1))
    out['rz11'].append(ops.nodeDisp(11, 3))
    out['def101'].extend(ops.eleResponse(101, 'deformation'))
    out['force101'].extend(ops.eleResponse(101, 'force'))
    out['basic102'].extend(ops.eleResponse(102, 'basicForce'))
    out['force1'].extend(ops.eleForce(1))
    out['eleForce102'].append(ops.eleForce(102, 6))
print(json.dumps(out))
