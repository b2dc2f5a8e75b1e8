#!/usr/bin/env bash
# Regenerates this example's committed outputs (about 2 s on two cores).
set -euo pipefail
cd "$(dirname "$0")"
t=$(realpath ../../build/tiptap)
$t trace scene.ini -o trace.csv --plot trace.png
