#!/usr/bin/env bash
# A run whose own error estimate says it is wrong (above 1e-3 of the free amplitude or
# 0.1 deg) says so in one warning line on stderr naming the key that tightens it:
# [solver] tolerance for dopri5 and radau, steps_per_cycle for rk4; scan, approach and
# trace alike. A run within those bounds gives none.
# usage: cli_estimate_warning.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

sp10=$src/examples/extreme/setpoint-10.ini
vac=$src/examples/extreme/vacuum-q1e4.ini
small=(--set scan.pixels=8 --set scan.lines=1 --set scan.line_rate=50Hz)

warns() { # name, expected key text ("" for none), command...
  local name=$1 key=$2; shift 2
  local out n
  out=$("$@" 2>&1 >/dev/null) || { bad "$name: failed: $(tail -1 <<<"$out")"; return; }
  n=$(grep -c "warning: the run's own error estimate is" <<<"$out")
  if [ -z "$key" ]; then
    [ "$n" -eq 0 ] && ok "$name: no warning" || bad "$name: warned: $out"
  elif [ "$n" -eq 1 ] && grep "warning: the run's own error estimate" <<<"$out" | grep -qF "$key"; then
    ok "$name: $(grep "warning: the run's own" <<<"$out")"
  else
    bad "$name: $n warning lines, wanted one naming '$key': $out"
  fi
}

# scan at Q 1e5 (the issue's case), loose and at rk4's few steps; and at the default
# (the figures depend on the tier, which at Q 1e5 is the envelope tier's since issue 20)
warns "scan Q 1e5 tolerance 1e-4" "of the free amplitude in amplitude and 1.4e+02 deg in phase (above 1e-3 of the free amplitude or 0.1 deg): tighten [solver] tolerance (now 0.0001)" \
  "$tiptap" scan "$vac" --set cantilever.quality_factor=1e5 --set solver.tolerance=1e-4 "${small[@]}" -o "$tmp/b2"
warns "scan rk4 16 steps" "raise [solver] steps_per_cycle (now 16)" \
  "$tiptap" scan "$vac" --set solver.method=rk4 --set solver.steps_per_cycle=16 "${small[@]}" -o "$tmp/c"
warns "scan at the default" "" "$tiptap" scan "$sp10" "${small[@]}" -o "$tmp/d"

warns "approach tolerance 1e-4" "deg in phase (above 1e-3 of the free amplitude or 0.1 deg): tighten [solver] tolerance (now 0.0001)" \
  "$tiptap" approach "$sp10" --set approach.points=4 --set solver.tolerance=1e-4 -o "$tmp/a.csv"
warns "approach at the default" "" "$tiptap" approach "$sp10" --set approach.points=4 -o "$tmp/b.csv"

warns "trace tolerance 1e-4" "tighten [solver] tolerance (now 0.0001)" \
  "$tiptap" trace "$sp10" --set trace.settle_cycles=100 --set solver.tolerance=1e-4 -o "$tmp/c.csv"
warns "trace rk4 16 steps" "raise [solver] steps_per_cycle (now 16)" \
  "$tiptap" trace "$sp10" --set trace.settle_cycles=100 --set solver.method=rk4 --set solver.steps_per_cycle=16 -o "$tmp/d.csv"
warns "trace at the default" "" "$tiptap" trace "$sp10" --set trace.settle_cycles=100 -o "$tmp/e.csv"

# -q: nothing on stderr, the estimate not run
out=$("$tiptap" trace "$sp10" --set solver.tolerance=1e-4 -q -o "$tmp/f.csv" 2>&1 >/dev/null)
[ -z "$out" ] && ok "quiet: no warning" || bad "quiet: '$out'"
exit $fail
