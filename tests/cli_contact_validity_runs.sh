#!/usr/bin/env bash
# tiptap trace and tiptap approach warn of contacts beyond the contact laws' small-contact
# bound as tiptap scan does (one function, tt_contact_warn_validity; docs/reliability.md,
# Tip shapes): a ramp of the modulus from 10 GPa to 1 MPa at -5 nm under the 10 nm tip
# widens the contact to 7.6 nm (0.76 R; 4.4 nm when ramped to 100 GPa instead, not
# warned of); an approach 10 nm into 50 MPa under a 1 nm tip (5 nm, 25 nm deep) is,
# a stiff one under 10 nm is not; once per run, under -q too.
# usage: cli_contact_validity_runs.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/t.ini" <<'INI'
[cantilever]
free_amplitude = 20 nm
[material soft]
youngs_modulus = 100 MPa
[trace]
separation = -5 nm
settle_cycles = 3000
cycles = 200
samples_per_cycle = 100
ramp = material.soft.youngs_modulus
ramp_from = 10 GPa
ramp_to = 1 MPa
INI
"$tiptap" trace "$tmp/t.ini" -o "$tmp/t.csv" -q 2>"$tmp/err" && ok "trace ramp: runs" || bad "trace: $(cat "$tmp/err")"
[ "$(grep -c "warning: \[material soft\]: contact radius up to" "$tmp/err")" -eq 1 ] &&
  ok "trace ramp: one warning, under -q" || bad "trace warnings: $(cat "$tmp/err")"
# the radius at the located deepest point: at least the widest of the trace's samples,
# and within 2 % of it (100 samples a cycle come close to the peak)
widest=$(awk -F, 'NR > 1 && $7 + 0 > m { m = $7 + 0 } END { print m }' "$tmp/t.csv")
a=$(sed -n 's/.*contact radius up to \([0-9.e+-]*\) nm at [0-9.e+-]* nm indentation on a tip of radius 10 nm,.*\[trace\] separation.*/\1/p' "$tmp/err")
awk -v a="$a" -v w="$widest" 'BEGIN { exit !(a != "" && a >= w * 0.999 && a <= w * 1.02) }' &&
  ok "trace ramp: names the radius ($a nm; the widest sample $widest nm), tip and keys" ||
  bad "trace figures (widest $widest): $(cat "$tmp/err")"
"$tiptap" trace "$tmp/t.ini" --set "trace.ramp_to=100 GPa" -o "$tmp/t2.csv" -q 2>"$tmp/err" &&
  ! grep -q "warning: \[material" "$tmp/err" && ok "trace ramp to stiff: no warning" ||
  bad "trace stiff: $(cat "$tmp/err")"

cat >"$tmp/a.ini" <<'INI'
[cantilever]
quality_factor = 100
[tip]
radius = 1 nm
[material soft]
youngs_modulus = 50 MPa
[approach]
from = 5 nm
to = -10 nm
points = 4
INI
"$tiptap" approach "$tmp/a.ini" -o "$tmp/a.csv" -q 2>"$tmp/err" && ok "approach: runs" || bad "approach: $(cat "$tmp/err")"
[ "$(grep -c "warning: \[material soft\]: contact radius up to" "$tmp/err")" -eq 1 ] &&
  ok "approach: one warning, under -q (none from the companion run)" || bad "approach warnings: $(cat "$tmp/err")"
# Hertz (no adhesion): a = sqrt(R delta), delta the deepest max_indentation of the rows
deepest=$(awk -F, 'NR > 1 && $6 + 0 > m { m = $6 + 0 } END { printf "%.3g", m }' "$tmp/a.csv")
figs=$(sed -n 's/.*contact radius up to \([0-9.e+-]*\) nm at \([0-9.e+-]*\) nm indentation on a tip of radius 1 nm,.*/\1 \2/p' "$tmp/err")
awk -v f="$figs" -v d="$deepest" 'BEGIN { split(f, v, " "); exit !(v[2] == d && (v[1] - sqrt(v[2])) ^ 2 < 0.01 ^ 2 * v[1] ^ 2) }' &&
  ok "approach: names the radius ($figs nm) at the deepest row's indentation ($deepest nm)" ||
  bad "approach figures '$figs' (deepest $deepest): $(cat "$tmp/err")"
grep -q "\[approach\] to" "$tmp/err" && ok "approach: names the keys" || bad "keys: $(cat "$tmp/err")"
"$tiptap" approach "$tmp/a.ini" --set material.soft.youngs_modulus=200GPa --set tip.radius=10nm \
  -o "$tmp/b.csv" -q 2>"$tmp/err" && ! grep -q "warning: \[material" "$tmp/err" &&
  ok "approach stiff: no warning" || bad "approach stiff: $(cat "$tmp/err")"
exit $fail
