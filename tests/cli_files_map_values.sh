#!/usr/bin/env bash
# Two materials whose map_value names one pixel of a PNG material map are refused before
# anything runs, naming the scene file, both materials, the value and the map (issue 19:
# every such pixel silently went to one of them).
# usage: cli_files_map_values.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

"$tiptap" scan "$tmp/s.ini" -o "$tmp/ok" -q && ok "distinct map_values scan" || bad "the scene does not scan"
printf '[material ring]\nmap_value = 0\n' >"$tmp/dup.ini"
expect_exact "same grey level" \
  "tiptap: $tmp/dup.ini: [material ring] map_value: 0 names the same pixel as [material silicon] map_value 0 in the 8-bit map $tmp/map.png; give each material a value of its own" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/dup.ini" -o "$tmp/dup"
[ -e "$tmp/dup" ] && bad "a refused scan made its folder" || ok "no folder"
# a colour and a grey level name one pixel of an 8-bit map when the colour is grey
expect_error "grey as a colour" \
  "[material ring] map_value: #000000 names the same pixel as [material silicon] map_value 0 in the 8-bit map" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/dup" --set "material.ring.map_value=#000000"
# a third material, used by no pixel, repeating a value
printf '[material glass]\nreduced_modulus = 70 GPa\nmap_value = #ff0000\n' >"$tmp/third.ini"
expect_error "third material" \
  "[material glass] map_value: #ff0000 names the same pixel as [material ring] map_value #ff0000" \
  "$tiptap" scan "$tmp/s.ini" "$tmp/third.ini" -o "$tmp/dup"
exit $fail
