"""geomTransf('PDelta'): a cantilever column (two elements) under a constant axial load P and a
lateral load, linear elastic, by LoadControl: the P-Delta equilibrium, which OpenSees's Newton
iterations converge to (``NormDispIncr 1e-14``), against the same column with a Linear
transformation; the element forces (global, local, basic) and the reactions of the PDelta one."""
import json
import sys

import openseespy.opensees as ops

E, A, I, H = 2e8, 0.01, 8e-5, 4.0
P, F = -800.0, 10.0                      # P: 0.12 of the Euler load pi^2 E I / (4 H^2)
out = {}
for kind in ('PDelta', 'Linear'):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.3, H / 2)              # a slightly inclined column: both components of the chord
    ops.node(3, 0.6, H)
    ops.fix(1, 1, 1, 1)
    ops.geomTransf(kind, 1)
    ops.element('elasticBeamColumn', 1, 1, 2, A, E, I, 1)
    ops.element('elasticBeamColumn', 2, 2, 3, A, E, I, 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(3, F, P, 0.0)
    ops.test('NormDispIncr', 1e-14, 100)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', 0.25)
    ops.analysis('Static')
    u = []
    for k in range(4):
        assert ops.analyze(1) == 0
        u += ops.nodeDisp(3) + ops.nodeDisp(2)
    out[f'u_{kind}'] = u
    if kind == 'PDelta':
        out['force1'] = ops.eleForce(1) + ops.eleForce(2)
        out['local1'] = ops.eleResponse(1, 'localForce')
        out['basic2'] = ops.eleResponse(2, 'basicForce')
        ops.reactions()
        out['reaction1'] = ops.nodeReaction(1)
print(json.dumps(out))
