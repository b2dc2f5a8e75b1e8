#!/usr/bin/env bash
# An output replaces only a regular file (issue 28): a pipe, a device node, a socket or a
# folder at an output's name, or a link to one, is refused with one line before anything
# runs, and left as it was (rename() put a regular file in its place; as root, -o
# /dev/null replaced /dev/null). Every command and every output: -o, --plot, a scan's
# files in its folder, the sweep's FILE.h5. /dev/null itself is never named here (the
# code before the fix would replace it): a device node of the test's own stands for it.
# usage: cli_files_special_outputs.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

kind() { stat -c %F "$1" 2>/dev/null; }
mkfifo "$tmp/pipe.csv" "$tmp/pipe.png" "$tmp/pipe.h5"
mkdir "$tmp/folder.csv"
ln -s pipe.csv "$tmp/to_pipe.csv"
nodes=(pipe.csv pipe.png pipe.h5 folder.csv to_pipe.csv)
# a link to /dev/null where it is the device (on a machine where something replaced it
# by a file, a link to it is a link to a regular file, which an output replaces)
[ -c /dev/null ] && ln -s /dev/null "$tmp/null.csv" && nodes+=(null.csv)
if mknod "$tmp/dev.csv" c 1 3 2>/dev/null; then nodes+=(dev.csv); else echo "     no mknod here: no device node of our own"; fi
if /usr/bin/python3 -c "import socket; socket.socket(socket.AF_UNIX).bind('$tmp/sock.csv')" 2>/dev/null; then
  nodes+=(sock.csv)
fi
declare -A before
for n in "${nodes[@]}"; do before[$n]=$(kind "$tmp/$n"); done

notreg="not a regular file (a device, pipe or socket); an output replaces only a regular file: name another"
expect_exact "trace -o a pipe" "tiptap: $tmp/pipe.csv: $notreg" \
  timeout 20 "$tiptap" trace "$tmp/s.ini" -o "$tmp/pipe.csv" -q --set trace.cycles=3
expect_exact "trace -o a folder" "tiptap: $tmp/folder.csv: is a folder; the output is a file: name another" \
  timeout 20 "$tiptap" trace "$tmp/s.ini" -o "$tmp/folder.csv" -q --set trace.cycles=3
[ -L "$tmp/null.csv" ] && expect_exact "approach -o a link to /dev/null" "tiptap: $tmp/null.csv: $notreg" \
  timeout 20 "$tiptap" approach "$tmp/s.ini" -o "$tmp/null.csv" -q
expect_error "accuracy -o a link to a pipe" "$tmp/to_pipe.csv: not a regular file" \
  timeout 20 "$tiptap" accuracy "$tmp/s.ini" -o "$tmp/to_pipe.csv" -q
[ -e "$tmp/dev.csv" ] && expect_exact "trace -o a device node" "tiptap: $tmp/dev.csv: $notreg" \
  timeout 20 "$tiptap" trace "$tmp/s.ini" -o "$tmp/dev.csv" -q --set trace.cycles=3
[ -e "$tmp/sock.csv" ] && expect_error "trace -o a socket" "$tmp/sock.csv: not a regular file" \
  timeout 20 "$tiptap" trace "$tmp/s.ini" -o "$tmp/sock.csv" -q --set trace.cycles=3
# a link into /proc (what /dev/stdout is): rename() would replace the link, /dev/stdout
# itself when named so; standard output a regular file here, a link to which passes
ln -s /proc/self/fd/1 "$tmp/stdout.csv"
out=$("$tiptap" trace "$tmp/s.ini" -o "$tmp/stdout.csv" -q --set trace.cycles=3 2>&1 >"$tmp/redirected"); rc=$?
[ $rc -eq 1 ] && [ "$out" = "tiptap: $tmp/stdout.csv: a link into /proc (/proc/self/fd/1), to a process's open file; the output would replace the link: name the file itself" ] &&
  [ -L "$tmp/stdout.csv" ] && ok "a link into /proc refused, left a link" || bad "a link into /proc: rc $rc, '$out'"
# --plot: refused before the table is written
expect_error "trace --plot a pipe" "$tmp/pipe.png: not a regular file" \
  timeout 20 "$tiptap" trace "$tmp/s.ini" -o "$tmp/t.csv" --plot "$tmp/pipe.png" -q --set trace.cycles=3
[ ! -e "$tmp/t.csv" ] && ok "no table before a refused plot" || bad "trace wrote its table"
expect_error "contact --plot a pipe" "$tmp/pipe.png: not a regular file" \
  timeout 20 "$tiptap" contact --lambda 1 -o "$tmp/c.csv" --plot "$tmp/pipe.png"
[ ! -e "$tmp/c.csv" ] && ok "contact wrote nothing" || bad "contact wrote its table"
expect_error "profiles -o a pipe" "$tmp/pipe.png: not a regular file" \
  timeout 20 "$tiptap" profiles -q -o "$tmp/pipe.png" "$tmp"
# the sweep: its table, its plot, FILE.h5; nothing runs (no journal)
vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
expect_error "sweep -o a pipe" "$tmp/pipe.csv: not a regular file" \
  timeout 20 "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/pipe.csv" -q
expect_error "sweep --hdf5 onto a pipe" "$tmp/pipe.h5: not a regular file" \
  timeout 20 "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/pipe.csv2" --hdf5 -q
[ -z "$(ls "$tmp" | grep partial)" ] && ok "no sweep ran" || bad "a journal was made"
# a scan's files in its folder
mkdir "$tmp/scan"
mkfifo "$tmp/scan/height_trace.png"
expect_error "scan: a channel's file a pipe" "$tmp/scan/height_trace.png: not a regular file" \
  timeout 20 "$tiptap" scan "$tmp/s.ini" -o "$tmp/scan" -q
[ ! -e "$tmp/scan/scene.ini" ] && ok "the refused scan wrote nothing" || bad "the scan wrote scene.ini"
mkfifo "$tmp/scan2.h5" && mkdir "$tmp/scan2" && mv "$tmp/scan2.h5" "$tmp/scan2/scan.h5"
expect_error "scan --hdf5: scan.h5 a pipe" "$tmp/scan2/scan.h5: not a regular file" \
  timeout 20 "$tiptap" scan "$tmp/s.ini" -o "$tmp/scan2" --hdf5 -q
"$tiptap" scan "$tmp/s.ini" -o "$tmp/scan2" -q 2>/dev/null && [ "$(kind "$tmp/scan2/scan.h5")" = fifo ] &&
  ok "without --hdf5 a pipe named scan.h5 is left alone" || bad "scan without --hdf5 beside a pipe"
for n in "${nodes[@]}"; do
  [ "$(kind "$tmp/$n")" = "${before[$n]}" ] && ok "$n still a ${before[$n]}" || bad "$n is now a $(kind "$tmp/$n")"
done
[ -z "$(find "$tmp" -name '*.tmp.*')" ] && ok "no temporary file left" || bad "temporary files left"
exit $fail
