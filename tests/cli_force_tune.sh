#!/usr/bin/env bash
# tiptap force and tiptap tune from the command line: --help, the CSV and PNG, the
# summary on stdout (the largest adhesion against tiptap contact's least load; the tuned
# k against the scene's within three of its errors), and refusals in one line naming the
# file and key, with no output left behind.
# usage: cli_force_tune.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

"$tiptap" force --help | grep -q "jump-in" && ok "force --help" || bad "force --help"
"$tiptap" tune --help | grep -q "equipartition" && ok "tune --help" || bad "tune --help"
"$tiptap" --help | grep -q "^  force " && "$tiptap" --help | grep -q "^  tune " &&
  ok "both listed in tiptap --help" || bad "tiptap --help lacks force or tune"

blend=$src/surfaces/polymer-blend.ini
scene=$src/examples/force-curves/scene.ini
if "$tiptap" force "$blend" "$scene" --set force.material=disk -o "$tmp/disk.csv" --plot "$tmp/disk.png" \
  -q >"$tmp/disk.txt" 2>"$tmp/disk.err"; then
  ok "force ran"
else
  bad "force: $(cat "$tmp/disk.err")"
fi
head -1 "$tmp/disk.csv" | grep -q "^t_ms,z_nm,deflection_nm,separation_nm,force_nN,lever_force_nN,contact,leg$" &&
  ok "force CSV header" || bad "force CSV header: $(head -1 "$tmp/disk.csv")"
[ -s "$tmp/disk.png" ] && ok "force plot" || bad "no force plot"
grep -q ",approach$" "$tmp/disk.csv" && grep -q ",retract$" "$tmp/disk.csv" && ok "both legs" || bad "a leg missing"
"$tiptap" contact "$blend" "$scene" --material disk -o "$tmp/c.csv" >"$tmp/c.txt" 2>/dev/null
least=$(awk -F' = ' '$1 == "pulloff_load_N" {print -$2 * 1e9}' "$tmp/c.txt")
adh=$(awk -F' = ' '$1 == "adhesion_nN" {print $2}' "$tmp/disk.txt")
awk -v a="$adh" -v l="$least" 'BEGIN { exit !(l > 0 && (a - l) ^ 2 < (0.002 * l) ^ 2) }' &&
  ok "adhesion $adh nN = least load $least nN" || bad "adhesion '$adh' nN against least load '$least' nN"

cat >"$tmp/soft.ini" <<'SCENE'
[cantilever]
spring_constant = 0.1 N/m
resonance_frequency = 10 kHz
quality_factor = 20
[noise]
temperature = 300 K
[tune]
duration = 0.4 s
SCENE
if "$tiptap" tune "$tmp/soft.ini" -o "$tmp/tune.csv" --plot "$tmp/tune.png" -q >"$tmp/tune.txt" 2>"$tmp/tune.err"; then
  ok "tune ran"
else
  bad "tune: $(cat "$tmp/tune.err")"
fi
head -1 "$tmp/tune.csv" | grep -q "^f_Hz,psd_m2_per_Hz,fit_m2_per_Hz$" && ok "tune CSV header" || bad "tune CSV header"
[ -s "$tmp/tune.png" ] && ok "tune plot" || bad "no tune plot"
awk -F' = ' '$1 == "k_N_per_m" {k = $2} $1 == "k_err_N_per_m" {e = $2} $1 == "chi" {c = $2}
  END { exit !(e > 0 && (k - 0.1) ^ 2 < 9 * e * e && c == 1) }' "$tmp/tune.txt" &&
  ok "tuned k within three errors, chi 1" || bad "tune: $(grep -E '^(k_|chi )' "$tmp/tune.txt")"

expect_error "force: from below to" "[force] from: the ramp must start farther" \
  "$tiptap" force "$blend" "$scene" --set "force.from=-5 nm" -o "$tmp/no1.csv"
expect_error "force: unknown material" "[force] material: no [material glass]" \
  "$tiptap" force "$blend" "$scene" --set force.material=glass -o "$tmp/no2.csv"
