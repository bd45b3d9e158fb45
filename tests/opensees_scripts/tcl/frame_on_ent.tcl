# The Tcl version of ../frame_on_ent.py: a portal on ENT springs that lift off, after gravity.
# The loads are given in the pattern's body; the ground motion by an inline Series.
set pi [expr {acos(-1.0)}]
set dt 0.005
set steps 500
set ag [list 0.0]
for {set k 1} {$k <= 300} {incr k} { lappend ag [expr {5.0 * sin(2 * $pi * $k * $dt / 0.45)}] }

wipe
model BasicBuilder -ndm 2 -ndf 3
foreach {tag x y} {21 0.0 0.0 22 2.0 0.0 1 0.0 0.0 2 2.0 0.0 3 0.0 3.5 4 2.0 3.5} { node $tag $x $y }
fix 21 1 1 1
fix 22 1 1 1
mass 3 30.0 30.0 0.0
mass 4 30.0 30.0 0.0
mass 1 2.0 2.0 0.0
mass 2 2.0 2.0 0.0
uniaxialMaterial ENT 1 2e5
uniaxialMaterial Elastic 2 5e5
element zeroLength 11 21 1 -mat 1 2 -dir 2 1
element zeroLength 12 22 2 -mat 1 2 -dir 2 1
geomTransf Linear 1
element elasticBeamColumn 1 1 3 0.16 30e6 2.133e-3 1
element elasticBeamColumn 2 2 4 0.16 30e6 2.133e-3 1
element elasticBeamColumn 3 3 4 0.15 30e6 2.813e-3 1

pattern Plain 1 Linear {
    load 3 0.0 [expr {-30.0 * 9.81}] 0.0
    load 4 0.0 [expr {-30.0 * 9.81}] 0.0
}
constraints Plain
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator LoadControl 1.0
analysis Static
if {[analyze 1] != 0} { error "gravity failed" }
loadConst -time 0.0
set static [list [nodeDisp 1 2] [nodeDisp 3 2] [lindex [eleResponse 11 basicForce] 0]]

wipeAnalysis
rayleigh 0.5 0.0 0.0 0.0
pattern UniformExcitation 2 1 -accel "Series -dt $dt -values {$ag}"
constraints Plain
numberer RCM
system BandGeneral
test NormDispIncr 1e-12 100
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient

set names {uy1 uy2 ux3 ent11 def12 force12 reaction21}
foreach name $names { set out($name) {} }
for {set k 0} {$k < $steps} {incr k} {
    if {[analyze 1 $dt] != 0} { error "analyze failed at step $k" }
    lappend out(uy1) [nodeDisp 1 2]
    lappend out(uy2) [nodeDisp 2 2]
    lappend out(ux3) [nodeDisp 3 1]
    set out(ent11) [concat $out(ent11) [eleResponse 11 basicForce]]
    set out(def12) [concat $out(def12) [eleResponse 12 deformation]]
    set out(force12) [concat $out(force12) [eleForce 12]]
    reactions
    set out(reaction21) [concat $out(reaction21) [nodeReaction 21]]
}
set f [open results.txt w]
puts $f "static $static"
foreach name $names { puts $f "$name $out($name)" }
close $f
