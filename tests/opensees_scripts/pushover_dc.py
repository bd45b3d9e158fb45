"""(13) Static pushover with DisplacementControl after gravity: a portal on ElasticPP base hinges
and ENT footings (one lifts off), 120 steps of 2 mm, then 40 more of 5 mm.

Gravity by LoadControl, loadConst('-time', 0.0), a Plain pattern of Linear series with lateral
loads at both floors' nodes (the load factor is the domain time), DisplacementControl of the roof.
"""
import json

import openseespy.opensees as ops

E, Ic, H = 30e6, 2.133e-3, 3.5
k_hinge = 20 * 6 * E * Ic / H

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (21, 0.0, 0.0), (22, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0),
                  (3, 0.0, H), (4, 6.0, H), (5, 0.0, 2 * H), (6, 6.0, 2 * H)):
    ops.node(tag, x, y)
ops.fix(21, 1, 1, 1)
ops.fix(22, 1, 1, 1)
ops.uniaxialMaterial('ENT', 1, 4e5)
ops.uniaxialMaterial('Elastic', 2, 8e5)
ops.uniaxialMaterial('Elastic', 3, 1e7)
ops.element('zeroLength', 31, 21, 1, '-mat', 1, 2, 3, '-dir', 2, 1, 3)
ops.element('zeroLength', 32, 22, 2, '-mat', 1, 2, 3, '-dir', 2, 1, 3)
ops.equalDOF(1, 11, 1, 2)
ops.equalDOF(2, 12, 1, 2)
ops.uniaxialMaterial('ElasticPP', 4, k_hinge, 110.0 / k_hinge, -90.0 / k_hinge)
ops.uniaxialMaterial('Steel01', 5, 100.0, k_hinge, 0.03)
ops.element('zeroLength', 101, 1, 11, '-mat', 4, '-dir', 3)
ops.element('zeroLength', 102, 2, 12, '-mat', 5, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 2, 12, 4, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 3, 3, 5, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 4, 4, 6, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 5, 3, 4, 0.15, E, 2.813e-3, 1)
ops.element('elasticBeamColumn', 6, 5, 6, 0.15, E, 2.813e-3, 1)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
for node in (3, 4, 5, 6):
    ops.load(node, 0.0, -60.0, 0.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 0.5)
ops.analysis('Static')
assert ops.analyze(2) == 0
ops.loadConst('-time', 0.0)

ops.timeSeries('Linear', 2)
ops.pattern('Plain', 2, 2)
ops.load(3, 1.0, 0.0, 0.0)
ops.load(5, 2.0, 0.0, 0.0)
ops.integrator('DisplacementControl', 5, 1, 0.002)
ops.analysis('Static')

out = {k: [] for k in ('lambda', 'u5', 'uy1', 'uy2', 'hinge101', 'hinge102', 'ent31', 'ent32', 'force5', 'react21')}
for k in range(160):
    if k == 120:
        ops.integrator('DisplacementControl', 5, 1, 0.005)
    assert ops.analyze(1) == 0
    out['lambda'].append(ops.getTime())
    out['u5'].extend(ops.nodeDisp(5))
    out['uy1'].append(ops.nodeDisp(1, 2))
    out['uy2'].append(ops.nodeDisp(2, 2))
    out['hinge101'].extend(ops.eleResponse(101, 'basicForce'))
    out['hinge102'].extend(ops.eleResponse(102, 'basicForce'))
    out['ent31'].append(ops.eleResponse(31, 'basicForce')[0])
    out['ent32'].append(ops.eleResponse(32, 'basicForce')[0])
    out['force5'].extend(ops.eleForce(5))
    ops.reactions()
    out['react21'].extend(ops.nodeReaction(21))
print(json.dumps(out))
