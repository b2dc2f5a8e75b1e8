#!/usr/bin/env bash
# tiptap sweep from the command line: a grid of two keys gives one row per combination
# with the keys in SI units; the table is byte-identical for -j 1 and -j 2, after a
# sweep killed part way is run again (it resumes from its journal), and under
# 'mpirun -np 2' when this tiptap was built with MPI; a bad combination is refused in one
# line naming it before anything runs; steady points obey Burnham et al.'s fig. 1 (on
# a stiff sample the amplitude is about the rest separation) and setpoint points hold
# the amplitude asked for.
# usage: cli_sweep.sh path/to/tiptap source_dir
set -u
tiptap=$1
src=$2
source "$(dirname "$0")/tt_cli.sh"
records() { local n; n=$(grep -c '^@' "$1" 2>/dev/null); echo "${n:-0}"; }

blend=$src/surfaces/polymer-blend.ini
grid=(--vary "approach.material=disk,matrix" --vary "approach.from=8nm:16nm:3")

"$tiptap" sweep "$blend" "${grid[@]}" -j 2 -q -o "$tmp/j2.csv" 2>"$tmp/j2.err" &&
  ok "sweep ran" || bad "sweep: $(cat "$tmp/j2.err")"
head -1 "$tmp/j2.csv" | grep -q '^combination,approach.material,approach.from\[m\],z_nm,amplitude_nm,phase_deg,' &&
  ok "header: keys with SI units, then observables" || bad "header: $(head -1 "$tmp/j2.csv")"
[ "$(wc -l <"$tmp/j2.csv")" -eq 7 ] && ok "one row per combination" || bad "rows: $(wc -l <"$tmp/j2.csv")"
awk -F, 'NR == 2 && $2 == "disk" && $3 == 8e-09 && $4 == 8 {f = 1} NR == 7 && $2 == "matrix" && $3 == 1.6e-08 {g = 1}
  END {exit !(f && g)}' "$tmp/j2.csv" && ok "first key slowest, values in SI" || bad "order: $(cat "$tmp/j2.csv")"
# Burnham et al. fig. 1: tapping a stiff sample, the amplitude is limited to about the
# rest separation (within the indentation and the attractive pull, 1.5 nm here)
awk -F, 'NR > 1 && $2 == "disk" { d = $5 - $4; if (d < 0) d = -d; if (d > 1.5) bad = 1; n++ }
  END {exit bad || n != 3}' "$tmp/j2.csv" && ok "amplitude about the rest separation on the stiff disk" ||
  bad "amplitudes: $(cat "$tmp/j2.csv")"

"$tiptap" sweep "$blend" "${grid[@]}" -j 1 -q -o "$tmp/j1.csv" && cmp -s "$tmp/j1.csv" "$tmp/j2.csv" &&
  ok "-j 1 and -j 2 byte-identical" || bad "-j 1 and -j 2 differ"

"$tiptap" sweep "$blend" --vary "cantilever.free_amplitude=log:10nm:1000nm:3" -q -o "$tmp/log.csv" &&
  [ "$(cut -d, -f2 "$tmp/log.csv" | tr '\n' ' ')" = "cantilever.free_amplitude[m] 1e-08 1e-07 1e-06 " ] &&
  ok "log range" || bad "log range: $(cut -d, -f2 "$tmp/log.csv" | tr '\n' ' ')"

# whole scene files as one varied key: each file's cantilever, and the keys set after it
printf '[cantilever]\nspring_constant = 2 N/m\nfree_amplitude = 5 nm\n' >"$tmp/soft.ini"
printf '[cantilever]\nspring_constant = 200 N/m\n' >"$tmp/stiff.ini"
(cd "$tmp" && "$tiptap" sweep "$blend" --vary scene=soft.ini,stiff.ini --vary "cantilever.free_amplitude=10nm" \
  --set approach.material=disk -q -o files.csv) &&
  awk -F, 'NR > 1 { print $2, $3, ($5 > 9 && $5 < 11) }' "$tmp/files.csv" | tr '\n' ' ' |
  grep -qx 'soft.ini 1e-08 1 stiff.ini 1e-08 1 ' && ok "scene files as a varied key, keys set after them" ||
  bad "scene files: $(cat "$tmp/files.csv")"

# setpoint points: the amplitude is the setpoint (50 and 80 % of 20 nm) to 1e-3 of A0
"$tiptap" sweep "$blend" --vary "feedback.setpoint=50%,80%" --set approach.material=disk --run setpoint -q \
  -o "$tmp/sp.csv" && awk -F, 'NR > 1 { d = $5 - $3; if (d < 0) d = -d; if (d > 0.02) bad = 1; n++ }
  END {exit bad || n != 2}' "$tmp/sp.csv" && ok "setpoint points hold the setpoint" ||
  bad "setpoint: $(cat "$tmp/sp.csv")"

