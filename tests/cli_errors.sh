#!/usr/bin/env bash
# The command line refuses bad input with one line naming file, section and key, and a
# non-zero exit; it leaves no half-written output behind.
# usage: cli_errors.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/typo.ini" <<'INI'
[cantilever]
spring_constnat = 2 N/m
INI
cat >"$tmp/nounit.ini" <<'INI'
[cantilever]
resonance_frequency = 52
INI
cat >"$tmp/neg.ini" <<'INI'
[cantilever]
spring_constant = -0.5 N/m
INI
cat >"$tmp/nan.ini" <<'INI'
[material glass]
adhesion_energy = nan J/m^2
INI
cat >"$tmp/good.ini" <<'INI'
[tip]
radius = 100 nm
[material glass]
reduced_modulus = 100 GPa
adhesion_energy = 100 mJ/m^2
INI

expect_error "typo in a key" "typo.ini: [cantilever] spring_constnat: unknown key" "$tiptap" approach "$tmp/typo.ini"
expect_error "missing unit" "nounit.ini: [cantilever] resonance_frequency: missing unit" "$tiptap" trace "$tmp/nounit.ini"
expect_error "negative stiffness" "neg.ini: [cantilever] spring_constant:" "$tiptap" approach "$tmp/neg.ini"
# the whole text of out-of-range messages, with a unit and without one (no double or
# trailing space)
expect_exact "out of range, exact text" \
  "tiptap: $tmp/neg.ini: [cantilever] spring_constant: -0.5 N/m is out of range; expected above 0 N/m" \
  "$tiptap" approach "$tmp/neg.ini"
# an angle's range in degrees, as it was given (issue 32: it read "above 0 rad and below 1.5708 rad")
expect_error "angle out of range in degrees" \
  "[tip] half_angle: 0 deg is out of range; expected above 0 deg and below 90 deg" \
  "$tiptap" scan "$tmp/good.ini" -o "$tmp/never" --set tip.shape=cone --set "tip.half_angle=0 deg"
# the contact law's local geometry runs every cycle: the reduced tiers refuse it by name
expect_error "local geometry on the envelope tier" \
  "[tip] contact_geometry: local runs on the every-cycle tier only (the envelope tier keys its models on the material" \
  "$tiptap" scan "$tmp/good.ini" -o "$tmp/never" --set tip.contact_geometry=local
expect_exact "out of range without a unit, exact text" \
  "tiptap: --set: [scan] pixels: 1 is out of range; expected at least 2 and at most 16384" \
  "$tiptap" scan "$tmp/good.ini" -o "$tmp/never" --set scan.pixels=1
expect_error "NaN" "nan.ini: [material glass] adhesion_energy:" "$tiptap" contact "$tmp/nan.ini"
expect_error "bad --set" "--set: [material glass] adhesion_energy:" "$tiptap" contact "$tmp/good.ini" --set "material.glass.adhesion_energy=5 kHz"
expect_error "missing scene" "$tmp/none.ini" "$tiptap" contact "$tmp/none.ini"
expect_error "unwritable output" "$tmp/no/such/dir/c.csv" "$tiptap" contact --lambda 1 -o "$tmp/no/such/dir/c.csv"
expect_error "unknown material" "no [material quartz]" "$tiptap" contact "$tmp/good.ini" --material quartz
expect_error "both moduli" "[material glass] reduced_modulus: given together with youngs_modulus" "$tiptap" contact "$tmp/good.ini" --set "material.glass.youngs_modulus=70 GPa"
# the z piezo noise's bandwidth: a frequency above 0, at most half the drive frequency
# (it is drawn once per drive cycle), refused before anything runs and no output written
zset=(--set "noise.z_piezo=0.3 pm/sqrt(Hz)" --set scan.pixels=4 --set scan.lines=1)
expect_error "z piezo bandwidth negative" "[noise] z_piezo_bandwidth: -1 kHz is out of range; expected above 0 Hz" \
  "$tiptap" scan "$tmp/good.ini" "${zset[@]}" --set "noise.z_piezo_bandwidth=-1 kHz" -o "$tmp/zbw"
