#!/usr/bin/env bash
# An output that is an input of the same run is refused before anything runs (issue 19:
# a sweep's -o s.ini replaced the scene): the same file by any name (a relative or
# absolute path, a link, a hard link), for every command that writes, scene files and
# PNG maps alike, and a scan folder holding an input under a name the scan writes.
# usage: cli_files_same_file.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

cp "$tmp/s.ini" "$tmp/orig.ini"
cp "$tmp/map.png" "$tmp/orig.png"
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
expect_exact "sweep -o the scene" \
  "tiptap: $tmp/s.ini: the same file as the scene file $tmp/s.ini that this run reads; write the output elsewhere" \
  "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/s.ini" -q
expect_error "sweep --plot the map" "the same file as the PNG map $tmp/map.png that this run reads" \
  "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" --plot "$tmp/map.png" -q
[ ! -e "$tmp/w.csv.partial" ] && [ ! -e "$tmp/w.csv" ] && ok "the refused sweep wrote nothing" || bad "sweep wrote"
(cd "$tmp" && expect_error "relative name" "./s.ini: the same file as the scene file" \
  "$tiptap" sweep s.ini "${vary[@]}" -o ./s.ini -q)
ln -s s.ini "$tmp/link.ini"
ln "$tmp/s.ini" "$tmp/hard.ini"
expect_error "a link to the scene" "link.ini: the same file as the scene file" \
  "$tiptap" trace "$tmp/s.ini" -o "$tmp/link.ini" -q
expect_error "a hard link to the scene" "hard.ini: the same file as the scene file" \
  "$tiptap" approach "$tmp/s.ini" -o "$tmp/hard.ini" -q
expect_error "the scene read through a link" "s.ini: the same file as the scene file $tmp/link.ini" \
  "$tiptap" approach "$tmp/link.ini" --plot "$tmp/s.ini" -q
expect_error "the second scene file" "the same file as the scene file $tmp/more.ini" \
  bash -c "printf '[trace]\ncycles = 3\n' >'$tmp/more.ini'; '$tiptap' trace '$tmp/s.ini' '$tmp/more.ini' -o '$tmp/more.ini' -q"
expect_error "accuracy -o the scene" "the same file as the scene file" \
  "$tiptap" accuracy "$tmp/s.ini" -o "$tmp/s.ini" -q
expect_error "contact --plot the map" "the same file as the PNG map" \
  "$tiptap" contact "$tmp/s.ini" --plot "$tmp/map.png"
cmp -s "$tmp/s.ini" "$tmp/orig.ini" && cmp -s "$tmp/map.png" "$tmp/orig.png" && ok "inputs untouched" ||
  bad "an input was replaced"

# scan: the folder's files; the effective scene of an earlier run is an input here
"$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q || bad "first scan"
sed -i "s|^map_png = .*|map_png = $tmp/map.png|" "$tmp/out/scene.ini"
cp "$tmp/out/scene.ini" "$tmp/effective.ini"
expect_exact "scan into the folder of its scene" \
  "tiptap: $tmp/out/scene.ini: the same file as the scene file $tmp/out/scene.ini that this run reads; write the output elsewhere" \
  "$tiptap" scan "$tmp/out/scene.ini" -o "$tmp/out" -q
cmp -s "$tmp/out/scene.ini" "$tmp/effective.ini" && ok "the folder's scene.ini kept" || bad "scene.ini replaced"
"$tiptap" scan "$tmp/out/scene.ini" -o "$tmp/again" -q && ok "the effective scene scans into another folder" ||
  bad "re-run elsewhere"
# a map named like a channel file this run would remove as stale
cp "$tmp/map.png" "$tmp/out/amplitude_trace.png"
expect_error "a map among the scan's names" "amplitude_trace.png: the same file as the PNG map" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q --set "surface.map_png=$tmp/out/amplitude_trace.png"
cmp -s "$tmp/out/amplitude_trace.png" "$tmp/map.png" && ok "the map kept" || bad "the map removed"
# profiles reads DIR/profile.csv
cp "$tmp/out/profile.csv" "$tmp/profile.orig"
expect_error "profiles -o its input" "profile.csv: the same file as the profile CSV $tmp/out/profile.csv" \
  "$tiptap" profiles -q -o "$tmp/out/profile.csv" "$tmp/out"
cmp -s "$tmp/out/profile.csv" "$tmp/profile.orig" && ok "the profile kept" || bad "the profile replaced"
# another file of the folder may be a scene
cp "$tmp/s.ini" "$tmp/out/mine.ini"
"$tiptap" scan "$tmp/out/mine.ini" -o "$tmp/out" -q --set "surface.map_png=$tmp/map.png" 2>/dev/null &&
  cmp -s "$tmp/out/mine.ini" "$tmp/s.ini" && ok "a scene beside the outputs" || bad "a scene beside the outputs refused"
# -o and --plot naming one file (by another name, or through a link to its folder): a
# usage error before anything runs, for every command that takes both
ln -s "$tmp" "$tmp/here"
for cmd in trace approach contact; do
  arg=("$tmp/s.ini"); [ $cmd = contact ] && arg=(--lambda 1)
  out=$("$tiptap" $cmd "${arg[@]}" -o "$tmp/both.png" --plot "$tmp/here/./both.png" 2>&1 >/dev/null); rc=$?
  [ $rc -eq 2 ] && [ "$out" = "tiptap $cmd: --plot $tmp/here/./both.png: the same file as -o $tmp/both.png; give each its own name" ] &&
    [ ! -e "$tmp/both.png" ] && ok "$cmd: -o and --plot into one file refused" || bad "$cmd -o = --plot: rc $rc '$out'"
done
# all of a run's outputs at once (issue 28: sweep -o t.csv --plot t.h5 --hdf5 wrote the
# plot over the HDF5 table and exited 0): FILE.h5, the journal
out=$("$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/t.csv" --plot "$tmp/here/t.h5" --hdf5 -q 2>&1); rc=$?
[ $rc -eq 2 ] && [ "$out" = "tiptap sweep: --hdf5 $tmp/t.h5: the same file as --plot $tmp/here/t.h5; give each its own name" ] &&
  [ -z "$(ls "$tmp" | grep '^t\.')" ] && ok "sweep --plot FILE.h5 --hdf5 refused before the run" ||
  bad "sweep --plot FILE.h5: rc $rc, '$out'"
expect_error "sweep --plot its journal" "the journal $tmp/t.csv.partial: the same file as --plot $tmp/./t.csv.partial" \
  "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/t.csv" --plot "$tmp/./t.csv.partial" -q
[ -z "$(ls "$tmp" | grep '^t[.]*')" ] && ok "the refused sweeps wrote nothing" || bad "a refused sweep wrote"
# contact with a scene: refused before its summary is printed
cp "$tmp/s.ini" "$tmp/c.ini"
sum=$("$tiptap" contact "$tmp/c.ini" -o "$tmp/c.ini" 2>"$tmp/c.err"); rc=$?
[ $rc -eq 1 ] && [ -z "$sum" ] && grep -qF "the same file as the scene file $tmp/c.ini" "$tmp/c.err" &&
  cmp -s "$tmp/c.ini" "$tmp/s.ini" && ok "contact -o its scene: refused before the summary" ||
  bad "contact -o its scene: rc $rc, stdout '$sum', $(cat "$tmp/c.err")"
exit $fail
