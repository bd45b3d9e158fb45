"""(7) The step-by-step loop ``for k in range(n): analyze(1, dt)`` equals ``analyze(n, dt)`` in pieces.

The frame on ENT springs of (4), run three times from a fresh model: one step at a time (reading
nodeDisp, nodeAccel, eleForce and eleResponse after every step), in pieces of 100 steps, and in one
call of all 1100 steps (longer than the first horizon of unilateral.opensees: the simulation is
restarted from its state on the way).
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.002, 1100
ag = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.45) for k in range(1, 551)]


def build():
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
    ops.test('NormDispIncr', 1e-15, 100)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', 1.0)
    ops.analysis('Static')
    assert ops.analyze(1) == 0
    ops.loadConst('-time', 0.0)
    ops.wipeAnalysis()
    ops.rayleigh(1.0, 0.0, 0.0, 0.0)
    ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
    ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
    ops.test('NormDispIncr', 1e-15, 100)
    ops.algorithm('Newton')
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')


def record(out):
    out['t'].append(ops.getTime())
    out['uy1'].append(ops.nodeDisp(1, 2))
    out['ux3'].append(ops.nodeDisp(3, 1))
    out['ax3'].append(ops.nodeAccel(3, 1))
    out['force1'].extend(ops.eleForce(1))
    out['ent11'].append(ops.eleResponse(11, 'basicForce')[0])


runs = {}
for name, piece in (('loop', 1), ('pieces', 100), ('whole', steps)):
    build()
    out = {k: [] for k in ('t', 'uy1', 'ux3', 'ax3', 'force1', 'ent11')}
    for k in range(steps // piece):
        assert ops.analyze(piece, dt) == 0
        if piece == 1 or name == 'pieces':
            record(out)
    if name == 'whole':
        record(out)
    runs[name] = out
print(json.dumps({f'{run}.{key}': values for run, out in runs.items() for key, values in out.items()}))
