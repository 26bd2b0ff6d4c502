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

**Branches.** Where a design's released state is bistable, which equilibrium the cold solve
reaches jumps with the parameters, and a local fit cannot cross the jump. A design may hold
*branch states* (``add_branch``: equilibria found by following a scan of an effect's strength,
``fit.follow_branches``); when it does and its measured row is known (``targets``), its value
at x is the equilibrium nearest to that row among the cold solve and the solves warm-started
from each branch state (all equilibria of the same model at x): the model's prediction for
the state the measured patch is in. A model uses the states found along the scans of its own
effects; the starting model uses every state (the reference of every test is never the less
flexible side). The cache key holds the number of states used, and a design without branch
states or without a target (validation rows, proposed designs) takes the cold solve.
(Measured: shared by every model, a state found along prestretch_loss's scan let
fill_exponent's folds reach a branch and tie with the true effect.)
"""
from __future__ import annotations

import numpy as np

from stitchswitch.blas import one_thread
from stitchswitch.reduced.model.params import Patch

__all__ = ["Evaluator", "solve_item", "MAX_NEWTON", "MAX_BRANCHES"]

#: Newton iterations per solve. A certified solve takes about 20 (3 warm-started); a few stiff
#: parameter combinations (a strong hardening term) stall just above the tolerance until the
#: budget runs out. Such a solve is used as it stands and counted as uncertified; a budget of
#: 200 (``simulate``: 500) bounds the time they cost a fit.
MAX_NEWTON = 200
#: Branch states kept per design (each costs one warm solve per evaluation of the design).
MAX_BRANCHES = 2


def solve_item(item):
    """(keypoints (5,), certified, solution or None, residual) of one (d, p, material, active
    effects, warm start or None[, keep]); the solution is returned for cold solves (future warm
    starts), and for warm ones when ``keep`` is true."""
    from stitchswitch.validation.discovery.effects import solve_effects

    d, p, material, active, warm = item[:5]
    keep = warm is None or (len(item) > 5 and item[5])
    sol = solve_effects(Patch(d, p), material, active, warm_start=warm, max_iter=MAX_NEWTON)
    kp = sol.keypoints
    values = np.array([kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm])
    return (values, sol.certified, (sol if keep else None), float(sol.residual))


def _design(design):
    return float(design[0]), float(design[1])


def _raw_key(spec, x, design):
    # the resolution is part of the key: the screening and the full-resolution specs share x
    return (spec.effect, spec.prior, spec.free, spec.start.n_nodes, spec.start.dr_max_mm,
            np.asarray(x, dtype=float).tobytes(), float(design[0]), float(design[1]))


class Evaluator:
    """``keypoints(spec, xs, designs)``: (n, 5) keypoints of every x in ``xs`` (cold, or the
    branch nearest the design's target, module docstring); ``perturbed(spec, centre, xs,
    designs)``: the same, warm-started from ``centre``'s equilibria; ``continued(spec, path,
    designs)``: each design followed along ``path``.

    ``executor``: a map-like from ``stitchswitch.executor`` (None: serial). ``progress``: called
    with the number of solves run so far after every batch. ``targets``: {(d, p): measured row
    (5,)}, the rows branch states are chosen by."""

    def __init__(self, executor=None, progress=None, targets=None):
        self.executor = executor
        self.progress = progress
        self.targets = {_design(d): np.asarray(v, dtype=float)
                        for d, v in (targets or {}).items()}
        self.branches: dict = {}
        self.raw: dict = {}
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
            with one_thread():              # once for the batch, not once per solve
                out = [solve_item(i) for i in items]
        self.calls += len(items)
        if self.progress:
            self.progress(self.calls)
        return out

    def _pool(self, spec, design) -> tuple:
        """The branch states ``spec`` evaluates ``design`` with: those found along the scans of
        its own effects (the candidate and the prior ones); the starting model (no effect)
        takes them all, so that the reference of every test is never less flexible."""
        d = _design(design)
        if d not in self.targets:
            return ()
        mine = (spec.effect,) + tuple(spec.prior)
        everything = spec.effect is None and not spec.prior
        return tuple(s for name, s in self.branches.get(d, ()) if everything or name in mine)

    def _key(self, spec, x, design):
        return _raw_key(spec, x, design) + (len(self._pool(spec, design)),)

    def add_branch(self, design, solution, effect=None) -> bool:
        """Keep ``solution``, found along a scan of ``effect``, as a branch state of ``design``
        (at most ``MAX_BRANCHES`` per design)."""
        d = _design(design)
        pool = self.branches.get(d, ())
        if d not in self.targets or len(pool) >= MAX_BRANCHES:
            return False
        self.branches[d] = pool + ((effect, solution),)
        return True

    def keypoints(self, spec, xs, designs) -> list[np.ndarray]:
        todo, items = {}, []
        for x in xs:
            material, active = spec.decode(x)
            for design in designs:
                rk = _raw_key(spec, x, design)
                if self._key(spec, x, design) in self.cold:
                    continue
                if rk not in self.raw and rk not in todo:
                    todo[rk] = len(items)
                    items.append((float(design[0]), float(design[1]), material, active, None))
                for i, state in enumerate(self._pool(spec, design)):
                    bk = rk + (i,)
                    if bk not in self.raw and bk not in todo:
                        todo[bk] = len(items)
                        items.append((float(design[0]), float(design[1]), material, active,
                                      state, True))
        for key, out in zip(todo, self._run(items)):
            self.raw[key] = out
        for x in xs:
            for design in designs:
                key = self._key(spec, x, design)
                if key in self.cold:
                    continue
                rk = _raw_key(spec, x, design)
                options = [self.raw[rk]] + [self.raw[rk + (i,)]
                                            for i in range(len(self._pool(spec, design)))]
                best = options[0]
                if len(options) > 1:
                    target = self.targets[_design(design)]
                    err = [float(np.sum((o[0] - target) ** 2)) for o in options]
                    best = options[int(np.argmin(err))]      # the cold solve on ties
                kp, ok, sol, _ = best
                self.cold[key] = kp
                self.solutions[key] = sol
                if not ok:
                    self.uncertified.add(key)
        return [np.array([self.cold[self._key(spec, x, d)] for d in designs]) for x in xs]

    def one(self, spec, x, designs) -> np.ndarray:
        return self.keypoints(spec, [x], designs)[0]

    def solution(self, spec, x, design):
        """The equilibrium behind ``one(spec, x, [design])``."""
        self.keypoints(spec, [x], [design])
        return self.solutions[self._key(spec, x, design)]

    def perturbed(self, spec, centre, xs, designs) -> list[np.ndarray]:
        """Keypoints at ``xs`` (near ``centre``), warm-started from the centre's equilibria."""
        self.keypoints(spec, [centre], designs)
        ckey = np.asarray(centre, dtype=float).tobytes()
        todo, items = {}, []
        for x in xs:
            material, active = spec.decode(x)
            for design in designs:
                key = (ckey,) + self._key(spec, x, design)
                if key not in self.warm and key not in todo:
                    todo[key] = len(items)
                    warm = self.solutions[self._key(spec, centre, design)]
                    items.append((float(design[0]), float(design[1]), material, active, warm))
        for key, (kp, *_) in zip(todo, self._run(items)):
            self.warm[key] = kp
        return [np.array([self.warm[(ckey,) + self._key(spec, x, d)] for d in designs])
                for x in xs]

    def from_states(self, spec, x, designs, states) -> np.ndarray:
        """(n, 5) keypoints of ``spec`` at ``x``, each design warm-started from the matching
        equilibrium of ``states`` (another model's, typically): where this model has an
        equilibrium near that state, it is the one found (not cached)."""
        material, active = spec.decode(x)
        items = [(float(d[0]), float(d[1]), material, active, st) for d, st in zip(designs, states)]
        return np.array([kp for kp, *_ in self._run(items)])

    def continued(self, spec, path, designs) -> list[tuple[np.ndarray, list]]:
        """[(keypoints (n, 5), solutions)] along ``path`` (a sequence of x): each design starts
        from its equilibrium at ``path[0]`` (``solution``) and is warm-started at every next
        point from its equilibrium at the previous one (a natural continuation; not cached)."""
        states = [self.solution(spec, path[0], d) for d in designs]
        out = [(self.one(spec, path[0], designs), list(states))]
        for x in path[1:]:
            material, active = spec.decode(x)
            items = [(float(d[0]), float(d[1]), material, active, s, True)
                     for d, s in zip(designs, states)]
            res = self._run(items)
            states = [r[2] for r in res]
            out.append((np.array([r[0] for r in res]), list(states)))
        return out

    def to_mm(self, designs, keypoints) -> np.ndarray:
        """``keypoints`` of ``designs`` as this evaluator returns them, in mm: unchanged
        (``relative_noise.ScaledEvaluator`` returns size-scaled ones)."""
        return np.asarray(keypoints, dtype=float)

    def n_uncertified(self, spec, x, designs) -> int:
        return sum(self._key(spec, x, d) in self.uncertified for d in designs)
