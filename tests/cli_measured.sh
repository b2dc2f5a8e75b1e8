#!/usr/bin/env bash
# tiptap scan on a measured topography (docs/surfaces.md, "Measured surfaces"): a tiptap
# image re-imaged from its GSF and from its .gwy by channel title, the artefact channel
# and the profiles' overlay; bad files refused in one line before anything runs.
# usage: cli_measured.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

small_scan "300 nm" 16 4
"$tiptap" scan "$src/surfaces/rough.ini" "$tmp/s.ini" -o "$tmp/first" -q || bad "first scan ran"

# the first scan's height, levelled, re-imaged at a lower setpoint
cat >"$tmp/m.ini" <<INI
[surface]
type = measured
image = $tmp/first/height_trace.gsf
level = plane
[feedback]
setpoint = 60 %
INI
"$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" -o "$tmp/again" -q || bad "re-imaged from the GSF"
for f in artefact_trace.gsf artefact_trace.png topography_trace.gsf height_trace.gsf; do
  [ -s "$tmp/again/$f" ] || bad "missing $f"
done
head -1 "$tmp/again/profile.csv" | grep -q "topography_trace_m.*artefact_trace_m" &&
  ok "artefact and topography in the profile" || bad "profile columns: $(head -1 "$tmp/again/profile.csv")"
grep -q "^type = measured$" "$tmp/again/scene.ini" && grep -q "^image = $tmp/first/height_trace.gsf$" "$tmp/again/scene.ini" &&
  ok "scene.ini names the image" || bad "scene.ini"
"$tiptap" profiles -q -o "$tmp/profiles.png" "$tmp/again" && [ -s "$tmp/profiles.png" ] &&
  ok "profiles overlays input and simulated height" || bad "profiles"

# the same image from the first scan's .gwy, by its channel title
"$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "surface.image=$tmp/first/scan.gwy" \
  --set "surface.channel=Height" -o "$tmp/gwy" -q || bad "re-imaged from the .gwy"
cmp -s "$tmp/again/topography_trace.gsf" "$tmp/gwy/topography_trace.gsf" &&
  bad "the .gwy's doubles gave the GSF's floats" || ok "the .gwy read (doubles, not the GSF's floats)"

# refusals: one line, non-zero, nothing written
head -c $(($(stat -c %s "$tmp/first/height_trace.gsf") - 100)) "$tmp/first/height_trace.gsf" >"$tmp/cut.gsf"
expect_error "truncated GSF" "[surface] image: $tmp/cut.gsf: truncated" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "surface.image=$tmp/cut.gsf" -o "$tmp/no1"
expect_error "missing channel" "no channel 'height'; expected a title or number of those it holds: 0 'Height'" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "surface.image=$tmp/first/scan.gwy" \
  --set "surface.channel=height" -o "$tmp/no2"
expect_error "image smaller than the scan" "[surface] edges: $tmp/first/height_trace.gsf: the image covers 300 x 300 nm" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "scan.size=1 um" -o "$tmp/no3"
expect_error "PNG without its scale" "png_height_range" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "surface.image=$tmp/first/height_trace.png" -o "$tmp/no4"
expect_error "8-bit PNG" "an 8-bit PNG (256 levels); expected a 16-bit grey image" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/m.ini" --set "surface.image=$src/surfaces/logo-height.png" \
  --set "surface.png_height_range=5 nm" --set "surface.pixel_size=2 nm" -o "$tmp/no5"
for d in no1 no2 no3 no4 no5; do [ -e "$tmp/$d" ] && bad "$d: a folder was written"; done
exit $fail
