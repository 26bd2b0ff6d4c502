"""Newtons from measured switching forces: one scale factor, fitted on the train rows of a force
table and validated on its held-out rows (docs/force.md).

The shell's shapes fix only stiffness ratios, so its switching force is known up to one factor:
F_N = s F_model. ``fit_force_scale`` computes F_model (``path.switching_path``, model units) for
every design of the table, fits s by least squares through the origin on the ``train`` rows,
s = sum F_meas F_model / sum F_model^2, and reports R^2 and the MAE on ``train`` and ``val``
(as the paper's Appendix B does for its polynomial). s is also given as the knit's tensile
stiffness it implies (``moduli.force_scale_n_per_model``), to compare with a tensile test.
Designs without a certified pop-up state in the frame have no switching force; they are listed,
not fitted. The table's ``source`` line (SYNTHETIC for the shipped table) is carried along.
"""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from stitchswitch.errors import InvalidInputError, StitchSwitchError
from stitchswitch.fem_reference.revolution.moduli import force_scale_n_per_model
from stitchswitch.fem_reference.revolution.params import DEFAULT_SHELL, ShellParams
from stitchswitch.fem_reference.snap.path import switching_path
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch


@dataclass(frozen=True)
class ForceScaleFit:
    scale_n_per_model: float
    knit_stiffness_n_per_m: float
    r2_train: float
    r2_val: float
    mae_train_n: float
    mae_val_n: float
    n_train: int
    n_val: int
    excluded: tuple            # (d_mm, fill) without a pop-up state
    source: str

    def as_dict(self) -> dict:
        from dataclasses import asdict

        out = asdict(self)
        out["excluded"] = [list(e) for e in self.excluded]
        return out


def _r2(y, y_hat) -> float:
    ss = float(np.sum((y - y.mean()) ** 2))
    return float("nan") if ss == 0.0 else 1.0 - float(np.sum((y - y_hat) ** 2)) / ss


def model_forces(designs, material: Material = DEFAULT_MATERIAL, params: ShellParams = DEFAULT_SHELL,
                 steps: int = 20) -> dict:
    """{(d, p): switching force in model units, or None without a pop-up state}."""
    out = {}
    for d, p in designs:
        try:
            out[(d, p)] = switching_path(Patch(d, p), material, params, steps=steps).switching_force
        except StitchSwitchError:
            out[(d, p)] = None
    return out


def fit_force_scale(samples, material: Material = DEFAULT_MATERIAL, params: ShellParams = DEFAULT_SHELL,
                    *, source: str = "unspecified", steps: int = 20, forces: dict | None = None) -> ForceScaleFit:
    """The scale fitted on the train rows of ``samples`` (``ForceSample``s); ``forces`` may give
    the model forces already computed (``model_forces``)."""
    samples = list(samples)
    designs = sorted({(s.diameter_mm, s.fill) for s in samples})
    forces = model_forces(designs, material, params, steps) if forces is None else forces
    excluded = tuple(k for k in designs if forces.get(k) is None)
    rows = {split: [(s.force_N, forces[(s.diameter_mm, s.fill)]) for s in samples
                    if s.split == split and forces.get((s.diameter_mm, s.fill)) is not None]
            for split in ("train", "val")}
    if len(rows["train"]) < 2 or not rows["val"]:
        raise InvalidInputError("the force table needs at least 2 train rows and 1 validation row "
                                "with a pop-up state")
    y, f = (np.array(v) for v in zip(*rows["train"]))
    s = float(y @ f / (f @ f))
    yv, fv = (np.array(v) for v in zip(*rows["val"]))
    unit = force_scale_n_per_model(material, replace(params, knit_stiffness_n_per_m=1.0))
    return ForceScaleFit(
        scale_n_per_model=s, knit_stiffness_n_per_m=s / unit,
        r2_train=_r2(y, s * f), r2_val=_r2(yv, s * fv),
        mae_train_n=float(np.mean(np.abs(y - s * f))), mae_val_n=float(np.mean(np.abs(yv - s * fv))),
        n_train=len(y), n_val=len(yv), excluded=excluded, source=source)
