"""Material files: one JSON object whose keys are the fields of ``Material``.

Fields with a default in ``Material`` (the compressive response, ``gamma_mm``, ``eta``,
``n_nodes``, ``dr_max_mm``, ``compression_floor``, ``domain_max_rb``, ``label``) may be left
out; the seven calibrated coefficients are required. ``label`` is text, every other field a
number. A file with the retired ``compression_ratio`` gets a message naming its replacement. Every
problem with a file (unreadable, not JSON, not an object, a duplicate, unknown or missing field,
a value that is not a number or that ``Material`` rejects) raises ``InvalidInputError`` with a
one-line message naming the file and the JSON path of the field (``files.json_checks``), e.g.
``material file 'm.json': $.k_r_emb: -1.0 must be > 0``.

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
from stitchswitch.files import json_checks as jc
from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.files.json_checks import child
from stitchswitch.files.textio import read_text
from stitchswitch.reduced.model.params import Material

__all__ = ["load_material", "save_material", "material_hash", "canonical_json",
           "default_material_path", "material_from_json"]

#: What a file with the retired slack-regularization ratio is told.
RETIRED = ("retired: the compressive response is now c_emb (stitched mats), c_fab (bare knit) and "
           "jam (the jamming stretch); see docs/model.md, 'Compression as physics'")

_FIELDS = {f.name: f for f in fields(Material)}
_REQUIRED = tuple(name for name, f in _FIELDS.items()
                  if f.default is MISSING and f.default_factory is MISSING)
_OPTIONAL = tuple(name for name in _FIELDS if name not in _REQUIRED)


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


def load_material(path: str | os.PathLike) -> Material:
    """Read and validate a material file; see the module docstring for the format."""
    where = f"material file {os.fspath(path)!r}"
    return material_from_json(read_text(path, where, encoding="utf-8"), where)


def material_from_json(text: str, where: str = "material") -> Material:
    """Parse and validate the JSON text of a material; errors start with ``where``."""
    data = jc.loads(text, where)
    with jc.reporting(where):
        if isinstance(data, dict) and "compression_ratio" in data:
            jc.fail(child(jc.ROOT, "compression_ratio"), RETIRED)
        jc.obj(data, jc.ROOT, required=_REQUIRED, optional=_OPTIONAL,
               what="a material (an object of material fields)")
        for name, value in data.items():
            if name == "label":
                jc.text(value, child(jc.ROOT, name))
            else:
                jc.number(value, child(jc.ROOT, name))
        try:
            return Material(**data)
        except InvalidInputError as exc:          # "<field>: <problem>": placed at the field
            name, sep, problem = str(exc).partition(": ")
            if sep and name in _FIELDS:
                jc.fail(child(jc.ROOT, name), problem)
            jc.fail(jc.ROOT, str(exc))
