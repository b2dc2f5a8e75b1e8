#!/usr/bin/env bash
# tiptap live's memory and latency promises (docs/live.md, "Limits that keep it
# running"): a scene whose scans, images or scope records the machine cannot hold is
# refused before anything is made, at start-up and from the page; a change is taken
# whole (its scan built) or refused with nothing changed; a change of line rate abandons
# the line under way; an export is streamed, not copied per request; and on port 80 a
# browser's port-less Host and Origin are this server's (tests/live_limits.py).
# usage: cli_live_limits.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_live.sh"
py=/usr/bin/python3
here=$(dirname "$0")
# freed memory waits in AddressSanitizer's quarantine (256 MB): the exports' check would
# read the writer's freed buffers, not what the requests hold (as in cli_live.sh)
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}quarantine_size_mb=4"
teach=("$src/examples/feedback-tuning/common.ini" "$src/surfaces/grating.ini")
small=(--set scan.pixels=32 --set scan.lines=4 --set scan.line_rate=8Hz --set scan.size=1um)

# Outside the sanitizers (whose shadow memory needs more) the address space is held to
# 8 GB, so that a console that allocated first fails at once rather than filling the
# machine (the console's check then counts 8 GB available).
ldd "$tiptap" | grep -q libasan || ulimit -v 8000000

# Start-up: refused with one line naming the key, before it listens.
limit() { exec timeout 120 "$@"; }
expect_error "0.0002 Hz at start-up (27 GB a scope record)" "[scan] line_rate:" \
  limit "$tiptap" live --port 0 "${teach[@]}" --set scan.line_rate=0.0002Hz
expect_error "16384 x 16384 pixels at start-up" "[scan] pixels:" \
  limit "$tiptap" live --port 0 "${teach[@]}" --set scan.pixels=16384 --set scan.lines=16384 \
  --set scan.line_rate=1Hz

stop() { kill -INT "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; }
run() { # mode, tiptap live's arguments...: a server, then live_limits.py MODE on it
  local mode=$1; shift
  live_start "$@"
  if [ -z "$port" ]; then
    bad "$mode: the server did not start: $(cat "$tmp/err")"
    return
  fi
  "$py" "$here/live_limits.py" "$mode" "$port" "$pid" || fail=1
  stop
}

if [ ! -x "$py" ]; then
  echo "skip the WebSocket tests: no $py (apt-get install python3)"
  exit $fail
fi
run changes "${teach[@]}" "${small[@]}"
# 0.01 Hz on the every-cycle tier: 3e7 drive cycles a line, minutes of work (blocks of
# 64 periods keep its scope record at 34 MB)
run abandon "${teach[@]}" "${small[@]}" --set scan.line_rate=0.01Hz --set solver.tier=every \
  --set lockin.periods_per_block=64
# 512 x 512 pixels on the averaged tier: a 25 MB scan.gwy
run exports "${teach[@]}" --set scan.pixels=512 --set scan.lines=512 --set scan.line_rate=4Hz \
  --set solver.tier=averaged
# port 80 where this test may take it (root, nothing else on it)
if [ "$(id -u)" = 0 ] && ! (exec 3<>/dev/tcp/127.0.0.1/80) 2>/dev/null; then
  "$tiptap" live --port 80 "${teach[@]}" "${small[@]}" >"$tmp/out80" 2>"$tmp/err80" &
  pid=$!
  for _ in $(seq 300); do
    grep -q "127.0.0.1:80/" "$tmp/out80" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if grep -q "127.0.0.1:80/" "$tmp/out80"; then
    "$py" "$here/live_limits.py" port80 80 || fail=1
  else
    echo "skip port 80: $(cat "$tmp/err80")"
  fi
  stop
else
  echo "skip port 80: not root, or another program has it"
fi
exit $fail
