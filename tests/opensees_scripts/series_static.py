"""Time series as OpenSees evaluates them: a static analysis of three unit springs loaded through
Path series (-dt with -startTime and -useLast, -time with -prependZero and -factor, a Path ending
early) and a Linear one with -factor, read at LoadControl steps that pass every end."""
import json

import openseespy.opensees as ops

ops.wipe()
ops.model('basic', '-ndm', 2, '-ndf', 3)
ops.node(1, 0.0, 0.0)
ops.node(2, 0.0, 0.0)
ops.fix(1, 1, 1, 1)
ops.uniaxialMaterial('Elastic', 1, 1.0)
ops.element('zeroLength', 1, 1, 2, '-mat', 1, 1, 1, '-dir', 1, 2, 3)
ops.timeSeries('Path', 1, '-dt', 0.5, '-values', 1.0, 3.0, -2.0, 4.0, '-startTime', 0.8, '-useLast')
ops.timeSeries('Path', 2, '-time', 0.3, 1.0, 2.2, 2.9, '-values', 2.0, -1.0, 5.0, 1.0, '-factor', 2.0,
               '-prependZero')
ops.timeSeries('Path', 3, '-dt', 0.4, '-values', 0.0, 1.0, 2.0)
ops.timeSeries('Linear', 4, '-factor', 0.25)
ops.pattern('Plain', 1, 1)
ops.load(2, 1.0, 0.0, 0.0)
ops.pattern('Plain', 2, 2, '-fact', 0.5)
ops.load(2, 0.0, 1.0, 0.0)
ops.pattern('Plain', 3, 3)
ops.load(2, 0.0, 0.0, 1.0)
ops.pattern('Plain', 4, 4)
ops.load(2, 0.0, 0.0, 0.5)
ops.integrator('LoadControl', 0.13)
ops.analysis('Static')
out = {'t': [], 'u': []}
for k in range(30):
    assert ops.analyze(1) == 0
    out['t'].append(ops.getTime())
    out['u'].extend(ops.nodeDisp(2))
ops.setTime(0.95)
ops.analyze(1)
out['after_setTime'] = ops.nodeDisp(2)
print(json.dumps(out))
