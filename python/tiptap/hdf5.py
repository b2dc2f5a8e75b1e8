"""HDF5 files of scans and sweeps, written by the library (docs/hdf5.md): the same
file `tiptap scan --hdf5` writes, byte for byte, from the same scene."""

import os

from ._errors import check
from ._lib import ffi, lib


def check_output(path, scene):
    """Refuse an output before the run: a folder that cannot be written, or a file the
    scene reads (its PNG maps): the library's one line, as the program's."""
    lib.tt_config_note_inputs(scene._p)
    f = ffi.new("tt_h5 **")
    check(lib.tt_h5_create(f, os.fsencode(path)))
    check(lib.tt_h5_close(f[0], 0))
