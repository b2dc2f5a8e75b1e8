#!/usr/bin/env bash
# The error estimate takes two phases a turn apart as the same phase: twice the largest
# difference of two phases, each difference reduced to within half a turn, is at most
# 360 deg. The lesson's 40 Hz lines (the averaged tier, its companion on the envelope
# tier) press the oscillation nearly to a stop at the grating's walls, where its phase
# lands anywhere: before the reduction their estimate read 550 deg at its largest.
# usage: cli_estimate_phase.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

ft=$src/examples/feedback-tuning
out=$("$tiptap" scan "$src/scans/standard.ini" "$src/surfaces/grating.ini" "$ft/common.ini" \
      "$ft/line-rate-fast.ini" --set scan.lines=2 -o "$tmp/s" 2>&1 >/dev/null) ||
  { bad "line-rate-fast, 2 lines: failed: $(tail -1 <<<"$out")"; exit 1; }
line=$(grep "^error_estimate_phase_deg = " <<<"$out")
rms=$(sed -n 's/^error_estimate_phase_deg = \([^ ]*\) (rms; max \([^)]*\)).*/\1/p' <<<"$line")
max=$(sed -n 's/^error_estimate_phase_deg = \([^ ]*\) (rms; max \([^)]*\)).*/\2/p' <<<"$line")
if [ -z "$max" ]; then
  bad "no error_estimate_phase_deg line: $out"
elif awk -v r="$rms" -v m="$max" 'BEGIN { exit !(m > 1 && m <= 360 && r > 0 && r <= m) }'; then
  ok "line-rate-fast, 2 lines: phase estimate $rms deg rms, $max deg at its largest (at most 360)"
else
  bad "line-rate-fast, 2 lines: phase estimate $rms deg rms, $max deg at its largest: over a turn"
fi
exit $fail
