#!/usr/bin/env bash
# A failed HDF5 write (past ulimit -f, a full disk) ends in one line naming the file and
# the reason, exit 1, no crash, no .h5 and no temporary file left, the files finished
# before it kept (issue 28: libhdf5's exit handler crashed, exit 139, with "cannot write
# HDF5: closing the file"; from Python the interpreter crashed at exit). The full disk
# is a small tmpfs, mounted where this test may mount (root), else skipped with a word.
# usage: cli_files_hdf5_faults.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"
source "$(dirname "$0")/tt_files.sh"

vary=(--vary "material.ring.reduced_modulus=50 GPa,60 GPa")
# the table (417 bytes) fits in 8 blocks of 1024 bytes, its FILE.h5 (34 kB) does not
out=$( (ulimit -f 8; "$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/w.csv" --hdf5 -q) 2>&1); rc=$?
[ $rc -eq 1 ] && [ "$out" = "tiptap: $tmp/w.h5: cannot write: File too large" ] &&
  ok "sweep --hdf5 past ulimit -f: exit 1, '$out'" || bad "sweep --hdf5 past ulimit -f: rc $rc, '$out'"
[ ! -e "$tmp/w.h5" ] && [ -s "$tmp/w.csv" ] && ok "no w.h5, the table kept" || bad "w.h5 left or no table"
# a scan: its channel files (12 kB at most) fit in 20 blocks, scan.h5 (48 kB) does not
out=$( (ulimit -f 20; "$tiptap" scan "$tmp/s.ini" -o "$tmp/o" --hdf5 -q) 2>&1); rc=$?
[ $rc -eq 1 ] && [ "$out" = "tiptap: $tmp/o/scan.h5: cannot write: File too large" ] &&
  ok "scan --hdf5 past ulimit -f: exit 1, '$out'" || bad "scan --hdf5 past ulimit -f: rc $rc, '$out'"
[ ! -e "$tmp/o/scan.h5" ] && [ -s "$tmp/o/scan.gwy" ] && ok "no scan.h5, scan.gwy kept" ||
  bad "scan.h5 left or scan.gwy missing"
[ -z "$(find "$tmp" -name '*.tmp.*')" ] && ok "no temporary file left" || bad "temporary files left"
"$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/full.csv" --hdf5 -q && [ -s "$tmp/full.h5" ] &&
  ok "without the limit FILE.h5 is written" || bad "no full.h5"

# from Python (the library through cffi): an exception naming the file and the reason,
# and the interpreter ends normally after it
pypath=$(realpath "$src")/python
lib=$(ldd "$tiptap" | sed -n 's/.*libtiptap\.so[^ ]* => \([^ ]*\) .*/\1/p')
# (a library built with the sanitizers loads only after their runtimes: py_* tests' case)
if [ -n "$lib" ] && ! ldd "$lib" | grep -q libasan && /usr/bin/python3 -c "import numpy, cffi" 2>/dev/null; then
  out=$( (ulimit -f 8; cd "$tmp" && TIPTAP_LIBRARY="$lib" PYTHONPATH="$pypath" PYTHONDONTWRITEBYTECODE=1 \
    /usr/bin/python3 -c "
import signal; signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
import tiptap
try:
    tiptap.sweep('s.ini', ['material.ring.reduced_modulus=50 GPa,60 GPa'], hdf5='p.h5', progress=False)
except tiptap.TiptapError as e:
    print('raised:', e)
print('the end')") 2>&1); rc=$?
  [ $rc -eq 0 ] && [ "$out" = "raised: p.h5: cannot write: File too large
the end" ] && ok "Python past ulimit -f: raised, and exit 0" || bad "Python past ulimit -f: rc $rc, '$out'"
  [ ! -e "$tmp/p.h5" ] && ok "Python left no p.h5" || bad "p.h5 left"
else
  echo "     no libtiptap.so, a sanitized one, or no numpy and cffi: the Python case skipped"
fi

# a full disk: a 16 kB tmpfs holds the table, not FILE.h5
mkdir "$tmp/mnt"
if mount -t tmpfs -o size=16k tmpfs "$tmp/mnt" 2>/dev/null; then
  trap 'umount "$tmp/mnt"; [ -n "${TT_KEEP_TMP:-}" ] || rm -rf "$tmp"' EXIT
  out=$("$tiptap" sweep "$tmp/s.ini" "${vary[@]}" -o "$tmp/mnt/w.csv" --hdf5 -q 2>&1); rc=$?
  [ $rc -eq 1 ] && [ "$out" = "tiptap: $tmp/mnt/w.h5: cannot write: No space left on device" ] &&
    ok "a full disk: exit 1, '$out'" || bad "a full disk: rc $rc, '$out'"
  [ "$(ls -A "$tmp/mnt")" = "w.csv" ] && ok "only the table on the full disk" ||
    bad "on the full disk: $(ls -A "$tmp/mnt" | tr '\n' ' ')"
else
  echo "     cannot mount a tmpfs here (not root, or no mount): the full-disk case skipped"
fi
exit $fail
