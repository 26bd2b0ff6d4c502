"""The machine and hoop catalogue: ``stitchswitch/data/machines.json`` plus the user's own file.

The one API for machines and hoops: ``catalogue(user_file)`` (or ``builtin_catalogue()``),
``Catalogue.machine(name)``, and on a ``Machine``: ``hoop(name)``, ``largest_hoop()``,
``hoops_fitting(w, h)``, ``choose_hoop(w, h, name)`` and ``stitches_per_minute``.
``DEFAULT_MACHINE`` names the machine used when none is given (a design file without
``machine.name``, ``stitchswitch patch``, ``StitchParams``' speed); ``default_machine()`` is it.

A catalogue file is a JSON object ``{"format": "stitchswitch machines", "version": 1,
"machines": [...]}``; each machine has ``name``, ``label``, ``stitches_per_minute``,
``default_format`` (an export format) and ``hoops``, each hoop ``name``, ``width_mm``,
``height_mm``, ``margin_mm``, ``frame_width_mm`` and ``jef_code`` (an integer or null); ``notes``
(text) is allowed on both. Unknown keys are refused. Every problem raises ``InvalidInputError``
naming the file and the JSON path of the bad value (``files.json_checks``), e.g. ``machines file
'm.json': $.machines[0].hoops[1].margin_mm: -3 must be >= 0 mm``. A user's machine with the name
of a built-in one replaces it (so measured margins and frame widths of a 550E can be given). The
export formats a ``default_format`` may name are passed in by the caller (``formats``): this
module does not import the export registry. See docs/fabrication.md; the JEF hoop codes of the
built-in hoops are explained in ``hoop_spec``.
"""
from __future__ import annotations

import json
import os
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import json_checks as jc
from stitchswitch.files.json_checks import child
from stitchswitch.layout.embroidery.hoop_spec import Hoop

__all__ = ["DEFAULT_MACHINE", "Machine", "Catalogue", "catalogue", "builtin_catalogue",
           "default_machine", "load_machines", "machines_from_dict"]

FORMAT = "stitchswitch machines"
VERSION = 1
#: The machine used when none is named (the paper's machine, appendix A).
DEFAULT_MACHINE = "janome-550e"
_MACHINE_KEYS = ("name", "label", "stitches_per_minute", "default_format", "hoops")
_HOOP_KEYS = ("name", "width_mm", "height_mm", "margin_mm", "frame_width_mm", "jef_code")


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
        """The hoop called ``name`` (case is ignored)."""
        for h in self.hoops:
            if h.name.lower() == str(name).lower():
                return h
        raise InvalidInputError(f"{jc.show(name)} is not a hoop of the {self.name} (hoops: "
                                + jc.show_all(h.name for h in self.hoops) + ")")

    def largest_hoop(self) -> Hoop:
        """The hoop with the largest sewing field (by area; the first of equal ones)."""
        return max(self.hoops, key=lambda h: h.area_mm2)

    def hoops_fitting(self, width_mm: float, height_mm: float) -> list[Hoop]:
        """The hoops whose sewing field holds a design of this extent (margin not applied)."""
        return [h for h in self.hoops if h.fits(width_mm, height_mm)]

    def choose_hoop(self, width_mm: float, height_mm: float, name: str | None = None,
                    margin: bool = False) -> Hoop:
        """The hoop ``name`` (checked to hold the design), or else the smallest (by area) that
        holds it; with ``margin`` the design must fit the usable area (field minus margin)."""
        def holds(h: Hoop) -> bool:
            if not margin:
                return h.fits(width_mm, height_mm)
            w, hh = h.usable_mm()
            return width_mm <= w + 1e-9 and height_mm <= hh + 1e-9
        if name is not None:
            hoop = self.hoop(name)
            if not holds(hoop):
                within = f" within its {hoop.margin_mm:g} mm margin" if margin else ""
                raise InvalidInputError(f"a {width_mm:.1f} x {height_mm:.1f} mm design does not "
                                        f"fit the hoop {hoop}{within}")
            return hoop
        fit = [h for h in self.hoops if holds(h)]
        if not fit:
            raise InvalidInputError(f"a {width_mm:.1f} x {height_mm:.1f} mm design fits no hoop; "
                                    f"the largest is {self.largest_hoop()}")
        return min(fit, key=lambda h: h.area_mm2)


