"""(10) An asymmetric 2-storey space frame: rigid diaphragm, ElasticPP base hinges, rigid links.

Four columns on a 6 m x 4 m plan with Iy != Iz and three different vecxz; a rigid diaphragm at the
first floor (its master at the plan's centre holds uz, rx, ry); the roof has beams only, with a
balcony mass on a rigidLink('beam') and a side post tied by a rigidLink('bar'). Three column bases
are held by equalDOF in 1 2 3 6 and zeroLength ElasticPP hinges about 4 and 5, the fourth stands on
a zeroLength of Elastic springs in all six directions. Gravity (Static) then two horizontal ground
accelerations (UniformExcitation 1 and 2) with Rayleigh damping.
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 600
ax = [0.0] + [4.0 * math.sin(2 * math.pi * k * dt / 0.6) * math.exp(-0.5 * k * dt) for k in range(1, 501)]
ay = [0.0] + [3.0 * math.sin(2 * math.pi * k * dt / 0.45 + 0.3) * math.sin(math.pi * k * dt / 2.5) for k in range(1, 501)]
E, G = 30e6, 12.5e6
plan = {1: (0.0, 0.0), 2: (6.0, 0.0), 3: (6.0, 4.0), 4: (0.0, 4.0)}

ops.wipe()
ops.model('basic', '-ndm', 3, '-ndf', 6)
for k, (x, y) in plan.items():
    ops.node(k, x, y, 0.0)
    ops.node(100 + k, x, y, 0.0)
    ops.node(10 + k, x, y, 3.5)
    ops.node(20 + k, x, y, 7.0)
    ops.fix(k, 1, 1, 1, 1, 1, 1)
ops.node(15, 3.0, 2.0, 3.5)
ops.fix(15, 0, 0, 1, 1, 1, 0)
ops.rigidDiaphragm(3, 15, 11, 12, 13, 14)
ops.node(30, 7.5, 0.0, 7.0)
ops.rigidLink('beam', 22, 30)
ops.node(5, 0.0, 5.5, 0.0)
ops.node(31, 0.0, 5.5, 7.0)
ops.fix(5, 1, 1, 1, 1, 1, 1)
ops.rigidLink('bar', 24, 31)

ops.uniaxialMaterial('ElasticPP', 1, 2.0e5, 60.0 / 2.0e5)
ops.uniaxialMaterial('ElasticPP', 2, 3.0e5, 80.0 / 3.0e5, -70.0 / 3.0e5)
ops.uniaxialMaterial('Elastic', 3, 8.0e5)
ops.uniaxialMaterial('Elastic', 4, 4.0e4)
for k in (1, 2, 3):
    ops.equalDOF(k, 100 + k, 1, 2, 3, 6)
    ops.element('zeroLength', 200 + k, k, 100 + k, '-mat', 1, 2, '-dir', 4, 5)
ops.element('zeroLength', 204, 4, 104, '-mat', 3, 3, 3, 4, 4, 4, '-dir', 1, 2, 3, 4, 5, 6)

ops.geomTransf('Linear', 1, 1.0, 0.0, 0.0)
ops.geomTransf('Linear', 2, 0.0, 1.0, 0.0)
ops.geomTransf('Linear', 3, 0.0, 0.0, 1.0)
ops.geomTransf('Linear', 4, 0.6, 0.8, 0.0)
A, Iy, Iz, J = 0.2, 0.4 * 0.5 ** 3 / 12, 0.5 * 0.4 ** 3 / 12, 3.0e-3
tag = 1
for k in plan:
    transf = {1: 1, 2: 2, 3: 4, 4: 1}[k]
    ops.element('elasticBeamColumn', tag, 100 + k, 10 + k, A, E, G, J, Iy, Iz, transf)
    ops.element('elasticBeamColumn', tag + 1, 10 + k, 20 + k, A, E, G, J, 0.8 * Iy, Iz, transf)
    tag += 2
for i, j in ((1, 2), (2, 3), (3, 4), (4, 1)):
    for floor in (10, 20):
        ops.element('elasticBeamColumn', tag, floor + i, floor + j, 0.15, E, G, 2e-3, 3.1e-3, 1.6e-3, 3)
        tag += 1
ops.element('elasticBeamColumn', tag, 5, 31, 0.05, E, G, 1e-4, 4e-4, 2e-4, 1)

masses = {11: 8.0, 12: 12.0, 13: 20.0, 14: 8.0, 21: 6.0, 22: 9.0, 23: 14.0, 24: 6.0, 31: 1.0}
for node, m in masses.items():
    ops.mass(node, m, m, m, 0.0, 0.0, 0.0)
ops.mass(30, 4.0, 4.0, 4.0, 0.5, 0.8, 1.2)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
for node, m in list(masses.items()) + [(30, 4.0)]:
    ops.load(node, 0.0, 0.0, -9.81 * m, 0.0, 0.0, 0.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('UmfPack')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
assert ops.analyze(1) == 0
ops.loadConst('-time', 0.0)
ops.reactions()
static = ops.nodeDisp(23) + ops.nodeDisp(30) + ops.eleForce(1) + ops.nodeReaction(4) + ops.nodeReaction(2)

ops.wipeAnalysis()
ops.rayleigh(0.4, 0.002, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ax)
ops.timeSeries('Path', 3, '-dt', dt, '-values', *ay)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.pattern('UniformExcitation', 3, 2, '-accel', 3)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('UmfPack')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('u23', 'u15', 'u13', 'u30', 'a31', 'col1', 'beam9', 'basic10', 'hinge201', 'def202',
                       'zl204', 'post', 'react2')}
out['static'] = static
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['u23'].extend(ops.nodeDisp(23))
    out['u15'].extend(ops.nodeDisp(15))
    out['u13'].extend(ops.nodeDisp(13))
    out['u30'].extend(ops.nodeDisp(30))
    out['a31'].extend(ops.nodeAccel(31))
    out['col1'].extend(ops.eleForce(1))
    out['beam9'].extend(ops.eleResponse(9, 'localForce'))
    out['basic10'].extend(ops.eleResponse(10, 'basicForce'))
    out['hinge201'].extend(ops.eleResponse(201, 'basicForce'))
    out['def202'].extend(ops.eleResponse(202, 'deformation'))
    out['zl204'].extend(ops.eleResponse(204, 'force'))
    out['post'].extend(ops.eleForce(tag))
    ops.reactions()
    out['react2'].extend(ops.nodeReaction(2))
print(json.dumps(out))
