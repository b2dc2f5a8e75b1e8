"""tiptap from Python: the tapping-mode AFM simulator's library (libtiptap) with scenes,
results as numpy arrays with their units and metadata, progress and Ctrl-C.

    import tiptap
    r = tiptap.scan(["scans/quick.ini", "surfaces/polymer-blend.ini"], scan__pixels=32)
    r["height"], r.units["height"], r.meta["cantilever.free_amplitude"]
    r.warnings  # [(category, message)], also raised as tiptap.TiptapWarning subclasses

docs/python.md has the whole API.
"""

from ._errors import (CaptureError, Interrupted, NumericalError, SceneError, TiptapError,
                      TiptapIOError, TiptapMemoryError)
from ._lib import lib as _clib, text as _text
from .scan import ScanResult, channel_table, scan
from .scene import Key, Scene, keys
from .sweep import sweep
from .tables import ForceVolume, Table, accuracy, approach, contact, force, force_volume, trace, tune
from ._warnings import (EstimateWarning, InputWarning, OscillationWarning, RunWarning,
                        SettleWarning, SetpointWarning, TiptapWarning, ValidityWarning)

__version__ = _text(_clib.tt_version())
version = __version__

__all__ = [
    "CaptureError", "EstimateWarning", "ForceVolume", "InputWarning", "Interrupted", "Key",
    "NumericalError", "OscillationWarning", "RunWarning", "ScanResult", "Scene", "SceneError", "SettleWarning",
    "SetpointWarning", "Table", "TiptapError", "TiptapIOError", "TiptapMemoryError",
    "TiptapWarning", "ValidityWarning", "accuracy", "approach", "channel_table", "contact",
    "force", "force_volume", "keys", "scan", "sweep", "trace", "tune", "version",
]
