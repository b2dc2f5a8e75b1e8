#!/usr/bin/env bash
# A scene setting that cannot work is refused before anything runs: one line on stderr,
# nothing on stdout, no estimate or progress line before it, no output file or folder
# made (issue 19, item 4). Each case was refused only after the run's first lines.
# usage: cli_refusal_order.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/s.ini" <<'INI'
[material silicon]
reduced_modulus = 100 GPa
[scan]
size = 100 nm
pixels = 16
lines = 2
line_rate = 100 Hz
settle_cycles = 10
channels = height, error, phase
[trace]
cycles = 20
[approach]
points = 20
INI

refused() { # name, expected fragment, output path that must not appear, command...
  local name=$1 frag=$2 made=$3; shift 3
  local err rc
  err=$("$@" 2>&1 >"$tmp/stdout"); rc=$?
  if [ $rc -ne 1 ]; then bad "$name: exit $rc, not 1"; return; fi
  if [ "$(printf '%s\n' "$err" | wc -l)" -ne 1 ]; then bad "$name: not one line: $err"; return; fi
  if ! grep -qF -- "$frag" <<<"$err"; then bad "$name: '$err' lacks '$frag'"; return; fi
  if [ -s "$tmp/stdout" ]; then bad "$name: printed on stdout"; return; fi
  if [ -e "$made" ]; then bad "$name: made $made"; return; fi
  ok "$name"
}

# rk4 too coarse for the contact: refused by the solver at its first step, after the
# estimate line (a scan made its folder and scene.ini; an approach wrote 38 rows)
rk4=(--set solver.method=rk4 --set solver.steps_per_cycle=8)
want="--set: [solver] steps_per_cycle: 8 steps a cycle are too few for rk4 on [material silicon]: its contact stiffens to 1.13e+03 N/m"
refused "scan, rk4 too coarse" "$want" "$tmp/scan" "$tiptap" scan "$tmp/s.ini" -o "$tmp/scan" "${rk4[@]}"
refused "trace, rk4 too coarse" "$want" "$tmp/t.csv" "$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" "${rk4[@]}"
refused "approach, rk4 too coarse" "at least 14 steps a cycle" "$tmp/a.csv" \
  "$tiptap" approach "$tmp/s.ini" -o "$tmp/a.csv" "${rk4[@]}"
# the figure it names is enough: 14 steps run (and the solver's own check agrees)
"$tiptap" trace "$tmp/s.ini" -o "$tmp/t14.csv" -q --set solver.method=rk4 --set solver.steps_per_cycle=14 &&
  ok "rk4 at the steps named runs" || bad "rk4 at 14 steps failed"
# a rest position inside the sample presses deeper: more steps needed
out=$("$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" -q --set solver.method=rk4 --set solver.steps_per_cycle=14 \
  --set "trace.separation=-20 nm" 2>&1)
grep -qF "a tip of 40 nm amplitude can press into it" <<<"$out" && ok "rk4: a rest inside the sample counts" ||
  bad "rk4 below the surface: '$out'"
# interaction damping outpacing the step
refused "rk4 and interaction damping" "its interaction damping (interaction_quality_factor = 0.01) acts 100 times faster than the drive, and rk4 follows that only with at least 252 steps a cycle" "$tmp/t.csv" \
  "$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" --set solver.method=rk4 --set solver.steps_per_cycle=64 \
  --set material.silicon.interaction_quality_factor=0.01

# a pixel shorter than a lock-in block: NaN amplitude and phase pixels, exit 0
refused "pixel shorter than a lock-in block" \
  "--set: [scan] line_rate: 3000 Hz gives a pixel as few as 3 drive cycles (50 each way along a line of [scan] pixels = 16 at 300 kHz), fewer than [lockin] periods_per_block = 4" \
  "$tmp/ppb" "$tiptap" scan "$tmp/s.ini" -o "$tmp/ppb" --set "scan.line_rate=3000 Hz"
out=$("$tiptap" scan "$tmp/s.ini" -o "$tmp/ppb" --set "scan.line_rate=3000 Hz" 2>&1)
grep -qF "at most 2343.75 Hz" <<<"$out" && ok "the largest line rate named" || bad "no largest rate: '$out'"
# ... and that rate runs with every pixel finite
"$tiptap" scan "$tmp/s.ini" -o "$tmp/fast" -q --set "scan.line_rate=2343.75 Hz" &&
  ! grep -qi nan "$tmp/fast/profile.csv" && ok "at the rate named every pixel is finite" ||
  bad "2343.75 Hz: $(grep -ci nan "$tmp/fast/profile.csv") NaN rows"
refused "a smaller block is named too" "[lockin] periods_per_block = 8" "$tmp/ppb" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/ppb" --set "scan.line_rate=2000 Hz" --set lockin.periods_per_block=8

# with the line rate left at its default, the key the scene set is named
printf '[scan]\nlines = 2\n' >"$tmp/slow.ini"
refused "block check named on the drive set" \
  "--set: [cantilever] drive_frequency: [scan] line_rate = 1 Hz gives a pixel as few as 3 drive cycles (500 each way along a line of [scan] pixels = 128 at 1 kHz)" \
  "$tmp/slow" "$tiptap" scan "$tmp/slow.ini" -o "$tmp/slow" --set "cantilever.drive_frequency=1 kHz" \
  --set "cantilever.resonance_frequency=1 kHz"

# the scan's own checks (its map file) came after the estimate and the unused-material
# warning
printf '[surface]\nmap = png\nmap_png = nosuch.png\n' >"$tmp/png.ini"
refused "missing map file" "png.ini: [surface] map_png: $tmp/nosuch.png: cannot open PNG map: No such file or directory" "$tmp/png" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/png.ini" -o "$tmp/png"

# a ramp end the scene cannot take: refused after the cycles before it, now up front
cat >"$tmp/ramp.ini" <<'INI'
[material soft]
reduced_modulus = 10 GPa
adhesion_energy = 50 mJ/m^2
[trace]
cycles = 4
settle_cycles = 4
ramp = material.soft.reduced_modulus
ramp_from = 10 GPa
ramp_to = 1 kPa
INI
refused "ramp_to refused up front" \
  "ramp.ini: [trace] ramp_to: [material soft] reduced_modulus: 1000 Pa gives lambda = 1.55e+04" \
  "$tmp/r.csv" "$tiptap" trace "$tmp/ramp.ini" -o "$tmp/r.csv"
exit $fail
