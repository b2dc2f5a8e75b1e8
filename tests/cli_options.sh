#!/usr/bin/env bash
# Numbers given to options are parsed strictly (the whole text, a whole number where one
# is counted, finite) and operands a command does not take are refused: one line naming
# the command and option, exit 2, nothing on stdout (issue 19, item 4).
# usage: cli_options.sh path/to/tiptap source_dir
set -u
tiptap=$1
source "$(dirname "$0")/tt_cli.sh"

printf '[material silicon]\nreduced_modulus = 100 GPa\n[scan]\npixels = 16\nlines = 2\n' >"$tmp/s.ini"

usage() { # name, the whole expected line, command...: exit 2, that one line, no stdout
  local name=$1 want=$2; shift 2
  local err rc
  err=$("$@" 2>&1 >"$tmp/stdout"); rc=$?
  if [ $rc -ne 2 ]; then bad "$name: exit $rc, not 2 ($err)"; return; fi
  if [ "$err" != "$want" ]; then bad "$name: '$err' is not '$want'"; return; fi
  if [ -s "$tmp/stdout" ]; then bad "$name: printed on stdout"; return; fi
  ok "$name"
}

# whole numbers: trailing text, fractions, out of range, hexadecimal, blanks, overflow
usage "bench --cycles 20abc" "tiptap bench: --cycles: '20abc' is not a whole number from 10 to 1000000000" \
  "$tiptap" bench --cycles 20abc
usage "bench --cycles 12.5" "tiptap bench: --cycles: '12.5' is not a whole number from 10 to 1000000000" \
  "$tiptap" bench --cycles 12.5
usage "bench --cycles 5" "tiptap bench: --cycles: '5' is not a whole number from 10 to 1000000000" \
  "$tiptap" bench --cycles 5
usage "bench --cycles overflowing" \
  "tiptap bench: --cycles: '99999999999999999999999' is not a whole number from 10 to 1000000000" \
  "$tiptap" bench --cycles 99999999999999999999999
usage "scan -j hexadecimal" "tiptap scan: -j: '0x10' is not a number of threads from 1 to 4096" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/never" -j 0x10
usage "scan -j with a blank" "tiptap scan: -j: ' 2' is not a number of threads from 1 to 4096" \
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/never" -j " 2"
usage "sweep -j 2x" "tiptap sweep: -j: '2x' is not a number of threads from 1 to 4096" \
  "$tiptap" sweep "$tmp/s.ini" -j 2x --vary "cantilever.free_amplitude=10 nm,20 nm"
usage "accuracy --cycles 1e99" "tiptap accuracy: --cycles: '1e99' is not a whole number from 10 to 100000000" \
  "$tiptap" accuracy "$tmp/s.ini" --cycles 1e99
usage "accuracy --repeats 2.5" "tiptap accuracy: --repeats: '2.5' is not a whole number from 1 to 100000000" \
  "$tiptap" accuracy "$tmp/s.ini" --repeats 2.5
# reals: finite, in range, nothing after the number
usage "contact --lambda inf" "tiptap contact: --lambda: 'inf' is not a number from 1e-4 to 1e4" \
  "$tiptap" contact --lambda inf
usage "contact --lambda 1e5" "tiptap contact: --lambda: '1e5' is not a number from 1e-4 to 1e4" \
  "$tiptap" contact --lambda 1e5
usage "contact --xi0 0.3x" "tiptap contact: --xi0: '0.3x' is not a positive number up to 1e6" \
  "$tiptap" contact --xi0 0.3x
usage "accuracy --target 1" "tiptap accuracy: --target: '1' is not a number between 0 and 1" \
  "$tiptap" accuracy "$tmp/s.ini" --target 1
# an exponent form of a whole number is that number
"$tiptap" bench --cycles 1e3 --no-steady --no-imaging --no-noise --no-scenes --no-lesson >/dev/null 2>&1 && ok "bench --cycles 1e3 accepted" ||
  bad "bench --cycles 1e3 refused"
"$tiptap" scan "$tmp/s.ini" -o "$tmp/j" -j 2e0 -q --set scan.pixels=2 --set scan.lines=1 >/dev/null 2>&1 &&
  ok "scan -j 2e0 accepted" || bad "scan -j 2e0 refused"

# operands a command does not take
usage "bench with an operand" \
  "tiptap bench: unexpected argument 'scene.ini': it runs the built-in standard scene; see 'tiptap bench --help'" \
  "$tiptap" bench scene.ini
usage "bench --print-scene with an operand" \
  "tiptap bench: unexpected argument 'x': it runs the built-in standard scene; see 'tiptap bench --help'" \
  "$tiptap" bench --print-scene x
usage "keys with operands" \
  "tiptap keys: unexpected arguments 'a' 'b': it lists the schema, not a scene; see 'tiptap keys --help'" \
  "$tiptap" keys a b
usage "contact --lambda with a scene" \
  "tiptap contact: unexpected argument '$tmp/s.ini': --lambda draws the normalised curve, which takes no scene; see 'tiptap contact --help'" \
  "$tiptap" contact --lambda 1 "$tmp/s.ini"

# every command's --help: exit 0, its usage line on stdout, nothing on stderr
for c in contact approach trace scan sweep profiles accuracy bench keys; do
  out=$("$tiptap" $c --help 2>"$tmp/err"); rc=$?
  [ $rc -eq 0 ] && grep -q "^Usage: tiptap $c" <<<"$out" && [ ! -s "$tmp/err" ] && ok "$c --help" ||
    bad "$c --help: rc $rc"
done
[ -e "$tmp/never" ] && bad "a refused scan made its folder" || ok "no folder"
exit $fail
