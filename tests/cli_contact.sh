#!/usr/bin/env bash
# tiptap contact from the command line: the DMT and JKR ends of the Maugis summary, enough
# digits for 1e-6 to mean something, the curve CSV and PNG, physical values and the
# Hamaker constant for each model of a scene, and one-line refusal of a misspelt key.
# usage: cli_contact.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

value() { # key, file: the value of "key = value"
  awk -v k="$1" '$1 == k && $2 == "=" { print $3; exit }' "$2"
}
near() { # got, want, tolerance: exit 0 when |got - want| <= tolerance
  awk -v g="$1" -v w="$2" -v t="$3" 'BEGIN { d = g - w; if (d < 0) d = -d; exit !(g != "" && d <= t) }'
}
digits() { # significant digits written in a number
  local m=${1%%[eE]*}
  m=${m#-}
  m=${m/./}
  m=$(sed 's/^0*//' <<<"$m")
  echo ${#m}
}

# the Maugis summary tends to JKR (-1.5) and DMT (-2), printed with 10 significant digits
for case in "1000 -1.5" "0.001 -2"; do
  set -- $case
  if ! "$tiptap" contact --lambda "$1" >"$tmp/l$1.txt"; then bad "contact --lambda $1 ran"; continue; fi
  p=$(value pulloff_load "$tmp/l$1.txt")
  near "$p" "$2" 1e-3 && ok "lambda $1: pulloff_load $p near $2" || bad "lambda $1: pulloff_load '$p', expected $2"
  n=$(digits "$p")
  [ "$n" -ge 10 ] && ok "lambda $1: $n significant digits" || bad "lambda $1: pulloff_load '$p' has $n digits"
  for k in P0 Delta0 pulloff_delta jumpout_delta jumpout_load jumpin_load; do
    [ -n "$(value $k "$tmp/l$1.txt")" ] || bad "lambda $1: no $k"
  done
done

# JKR's infinite lambda is explained, and the value still reads as a number
"$tiptap" contact --model jkr >"$tmp/jkr.txt" || bad "contact --model jkr ran"
grep -qx "lambda = inf (JKR limit)" "$tmp/jkr.txt" && [ "$(value lambda "$tmp/jkr.txt")" = inf ] &&
  ok "JKR lambda" || bad "JKR lambda: $(grep lambda "$tmp/jkr.txt")"

# the curve: CSV with its header, PNG with its signature
if "$tiptap" contact --lambda 2 -o "$tmp/curve.csv" --plot "$tmp/curve.png" >/dev/null; then
  head -1 "$tmp/curve.csv" | grep -qx "A,Delta,P,stable" && ok "CSV header" || bad "CSV header: $(head -1 "$tmp/curve.csv")"
  [ "$(wc -l <"$tmp/curve.csv")" -gt 100 ] && ok "CSV rows" || bad "CSV has $(wc -l <"$tmp/curve.csv") lines"
  sig=$(head -c 8 "$tmp/curve.png" | od -An -tx1 | tr -d ' \n')
  [ "$sig" = 89504e470d0a1a0a ] && ok "PNG signature" || bad "PNG signature '$sig'"
else
  bad "contact -o --plot ran"
fi

# a scene: physical values and the Hamaker constant, for each model
cat >"$tmp/glass.ini" <<'INI'
[tip]
radius = 100 nm
[material glass]
reduced_modulus = 100 GPa
adhesion_energy = 100 mJ/m^2
interatomic_distance = 0.265 nm
[material mica]
reduced_modulus = 50 GPa
adhesion_energy = 200 mJ/m^2
interatomic_distance = 0.3 nm
INI
for model in maugis dmt jkr hertz; do
  out="$tmp/scene-$model.txt"
  if ! "$tiptap" contact "$tmp/glass.ini" --model $model >"$out"; then bad "scene, $model ran"; continue; fi
  miss=""
  for k in reduced_modulus_Pa radius_m adhesion_energy_J_per_m2 hamaker_J loop_energy_J; do
    [ -n "$(value $k "$out")" ] || miss="$miss $k"
  done
  if [ "$model" != hertz ]; then
    for k in force_scale_N depth_scale_m P0_N delta0_m pulloff_load_N jumpout_delta_m jumpin_load_N; do
      [ -n "$(value $k "$out")" ] || miss="$miss $k"
    done
    # physical = normalised * F*, F* = pi w R = 3.14159e-8 N
    near "$(value pulloff_load_N "$out")" "$(awk -v p="$(value pulloff_load "$out")" 'BEGIN { printf "%.12g", p * 3.14159265358979e-8 }')" 1e-16 ||
      miss="$miss pulloff_load_N(=pulloff_load*F*)"
  fi
  [ -z "$miss" ] && ok "scene, $model: physical values" || bad "scene, $model: missing or wrong$miss"
done
# the Hamaker constant by continuity is of the order of 1e-19 J (Burnham et al.), none for JKR and Hertz
for case in "maugis 5e-20 5e-19" "dmt 5e-20 5e-19" "jkr 0 0" "hertz 0 0"; do
  set -- $case
  h=$(value hamaker_J "$tmp/scene-$1.txt")
  awk -v h="$h" -v lo="$2" -v hi="$3" 'BEGIN { exit !(h != "" && h >= lo && h <= hi) }' &&
    ok "scene, $1: hamaker_J = $h" || bad "scene, $1: hamaker_J '$h' outside [$2, $3]"
done
# --material picks the section; the first one is the default
"$tiptap" contact "$tmp/glass.ini" --material mica >"$tmp/mica.txt" || bad "--material mica ran"
[ "$(value adhesion_energy_J_per_m2 "$tmp/mica.txt")" = 0.2 ] && ok "--material mica" || bad "--material mica: $(value adhesion_energy_J_per_m2 "$tmp/mica.txt")"
[ "$(value adhesion_energy_J_per_m2 "$tmp/scene-maugis.txt")" = 0.1 ] && ok "first material by default" || bad "default material"

# a misspelt key: non-zero exit, one line naming the file, the section and the key
cat >"$tmp/typo.ini" <<'INI'
[cantilever]
spring_constnat = 2 N/m
INI
err=$("$tiptap" contact "$tmp/typo.ini" 2>&1 >/dev/null); rc=$?
if [ $rc -eq 0 ]; then
  bad "typo: exit 0"
elif [ "$(wc -l <<<"$err")" -ne 1 ]; then
  bad "typo: not one line: $err"
elif ! grep -qF "typo.ini: [cantilever] spring_constnat:" <<<"$err"; then
  bad "typo: '$err' does not name file, section and key"
else
  ok "typo: exit $rc, one line naming file, section and key"
fi
exit $fail
