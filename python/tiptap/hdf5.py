"""HDF5 files of scans and sweeps, written by the library (docs/hdf5.md): the same
file `tiptap scan --hdf5` writes, byte for byte, from the same scene."""

import os

from ._errors import check
from ._lib import ffi, lib
from .scan import scan_meta


def check_output(path, scene):
    """Refuse an output before the run: a folder that cannot be written, or a file the
    scene reads (its PNG maps): the library's one line, as the program's."""
    lib.tt_config_note_inputs(scene._p)
    f = ffi.new("tt_h5 **")
    check(lib.tt_h5_create(f, os.fsencode(path)))
    check(lib.tt_h5_close(f[0], 0))


def write_scan(scan_p, scene, path):
    """The scan as one HDF5 file at path (written under a temporary name, then renamed)."""
    m = scan_meta(scan_p, scene)
    try:
        check(lib.tt_scan_write_hdf5(os.fsencode(path), scan_p, m.keys, m.values, m.n,
                                     scene.text().encode()))
    finally:
        lib.tt_meta_free(m)