expect_error "force: from and range" "[force] range: give from or range, not both" \
  "$tiptap" force "$blend" "$scene" --set "force.range=5 nm" -o "$tmp/no3.csv"
grep -v "^temperature" "$tmp/soft.ini" >"$tmp/cold.ini"
expect_error "tune at 0 K" "cold.ini: [noise] temperature: tiptap tune needs the thermal force" \
  "$tiptap" tune "$tmp/cold.ini" -o "$tmp/no4.csv"
expect_error "tune: record too short" "[tune] duration: the record (0.001 s) holds fewer than 8" \
  "$tiptap" tune "$tmp/soft.ini" --set "tune.duration=1 ms" -o "$tmp/no5.csv"
# --volume: a folder of maps, the same bytes on one thread and two (noise on), and its
# refusals before any folder is made
vol=(--volume --set scan.size=500nm --set scan.pixels=6 --set scan.lines=2 --set "noise.temperature=300 K" -q)
if "$tiptap" force "$blend" "$scene" "${vol[@]}" -o "$tmp/vol1" -j 1 --hdf5 >"$tmp/vol1.txt" 2>"$tmp/vol.err" &&
  "$tiptap" force "$blend" "$scene" "${vol[@]}" -o "$tmp/vol2" -j 2 >/dev/null 2>>"$tmp/vol.err"; then
  ok "force --volume ran"
else
  bad "force --volume: $(cat "$tmp/vol.err")"
fi
for m in height adhesion stiffness pulloff_distance pulloff_force indentation max_force material; do
  [ -s "$tmp/vol1/$m.gsf" ] && [ -s "$tmp/vol1/$m.png" ] || bad "force --volume: no $m map"
  cmp -s "$tmp/vol1/$m.gsf" "$tmp/vol2/$m.gsf" || bad "force --volume: $m.gsf differs on 1 and 2 threads"
done
[ -s "$tmp/vol1/force_volume.gwy" ] && [ -s "$tmp/vol1/force_volume.h5" ] && [ -s "$tmp/vol1/scene.ini" ] &&
  [ ! -e "$tmp/vol2/force_volume.h5" ] && ok "force --volume files" || bad "force --volume: .gwy, .h5 or scene.ini"
grep -q "^lines_finished = 2$" "$tmp/vol1.txt" && ok "force --volume stdout" || bad "force --volume: $(cat "$tmp/vol1.txt")"
expect_error "force: --plot with --volume" "--plot draws one curve" \
  "$tiptap" force "$blend" "$scene" --volume --plot "$tmp/no.png" -o "$tmp/novol1"
expect_error "force: --hdf5 without --volume" "--hdf5 goes with --volume" \
  "$tiptap" force "$blend" "$scene" --hdf5 -o "$tmp/no6.csv"
expect_error "force --volume: bad [force] key" "[force] from: the ramp must start farther" \
  "$tiptap" force "$blend" "$scene" --volume --set "force.from=-5 nm" -o "$tmp/novol2"
ls -d "$tmp"/novol* >/dev/null 2>&1 && bad "a refused volume left a folder" || ok "refused volumes leave no folder"
# SIGINT during a long volume: exit 130, the lines finished written (their count in the
# maps' metadata), the others NaN
"$tiptap" force "$blend" "$scene" --volume --set scan.pixels=2 --set scan.lines=5000 -o "$tmp/volint" -j 1 \
  -q >"$tmp/volint.txt" 2>"$tmp/volint.err" &
pid=$!
sleep 3
kill -INT $pid
wait $pid
rc=$?
n=$(awk -F' = ' '$1 == "lines_finished" {print $2}' "$tmp/volint.txt")
if [ "$rc" -eq 130 ] && [ -n "$n" ] && [ "$n" -gt 0 ] && [ "$n" -lt 5000 ] &&
  grep -aq "^lines_finished = $n$" "$tmp/volint/adhesion.gsf"; then
  ok "force --volume interrupted: exit 130, $n lines written"
else
  bad "force --volume interrupted: exit $rc, lines '$n': $(cat "$tmp/volint.err")"
fi
ls "$tmp"/no*.csv >/dev/null 2>&1 && bad "a refused run left a file" || ok "refused runs leave no file"
exit $fail
