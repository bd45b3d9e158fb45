"""(6) Gravity by a static analysis in ten LoadControl steps, loadConst, then a transient analysis.

The portal of (3) with base hinges (one ElasticPP with an initial strain eps0), gravity loads and
moments on the beam ends, an Elastic side spring with a dashpot (eta) at the roof, and a mass given
with node(..., '-mass', ...).
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 400
ag = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.5) * math.exp(-0.8 * k * dt) for k in range(1, 301)]
E, Ic, H = 30e6, 2.133e-3, 3.5
k_hinge = 20 * 6 * E * Ic / H

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0), (3, 0.0, H), (5, 6.0, H)):
    ops.node(tag, x, y)
ops.node(4, 6.0, H, '-mass', 30.0, 30.0, 0.0)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.fix(5, 1, 1, 1)
ops.equalDOF(1, 11, 1, 2)
ops.equalDOF(2, 12, 1, 2)
ops.mass(3, 30.0, 30.0, 0.0)
ops.uniaxialMaterial('ElasticPP', 1, k_hinge, 140.0 / k_hinge, -140.0 / k_hinge, 2e-5)
ops.uniaxialMaterial('ElasticPP', 2, k_hinge, 140.0 / k_hinge)
ops.uniaxialMaterial('Elastic', 3, 2e3, 40.0)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 102, 2, 12, '-mat', 2, '-dir', 3)
ops.element('zeroLength', 103, 4, 5, '-mat', 3, '-dir', 1)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 2, 12, 4, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, E, 2.813e-3, 1)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.load(3, 0.0, -30.0 * 9.81 - 90.0, 45.0)
ops.load(4, 0.0, -30.0 * 9.81 - 90.0, -45.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 0.1)
ops.analysis('Static')
assert ops.analyze(10) == 0
ops.loadConst('-time', 0.0)
ops.reactions()
static = [ops.getTime(), ops.nodeDisp(3, 2), ops.nodeDisp(3, 3), ops.eleResponse(101, 'basicForce')[0]]
static += ops.nodeReaction(1) + ops.eleForce(3)

ops.wipeAnalysis()
ops.rayleigh(0.3, 0.001, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('t', 'ux3', 'uy4', 'hinge101', 'hinge102', 'spring103', 'force3', 'reaction2')}
out['static'] = static
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['t'].append(ops.getTime())
    out['ux3'].append(ops.nodeDisp(3, 1))
    out['uy4'].append(ops.nodeDisp(4, 2))
    out['hinge101'].extend(ops.eleResponse(101, 'basicForce'))
    out['hinge102'].extend(ops.eleResponse(102, 'basicForce'))
    out['spring103'].extend(ops.eleResponse(103, 'basicForce'))
    out['force3'].extend(ops.eleForce(3))
    ops.reactions()
    out['reaction2'].extend(ops.nodeReaction(2))
print(json.dumps(out))
