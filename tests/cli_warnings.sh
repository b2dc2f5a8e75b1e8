#!/usr/bin/env bash
# The library decides the warnings and the program prints each as "tiptap CMD: warning:
# MESSAGE" (util/warning.h), also under -q: an approach's points not settled and a scan's
# z piezo at the end of its range read so, like every other warning; a run without
# cause gives none.
# usage: cli_warnings.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

vac=$src/examples/extreme/vacuum-q1e4.ini
out=$("$tiptap" approach "$vac" --set approach.points=2 --set approach.steady=settle \
  --set approach.max_cycles=100 -o "$tmp/a.csv" -q 2>&1 >/dev/null)
[ "$out" = "tiptap approach: warning: 2 of 2 points found no period up to 64 cycles within max_cycles = 100 (z = 22, 2 nm): their rows are the means over their last 64 cycles (period 0); chaos, or raise [approach] max_cycles" ] &&
  ok "approach: unsettled points, under -q too" || bad "approach: '$out'"

quick=("$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini" --set scan.pixels=16 --set scan.lines=2)
out=$("$tiptap" scan "${quick[@]}" --set feedback.z_range=0.5nm -o "$tmp/z" -q 2>&1 >/dev/null)
grep -qx "tiptap scan: warning: the z piezo reached the end of its range (\[feedback\] z_range)" <<<"$out" &&
  ok "scan: the z piezo's range, under -q too" || bad "scan z_range: '$out'"
out=$("$tiptap" scan "${quick[@]}" -o "$tmp/q" -q 2>&1 >/dev/null)
grep -q "z piezo" <<<"$out" && bad "the default z_range warned: '$out'" || ok "scan: no z piezo warning within the range"
# every warning line names its command
out=$("$tiptap" scan "${quick[@]}" --set feedback.z_range=0.5nm -o "$tmp/z2" 2>&1 >/dev/null)
n=$(grep -c "warning:" <<<"$out")
m=$(grep -c "^tiptap scan: warning: " <<<"$out")
[ "$n" -ge 2 ] && [ "$n" -eq "$m" ] && ok "$n warning lines, each 'tiptap scan: warning: '" || bad "warning lines: '$out'"
exit $fail
