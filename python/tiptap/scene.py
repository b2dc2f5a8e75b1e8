"""Scenes: INI files in SI units read by the library's configuration layer
(docs/scene-format.md), keys overridden as `tiptap --set` does, and the schema of every
key with its unit and default."""

import collections
import math
import os
import threading

from ._errors import SceneError, check
from ._lib import ffi, lib, owned_text, text

Key = collections.namedtuple(
    "Key", "section key kind unit units default min max choices path doc named"
)
Key.__doc__ = """One scene key of the schema.

section, key: "[section]" and the key ("material" is named: material.NAME.key);
kind: "quantity", "int", "enum", "string" or "bool"; unit: the SI unit a number given
from Python is read in ("" for plain numbers and keys without one; None where a
number alone is ambiguous, as a setpoint that is a length or a percentage); units: every
SI unit the key accepts; default: as written in a scene (None: absent unless given);
min, max: the allowed range in SI units; choices: an enum's values; path: a file name
relative to the scene file; doc: its one-line meaning; named: the section repeats with
names."""

_KINDS = ("quantity", "int", "enum", "string", "bool")


def _schema():
    count = ffi.new("size_t *")
    sections = lib.tt_scene_schema(count)
    out = {}
    for i in range(count[0]):
        sec = sections[i]
        name = text(sec.name)
        for j in range(sec.nkeys):
            k = sec.keys[j]
            units = []
            bit = 1
            while bit <= k.dims:
                if k.dims & bit:
                    units.append(text(lib.tt_units_symbol(bit)))
                bit <<= 1
            kind = _KINDS[k.kind]
            if kind != "quantity":
                unit = ""
            elif len(units) == 1 and not (k.dims & lib.TT_DIM_FRACTION):
                unit = units[0]
            else:
                unit = None
            out[(name, text(k.key))] = Key(
                name, text(k.key), kind, unit, tuple(units),
                text(getattr(k, "def")) if getattr(k, "def") != ffi.NULL else None,
                k.min, k.max,
                tuple(text(k.choices).split("|")) if k.choices != ffi.NULL else (),
                bool(k.flags & 4), text(k.doc), bool(sec.named),
            )
    return out


SCHEMA = _schema()


def keys():
    """Every scene key the library knows, in documentation order (a list of Key)."""
    return list(SCHEMA.values())


def _key_name(name):
    """'feedback__setpoint' (a keyword argument) -> 'feedback.setpoint'."""
    return name.replace("__", ".")


def check_keywords(func, keys):
    """Keyword arguments that name no scene key (section__key, material__NAME__key)
    refused as Python refuses an unknown keyword, naming func: a misspelt `treads=2`
    is a TypeError, not a scene assignment."""
    for k in keys:
        dotted = _key_name(k)
        if "." not in dotted:
            raise TypeError(f"{func}() got an unexpected keyword argument {k!r}")
        if _schema_key(dotted) is None:
            raise TypeError(f"{func}() got an unexpected keyword argument {k!r} (no scene key "
                            f"{dotted}; tiptap.keys() lists them)")


def c_bytes(value, name):
    """A text for the library as bytes (paths as the file system spells them); a NUL byte,
    where C would end the text unseen, is refused naming the argument."""
    if isinstance(value, (str, os.PathLike)):
        b = os.fsencode(value)
    elif isinstance(value, bytes):
        b = value
    else:
        raise TypeError(f"{name}: a str, bytes or path, not {type(value).__name__}")
    if b"\0" in b:
        raise ValueError(f"{name}: {value!r} contains a NUL byte")
    return b


def _schema_key(assignment_key):
    parts = assignment_key.split(".")
    if len(parts) < 2:
        return None
    section, key = parts[0], parts[-1]
    return SCHEMA.get((section, key))


def format_value(key, value):
    """A Python value as the scene text of key ("section.key" or "material.NAME.key"):
    strings as they are ("52 kHz", "80 %"); True/False as yes/no; numbers in the key's SI
    unit, written so that they read back to the same double."""
    if isinstance(value, str):
        return value
    if isinstance(value, bool):
        return "yes" if value else "no"
    spec = _schema_key(key)
    if isinstance(value, int) and (spec is None or spec.kind != "quantity"):
        return str(value)
    if isinstance(value, (int, float)) or hasattr(value, "__float__"):
        v = float(value)
        if not math.isfinite(v):
            raise SceneError(lib.TT_EINVAL, f"{key}: {value!r} is not a finite number")
        if spec is None or spec.kind != "quantity":
            return repr(v)
        if spec.unit is None:
            raise SceneError(
                lib.TT_EINVAL,
                f"{key}: a number alone is ambiguous here; give the text with its unit "
                f"({text(lib.tt_units_describe(_dims(spec)))})",
            )
        return f"{v!r} {spec.unit}".rstrip()
    raise TypeError(f"{key}: a value is a str, bool or number, not {type(value).__name__}")


