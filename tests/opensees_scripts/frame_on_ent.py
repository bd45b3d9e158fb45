"""(4) A portal frame on compression-only ENT springs that lift off, after gravity by a static analysis.

Each column base rests on a vertical ENT spring and is held horizontally by an Elastic spring to a
fixed ground node; gravity (Static, LoadControl) then loadConst, then a ground acceleration.
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 500
ag = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.45) for k in range(1, 301)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((21, 0.0, 0.0), (22, 2.0, 0.0), (1, 0.0, 0.0), (2, 2.0, 0.0), (3, 0.0, 3.5), (4, 2.0, 3.5)):
    ops.node(tag, x, y)
ops.fix(21, 1, 1, 1)
ops.fix(22, 1, 1, 1)
ops.mass(3, 30.0, 30.0, 0.0)
ops.mass(4, 30.0, 30.0, 0.0)
ops.mass(1, 2.0, 2.0, 0.0)
ops.mass(2, 2.0, 2.0, 0.0)
ops.uniaxialMaterial('ENT', 1, 2e5)
ops.uniaxialMaterial('Elastic', 2, 5e5)
ops.element('zeroLength', 11, 21, 1, '-mat', 1, 2, '-dir', 2, 1)
ops.element('zeroLength', 12, 22, 2, '-mat', 1, 2, '-dir', 2, 1)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 3, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 2, 2, 4, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, 30e6, 2.813e-3, 1)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.load(3, 0.0, -30.0 * 9.81, 0.0)
ops.load(4, 0.0, -30.0 * 9.81, 0.0)
ops.constraints('Plain')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
assert ops.analyze(1) == 0
ops.loadConst('-time', 0.0)
static = [ops.nodeDisp(1, 2), ops.nodeDisp(3, 2), ops.eleResponse(11, 'basicForce')[0]]

ops.wipeAnalysis()
ops.rayleigh(0.5, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.constraints('Plain')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('uy1', 'uy2', 'ux3', 'ent11', 'def12', 'force12', 'reaction21')}
out['static'] = static
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['uy1'].append(ops.nodeDisp(1, 2))
    out['uy2'].append(ops.nodeDisp(2, 2))
    out['ux3'].append(ops.nodeDisp(3, 1))
    out['ent11'].extend(ops.eleResponse(11, 'basicForce'))
    out['def12'].extend(ops.eleResponse(12, 'deformation'))
    out['force12'].extend(ops.eleForce(12))
    ops.reactions()
    out['reaction21'].extend(ops.nodeReaction(21))
print(json.dumps(out))
