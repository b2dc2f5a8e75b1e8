#!/usr/bin/env bash
# Regenerates docs/accuracy-*.png, .csv and .txt (the summaries): the work-precision
# diagrams of docs/accuracy.md (about four minutes on two cores). Run times depend on
# the machine and its load; the errors do not.
set -euo pipefail
cd "$(dirname "$0")/.."
t=build/tiptap
run() { # name, arguments...
  local name=$1; shift
  "$t" accuracy "$@" -o "docs/accuracy-$name.csv" --plot "docs/accuracy-$name.png" \
    >"docs/accuracy-$name.txt" 2>&1
  sed -i "1i \$ tiptap accuracy $* -o docs/accuracy-$name.csv --plot docs/accuracy-$name.png" \
    "docs/accuracy-$name.txt"
}
run standard scans/standard.ini surfaces/polymer.ini --point 16nm --repeats 7 --clock cpu
run standard-scan scans/standard.ini surfaces/polymer.ini --clock cpu
run fig4a examples/seed-fig4a/scene.ini --set "cantilever.free_amplitude=150 nm" --repeats 7 --clock cpu
run edges scans/standard.ini surfaces/edges.ini --methods dopri5,envelope --pixels 64 --repeats 3 --clock cpu
