#!/usr/bin/env bash
# tiptap sweep --run setpoint says when the setpoint was not reached: at Q = 1 the
# amplitude on the stiff disk never comes down to 5 % of 20 nm (1 nm), and at Q = 1e4
# the points do not settle within max_cycles, so no point of the search holds 50 %;
# those rows say found=unreachable (with the closest point, its amplitude away from the
# setpoint by more than the search's 1e-3 of A0) and stderr names their combinations;
# the setpoints that are reached keep their amplitude within 1e-3 of A0 and say how they
# were found.
# usage: cli_sweep_setpoint.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
cd "$tmp" || exit 1
blend=$src/surfaces/polymer-blend.ini

"$tiptap" sweep "$blend" --set approach.material=disk --vary "cantilever.quality_factor=1,400,1e4" \
  --vary "feedback.setpoint=5%,50%" --run setpoint -j 2 -q -o sp.csv 2>sp.err
rc=$?
[ $rc -eq 0 ] && ok "the sweep goes on and exits 0" || bad "exit $rc: $(cat sp.err)"
# columns: 2 Q, 3 setpoint, 4 setpoint_nm, 6 amplitude_nm, last found
awk -F, 'NR > 1 { d = $6 - $4; if (d < 0) d = -d; print $1, $NF, (d > 0.02) }' sp.csv >verdicts
# combination 1 (Q 1, 5 %) and 6 (Q 1e4, 50 %) away from the setpoint and marked
grep -qx '1 unreachable 1' verdicts && ok "Q 1 at 5 %: found=unreachable, amplitude away from 1 nm" ||
  bad "Q 1 at 5 %: $(sed -n 2p sp.csv)"
grep -qx '6 unreachable 1' verdicts && ok "Q 1e4 at 50 %: found=unreachable" || bad "Q 1e4 at 50 %: $(sed -n 7p sp.csv)"
# the class: a row is marked exactly when its amplitude misses the setpoint
awk '($2 == "unreachable") != ($3 == 1) {bad = 1} END {exit bad}' verdicts &&
  ok "marked exactly where the amplitude misses the setpoint by over 1e-3 of A0" || bad "verdicts: $(cat verdicts)"
grep -qE '^(3|4) (newton|settled) 0$' verdicts && [ "$(grep -c ' 0$' verdicts)" -ge 2 ] &&
  ok "reached setpoints keep newton or settled" || bad "reached: $(cat verdicts)"
unreached=$(awk '$2 == "unreachable" {printf "%s%s", n++ ? ", " : "", $1}' verdicts)
grep -qx "tiptap sweep: warning: the setpoint was not reached in $(grep -c unreachable verdicts) of 6 combinations (found=unreachable; each row holds the closest point): $unreached" sp.err &&
  ok "stderr names the combinations ($unreached), also with -q" || bad "warning: $(cat sp.err)"
exit $fail
