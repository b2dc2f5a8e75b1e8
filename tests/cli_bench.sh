#!/usr/bin/env bash
# tiptap bench's imaging, noise and scene figures come out whole and sane (nothing is
# timed here: --quick runs each figure once on lines of 16 pixels at 32 Hz): every row
# present with finite figures, each error estimate at or above the error measured
# against the reference, the envelope tier skipping cycles on the edge sample, the full
# noise set moving the images more than the detector's noise alone, the default tier's
# noise statistics those of every cycle within their sampling error, the averaged row
# either measured or 'not available', and the blend figure's scene the README main
# job's (scans/quick.ini with surfaces/polymer-blend.ini); the lesson's row on the
# envelope tier and, with --lesson-tier averaged, on the averaged tier with its colder
# run's errors.
# usage: cli_bench.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

if diff <("$tiptap" bench --print-blend-scene) <(cat "$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini") \
  >"$tmp/diff"; then
  ok "the blend figure's scene is scans/quick.ini + surfaces/polymer-blend.ini"
else
  bad "the blend figure's scene differs from scans/quick.ini + surfaces/polymer-blend.ini: $(head -5 "$tmp/diff")"
fi

err=$("$tiptap" bench --seeds 0 2>&1 >/dev/null)
[ "$err" = "tiptap bench: --seeds: '0' is not a whole number from 1 to 100" ] && ok "--seeds 0 refused" ||
  bad "--seeds 0: '$err'"

out=$tmp/bench.txt
if ! "$tiptap" bench --quick --no-steady --seeds 2 >"$out" 2>"$tmp/err"; then
  bad "bench --quick failed: $(tail -1 "$tmp/err")"
  exit 1
fi

# The imaging tables: per figure, its rows' labels and figures (wall_j1 to integr_%);
# '-' where a row has none, 'not available' for a tier the build lacks.
awk '
  function num(x) { return x ~ /^-?[0-9.]+(e[-+]?[0-9]+)?$/ }
  /^setting +wall_j1/ { fig++; inrow = 1; next }
  /^#/ || /^$/ { inrow = 0; next }
  inrow && /not available: / { sub(/ +not available: .*/, ""); print fig "|" $0 "|na"; next }
  inrow {
    n = NF; bad = ""
    for (i = n - 10; i <= n; i++) if ($i != "-" && !num($i)) bad = bad " " $i
    lab = $1; for (i = 2; i < n - 10; i++) lab = lab " " $i
    print fig "|" lab "|" (bad == "" ? "ok " $n : "bad" bad)
  }' "$out" >"$tmp/rows"
want="1|reference dopri5 tol 1e-10
1|dopri5 tol 1e-6
1|dopri5 tol 1e-7
1|dopri5 tol 1e-8
1|envelope dopri5 tol 1e-8
1|averaged dopri5 tol 1e-8
2|reference dopri5 tol 1e-10
2|every cycle dopri5 tol 1e-8
2|default tol 1e-8
2|envelope tol 3e-8 (the scene's)
3|reference dopri5 tol 1e-10
3|every cycle dopri5 tol 1e-8
3|default tol 1e-8"
got=$(cut -d'|' -f1,2 "$tmp/rows" | sed 's/|[a-z]* (default) /|default /')
[ "$got" = "$want" ] && ok "imaging, blend and Q 1e4 figures: every row present" ||
  bad "rows: got
$got"
while IFS='|' read -r fig lab res; do
  case $res in
    na) grep -q "^$lab *not available: .*tier" "$out" && ok "$lab: not available (a tier this build lacks)" ||
          bad "$lab: not available for another reason: $(grep "^$lab" "$out")" ;;
    # the averaged tier integrates no cycle; every other row some
    ok\ *) awk -v x="${res#ok }" -v l="$lab" 'BEGIN { exit !((x > 0 || l ~ /^averaged/) && x >= 0 && x <= 100) }' &&
             ok "figure $fig, $lab: finite, ${res#ok }% integrated" ||
             bad "figure $fig, $lab: integrated ${res#ok }%" ;;
    *) bad "figure $fig, $lab: not a number:$res" ;;
  esac
