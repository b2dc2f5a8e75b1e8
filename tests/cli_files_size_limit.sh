#!/usr/bin/env bash
# Past a file-size limit (ulimit -f) a write fails with the file and the reason, exit 1,
# no temporary file is left, and the files finished before it stay, each complete
# (issue 19: SIGXFSZ ended the run without a word and left a .tmp).
# usage: cli_files_size_limit.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

"$tiptap" scan "$tmp/s.ini" -o "$tmp/full" -q || bad "the unlimited scan"
# bash counts ulimit -f in blocks of 1024 bytes; scene.ini and the GSF files fit in 8,
# the previews soon reach it
for blocks in 8 1; do
  out=$( (ulimit -f $blocks; "$tiptap" scan "$tmp/s.ini" -o "$tmp/lim$blocks" -q) 2>&1); rc=$?
  if [ $rc -eq 1 ] && [ "$(wc -l <<<"$out")" -eq 1 ] &&
     grep -qE "^tiptap: $tmp/lim$blocks/[a-z_]+\.(ini|gsf|png|gwy|csv): cannot write: File too large$" <<<"$out"; then
    ok "ulimit -f $blocks: exit 1, '$out'"
  else
    bad "ulimit -f $blocks: rc $rc, '$out'"
  fi
  left=$(ls -A "$tmp/lim$blocks" | grep -c '\.tmp\.')
  [ "$left" -eq 0 ] && ok "ulimit -f $blocks: no temporary file left" || bad "ulimit -f $blocks: $left temporaries"
  failed=$(sed -E 's|^tiptap: (.*): cannot write.*|\1|' <<<"$out")
  [ ! -e "$failed" ] && ok "ulimit -f $blocks: the failed file is not there" || bad "$failed left"
  kept=0
  for f in "$tmp/lim$blocks"/*; do
    [ -e "$f" ] || continue
    cmp -s "$f" "$tmp/full/$(basename "$f")" && kept=$((kept + 1)) || bad "ulimit -f $blocks: $(basename "$f") incomplete"
  done
  echo "     $kept files kept under ulimit -f $blocks"
done
[ -s "$tmp/lim8/scene.ini" ] && ok "the files before the failure kept" || bad "scene.ini not kept"

# a sweep's table and a trace's CSV
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
out=$( (ulimit -f 1; "$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" -q --set trace.cycles=50) 2>&1); rc=$?
[ $rc -eq 1 ] && grep -qF "$tmp/t.csv: cannot write: File too large" <<<"$out" && [ ! -e "$tmp/t.csv" ] &&
  [ -z "$(ls "$tmp" | grep 't.csv.tmp')" ] && ok "trace: '$out'" || bad "trace: rc $rc, '$out'"
# standard output redirected into a file is output too
out=$( (ulimit -f 1; "$tiptap" keys >"$tmp/keys.txt") 2>&1); rc=$?
[ $rc -eq 1 ] && [ "$out" = "tiptap: standard output: cannot write: File too large" ] &&
  ok "stdout past the limit" || bad "stdout: rc $rc, '$out'"
exit $fail