@dataclass(frozen=True)
class Catalogue:
    machines: tuple[Machine, ...]

    def names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.machines)

    def machine(self, name: str = DEFAULT_MACHINE) -> Machine:
        """The machine called ``name`` (case is ignored)."""
        for m in self.machines:
            if m.name.lower() == str(name).lower():
                return m
        raise InvalidInputError(f"unknown machine {jc.show(name)} (machines: "
                                + jc.show_all(self.names()) + ")")

    def with_machines(self, extra) -> "Catalogue":
        """This catalogue with ``extra`` machines added; a name already present is replaced."""
        extra = tuple(extra)
        names = {m.name.lower() for m in extra}
        kept = tuple(m for m in self.machines if m.name.lower() not in names)
        return Catalogue(kept + extra)


# --- reading --------------------------------------------------------------------------------

def _length(obj, key, path, positive: bool) -> float:
    return jc.number(obj[key], child(path, key), low=0.0, low_open=positive, unit="mm")


def _notes(obj, path) -> str:
    return jc.text(obj.get("notes", ""), child(path, "notes"))


def _hoop(obj, path: str) -> Hoop:
    jc.obj(obj, path, required=_HOOP_KEYS, optional=("notes",))
    name = jc.text(obj["name"], child(path, "name"), nonempty=True).strip()
    w, h = _length(obj, "width_mm", path, True), _length(obj, "height_mm", path, True)
    margin = _length(obj, "margin_mm", path, False)
    frame = _length(obj, "frame_width_mm", path, False)
    if 2 * margin >= min(w, h):
        jc.fail(child(path, "margin_mm"), f"{margin:g} leaves no usable area in a {w:g} x {h:g} "
                                          "mm field")
    code = jc.integer(obj["jef_code"], child(path, "jef_code"), low=0, nullable=True)
    _notes(obj, path)
    return Hoop(name, w, h, code, margin, frame)


def _machine(obj, path: str, source: str, formats) -> Machine:
    jc.obj(obj, path, required=_MACHINE_KEYS, optional=("notes",))
    name = jc.text(obj["name"], child(path, "name"), nonempty=True).strip()
    label = jc.text(obj["label"], child(path, "label"), nonempty=True).strip()
    spm = jc.number(obj["stitches_per_minute"], child(path, "stitches_per_minute"), low=0.0,
                    low_open=True)
    fmt_path = child(path, "default_format")
    fmt = jc.text(obj["default_format"], fmt_path, nonempty=True).strip().lower()
    if formats is not None:
        fmt = jc.choice(fmt, fmt_path, formats, what="an export format")
    hoops_path = child(path, "hoops")
    hoops = tuple(jc.items(obj["hoops"], hoops_path, _hoop, nonempty=True))
    jc.unique([h.name for h in hoops], hoops_path, "name", ignore_case=True)
    return Machine(name, label, spm, fmt, hoops, source, _notes(obj, path))


def machines_from_dict(obj, source: str, formats=None) -> tuple[Machine, ...]:
    """The machines of a parsed catalogue object (``source`` names it in errors); if
    ``formats`` is given, every ``default_format`` must be one of them."""
    root = jc.ROOT
    with jc.reporting(source):
        jc.obj(obj, root, required=("format", "version", "machines"), optional=("about",),
               what="a machines file")
        if obj["format"] != FORMAT:
            jc.fail(child(root, "format"), f"{jc.show(obj['format'])} must be {FORMAT!r}")
        if obj["version"] != VERSION or isinstance(obj["version"], bool):
            jc.fail(child(root, "version"), f"{jc.show(obj['version'])} is not a supported "
                                            f"version ({VERSION})")
        jc.text(obj.get("about", ""), child(root, "about"))
        machines_path = child(root, "machines")
        out = tuple(jc.items(obj["machines"], machines_path,
                             lambda m, path: _machine(m, path, source, formats), nonempty=True))
        jc.unique([m.name for m in out], machines_path, "name", ignore_case=True)
        return out


def load_machines(path, formats=None) -> tuple[Machine, ...]:
    """The machines of a user's catalogue file; ``formats``: the export formats a
    ``default_format`` may name (None: not checked here)."""
    where = f"machines file {os.fspath(path)!r}"
    return machines_from_dict(jc.load_file(path, where), where, formats)


@lru_cache(maxsize=1)
def builtin_catalogue() -> Catalogue:
    """The shipped catalogue (its export formats are checked by the tests)."""
    text = resources.files("stitchswitch").joinpath("data/machines.json").read_text("utf-8")
    return Catalogue(machines_from_dict(json.loads(text), "built-in machines.json"))


def default_machine() -> Machine:
    """The built-in ``DEFAULT_MACHINE``."""
    return builtin_catalogue().machine(DEFAULT_MACHINE)


def catalogue(user_file=None, formats=None) -> Catalogue:
    """The built-in catalogue, with the machines of ``user_file`` added (or replacing);
    ``formats`` as for ``load_machines``."""
    base = builtin_catalogue()
    return base if user_file is None else base.with_machines(load_machines(user_file, formats))
