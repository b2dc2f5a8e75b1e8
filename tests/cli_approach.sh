#!/usr/bin/env bash
# tiptap approach from the command line, steady mode by shooting: stderr tells how many
# points Newton found and names the separations where the approach and the retract
# branch found two stable orbits (the bistable scene, Garcia and San Paulo 1999); the
# settle mode agrees row by row; a misspelt mode is refused in one line.
# usage: cli_approach.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"

scene=$src/examples/extreme/bistable.ini
range=(--set "approach.from=4.9 nm" --set "approach.to=4.1 nm" --set approach.points=5)
if "$tiptap" approach "$scene" "${range[@]}" -o "$tmp/shoot.csv" 2>"$tmp/shoot.err"; then
  ok "approach by shooting ran"
else
  bad "approach by shooting: $(cat "$tmp/shoot.err")"
fi
grep -q "^shooting = [0-9]* of 10 points by Newton, largest Floquet |mu| = 0\.99" "$tmp/shoot.err" &&
  ok "shooting summary" || bad "shooting summary: $(grep shooting "$tmp/shoot.err")"
grep -q "^bistable: two stable orbits (approach and retract branch) at [1-9]" "$tmp/shoot.err" &&
  ok "bistability reported" || bad "no bistability line: $(cat "$tmp/shoot.err")"

"$tiptap" approach "$scene" "${range[@]}" --set approach.steady=settle -o "$tmp/settle.csv" \
  2>"$tmp/settle.err" || bad "approach by settling: $(cat "$tmp/settle.err")"
grep -q "^shooting" "$tmp/settle.err" && bad "settle mode prints a shooting summary" ||
  ok "settle mode: no shooting summary"
# amplitude (nm) and phase (deg) row by row: 1e-6 of the 5 nm free amplitude, 1e-3 deg
paste -d, "$tmp/shoot.csv" "$tmp/settle.csv" | awk -F, 'NR > 1 {
    n = NF / 2; da = $2 - $(n + 2); dp = $3 - $(n + 3)
    if (da < 0) da = -da; if (dp < 0) dp = -dp
    if (da > 5e-6 || dp > 1e-3) { print "row " NR ": " $2 " " $(n + 2) " " $3 " " $(n + 3); bad = 1 }
  } END { exit bad }' && ok "shooting agrees with settling" || bad "shooting and settling differ"

expect_error "misspelt steady mode" "[approach] steady" "$tiptap" approach "$scene" \
  --set approach.steady=newton -o "$tmp/x.csv"

# a steady point on a periodic orbit says so (Burnham et al.'s figure-4a cantilever at
# 200 nm free amplitude, approached in 0.25 nm steps: a period-4 orbit at 7.25 nm): its
# row has period 4 and is settled, and the warning names it
fig4a=$src/examples/seed-fig4a/scene.ini
"$tiptap" approach "$fig4a" --set approach.mode=steady --set "approach.from=20 nm" \
  --set "approach.to=7.25 nm" --set approach.points=52 --set approach.retract=no \
  --set "cantilever.free_amplitude=200 nm" --set approach.max_cycles=1000 -o "$tmp/p4.csv" 2>"$tmp/p4.err"
grep -q "^tiptap approach: warning: 1 of 52 points are periodic orbits .*(z = 7.25 (period 4) nm)" "$tmp/p4.err" &&
  ok "periodic point named in a warning" || bad "periodic point: $(cat "$tmp/p4.err")"
[ "$(tail -n 1 "$tmp/p4.csv" | awk -F, '{print $1, $10, $16}')" = "7.25 1 4" ] &&
  ok "its row: settled, period 4" || bad "its row: $(tail -n 1 "$tmp/p4.csv")"
# a ramp with more rows than cycles is refused before it runs, naming the limit
expect_error "ramp rows beyond its cycles" "[approach] points" "$tiptap" approach "$fig4a" \
  --set "approach.from=130 nm" --set "approach.to=0 nm" --set "approach.speed=40 um/s" --set approach.points=400 \
  -o "$tmp/r.csv"
exit $fail
