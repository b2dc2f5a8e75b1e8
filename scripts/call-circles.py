#!/usr/bin/env python3
"""Call circles among the files of a layer: which file calls which (from the object
files' defined and undefined symbols, `nm`), and every strongly connected group of two
or more files. Exit 1 when there is one.
    scripts/call-circles.py [BUILD_DIR] [LAYER...]   (default: build, solver instrument)"""
import glob
import os
import subprocess
import sys

build = sys.argv[1] if len(sys.argv) > 1 else "build"
layers = sys.argv[2:] or ["solver", "instrument"]
bad = 0
for layer in layers:
    objs = glob.glob(os.path.join(build, "CMakeFiles", "tiptap_objects.dir", "src", layer, "*.o"))
    defs, uses = {}, {}
    for o in objs:
        f = os.path.basename(o)[:-4]
        for line in subprocess.run(["nm", o], capture_output=True, text=True).stdout.splitlines():
            p = line.split()
            if len(p) == 3 and p[1] in "TD":
                defs[p[2]] = f
            elif len(p) == 2 and p[0] == "U":
                uses.setdefault(f, set()).add(p[1])
    calls = {f: {defs[u] for u in us if u in defs and defs[u] != f} for f, us in uses.items()}
    # Tarjan's strongly connected components
    index, low, stack, on, groups = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in calls.get(v, ()):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    for v in sorted(calls):
        if v not in index:
            visit(v)
    print(f"src/{layer}: {len(objs)} files, " + ("no call circle" if not groups else
          "call circles: " + "; ".join(" <-> ".join(g) for g in groups)))
    bad |= bool(groups) or not objs
sys.exit(1 if bad else 0)
