#!/usr/bin/env bash
# The run's own error estimate holds on every extreme scene (examples/extreme/*.ini), for
# each command that prints one: scan, approach and trace at the default setting each
# report an estimate at least as large as their difference from the same run at a
# 1000 times tighter tolerance (1e-11; the estimate's own companion runs at 1e-10, so
# the reference is not the companion). Small runs: 8 pixels of one line at 50 Hz, 4
# approach points, 300 settling cycles of the trace; differences within the CSVs' 9-digit
# rounding count as none.
# usage: cli_estimate_extreme.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

ref=1e-11
val() { sed -n "s/^$1 = \([^ ]*\).*/\1/p" "$2"; } # a stderr figure, the first word after =
# the CSVs print 9 digits: a difference within their rounding is none
rnd='function r(x, a, b) { a = a < 0 ? -a : a; b = b < 0 ? -b : b; x -= 1e-8 * (a > b ? a : b); return x > 0 ? x : 0 }'
ge() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 >= b + 0 && a != "") }'; }

for scene in "$src"/examples/extreme/*.ini; do
  n=$(basename "$scene" .ini)
  A0=$(sed -n 's/^free_amplitude *= *\([0-9.e+-]*\) nm.*/\1/p' "$scene")
  A0=${A0:-20}

  # scan: the profile line's height (m), error (m) and phase (deg), trace and retrace
  # (profile.csv: position, then height, error, amplitude, phase, ... each trace, retrace)
  set -- --set scan.pixels=8 --set scan.lines=1 --set scan.line_rate=50Hz
  if "$tiptap" scan "$scene" "$@" -o "$tmp/s-$n" 2>"$tmp/s-$n.err" >/dev/null &&
     "$tiptap" scan "$scene" "$@" --set solver.tolerance=$ref -o "$tmp/r-$n" -q 2>/dev/null >/dev/null; then
    meas=$(paste -d, "$tmp/s-$n/profile.csv" "$tmp/r-$n/profile.csv" | awk -F, -v A0="$A0" "$rnd"'
      function d(a, b) { return r(a > b ? a - b : b - a, a, b) }
      NR > 1 { for (c = 2; c <= 3; c++) if (d($c, $(c+15)) > h) h = d($c, $(c+15))
               for (c = 4; c <= 5; c++) if (d($c, $(c+15)) / (A0 * 1e-9) > a) a = d($c, $(c+15)) / (A0 * 1e-9)
               for (c = 8; c <= 9; c++) { x = d($c, $(c+15)); if (x > 180) x = 360 - x; if (x > p) p = x } }
      END { printf "%.3g %.3g %.3g", h, a, p }')
    set -- $meas
    eh=$(sed -n 's/^error_estimate_height_m = .*max \([^)]*\)).*/\1/p' "$tmp/s-$n.err")
    ea=$(sed -n 's/^error_estimate_amplitude_rel = .*max \([^)]*\)).*/\1/p' "$tmp/s-$n.err")
    ep=$(sed -n 's/^error_estimate_phase_deg = .*max \([^)]*\)).*/\1/p' "$tmp/s-$n.err")
    if ge "$eh" "$1" && ge "$ea" "$2" && ge "$ep" "$3"; then
      ok "scan $n: estimate $eh m, $ea, $ep deg >= measured $1 m, $2, $3 deg"
    else
      bad "scan $n: estimate '$eh' m, '$ea', '$ep' deg below measured $1 m, $2, $3 deg"
    fi
  else
    bad "scan $n: failed: $(tail -1 "$tmp/s-$n.err")"
  fi

  # approach: amplitude (relative to A0) and phase of the points settled in both runs
  set -- --set approach.points=4
  if "$tiptap" approach "$scene" "$@" -o "$tmp/a-$n.csv" 2>"$tmp/a-$n.err" &&
     "$tiptap" approach "$scene" "$@" --set solver.tolerance=$ref -o "$tmp/b-$n.csv" -q; then
    meas=$(paste -d, "$tmp/a-$n.csv" "$tmp/b-$n.csv" | awk -F, -v A0="$A0" "$rnd"'
      function d(a, b) { return r(a > b ? a - b : b - a, a, b) }
      NR > 1 && $10 == 1 && $25 == 1 { x = d($2, $17) / A0; if (x > a) a = x
                                       x = d($3, $18); if (x > 180) x = 360 - x; if (x > p) p = x }
      END { printf "%.3g %.3g", a, p }')
    set -- $meas
    ea=$(val error_estimate_amplitude_rel "$tmp/a-$n.err")
    ep=$(val error_estimate_phase_deg "$tmp/a-$n.err")
    if ge "$ea" "$1" && ge "$ep" "$2"; then
      ok "approach $n: estimate $ea, $ep deg >= measured $1, $2 deg"
    else
      bad "approach $n: estimate '$ea', '$ep' deg below measured $1, $2 deg"
    fi
  else
    bad "approach $n: failed: $(tail -1 "$tmp/a-$n.err")"
  fi

  # trace: the deflection samples, relative to A0
  set -- --set trace.settle_cycles=300
  if "$tiptap" trace "$scene" "$@" -o "$tmp/t-$n.csv" 2>"$tmp/t-$n.err" &&
     "$tiptap" trace "$scene" "$@" --set solver.tolerance=$ref -o "$tmp/u-$n.csv" -q; then
    meas=$(paste -d, "$tmp/t-$n.csv" "$tmp/u-$n.csv" | awk -F, -v A0="$A0" "$rnd"'
      NR > 1 { x = r($5 > $14 ? $5 - $14 : $14 - $5, $5, $14) / A0; if (x > m) m = x }
      END { printf "%.3g", m }')
    ed=$(val error_estimate_deflection_rel "$tmp/t-$n.err")
    if ge "$ed" "$meas"; then
      ok "trace $n: estimate $ed >= measured $meas"
    else
      bad "trace $n: estimate '$ed' below measured $meas"
    fi
  else
    bad "trace $n: failed: $(tail -1 "$tmp/t-$n.err")"
  fi
done
exit $fail
