"""Switching force of a patch: the paper's second-order polynomial model (Appendix B).

The force needed to switch a patch between its two stable states is modelled as

    F(d, p) = c_1 + c_d d + c_p p + c_dd d^2 + c_pp p^2 + c_dp d p      [N]

with d the patch diameter in mm (pre-stretched fabric, as everywhere) and p the fill fraction.
The six coefficients are fitted by least squares (``numpy.linalg.lstsq``) to the ``train`` rows
of a force table; R^2 and the mean absolute error are reported on the train and ``val`` rows.
R^2 of a split is ``1 - SS_res / SS_tot`` about that split's own mean (nan if its forces are
all equal). *The paper* fitted 25 calibration and 28 validation patches (forces 0.04-0.77 N over
d 20-90 mm, p 0.6-1.0) and reports R^2 = 0.95 (train) / 0.80 (validation) and a validation MAE
of 0.06 N; its data are not published.

The shipped default table, ``stitchswitch/data/force_synthetic.csv``, is therefore SYNTHETIC:
drawn by ``scripts/make_force_dataset.py`` from a smooth made-up "true" force plus Gaussian
noise, with the paper's design and range. It is not a measurement; its first line says so, and
``ForceFit.source`` carries that line to every output.

Force table (CSV, UTF-8): a header naming at least ``d_mm, fill, force_N, split`` (any order;
other columns such as ``sample_id`` or ``notes`` are ignored), one row per sample. Lines whose
first non-blank character is ``#`` are comments and blank lines are skipped; the first comment
``# source: ...`` is the table's provenance. ``load_force_csv`` rejects, naming the line and
column: a missing column, a wrong field count, a value that is not a finite number, d outside
[10, 150] mm, fill outside (0, 1], a negative force, a split other than train/val.
"""
from __future__ import annotations

import os
from dataclasses import dataclass, fields
from functools import lru_cache
from importlib import resources

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import show
from stitchswitch.files.textio import csv_number, csv_records, read_text
from stitchswitch.reduced.model.params import DIAMETER_RANGE_MM

__all__ = ["ForceModel", "ForceFit", "ForceSample", "fit_force_model", "load_force_csv",
           "parse_force_csv", "default_force_fit", "default_force_csv_path", "FEATURES"]

FEATURES = ("1", "d", "p", "d^2", "p^2", "d*p")
REQUIRED_COLUMNS = ("d_mm", "fill", "force_N", "split")
SPLITS = ("train", "val")


def _features(diameter_mm, fill) -> np.ndarray:
    d, p = np.broadcast_arrays(np.asarray(diameter_mm, float), np.asarray(fill, float))
    return np.stack([np.ones_like(d), d, p, d * d, p * p, d * p], axis=-1)


@dataclass(frozen=True)
class ForceModel:
    """Coefficients of F = c_1 + c_d d + c_p p + c_dd d^2 + c_pp p^2 + c_dp d p (F in N, d in mm)."""

    c_1: float
    c_d: float
    c_p: float
    c_dd: float
    c_pp: float
    c_dp: float

    @classmethod
    def from_coefficients(cls, coef) -> "ForceModel":
        """From six numbers in the order of ``FEATURES``."""
        return cls(*(float(c) for c in np.asarray(coef, float).reshape(6)))

    @property
    def coefficients(self) -> np.ndarray:
        return np.array([getattr(self, f.name) for f in fields(self)])

    def predict(self, diameter_mm, fill) -> np.ndarray:
        """Switching force in N; diameter_mm and fill broadcast (scalars give a 0-d array)."""
        return _features(diameter_mm, fill) @ self.coefficients

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


@dataclass(frozen=True)
class ForceSample:
    """One row of a force table (``diameter_mm`` is the column ``d_mm``)."""

    diameter_mm: float
    fill: float
    force_N: float
    split: str
    sample_id: str = ""


@dataclass(frozen=True)
class ForceFit:
    """A fitted ``ForceModel`` with its scores and the range of the train designs it was fitted on."""

    model: ForceModel
    r2_train: float
    r2_val: float
    mae_train_N: float
    mae_val_N: float
    n_train: int
    n_val: int
    source: str
    d_range_mm: tuple[float, float]
    fill_range: tuple[float, float]

    def extrapolates(self, diameter_mm: float, fill: float) -> bool:
        """True if (d, p) lies outside the min/max box of the train designs."""
        return not (self.d_range_mm[0] <= diameter_mm <= self.d_range_mm[1]
                    and self.fill_range[0] <= fill <= self.fill_range[1])

    def as_dict(self) -> dict:
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "model"}
        out.update(d_range_mm=list(self.d_range_mm), fill_range=list(self.fill_range),
                   coefficients=self.model.as_dict())
        return out


