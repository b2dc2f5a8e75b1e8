#!/usr/bin/env bash
# tiptap sweep's journal (OUT.partial): its header names the program's version, each
# record carries the CRC-32 of its line and rows (checked here against gzip's CRC-32);
# resuming refuses, in one line naming the journal (and the line), a damaged record, a
# journal of another version (both named), an empty journal (named as empty) and one in
# the older format, leaving the journal as it was; a record cut short by a kill is
# dropped and the resumed table is the uninterrupted one; a failed journal write says
# why (the errno text) with the file's name.
# usage: cli_sweep_journal.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
cd "$tmp" || exit 1
blend=$src/surfaces/polymer-blend.ini
records() { local n; n=$(grep -c '^@' "$1" 2>/dev/null); echo "${n:-0}"; }
crc32() { gzip -c | tail -c8 | head -c4 | od -An -tx4 | tr -d ' \n'; }
version=$("$tiptap" --version | cut -d' ' -f2)

slow=(--vary "approach.material=matrix" --vary "approach.from=4nm:15nm:12")
"$tiptap" sweep "$blend" "${slow[@]}" -j 2 -q -o ref.csv || bad "reference sweep"
"$tiptap" sweep "$blend" "${slow[@]}" -j 1 -q -o k.csv 2>k.err &
pid=$!
for _ in $(seq 400); do
  [ "$(records k.csv.partial)" -ge 3 ] && break
  sleep 0.05
done
kill -TERM $pid
wait $pid
[ "$(records k.csv.partial)" -ge 3 ] && cp k.csv.partial journal || bad "no journal of 3 records"

head -1 journal | grep -qE "^tiptap-sweep-journal 2 $version [0-9a-f]{16} 12\$" &&
  ok "header: format, version $version, fingerprint, count" || bad "header: $(head -1 journal)"
# every record: "@INDEX BYTES CRC", CRC-32 of "@INDEX BYTES" and the rows
awk 'NR > 1 && /^@/ {print NR}' journal >lines
checked=0
while read -r n; do
  set -- $(sed -n "${n}p" journal)
  want=$3
  got=$({ printf '%s %s' "$1" "$2"; tail -c +"$(($(head -n "$n" journal | wc -c) + 1))" journal | head -c "$2"; } | crc32)
  [ "$got" = "$want" ] && checked=$((checked + 1)) || bad "record at line $n: crc $want, gzip says $got"
done <lines
[ "$checked" -ge 3 ] && ok "$checked records carry the CRC-32 of their line and rows" || bad "records checked: $checked"

refused() { # name, fragment, journal file to resume from
  cp "$3" o.csv.partial
  expect_error "$1" "$2" "$tiptap" sweep "$blend" "${slow[@]}" -j 1 -q -o o.csv
  cmp -s "$3" o.csv.partial && [ ! -e o.csv ] || bad "$1: the journal was changed or a table written"
}
# one byte of the first record's rows changed: combination 1's row says 2
sed '3s/^1,/2,/' journal >digit
cmp -s digit journal && bad "no corrupted copy"
refused "changed rows refused" "o.csv.partial: line 2: the record of combination 1 fails its checksum (damaged); remove it" digit
sed '2s/^@/#/' journal >line
refused "damaged record line refused" "o.csv.partial: line 2: not a record of this journal (damaged)" line
sed "1s/ $version / 0.0.1 /" journal >old
refused "another version refused, both named" \
  "o.csv.partial: the journal of another sweep, written by tiptap 0.0.1, and this is tiptap $version" old
: >empty
refused "empty journal named as empty" "o.csv.partial: the journal is empty" empty
sed '1s/^tiptap-sweep-journal 2 [^ ]* /tiptap-sweep-journal /' journal >format1
refused "the older format refused" "the journal of another sweep, in an older tiptap's format" format1
printf 'PNG\n' >notjournal
refused "not a journal" "not a sweep journal" notjournal

# a record cut short at the end, as a kill while writing leaves it: dropped, rerun
head -c -7 journal >o.csv.partial
"$tiptap" sweep "$blend" "${slow[@]}" -j 2 -o o.csv 2>resume.err
grep -q "resuming o.csv.partial: $(($(records journal) - 1)) of 12" resume.err && cmp -s ref.csv o.csv &&
  [ ! -e o.csv.partial ] && ok "a record cut short is dropped and run again" || bad "cut record: $(cat resume.err)"

# a journal write that fails (a file size limit) names the file and the reason
(
  ulimit -f 1
  trap '' XFSZ
  "$tiptap" sweep "$blend" --vary "approach.material=disk" --vary "approach.from=8nm:16nm:9" -j 1 -q -o w.csv \
    2>w.err
  echo $? >w.rc
)
[ "$(cat w.rc)" = 1 ] && grep -qx "tiptap: w.csv.partial: cannot write: File too large" w.err &&
  ok "journal write failure: file and errno text" || bad "write failure: rc $(cat w.rc), $(cat w.err)"
# two sweeps with one -o: the second is refused at once, the first's journal untouched
"$tiptap" sweep "$blend" --set solver.method=rk4 --vary "solver.steps_per_cycle=512,10000000" -j 1 -q \
  -o two.csv 2>two-a.err &
pid=$!
for _ in $(seq 600); do [ "$(records two.csv.partial)" -ge 1 ] && break; sleep 0.05; done
cp two.csv.partial two-before
msg=$("$tiptap" sweep "$blend" --set solver.method=rk4 --vary "solver.steps_per_cycle=512,10000000" -j 1 -q \
  -o two.csv 2>&1 >/dev/null); rc=$?
kill -TERM $pid; wait $pid
[ $rc -eq 1 ] && [ "$msg" = "tiptap: two.csv.partial is in use by another tiptap sweep" ] && cmp -s two-before two.csv.partial &&
  ok "a second sweep on one journal refused" || bad "second sweep: rc $rc '$msg'"
exit $fail