done <"$tmp/rows"
# the envelope tier skips cycles over the edge sample's terraces
env_int=$(grep -m1 '^1|envelope dopri5' "$tmp/rows" | sed 's/.*|ok //')
awk -v x="$env_int" 'BEGIN { exit !(x < 100) }' && ok "the envelope tier integrated $env_int % of the edge lines' cycles" ||
  bad "the envelope tier integrated $env_int % of the edge lines' cycles"

# Each estimate at or above the measured error (the companion line against the reference).
awk '/^setting +h_rms_est/ { t = 1; next } /^#/ || /^$/ { t = 0; next }
  t { n = NF; while (n > 1 && $n !~ /^[-+0-9.eE]+$/ && $n != "nan") n--  # past the check column
      if (n < NF && $(n + 1) != "ok") print $0
      lab = $1; for (i = 2; i <= n - 8; i++) lab = lab " " $i
      for (i = n - 7; i <= n; i += 2) if (!($i + 0 >= $(i + 1) + 0)) print lab ": estimate " $i " below " $(i + 1)
      rows++ }
  END { print rows " rows" }' "$out" >"$tmp/est"
if [ "$(cat "$tmp/est")" = "$(( $(grep -c '|ok' "$tmp/rows") - 3 )) rows" ]; then
  ok "every estimate at or above the measured error ($(cat "$tmp/est"))"
else
  bad "estimates: $(cat "$tmp/est")"
fi

# The estimate with noise: a row per seed with finite figures, its check saying BELOW
# exactly where a max estimate lies under the measured error (with noise it may).
awk '/^noisy run +h_rms_est/ { t = 1; next } /^#/ || /^$/ { t = 0; next }
  t { for (i = 4; i <= 11; i++) if ($i !~ /^[-+0-9.eE]+$/ || $i + 0 < 0) print "not a figure: " $0
      below = $6 + 0 < $7 + 0 || $10 + 0 < $11 + 0
      if (below != ($12 ~ /^BELOW/)) print "check column wrong: " $0
      if (!($5 + 0 > 0 && $7 + 0 > 0)) print "no error measured: " $0
      rows++ }
  END { print rows " rows" }' "$out" >"$tmp/noisy"
[ "$(cat "$tmp/noisy")" = "2 rows" ] && ok "noisy estimate: 2 rows, its check says where it is below" ||
  bad "noisy estimate: $(cat "$tmp/noisy")"

# The noise figure: six rows, positive finite sds, the full set above the detector alone.
awk '/^setting +rtf_j2/ { t = 1; next } /^#/ || /^$/ { t = 0; next }
  t { lab = $1; for (i = 2; i <= NF - 7; i++) lab = lab " " $i
      split($(NF - 3), h, /\+-/); split($(NF - 1), p, /\+-/)
      print lab "|" h[1] "|" p[1] }' "$out" >"$tmp/noise"
