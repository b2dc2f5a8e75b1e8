#!/usr/bin/env bash
# tiptap scan and trace from the command line: the files written, a re-runnable
# effective scene, Ctrl-C keeping finished lines, bad output folders, trace ramps.
# usage: cli_scan.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

small_scan "500 nm" 8 4
"$tiptap" scan "$src/surfaces/png-map.ini" "$tmp/s.ini" -o "$tmp/out" -q || bad "scan ran"
for ch in height amplitude phase peak_force indentation dissipation; do
  for d in trace retrace; do
    [ -s "$tmp/out/${ch}_$d.gsf" ] && [ -s "$tmp/out/${ch}_$d.png" ] || bad "missing ${ch}_$d"
  done
done
head -c 26 "$tmp/out/height_trace.gsf" | grep -q "Gwyddion Simple Field 1.0" && ok "GSF written" || bad "GSF magic"
# the run's parameters as metadata Gwyddion shows; one .gwy with every channel
grep -aq "^feedback.setpoint = " "$tmp/out/height_trace.gsf" && grep -aq "^scan.line_rate = 40 Hz$" "$tmp/out/height_trace.gsf" &&
  grep -aq "^tip.radius = " "$tmp/out/height_trace.gsf" && grep -aq "^solver.method = " "$tmp/out/height_trace.gsf" &&
  ok "GSF metadata" || bad "GSF metadata"
head -c 4 "$tmp/out/scan.gwy" | grep -q "GWYP" && ok "scan.gwy written" || bad "scan.gwy"
if command -v gwyddion-thumbnailer >/dev/null 2>&1; then
  gwyddion-thumbnailer gnome2 64 "$tmp/out/scan.gwy" "$tmp/gwy.png" && [ -s "$tmp/gwy.png" ] &&
    ok "Gwyddion loads scan.gwy" || bad "Gwyddion does not load scan.gwy"
fi
# stderr not a terminal: plain progress lines; the summary names the folder
"$tiptap" scan "$tmp/s.ini" -o "$tmp/log" 2>"$tmp/log.err" || bad "scan with a log"
grep -q "^scan: 4/4 lines" "$tmp/log.err" && ! grep -q $'\r' "$tmp/log.err" && ok "plain progress line" || bad "progress in a log"
grep -q "^output = $tmp/log: 33 files (scan.gwy" "$tmp/log.err" && ok "summary names the output" || bad "summary output line"
# the profile line's full-rate record: a point per lock-in block, trace and retrace
head -1 "$tmp/log/scope.csv" | grep -qx "direction,time_s,position_m,z_m,error_m,amplitude_m,phase_deg,surface_m,pixel,material" &&
  [ "$(grep -c "^trace," "$tmp/log/scope.csv")" -gt 100 ] && [ "$(grep -c "^retrace," "$tmp/log/scope.csv")" -gt 100 ] &&
  head -c 8 "$tmp/log/scope.png" | grep -q PNG && ok "scope.csv and scope.png" || bad "scope files"
head -1 "$tmp/out/profile.csv" | grep -q "^position_nm,height_trace_m" && ok "profile" || bad "profile header"
ls "$tmp/out" | grep -q "\.tmp\." && bad "temporary files left" || ok "no temporary files"
# the profiles overlay reads the folder's profile line
"$tiptap" profiles -q -o "$tmp/prof.png" "$tmp/out" "$tmp/out" && [ -s "$tmp/prof.png" ] && ok "profiles" ||
  bad "profiles overlay"
"$tiptap" profiles -q -o "$tmp/prof.png" "$tmp/nowhere" 2>/dev/null && bad "profiles of a missing folder" ||
  ok "profiles refuses a missing folder"
# a profile line the scan never finished (NaN) gets a note in its panel and on stderr
mkdir "$tmp/nan" && printf 'position_nm,height_trace_m,height_retrace_m\n10,nan,nan\n20,nan,nan\n' >"$tmp/nan/profile.csv"
"$tiptap" profiles -q -o "$tmp/nan.png" "$tmp/nan" "$tmp/out" 2>"$tmp/nan.err" && [ -s "$tmp/nan.png" ] &&
  grep -q "^tiptap profiles: $tmp/nan: the profile line holds no height" "$tmp/nan.err" &&
  ok "a NaN profile line is named" || bad "NaN profile: $(cat "$tmp/nan.err")"
