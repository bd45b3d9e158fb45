"""The portal of tests/pushover_frames.py in OpenSees: a pushover by DisplacementControl.

Elastic beam-columns (Linear transformation) joined at every hinge by a zeroLength rotational
ElasticPP spring (stiffness ``k_hinge``, yield moment Mp) between two nodes tied in ux, uy by
equalDOF; the gravity of 10 t at each top node first (LoadControl, then held), then 1 kN at node 2
per unit load factor, node 2's ux driven to 0.1 m in 200 steps, Newton to NormDispIncr 1e-12.
Prints the JSON of node 2's ux, the load factor and the base shear (the columns' shears at their base
nodes: the supports' reactions reach the columns through equalDOF) per step.

Run: python tests/pushover_opensees_portal.py K_HINGE (openseespy's lib on LD_LIBRARY_PATH)
"""
import json
import sys

import openseespy.opensees as ops

H, L, E, A, I_COL, I_BEAM = 3.0, 4.0, 30e6, 0.09, 6.75e-4, 1.35e-3
MP_COL, MP_BEAM = 100.0, 80.0
k_hinge = float(sys.argv[1])
steps, target = 200, 0.1

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (11, 0.0, 0.0), (2, 0.0, H), (21, 0.0, H), (3, L, H), (31, L, H), (4, L, 0.0),
                  (41, L, 0.0)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(4, 1, 1, 1)
for master, slave in ((1, 11), (4, 41), (2, 21), (3, 31)):
    ops.equalDOF(master, slave, 1, 2)
ops.uniaxialMaterial('ElasticPP', 1, k_hinge, MP_COL / k_hinge)
ops.uniaxialMaterial('ElasticPP', 2, k_hinge, MP_BEAM / k_hinge)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 102, 4, 41, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 103, 2, 21, '-mat', 2, '-dir', 3)
ops.element('zeroLength', 104, 3, 31, '-mat', 2, '-dir', 3)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 2, A, E, I_COL, 1)
ops.element('elasticBeamColumn', 2, 41, 3, A, E, I_COL, 1)
ops.element('elasticBeamColumn', 3, 21, 31, A, E, I_BEAM, 1)

ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.load(2, 0.0, -10.0 * 9.81, 0.0)
ops.load(3, 0.0, -10.0 * 9.81, 0.0)
ops.constraints('Transformation')
ops.numberer('RCM')
ops.system('BandGeneral')
ops.test('NormDispIncr', 1e-12, 100)
ops.algorithm('Newton')
ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
assert ops.analyze(1) == 0
ops.loadConst('-time', 0.0)

ops.timeSeries('Linear', 2)
ops.pattern('Plain', 2, 2)
ops.load(2, 1.0, 0.0, 0.0)
ops.integrator('DisplacementControl', 2, 1, target / steps)
ops.analysis('Static')
out = {'ux2': [ops.nodeDisp(2, 1)], 'load_factor': [0.0], 'base_shear': [0.0]}
for _ in range(steps):
    assert ops.analyze(1) == 0
    out['ux2'].append(ops.nodeDisp(2, 1))
    out['load_factor'].append(ops.getLoadFactor(2))
    out['base_shear'].append(-(ops.eleForce(1, 1) + ops.eleForce(2, 1)))     # the columns' shears at the base
print(json.dumps(out))
