"""eleLoad -beamUniform on 2-D elasticBeamColumn elements: a gable frame (inclined rafters, both
Wy and Wx, '-ele' and '-range'), a column with a lateral Wy, by LoadControl; then loadConst and a
ground motion. Nodal displacements, element forces (global, local, basic) and reactions."""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.01, 200
ag = [0.0] + [2.0 * math.sin(2 * math.pi * k * dt / 0.6) for k in range(1, 101)]
E = 3e7
ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 8.0, 0.0), (3, 0.0, 4.0), (4, 8.0, 4.0), (5, 4.0, 5.5)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 0)                                         # a pinned base: its end moment is released
for tag in (3, 4, 5):
    ops.mass(tag, 5.0, 5.0, 0.0)
ops.geomTransf('Linear', 1)
for tag, i, j in ((1, 1, 3), (2, 2, 4), (3, 3, 5), (4, 5, 4)):
    ops.element('elasticBeamColumn', tag, i, j, 0.12, E, 1.6e-3, 1)
ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.eleLoad('-ele', 3, '-type', '-beamUniform', -12.0, 2.0)
ops.eleLoad('-range', 4, 4, '-type', '-beamUniform', -8.0)
ops.eleLoad('-ele', 1, 2, '-type', '-beamUniform', 3.0)          # wind on the columns (local y)
ops.load(5, 0.0, -20.0, 0.0)
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 0.25)
ops.analysis('Static')
out = {k: [] for k in ('u', 'force', 'local', 'basic', 'reaction', 'drift', 'dyn_force')}
for k in range(4):
    assert ops.analyze(1) == 0
    for node in (2, 3, 4, 5):
        out['u'] += ops.nodeDisp(node)
    for tag in (1, 2, 3, 4):
        out['force'] += ops.eleForce(tag)
        out['local'] += ops.eleResponse(tag, 'localForce')
        out['basic'] += ops.eleResponse(tag, 'basicForce')
    ops.reactions()
    out['reaction'] += ops.nodeReaction(1) + ops.nodeReaction(2)
ops.loadConst('-time', 0.0)
ops.wipeAnalysis()
ops.rayleigh(0.2, 0.001, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
for k in range(steps):
    assert ops.analyze(1, dt) == 0
    out['drift'] += ops.nodeDisp(5)
    out['dyn_force'] += ops.eleForce(3) + ops.eleResponse(1, 'basicForce')
print(json.dumps(out))
