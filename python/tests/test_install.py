"""docs/python.md says where `cmake --install build --prefix X` puts the package; it is
there, and it loads the library installed beside it."""

import glob
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import SRC

BIN = os.environ.get("TT_BINARY_DIR", os.path.join(SRC, "build"))


def cache(name):
    with open(os.path.join(BIN, "CMakeCache.txt")) as f:
        m = re.search(rf"^{name}:\w+=(.*)$", f.read(), re.M)
    return m.group(1) if m else None


@pytest.mark.skipif(shutil.which("cmake") is None, reason="needs cmake")
def test_the_documented_install_folder(tmp_path):
    if cache("CMAKE_INSTALL_PREFIX") != "/usr/local" or "TT_PYTHON_DIR:STRING=lib/python" not in \
            open(os.path.join(BIN, "CMakeCache.txt")).read():
        pytest.skip("the docs' example is the default configuration's")
    subprocess.run(["cmake", "--install", BIN, "--prefix", str(tmp_path)], check=True,
                   capture_output=True)
    found = [os.path.relpath(p, tmp_path) for p in
             glob.glob(str(tmp_path / "**" / "tiptap" / "__init__.py"), recursive=True)]
    with open(os.path.join(SRC, "docs", "python.md")) as f:
        doc = f.read()
    said = re.search(r"the package lies in\s+`X/(\S+)/tiptap`", doc).group(1)
    version = "%d.%d" % sys.version_info[:2]
    assert found == [said.replace("python3.X", "python" + version) + "/tiptap/__init__.py"]
    env = {k: v for k, v in os.environ.items() if k != "TIPTAP_LIBRARY"}
    env["PYTHONPATH"] = str(tmp_path / os.path.dirname(os.path.dirname(found[0])))
    p = subprocess.run([sys.executable, "-c", "import tiptap, tiptap._lib as l; "
                        "print(l._library_path())"], capture_output=True, text=True, env=env,
                       cwd=tmp_path, check=True)
    assert os.path.realpath(p.stdout.strip()).startswith(str(tmp_path) + "/")
