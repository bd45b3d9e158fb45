"""truss braces: an elastic diagonal brace with its own mass ('-rho') and a '-doRayleigh' one, then
tension-only X braces (ElasticPPGap tension gaps, slack 1e-5) that go slack and taut in turn, and
an ENT (compression-only) strut; ground motions, Rayleigh damping."""
import json
import math

import openseespy.opensees as ops

dt, steps = 0.005, 500
ag = [0.0] + [4.0 * math.sin(2 * math.pi * k * dt / 0.35) * math.exp(-0.5 * k * dt) for k in range(1, 301)]
E, H, Lb = 2e8, 3.0, 4.0
out = {}
for case in ('elastic', 'tension_only'):
    ops.wipe()
    ops.model('basic', '-ndm', 2, '-ndf', 3)
    for tag, x, y in ((1, 0.0, 0.0), (2, Lb, 0.0), (3, 0.0, H), (4, Lb, H), (5, 2 * Lb, 0.0), (6, 2 * Lb, H)):
        ops.node(tag, x, y)
    for tag in (1, 2, 5):
        ops.fix(tag, 1, 1, 1)
    for tag in (3, 4, 6):
        ops.mass(tag, 20.0, 20.0, 0.0)
    ops.geomTransf('Linear', 1)
    for tag, i, j, A, I in ((1, 1, 3, 0.01, 2e-5), (2, 2, 4, 0.01, 2e-5), (3, 5, 6, 0.01, 2e-5),
                            (4, 3, 4, 0.01, 1e-4), (5, 4, 6, 0.01, 1e-4)):
        ops.element('elasticBeamColumn', tag, i, j, A, E, I, 1)
    ops.rayleigh(0.3, 0.0005, 0.0, 0.0)
    if case == 'elastic':
        ops.uniaxialMaterial('Elastic', 1, E)
        ops.uniaxialMaterial('Elastic', 2, E, 2e4)                       # with a viscosity eta
        ops.element('truss', 11, 1, 4, 5e-4, 1, '-rho', 8.0, '-doRayleigh', 1)
        ops.element('Truss', 12, 4, 5, 3e-4, 2, '-rho', 4.0)
        braces = (11, 12)
    else:
        ops.uniaxialMaterial('ElasticPPGap', 1, E, 1e9, 1e-5)           # tension only, slack 1e-5
        ops.uniaxialMaterial('ENT', 2, E)
        ops.element('truss', 11, 1, 4, 5e-4, 1)
        ops.element('truss', 12, 2, 3, 5e-4, 1)
        ops.element('truss', 13, 2, 6, 2e-4, 2, '-rho', 3.0)            # a compression-only strut
        braces = (11, 12, 13)
    ops.timeSeries('Linear', 1)
    ops.pattern('Plain', 1, 1)
    ops.load(3, 0.0, -100.0, 0.0)
    ops.load(6, 0.0, -100.0, 0.0)
    ops.test('NormDispIncr', 1e-12, 100)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', 0.5)
    ops.analysis('Static')
    assert ops.analyze(2) == 0
    ops.loadConst('-time', 0.0)
    ops.wipeAnalysis()
    ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
    ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
    ops.test('NormDispIncr', 1e-12, 100)
    ops.algorithm('Newton')
    ops.integrator('Newmark', 0.5, 0.25)
    ops.analysis('Transient')
    hist = {k: [] for k in ('drift', 'axial', 'deformation', 'force', 'reaction')}
    for k in range(steps):
        assert ops.analyze(1, dt) == 0
        hist['drift'].append(ops.nodeDisp(4, 1))
        for b in braces:
            hist['axial'] += ops.eleResponse(b, 'axialForce')
            hist['deformation'] += ops.eleResponse(b, 'deformation')
            hist['force'] += ops.eleForce(b)
        ops.reactions()
        hist['reaction'] += ops.nodeReaction(1) + ops.nodeReaction(2)
    for key, values in hist.items():
        out[f'{key}_{case}'] = values
print(json.dumps(out))
