#!/usr/bin/env bash
# A scan's files are written as jobs on its threads (src/run/run_scan.c): every file's
# bytes are the same on one thread and two, and past a file-size limit (ulimit -f) both
# report the same file, the first of the table that fails (each channel's GSF and PNG,
# then scan.gwy and profile.csv), with the other files still written, each complete,
# and no temporary left.
# usage: cli_files_threads.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

# more channels than threads, so that files are written side by side
sed -i 's/^channels = .*/channels = height, phase, error, amplitude, peak_force, dissipation/' "$tmp/s.ini"
for j in 1 2; do
  "$tiptap" scan "$tmp/s.ini" -o "$tmp/full$j" -q -j$j || bad "the scan on $j thread(s)"
done
n=$(ls "$tmp/full1" | wc -l)
diff -r "$tmp/full1" "$tmp/full2" >/dev/null && [ "$n" -gt 20 ] &&
  ok "-j1 and -j2: the same $n files, byte for byte" || bad "-j1 and -j2 differ ($n files)"

# 8 blocks of 1024 bytes: the GSFs fit, the previews and scan.gwy do not
for j in 1 2; do
  out[$j]=$( (ulimit -f 8; "$tiptap" scan "$tmp/s.ini" -o "$tmp/lim$j" -q -j$j) 2>&1); rc[$j]=$?
  left=$(ls -A "$tmp/lim$j" | grep -c '\.tmp\.')
  [ "$left" -eq 0 ] && ok "-j$j past the limit: no temporary file left" || bad "-j$j: $left temporaries"
  kept[$j]=0
  for f in "$tmp/lim$j"/*; do
    [ -e "$f" ] || continue
    cmp -s "$f" "$tmp/full1/$(basename "$f")" && kept[$j]=$((kept[$j] + 1)) || bad "-j$j: $(basename "$f") incomplete"
  done
done
msg1=${out[1]//lim1/limN}
msg2=${out[2]//lim2/limN}
if [ "${rc[1]}" -eq 1 ] && [ "${rc[2]}" -eq 1 ] && [ "$(wc -l <<<"${out[2]}")" -eq 1 ] && [ "$msg1" = "$msg2" ] &&
   grep -qE "^tiptap: $tmp/lim2/[a-z_]+\.(png|gwy|csv): cannot write: File too large$" <<<"${out[2]}"; then
  ok "past the limit, -j1 and -j2 report the same file: '${out[2]}'"
else
  bad "past the limit: -j1 rc ${rc[1]} '${out[1]}', -j2 rc ${rc[2]} '${out[2]}'"
fi
# every job runs after a failure: the files that fit are there on both
[ "${kept[1]}" -eq "${kept[2]}" ] && [ "${kept[2]}" -gt 12 ] &&
  ok "the files that fit are written on both: ${kept[2]} of $n" || bad "kept: -j1 ${kept[1]}, -j2 ${kept[2]} of $n"
exit $fail
