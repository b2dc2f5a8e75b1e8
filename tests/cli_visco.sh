#!/usr/bin/env bash
# Viscous samples in every command (docs/physics.md, Viscoelastic samples): a zero
# viscosity writes the elastic scene's files byte for byte; approach and sweep book the
# loss per mechanism; trace ramps the viscosity; a scan of examples/viscoelastic-blend
# shows the viscous disks' dissipation, all of it in its viscous channel; a film
# stiffens the contact; the console serves the blend; bad keys are refused with one line.
# usage: cli_visco.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

cat >"$tmp/soft.ini" <<'EOF'
[material soft]
youngs_modulus = 1 GPa
poisson_ratio = 0.4
interaction_quality_factor = 20
[approach]
from = 10 nm
to = -2 nm
points = 4
EOF
ap() { "$tiptap" approach -q "$tmp/soft.ini" "$@" 2>/dev/null; }

# zero viscosity is the elastic law: the same bytes, the same columns
ap -o "$tmp/e.csv" && ap --set "material.soft.viscosity=0 Pa s" -o "$tmp/z.csv" &&
  cmp -s "$tmp/e.csv" "$tmp/z.csv" && ! grep -q viscous "$tmp/e.csv" &&
  ok "zero viscosity: the elastic approach byte for byte" || bad "zero viscosity differs"

# a viscous sample: three more columns, the total their sum, the viscous part positive
ap --set "material.soft.viscosity=200 Pa s" -o "$tmp/v.csv"
if head -1 "$tmp/v.csv" | grep -q ',dissipated_hysteresis_aJ,dissipated_damping_aJ,dissipated_viscous_aJ$' &&
   awk -F, 'NR > 1 { s = $17 + $18 + $19; if ($19 <= 0 || $18 <= 0 || (s - $8) ^ 2 > 1e-14 * $8 ^ 2) bad = 1 }
            END { exit bad || NR < 5 }' "$tmp/v.csv"; then
  ok "viscous approach: dissipated = hysteresis + damping + viscous"
else
  bad "viscous approach: $(cat "$tmp/v.csv")"
fi

# a sweep over the viscosity: the viscous loss grows with it
"$tiptap" sweep -q "$tmp/soft.ini" --vary "material.soft.viscosity=0 Pa s,100 Pa s,300 Pa s" -j 1 \
  -o "$tmp/s.csv" 2>/dev/null
if head -1 "$tmp/s.csv" | grep -q 'material.soft.viscosity\[Pa s\].*,dissipated_viscous_aJ$' &&
   awk -F, 'NR > 1 { if ($NF < prev || (NR == 2 && $NF != 0)) bad = 1; prev = $NF } END { exit bad || prev <= 0 }' "$tmp/s.csv"; then
  ok "sweep over the viscosity: $(awk -F, 'NR > 1 { printf "%s ", $NF }' "$tmp/s.csv")aJ"
else
  bad "sweep: $(cat "$tmp/s.csv")"
fi

# a trace ramping the viscosity
if "$tiptap" trace -q "$tmp/soft.ini" --set trace.separation=5nm --set trace.cycles=4 \
     --set trace.ramp=material.soft.viscosity --set "trace.ramp_from=0 Pa s" \
     --set "trace.ramp_to=300 Pa s" -o "$tmp/t.csv" 2>"$tmp/t.err" &&
   [ "$(wc -l <"$tmp/t.csv")" -gt 100 ]; then
  ok "trace ramps the viscosity"
else
  bad "trace: $(cat "$tmp/t.err")"
fi

# the blend example: the viscous disks dissipate, the elastic matrix does not
blend=("$src/scans/quick.ini" "$src/examples/viscoelastic-blend/scene.ini" --set scan.pixels=16
       --set scan.lines=2 --set scan.profile_line=0)
if "$tiptap" scan "${blend[@]}" -o "$tmp/blend" 2>"$tmp/blend.err" >/dev/null &&
   awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "dissipation_trace_J") c = i }
            NR > 1 { if ($c > 5e-18) hi++; if ($c == 0) zero++ } END { exit !(hi > 0 && zero > 0) }' \
     "$tmp/blend/profile.csv"; then
  ok "blend scan: dissipation on the disks, none on the matrix"
else
  bad "blend scan: $(cat "$tmp/blend.err")"
fi

# its loss per mechanism: all of it viscous, the channel's files written
if [ -f "$tmp/blend/dissipation_viscous_trace.gsf" ] && [ -f "$tmp/blend/dissipation_viscous_trace.png" ] &&
   awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
            { if ($c["dissipation_hysteresis_trace_J"] != 0 || $c["dissipation_damping_trace_J"] != 0 ||
                  $c["dissipation_viscous_trace_J"] != $c["dissipation_trace_J"]) bad = 1 }
            END { exit bad || NR < 17 }' "$tmp/blend/profile.csv"; then
  ok "blend scan: dissipation_viscous holds the whole loss, hysteresis and damping none"
else
  bad "blend scan's loss channels: $(head -2 "$tmp/blend/profile.csv")"
fi
expect_error "the loss per mechanism on the averaged tier" "[scan] channels: the averaged tier books" \
  "$tiptap" scan "${blend[@]}" --set solver.tier=averaged -o "$tmp/avg"

# a thin film on a rigid substrate is stiffer: less indentation at the same separation
ap --set "material.soft.film_thickness=5 nm" -o "$tmp/f.csv"
if awk -F, 'FNR == 1 { next } NR == FNR { e[FNR] = $6; next } { if ($6 >= e[FNR]) bad = 1 } END { exit bad }' \
     "$tmp/e.csv" "$tmp/f.csv"; then
  ok "film: less indentation than bulk"
else
  bad "film: $(cat "$tmp/f.csv")"
fi

expect_error "a film on an adhesive law" "[material soft] film_thickness" \
  "$tiptap" approach "$tmp/soft.ini" --set "material.soft.film_thickness=5 nm" \
  --set "material.soft.adhesion_energy=50 mJ/m^2" -o "$tmp/x.csv"
expect_error "a viscosity without its unit" "expected a viscosity such as '5 Pa s'" \
  "$tiptap" approach "$tmp/soft.ini" --set "material.soft.viscosity=5 Pa" -o "$tmp/x.csv"
expect_error "a negative viscosity" "[material soft] viscosity" \
  "$tiptap" approach "$tmp/soft.ini" --set "material.soft.viscosity=-1 Pa s" -o "$tmp/x.csv"

# the console runs the blend: a row of the image arrives
if [ -x /usr/bin/python3 ]; then
  source "$(dirname "$0")/tt_live.sh"
  mkdir -p "$tmp/tmpdir"
  export TMPDIR="$tmp/tmpdir"
  live_start "${blend[@]}" --set scan.line_rate=8Hz
  if [ -n "$port" ] && PYTHONPATH="$(dirname "$0")" timeout 60 /usr/bin/python3 -c "
import sys
from live_ws import WS
ws = WS(int(sys.argv[1]))
ws.recv_type('row')
ws.close()" "$port"; then
    ok "live serves the viscous blend"
  else
    bad "live: $(cat "$tmp/err")"
  fi
  [ -n "$pid" ] && kill -INT "$pid" 2>/dev/null && wait "$pid"
else
  echo "skip the console: no /usr/bin/python3"
fi
exit $fail
