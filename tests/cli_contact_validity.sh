#!/usr/bin/env bash
# tiptap scan warns, once per material and run, of contacts beyond the contact laws'
# small-contact bound (docs/reliability.md, Tip shapes): a soft material under a 1 nm
# tip is pressed tens of nm deep; a stiff one under the default 10 nm tip is not warned of.
# usage: cli_contact_validity.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/s.ini" <<'INI'
[cantilever]
quality_factor = 100
[material soft]
youngs_modulus = 50 MPa
[scan]
size = 1 um
pixels = 16
lines = 2
line_rate = 200 Hz
settle_cycles = 1000
channels = height, indentation
[feedback]
setpoint = 50 %
INI

"$tiptap" scan "$tmp/s.ini" --set tip.radius=1nm --set tip.shape=sphere -o "$tmp/a" -q 2>"$tmp/err" \
  && ok "sharp tip on soft: runs" || bad "sharp tip on soft: $(cat "$tmp/err")"
n=$(grep -c "warning: \[material soft\]" "$tmp/err")
[ "$n" -eq 1 ] && ok "one warning for the soft material, under -q too" || bad "$n warnings: $(cat "$tmp/err")"
# Hertz (no adhesion): a = sqrt(R delta), and delta past R
figs=$(sed -n 's/.*contact radius up to \([0-9.e+-]*\) nm at \([0-9.e+-]*\) nm indentation on a tip of radius 1 nm,.*/\1 \2/p' "$tmp/err")
awk -v f="$figs" 'BEGIN { split(f, v, " "); exit !(v[2] > 1 && (v[1] - sqrt(v[2])) ^ 2 < 0.01 ^ 2 * v[1] ^ 2) }' \
  && ok "names the radius ($figs nm), the indentation and the tip" || bad "figures '$figs': $(cat "$tmp/err")"
grep "warning: \[material soft\]" "$tmp/err" | grep -q "\[tip\] radius.*\[feedback\] setpoint.*\[cantilever\] free_amplitude" \
  && ok "names the keys" || bad "keys: $(cat "$tmp/err")"

"$tiptap" scan "$tmp/s.ini" --set material.soft.youngs_modulus=200GPa -o "$tmp/b" -q 2>"$tmp/err" \
  && ok "stiff: runs" || bad "stiff: $(cat "$tmp/err")"
grep -q "warning: \[material" "$tmp/err" && bad "stiff under 10 nm warned: $(cat "$tmp/err")" || ok "stiff under 10 nm: no warning"
exit $fail
