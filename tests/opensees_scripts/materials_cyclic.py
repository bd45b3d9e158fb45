"""(11) Steel01, Hardening, ElasticBilin and Parallel, each under its own mass, shaken to yield.

Each material is a zeroLength in direction 1 from a fixed node to a node with a mass (free in ux
only); one ground motion drives all of them through several cycles of yielding (or, for the
ElasticBilin laws, across their stiffness changes). Two masses sit on a zeroLength of two
materials (directions 1 and 2) with a Parallel in each.
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.004, 900
ag = [0.0] + [7.0 * math.sin(2 * math.pi * k * dt / 0.5) * math.exp(-0.6 * k * dt) for k in range(1, 751)]
agy = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.35) for k in range(1, 751)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.uniaxialMaterial('Steel01', 1, 50.0, 2.0e4, 0.05)
ops.uniaxialMaterial('Steel01', 2, 40.0, 1.5e4, 0.0)
ops.uniaxialMaterial('Hardening', 3, 2.0e4, 40.0, 0.0, 2.0e3)
ops.uniaxialMaterial('ElasticBilin', 4, 1.0e4, 3.0e4, 0.004, 2.0e4, 5.0e4, -0.003)
ops.uniaxialMaterial('ElasticBilin', 5, 1.2e4, 2.0e4, 0.003)
ops.uniaxialMaterial('ENT', 6, 5.0e3)
ops.uniaxialMaterial('Elastic', 7, 2.0e3)
ops.uniaxialMaterial('Parallel', 8, 1, 6, 7)
ops.uniaxialMaterial('Steel01', 9, 30.0, 1.0e4, 0.1, 0.0, 1.0, 0.0, 1.0)
ops.uniaxialMaterial('Parallel', 10, 9, 3)
mats = (1, 2, 3, 4, 5, 8)
for k, m in enumerate(mats):
    ops.node(10 * k + 1, 0.0, float(k))
    ops.node(10 * k + 2, 0.0, float(k))
    ops.fix(10 * k + 1, 1, 1, 1)
    ops.fix(10 * k + 2, 0, 1, 1)
    ops.mass(10 * k + 2, 12.0 + 2.0 * k, 0.0, 0.0)
    ops.element('zeroLength', 100 + k, 10 * k + 1, 10 * k + 2, '-mat', m, '-dir', 1)
ops.node(91, 5.0, 0.0)
ops.node(92, 5.0, 0.0, '-mass', 15.0, 15.0, 0.0)
ops.fix(91, 1, 1, 1)
ops.fix(92, 0, 0, 1)
ops.element('zeroLength', 190, 91, 92, '-mat', 10, 8, '-dir', 1, 2)
ops.rayleigh(0.2, 0.0, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *agy)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.pattern('UniformExcitation', 2, 2, '-accel', 2)
ops.constraints('Plain')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {f'f{100 + k}': [] for k in range(len(mats))}
out.update({f'u{100 + k}': [] for k in range(len(mats))})
out.update({'f190': [], 'u92': []})
for step in range(steps):
    assert ops.analyze(1, dt) == 0
    for k in range(len(mats)):
        out[f'f{100 + k}'].extend(ops.eleResponse(100 + k, 'basicForce'))
        out[f'u{100 + k}'].extend(ops.eleResponse(100 + k, 'deformation'))
    out['f190'].extend(ops.eleResponse(190, 'basicForce'))
    out['u92'].extend(ops.nodeDisp(92)[:2])
print(json.dumps(out))
