#!/usr/bin/env bash
# Runs every committed example (Burnham et al.'s figures, extreme scenes, imaging
# examples, the README's main job) with the tiptap binary given, writing all outputs
# under OUTDIR.
# Used with scripts/compare-outputs.sh to prove a refactor changes no output byte.
#   scripts/regenerate-all.sh BINARY OUTDIR [quick]
# "quick" skips the imaging examples (the slow part).
set -euo pipefail
bin=$(realpath "$1"); out=$(realpath -m "$2"); mode=${3:-full}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
cd "$root/examples"
t=$bin; o=$out
(cd seed-fig3 && for l in 1 3; do $t contact --lambda $l --plot $o/contact-lambda$l.png -o $o/contact-lambda$l.csv >$o/summary-lambda$l.txt 2>/dev/null; done)
(cd seed-fig3 && $t contact --lambda 1 --model jkr -o $o/contact-jkr.csv >$o/summary-jkr.txt 2>/dev/null)
(cd seed-fig4a && $t approach scene.ini -o $o/fig4a-approach.csv --plot $o/fig4a-approach.png 2>/dev/null)
(cd seed-fig4b && $t trace scene.ini -o $o/fig4b-trace.csv --plot $o/fig4b-trace.png 2>/dev/null)
(cd seed-fig5 && for w in 2 37 72; do
   $t trace scene.ini --set "material.glass.adhesion_energy=$w mJ/m^2" -o $o/trace-w$w.csv --plot $o/trace-w$w.png 2>/dev/null
   $t approach scene.ini --set "material.glass.adhesion_energy=$w mJ/m^2" -o $o/approach-w$w.csv 2>/dev/null
 done)
(cd extreme && $t approach bistable.ini -o $o/bistable-approach.csv --plot $o/bistable-approach.png 2>/dev/null)
(cd extreme && for f in *.ini; do
   [ "$f" = bistable.ini ] && continue
   $t contact "$f" >$o/extreme-contact-${f%.ini}.txt 2>/dev/null || echo "exit $?" >>$o/extreme-contact-${f%.ini}.txt
 done)
$t keys >$o/keys.txt
$t keys --markdown >$o/keys.md
cd "$root"
$t scan scans/quick.ini surfaces/polymer-blend.ini -o $o/quick-blend 2>/dev/null
for s in steps particles rough png-map grating; do
  # particles: a smaller field, so that 4 lines still resolve the spheres
  size=(); [ $s = particles ] && size=(--set "scan.size=100 nm" --set surface.particle_count=3)
  $t scan scans/quick.ini surfaces/$s.ini --set scan.pixels=16 --set scan.lines=4 "${size[@]}" -o $o/quick-$s 2>/dev/null
done
if [ "$mode" != quick ]; then
  $t scan scans/standard.ini surfaces/polymer-blend.ini examples/polymer-blend/scan.ini -o $o/polymer-blend 2>/dev/null
  $t scan scans/standard.ini surfaces/grating.ini examples/grating/scan.ini -o $o/grating 2>/dev/null
  for s in gain-low gain-right gain-ringing gain-unstable line-rate-fast; do
    $t scan scans/standard.ini surfaces/grating.ini examples/feedback-tuning/common.ini \
       examples/feedback-tuning/$s.ini -o $o/$s 2>/dev/null
  done
fi
