#!/usr/bin/env bash
# A drive far from the resonance is refused before anything runs: one line naming the
# file, [cantilever] drive_frequency, the value and the range (0.1 to 10 times the
# resonance frequency), exit 1, no output; a drive at the range's ends runs. At 100 Hz a
# trace used to run for 63 s and report an energy balance of 2.7e11 with exit 0.
# usage: cli_drive_range.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

scene=$src/examples/extreme/setpoint-10.ini
for f in "1 mHz|1 Hz" "100 Hz|100 Hz" "29 kHz|29 kHz" "3.1 MHz|3100 kHz"; do
  value=${f%%|*} shown=${f##*|}
  printf '[cantilever]\ndrive_frequency = %s\n' "$value" >"$tmp/drive.ini"
  for cmd in trace approach; do
    expect_exact "$cmd at $value" \
      "tiptap: $tmp/drive.ini: [cantilever] drive_frequency: ${shown/1 Hz/0.001 Hz} is outside 30 to 3000 kHz (0.1 to 10 times the resonance_frequency: tapping drives near resonance, docs/physics.md)" \
      "$tiptap" $cmd "$scene" "$tmp/drive.ini" -o "$tmp/$cmd.csv"
    [ -e "$tmp/$cmd.csv" ] && bad "$cmd at $value wrote $tmp/$cmd.csv" || ok "$cmd at $value: no output"
  done
  expect_error "scan at $value" "[cantilever] drive_frequency: ${shown/1 Hz/0.001 Hz} is outside 30 to 3000 kHz" \
    "$tiptap" scan "$scene" "$tmp/drive.ini" -o "$tmp/scan"
  [ -e "$tmp/scan" ] && bad "scan at $value made its folder" || ok "scan at $value: no folder"
done

# the range's ends run, with a finite error estimate
for value in "30 kHz" "3 MHz"; do
  out=$("$tiptap" trace "$scene" --set "cantilever.drive_frequency=$value" --set trace.settle_cycles=0 \
    --set trace.cycles=2 -o "$tmp/end.csv" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ] && grep -qE '^error_estimate_deflection_rel = [0-9.e+-]+ ' <<<"$out"; then
    ok "drive at $value runs"
  else
    bad "drive at $value: rc=$rc '$out'"
  fi
done
exit $fail
