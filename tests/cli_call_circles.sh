#!/usr/bin/env bash
# No call circle among the files of src/instrument (issue 29: the scan's files called
# one another both ways), from the build's object files (scripts/call-circles.py).
# usage: cli_call_circles.sh path/to/tiptap source_dir
set -u
build=$(dirname "$(realpath "$1")")
src=$2
source "$(dirname "$0")/tt_cli.sh"
command -v nm >/dev/null && command -v python3 >/dev/null || { echo "not checked: no nm or python3"; exit 0; }
out=$(python3 "$src/scripts/call-circles.py" "$build" instrument 2>&1)
if [ $? -eq 0 ]; then ok "$out"; else bad "$out"; fi
exit $fail
