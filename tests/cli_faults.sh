#!/usr/bin/env bash
# Faults and odd input from the command line: only regular files are scenes, option
# values are checked, SIGTERM exits 143, and the scene.ini that scan writes from a deep
# folder (long absolute paths) loads again.
# usage: cli_faults.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

# a folder was read as an empty scene and /dev/zero never ended
expect_exact "folder as scene" "tiptap: $tmp: is a folder, not a scene file" "$tiptap" contact "$tmp"
expect_error "folder as scan scene" "is a folder, not a scene file" "$tiptap" scan "$tmp" -o "$tmp/never"
[ -e "$tmp/never" ] && bad "refused scan made its folder" || ok "refused scan made no folder"
expect_error "device as scene" "/dev/zero: not a regular file" timeout 10 "$tiptap" contact /dev/zero

# -j abc and -j -3 ran on all cores; --xi0 inf printed nan
cat >"$tmp/s.ini" <<'INI'
[scan]
size = 100 nm
pixels = 2
lines = 2
line_rate = 100 Hz
settle_cycles = 10
INI
expect_exact "-j abc" "tiptap scan: -j: 'abc' is not a number of threads from 1 to 4096" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/j" -j abc
expect_error "-j -3" "'-3' is not a number of threads" "$tiptap" scan "$tmp/s.ini" -o "$tmp/j" -j -3
expect_error "-j 0" "'0' is not a number of threads" "$tiptap" scan "$tmp/s.ini" -o "$tmp/j" -j 0
expect_exact "--xi0 inf" "tiptap contact: --xi0: 'inf' is not a positive number up to 1e6" \
  "$tiptap" contact --xi0 inf

# a line break in a --set value would have split a key in scene.ini
expect_error "newline in --set" "holds a control character" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/nl" --set "surface.png=a.png
[cantilever]"
expect_error "empty material name" "--set material..adhesion_energy=1 J/m^2: empty name" \
  "$tiptap" contact "$tmp/s.ini" --set "material..adhesion_energy=1 J/m^2"

# the effective scene written in a deep folder names the map by a path of over 200
# bytes, which the old INI reader cut
deep="$tmp/$(printf 'a_rather_deep_folder_%02d/' $(seq 1 12))"
mkdir -p "$deep"
cp "$src/surfaces/logo-materials.png" "$deep/map.png"
cat >"$deep/map.ini" <<'INI'
[material glass]
map_value = 0
[material ring]
reduced_modulus = 60 GPa
map_value = #ff0000
[surface]
map = png
map_png = map.png
INI
if "$tiptap" scan "$deep/map.ini" "$tmp/s.ini" -o "$deep/out" -q 2>"$tmp/deep.err"; then
  grep -q "^map_png = $deep" "$deep/out/scene.ini" && ok "long absolute path written" || bad "path: $(grep map_png "$deep/out/scene.ini")"
  (cd / && "$tiptap" scan "$deep/out/scene.ini" -o "$deep/again" -q) && ok "effective scene with a long path re-runs" || bad "re-run of $deep/out/scene.ini"
else
  bad "deep scan: $(cat "$tmp/deep.err")"
fi

# SIGTERM stops like Ctrl-C and exits 128 + 15 (it exited 130)
cat >"$tmp/long.ini" <<'INI'
[trace]
separation = 15 nm
cycles = 100000000
INI
"$tiptap" trace "$tmp/long.ini" -o "$tmp/long.csv" -q 2>/dev/null &
pid=$!
sleep 2
kill -TERM $pid
wait $pid; rc=$?
[ $rc -eq 143 ] && ok "SIGTERM exit 143" || bad "SIGTERM exit $rc"

exit $fail
