# The Tcl version of ../gravity_then_transient.py: gravity in ten LoadControl steps, loadConst,
# then a transient analysis; the ground motion read from a file with -filePath.
set pi [expr {acos(-1.0)}]
set dt 0.005
set steps 400
set fh [open ag_gravity.txt w]
puts $fh 0.0
for {set k 1} {$k <= 300} {incr k} {
    puts $fh [expr {5.0 * sin(2 * $pi * $k * $dt / 0.5) * exp(-0.8 * $k * $dt)}]
}
close $fh
set E 30e6; set Ic 2.133e-3; set H 3.5
set kh [expr {20 * 6 * $E * $Ic / $H}]

wipe
model basic -ndm 2 -ndf 3
node 1 0.0 0.0; node 2 6.0 0.0; node 11 0.0 0.0; node 12 6.0 0.0; node 3 0.0 $H; node 5 6.0 $H
node 4 6.0 $H -mass 30.0 30.0 0.0
fix 1 1 1 1; fix 2 1 1 1; fix 5 1 1 1
equalDOF 1 11 1 2
equalDOF 2 12 1 2
mass 3 30.0 30.0 0.0
uniaxialMaterial ElasticPP 1 $kh [expr {140.0 / $kh}] [expr {-140.0 / $kh}] 2e-5
uniaxialMaterial ElasticPP 2 $kh [expr {140.0 / $kh}]
uniaxialMaterial Elastic 3 2e3 40.0
element zeroLength 101 1 11 -mat 1 -dir 3
element zeroLength 102 2 12 -mat 2 -dir 3
element zeroLength 103 4 5 -mat 3 -dir 1
geomTransf Linear 1
element elasticBeamColumn 1 11 3 0.16 $E $Ic 1
element elasticBeamColumn 2 12 4 0.16 $E $Ic 1
element elasticBeamColumn 3 3 4 0.15 $E 2.813e-3 1

timeSeries Linear 1
pattern Plain 1 1 {
    load 3 0.0 [expr {-30.0 * 9.81 - 90.0}] 45.0
    load 4 0.0 [expr {-30.0 * 9.81 - 90.0}] -45.0
}
constraints Transformation
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator LoadControl 0.1
analysis Static
if {[analyze 10] != 0} { error "gravity failed" }
loadConst -time 0.0
reactions
set static [list [getTime] [nodeDisp 3 2] [nodeDisp 3 3] [lindex [eleResponse 101 basicForce] 0]]
set static [concat $static [nodeReaction 1] [eleForce 3]]

wipeAnalysis
rayleigh 0.3 0.001 0.0 0.0
timeSeries Path 2 -dt $dt -filePath ag_gravity.txt
pattern UniformExcitation 2 1 -accel 2
constraints Transformation
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient

set names {t ux3 uy4 hinge101 hinge102 spring103 force3 reaction2}
foreach name $names { set out($name) {} }
for {set k 0} {$k < $steps} {incr k} {
    if {[analyze 1 $dt] != 0} { error "analyze failed at step $k" }
    lappend out(t) [getTime]
    lappend out(ux3) [nodeDisp 3 1]
    lappend out(uy4) [nodeDisp 4 2]
    set out(hinge101) [concat $out(hinge101) [eleResponse 101 basicForce]]
    set out(hinge102) [concat $out(hinge102) [eleResponse 102 basicForce]]
    set out(spring103) [concat $out(spring103) [eleResponse 103 basicForce]]
    set out(force3) [concat $out(force3) [eleForce 3]]
    reactions
    set out(reaction2) [concat $out(reaction2) [nodeReaction 2]]
}
set f [open results.txt w]
puts $f "static $static"
foreach name $names { puts $f "$name $out($name)" }
close $f
