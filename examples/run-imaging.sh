#!/usr/bin/env bash
# Regenerates the imaging examples' images (a few minutes on two cores).
set -euo pipefail
cd "$(dirname "$0")/.."
t=build/tiptap
$t scan scans/standard.ini surfaces/polymer-blend.ini examples/polymer-blend/scan.ini -o examples/polymer-blend/out
$t scan scans/standard.ini surfaces/grating.ini examples/grating/scan.ini -o examples/grating/out
for s in gain-low gain-right gain-high line-rate-fast; do
  $t scan scans/standard.ini surfaces/grating.ini examples/feedback-tuning/common.ini \
     examples/feedback-tuning/$s.ini -o examples/feedback-tuning/$s
done
for s in tip tilt drift piezo creep; do
  $t scan scans/standard.ini examples/instrument/common.ini examples/instrument/$s.ini \
     -o examples/instrument/$s
done
