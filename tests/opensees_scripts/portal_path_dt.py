"""(1) An elastic portal frame under a ground acceleration from a Path series with -dt, Rayleigh damping.

Run with OpenSeesPy or, with the import changed, with unilateral.opensees; prints the histories as JSON.
"""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.01, 400
ag = [0.0] + [3.0 * math.sin(2 * math.pi * k * dt / 0.35) * math.exp(-k * dt) for k in range(1, 301)]

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0)
ops.node(2, 6.0, 0.0)
ops.node(3, 0.0, 3.5)
ops.node(4, 6.0, 3.5)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.mass(3, 20.0, 20.0, 0.0)
ops.mass(4, 20.0, 20.0, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 3, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 2, 2, 4, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, 30e6, 2.813e-3, 1)
ops.rayleigh(0.4, 0.002, 0.0, 0.0)
ops.timeSeries('Path', 1, '-dt', dt, '-values', *ag, '-factor', 1.5)
ops.pattern('UniformExcitation', 1, 1, '-accel', 1)
ops.constraints('Plain')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')

out = {k: [] for k in ('t', 'ux3', 'vx3', 'ax3', 'uy4', 'rz4', 'force1', 'force3', 'reaction1')}
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['t'].append(ops.getTime())
    out['ux3'].append(ops.nodeDisp(3, 1))
    out['vx3'].append(ops.nodeVel(3, 1))
    out['ax3'].append(ops.nodeAccel(3, 1))
    out['uy4'].append(ops.nodeDisp(4, 2))
    out['rz4'].append(ops.nodeDisp(4)[2])
    out['force1'].extend(ops.eleForce(1))
    out['force3'].extend(ops.eleForce(3))
    ops.reactions()
    out['reaction1'].extend(ops.nodeReaction(1))
print(json.dumps(out))