def _dims(spec):
    count = ffi.new("size_t *")
    sections = lib.tt_scene_schema(count)
    for i in range(count[0]):
        if text(sections[i].name) == spec.section:
            for j in range(sections[i].nkeys):
                if text(sections[i].keys[j].key) == spec.key:
                    return sections[i].keys[j].dims
    return 0


class Scene:
    """A scene: files read in order (later ones override earlier ones), then keys set.

        s = tiptap.Scene("scans/quick.ini", "surfaces/polymer-blend.ini",
                         feedback__setpoint="70 %", scan__pixels=32)
        s.set({"material.disk.reduced_modulus": 3e9})      # SI numbers take the key's unit
        s["cantilever.free_amplitude"]                     # '20 nm' (the effective value)

    Keyword arguments name keys with double underscores (section__key,
    material__NAME__key); one that names no key is a TypeError. A dict takes any key as
    `tiptap --set` spells it. Every value is checked by the library as the command
    line's are: a bad key, value or unit raises SceneError with the library's one line
    naming file, section and key; a NUL byte in a name or value raises ValueError.

    A Scene may be shared between threads: each call holds the scene's lock, and a run
    works on its own copy, taken when it starts, so that a change made during the run
    reaches neither the run nor its result.
    """

    def __init__(self, *files, text=None, set=None, **keys):
        check_keywords("Scene", keys)
        self._lock = threading.RLock()
        p = lib.tt_scene_alloc()
        if p == ffi.NULL:
            raise MemoryError("tiptap: out of memory for a scene")
        self._p = ffi.gc(p, lib.tt_scene_free)
        for f in files:
            self.load(f)
        if text is not None:
            self.load_string(text)
        self.set(set, **keys)

    @classmethod
    def of(cls, scene, set=None, *, caller="run", **keys):
        """The scene a run works on, always its own: a copy of a Scene (so that later
        changes to it reach neither the run nor its result), or a new one from a file
        name or a list of them; keys set on it. An empty list is refused, as the program
        refuses a command without a scene file; keywords naming no key are TypeErrors
        naming caller."""
        check_keywords(caller, keys)
        if isinstance(scene, Scene):
            s = scene.copy()
            s.set(set, **keys)
            return s
        if isinstance(scene, (str, bytes, os.PathLike)):
            scene = [scene]
        scene = list(scene)
        if not scene:
            raise SceneError(lib.TT_EINVAL, f"{caller}: needs a scene file (the list is empty); "
                                            "tiptap.Scene() is the built-in defaults")
        return cls(*scene, set=set, **keys)

    def load(self, path):
        """Read a scene file over this scene."""
        b = c_bytes(path, "path")
        with self._lock:
            check(lib.tt_scene_load(self._p, b))
        return self

    def load_string(self, text, origin="scene"):
        """Read scene text over this scene; origin names it in messages."""
        t, o = c_bytes(text, "text"), c_bytes(origin, "origin")
        with self._lock:
            check(lib.tt_scene_load_string(self._p, t, o))
        return self

    def set(self, assignments=None, **keys):
        """Set keys: a dict {"section.key": value} and/or section__key=value."""
        check_keywords("set", keys)
        items = list((assignments or {}).items()) + [(_key_name(k), v) for k, v in keys.items()]
        lines = []
        for k, v in items:
            key, value = c_bytes(k, "key"), c_bytes(format_value(k, v), k)
            lines.append(key + b"=" + value)
        with self._lock:
            for line in lines:
                check(lib.tt_scene_set(self._p, line))
        return self

    def _gsf(self, prefix, name, z, dx, dy, keys):
        """z (2-D float32) as a Gwyddion Simple Field file with the header keys given, in a
        temporary folder that lives as long as this scene and its copies; its path."""
        import tempfile

        ny, nx = z.shape
        folder = tempfile.TemporaryDirectory(prefix=prefix)
        path = os.path.join(folder.name, name)
        head = (f"Gwyddion Simple Field 1.0\nXRes = {nx}\nYRes = {ny}\nXReal = {nx * dx!r}\n"
                f"YReal = {ny * dy!r}\nXYUnits = m\n{keys}").encode()
        with open(path, "wb") as f:
            f.write(head + b"\0" * (4 - len(head) % 4) + z.tobytes())
        self.__dict__.setdefault("_folders", []).append(folder)
        return path

    def set_surface_image(self, heights, pixel_size):
        """A measured topography from a numpy array: heights (2-D, metres, row 0 at y = 0)
        with pixel_size (metres, a number or (dx, dy)) become [surface] type = measured,
        through a Gwyddion Simple Field file (float32, as the format stores heights) in a
        temporary folder that lives as long as this scene and its copies. The preparation
        keys (level, line_level, crop, interpolation, edges, z_scale, z_offset) apply as to
        a file (docs/surfaces.md). The library's checks apply: a NaN pixel or an absurd
        pixel size raises SceneError when the scene is run."""
        import numpy as np

        z = np.asarray(heights, dtype="<f4")
        if z.ndim != 2:
            raise ValueError(f"set_surface_image: heights must be a 2-D array, not {z.ndim}-D")
        dx, dy = (pixel_size, pixel_size) if np.ndim(pixel_size) == 0 else pixel_size
        dx, dy = float(dx), float(dy)
        path = self._gsf("tiptap-surface-", "heights.gsf", z, dx, dy, "ZUnits = m\nTitle = numpy\n")
        return self.set({"surface.type": "measured", "surface.image": path})

    def set_material_labels(self, labels, pixel_size, materials):
        """A material map from a numpy integer array: labels (2-D, row 0 at y = 0) with
        pixel_size (metres, a number or (dx, dy)) and materials {label: "NAME"} become
        [surface] map = labels, each [material NAME] map_value its label, through a
        Gwyddion Simple Field file in a temporary folder that lives as long as this scene
        and its copies (docs/surfaces.md, "Material maps from data"; edges applies). A
        non-integer array, a label outside 0-65535 or a material the scene has no section
        for raises ValueError here; a label in the array that no material has raises
        SceneError when the scene is run."""
        import numpy as np

        a = np.asarray(labels)
        if a.ndim != 2:
            raise ValueError(f"set_material_labels: labels must be a 2-D array, not {a.ndim}-D")
        if a.dtype.kind not in "iub":
            raise ValueError(f"set_material_labels: labels must be integers, not {a.dtype}; "
                             "threshold a measured channel with [surface] map = threshold")
        if a.size and (a.min() < 0 or a.max() > 65535):
            raise ValueError(f"set_material_labels: labels {a.min()} to {a.max()}; expected 0 to 65535")
        known = {k.split(".")[1] for k in self.items() if k.startswith("material.")}
        changes = {}
        for label, name in materials.items():
            if name not in known:
                raise ValueError(f"set_material_labels: label {label}: no [material {name}] in the "
                                 f"scene; expected one of {', '.join(sorted(known)) or '(none)'}")
            if not 0 <= int(label) <= 65535:
                raise ValueError(f"set_material_labels: label {label}; expected 0 to 65535")
            changes[f"material.{name}.map_value"] = str(int(label))
        dx, dy = (pixel_size, pixel_size) if np.ndim(pixel_size) == 0 else pixel_size
        dx, dy = float(dx), float(dy)
        # float32 holds every label 0-65535 exactly
        path = self._gsf("tiptap-labels-", "labels.gsf", a.astype("<f4"), dx, dy, "Title = labels\n")
        changes.update({"surface.map": "labels", "surface.map_image": path})
        return self.set(changes)

    def copy(self):
        """A deep copy."""
        c = Scene.__new__(Scene)
        c._lock = threading.RLock()
        c._folders = list(getattr(self, "_folders", []))
        with self._lock:
            p = lib.tt_scene_copy(self._p)
        if p == ffi.NULL:
            raise MemoryError("tiptap: out of memory copying a scene")
        c._p = ffi.gc(p, lib.tt_scene_free)
        return c

    @property
    def origin(self):
        """The file name messages give (the first file read, or "scene")."""
        with self._lock:
            return text(lib.tt_scene_origin(self._p))

    def text(self, sections=None):
        """The effective scene as INI text: every key, defaults included (of [surface], only
        the chosen type's and the map's), paths absolute (what `tiptap scan` writes as
        scene.ini). sections: e.g. "cantilever|tip"."""
        sec = c_bytes(sections, "sections") if sections else ffi.NULL
        with self._lock:
            t = lib.tt_scene_write_string(self._p, sec)
        if t == ffi.NULL:
            check(lib.TT_ENOMEM)
        return owned_text(t)

    def items(self):
        """The effective scene as a dict {"section.key": "value with unit"}, named
        sections as "material.NAME.key" (as --set spells them)."""
        out = {}
        section = None
        for line in self.text().splitlines():
            line = line.strip()
            if not line or line[0] in ";#":
                continue
            if line.startswith("[") and line.endswith("]"):
                section = line[1:-1].strip().replace(" ", ".", 1)
            elif " = " in line and section:
                k, v = line.split(" = ", 1)
                out[f"{section}.{k.strip()}"] = v.strip()
        return out

    def __getitem__(self, key):
        return self.items()[key]

    def __repr__(self):
        return f"<tiptap.Scene {self.origin!r}>"
