#!/usr/bin/env bash
# The noise soak's short form (scripts/soak-noise.sh -x 0): the full noise set on 10 nm
# steps and on the flat standard polymer, seeds 1-4 each, every one to the end. Seed 1
# of the steps and seed 2 of the polymer stalled a line before the grazing-touch fix
# (docs/reliability.md, "Noise never stalls a scan"); the longer soak over seeds 1-200
# is `scripts/soak-noise.sh`.
# usage: cli_noise_soak.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
out=$(bash "$src/scripts/soak-noise.sh" -b "$tiptap" -s 1 -e 4 -x 0 2>&1)
rc=$?
echo "$out"
if [ $rc -eq 0 ] && grep -q "every seed ran to the end" <<<"$out"; then
  echo "1 passed, 0 failed"
else
  echo "0 passed, 1 failed"
  exit 1
fi
