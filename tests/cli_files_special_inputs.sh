#!/usr/bin/env bash
# Only regular files are read (issue 19): a pipe, a device, a link to /dev/zero or a
# folder given as a PNG map, a sweep journal or a profile CSV is refused at once with one
# line, before anything runs (a pipe without a writer blocked the open, /dev/zero was
# read for ever).
# usage: cli_files_special_inputs.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

mkfifo "$tmp/fifo.png"
ln -s /dev/zero "$tmp/zero.png"
for key in map_png png; do
  set_type=()
  [ $key = png ] && set_type=(--set surface.type=png)
  expect_exact "$key a pipe" \
    "tiptap: --set: [surface] $key: $tmp/fifo.png: not a regular file (a device, pipe or socket); a map is a file" \
    timeout 10 "$tiptap" scan "$tmp/s.ini" -o "$tmp/o" "${set_type[@]}" --set "surface.$key=$tmp/fifo.png"
  expect_error "$key a link to /dev/zero" "[surface] $key: $tmp/zero.png: not a regular file" \
    timeout 10 "$tiptap" scan "$tmp/s.ini" -o "$tmp/o" "${set_type[@]}" --set "surface.$key=$tmp/zero.png"
  expect_error "$key a device" "[surface] $key: /dev/null: not a regular file" \
    timeout 10 "$tiptap" scan "$tmp/s.ini" -o "$tmp/o" "${set_type[@]}" --set "surface.$key=/dev/null"
  expect_error "$key a folder" "[surface] $key: $tmp: is a folder, not a PNG map" \
    timeout 10 "$tiptap" scan "$tmp/s.ini" -o "$tmp/o" "${set_type[@]}" --set "surface.$key=$tmp"
done
[ -e "$tmp/o" ] && bad "a refused scan made its folder" || ok "no folder"

# the sweep's journal
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
mkfifo "$tmp/w.csv.partial"
expect_exact "journal a pipe" \
  "tiptap: $tmp/w.csv.partial: not a regular file (a device, pipe or socket); a sweep journal is a file" \
  timeout 10 "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q
rm "$tmp/w.csv.partial"
mkdir "$tmp/w.csv.partial"
expect_error "journal a folder" "$tmp/w.csv.partial: is a folder, not a sweep journal" \
  timeout 10 "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q

# profiles reads DIR/profile.csv
mkdir -p "$tmp/p1" "$tmp/p2" "$tmp/p3"
mkfifo "$tmp/p1/profile.csv"
ln -s /dev/zero "$tmp/p2/profile.csv"
mkdir "$tmp/p3/profile.csv"
expect_exact "profile a pipe" \
  "tiptap: $tmp/p1/profile.csv: not a regular file (a device, pipe or socket); a profile is a file" \
  timeout 10 "$tiptap" profiles -q -o "$tmp/p.png" "$tmp/p1"
expect_error "profile a link to /dev/zero" "$tmp/p2/profile.csv: not a regular file" \
  timeout 10 "$tiptap" profiles -q -o "$tmp/p.png" "$tmp/p2"
expect_error "profile a folder" "$tmp/p3/profile.csv: is a folder, not a profile CSV" \
  timeout 10 "$tiptap" profiles -q -o "$tmp/p.png" "$tmp/p3"
[ -e "$tmp/p.png" ] && bad "profiles wrote a figure" || ok "no figure"
exit $fail
