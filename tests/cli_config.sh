#!/usr/bin/env bash
# Every key and every material is checked before anything runs: a bad material that no
# pixel uses, or that the scan reaches only mid-image, is refused at once with one line
# naming the file, the section and the key; a refused scan makes no output folder and
# leaves an existing one as it was.
# usage: cli_config.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/base.ini" <<'INI'
[cantilever]
quality_factor = 100
[material good]
reduced_modulus = 50 GPa
adhesion_energy = 20 mJ/m^2
[scan]
size = 500 nm
pixels = 8
lines = 2
line_rate = 40 Hz
settle_cycles = 200
INI
"$tiptap" scan "$tmp/base.ini" -o "$tmp/ok" -q && [ -s "$tmp/ok/height_trace.gsf" ] && ok "the base scene scans" || bad "base scan"

# a material no pixel uses (a uniform map shows only the first)
cat >"$tmp/unused.ini" <<'INI'
[material unused]
adhesion_energy = 40 mJ/m^2
lambda = 1e5
INI
expect_exact "unused bad material refused" \
  "tiptap: $tmp/unused.ini: [material unused] lambda: 100000 is outside 1e-4 to 1e4; use model = dmt or jkr for the limits" \
  "$tiptap" scan "$tmp/base.ini" "$tmp/unused.ini" -o "$tmp/unused" -q
[ -e "$tmp/unused" ] && bad "a refused scan made its folder" || ok "no folder for a refused scan"

# a material the raster reaches only mid-line: stripes of "good" up to 3/4 of the
# width, then "late", whose lambda (derived from xi0, eq. 3) no force law can take
cat >"$tmp/late.ini" <<'INI'
[material late]
youngs_modulus = 2 GPa
adhesion_energy = 40 mJ/m^2
interatomic_distance = 1e-6 nm
[surface]
map = stripes
map_materials = late, good
map_period = 500 nm
map_duty = 75 %
INI
expect_error "material reached mid-image refused" \
  "$tmp/late.ini: [material late] interatomic_distance: 1e-6 nm gives lambda = " \
  "$tiptap" scan "$tmp/base.ini" "$tmp/late.ini" -o "$tmp/late" -q
[ -e "$tmp/late" ] && bad "a refused scan made its folder" || ok "no folder for a material reached late"

# an existing folder is left as it was
mkdir "$tmp/keep"
echo "an earlier scene" >"$tmp/keep/scene.ini"
touch -d "2001-01-01 00:00" "$tmp/keep/scene.ini" "$tmp/keep"
before=$(ls -la --time-style=full-iso "$tmp/keep"; cat "$tmp/keep/scene.ini")
"$tiptap" scan "$tmp/base.ini" "$tmp/unused.ini" -o "$tmp/keep" -q 2>/dev/null && bad "refused scan exit 0"
after=$(ls -la --time-style=full-iso "$tmp/keep"; cat "$tmp/keep/scene.ini")
[ "$before" = "$after" ] && ok "an existing folder is not touched" || bad "the existing folder changed"

# the other commands check every material up front too
cat >"$tmp/ap.ini" <<'INI'
[approach]
from = 20 nm
to = 10 nm
points = 3
INI
expect_error "approach refuses an unused bad material" "$tmp/unused.ini: [material unused] lambda:" \
  "$tiptap" approach "$tmp/base.ini" "$tmp/ap.ini" "$tmp/unused.ini" -o "$tmp/ap.csv" -q
[ -e "$tmp/ap.csv" ] && bad "refused approach wrote its CSV" || ok "no CSV for a refused approach"
# a bad map_value is refused even when no PNG map reads it
expect_error "bad map_value refused" "[material good] map_value:" \
  "$tiptap" scan "$tmp/base.ini" -o "$tmp/mv" -q --set "material.good.map_value=#zz0000"
exit $fail
