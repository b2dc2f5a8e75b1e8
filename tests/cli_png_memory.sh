#!/usr/bin/env bash
# A PNG map too large for the memory is refused naming the scene, the key and the file,
# whichever allocation fails: an 8192 x 8192 16-bit grey height map (130 kB on disk,
# 134 MB decoded, a 537 MB height grid) and an RGBA material map (537 MB decoded) under
# ulimit -v from 50 to 600 MB. Before, the height grid's refusal read "out of memory for
# the height map's grid" and the decoder's "cannot read as PNG: out of memory".
# Skipped under AddressSanitizer, whose shadow memory takes more than any such limit.
# usage: cli_png_memory.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
source "$(dirname "$0")/tt_cli.sh"
if ldd "$tiptap" 2>/dev/null | grep -q "libasan"; then
  ok "skipped: an AddressSanitizer build cannot run under ulimit -v"
  exit 0
fi

python3 - "$tmp" <<'PY'
import struct, sys, zlib
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
def png(path, colour, pixel):
    n = 8192
    c = zlib.compressobj(9)
    row = b"\0" + pixel * n
    data = b"".join(c.compress(row) for _ in range(n)) + c.flush()
    ihdr = struct.pack(">IIBBBBB", n, n, 16, colour, 0, 0, 0)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", data) + chunk(b"IEND", b""))
png(sys.argv[1] + "/height.png", 0, b"\0\0")
png(sys.argv[1] + "/materials.png", 6, b"\0\0\0\0\0\0\xff\xff")
PY
cat >"$tmp/h.ini" <<'INI'
[material substrate]
reduced_modulus = 50 GPa
map_value = 0
[surface]
type = png
png = height.png
[scan]
pixels = 4
lines = 2
INI
sed 's/^type = png$/type = flat\nmap = png\nmap_png = materials.png/; /^png = /d' "$tmp/h.ini" >"$tmp/m.ini"

for map in h:png:height.png m:map_png:materials.png; do
  IFS=: read -r scene key file <<<"$map"
  nomem=0
  for lim in 50000 100000 150000 200000 250000 300000 400000 600000; do
    out=$( (ulimit -v $lim; "$tiptap" scan "$tmp/$scene.ini" -o "$tmp/out$scene$lim" -q) 2>&1); rc=$?
    # below the program's own needs the loader fails before main: not tiptap's message
    grep -q "error while loading shared libraries" <<<"$out" && continue
    grep -q "out of memory" <<<"$out" || continue
    nomem=$((nomem + 1))
    if [ $rc -ne 0 ] && [ "$(wc -l <<<"$out")" -eq 1 ] &&
      grep -q "^tiptap scan: .*$scene.ini: \[surface\] $key: .*$file: out of memory for .* of 8192 x 8192 pixels ([0-9.]* MB)$" <<<"$out"; then
      ok "$file under ulimit -v $lim: '$out'"
    else
      bad "$file under ulimit -v $lim: rc $rc, '$out'"
    fi
  done
  [ $nomem -gt 0 ] && ok "$file: $nomem limits ran out of memory" || bad "$file: no limit ran out of memory"
done
exit $fail
