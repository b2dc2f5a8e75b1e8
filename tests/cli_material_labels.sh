#!/usr/bin/env bash
# Material maps from data (docs/surfaces.md, "Material maps from data"): a two-phase
# sample's phase image thresholded into its domains and re-imaged, the materials coming
# back where the phase put them; a bad threshold refused in one line before anything runs.
# usage: cli_material_labels.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

small_scan "1 um" 16 16
"$tiptap" scan "$src/surfaces/polymer-blend.ini" "$tmp/s.ini" -o "$tmp/first" -q 2>/dev/null || bad "first scan ran"

# the disks' phase is 54-58 deg at their centres, the matrix's 106 deg: 80 deg splits them
cat >"$tmp/t.ini" <<INI
[surface]
map = threshold
map_image = $tmp/first/phase_trace.gsf
map_threshold = 80 deg
map_materials = disk, matrix
INI
"$tiptap" scan "$src/surfaces/polymer-blend.ini" "$tmp/s.ini" "$tmp/t.ini" -o "$tmp/again" -q 2>/dev/null ||
  bad "re-imaged from the thresholded phase"
phase() { # file, then pixel indices: the phase at each, one a line
  python3 - "$@" <<'PY'
import struct, sys
b = open(sys.argv[1], 'rb').read()
at = (b.index(b'\0') // 4 + 1) * 4
for k in sys.argv[2:]:
    print('%.1f' % struct.unpack_from('<f', b, at + 4 * int(k))[0])
PY
}
# a disk's centre (column 4, row 3) and the matrix (column 8, row 8) in both scans
first=$(phase "$tmp/first/phase_trace.gsf" 52 136 | tr '\n' ' ')
again=$(phase "$tmp/again/phase_trace.gsf" 52 136 | tr '\n' ' ')
python3 - "$first" "$again" <<'PY' && ok "the domains come back: $first/ $again" || bad "domains: $first/ $again"
import sys
a, b = (list(map(float, s.split())) for s in sys.argv[1:3])
sys.exit(0 if a[0] < 80 and b[0] < 80 and a[1] > 100 and b[1] > 100 and abs(a[0] - b[0]) < 3 else 1)
PY
grep -q "^map = threshold$" "$tmp/again/scene.ini" && ok "scene.ini keeps the map" || bad "scene.ini"

expect_error "a threshold in radians on a deg image" "[surface] map_threshold: 1.4 rad, but $tmp/first/phase_trace.gsf is in 'deg'" \
  "$tiptap" scan "$src/surfaces/polymer-blend.ini" "$tmp/s.ini" "$tmp/t.ini" --set surface.map_threshold="1.4 rad" -o "$tmp/no" -q
[ ! -e "$tmp/no" ] && ok "nothing written" || bad "$tmp/no written"
expect_error "a label image of phases" "pixel (0, 0) is 105.9" \
  "$tiptap" scan "$src/surfaces/polymer-blend.ini" "$tmp/s.ini" "$tmp/t.ini" --set surface.map=labels -o "$tmp/no" -q
exit $fail
