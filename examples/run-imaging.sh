#!/usr/bin/env bash
# Regenerates the imaging examples' images (a few minutes on two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
t=build/tiptap
$t scan scans/standard.ini surfaces/polymer-blend.ini examples/polymer-blend/scan.ini -o examples/polymer-blend/out
$t scan scans/standard.ini surfaces/grating.ini examples/grating/scan.ini -o examples/grating/out
$t scan scans/standard.ini surfaces/polymer-blend.ini examples/bimodal/scan.ini -o examples/bimodal/out
$t approach scans/standard.ini surfaces/polymer-blend.ini examples/bimodal/approach.ini -o examples/bimodal/out/approach.csv --plot examples/bimodal/out/approach.png
for s in gain-low gain-right gain-ringing gain-unstable line-rate-fast; do
  $t scan scans/standard.ini surfaces/grating.ini examples/feedback-tuning/common.ini \
     examples/feedback-tuning/$s.ini -o examples/feedback-tuning/$s
done
for s in tip tilt drift piezo creep; do
  $t scan scans/standard.ini examples/instrument/common.ini examples/instrument/$s.ini \
     -o examples/instrument/$s
done
# the tuning runs' profile lines in one figure
$t profiles -q --title "feedback tuning: trace, retrace and the true surface of the profile line" \
   -o examples/feedback-tuning/profiles.png examples/feedback-tuning/{gain-low,gain-right,gain-ringing,gain-unstable,line-rate-fast}
# creep on its own scale: the tracking error of the creep run and of the same scan on an
# ideal piezo, side by side
$t scan scans/standard.ini examples/instrument/common.ini examples/instrument/creep.ini \
   --set instrument.creep=0 -q -o /tmp/tt-ideal.$$
mkdir -p /tmp/tt-cmp.$$ && cp -r /tmp/tt-ideal.$$ /tmp/tt-cmp.$$/ideal-piezo && cp -r examples/instrument/creep /tmp/tt-cmp.$$/creep
$t profiles -q --minus-surface --range -1.5:2.5 \
   --title "creep: height - true surface of the profile line (walls cut off)" \
   -o examples/instrument/creep.png /tmp/tt-cmp.$$/creep /tmp/tt-cmp.$$/ideal-piezo
rm -rf /tmp/tt-ideal.$$ /tmp/tt-cmp.$$
# the ridge of README.md there: line-rate-fast without noise, independent lines, the scan
# ending on a wall (2 um; profile from the former example) and mid-line (2.25 um), both on
# the envelope tier the set ran on then (common.ini now gives the averaged one)
off="--set noise.temperature=0K --set noise.detector=0m/sqrt(Hz) --set noise.z_piezo=0m/sqrt(Hz)"
$t scan scans/standard.ini surfaces/grating.ini examples/feedback-tuning/common.ini \
   examples/feedback-tuning/line-rate-fast.ini $off --set scan.lines_mode=independent \
   --set solver.tier=envelope -q -o /tmp/tt-mid.$$
cp /tmp/tt-mid.$$/profile.csv examples/feedback-tuning/ridge/turnaround-mid-line/ && rm -rf /tmp/tt-mid.$$
$t profiles -q --title "line-rate-fast without noise: turnaround on a wall (2 um) and mid-line (2.25 um)" \
   -o examples/feedback-tuning/ridge.png examples/feedback-tuning/ridge/turnaround-on-a-wall \
   examples/feedback-tuning/ridge/turnaround-mid-line
# each scan's scope.csv holds a point per lock-in block (megabytes at 2 Hz): not
# committed; scope.png shows it, and the scan writes it again
find examples -name scope.csv -delete
# a tiptap image re-imaged as a measured surface; only its small files are committed
$t scan scans/quick.ini examples/measured-reimage/scene.ini -q -o examples/measured-reimage/out
$t profiles -q --title "re-imaged at 1 Hz: trace, retrace and the input (the 4 Hz scan's height)" \
   -o examples/measured-reimage/profiles.png examples/measured-reimage/out
find examples/measured-reimage/out -type f ! -name 'profile.csv' ! -name 'artefact_*.png' \
   ! -name 'height_trace.png' ! -name 'topography_trace.png' -delete
# a grating imaged by a blunt tip, re-imaged sharp as it is and with the blunt tip eroded
# out; only the profile lines and the blunt image (the others' input) are committed
e=examples/eroded-reimage
$t scan scans/quick.ini surfaces/grating.ini $e/blunt.ini -q -o $e/blunt
$t scan scans/quick.ini $e/raw.ini -q -o $e/raw
$t scan scans/quick.ini $e/eroded.ini -q -o $e/eroded
$t profiles -q --title "100 nm lines and trenches: a blunt tip's image, re-imaged sharp as it is (raw) and eroded first" \
   -o $e/profiles.png $e/blunt $e/raw $e/eroded
find $e/blunt -type f ! -name profile.csv ! -name height_trace.gsf -delete
find $e/raw $e/eroded -type f ! -name profile.csv -delete