labels=$(cut -d'|' -f1 "$tmp/noise" | sed 's/(default)/D/; s/, [a-z]* D$/, default/')
[ "$labels" = "full noise, every cycle
full noise, default
thermal + detector, every cycle
thermal + detector, default
detector noise, every cycle
detector noise, default" ] && ok "noise figure: six rows" || bad "noise rows: $labels"
awk -F'|' '{ if (!($2 > 0 && $2 < 1e6 && $3 > 0 && $3 < 180)) { print "row " NR ": sd " $2 " pm, " $3 " deg"; b = 1 } }
  NR <= 2 { fh[NR] = $2; fp[NR] = $3 } NR > 4 { if (!(fh[NR - 4] > $2 && fp[NR - 4] > $3)) { print "full set not above the detector: " $0; b = 1 } }
  END { exit b }' "$tmp/noise" >"$tmp/noise.bad" && ok "noise: sds positive and finite; the full set's above the detector's alone" ||
  bad "noise: $(cat "$tmp/noise.bad")"
# the default tier against every cycle at the same seeds: sd ratios within 4 standard
# errors (and 0.1) of 1
awk '/^noise +h_sd_ratio/ { t = 1; next } /^#/ || /^$/ { t = 0; next }
  t { for (i = NF - 5; i <= NF - 4; i++) { split($i, r, /\+-/)
        d = r[1] - 1; if (d < 0) d = -d
        if (!(d <= 4 * r[2] + 0.1)) { print $0; b = 1 } }
      rows++ }
  END { if (rows != 3) { print rows " rows"; b = 1 } exit b }' "$out" >"$tmp/ratio.bad" &&
  ok "noise: the default tier's sds those of every cycle within sampling error" || bad "noise ratios: $(cat "$tmp/ratio.bad")"

# The lesson figure (--quick: the 40 Hz lines' setting, two lines): its row with finite
# figures, the every-cycle tier integrating every cycle and the default tier fewer, and
# the counts of why, per line, the model having run cycles.
awk '/^setting +tier +rt\/cpu_s/ { t = 1; next } /^ / { next } /^#/ || /^$/ { t = 0; next }
  t { split($(NF - 2), h, "/"); split($(NF - 1), p, "/")
      if (!($1 == "40" && $(NF - 6) == "envelope" && $(NF - 5) > 0 && $(NF - 4) > 0 && $(NF - 4) < 100 &&
            $(NF - 3) > 0 && $NF == 100.0 && h[1] >= h[2] && h[2] >= 0 && p[1] >= p[2] && p[2] >= 0 && h[1] < 1e3)) {
        print $0; b = 1 }
      rows++ }
  /^setting +model +check_pass/ { w = 1; next }
  w && /^40 Hz lines/ { if (!($(NF - 15) > 0 && $(NF - 8) > 0)) { print "why: " $0; b = 1 } whys++ }
  END { if (rows != 1 || whys != 1) { print rows " rows, " whys " why rows"; b = 1 } exit b }' "$out" >"$tmp/lesson.bad" &&
  ok "lesson: the 40 Hz lines' row and its counts" || bad "lesson: $(cat "$tmp/lesson.bad")"
err=$("$tiptap" bench --lesson-lines 1 2>&1 >/dev/null)
[ "$err" = "tiptap bench: --lesson-lines: '1' is not a whole number from 2 to 64" ] && ok "--lesson-lines 1 refused" ||
  bad "--lesson-lines 1: '$err'"
err=$("$tiptap" bench --lesson-setting 8 2>&1 >/dev/null)
[ "$err" = "tiptap bench: --lesson-setting: '8' is not a whole number from 1 to 7" ] && ok "--lesson-setting 8 refused" ||
  bad "--lesson-setting 8: '$err'"
err=$("$tiptap" bench --lesson-tier every 2>&1 >/dev/null)
[ "$err" = "tiptap bench: --lesson-tier: 'every' is not envelope or averaged" ] && ok "--lesson-tier every refused" ||
  bad "--lesson-tier every: '$err'"

# The lesson on the averaged tier (the 40 Hz lines, two lines): its row with the colder
# run's errors, finite and at most the noisy run's by a fifth plus 1 nm and 20 deg, some
# cycles integrated where the slow flow fails but not most, and the colder ring of both
# tiers (frequency, amplitude) positive.
"$tiptap" bench --lesson-only --lesson-tier averaged --lesson-setting 7 --lesson-lines 2 >"$tmp/avg.txt" 2>&1
awk '/^40 Hz lines/ { split($(NF - 6), h, "/"); split($(NF - 3), c, "/"); split($(NF - 2), q, "/")
      split($(NF - 1), rf, "/"); split($NF, ra, "/")
      if (!($(NF - 10) == "averaged" && $(NF - 9) > 0 && $(NF - 8) > 0 && $(NF - 8) < 50 && c[1] >= c[2] &&
            c[2] > 0 && c[1] <= 1.2 * h[1] + 1 && q[1] >= q[2] && q[1] < 360 && rf[1] > 0 && rf[2] > 0 &&
            ra[1] > 0 && ra[2] > 0)) { print $0; b = 1 }
      rows++ }
  /why the envelope tier/ { print "the envelope counts on the averaged tier"; b = 1 }
  END { if (rows != 1) { print rows " rows"; b = 1 } exit b }' "$tmp/avg.txt" >"$tmp/avg.bad" &&
  ok "lesson on the averaged tier: the 40 Hz lines' row with its colder errors" || bad "lesson averaged: $(cat "$tmp/avg.bad")"

exit $fail
