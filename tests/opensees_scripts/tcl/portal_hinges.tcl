# The Tcl version of ../portal_hinges.py: a portal with zeroLength ElasticPP base hinges (yielding).
# Writes results.txt: one line per history, its name then its values.
set pi [expr {acos(-1.0)}]
set dt 0.005
set steps 600
set ag [list 0.0]
for {set k 1} {$k <= 500} {incr k} {
    lappend ag [expr {6.0 * sin(2 * $pi * $k * $dt / 0.5) * exp(-0.8 * $k * $dt)}]
}
set E 30e6; set Ic 2.133e-3; set H 3.5
set kh [expr {20 * 6 * $E * $Ic / $H}]

wipe
model basic -ndm 2 -ndf 3
node 1 0.0 0.0; node 2 6.0 0.0; node 11 0.0 0.0; node 12 6.0 0.0
node 3 0.0 $H; node 4 6.0 $H
fix 1 1 1 1
fix 2 1 1 1
equalDOF 1 11 1 2
equalDOF 2 12 1 2
mass 3 30.0 30.0 0.0
mass 4 30.0 30.0 0.0
uniaxialMaterial ElasticPP 1 $kh [expr {120.0 / $kh}] [expr {-150.0 / $kh}]
uniaxialMaterial ElasticPP 2 $kh [expr {140.0 / $kh}]
element zeroLength 101 1 11 -mat 1 -dir 3
element zeroLength 102 2 12 -mat 2 -dir 3
geomTransf Linear 1
element elasticBeamColumn 1 11 3 0.16 $E $Ic 1
element elasticBeamColumn 2 12 4 0.16 $E $Ic 1
element elasticBeamColumn 3 3 4 0.15 $E 2.813e-3 1
rayleigh 0.3 0.001 0.0 0.0
timeSeries Path 1 -dt $dt -values $ag
pattern UniformExcitation 1 1 -accel 1
constraints Transformation
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient

foreach name {ux3 ax4 rz11 def101 force101 basic102 force1 eleForce102} { set out($name) {} }
for {set k 0} {$k < $steps} {incr k} {
    if {[analyze 1 $dt] != 0} { error "analyze failed at step $k" }
    lappend out(ux3) [nodeDisp 3 1]
    lappend out(ax4) [nodeAccel 4 1]
    lappend out(rz11) [nodeDisp 11 3]
    set out(def101) [concat $out(def101) [eleResponse 101 deformation]]
    set out(force101) [concat $out(force101) [eleResponse 101 force]]
    set out(basic102) [concat $out(basic102) [eleResponse 102 basicForce]]
    set out(force1) [concat $out(force1) [eleForce 1]]
    lappend out(eleForce102) [eleForce 102 6]
}
set f [open results.txt w]
foreach name {ux3 ax4 rz11 def101 force101 basic102 force1 eleForce102} { puts $f "$name $out($name)" }
close $f
