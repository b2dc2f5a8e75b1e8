#!/usr/bin/env bash
# tiptap contact at the extremes of its numeric options: each value is either refused in
# one line with a non-zero exit, or computed, with no nan (and no inf but JKR's lambda)
# in its summary or CSV. Before, --xi0 1e300 printed loop_area = -nan with exit 0 (its
# van der Waals branch squared the distance), and a scene's interatomic_distance = 1e300 m
# beside a given lambda printed xi0_m = inf, hamaker_J = inf and loop_energy_J = -nan.
# The loop area now converges as xi0 grows (1.636405e-5 at lambda 1 from xi0 = 1e4 on).
# usage: cli_contact_extremes.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
source "$(dirname "$0")/tt_cli.sh"

check() { # name, args...: refused in one line, or no nan/inf in the output
  local name=$1; shift
  local rc out
  "$tiptap" contact "$@" -o "$tmp/c.csv" >"$tmp/out" 2>"$tmp/err"; rc=$?
  if [ $rc -ne 0 ]; then
    [ "$(wc -l <"$tmp/err")" -eq 1 ] && [ ! -s "$tmp/out" ] && ok "$name: refused ($(cut -c1-90 "$tmp/err"))" ||
      bad "$name: exit $rc, stderr $(cat "$tmp/err"), stdout $(cat "$tmp/out")"
    return
  fi
  if grep -v "^lambda = inf (JKR limit)$" "$tmp/out" | grep -qi "nan\|inf" || grep -qi "nan\|inf" "$tmp/c.csv"; then
    bad "$name: exit 0 with $(grep -i "nan\|inf" "$tmp/out" "$tmp/c.csv" | head -3)"
  else
    ok "$name: computed"
  fi
}

for v in 1e-300 1e-5 1e4 1e300 inf -inf nan 0 -1; do
  check "--lambda $v" --lambda "$v"
done
for model in maugis dmt jkr hertz; do
  lam=(); [ $model = maugis ] && lam=(--lambda 1)
  for v in 1e-300 1e-6 0.3 1e6 1e7 1e300 inf nan 0 -1; do
    check "--model $model --xi0 $v" "${lam[@]}" --model $model --xi0 "$v"
  done
done
printf '[material m]\nyoungs_modulus = 1 GPa\nadhesion_energy = 50 mJ/m^2\n' >"$tmp/m.ini"
for model in maugis dmt jkr; do
  for v in 1e-300m 1e-15m 1e-3m 1e300m; do
    check "scene $model, lambda 1, interatomic_distance $v" "$tmp/m.ini" --set material.m.model=$model \
      --set material.m.lambda=1 --set "material.m.interatomic_distance=$v"
  done
done
for kv in youngs_modulus=1e-300Pa youngs_modulus=1e300Pa adhesion_energy=1e-300J/m^2 adhesion_energy=1e300J/m^2 \
  poisson_ratio=1e-300 poisson_ratio=0.4999 interaction_quality_factor=1e-300 interaction_quality_factor=1e300; do
  check "scene $kv" "$tmp/m.ini" --set "material.m.$kv"
done
# the loop area converges as the distance grows (as 1 / xi0), where it was lost to
# rounding (1.4e-5 of it at 1e6)
a5=$("$tiptap" contact --lambda 1 --xi0 1e5 2>/dev/null | sed -n 's/^loop_area = //p')
a6=$("$tiptap" contact --lambda 1 --xi0 1e6 2>/dev/null | sed -n 's/^loop_area = //p')
awk -v a="$a5" -v b="$a6" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d < 1e-6 * a && a > 1.6e-5 && a < 1.7e-5) }' &&
  ok "loop area at xi0 1e5 and 1e6: $a5, $a6" || bad "loop area at xi0 1e5 and 1e6: $a5, $a6"
exit $fail
