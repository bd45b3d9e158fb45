"""(12) Recorders: Node (disp, accel with -dT, reaction), Element (basicForce, localForce) and
EnvelopeNode, EnvelopeElement files.

The portal of (6) with its hinges, gravity by LoadControl (recorded) then a ground motion; the
recorders are defined before the gravity analysis. At the end ``wipe()`` closes the files, and the
script reads them back into its JSON (values and shapes), so that the two runs compare files.
"""
import json
import math
import os
import tempfile

import openseespy.opensees as ops

dt, steps = 0.005, 300
ag = [0.0] + [5.0 * math.sin(2 * math.pi * k * dt / 0.5) * math.exp(-0.8 * k * dt) for k in range(1, 301)]
E, Ic, H = 30e6, 2.133e-3, 3.5
k_hinge = 20 * 6 * E * Ic / H
folder = tempfile.mkdtemp()
files = {name: os.path.join(folder, name + '.out') for name in ('disp', 'accel', 'react', 'hinges', 'local', 'envnode',
                                                              'envele')}

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0), (3, 0.0, H), (4, 6.0, H)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.equalDOF(1, 11, 1, 2)
ops.equalDOF(2, 12, 1, 2)
ops.mass(3, 30.0, 30.0, 0.0)
ops.mass(4, 30.0, 30.0, 0.0)
ops.uniaxialMaterial('ElasticPP', 1, k_hinge, 130.0 / k_hinge)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 102, 2, 12, '-mat', 1, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 2, 12, 4, 0.16, E, Ic, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, E, 2.813e-3, 1)

ops.recorder('Node', '-file', files['disp'], '-time', '-precision', 16, '-node', 3, 4, '-dof', 1, 2, 3, 'disp')
ops.recorder('Node', '-file', files['accel'], '-time', '-dT', 0.02, '-precision', 12, '-nodeRange', 3, 4,
             '-dof', 1, 'accel')
ops.recorder('Node', '-file', files['react'], '-precision', 16, '-node', 1, '-dof', 1, 2, 3, 'reaction')
ops.recorder('Element', '-file', files['hinges'], '-time', '-precision', 16, '-ele', 101, 102, 'basicForce')
ops.recorder('Element', '-file', files['local'], '-eleRange', 1, 3, 'localForce')
ops.recorder('EnvelopeNode', '-file', files['envnode'], '-time', '-precision', 16, '-node', 3, 4, '-dof', 1, 3, 'disp')
ops.recorder('EnvelopeElement', '-file', files['envele'], '-precision', 16, '-ele', 101, 1, 'basicForce')

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.load(3, 0.0, -30.0 * 9.81, 20.0)
ops.load(4, 0.0, -30.0 * 9.81, -20.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 0.25)
ops.analysis('Static')
assert ops.analyze(4) == 0
ops.loadConst('-time', 0.0)

ops.wipeAnalysis()
ops.rayleigh(0.3, 0.001, 0.0, 0.0)
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
assert ops.analyze(steps, dt) == 0
ops.wipe()

out = {}
for name, path in files.items():
    rows = [[float(x) for x in line.split()] for line in open(path) if line.strip()]
    out[name] = [x for row in rows for x in row]
    out[name + '.shape'] = [len(rows), len(rows[0]) if rows else 0]
print(json.dumps(out))
