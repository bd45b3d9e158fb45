"""A static pushover for `unilateral convert`: a portal on rotational ElasticPP base hinges and a
Steel01 girder-end spring, gravity -g m by LoadControl held by loadConst, then DisplacementControl
of the roof under a Linear lateral pattern."""
import openseespy.opensees as ops

g, m = 9.81, 20.0
ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (11, 0.0, 0.0), (12, 6.0, 0.0), (3, 0.0, 3.5), (4, 6.0, 3.5),
                  (5, 6.0, 3.5)):
    ops.node(tag, x, y)
ops.fix(1, 1, 1, 1)
ops.fix(2, 1, 1, 1)
ops.fix(11, 1, 1, 0)
ops.fix(12, 1, 1, 0)
ops.equalDOF(1, 11, 1, 2)             # a hinge node tied to its support: a support of its own
ops.mass(3, m, m, 0.0)
ops.mass(4, m, m, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 11, 3, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 2, 12, 4, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 3, 3, 5, 0.15, 30e6, 2.813e-3, 1)
ops.uniaxialMaterial('ElasticPP', 1, 2.0e6, 4.0e-5)
ops.uniaxialMaterial('Steel01', 2, 90.0, 1.5e6, 0.05)
ops.uniaxialMaterial('Elastic', 3, 1e9)
ops.element('zeroLength', 101, 1, 11, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 102, 2, 12, '-mat', 1, '-dir', 3)
ops.element('zeroLength', 103, 4, 5, '-mat', 3, 3, 2, '-dir', 1, 2, 3)
ops.timeSeries('Linear', 1)
ops.pattern('Plain', 1, 1)
ops.load(3, 0.0, -g * m, 0.0)
ops.load(4, 0.0, -g * m, 0.0)
ops.integrator('LoadControl', 0.1)
ops.analysis('Static')
ops.analyze(10)
ops.loadConst('-time', 0.0)
ops.timeSeries('Linear', 2)
ops.pattern('Plain', 2, 2)
ops.load(3, 1.0, 0.0, 0.0)
ops.load(4, 1.0, 0.0, 0.0)
ops.integrator('DisplacementControl', 3, 1, 0.002)
ops.analyze(40)
ops.integrator('DisplacementControl', 3, 1, 0.004)
ops.analyze(20)
