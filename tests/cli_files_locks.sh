#!/usr/bin/env bash
# Every writer into a scan folder takes its lock (issue 19: sweep --run scan ignored the
# lock of a scan running in its combination's folder): a folder held by a live run is
# refused, naming the folder, the command and the pid; a lock left by a dead run is
# taken over.
# usage: cli_files_locks.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa" --run scan)
# a slow scan into the sweep's first combination folder
"$tiptap" scan "$tmp/s.ini" -o "$tmp/w/0001" -q --set "scan.line_rate=0.001 Hz" 2>/dev/null &
first=$!
for _ in $(seq 1 600); do
  [ -s "$tmp/w/0001/.tiptap.lock" ] && [ -e "$tmp/w/0001/scene.ini" ] && break
  sleep 0.1
done
cp "$tmp/w/0001/scene.ini" "$tmp/first.ini"
expect_exact "sweep into a folder a scan holds" \
  "tiptap: $tmp/w/0001 is in use by another tiptap scan (pid $first)" \
  timeout 60 "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q
cmp -s "$tmp/w/0001/scene.ini" "$tmp/first.ini" && [ ! -e "$tmp/w/0001/height_trace.gsf" ] &&
  ok "the scan's folder untouched" || bad "the sweep wrote into the scan's folder"
kill -TERM $first
wait $first
[ ! -e "$tmp/w/0001/.tiptap.lock" ] && ok "the stopped scan released its folder" || bad "lock left"
"$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" -q && [ -s "$tmp/w/0002/height_trace.gsf" ] &&
  ok "the sweep runs once the folder is free" || bad "sweep after the scan"
[ ! -e "$tmp/w/0001/.tiptap.lock" ] && [ ! -e "$tmp/w/0002/.tiptap.lock" ] && ok "the sweep leaves no lock" ||
  bad "sweep lock left"

# a scan into a combination folder while a sweep writes there
"$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/v.csv" -q --set "scan.line_rate=0.001 Hz" 2>/dev/null &
sweep=$!
for _ in $(seq 1 600); do
  [ -s "$tmp/v/0001/.tiptap.lock" ] && break
  sleep 0.1
done
expect_exact "scan into a folder a sweep holds" \
  "tiptap scan: $tmp/v/0001 is in use by another tiptap sweep (pid $sweep)" \
  timeout 60 "$tiptap" scan "$tmp/s.ini" -o "$tmp/v/0001" -q
kill -TERM $sweep
wait $sweep

# a lock file left by a run that died (kill -9 leaves the file, not the lock)
mkdir -p "$tmp/dead"
printf '999999999 scan\n' >"$tmp/dead/.tiptap.lock"
"$tiptap" scan "$tmp/s.ini" -o "$tmp/dead" -q && [ ! -e "$tmp/dead/.tiptap.lock" ] &&
  ok "a dead run's lock is taken over" || bad "stale lock blocked the folder"
exit $fail
