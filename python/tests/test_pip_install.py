"""`pip install ./python` installs the package alone, from what is on the machine: with
Debian's pip and setuptools (--no-build-isolation), no index (--no-index) and no
dependencies fetched (--no-deps), the installed copy imports and runs against the
library named by TIPTAP_LIBRARY (docs/python.md, "Install")."""

import os
import shutil
import subprocess
import sys

from conftest import QUICK, src


def test_pip_installs_the_package_without_a_download(tmp_path):
    # a copy: setuptools writes its build/ and egg-info beside the sources
    shutil.copytree(src("python"), tmp_path / "python",
                    ignore=shutil.ignore_patterns("tests", "__pycache__", "*.egg-info", "build"))
    env = {**os.environ, "PIP_NO_INDEX": "1", "PIP_DISABLE_PIP_VERSION_CHECK": "1"}
    p = subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation",
                        "--no-deps", "--no-index", "--target", str(tmp_path / "site"),
                        str(tmp_path / "python")], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    assert (tmp_path / "site" / "tiptap" / "__init__.py").is_file()
    # the installed copy, not the source tree's, in a fresh interpreter
    env["PYTHONPATH"] = str(tmp_path / "site")
    code = ("import tiptap, sys; s = tiptap.Scene(*sys.argv[1:]); "
            "print(tiptap.__file__); print(s['scan.pixels'])")
    p = subprocess.run([sys.executable, "-c", code, *QUICK], capture_output=True, text=True,
                       env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    where, pixels = p.stdout.split("\n")[:2]
    assert where == str(tmp_path / "site" / "tiptap" / "__init__.py")
    assert int(pixels) > 0
