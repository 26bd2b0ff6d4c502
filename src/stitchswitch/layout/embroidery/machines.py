"""The machine and hoop catalogue: ``stitchswitch/data/machines.json`` plus the user's own file.

A catalogue file is a JSON object ``{"format": "stitchswitch machines", "version": 1,
"machines": [...]}``; each machine has ``name``, ``label``, ``stitches_per_minute``,
``default_format`` (an export format) and ``hoops``, each hoop ``name``, ``width_mm``,
``height_mm``, ``margin_mm``, ``frame_width_mm`` and ``jef_code`` (an integer or null); ``notes``
(text) is allowed on both. Unknown keys are refused. Every problem raises ``InvalidInputError``
naming the file and the JSON path of the bad value, e.g. ``machines file 'm.json':
machines[0].hoops[1].margin_mm: -3 must be >= 0``. A user's machine with the name of a built-in
one replaces it (so measured margins and frame widths of a 550E can be given). See
docs/fabrication.md.
"""
from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.textio import read_text
from stitchswitch.layout.embroidery.hoop_spec import Hoop

FORMAT = "stitchswitch machines"
VERSION = 1
_MACHINE_KEYS = ("name", "label", "stitches_per_minute", "default_format", "hoops", "notes")
_HOOP_KEYS = ("name", "width_mm", "height_mm", "margin_mm", "frame_width_mm", "jef_code", "notes")


@dataclass(frozen=True)
class Machine:
    name: str
    label: str
    stitches_per_minute: float
    default_format: str
    hoops: tuple[Hoop, ...]
    source: str = "built-in"
    notes: str = ""

    def hoop(self, name: str) -> Hoop:
        for h in self.hoops:
            if h.name.lower() == str(name).lower():
                return h
        raise InvalidInputError(f"{name!r} is not a hoop of the {self.name}; its hoops are "
                                + ", ".join(h.name for h in self.hoops))


@dataclass(frozen=True)
class Catalogue:
    machines: tuple[Machine, ...]

    def names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.machines)

    def machine(self, name: str) -> Machine:
        for m in self.machines:
            if m.name.lower() == str(name).lower():
                return m
        raise InvalidInputError(f"unknown machine {name!r}; the machines are "
                                + ", ".join(self.names()))

    def with_machines(self, extra) -> "Catalogue":
        """This catalogue with ``extra`` machines added; a name already present is replaced."""
        extra = tuple(extra)
        names = {m.name.lower() for m in extra}
        kept = tuple(m for m in self.machines if m.name.lower() not in names)
        return Catalogue(kept + extra)


class _Bad(Exception):
    def __init__(self, path: str, message: str):
        super().__init__(f"{path}: {message}")


def _keys(obj, path: str, allowed, required) -> None:
    if not isinstance(obj, dict):
        raise _Bad(path, f"must be an object, not {type(obj).__name__}")
    for k in obj:
        if k not in allowed:
            raise _Bad(f"{path}.{k}" if path else k, "unknown key; allowed: " + ", ".join(allowed))
    for k in required:
        if k not in obj:
            raise _Bad(f"{path}.{k}" if path else k, "is missing")


def _text(obj, key, path) -> str:
    v = obj[key]
    if not isinstance(v, str) or not v.strip():
        raise _Bad(f"{path}.{key}", f"{v!r} must be a non-empty string")
    return v.strip()


def _number(obj, key, path, minimum=0.0, strict=True) -> float:
    v = obj[key]
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
        raise _Bad(f"{path}.{key}", f"{v!r} must be a finite number")
    if (strict and v <= minimum) or (not strict and v < minimum):
        raise _Bad(f"{path}.{key}", f"{v!r} must be {'>' if strict else '>='} {minimum:g}")
    return float(v)


