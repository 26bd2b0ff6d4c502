"""Noise proportional to the keypoint size: the fit on size-scaled keypoints.

A measurement error that grows with the keypoint (a height read off a photograph to a share of
itself, not to a fixed fraction of a millimetre) makes the big keypoints noisier than the small
ones, and an unweighted least-squares fit then listens most to the noisiest rows. With noise of
standard deviation sigma_q s_iq (s_iq: the size of keypoint q of design i relative to the mean
size of q), dividing every keypoint, measured and predicted, by s_iq gives residuals of equal
variance sigma_q^2: the workflow's least squares, F test, cross-validation and noise-floor
estimate then hold as they are, in millimetres at the mean size.

The sizes are a smooth surface, not the measured values themselves: a quadratic in (d, p)
(``residuals.design_basis``) fitted to the training rows' |keypoint|, so that a row's own noise
does not set its weight (dividing by the measured value pulls the fit towards the rows measured
low), and so that a design never measured (the proposal's candidates) has a size too. A size is
at least ``SIZE_FLOOR_MM``, as in the benchmark's heteroscedastic data: a keypoint near zero
(z_a of a flat patch) is not given an unbounded weight.

``KeypointScale`` is that surface; ``ScaledEvaluator`` wraps an ``evaluate.Evaluator`` so that
every keypoint it returns, and the rows it chooses branch states by, are size-scaled, and
``to_mm`` converts back.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from stitchswitch.validation.discovery.residuals import design_basis

__all__ = ["KeypointScale", "ScaledEvaluator", "SIZE_FLOOR_MM"]

#: the least size a keypoint is given (mm)
SIZE_FLOOR_MM = 1.0


@dataclass(frozen=True)
class KeypointScale:
    """The relative size s(d, p) of each keypoint: ``coef`` (6, 5) of the quadratic surface of
    the sizes over the training designs ``fitted_on`` ((d values), (p values)), divided by
    ``mean_mm`` (5,), the surface's mean over those designs (so their mean scale is 1)."""

    coef: np.ndarray
    fitted_on: tuple
    mean_mm: np.ndarray

    @classmethod
    def from_rows(cls, designs, measured) -> "KeypointScale":
        """The surface fitted to the sizes max(|measured|, ``SIZE_FLOOR_MM``) of ``designs``
        ((d, p) pairs, (n, 5) keypoints)."""
        a = np.asarray(designs, dtype=float).reshape(-1, 2)
        size = np.maximum(np.abs(np.asarray(measured, dtype=float)), SIZE_FLOOR_MM)
        fitted_on = (tuple(a[:, 0]), tuple(a[:, 1]))
        coef = np.linalg.lstsq(design_basis(*fitted_on), size, rcond=None)[0]
        surface = np.maximum(design_basis(*fitted_on) @ coef, SIZE_FLOOR_MM)
        return cls(coef, fitted_on, surface.mean(axis=0))

    def size_mm(self, designs) -> np.ndarray:
        """(n, 5) keypoint sizes (mm) at ``designs``."""
        a = np.asarray(designs, dtype=float).reshape(-1, 2)
        X = design_basis(a[:, 0], a[:, 1], like=self.fitted_on)
        return np.maximum(X @ self.coef, SIZE_FLOOR_MM)

    def __call__(self, designs) -> np.ndarray:
        """(n, 5) relative sizes s at ``designs``."""
        return self.size_mm(designs) / self.mean_mm


def _design(d) -> tuple:
    return (float(d[0]), float(d[1]))


class ScaledEvaluator:
    """An ``Evaluator`` seen through ``scale``: the keypoints of ``keypoints``, ``one``,
    ``perturbed``, ``from_states`` and ``continued`` and the branch ``targets`` are divided by
    ``scale(designs)``; everything else (the solutions, the branch states, the counts) is the
    wrapped evaluator's. The wrapped one still chooses a bistable design's branch by its
    measured row in mm."""

    def __init__(self, ev, scale: KeypointScale):
        self.ev = ev
        self.scale = scale
        self.targets = {d: np.asarray(row, dtype=float) / scale([d])[0]
                        for d, row in ev.targets.items()}

    def __getattr__(self, name):
        return getattr(self.ev, name)

    def to_mm(self, designs, keypoints) -> np.ndarray:
        """Scaled keypoints (n, 5) of ``designs`` back in mm."""
        return np.asarray(keypoints, dtype=float) * self.scale([_design(d) for d in designs])

    def _scaled(self, designs, kp):
        return np.asarray(kp, dtype=float) / self.scale([_design(d) for d in designs])

    def keypoints(self, spec, xs, designs) -> list[np.ndarray]:
        return [self._scaled(designs, kp) for kp in self.ev.keypoints(spec, xs, designs)]

    def one(self, spec, x, designs) -> np.ndarray:
        return self.keypoints(spec, [x], designs)[0]

    def perturbed(self, spec, centre, xs, designs) -> list[np.ndarray]:
        return [self._scaled(designs, kp)
                for kp in self.ev.perturbed(spec, centre, xs, designs)]

    def from_states(self, spec, x, designs, states) -> np.ndarray:
        return self._scaled(designs, self.ev.from_states(spec, x, designs, states))

    def continued(self, spec, path, designs) -> list[tuple[np.ndarray, list]]:
        return [(self._scaled(designs, kp), states)
                for kp, states in self.ev.continued(spec, path, designs)]
