"""The files of a calibration next to its material file ``FILE`` (``calibrate --out FILE``).

* ``FILE``: the calibrated material, written only when the search has finished;
* ``provenance_path(FILE)`` (FILE's stem + ``.calibration.json``): how it was fitted, written
  together with ``FILE``;
* ``checkpoint_path(FILE)`` (FILE's stem + ``.checkpoint.json``): the best point so far, the
  same record with ``"message": "in progress"``, replaced atomically after every generation
  and removed when the run finishes. A killed run leaves it and the previous ``FILE``
  untouched.

``resume_point(FILE, data_sha256)`` reads the checkpoint (or, when there is none, the
provenance of a finished run) to start again from its best material; a file that is empty, not
JSON, not such a record, fitted to other data or holding an invalid material raises one
``InvalidInputError`` naming the file.
"""
from __future__ import annotations

import json
from pathlib import Path

from stitchswitch.errors import InvalidInputError
from stitchswitch.files import json_checks as jc

__all__ = ["provenance_path", "checkpoint_path", "resume_point"]


def provenance_path(out) -> Path:
    out = Path(out)
    return out.with_name(out.stem + ".calibration.json")


def checkpoint_path(out) -> Path:
    out = Path(out)
    return out.with_name(out.stem + ".checkpoint.json")


def resume_point(out, data_sha256: str):
    """``(material, path)``: the best material of the previous run for ``out`` and the file it
    was read from."""
    from stitchswitch.reduced.model.material_io import material_from_json

    path = next((p for p in (checkpoint_path(out), provenance_path(out)) if p.exists()), None)
    if path is None:
        raise InvalidInputError(f"--resume: no previous run at {str(checkpoint_path(out))!r} or "
                                f"{str(provenance_path(out))!r}")
    where = f"--resume: calibration record {str(path)!r}"
    record = jc.load_file(path, where)
    with jc.reporting(where):
        if not isinstance(record, dict):
            jc.fail(jc.ROOT, f"must be a calibration record (a JSON object), got {jc.kind(record)}")
        for key in ("material", "data"):
            if key not in record:
                jc.fail(jc.child(jc.ROOT, key), "missing (not a calibration record)")
        data = jc.obj(record["data"], "$.data", ("sha256",), ("path", "source", "n_train"))
        sha = jc.text(data["sha256"], "$.data.sha256")
        if sha != data_sha256:
            jc.fail("$.data.sha256", f"fitted to other data (sha256 {jc.clip(sha, 12)}, this "
                                     f"data {data_sha256[:12]})")
    material = material_from_json(json.dumps(record["material"]), f"{where}: $.material")
    return material, path
