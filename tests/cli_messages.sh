#!/usr/bin/env bash
# Every message names the file and the key (issue 19, item 4): [trace] ramp refusals,
# a rule between keys is named on the key the scene set, not on a default of the rule
printf '[surface]\ntype = particles\n[scan]\nsize = 100 um\npixels = 16\nlines = 16\n' >"$tmp/p.ini"
expect_error "particles: the scan size named, not the defaulted radius" \
  "p.ini: [scan] size: spheres of 40 nm across are narrower than a pixel of the image (6250 nm)" \
  "$tiptap" scan "$tmp/p.ini" -o "$tmp/p"
[ -e "$tmp/p" ] && bad "a refused scan made its folder" || ok "no folder"

# an allocation that fails, a derived quantity out of range (named by the key the user
# set, not by one the scene never set).
# usage: cli_messages.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

# [trace] ramp: these lost the file name (the ramp is applied by the run's setup)
ramp() { # name, expected message after "tiptap: FILE: ", ramp lines
  local name=$1 want=$2; shift 2
  printf '[material silicon]\n[trace]\ncycles = 4\nsettle_cycles = 4\n' >"$tmp/r.ini"
  printf '%s\n' "$@" >>"$tmp/r.ini"
  expect_exact "$name" "tiptap: $tmp/r.ini: $want" "$tiptap" trace "$tmp/r.ini" -o "$tmp/r.csv"
}
ramp "ramp of an unrampable key" \
  "[trace] ramp: trace.cycles: only [cantilever], [tip] and [material] keys can be ramped" \
  "ramp = trace.cycles" "ramp_from = 1" "ramp_to = 2"
ramp "ramp of a missing material" \
  "[trace] ramp: material.nosuch.reduced_modulus: no [material nosuch] in the scene" \
  "ramp = material.nosuch.reduced_modulus" "ramp_from = 1 GPa" "ramp_to = 2 GPa"
ramp "ramp of the drive frequency" \
  "[trace] ramp_to: cantilever.drive_frequency: a ramp may not change the drive frequency" \
  "ramp = cantilever.drive_frequency" "ramp_from = 300 kHz" "ramp_to = 200 kHz"
[ -e "$tmp/r.csv" ] && bad "a refused trace wrote its file" || ok "no trace file"
# [approach]'s own checks name the file too
printf '[approach]\nmode = ramp\nfrom = 20 nm\nto = 0 nm\npoints = 100\nspeed = 1 mm/s\n' >"$tmp/a.ini"
expect_error "approach ramp check names the file" "$tmp/a.ini: [approach] points: 100 rows but the ramp takes" \
  "$tiptap" approach "$tmp/a.ini" -o "$tmp/a.csv"

# a modulus of 1 kPa with adhesion: refused as interatomic_distance, a key never set
printf '[material soft]\nreduced_modulus = 1 kPa\nadhesion_energy = 50 mJ/m^2\n' >"$tmp/soft.ini"
expect_error "derived lambda names the modulus" \
  "soft.ini: [material soft] reduced_modulus: 1 kPa gives lambda = 1.55e+04 (Burnham et al. eq. 3" \
  "$tiptap" contact "$tmp/soft.ini"
out=$("$tiptap" contact "$tmp/soft.ini" 2>&1)
grep -qF "the reduced modulus would have to lie from 1.93e+03 to 1.93e+15 Pa" <<<"$out" &&
  ok "the moduli that would do" || bad "no range: '$out'"
# ... and the range it names works at its lower end
"$tiptap" contact "$tmp/soft.ini" --set "material.soft.reduced_modulus=1.94 kPa" >/dev/null 2>&1 &&
  ok "1.94 kPa accepted" || bad "1.94 kPa refused"
printf '[material soft]\nyoungs_modulus = 1 kPa\nadhesion_energy = 50 mJ/m^2\n' >"$tmp/young.ini"
expect_error "derived lambda names youngs_modulus" "young.ini: [material soft] youngs_modulus: 1 kPa gives lambda" \
  "$tiptap" trace "$tmp/young.ini"
printf '[material weak]\nadhesion_energy = 1e-12 J/m^2\n' >"$tmp/weak.ini"
expect_error "derived lambda names the adhesion energy" \
  "weak.ini: [material weak] adhesion_energy: 1e-12 J/m^2 gives lambda = 5.5e-08" "$tiptap" approach "$tmp/weak.ini"

# a rule between keys is named on the key the scene set, not on a default of the rule
printf '[surface]\ntype = particles\n[scan]\nsize = 100 um\npixels = 16\nlines = 16\n' >"$tmp/p.ini"
expect_error "particles: the scan size named, not the defaulted radius" \
  "p.ini: [scan] size: spheres of 40 nm across are narrower than a pixel of the image (6250 nm)" \
  "$tiptap" scan "$tmp/p.ini" -o "$tmp/p"
[ -e "$tmp/p" ] && bad "a refused scan made its folder" || ok "no folder"

# an allocation that fails says what it was for and the file: a scene line of 100 MB
# under a 300 MB address space (a sanitizer build cannot start under ulimit -v: skipped)
if (ulimit -v 300000; "$tiptap" keys >/dev/null 2>&1); then
  { printf '[material x]\nmap_value = '; head -c 100000000 /dev/zero | tr '\0' A; echo; } >"$tmp/big.ini"
  expect_exact "out of memory names what and the file" \
    "tiptap: out of memory for line 2 of $tmp/big.ini (100000012 bytes)" \
    bash -c "ulimit -v 300000; exec '$tiptap' contact '$tmp/big.ini'"
  rm -f "$tmp/big.ini"
else
  ok "out of memory: skipped (cannot run under ulimit -v)"
fi
exit $fail
