#!/usr/bin/env bash
# Regenerates the committed outputs of the sweep examples (docs/sweeps.md): the polymer
# blend's material contrast against setpoint and free amplitude, and the cantilever
# choice (about half a minute on two cores).
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../build/tiptap)
(cd material-contrast && rm -f contrast.csv.partial &&
 $t sweep ../../surfaces/polymer-blend.ini scene.ini --vary "cantilever.free_amplitude=10nm,20nm,40nm,80nm" \
   --vary approach.material=matrix,disk --vary "feedback.setpoint=10%:95%:18" --run setpoint \
   --contrast approach.material -o contrast.csv --plot contrast.png -q)
(cd cantilever-choice && rm -f approach.csv.partial &&
 $t sweep ../../surfaces/polymer-blend.ini scene.ini --vary scene=soft.ini,standard.ini,stiff.ini \
   --vary approach.material=disk,matrix --run approach -o approach.csv --plot approach.png -q)