expect_error "unknown key" "--vary cantilever.stiffness: unknown key" \
  "$tiptap" sweep "$blend" --vary "cantilever.stiffness=1N/m,2N/m" -o "$tmp/x.csv"
expect_error "bad combination named before anything runs" "combination 3 (cantilever.free_amplitude=-1 nm)" \
  "$tiptap" sweep "$blend" --vary "cantilever.free_amplitude=10 nm,20 nm,-1 nm" -o "$tmp/bad.csv"
[ -e "$tmp/bad.csv" ] || [ -e "$tmp/bad.csv.partial" ] && bad "a refused sweep wrote files" ||
  ok "a refused sweep writes nothing"
expect_error "mixed units" "has another unit" \
  "$tiptap" sweep "$blend" --vary "feedback.setpoint=50%,8nm" --run setpoint -o "$tmp/x.csv"

# kill part way, then the same command again: it resumes and ends with the same table
slow=(--vary "approach.material=matrix" --vary "approach.from=4nm:15nm:12")
"$tiptap" sweep "$blend" "${slow[@]}" -j 2 -q -o "$tmp/ref.csv" || bad "reference sweep"
"$tiptap" sweep "$blend" "${slow[@]}" -j 1 -q -o "$tmp/kill.csv" 2>"$tmp/kill.err" &
pid=$!
for _ in $(seq 200); do
  [ "$(records "$tmp/kill.csv.partial")" -ge 2 ] && break
  sleep 0.05
done
kill -TERM $pid
wait $pid
rc=$?
[ $rc -eq 143 ] && [ ! -e "$tmp/kill.csv" ] && [ -s "$tmp/kill.csv.partial" ] &&
  ok "killed sweep exits 143 keeping its journal" || bad "killed sweep: rc $rc, $(cat "$tmp/kill.err")"
"$tiptap" sweep "$blend" "${slow[@]}" -j 2 -o "$tmp/kill.csv" 2>"$tmp/resume.err"
grep -q "^sweep: resuming .*kill.csv.partial: [1-9][0-9]* of 12 combinations already done" "$tmp/resume.err" &&
  ok "resumed from the journal" || bad "resume: $(cat "$tmp/resume.err")"
cmp -s "$tmp/ref.csv" "$tmp/kill.csv" && [ ! -e "$tmp/kill.csv.partial" ] &&
  ok "resumed table identical, journal removed" || bad "resumed table differs"
expect_error "journal of another sweep" "the journal of another sweep" \
  bash -c "printf 'tiptap-sweep-journal 0 1\n' >'$tmp/o.csv.partial'; '$tiptap' sweep '$blend' -q -o '$tmp/o.csv'"

# MPI: two ranks (as root and oversubscribed, as in CI) give the same bytes
if command -v mpirun >/dev/null; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ASAN_OPTIONS=detect_leaks=0
  mpirun --allow-run-as-root --oversubscribe -np 2 "$tiptap" sweep "$blend" "${grid[@]}" -j 1 -q \
    -o "$tmp/mpi.csv" >"$tmp/mpi.out" 2>&1
  if grep -q "built without MPI" "$tmp/mpi.out"; then
    ok "mpirun refused by a build without MPI (skipped the comparison)"
  else
    cmp -s "$tmp/mpi.csv" "$tmp/j1.csv" && ok "mpirun -np 2 byte-identical to one process" ||
      bad "mpirun -np 2: $(cat "$tmp/mpi.out")"
    mpirun --allow-run-as-root --oversubscribe -np 2 "$tiptap" sweep "$blend" "${slow[@]}" -j 1 -q \
      -o "$tmp/mk.csv" >/dev/null 2>&1 &
    pid=$!
    for _ in $(seq 200); do
      [ "$(records "$tmp/mk.csv.partial")" -ge 2 ] && break
      sleep 0.05
    done
    kill -TERM $pid
    wait $pid
    mpirun --allow-run-as-root --oversubscribe -np 2 "$tiptap" sweep "$blend" "${slow[@]}" -j 1 -q \
      -o "$tmp/mk.csv" >"$tmp/mk.out" 2>&1
    cmp -s "$tmp/ref.csv" "$tmp/mk.csv" && ok "mpirun sweep killed and resumed: identical" ||
      bad "mpirun kill and resume: $(cat "$tmp/mk.out")"
  fi
else
  ok "no mpirun: MPI checks skipped"
fi
exit $fail