def _hoop(obj, path: str) -> Hoop:
    _keys(obj, path, _HOOP_KEYS, _HOOP_KEYS[:-1])
    name = _text(obj, "name", path)
    w, h = _number(obj, "width_mm", path), _number(obj, "height_mm", path)
    margin = _number(obj, "margin_mm", path, strict=False)
    frame = _number(obj, "frame_width_mm", path, strict=False)
    if 2 * margin >= min(w, h):
        raise _Bad(f"{path}.margin_mm", f"{margin:g} leaves no usable area in a {w:g} x {h:g} mm "
                                        "field")
    code = obj["jef_code"]
    if code is not None and (isinstance(code, bool) or not isinstance(code, int) or code < 0):
        raise _Bad(f"{path}.jef_code", f"{code!r} must be a non-negative integer or null")
    if "notes" in obj and not isinstance(obj["notes"], str):
        raise _Bad(f"{path}.notes", "must be a string")
    return Hoop(name, w, h, code, margin, frame)


def _machine(obj, path: str, source: str, formats) -> Machine:
    _keys(obj, path, _MACHINE_KEYS, _MACHINE_KEYS[:-1])
    name, label = _text(obj, "name", path), _text(obj, "label", path)
    spm = _number(obj, "stitches_per_minute", path)
    fmt = _text(obj, "default_format", path).lower()
    if formats is not None and fmt not in formats:
        raise _Bad(f"{path}.default_format", f"{fmt!r} is not an export format ("
                   + ", ".join(formats) + ")")
    hoops = obj["hoops"]
    if not isinstance(hoops, list) or not hoops:
        raise _Bad(f"{path}.hoops", "must be a non-empty array")
    parsed = tuple(_hoop(h, f"{path}.hoops[{i}]") for i, h in enumerate(hoops))
    seen = set()
    for i, h in enumerate(parsed):
        if h.name.lower() in seen:
            raise _Bad(f"{path}.hoops[{i}].name", f"{h.name!r} appears twice")
        seen.add(h.name.lower())
    notes = obj.get("notes", "")
    if not isinstance(notes, str):
        raise _Bad(f"{path}.notes", "must be a string")
    return Machine(name, label, spm, fmt, parsed, source, notes)


def machines_from_dict(obj, source: str, formats=None) -> tuple[Machine, ...]:
    """The machines of a parsed catalogue object (``source`` names it in errors); if
    ``formats`` is given, every ``default_format`` must be one of them."""
    try:
        _keys(obj, "", ("format", "version", "about", "machines"),
              ("format", "version", "machines"))
        if obj["format"] != FORMAT:
            raise _Bad("format", f"{obj['format']!r} must be {FORMAT!r}")
        if obj["version"] != VERSION or isinstance(obj["version"], bool):
            raise _Bad("version", f"{obj['version']!r} is not a supported version ({VERSION})")
        ms = obj["machines"]
        if not isinstance(ms, list) or not ms:
            raise _Bad("machines", "must be a non-empty array")
        out = tuple(_machine(m, f"machines[{i}]", source, formats) for i, m in enumerate(ms))
        seen = set()
        for i, m in enumerate(out):
            if m.name.lower() in seen:
                raise _Bad(f"machines[{i}].name", f"{m.name!r} appears twice")
            seen.add(m.name.lower())
        return out
    except _Bad as exc:
        raise InvalidInputError(f"{source}: {exc}") from None


def load_machines(path) -> tuple[Machine, ...]:
    """The machines of a user's catalogue file."""
    where = f"machines file {os.fspath(path)!r}"
    text = read_text(path, where)
    try:
        obj = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InvalidInputError(f"{where}: not valid JSON ({exc.msg} at line {exc.lineno}, "
                                f"column {exc.colno})") from None
    from stitchswitch.layout.embroidery.export import supported_formats
    return machines_from_dict(obj, where, supported_formats())


@lru_cache(maxsize=1)
def builtin_catalogue() -> Catalogue:
    """The shipped catalogue (its export formats are checked by the tests: reading it must not
    import the export registry, which itself needs ``layout.embroidery.hoops``)."""
    text = resources.files("stitchswitch").joinpath("data/machines.json").read_text("utf-8")
    return Catalogue(machines_from_dict(json.loads(text), "built-in machines.json"))


def catalogue(user_file=None) -> Catalogue:
    """The built-in catalogue, with the machines of ``user_file`` added (or replacing)."""
    base = builtin_catalogue()
    return base if user_file is None else base.with_machines(load_machines(user_file))
