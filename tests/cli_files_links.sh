#!/usr/bin/env bash
# tiptap never writes through a link (issue 19): a link planted as a scan's lock file or
# as the sweep's journal is refused and the file it names stays as it was; an output
# whose name is a link is replaced by the file (rename replaces the link), its target
# untouched.
# usage: cli_files_links.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

echo precious >"$tmp/precious"
mkdir -p "$tmp/out"
ln -s "$tmp/precious" "$tmp/out/.tiptap.lock"
expect_exact "lock file a link" \
  "tiptap scan: $tmp/out/.tiptap.lock: is a symbolic link; tiptap never writes through a link: remove it" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q
[ "$(cat "$tmp/precious")" = precious ] && ok "the lock link's target is untouched" || bad "precious: $(cat "$tmp/precious")"
rm "$tmp/out/.tiptap.lock"
ln "$tmp/precious" "$tmp/out/.tiptap.lock"
expect_error "lock file with another hard link" "$tmp/out/.tiptap.lock: not a plain file of its own" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q
[ "$(cat "$tmp/precious")" = precious ] && ok "the hard link's other name is untouched" || bad "precious truncated"
rm "$tmp/out/.tiptap.lock"

# outputs named by links: the file replaces the link
ln -s "$tmp/precious" "$tmp/out/height_trace.gsf"
ln -s "$tmp/precious" "$tmp/t.csv"
"$tiptap" scan "$tmp/s.ini" -o "$tmp/out" -q && "$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" -q --set trace.cycles=3 &&
  ok "outputs written over links" || bad "outputs over links failed"
[ ! -L "$tmp/out/height_trace.gsf" ] && [ -s "$tmp/out/height_trace.gsf" ] && [ ! -L "$tmp/t.csv" ] &&
  head -c 25 "$tmp/out/height_trace.gsf" | grep -q "Gwyddion Simple Field" &&
  ok "the link replaced by the file" || bad "output link: $(ls -l "$tmp/out/height_trace.gsf" "$tmp/t.csv")"
[ "$(cat "$tmp/precious")" = precious ] && ok "the output links' target is untouched" || bad "precious written through"

# the sweep's journal: a link is refused, whether it names a file or nothing
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
ln -s "$tmp/precious" "$tmp/w.csv.partial"
expect_exact "journal a link" \
  "tiptap: $tmp/w.csv.partial: the sweep journal is a symbolic link; tiptap never writes through a link: remove it" \
  "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q
rm "$tmp/w.csv.partial"
ln -s "$tmp/nothing" "$tmp/w.csv.partial"
expect_error "journal a dangling link" "the sweep journal is a symbolic link" \
  "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q
[ ! -e "$tmp/nothing" ] && [ "$(cat "$tmp/precious")" = precious ] && ok "no file made through the journal link" ||
  bad "journal link followed"
rm "$tmp/w.csv.partial"
"$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q && [ -s "$tmp/w.csv" ] && [ ! -e "$tmp/w.csv.partial" ] &&
  ok "the sweep runs once the link is gone" || bad "sweep after the link"
exit $fail
