#!/usr/bin/env bash
# tiptap accuracy from the command line: the CSV and its header, the work-precision
# PNG, the summary, and bad options and scenes refused with one line and a non-zero exit.
# usage: cli_accuracy.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

# a cheap tapping point: Q 40 settles in about 240 cycles
cat >"$tmp/tap.ini" <<'INI'
[cantilever]
spring_constant = 40 N/m
resonance_frequency = 300 kHz
quality_factor = 40
free_amplitude = 20 nm
[tip]
radius = 10 nm
[material polymer]
youngs_modulus = 2 GPa
adhesion_energy = 40 mJ/m^2
interaction_quality_factor = 2
INI
"$tiptap" accuracy "$tmp/tap.ini" --methods dopri5 --repeats 1 -o "$tmp/a.csv" --plot "$tmp/a.png" \
  >"$tmp/out.txt" 2>"$tmp/err.txt" || bad "accuracy ran: $(cat "$tmp/err.txt")"
head -1 "$tmp/a.csv" | grep -qx "method,tier,knob,value,run_time_s,cpu_time_s,steps_per_cycle,integrated,amplitude_err_rel,phase_err_deg,mean_err_m,peak_force_err_rel,dissipation_err_rel,residual_rel,role,is_default,status" \
  && ok "CSV header" || bad "CSV header: $(head -1 "$tmp/a.csv")"
# reference, floor, 15 tolerances with the default among them
[ "$(wc -l <"$tmp/a.csv")" -eq 18 ] && ok "CSV rows" || bad "CSV rows $(wc -l <"$tmp/a.csv")"
grep -q "^dopri5,every,tolerance,1e-08,.*,setting,1,ok$" "$tmp/a.csv" && ok "default row marked" || bad "default row"
grep -q "^dopri5,every,tolerance,1e-12,.*,floor,0,ok$" "$tmp/a.csv" && ok "floor row" || bad "floor row"
[ "$(head -c 8 "$tmp/a.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] && ok "PNG written" || bad "PNG"
grep -q "(default)" "$tmp/out.txt" && ok "table on stdout" || bad "table: $(cat "$tmp/out.txt")"
grep -q "^cheapest dopri5 with relative amplitude error <= 0.0001: dopri5 tolerance" "$tmp/err.txt" && ok "cheapest setting" || bad "cheapest: $(cat "$tmp/err.txt")"
grep -q "^ten times more accurate" "$tmp/err.txt" && ok "ten times more accurate" || bad "10x: $(cat "$tmp/err.txt")"
# (a sanitizer build appends its leak-suppression report: cut it off)
sed '/^-----/,$d' "$tmp/err.txt" >"$tmp/summary.txt"
tail -2 "$tmp/summary.txt" | head -1 | grep -q "^run_time_s = " && tail -1 "$tmp/summary.txt" | grep -q "^error_estimate = " \
  && ok "ends with run time and error estimate" || bad "summary end: $(tail -2 "$tmp/summary.txt")"
ls "$tmp" | grep -q "\.tmp\." && bad "temporary files left" || ok "no temporary files"

# a scan scene is judged by a short line: height and phase columns, and the envelope
# tier (the scan's default) has its own ladder
cat >"$tmp/scan.ini" <<'INI'
[scan]
size = 1 um
pixels = 64
line_rate = 50 Hz
settle_cycles = 300
INI
"$tiptap" accuracy "$tmp/tap.ini" "$tmp/scan.ini" --methods rk4 --pixels 3 --repeats 1 -q -o "$tmp/l.csv" \
  || bad "line ran"
head -1 "$tmp/l.csv" | grep -qx "method,tier,knob,value,run_time_s,cpu_time_s,steps_per_cycle,integrated,height_err_max_m,height_err_rms_m,phase_err_max_deg,phase_err_rms_deg,residual_rel,role,is_default,status" \
  && ok "line CSV header" || bad "line CSV header: $(head -1 "$tmp/l.csv")"
# the default (envelope tier, dopri5 1e-8) is judged even when its ladder is left out
grep -q "^dopri5,envelope,tolerance,1e-08,.*,setting,1,ok$" "$tmp/l.csv" && ok "line default on the envelope tier" \
  || bad "line default: $(cat "$tmp/l.csv")"
"$tiptap" accuracy "$tmp/tap.ini" "$tmp/scan.ini" --methods envelope --pixels 3 --repeats 1 -o "$tmp/e.csv" \
  >"$tmp/eout.txt" 2>"$tmp/eerr.txt" || bad "envelope ladder ran: $(cat "$tmp/eerr.txt")"
[ "$(grep -c "^dopri5,envelope,tolerance,.*,setting,[01],ok$" "$tmp/e.csv")" -eq 15 ] && ok "envelope ladder rows" \
  || bad "envelope rows: $(cat "$tmp/e.csv")"
grep -q "^envelope (dopri5) tolerance 1e-08 (default)" "$tmp/eout.txt" && ok "envelope rows named" \
  || bad "envelope table: $(cat "$tmp/eout.txt")"
grep -q "^cheapest envelope with largest height error / free amplitude <= 0.0001: .*of the cycles integrated)$" \
  "$tmp/eerr.txt" && ok "envelope summary" || bad "envelope summary: $(cat "$tmp/eerr.txt")"
expect_error "envelope on a point" "judged on scan lines" "$tiptap" accuracy "$tmp/tap.ini" --methods envelope

cat >"$tmp/typo.ini" <<'INI'
[solver]
tolerence = 1e-9
INI
expect_error "bad scene key" "typo.ini: [solver] tolerence: unknown key" "$tiptap" accuracy "$tmp/typo.ini"
expect_error "unknown option" "unrecognized option" "$tiptap" accuracy --frobnicate "$tmp/tap.ini"
expect_error "bad --point" "--point: '16 kHz': wrong unit" "$tiptap" accuracy "$tmp/tap.ini" --point "16 kHz"
expect_error "unknown method" "unknown method 'euler'" "$tiptap" accuracy "$tmp/tap.ini" --methods euler
expect_error "bad --cycles" "--cycles" "$tiptap" accuracy "$tmp/tap.ini" --cycles 3
expect_error "bad --clock" "--clock" "$tiptap" accuracy "$tmp/tap.ini" --clock sundial
expect_error "missing scene" "$tmp/none.ini" "$tiptap" accuracy "$tmp/none.ini"
expect_error "no scene" "needs a scene file" "$tiptap" accuracy
expect_error "unknown material" "no [material quartz]" "$tiptap" accuracy "$tmp/tap.ini" --set approach.material=quartz
expect_error "unwritable output" "$tmp/no/dir/a.csv" "$tiptap" accuracy "$tmp/tap.ini" -o "$tmp/no/dir/a.csv"
"$tiptap" accuracy --help | grep -q "^Usage: tiptap accuracy" && ok "--help" || bad "--help"
exit $fail
