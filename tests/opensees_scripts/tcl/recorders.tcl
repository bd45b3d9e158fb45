# The Tcl version of ../recorders.py: Node and Element recorders written to the current directory
# (disp.out, accel.out, react.out, hinges.out, local.out), closed by wipe.
set pi [expr {acos(-1.0)}]
set dt 0.005
set steps 300
set ag [list 0.0]
for {set k 1} {$k <= 300} {incr k} {
    lappend ag [expr {5.0 * sin(2 * $pi * $k * $dt / 0.5) * exp(-0.8 * $k * $dt)}]
}
set E 30e6; set Ic 2.133e-3; set H 3.5
set kh [expr {20 * 6 * $E * $Ic / $H}]

wipe
model basic -ndm 2 -ndf 3
node 1 0.0 0.0; node 2 6.0 0.0; node 11 0.0 0.0; node 12 6.0 0.0; node 3 0.0 $H; node 4 6.0 $H
fix 1 1 1 1; fix 2 1 1 1
equalDOF 1 11 1 2
equalDOF 2 12 1 2
mass 3 30.0 30.0 0.0
mass 4 30.0 30.0 0.0
uniaxialMaterial ElasticPP 1 $kh [expr {130.0 / $kh}]
element zeroLength 101 1 11 -mat 1 -dir 3
element zeroLength 102 2 12 -mat 1 -dir 3
geomTransf Linear 1
element elasticBeamColumn 1 11 3 0.16 $E $Ic 1
element elasticBeamColumn 2 12 4 0.16 $E $Ic 1
element elasticBeamColumn 3 3 4 0.15 $E 2.813e-3 1

recorder Node -file disp.out -time -precision 16 -node 3 4 -dof 1 2 3 disp
recorder Node -file accel.out -time -dT 0.02 -precision 12 -nodeRange 3 4 -dof 1 accel
recorder Node -file react.out -precision 16 -node 1 -dof 1 2 3 reaction
recorder Element -file hinges.out -time -precision 16 -ele 101 102 basicForce
recorder Element -file local.out -eleRange 1 3 localForce

timeSeries Linear 1
pattern Plain 1 1 {
    load 3 0.0 [expr {-30.0 * 9.81}] 20.0
    load 4 0.0 [expr {-30.0 * 9.81}] -20.0
}
constraints Transformation
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator LoadControl 0.25
analysis Static
analyze 4
loadConst -time 0.0

wipeAnalysis
rayleigh 0.3 0.001 0.0 0.0
timeSeries Path 2 -dt $dt -values $ag
pattern UniformExcitation 2 1 -accel 2
constraints Transformation
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient
if {[analyze $steps $dt] != 0} { error "analyze failed" }
wipe
