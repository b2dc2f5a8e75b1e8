#!/usr/bin/env bash
# Regenerates the committed outputs of examples/force-curves and examples/thermal-tune
# (about half a minute on one core; docs/force-and-tune.md).
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../build/tiptap)
(cd force-curves && for m in matrix disk; do
   $t force ../../surfaces/polymer-blend.ini scene.ini --set force.material=$m -o $m.csv --plot $m.png -q >$m.txt
 done)
(cd thermal-tune && for l in soft medium stiff; do
   $t tune $l.ini -o $l.csv --plot $l.png -q >$l.txt
 done)
