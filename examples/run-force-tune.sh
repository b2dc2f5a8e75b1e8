#!/usr/bin/env bash
# Regenerates the committed outputs of examples/force-curves, examples/force-volume and
# examples/thermal-tune (about two minutes of processor time, most of it the force
# volume's; docs/force-and-tune.md).
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../build/tiptap)
(cd force-curves && for m in matrix disk; do
   $t force ../../surfaces/polymer-blend.ini scene.ini --set force.material=$m -o $m.csv --plot $m.png -q >$m.txt
 done
 # the viscoelastic rubber at two ramp speeds; the loop's energy, -(closed integral of
 # F d(separation)) over approach and retract, appended to what the command printed
 for s in slow:0.1 fast:2; do
   $t force scene.ini viscoelastic.ini --set force.speed=${s#*:}um/s -o visco-${s%:*}.csv \
     --plot visco-${s%:*}.png -q >visco-${s%:*}.txt
   awk -F, 'NR > 1 && $8 != "dwell" { if ($8 == p) w -= ($5 + f) / 2 * ($4 - x); p = $8; x = $4; f = $5 }
     END { printf "loop_energy_aJ = %.4g\n", w }' visco-${s%:*}.csv >>visco-${s%:*}.txt
 done)
(cd force-volume && $t force ../../surfaces/polymer-blend.ini scene.ini --volume -o maps -j 2 -q >run.txt)
(cd thermal-tune && for l in soft medium stiff beam; do
   $t tune $l.ini -o $l.csv --plot $l.png -q >$l.txt
 done)
