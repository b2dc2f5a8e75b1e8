"""The library's warnings (tiptap/util/warning.h) as Python warnings.

A run whose numbers may mislead (a contact past the force laws' validity, a loop that
oscillates, a setpoint not reached, points not settled, an error estimate above the
tolerance, a scene part not used) still returns them; the library says what to doubt
through a handler installed per thread. Around each library call the package installs
one on the thread that makes the call, collects (category, message) pairs, raises each
with warnings.warn under its TiptapWarning subclass, and keeps them on the result
(result.warnings).
"""

import contextlib
import warnings

from ._lib import ffi, lib, text


class TiptapWarning(UserWarning):
    """A warning of the library about a run (its category: .category)."""

    category = "run"


class ValidityWarning(TiptapWarning):
    """Past the force laws' or the model's validity (a contact radius past 0.5 R, the
    averaged tier's oscillation collapsed)."""

    category = "validity"


class OscillationWarning(TiptapWarning):
    """The feedback loop oscillates."""

    category = "oscillation"


class SetpointWarning(TiptapWarning):
    """A setpoint or amplitude not reached (the z piezo at the end of its range, a
    setpoint sweep's unreachable combinations)."""

    category = "setpoint"


class SettleWarning(TiptapWarning):
    """Points not settled."""

    category = "settle"


class EstimateWarning(TiptapWarning):
    """The run's own error estimate above the tolerance."""

    category = "estimate"


class InputWarning(TiptapWarning):
    """A part of the scene given but not used."""

    category = "input"


class RunWarning(TiptapWarning):
    """Anything else about how the run went (a run of more than a minute by estimate)."""

    category = "run"


CLASSES = {c.category: c for c in (ValidityWarning, OscillationWarning, SetpointWarning,
                                   SettleWarning, EstimateWarning, InputWarning, RunWarning)}

for _c in (TiptapWarning, *CLASSES.values()):
    _c.__module__ = "tiptap"


class Collector:
    """The warnings of one run: installed on each thread that calls the library for it
    (`with c.installed():`), kept in order in .items, raised by emit()."""

    def __init__(self):
        self.items = []
        self._emitted = 0
        self._c = ffi.callback("void(const char *, const char *, void *)", self._on)

    def _on(self, category, message, data):
        # called from C: never raise into it
        try:
            self.items.append((text(category), text(message)))
        except BaseException:  # noqa: B902
            pass

    @contextlib.contextmanager
    def installed(self):
        """This collector as the calling thread's handler, the previous one back after."""
        previous = lib.tt_warning_push(self._c, ffi.NULL)
        try:
            yield self
        finally:
            lib.tt_warning_pop(previous)

    def emit(self, stacklevel=2, result=None):
        """warnings.warn each warning not raised yet (stacklevel counts from the caller of
        emit), and keep the whole list on result.warnings. A warning turned into an
        exception by a warnings filter is raised once the list is kept."""
        if result is not None:
            result.warnings = list(self.items)
        pending, self._emitted = self.items[self._emitted:], len(self.items)
        for category, message in pending:
            warnings.warn(message, CLASSES.get(category, TiptapWarning), stacklevel=stacklevel + 1)
