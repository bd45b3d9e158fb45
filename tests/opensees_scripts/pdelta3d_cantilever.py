"""geomTransf('PDelta') in 3-D: an inclined cantilever column (two elements, Iy != Iz, a skew vecxz)
under a constant axial load P and lateral loads along x and y, linear elastic, by LoadControl: the
P-Delta equilibrium, which OpenSees's Newton iterations converge to (``NormDispIncr 1e-14``),
against the same column with a Linear transformation; the element forces and reactions of the
PDelta one; then a transient after the static state (Newmark, Rayleigh), where the axial forces
change a little on the inclined column (the lateral load has a component along its chord; they are
kept constant here) and not at all on a vertical one."""
import json

import openseespy.opensees as ops

E, G, A, Iy, Iz, J, H = 2e8, 8e7, 0.01, 8e-5, 5e-5, 1e-4, 4.0
P, Fx, Fy = -500.0, 10.0, -6.0           # P: 0.12 of the weak Euler load pi^2 E Iz / (4 H^2)
out = {}
for kind, lean in (('PDelta', 1.0), ('Linear', 1.0), ('PDelta', 0.0)):
    name = kind if lean else f'{kind}_vertical'
    ops.wipe()
    ops.model('basic', '-ndm', 3, '-ndf', 6)
    ops.node(1, 0.0, 0.0, 0.0)
    ops.node(2, 0.2 * lean, 0.1 * lean, H / 2)         # slightly inclined: every component of the chord
    ops.node(3, 0.4 * lean, 0.2 * lean, H)
    ops.fix(1, 1, 1, 1, 1, 1, 1)
    ops.mass(3, 2.0, 2.0, 2.0, 0.0, 0.0, 0.0)
    ops.mass(2, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0)
    ops.geomTransf(kind, 1, 0.6, 0.8, 0.0)
    ops.element('elasticBeamColumn', 1, 1, 2, A, E, G, J, Iy, Iz, 1)
    ops.element('elasticBeamColumn', 2, 2, 3, A, E, G, J, Iy, Iz, 1)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(3, Fx, Fy, P, 0.0, 0.0, 0.0)
    ops.constraints('Plain')
    ops.numberer('Plain')
    ops.system('FullGeneral')
    ops.test('NormDispIncr', 1e-14, 100)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', 0.25)
    ops.analysis('Static')
    u = []
    for k in range(4):
        assert ops.analyze(1) == 0
        u += ops.nodeDisp(3) + ops.nodeDisp(2)
    out[f'u_{name}'] = u
    if name == 'PDelta':
        out['force1'] = ops.eleForce(1) + ops.eleForce(2)
        out['basic2'] = ops.eleResponse(2, 'basicForce')[:1]
        ops.reactions()
        out['reaction1'] = ops.nodeReaction(1)
    ops.loadConst('-time', 0.0)
    ops.timeSeries('Path', 2, '-dt', 0.01, '-values', *[0.0, 1.0, 0.5, -0.5, 0.0] + [0.0] * 46)
    ops.pattern('Plain', 2, 2)
    ops.load(3, 0.0, 40.0, 0.0, 0.0, 0.0, 0.0)
    ops.wipeAnalysis()
    ops.constraints('Plain')
    ops.numberer('Plain')
    ops.system('FullGeneral')
    ops.test('NormDispIncr', 1e-14, 100)
    ops.algorithm('Newton')
    ops.rayleigh(0.2, 0.0, 0.0, 0.0)
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')
    tip = []
    for k in range(50):
        assert ops.analyze(1, 0.01) == 0
        tip += ops.nodeDisp(3)[:3]
    out[f'tip_{name}'] = tip
print(json.dumps(out))
