# Shared by the tests of tiptap live (sourced after tt_cli.sh): live_start ARGS... starts
# `tiptap live --port 0 ARGS...` in the background with its stdout and stderr in
# $tmp/out and $tmp/err, and sets pid and port (port empty: it did not start).
live_start() {
  # emptied here, not by the background job's redirection, which may come after the
  # first read below and leave the previous server's port to be read (seen under load)
  : >"$tmp/out"
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
# live_in_browser SCRIPT ARGS...: tests/SCRIPT (python, driving Debian's headless Chromium)
# against `tiptap live ARGS...`, then Ctrl-C; exits 77 (skip) where Chromium or python3 is
# missing, else with the test's status. Screenshots go to $TT_LIVE_SHOTS where it is set.
live_in_browser() {
  local script=$1; shift
  local chromium rc
  chromium=$(command -v chromium || command -v chromium-browser || true)
  if [ -z "$chromium" ] || [ ! -x /usr/bin/python3 ]; then
    echo "skip: the browser test needs Debian's chromium and python3 (apt-get install chromium python3)"
    exit 77
  fi
  local shots=${TT_LIVE_SHOTS:-$tmp}
  mkdir -p "$shots"
  live_start "$@"
  if [ -z "$port" ]; then
    bad "the server did not start: $(cat "$tmp/err")"
    exit 1
  fi
  /usr/bin/python3 "$(dirname "${BASH_SOURCE[0]}")/$script" "$chromium" "http://127.0.0.1:$port/" "$shots" || fail=1
  kill -INT "$pid"
  wait "$pid"
  rc=$?
  [ $rc -eq 130 ] && ok "the server stopped on Ctrl-C" || bad "the server's exit: $rc; $(cat "$tmp/err")"
  exit $fail
}
