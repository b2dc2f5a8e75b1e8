# Shared by the tests/cli_*.sh scripts (sourced, not run): a scratch folder removed at
# exit, ok/bad reporting that sets the exit status, checks of refused commands and a
# small scan's scene.
tmp=$(mktemp -d)
trap '[ -n "${TT_KEEP_TMP:-}" ] || rm -rf "$tmp"' EXIT
fail=0
ok() { echo "ok   $1"; }
bad() { echo "FAIL $1"; fail=1; }

expect_error() { # name, expected fragment, command...: non-zero exit, one line naming it
  local name=$1 frag=$2; shift 2
  local out rc
  out=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ]; then bad "$name: exit 0"; return; fi
  if ! grep -qF -- "$frag" <<<"$out"; then bad "$name: '$out' lacks '$frag'"; return; fi
  if [ "$(wc -l <<<"$out")" -ne 1 ]; then bad "$name: not one line: $out"; return; fi
  ok "$name"
}

expect_exact() { # name, the whole expected message, command...
  local name=$1 want=$2; shift 2
  local out rc
  out=$("$@" 2>&1 >/dev/null); rc=$?
  if [ $rc -eq 0 ]; then bad "$name: exit 0"; return; fi
  if [ "$out" != "$want" ]; then bad "$name: '$out' is not '$want'"; return; fi
  ok "$name"
}

need_python() { # modules...: exit 77 (skipped) where Debian's python3 lacks one; sets py
  py=/usr/bin/python3
  local missing
  if ! missing=$(cd "$tmp" && MPLBACKEND=Agg "$py" -c "
import importlib.util, sys
gone = [m for m in sys.argv[1:] if importlib.util.find_spec(m.split('.')[0]) is None]
print(' '.join(gone)); sys.exit(1 if gone else 0)" "$@"); then
    echo "skipped: $py lacks $missing (Debian's python3-* packages: tests/vendor/README.md)"
    exit 77
  fi
}

small_scan() { # size, pixels, lines: $tmp/s.ini, a scan of a few seconds (Q 100 settles fast)
  cat >"$tmp/s.ini" <<INI
[cantilever]
quality_factor = 100
[scan]
size = $1
pixels = $2
lines = $3
line_rate = 40 Hz
settle_cycles = 1000
INI
}
