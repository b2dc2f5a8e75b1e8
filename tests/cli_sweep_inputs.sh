#!/usr/bin/env bash
# tiptap sweep refuses before anything runs, in one line and writing nothing: a grid
# beyond the maximum (with its --vary arguments and the count, also far beyond 64 bits,
# at once: nothing is enumerated), ranges that would repeat or drop values, and an
# output it could not write at the end (the table, the --plot PNG, a scan's folders);
# a range whose span overflows a double still gives finite values, never -nan.
# usage: cli_sweep_inputs.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
blend=$src/surfaces/polymer-blend.ini
cd "$tmp" || exit 1

# counts: three ranges of 1e7 (1e21, beyond 2^64) and one range of 10^400 points
expect_error "1e21 combinations refused with the count" \
  "--vary approach.from=1nm:2nm:10000000 --vary cantilever.free_amplitude=1nm:2nm:10000000 --vary approach.points=1:1000:10000000: 1e+21 (about 2^70) combinations, more than the 10000000" \
  "$tiptap" sweep "$blend" --vary approach.from=1nm:2nm:10000000 --vary cantilever.free_amplitude=1nm:2nm:10000000 \
  --vary approach.points=1:1000:10000000 -o big.csv
n400=$(printf '9%.0s' $(seq 400))
expect_error "10^400 combinations refused" "about 10^400 combinations" \
  "$tiptap" sweep "$blend" --vary "approach.from=1nm:2nm:$n400" -o big.csv
expect_error "one over the maximum refused exactly" ": 10001000 combinations, more than the 10000000" \
  "$tiptap" sweep "$blend" --vary approach.from=1nm:2nm:1000 --vary cantilever.free_amplitude=1nm:2nm:10001 -o big.csv
# at once: within a generous bound (the issue asks for O(1)), 20 grids in a row; the
# bound tells a refusal from counting 1e14 points (years), not one machine from another:
# 20 starts of the sanitizer build took 11 to 12 s at a load of 7 to 8
start=$(date +%s%N)
for _ in $(seq 20); do
  "$tiptap" sweep "$blend" --vary approach.from=1nm:2nm:10000000 --vary approach.points=1:1000:10000000 \
    -o big.csv 2>/dev/null
done
ms=$((($(date +%s%N) - start) / 1000000))
[ "$ms" -lt 60000 ] && ok "20 refusals of 1e14 combinations in $ms ms" || bad "refusals took $ms ms"

# ranges: duplicates, a dropped end, alike ends
expect_error "whole-number range with repeats" "approach.points=2:4:5: 5 whole numbers from 2 to 4 would repeat" \
  "$tiptap" sweep "$blend" --vary approach.points=2:4:5 -o r.csv
expect_error "N = 1 would drop TO" "cantilever.free_amplitude=10nm:30nm:1: FROM:TO:1 is one value, so TO would be dropped" \
  "$tiptap" sweep "$blend" --vary cantilever.free_amplitude=10nm:30nm:1 -o r.csv
expect_error "FROM = TO with N > 1" "FROM equals TO" \
  "$tiptap" sweep "$blend" --vary approach.from=8nm:8nm:3 -o r.csv
expect_error "values alike at 15 digits" "values 1 and 2 are both '8e-09 m'" \
  "$tiptap" sweep "$blend" --vary approach.from=8nm:8.000000000000002nm:3 -o r.csv
ls ./*.csv ./*.partial >/dev/null 2>&1 && bad "a refused sweep wrote files: $(ls)" || ok "refused sweeps wrote nothing"
# a span beyond the largest double: finite values (the middle one 0), no -nan anywhere
"$tiptap" sweep "$blend" --vary "approach.from=-1.7e308m:1.7e308m:3" -q -o span.csv 2>span.err
cut -d, -f2 span.csv | tr '\n' ' ' | grep -qx 'approach.from\[m\] -1.7e+308 0 1.7e+308 ' &&
  ! grep -qi nan span.err && ok "overflowing span: finite values" ||
  bad "overflowing span: $(cut -d, -f2 span.csv | tr '\n' ' ') $(cat span.err)"
rm -f span.csv

# outputs, each checked before the first combination (which would take seconds here)
touch afile scf
mkdir adir
grid=(--vary "approach.from=8nm:16nm:3" -j 1)
expect_error "-o under a file" "afile/t.csv: cannot write: Not a directory" \
  "$tiptap" sweep "$blend" "${grid[@]}" -o afile/t.csv
expect_error "-o in a missing folder" "nodir/t.csv: cannot write: No such file or directory" \
  "$tiptap" sweep "$blend" "${grid[@]}" -o nodir/t.csv
expect_error "-o a folder" "adir: is a folder" "$tiptap" sweep "$blend" "${grid[@]}" -o adir
expect_error "--plot in a missing folder" "nodir/p.png: cannot write: No such file or directory" \
  "$tiptap" sweep "$blend" "${grid[@]}" -o t.csv --plot nodir/p.png
expect_error "--plot of a scan" "--plot: not for scans" \
  "$tiptap" sweep "$blend" "${grid[@]}" --run scan -o t.csv --plot p.png
expect_error "--plot with only the contrast key" "--plot: needs a varied key besides the contrast key" \
  "$tiptap" sweep "$blend" "${grid[@]}" --contrast approach.from -o t.csv --plot p.png
expect_error "scan folder is a file" "scf: not a folder" \
  "$tiptap" sweep "$blend" "${grid[@]}" --run scan -o scf.csv
mkdir sc && touch sc/0002
expect_error "a combination's scan folder is a file" "sc/0002: is not a folder; combination 2 writes its scan there" \
  "$tiptap" sweep "$blend" "${grid[@]}" --run scan --set scan.pixels=4 --set scan.lines=2 -o sc.csv
[ ! -e t.csv ] && [ ! -e t.csv.partial ] && [ ! -e sc.csv.partial ] && [ -z "$(ls sc | grep -v 0002)" ] &&
  ! ls ./*.tmp.* >/dev/null 2>&1 && ok "nothing ran or was left" || bad "left: $(ls -R)"
exit $fail
