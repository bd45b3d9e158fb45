"""Element loads, masses, stiffness-proportional Rayleigh damping with -doRayleigh springs and a
truss with -rho, for `unilateral convert`: gravity (eleLoad -beamUniform) then a ground motion."""
import math

import openseespy.opensees as ops

dt, steps = 0.005, 500
ag = [0.0] + [3.0 * math.sin(2 * math.pi * k * dt / 0.4) * math.exp(-1.5 * k * dt) for k in range(1, 401)]
ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
for tag, x, y in ((1, 0.0, 0.0), (2, 6.0, 0.0), (3, 0.0, 3.5), (4, 6.0, 3.5), (5, 0.0, 0.0), (6, 6.0, 0.0)):
    ops.node(tag, x, y)
ops.fix(5, 1, 1, 1)
ops.fix(6, 1, 1, 1)
ops.fix(1, 0, 0, 1)
ops.fix(2, 0, 0, 1)
ops.mass(3, 15.0, 15.0, 0.0)
ops.mass(4, 15.0, 15.0, 0.0)
ops.mass(1, 2.0, 2.0, 0.0)
ops.mass(2, 2.0, 2.0, 0.0)
ops.geomTransf('Linear', 1)
ops.element('elasticBeamColumn', 1, 1, 3, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 2, 2, 4, 0.16, 30e6, 2.133e-3, 1)
ops.element('elasticBeamColumn', 3, 3, 4, 0.15, 30e6, 2.813e-3, 1)
ops.uniaxialMaterial('Elastic', 1, 8.0e4, 30.0)
ops.uniaxialMaterial('ENT', 2, 4.0e5)
ops.uniaxialMaterial('Elastic', 3, 2.0e8)
ops.element('zeroLength', 11, 5, 1, '-mat', 1, '-dir', 1, '-doRayleigh', 1)
ops.element('zeroLength', 12, 6, 2, '-mat', 1, '-dir', 1, '-doRayleigh', 1)
ops.element('zeroLength', 21, 5, 1, '-mat', 2, '-dir', 2)
ops.element('zeroLength', 22, 6, 2, '-mat', 2, '-dir', 2)
ops.element('truss', 13, 1, 4, 0.002, 3, '-rho', 0.05, '-doRayleigh', 1)
ops.rayleigh(0.25, 0.0015, 0.0, 0.0)
ops.timeSeries('Constant', 1)
ops.pattern('Plain', 1, 1)
ops.eleLoad('-ele', 3, '-type', '-beamUniform', -12.0, 1.0)
ops.load(3, 5.0, -30.0, 0.0)
ops.integrator('LoadControl', 1.0)
ops.analysis('Static')
ops.analyze(1)
ops.loadConst('-time', 0.0)
ops.wipeAnalysis()
ops.timeSeries('Path', 2, '-dt', dt, '-values', *ag)
ops.pattern('UniformExcitation', 2, 1, '-accel', 2)
ops.timeSeries('Linear', 3, '-factor', 2.0)
ops.pattern('Plain', 3, 3)
ops.load(4, 1.0, 0.0, 0.0)
ops.integrator('Newmark', 0.5, 0.25)
ops.analysis('Transient')
for k in range(steps):
    ops.analyze(1, dt)
