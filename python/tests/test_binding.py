"""The package's declarations of the library (tiptap/_lib.py's cdef) are the headers':
each prototype as the compiler reads include/tiptap/, each struct's size and field
offsets and each constant as a program compiled against the headers sees them. A
header that changes a signature or a struct fails here by name, not as a crash."""

import os
import re
import shutil
import subprocess

import pytest

from tiptap._lib import CDEF, ffi, lib
from conftest import SRC

BIN = os.environ.get("TT_BINARY_DIR", os.path.join(SRC, "build"))
INCLUDES = ["-I", os.path.join(SRC, "include"), "-I", os.path.join(BIN, "include")]
pytestmark = pytest.mark.skipif(shutil.which("gcc") is None, reason="needs gcc")


def normal(proto):
    proto = re.sub(r"\blong int\b", "long", proto)
    proto = re.sub(r"\bunsigned int\b", "unsigned", proto)
    proto = re.sub(r"\b(const|extern)\b", "", proto)
    return re.sub(r"\s+", "", proto).rstrip(";")


def header_prototypes(tmp_path):
    c = tmp_path / "all.c"
    c.write_text('#include "tiptap.h"\n')
    aux = tmp_path / "aux"
    subprocess.run(["gcc", "-std=c11", "-fsyntax-only", "-aux-info", str(aux), *INCLUDES, str(c)],
                   check=True)
    out = {}
    for line in aux.read_text().splitlines():
        m = re.match(r"/\* (\S+):\d+:\w+ \*/ (.*)$", line)
        if m and "/include/tiptap" in m.group(1):
            name = re.search(r"(tt_\w+) \(", m.group(2)).group(1)
            out[name] = normal(m.group(2))
    return out


def cdef_functions():
    return [n for n in dir(lib) if n.startswith("tt_")
            and ffi.typeof(getattr(lib, n)).kind == "function"]


def test_every_prototype_is_the_headers(tmp_path):
    headers = header_prototypes(tmp_path)
    # cffi spells a function-pointer typedef out; the compiler keeps its name
    for alias in re.findall(r"typedef [^;]*\(\*(\w+)\)", CDEF):
        spelled = normal(ffi.typeof(alias).cname)
        headers = {k: re.sub(rf"\b{alias}\b", lambda m: spelled, v) for k, v in headers.items()}
    names = cdef_functions()
    assert len(names) > 40
    for name in names:
        t = ffi.typeof(getattr(lib, name))
        args = ",".join(a.cname for a in t.args) + (",..." if t.ellipsis else "") or "void"
        mine = normal(f"{t.result.cname} {name} ({args})")
        assert name in headers, f"{name}: declared in no public header"
        assert mine == headers[name], f"{name}: cdef {mine} != header {headers[name]}"


def test_every_struct_and_constant_is_the_headers(tmp_path):
    structs = re.findall(r"}\s*(tt_\w+);", CDEF)
    constants = sorted(set(re.findall(r"\b(TT_[A-Z0-9_]+)\s*=", CDEF) +
                           re.findall(r"[{,]\s*(TT_[A-Z0-9_]+)\s*[,}]", CDEF)))
    lines = ['#include <stddef.h>', '#include <stdio.h>', '#include "tiptap.h"',
             "int main(void) {"]
    expect = []
    for s in structs:
        t = ffi.typeof(s)
        if t.kind != "struct":
            continue
        lines.append(f'printf("sizeof {s} %zu\\n", sizeof({s}));')
        expect.append(f"sizeof {s} {ffi.sizeof(s)}")
        for fname, f in t.fields:
            lines.append(f'printf("offsetof {s}.{fname} %zu\\n", offsetof({s}, {fname}));')
            expect.append(f"offsetof {s}.{fname} {f.offset}")
    for c in constants:
        lines.append(f'printf("{c} %ld\\n", (long)({c}));')
        expect.append(f"{c} {getattr(lib, c)}")
    lines.append("return 0; }")
    c = tmp_path / "layout.c"
    c.write_text("\n".join(lines) + "\n")
    exe = tmp_path / "layout"
    subprocess.run(["gcc", "-std=c11", *INCLUDES, str(c), "-o", str(exe)], check=True)
    got = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout.splitlines()
    assert len(structs) >= 4 and len(constants) >= 20
    assert got == expect


def test_versions_agree():
    """The package, the library, the headers and the program say the same version."""
    import tiptap
    from conftest import cli

    with open(os.path.join(BIN, "include", "tiptap", "version.h")) as f:
        header = re.search(r'TIPTAP_VERSION_STRING "([^"]+)"', f.read()).group(1)
    with open(os.path.join(SRC, "python", "pyproject.toml")) as f:
        project = re.search(r'^version = "([^"]+)"', f.read(), re.M).group(1)
    assert tiptap.version == header == project
    assert cli("--version").stdout.strip() == f"tiptap {header}"
    major, minor, patch = map(int, header.split("."))
    assert lib.tt_version_number() == 10000 * major + 100 * minor + patch