expect_error "z piezo bandwidth unit" "[noise] z_piezo_bandwidth: missing unit in '2'" \
  "$tiptap" scan "$tmp/good.ini" "${zset[@]}" --set "noise.z_piezo_bandwidth=2" -o "$tmp/zbw"
expect_error "z piezo bandwidth above the drive's Nyquist" \
  "[noise] z_piezo_bandwidth: the z piezo's noise bandwidth (200 kHz) is above half the drive frequency (150 kHz)" \
  "$tiptap" scan "$tmp/good.ini" "${zset[@]}" --set "noise.z_piezo_bandwidth=200 kHz" -o "$tmp/zbw"
[ ! -e "$tmp/zbw" ] && echo "ok   z piezo bandwidth: no output" || { echo "FAIL z piezo bandwidth wrote $tmp/zbw"; fail=1; }

# no temporary or partial files left behind
if ls "$tmp"/*.tmp.* >/dev/null 2>&1; then echo "FAIL temporary files left"; fail=1; fi

# the contact summary: DMT and JKR limits, exactly
"$tiptap" contact --model dmt >"$tmp/dmt.txt" || fail=1
grep -q "^pulloff_load = -2$" "$tmp/dmt.txt" && echo "ok   DMT pull-off -2" || { echo "FAIL DMT: $(cat "$tmp/dmt.txt")"; fail=1; }
"$tiptap" contact --model jkr >"$tmp/jkr.txt" || fail=1
grep -q "^pulloff_load = -1.5$" "$tmp/jkr.txt" && echo "ok   JKR pull-off -1.5" || { echo "FAIL JKR: $(cat "$tmp/jkr.txt")"; fail=1; }
grep -q "^jumpout_load = -0.833333333" "$tmp/jkr.txt" && echo "ok   JKR displacement-controlled pull-off -5/6" || { echo "FAIL JKR -5/6"; fail=1; }
"$tiptap" contact --lambda 1 -o "$tmp/c.csv" --plot "$tmp/c.png" >/dev/null || fail=1
head -1 "$tmp/c.csv" | grep -qx "A,Delta,P,stable" && echo "ok   CSV header" || { echo "FAIL CSV header"; fail=1; }
[ -s "$tmp/c.png" ] && echo "ok   plot written" || { echo "FAIL plot"; fail=1; }
"$tiptap" --version | grep -q "^tiptap " && echo "ok   --version" || { echo "FAIL --version"; fail=1; }
# a value that overflows once in SI units, and a modulus past any material (1e300 Pa
# once gave a depth scale of 1e-200 m and a trace cycle that never ended)
printf '[material hard]\nreduced_modulus = 1e308 GPa\n' >"$tmp/huge.ini"
printf '[material hard]\nreduced_modulus = 1e300 Pa\n' >"$tmp/stiff.ini"
for f in huge stiff; do
  msg=$("$tiptap" trace "$tmp/$f.ini" -o "$tmp/$f.csv" 2>&1 >/dev/null); rc=$?
  want="tiptap: $tmp/$f.ini: [material hard] reduced_modulus: "
  [ $rc -eq 1 ] && [ "$(wc -l <<<"$msg")" -eq 1 ] && grep -qF "$want" <<<"$msg" && [ ! -e "$tmp/$f.csv" ] &&
    echo "ok   $f modulus refused" || { echo "FAIL $f modulus: rc $rc '$msg'"; fail=1; }
done
grep -qF "beyond the largest number in SI units" <<<"$("$tiptap" trace "$tmp/huge.ini" 2>&1)" &&
  echo "ok   overflow in SI named" || { echo "FAIL overflow message"; fail=1; }
grep -qF "out of range; expected at most 1e+15 Pa" <<<"$("$tiptap" trace "$tmp/stiff.ini" 2>&1)" &&
  echo "ok   modulus bound named" || { echo "FAIL modulus bound message"; fail=1; }
"$tiptap" frobnicate 2>/dev/null; [ $? -eq 2 ] && echo "ok   unknown command exit 2" || { echo "FAIL unknown command"; fail=1; }
exit $fail
