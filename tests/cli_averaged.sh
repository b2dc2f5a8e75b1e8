#!/usr/bin/env bash
# The averaged tier on the command line: a bad [solver] tier names the three values; a
# scan on the averaged tier reports its tables and integrates nothing; a wall higher
# than the amplitude (the grating's 20 nm) collapses the oscillation, which the scan
# names in a warning; the standard polymer does not.
# usage: cli_averaged.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

"$tiptap" scan "$src/scans/quick.ini" "$src/surfaces/polymer.ini" --set solver.tier=fast \
  -o "$tmp/bad" 2>"$tmp/bad.err" >/dev/null
rc=$?
if [ $rc -ne 0 ] && grep -q "tier.*every|envelope|averaged" "$tmp/bad.err"; then
  ok "a bad tier names every|envelope|averaged"
else
  bad "bad tier: rc $rc, $(cat "$tmp/bad.err")"
fi

run() { # name surface: the scan's stderr in $tmp/name.err
  "$tiptap" scan "$src/scans/standard.ini" "$src/surfaces/$2.ini" --set scan.pixels=32 \
    --set scan.lines=1 --set scan.line_rate=8Hz --set solver.tier=averaged -o "$tmp/$1" \
    2>"$tmp/$1.err" >/dev/null
}
if run poly polymer && grep -q '^averaged_tables_s = ' "$tmp/poly.err" &&
   ! grep -q 'collapsed' "$tmp/poly.err" && ! grep -q '^cycles_integrated' "$tmp/poly.err"; then
  ok "polymer: tables reported, no collapse"
else
  bad "polymer: $(cat "$tmp/poly.err")"
fi
if run wall grating && grep -q 'warning: the oscillation collapsed in [0-9]* pixels\? (first: line 0, pixel' "$tmp/wall.err"; then
  ok "grating: $(grep -o 'collapsed in [0-9]* pixels\?' "$tmp/wall.err")"
else
  bad "grating: no collapse named: $(cat "$tmp/wall.err")"
fi
exit $fail
