"""A 2-storey, 1-bay frame with rotational ElasticPP hinges at both beam ends, each hinge node tied
to its joint by equalDOF 1 2 (the joints and hinge nodes are free: the model file's [[equal_dofs]]),
Rayleigh damping, a ground motion strong enough to yield the hinges."""
import math

import openseespy.opensees as ops

E, span, h = 2.0e8, 6.0, 3.5
col, beam = (0.02, 2.0e-4), (0.015, 1.5e-4)
ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for f in range(3):
    for l in range(2):
        ops.node(10 * f + l + 1, l * span, f * h)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.geomTransf('Linear', 1)
k_hinge = 6 * E * beam[1] / span * 20
ops.uniaxialMaterial('ElasticPP', 2, k_hinge, 60.0 / k_hinge)
tag = 1
for f in range(2):
    for l in range(2):
        ops.element('elasticBeamColumn', tag, 10 * f + l + 1, 10 * (f + 1) + l + 1, col[0], E, col[1], 1)
        tag += 1
for f in (1, 2):
    ends = []
    for side in (0, 1):
        joint, n = 10 * f + side + 1, 100 + 10 * f + side
        ops.node(n, side * span, f * h)
        ops.equalDOF(joint, n, 1, 2)
        ops.element('zeroLength', 1000 + n, joint, n, '-mat', 2, '-dir', 3)
        ends.append(n)
    ops.element('elasticBeamColumn', tag, ends[0], ends[1], beam[0], E, beam[1], 1)
    tag += 1
    for side in (0, 1):
        ops.mass(10 * f + side + 1, 20.0, 20.0, 0.0)
ops.rayleigh(0.3, 0.0, 0.0, 0.0)
dt, steps = 0.01, 200
record = [0.0] + [6.0 * math.sin(2 * math.pi * k * dt / 0.6) * math.exp(-0.5 * k * dt) for k in range(1, steps + 1)]
ops.timeSeries('Path', 1, '-dt', dt, '-values', *record)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('UmfPack')
ops.test('NormDispIncr', 1e-10, 50)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
ops.analyze(steps, dt)
