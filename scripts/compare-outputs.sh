#!/usr/bin/env bash
# Proves a change leaves every output byte as it was: runs scripts/regenerate-all.sh
# with a reference binary (built from another commit) and with this tree's binary,
# then compares the two folders file by file.
#   scripts/compare-outputs.sh REFERENCE_BINARY [NEW_BINARY] [quick]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
ref=$1; new=${2:-$root/build/tiptap}; mode=${3:-full}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$root/scripts/regenerate-all.sh" "$ref" "$work/ref" "$mode"
"$root/scripts/regenerate-all.sh" "$new" "$work/new" "$mode"
if diff -r "$work/ref" "$work/new" >"$work/diff"; then
  echo "identical: $(find "$work/ref" -type f | wc -l) files"
else
  head -40 "$work/diff"; echo "outputs differ"; exit 1
fi
