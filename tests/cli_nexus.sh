#!/usr/bin/env bash
# scan --hdf5 as a NeXus NXafm entry (/entry, beside the NSID /Measurement_000): every
# group, field and attribute that FAIRmat's NXafm definition (with NXspm, which it
# extends) requires is there with its class, type, units and allowed value, as listed
# from the definition in tests/data/nxafm-required.txt (Debian packages no NeXus
# validator that knows NXafm: nexus-tools 4.4.3 has none); the lock-in, z controller,
# cantilever, scan region and sample carry the scene's values; the NXdata's images are
# the measurement's, linked. Exit 77 (skipped) without Debian's python3-h5py.
# usage: cli_nexus.sh path/to/tiptap source_dir
set -u
tiptap=$(realpath "$1")
src=$(realpath "$2")
source "$(dirname "$0")/tt_cli.sh"

py=/usr/bin/python3
"$py" -c "import h5py, numpy" 2>/dev/null || { echo "skipped: $py lacks h5py or numpy"; exit 77; }
"$tiptap" scan "$src/scans/quick.ini" "$src/surfaces/polymer-blend.ini" --set scan.pixels=8 \
  --set scan.lines=3 --set scan.size=800nm -o "$tmp/s" --hdf5 -q 2>"$tmp/err" || { cat "$tmp/err"; bad "scan ran"; exit 1; }

cd "$tmp" && "$py" - "$tmp/s/scan.h5" "$src/tests/data/nxafm-required.txt" <<'PY'
import re
import sys

import h5py
import numpy as np

fail = 0


def check(ok, what):
    global fail
    print(("ok   " if ok else "FAIL ") + what)
    fail |= not ok


LENGTH = {"m": 1, "mm": 1e-3, "um": 1e-6, "nm": 1e-9, "pm": 1e-12}


def matches(obj, parent, seg, kind, typ):
    """Whether obj, a member of parent named by its last path part, stands for seg."""
    name = obj.name.split("/")[-1]
    fixed = re.match(r"^([a-z_]*)([A-Z_]*)$", seg)
    if fixed.group(2) == "":  # a fixed name
        ok = name == seg
    elif seg == "DATA" and parent.attrs.get("NX_class") == "NXdata":  # the signal
        ok = name == parent.attrs.get("signal")
    elif seg == "AXISNAME" and parent.attrs.get("NX_class") == "NXdata":
        ok = name in list(parent.attrs.get("axes", []))
    else:  # any name, or one that starts with the lower-case letters
        ok = name.startswith(fixed.group(1))
    if kind == "group":
        return ok and isinstance(obj, h5py.Group) and obj.attrs.get("NX_class") == typ
    return ok and isinstance(obj, h5py.Dataset)


def find(group, parts, kind, typ, classes, done=""):
    """The objects at the path parts below group, each group above of the class the
    definition gives it (classes: path -> class)."""
    seg, rest = parts[0], parts[1:]
    here = done + "/" + seg
    found = []
    for k in group:
        obj = group[k]
        if rest:
            if isinstance(obj, h5py.Group) and matches(obj, group, seg, "group", classes[here]):
                found += find(obj, rest, kind, typ, classes, here)
        elif matches(obj, group, seg, kind, typ):
            found.append(obj)
    return found


with h5py.File(sys.argv[1], "r") as f:
    lines = [l.split(" ", 4) for l in open(sys.argv[2]).read().splitlines() if not l.startswith("#")]
    classes = {l[0]: l[2] for l in lines if l[1] == "group"}
    check(len(lines) >= 20, f"{len(lines)} required elements listed")
    for path, kind, typ, units, values in lines:
        objs = find(f, path.strip("/").split("/"), kind, typ, classes)
        ok = bool(objs)
        for o in objs:
            if kind == "field" and typ == "NX_NUMBER":
                ok &= o.dtype.kind in "fiu"
            if units == "NX_LENGTH":
                ok &= o.attrs.get("units") in LENGTH
            if values != "-":
                v = o[()]
                ok &= (v.decode() if isinstance(v, bytes) else str(v)) in values.split("|")
        check(ok, f"{path} ({kind} {typ}{'' if units == '-' else ', ' + units}): "
                  f"{', '.join(o.name for o in objs) or 'missing'}")

    e = f["entry"]
    check(f.attrs["default"] == "entry" and e.attrs["default"] == "data", "root and entry name their defaults")
    m = f["Measurement_000"]
    d = e["data"]
    images = [m[c][k] for c in m if c.startswith("Channel_") for k in m[c]
              if isinstance(m[c][k], h5py.Dataset) and k not in ("x", "y")]
    check(len(images) == 14 and all(d[i.name.split("/")[-1]].id == i.id for i in images),
          f"the NXdata holds the {len(images)} images, the measurement's own (links)")
    check(d.attrs["signal"] == "height_trace" and list(d.attrs["axes"]) == ["y", "x"] and
          d["x"].id == m["Channel_000/x"].id and np.isclose(d["x"][-1], 800e-9 * 15 / 16),
          "signal height_trace, axes y, x: the pixel centres in m")

    def field(path, value, unit):
        o = e[path]
        ok = np.isclose(o[()], value) and o.attrs.get("units", "") == unit
        check(ok, f"{path} = {o[()]} {o.attrs.get('units', '')} (scene: {value} {unit})")

    ins = "instrument/"
    check(e[ins + "lockin_amplifier"].attrs["NX_class"] == "NXlockin", "the lock-in is an NXlockin")
    field(ins + "lockin_amplifier/time_constant", 100, "us")
    field(ins + "lockin_amplifier/lp_filter_order_1", 2, "")
    check(e[ins + "positioner_spm/z_controller"].attrs["NX_class"] == "NXpid_controller",
          "the z feedback is an NXpid_controller")
    field(ins + "positioner_spm/z_controller/setpoint", 80, "%")
    field(ins + "positioner_spm/z_controller/K_i", 1000, "Hz")
    check(e[ins + "cantilever_spm"].attrs["NX_class"] == "NXspm_cantilever", "the cantilever is an NXspm_cantilever")
    field(ins + "cantilever_spm/spring_constant", 40, "N/m")
    field(ins + "cantilever_spm/cantilever_oscillator/reference_amplitude", 20, "nm")
    field(ins + "cantilever_spm/cantilever_oscillator/reference_frequency", 300, "kHz")
    field(ins + "scan_environment/scan_control/scan_region/scan_end_x", 800e-9, "m")
    field(ins + "scan_environment/scan_control/mesh_scan/scan_points_y", 3, "")
    s = e["sample"]
    check(s.attrs["NX_class"] == "NXsample" and s["material.disk.youngs_modulus"][()] == b"3 GPa" and
          s["surface.map"][()] == b"disks", "the sample: the scene's surface and materials")
sys.exit(fail)
PY
rc=$?
[ $rc -eq 0 ] && ok "the NXafm entry has every required element" || bad "NXafm entry: exit $rc"
exit $fail
