#!/usr/bin/env bash
# Regenerates the committed outputs of the examples that reproduce Burnham et al.'s
# figures (examples/seed-fig*; docs/physics.md) and the bistability figure (about a
# minute on two cores); the imaging examples have run-imaging.sh.
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../build/tiptap)
(cd seed-fig3 && for l in 1 3; do $t contact --lambda $l --plot contact-lambda$l.png >summary-lambda$l.txt 2>/dev/null; done)
(cd seed-fig4a && $t approach scene.ini -o approach.csv --plot approach.png)
(cd seed-fig4b && $t trace scene.ini -o trace.csv --plot trace.png)
(cd seed-fig5 && for w in 2 37 72; do
   $t trace scene.ini --set "material.glass.adhesion_energy=$w mJ/m^2" -o trace-w$w.csv --plot trace-w$w.png
   $t approach scene.ini --set "material.glass.adhesion_energy=$w mJ/m^2" -o approach-w$w.csv
 done)
(cd extreme && $t approach bistable.ini -o bistable-approach.csv --plot bistable-approach.png)
