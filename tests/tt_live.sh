# Shared by the tests of tiptap live (sourced after tt_cli.sh): live_start ARGS... starts
# `tiptap live --port 0 ARGS...` in the background with its stdout and stderr in
# $tmp/out and $tmp/err, and sets pid and port (port empty: it did not start).
live_start() {
  "$tiptap" live --port 0 "$@" >"$tmp/out" 2>"$tmp/err" &
  pid=$!
  port=""
  for _ in $(seq 600); do
    port=$(sed -n 's|^tiptap live: http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$tmp/out")
    [ -n "$port" ] && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
}