# the effective scene runs again from anywhere and gives the same height image
(cd / && "$tiptap" scan "$tmp/out/scene.ini" -o "$tmp/again" -q) || bad "effective scene re-runs"
cmp -s "$tmp/out/height_trace.gsf" "$tmp/again/height_trace.gsf" && ok "effective scene reproduces the image" || bad "re-run differs"
# every channel, and the scene it writes is the one it read (a fixed point)
same=1
for f in "$tmp"/out/*.gsf "$tmp/out/scene.ini"; do cmp -s "$f" "$tmp/again/$(basename "$f")" || { same=0; echo "re-run differs: $(basename "$f")"; }; done
[ $same -eq 1 ] && ok "effective scene reproduces every channel and itself" || bad "re-run of the effective scene differs"
# of [surface], only the png type's keys and the map's: no other type's defaults
awk '/^\[surface\]/{f=1;next} /^\[/{f=0} f' "$tmp/out/scene.ini" >"$tmp/surface.keys"
grep -q "^png = .*logo-height.png$" "$tmp/surface.keys" && grep -q "^png_height_range = " "$tmp/surface.keys" &&
  grep -q "^map_png = " "$tmp/surface.keys" &&
  ! grep -qE "^(particle_radius|step_height|rms|period|duty|lattice|image|seed) = " "$tmp/surface.keys" &&
  ok "effective scene: the surface type's keys only" || bad "effective scene's [surface]: $(cat "$tmp/surface.keys")"
# results do not depend on the number of threads
"$tiptap" scan "$src/surfaces/png-map.ini" "$tmp/s.ini" -o "$tmp/one" -q -j 1 || bad "one thread"
same=1
for f in "$tmp"/out/*.gsf; do cmp -s "$f" "$tmp/one/$(basename "$f")" || { same=0; echo "differs: $(basename "$f")"; }; done
[ $same -eq 1 ] && ok "independent of threads (every channel)" || bad "threads change the images"

# higher-harmonic channels: files in SI units, profile columns, the other channels unchanged
"$tiptap" scan "$src/surfaces/png-map.ini" "$tmp/s.ini" -o "$tmp/harm" -q \
  --set lockin.harmonics=3 --set "scan.channels=height, harmonic2, harmonic3_phase" || bad "harmonic scan ran"
grep -aq "^ZUnits = m$" "$tmp/harm/harmonic2_trace.gsf" && [ -s "$tmp/harm/harmonic2_retrace.png" ] &&
  grep -aq "^ZUnits = deg$" "$tmp/harm/harmonic3_phase_trace.gsf" && ok "harmonic files" || bad "harmonic files"
head -1 "$tmp/harm/profile.csv" | grep -q "^position_nm,height_trace_m,height_retrace_m,harmonic2_trace_m,harmonic2_retrace_m,harmonic3_phase_trace_deg,harmonic3_phase_retrace_deg$" &&
  ok "harmonic profile columns" || bad "harmonic profile header: $(head -1 "$tmp/harm/profile.csv")"
# the data only (8 x 4 float32 at the end): the metadata name the harmonics. The same
# channels but the harmonics: on the envelope tier the channels recorded (peak force,
# indentation) are among what its checks compare, so they choose the cycles integrated.
"$tiptap" scan "$src/surfaces/png-map.ini" "$tmp/s.ini" -o "$tmp/harm2" -q --set lockin.harmonics=3 \
  --set "scan.channels=height, error, phase, peak_force, indentation, dissipation, harmonic2" || bad "harmonic scan ran"
cmp -s <(tail -c 128 "$tmp/out/height_trace.gsf") <(tail -c 128 "$tmp/harm2/height_trace.gsf") && ok "harmonics leave the height alone" || bad "harmonics change the height"
"$tiptap" scan "$tmp/s.ini" -o "$tmp/harm2" -q --set scan.channels=harmonic2 2>"$tmp/harm2.err" && bad "harmonic2 without harmonics accepted"
grep -q "^tiptap: --set: \[scan\] channels: harmonic2 needs \[lockin\] harmonics = 2 or more (it is 1)$" "$tmp/harm2.err" &&
  ok "harmonic2 needs [lockin] harmonics" || bad "message: $(cat "$tmp/harm2.err")"

# Ctrl-C keeps the finished lines in valid files. Lines are cheap (about 2000 cycles:
# a tenth of a second, a second under the sanitizers) and many, so that some but not all
# are finished after a few seconds on any build.
cat >"$tmp/long.ini" <<'INI'
[scan]
size = 500 nm
pixels = 8
lines = 4000
line_rate = 200 Hz
settle_cycles = 500
INI
"$tiptap" scan "$tmp/long.ini" -o "$tmp/int" -q -j 1 &
pid=$!
sleep 6
kill -INT $pid
wait $pid; rc=$?
[ $rc -eq 130 ] && ok "interrupted exit 130" || bad "interrupt exit $rc"
done_lines=$(grep -a "^lines_finished = " "$tmp/int/height_trace.gsf" | sed 's/.*= //')
if [ -n "$done_lines" ] && [ "$done_lines" -gt 0 ] && [ "$done_lines" -lt 4000 ]; then ok "kept $done_lines finished lines"; else bad "lines kept: '$done_lines'"; fi

# an output folder that cannot be made fails at once with its name
out=$("$tiptap" scan "$tmp/s.ini" -o /proc/tiptap-out 2>&1 >/dev/null); rc=$?
[ $rc -ne 0 ] && grep -q "/proc/tiptap-out" <<<"$out" && ok "unwritable output folder" || bad "unwritable folder: $rc $out"

# a trace with a ramp of the adhesion energy writes the ramped value per row
cat >"$tmp/t.ini" <<'INI'
[material glass]
reduced_modulus = 100 GPa
[trace]
separation = 15 nm
cycles = 5
samples_per_cycle = 10
ramp = material.glass.adhesion_energy
ramp_from = 10 mJ/m^2
ramp_to = 50 mJ/m^2
INI
"$tiptap" trace "$tmp/t.ini" -o "$tmp/t.csv" -q || bad "trace ramp ran"
[ "$(wc -l <"$tmp/t.csv")" -eq 51 ] && ok "trace rows" || bad "trace rows $(wc -l <"$tmp/t.csv")"
head -1 "$tmp/t.csv" | grep -q "t_us,base_nm,tip_nm,sample_nm,deflection_nm,force_nN,contact_radius_nm,pressure_GPa" && ok "trace header" || bad "trace header"
first=$(sed -n 2p "$tmp/t.csv" | awk -F, '{print $NF}'); last=$(tail -1 "$tmp/t.csv" | awk -F, '{print $NF}')
[ "$first" = "0.01" ] && [ "$last" = "0.05" ] && ok "ramp 0.01 to 0.05 J/m^2" || bad "ramp $first $last"
out=$("$tiptap" trace "$tmp/t.ini" --set trace.ramp=material.glass.colour -o "$tmp/t2.csv" 2>&1 >/dev/null)
[ $? -ne 0 ] && grep -q "\[trace\] ramp" <<<"$out" && ok "bad ramp key named" || bad "bad ramp: $out"
exit $fail
