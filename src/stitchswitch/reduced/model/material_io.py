"""Material files: one JSON object whose keys are the fields of ``Material``.

Fields with a default in ``Material`` (``gamma_mm``, ``eta``, ``n_nodes``, ``dr_max_mm``,
``compression_ratio``) may be left out; the seven calibrated coefficients are required. Every
problem with a file (unreadable, not JSON, not an object, a duplicate, unknown or missing field,
a value that is not a number or that ``Material`` rejects) raises ``InvalidInputError`` with a
one-line message naming the file and the field or value.

``save_material`` writes the canonical form: sorted keys, two-space indent, floats as Python's
shortest round-trip repr, a final newline. Equal materials therefore give byte-identical files,
and ``material_hash`` is the sha256 of exactly those bytes (``sha256sum`` of a saved file).
The built-in ``DEFAULT_MATERIAL`` ships as ``stitchswitch/data/default_material.json``.
"""
from __future__ import annotations

import hashlib
import json
import os
from dataclasses import MISSING, fields
from importlib import resources

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.textio import read_text
from stitchswitch.reduced.model.params import Material

__all__ = ["load_material", "save_material", "material_hash", "canonical_json",
           "default_material_path", "material_from_json"]

_FIELDS = {f.name: f for f in fields(Material)}
_REQUIRED = [name for name, f in _FIELDS.items()
             if f.default is MISSING and f.default_factory is MISSING]


def default_material_path():
    """The shipped copy of ``DEFAULT_MATERIAL`` (an importlib.resources Traversable)."""
    return resources.files("stitchswitch") / "data" / "default_material.json"


def canonical_json(material: Material) -> str:
    """The text ``save_material`` writes for ``material``."""
    if not isinstance(material, Material):
        raise TypeError(f"expected a Material, got {type(material).__name__}")
    return json.dumps(material.as_dict(), sort_keys=True, indent=2, allow_nan=False) + "\n"


def material_hash(material: Material) -> str:
    """sha256 hex digest of ``canonical_json(material)`` (UTF-8)."""
    return hashlib.sha256(canonical_json(material).encode("utf-8")).hexdigest()


def save_material(material: Material, path: str | os.PathLike) -> None:
    """Write ``material`` to ``path`` in canonical form, atomically."""
    atomic_write_text(path, canonical_json(material))


class _Duplicate(Exception):
    """A key seen twice in one JSON object (json.loads would silently keep the last)."""


def _no_duplicates(pairs: list[tuple[str, object]]) -> dict:
    out: dict = {}
    for key, value in pairs:
        if key in out:
            raise _Duplicate(key)
        out[key] = value
    return out


def load_material(path: str | os.PathLike) -> Material:
    """Read and validate a material file; see the module docstring for the format."""
    where = f"material file {os.fspath(path)!r}"
    return material_from_json(read_text(path, where, encoding="utf-8"), where)


def material_from_json(text: str, where: str = "material") -> Material:
    """Parse and validate the JSON text of a material; errors start with ``where``."""
    try:
        data = json.loads(text, object_pairs_hook=_no_duplicates)
    except json.JSONDecodeError as exc:
        raise InvalidInputError(
            f"{where}: invalid JSON at line {exc.lineno} column {exc.colno}: {exc.msg}") from None
    except _Duplicate as exc:
        raise InvalidInputError(f"{where}: field {exc.args[0]!r} appears more than once") from None
    if not isinstance(data, dict):
        raise InvalidInputError(
            f"{where}: expected a JSON object of material fields, got a JSON {_json_type(data)}")
    unknown = sorted(set(data) - set(_FIELDS))
    if unknown:
        raise InvalidInputError(
            f"{where}: unknown field(s) {', '.join(map(repr, unknown))}; "
            f"known fields: {', '.join(_FIELDS)}")
    missing = [name for name in _REQUIRED if name not in data]
    if missing:
        raise InvalidInputError(f"{where}: missing required field(s) {', '.join(map(repr, missing))}")
    for name, value in data.items():
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InvalidInputError(
                f"{where}: field {name!r}: {json.dumps(value)} is not a number")
    try:
        return Material(**data)
    except InvalidInputError as exc:
        raise InvalidInputError(f"{where}: {exc}") from None


def _json_type(value: object) -> str:
    names = {list: "array", str: "string", bool: "boolean", int: "number", float: "number",
             type(None): "null"}
    return names.get(type(value), type(value).__name__)
