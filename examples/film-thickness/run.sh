#!/usr/bin/env bash
# Regenerates this example's committed outputs (about half a minute on two cores): the
# steady points against the film's thickness (sweep.csv: elastic and viscous; sweep.png:
# the viscous film) and the scan of bulk and 5 nm film stripes (out/).
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../../build/tiptap)
q=../../scans/quick.ini
h="material.film.film_thickness=log:3nm:300nm:11"
$t sweep $q scene.ini --vary "material.film.viscosity=0 Pa s,300 Pa s" --vary "$h" \
   --run setpoint -o sweep.csv -q
$t sweep $q scene.ini --vary "$h" --run setpoint -o /tmp/tt-film.$$.csv --plot sweep.png -q
rm -f /tmp/tt-film.$$.csv
$t scan $q scene.ini -q -o /tmp/tt-film.$$
mkdir -p out
for f in height_trace.png phase_trace.png dissipation_viscous_trace.png profile.csv; do
  cp /tmp/tt-film.$$/$f out/
done
rm -rf /tmp/tt-film.$$
