#!/usr/bin/env bash
# Periodic orbits in the program's tables (docs/dynamics.md, Settling): the standard
# cantilever over the polymer blend's soft, sticky matrix at 5 and 6 nm jumps in three
# cycles of four. `tiptap sweep --run steady` says found=periodic, period 4, settled 1,
# with the mean dissipation over the orbit (10.5 and 11.6 aJ; one cycle of the orbit
# read 0 or 15.5 aJ before, beside found=settled and settled 0), and warns naming the
# combinations; `tiptap approach` has the period column and warns naming the points.
# usage: cli_periodic.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
blend=("$src/scans/standard.ini" "$src/surfaces/polymer-blend.ini")
printf '[approach]\nmaterial = matrix\n' >"$tmp/m.ini"

"$tiptap" sweep "${blend[@]}" "$tmp/m.ini" --vary approach.from=5nm,6nm --run steady -o "$tmp/s.csv" -q \
  2>"$tmp/s.err" && ok "sweep runs" || bad "sweep: $(cat "$tmp/s.err")"
head -n 1 "$tmp/s.csv" | grep -q ",settled,cycles,period,found$" && ok "sweep: period column before found" ||
  bad "header: $(head -n 1 "$tmp/s.csv")"
# columns: 3 z_nm, 10 dissipated_aJ, 15 settled, 17 period, 18 found
rows=$(awk -F, 'NR > 1 { printf "%s %s %s %s;", $3, $15, $17, $18 }' "$tmp/s.csv")
[ "$rows" = "5 1 4 periodic;6 1 4 periodic;" ] && ok "sweep: found=periodic, period 4, settled" ||
  bad "rows: $rows"
awk -F, 'NR > 1 && ($10 < 10 || $10 > 12) { bad = 1 } END { exit bad }' "$tmp/s.csv" &&
  ok "sweep: dissipated the orbit's mean (10 to 12 aJ)" || bad "dissipated: $(cut -d, -f3,10 "$tmp/s.csv")"
grep -qx "tiptap sweep: warning: 2 of 2 points are periodic orbits of more than one cycle, not steady oscillations (found=periodic; combinations 1, 2): .*" "$tmp/s.err" &&
  ok "sweep: warns naming the combinations, under -q" || bad "sweep warning: $(cat "$tmp/s.err")"

"$tiptap" approach "${blend[@]}" "$tmp/m.ini" --set approach.from=7nm --set approach.to=5nm \
  --set approach.points=3 -o "$tmp/a.csv" -q 2>"$tmp/a.err" && ok "approach runs" || bad "approach: $(cat "$tmp/a.err")"
head -n 1 "$tmp/a.csv" | grep -q ",deflection_max_nm,period$" && ok "approach: period column" ||
  bad "header: $(head -n 1 "$tmp/a.csv")"
[ "$(awk -F, 'NR > 1 { printf "%s ", $16 }' "$tmp/a.csv")" = "4 4 4 " ] && ok "approach: period 4 at 7, 6, 5 nm" ||
  bad "periods: $(cut -d, -f1,16 "$tmp/a.csv")"
grep -q "^tiptap approach: warning: 3 of 3 points are periodic orbits .*(z = 7 (period 4), 6 (period 4), 5 (period 4) nm)" "$tmp/a.err" &&
  ok "approach: warns naming the points" || bad "approach warning: $(cat "$tmp/a.err")"
exit $fail
