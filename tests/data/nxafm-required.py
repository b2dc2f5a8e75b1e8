#!/usr/bin/env python3
"""Writes tests/data/nxafm-required.txt: the groups, fields and attributes that FAIRmat's
NXafm application definition requires, with those of NXspm, the definition it extends.
Run on a checkout of github.com/FAIRmat-NFDI/nexus_definitions:
    python3 tests/data/nxafm-required.py DEFINITIONS_DIR > tests/data/nxafm-required.txt
An element is required unless it says optional="true", recommended="true" or
minOccurs="0" (NXDL 3.1: an application definition's elements are required by default);
a required element under an optional group is left out. Each line: the path (a name in
capitals stands for any name of that class; lower-case letters before capitals fix the
name's start, as in meshSCAN), the kind, the NeXus class or type, the units' kind and
the allowed values ('|'-separated), '-' where none."""
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

NS = "{http://definition.nexusformat.org/nxdl/3.1}"


def required(e):
    return not (e.get("optional") == "true" or e.get("recommended") == "true" or e.get("minOccurs") == "0")


def walk(e, path, out):
    for c in e:
        kind = c.tag.replace(NS, "")
        if kind not in ("group", "field", "attribute") or not required(c):
            continue
        name = c.get("name") or c.get("type", "")[2:].upper()
        p = f"{path}/{'@' if kind == 'attribute' else ''}{name}"
        enum = c.find(NS + "enumeration")
        values = "|".join(i.get("value") for i in enum.findall(NS + "item")) if enum is not None else "-"
        out[p] = (kind, c.get("type", "-") or "-", c.get("units", "-"), values)
        walk(c, p, out)


root = sys.argv[1]
out = {}
for name in ("NXspm", "NXafm"):  # NXafm's own lines replace NXspm's of the same path
    walk(ET.parse(os.path.join(root, "contributed_definitions", name + ".nxdl.xml")).getroot(), "", out)
commit = subprocess.run(["git", "-C", root, "rev-parse", "HEAD"], capture_output=True, text=True).stdout.strip()
print(f"# NXafm (extends NXspm), github.com/FAIRmat-NFDI/nexus_definitions commit {commit or 'unknown'}")
print("# written by tests/data/nxafm-required.py: path kind class-or-type units values")
for p, (kind, typ, units, values) in out.items():
    print(p, kind, typ, units, values)
