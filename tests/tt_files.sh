# Shared by the tests of files, links and locks (tests/cli_files_*.sh; sourced after
# tt_cli.sh): a small scan scene over the bundled material map, copied into $tmp.
# under the sanitizers, LeakSanitizer's summary of suppressed leaks (fontconfig's, when a
# preview draws text) would follow the one line a refusal prints
export LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}print_suppressions=0"
cp "$src/surfaces/logo-materials.png" "$tmp/map.png"
cat >"$tmp/s.ini" <<'INI'
[material silicon]
reduced_modulus = 100 GPa
map_value = 0
[material ring]
reduced_modulus = 60 GPa
map_value = #ff0000
[scan]
size = 100 nm
pixels = 16
lines = 2
line_rate = 100 Hz
settle_cycles = 10
channels = height, phase
[surface]
map = png
map_png = map.png
INI
