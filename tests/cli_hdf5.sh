#!/usr/bin/env bash
# scan --hdf5 and sweep --hdf5 from the command line: the files are HDF5 (the signature
# at offset 0), written under a temporary name that does not remain, the same bytes for
# the same run, and refused outputs named in one line before anything runs. (Their
# layout is read back by h5py in python/tests/test_hdf5.py and test_sweep.py.)
# usage: cli_hdf5.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$2
source "$(dirname "$0")/tt_cli.sh"

is_hdf5() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "894844460d0a1a0a" ]; }
scan=("$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini" --set scan.pixels=8 --set scan.lines=2)
"$tiptap" scan "${scan[@]}" -o "$tmp/a" --hdf5 2>"$tmp/a.err" || bad "scan --hdf5 ran"
is_hdf5 "$tmp/a/scan.h5" && ok "scan --hdf5 writes DIR/scan.h5" || bad "no HDF5 at $tmp/a/scan.h5"
grep -q "; scan.h5)$" "$tmp/a.err" && ok "the summary names scan.h5" || bad "summary: $(grep output "$tmp/a.err")"
[ -z "$(find "$tmp/a" -name '*.tmp.*')" ] && ok "no temporary file remains" || bad "temporary files left"
"$tiptap" scan "${scan[@]}" -o "$tmp/b" --hdf5 -q 2>/dev/null
cmp -s "$tmp/a/scan.h5" "$tmp/b/scan.h5" && ok "the same run gives the same bytes" || bad "scan.h5 differs between runs"
# a folder in the way of scan.h5: refused before the scan, in one line
mkdir -p "$tmp/c/scan.h5"
expect_error "scan.h5 a folder" "$tmp/c/scan.h5: is a folder" "$tiptap" scan "${scan[@]}" -o "$tmp/c" --hdf5 -q
[ ! -e "$tmp/c/height_trace.gsf" ] && ok "nothing scanned into a refused folder" || bad "scanned anyway"

sweep=("$src/examples/seed-fig4a/scene.ini" --set approach.points=1 --vary "cantilever.quality_factor=20,40")
"$tiptap" sweep "${sweep[@]}" -o "$tmp/s.csv" --hdf5 -q || bad "sweep --hdf5 ran"
is_hdf5 "$tmp/s.h5" && ok "sweep --hdf5 writes FILE.h5" || bad "no $tmp/s.h5"
"$tiptap" sweep "${sweep[@]}" -o "$tmp/t" --hdf5 -q && is_hdf5 "$tmp/t.h5" && ok "FILE without extension: FILE.h5" ||
  bad "sweep -o t --hdf5"
out=$("$tiptap" sweep "${sweep[@]}" -o "$tmp/u.h5" --hdf5 -q 2>&1); rc=$?
[ $rc -eq 2 ] && [ "$out" = "tiptap sweep: --hdf5 $tmp/u.h5: the same file as -o $tmp/u.h5; give each its own name" ] &&
  [ ! -e "$tmp/u.h5" ] && ok "the table named .h5: refused, exit 2" || bad "the table named .h5: rc $rc, '$out'"
# a varied key's dimension scale carries the unit of the table's column ("1" for the
# setpoint, a fraction of the free amplitude, and for plain numbers; it was ""), read
# with h5py where /usr/bin/python3 has it
"$tiptap" sweep "${sweep[@]}" --vary "feedback.setpoint=70%,80%" -o "$tmp/sp.csv" --hdf5 -q || bad "setpoint sweep"
if /usr/bin/python3 -c "import h5py" 2>/dev/null; then
  units=$(/usr/bin/python3 -c "
import h5py
c = h5py.File('$tmp/sp.h5')['Measurement_000/Channel_000']
print(*(repr(c[k].attrs['units']) for k in ('cantilever.quality_factor', 'feedback.setpoint', 'z')))")
  [ "$units" = "'1' '1' 'm'" ] && ok "key scales' units as the table's: $units" || bad "key scales' units: $units"
else
  echo "     no h5py for /usr/bin/python3: the units not read back"
fi
mkdir "$tmp/v.h5"
expect_error "FILE.h5 a folder" "$tmp/v.h5: is a folder" "$tiptap" sweep "${sweep[@]}" -o "$tmp/v.csv" --hdf5 -q
[ ! -e "$tmp/v.csv" ] && ok "no table written when FILE.h5 is refused" || bad "table written"
# the HDF5 module is loaded from beside the library on the first file: without it, one
# line, before the scan runs; every other command runs without it
lib=$(ldd "$tiptap" | sed -n 's/.*libtiptap\.so[^ ]* => \([^ ]*\) .*/\1/p')
if [ -n "$lib" ]; then
  mkdir -p "$tmp/nomodule"
  cp "$(realpath "$lib")" "$tmp/nomodule/$(basename "$lib")"
  expect_error "no HDF5 module" "libtiptap_hdf5.so" env LD_LIBRARY_PATH="$tmp/nomodule" \
    "$tiptap" scan "${scan[@]}" -o "$tmp/d" --hdf5 -q
  [ ! -e "$tmp/d/height_trace.gsf" ] && ok "no scan without the module" || bad "scanned without the module"
  env LD_LIBRARY_PATH="$tmp/nomodule" "$tiptap" scan "${scan[@]}" -o "$tmp/e" -q 2>/dev/null &&
    [ -s "$tmp/e/height_trace.gsf" ] && ok "a scan without --hdf5 needs no module" || bad "scan without the module"
fi
"$tiptap" scan --help | grep -q -- "--hdf5" && "$tiptap" sweep --help | grep -q -- "--hdf5" &&
  ok "--help lists --hdf5" || bad "--hdf5 not in --help"
exit $fail