def _r2(y: np.ndarray, y_hat: np.ndarray) -> float:
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    return float("nan") if ss_tot == 0.0 else 1.0 - float(np.sum((y - y_hat) ** 2)) / ss_tot


def fit_force_model(rows, source: str = "unspecified") -> ForceFit:
    """Least-squares fit of ``ForceModel`` to the train rows of ``rows`` (``ForceSample``s)."""
    rows = list(rows)
    split = {s: [r for r in rows if r.split == s] for s in SPLITS}
    for s in SPLITS:
        if not split[s]:
            raise InvalidInputError(f"force data ({source}): the {s} split is empty")
    if len(split["train"]) < 6:
        raise InvalidInputError(f"force data ({source}): {len(split['train'])} train rows, "
                                "need at least 6 for the six polynomial coefficients")
    arr = {s: np.array([(r.diameter_mm, r.fill, r.force_N) for r in split[s]], float) for s in SPLITS}
    X, y = _features(arr["train"][:, 0], arr["train"][:, 1]), arr["train"][:, 2]
    coef, _, rank, _ = np.linalg.lstsq(X, y, rcond=None)
    if rank < 6:
        raise InvalidInputError(f"force data ({source}): the train designs determine only {rank} of "
                                "the 6 coefficients (need at least 3 distinct d and 3 distinct fill "
                                "values, not all on one line)")
    model = ForceModel.from_coefficients(coef)
    score = {}
    for s in SPLITS:
        y_s, y_hat = arr[s][:, 2], model.predict(arr[s][:, 0], arr[s][:, 1])
        score[s] = (_r2(y_s, y_hat), float(np.mean(np.abs(y_s - y_hat))))
    d, p = arr["train"][:, 0], arr["train"][:, 1]
    return ForceFit(model, score["train"][0], score["val"][0], score["train"][1], score["val"][1],
                    len(split["train"]), len(split["val"]), source,
                    (float(d.min()), float(d.max())), (float(p.min()), float(p.max())))


def _sample(fields_: dict[str, str], where: str) -> ForceSample:
    d, p, f = (csv_number(fields_[c], where, c) for c in ("d_mm", "fill", "force_N"))
    if not DIAMETER_RANGE_MM[0] <= d <= DIAMETER_RANGE_MM[1]:
        raise InvalidInputError(f"{where}, column d_mm: {d:g} is outside "
                                f"[{DIAMETER_RANGE_MM[0]:g}, {DIAMETER_RANGE_MM[1]:g}] mm")
    if not 0.0 < p <= 1.0:
        raise InvalidInputError(f"{where}, column fill: {p:g} is outside (0, 1]")
    if f < 0.0:
        raise InvalidInputError(f"{where}, column force_N: {f:g} is negative")
    if fields_["split"] not in SPLITS:
        raise InvalidInputError(f"{where}, column split: {show(fields_['split'])} is not train or val")
    return ForceSample(d, p, f, fields_["split"], fields_.get("sample_id", ""))


def parse_force_csv(text: str, name: str = "<text>") -> tuple[list[ForceSample], str]:
    """Rows and provenance of a force table given as text; ``name`` labels the errors."""
    rows, header = [], None
    source, records = csv_records(text)
    for lineno, cells in records:
        where = f"force data {name}, line {lineno}"
        if header is None:
            missing = [c for c in REQUIRED_COLUMNS if c not in cells]
            if missing:
                raise InvalidInputError(f"{where}: header has no column {show(missing[0])} "
                                        f"(need {', '.join(REQUIRED_COLUMNS)})")
            dup = next((c for c in cells if cells.count(c) > 1), None)
            if dup is not None:
                raise InvalidInputError(f"{where}: column {show(dup)} appears twice in the header")
            header = cells
            continue
        if len(cells) != len(header):
            raise InvalidInputError(f"{where}: {len(cells)} fields, the header has {len(header)}")
        rows.append(_sample(dict(zip(header, cells)), where))
    if header is None or not rows:
        raise InvalidInputError(f"force data {name}: no {'header' if header is None else 'data rows'}")
    return rows, source if source is not None else f"unspecified (no '# source:' line in {name})"


def load_force_csv(path: str | os.PathLike) -> tuple[list[ForceSample], str]:
    """Read and validate a force table file: ``(rows, provenance)``."""
    name = repr(os.fspath(path))
    return parse_force_csv(read_text(path, f"force data {name}"), name)


def default_force_csv_path():
    """The shipped synthetic table (an importlib.resources Traversable)."""
    return resources.files("stitchswitch") / "data" / "force_synthetic.csv"


@lru_cache(maxsize=1)
def default_force_fit() -> ForceFit:
    """The model fitted to the shipped SYNTHETIC table (cached; ``ForceFit`` is frozen)."""
    rows, source = parse_force_csv(default_force_csv_path().read_text("utf-8"), "force_synthetic.csv")
    return fit_force_model(rows, source)
