# The Tcl version of ../frame3d_asymmetric.py (an asymmetric space frame with a rigid diaphragm,
# rigid links and ElasticPP base hinges), writing results.txt: one line per history.
set pi [expr {acos(-1.0)}]
set dt 0.005
set steps 600
set ax [list 0.0]; set ay [list 0.0]
for {set k 1} {$k <= 500} {incr k} {
    lappend ax [expr {4.0 * sin(2 * $pi * $k * $dt / 0.6) * exp(-0.5 * $k * $dt)}]
    lappend ay [expr {3.0 * sin(2 * $pi * $k * $dt / 0.45 + 0.3) * sin($pi * $k * $dt / 2.5)}]
}
set E 30e6; set G 12.5e6

wipe
model basic -ndm 3 -ndf 6
foreach {k x y} {1 0.0 0.0 2 6.0 0.0 3 6.0 4.0 4 0.0 4.0} {
    node $k $x $y 0.0
    node [expr {100 + $k}] $x $y 0.0
    node [expr {10 + $k}] $x $y 3.5
    node [expr {20 + $k}] $x $y 7.0
    fix $k 1 1 1 1 1 1
}
node 15 3.0 2.0 3.5
fix 15 0 0 1 1 1 0
rigidDiaphragm 3 15 11 12 13 14
node 30 7.5 0.0 7.0
rigidLink beam 22 30
node 5 0.0 5.5 0.0
node 31 0.0 5.5 7.0
fix 5 1 1 1 1 1 1
rigidLink bar 24 31

uniaxialMaterial ElasticPP 1 2.0e5 [expr {60.0 / 2.0e5}]
uniaxialMaterial ElasticPP 2 3.0e5 [expr {80.0 / 3.0e5}] [expr {-70.0 / 3.0e5}]
uniaxialMaterial Elastic 3 8.0e5
uniaxialMaterial Elastic 4 4.0e4
foreach k {1 2 3} {
    equalDOF $k [expr {100 + $k}] 1 2 3 6
    element zeroLength [expr {200 + $k}] $k [expr {100 + $k}] -mat 1 2 -dir 4 5
}
element zeroLength 204 4 104 -mat 3 3 3 4 4 4 -dir 1 2 3 4 5 6

geomTransf Linear 1 1.0 0.0 0.0
geomTransf Linear 2 0.0 1.0 0.0
geomTransf Linear 3 0.0 0.0 1.0
geomTransf Linear 4 0.6 0.8 0.0
set A 0.2; set Iy [expr {0.4 * pow(0.5, 3) / 12}]; set Iz [expr {0.5 * pow(0.4, 3) / 12}]; set J 3.0e-3
set tag 1
foreach {k transf} {1 1 2 2 3 4 4 1} {
    element elasticBeamColumn $tag [expr {100 + $k}] [expr {10 + $k}] $A $E $G $J $Iy $Iz $transf
    element elasticBeamColumn [expr {$tag + 1}] [expr {10 + $k}] [expr {20 + $k}] $A $E $G $J [expr {0.8 * $Iy}] $Iz $transf
    incr tag 2
}
foreach {i j} {1 2 2 3 3 4 4 1} {
    foreach floor {10 20} {
        element elasticBeamColumn $tag [expr {$floor + $i}] [expr {$floor + $j}] 0.15 $E $G 2e-3 3.1e-3 1.6e-3 3
        incr tag
    }
}
element elasticBeamColumn $tag 5 31 0.05 $E $G 1e-4 4e-4 2e-4 1

set masses {11 8.0 12 12.0 13 20.0 14 8.0 21 6.0 22 9.0 23 14.0 24 6.0 31 1.0}
foreach {n m} $masses { mass $n $m $m $m 0.0 0.0 0.0 }
mass 30 4.0 4.0 4.0 0.5 0.8 1.2

timeSeries Linear 1
pattern Plain 1 1 {
    foreach {n m} $masses { load $n 0.0 0.0 [expr {-9.81 * $m}] 0.0 0.0 0.0 }
    load 30 0.0 0.0 [expr {-9.81 * 4.0}] 0.0 0.0 0.0
}
constraints Transformation
numberer RCM
system UmfPack
test NormDispIncr 1e-12 100
algorithm Newton
integrator LoadControl 1.0
analysis Static
if {[analyze 1] != 0} { error "gravity failed" }
loadConst -time 0.0

wipeAnalysis
rayleigh 0.4 0.002 0.0 0.0
timeSeries Path 2 -dt $dt -values $ax
timeSeries Path 3 -dt $dt -values $ay
pattern UniformExcitation 2 1 -accel 2
pattern UniformExcitation 3 2 -accel 3
constraints Transformation
numberer RCM
system UmfPack
test NormDispIncr 1e-12 100
algorithm Newton
integrator Newmark 0.5 0.25
analysis Transient

set names {u23 u30 col1 hinge201 basic10}
foreach name $names { set out($name) {} }
for {set k 0} {$k < $steps} {incr k} {
    if {[analyze 1 $dt] != 0} { error "analyze failed at step $k" }
    set out(u23) [concat $out(u23) [nodeDisp 23]]
    set out(u30) [concat $out(u30) [nodeDisp 30]]
    set out(col1) [concat $out(col1) [eleForce 1]]
    set out(hinge201) [concat $out(hinge201) [eleResponse 201 basicForce]]
    set out(basic10) [concat $out(basic10) [eleResponse 10 basicForce]]
}
set f [open results.txt w]
foreach name $names { puts $f "$name $out($name)" }
close $f
