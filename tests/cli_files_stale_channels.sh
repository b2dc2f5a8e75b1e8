#!/usr/bin/env bash
# A scan into a folder holding another run's channel files that it does not write (an
# earlier run with more channels) removes them once its own files are written and names
# them on stderr (issue 19: they stayed, mixed with the new run's); only the names tiptap
# writes are touched. A scan that fails removes nothing.
# usage: cli_files_stale_channels.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

"$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q --set "scan.channels=height, phase, error" ||
  bad "the first scan"
echo notes >"$tmp/out/phase_notes.txt"
echo mine >"$tmp/out/phase_trace.gsf.bak"
echo precious >"$tmp/precious"
rm "$tmp/out/error_retrace.png"
ln -s "$tmp/precious" "$tmp/out/error_retrace.png"
# a failed run keeps the earlier files
"$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q --set scan.channels=height --set "material.ring.map_value=#00ff00" \
  2>/dev/null && bad "the map with an unnamed colour scanned"
[ -e "$tmp/out/phase_trace.gsf" ] && ok "a refused scan removes nothing" || bad "a refused scan removed files"
out=$("$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q --set scan.channels=height 2>&1); rc=$?
want="tiptap: $tmp/out: removed 8 files of an earlier run with channels this run does not write: error_trace.gsf, error_trace.png, error_retrace.gsf, error_retrace.png, phase_trace.gsf, phase_trace.png, phase_retrace.gsf, phase_retrace.png"
[ $rc -eq 0 ] && [ "$out" = "$want" ] && ok "stale files named" || bad "rc $rc, '$out'"
left=$(cd "$tmp/out" && ls -A | tr '\n' ' ')
[ "$left" = "height_retrace.gsf height_retrace.png height_trace.gsf height_trace.png phase_notes.txt phase_trace.gsf.bak profile.csv scan.gwy scene.ini scope.csv scope.png " ] &&
  ok "the folder holds this run's files and the user's" || bad "left: $left"
[ "$(cat "$tmp/precious")" = precious ] && ok "a stale link removed, its target kept" || bad "precious"
# the same in a sweep's combination folders
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa" --run scan)
"$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q || bad "first sweep"
[ -e "$tmp/w/0002/phase_trace.gsf" ] || bad "the sweep wrote no phase"
out=$("$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q --set scan.channels=height 2>&1); rc=$?
[ $rc -eq 0 ] && [ ! -e "$tmp/w/0001/phase_trace.gsf" ] && [ ! -e "$tmp/w/0002/phase_retrace.png" ] &&
  grep -qF "tiptap: $tmp/w/0002: removed 4 files" <<<"$out" && ok "sweep: stale files removed and named" ||
  bad "sweep: rc $rc, '$out'"
exit $fail
