"""Keypoints of many (design, parameter vector) pairs: cached, optionally in parallel.

Function values are cold certified solves (``effects.solve_effects`` from the released state,
the same deterministic solve as ``stitchswitch simulate``, at most ``MAX_NEWTON`` iterations): a
prediction depends only on the design and the parameters, so it is cached, and a fit or a
cross-validation fold revisiting a point costs nothing.

Finite-difference Jacobians need solves at points 1-2 % away from a centre that was just solved.
Those are warm-started from the centre's equilibrium of the same design (``solve(...,
warm_start=...)``): about 3 Newton iterations instead of about 20, and the same branch as the
centre, which is what a derivative needs. They are cached apart from the cold values, keyed by
their centre. ``Evaluator.calls`` counts the solves actually run (cold and warm).
"""
from __future__ import annotations

import numpy as np

from stitchswitch.reduced.model.params import Patch

__all__ = ["Evaluator", "solve_item", "MAX_NEWTON"]

#: Newton iterations per solve. A certified solve takes about 20 (3 warm-started); a few stiff
#: parameter combinations (a strong hardening term) stall just above the tolerance until the
#: budget runs out. Such a solve is used as it stands and counted as uncertified; a budget of
#: 200 (``simulate``: 500) bounds the time they cost a fit.
MAX_NEWTON = 200


def solve_item(item):
    """(keypoints (5,), certified, solution or None, residual) of one (d, p, material, active
    effects, warm start or None); the solution is returned for cold solves (future warm
    starts)."""
    from stitchswitch.validation.discovery.effects import solve_effects

    d, p, material, active, warm = item
    sol = solve_effects(Patch(d, p), material, active, warm_start=warm, max_iter=MAX_NEWTON)
    kp = sol.keypoints
    values = np.array([kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm])
    return (values, sol.certified, (sol if warm is None else None),
            float(sol.residual))


def _key(spec, x, design):
    # the resolution is part of the key: the screening and the full-resolution specs share x
    return (spec.effect, spec.prior, spec.free, spec.start.n_nodes, spec.start.dr_max_mm,
            np.asarray(x, dtype=float).tobytes(), float(design[0]), float(design[1]))


class Evaluator:
    """``keypoints(spec, xs, designs)``: cold (n, 5) keypoints of every x in ``xs``;
    ``perturbed(spec, centre, xs, designs)``: the same, warm-started from ``centre``.

    ``executor``: a map-like from ``stitchswitch.executor`` (None: serial). ``progress``: called
    with the number of solves run so far after every batch."""

    def __init__(self, executor=None, progress=None):
        self.executor = executor
        self.progress = progress
        self.cold: dict = {}
        self.warm: dict = {}
        self.solutions: dict = {}
        self.uncertified: set = set()
        self.calls = 0

    def _run(self, items):
        if not items:
            return []
        if self.executor is not None:
            out = self.executor.map(solve_item, items)
        else:
            out = [solve_item(i) for i in items]
        self.calls += len(items)
        if self.progress:
            self.progress(self.calls)
        return out

    def keypoints(self, spec, xs, designs) -> list[np.ndarray]:
        todo, items = {}, []
        for x in xs:
            material, active = spec.decode(x)
            for design in designs:
                key = _key(spec, x, design)
                if key not in self.cold and key not in todo:
                    todo[key] = len(items)
                    items.append((float(design[0]), float(design[1]), material, active, None))
        for key, (kp, ok, sol, _) in zip(todo, self._run(items)):
            self.cold[key] = kp
            self.solutions[key] = sol
            if not ok:
                self.uncertified.add(key)
        return [np.array([self.cold[_key(spec, x, d)] for d in designs]) for x in xs]

    def one(self, spec, x, designs) -> np.ndarray:
        return self.keypoints(spec, [x], designs)[0]

    def perturbed(self, spec, centre, xs, designs) -> list[np.ndarray]:
        """Keypoints at ``xs`` (near ``centre``), warm-started from the centre's equilibria."""
        self.keypoints(spec, [centre], designs)
        ckey = np.asarray(centre, dtype=float).tobytes()
        todo, items = {}, []
        for x in xs:
            material, active = spec.decode(x)
            for design in designs:
                key = (ckey,) + _key(spec, x, design)
                if key not in self.warm and key not in todo:
                    todo[key] = len(items)
                    warm = self.solutions[_key(spec, centre, design)]
                    items.append((float(design[0]), float(design[1]), material, active, warm))
        for key, (kp, *_) in zip(todo, self._run(items)):
            self.warm[key] = kp
        return [np.array([self.warm[(ckey,) + _key(spec, x, d)] for d in designs]) for x in xs]

    def n_uncertified(self, spec, x, designs) -> int:
        return sum(_key(spec, x, d) in self.uncertified for d in designs)
