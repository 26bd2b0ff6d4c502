"""SYNTHETIC datasets with a hidden effect, for proving the discovery workflow (and its demo).

Nothing here is measured. A dataset follows the paper's design (25 training patches at
p in {0.6, 0.7, 0.8, 0.9, 1.0} x d in {20, 40, 60, 70, 90} mm, 28 validation patches at random
d in [15, 100] mm and p in [0.6, 1.0]); its keypoints are certified solves of a "true" model,
plus Gaussian noise with the per-quantity sigma of the synthetic reference dataset
(``scripts/make_measured_dataset.py``: h 2.3, r_a 1.7, z_a 1.6, r_b 1.8, z_b 1.2 mm), clipped
and rounded like it.

The true model is ``TRUE_MATERIAL`` (the default material with the reference datasets' true
factors of the coefficients the fits free, ``validation.reference_truth``, without hardening)
plus at most one hidden *source*:

* a library effect at given values (``validation.discovery.effects``);
* ``gravity_sag``: the control effect that is not in the library (each patch solved without it
  first, then with it from that equilibrium: it pops up, then sags);
* ``fem_shell``: keypoints of the finite-element shell reference with hoop bending and Poisson
  coupling (``fem_reference``), started from the reduced equilibrium;
* None: the starting model's physics only (a null dataset).

The keypoints of a library source (or of None) are solved at the true parameters **as the fit
represents them** (``as_fitted``: the material's free coefficients through the search vector's
log10 and back, the effect's values through its probe scaling), the same cold solve from the
released state that the fit's ``Evaluator`` runs. Solving the truth from the unencoded
material instead differs from it at round-off level, and on designs whose released state is
bistable (a negative ``tension_asymmetry``) that is enough to settle in another equilibrium: the
model could then not reproduce its own data at its own true parameters. ``bistable_designs``
lists the designs whose equilibrium moves by more than ``BISTABLE_MM`` under a round-off
perturbation of the true parameters; the dataset names them on its hidden-truth line.

``unabsorbed(designs, clean, start)``: how much of a hidden effect a recalibration cannot
absorb: the starting model fitted to NOISE-FREE keypoints of the truth as the workflow's step 1
fits it; the RSS it leaves, over the noise variance, is the noncentrality of the F test an
oracle would run (``cv.oracle_power``; the benchmark's detectability and the absorbability
table of docs/discovery.md).

The workflow starts from ``START_MATERIAL`` (the default material without hardening) and is not
told the source: the file's ``# source:`` line says only that the data are synthetic; the truth
is on a separate ``# hidden truth`` comment line, which the loader ignores.
``numpy.random.default_rng(seed)`` draws, in order: validation d, validation p, the noise.
"""
from __future__ import annotations

import numpy as np

from stitchswitch.errors import InvalidInputError
from stitchswitch.reduced.calibration.designs import CALIBRATION_DIAMETERS_MM, CALIBRATION_FILLS
from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material, Patch
from stitchswitch.validation.discovery.effects import LIBRARY, resolve
from stitchswitch.validation.discovery.space import BASE_FREE
from stitchswitch.validation.reference_truth import describe, true_material

__all__ = ["TRUE_MATERIAL", "START_MATERIAL", "SIGMA_MM", "TRAIN_FILL", "TRAIN_D_MM", "N_VAL",
           "SOURCES", "draw_values", "paper_designs", "as_fitted", "true_keypoints",
           "bistable_designs", "BISTABLE_MM", "unabsorbed", "dataset_text"]

TRUE_MATERIAL = true_material(names=BASE_FREE).replace(w_log=0.0)
START_MATERIAL = DEFAULT_MATERIAL.replace(w_log=0.0)
#: Noise of the synthetic reference dataset (scripts/make_measured_dataset.py, SIGMA_MM).
SIGMA_MM = (2.3, 1.7, 1.6, 1.8, 1.2)
TRAIN_FILL, TRAIN_D_MM = CALIBRATION_FILLS, CALIBRATION_DIAMETERS_MM     # the paper's training grid
N_VAL = 28
#: Hidden sources besides the library effects (None: no hidden effect).
SOURCES = ("gravity_sag", "fem_shell")
FEM_POISSON = 0.3
#: A solve whose certificate is at most this but that is not certified (no strict local minimum
#: was shown, or a stiff hardening term stalled Newton at its round-off floor) is accepted for
#: data generation; it equals the solver's default tolerance.
NEAR_CONVERGED = 1e-9
#: A design whose keypoints move by more than this (mm) when the true parameters are perturbed
#: at round-off level (``ROUND_OFF`` in the log10 / probe units of the search vector) has two
#: equilibria within reach of the same cold solve: it is bistable at round-off.
BISTABLE_MM = 0.05
ROUND_OFF = 1e-12


def _source_effect(source: str):
    return resolve(source)


def draw_values(source: str, rng: np.random.Generator) -> tuple:
    """Random values of ``source``'s parameters, uniform in their ``hidden`` ranges (strong
    enough to matter against the noise), rounded to 4 significant digits."""
    return tuple(float(f"{rng.uniform(*p.hidden):.4g}") for p in _source_effect(source).parameters)


def paper_designs(rng: np.random.Generator, n_val: int = N_VAL, train_d=TRAIN_D_MM,
                  train_fill=TRAIN_FILL):
    """(train designs, val designs) [(d, p)] of the paper's layout; draws the val designs."""
    p_tr, d_tr = (a.ravel() for a in np.meshgrid(train_fill, train_d, indexing="ij"))
    d_va = np.round(rng.uniform(15.0, 100.0, n_val), 1)
    p_va = np.round(rng.uniform(0.6, 1.0, n_val), 2)
    return list(zip(d_tr.tolist(), p_tr.tolist())), list(zip(d_va.tolist(), p_va.tolist()))


def _fem(design, material):
    from stitchswitch.fem_reference.shell import ShellModel
    from stitchswitch.reduced.model.keypoints import keypoints_from_profile
    from stitchswitch.reduced.solvers.solve import solve

    patch = Patch(*design)
    start = solve(patch, material)
    model = ShellModel(patch, material, elements_inside=40, growth=1.08, hoop_bending=True,
                       poisson=FEM_POISSON)
    sol = model.solve(model.start_from_profile(start.R_mm, start.r_mm, start.z_mm), max_iter=600)
    kp = keypoints_from_profile(*sol.sample())
    return (kp.h_mm, kp.r_a_mm, kp.z_a_mm, kp.r_b_mm, kp.z_b_mm), bool(sol.converged)


def as_fitted(material: Material, source: str | None, values=(), shift: float = 0.0):
    """(material, active effects) of the truth as the fit represents it: ``ModelSpec.encode``
    then ``decode`` (the free coefficients through log10, the effect values through their
    probe), every search coordinate moved by ``shift`` (0: none)."""
    from stitchswitch.validation.discovery.space import ModelSpec

    spec = ModelSpec(material, source, BASE_FREE)
    x = spec.encode(material, tuple(values)) + shift
    return spec.decode(x)


def _library_items(designs, material, source, values, shift=0.0):
    material, active = as_fitted(material, source, values, shift)
    return [(float(d), float(p), material, active, None) for d, p in designs]


def bistable_designs(designs, source: str | None, values=(), material: Material = TRUE_MATERIAL,
                     executor=None) -> list[tuple[float, float]]:
    """The designs (of a library source or None) whose keypoints move by more than
    ``BISTABLE_MM`` when every coordinate of the true search vector is moved by
    +-``ROUND_OFF``: two equilibria within reach of the same solve."""
    from stitchswitch.validation.discovery.evaluate import solve_item

    mapper = executor.map if executor is not None else (lambda f, it: [f(i) for i in it])
    runs = [np.array([kp for kp, *_ in mapper(solve_item, _library_items(
        designs, material, source, values, shift))]) for shift in (0.0, ROUND_OFF, -ROUND_OFF)]
    moved = np.max(np.abs(np.stack(runs[1:]) - runs[0]), axis=(0, 2))
    return [tuple(map(float, d)) for d, m in zip(designs, moved) if m > BISTABLE_MM]


def true_keypoints(designs, source: str | None = None, values=(), material: Material = TRUE_MATERIAL,
                   executor=None) -> tuple[np.ndarray, int]:
    """(n, 5) noise-free keypoints of the true model and the number of solves that are neither
    certified nor within ``NEAR_CONVERGED`` of it."""
    from stitchswitch.validation.discovery.evaluate import solve_item

    mapper = executor.map if executor is not None else (lambda f, it: [f(i) for i in it])
    if source == "fem_shell":
        out = mapper(_fem_item, [(tuple(map(float, d)), material) for d in designs])
    elif source == "gravity_sag":
        out = mapper(_sag_item, [(float(d), float(p), material, tuple(values)) for d, p in designs])
    else:
        items = _library_items(designs, material, source, values)
        out = [(kp, ok or res <= NEAR_CONVERGED) for kp, ok, _, res in mapper(solve_item, items)]
    return np.array([kp for kp, _ in out], dtype=float), sum(not ok for _, ok in out)


def _fem_item(item):
    return _fem(*item)


def _sag_item(item):
    """Pop up without gravity, then add it from that equilibrium (see ``gravity_sag``)."""
    from stitchswitch.reduced.solvers.solve import solve
    from stitchswitch.validation.discovery.evaluate import solve_item

    d, p, material, values = item
    popped = solve(Patch(d, p), material)
    kp, ok, _, res = solve_item((d, p, material, {"gravity_sag": values}, popped))
    return kp, ok or res <= NEAR_CONVERGED


def unabsorbed(designs, clean, start, *, config=None) -> dict:
    """{"rss_clean_mm2", "mse_clean_mm2", "solves"} of the starting model fitted to ``clean``
    (n, 5) at ``designs`` from the material ``start``, with ``config``'s (a ``DiscoveryConfig``)
    screening resolution and step budgets."""
    from stitchswitch.validation.discovery.evaluate import Evaluator
    from stitchswitch.validation.discovery.fit import fit
    from stitchswitch.validation.discovery.space import BASE_FREE, ModelSpec
    from stitchswitch.validation.discovery.workflow import DiscoveryConfig, screen_spec

    config = config or DiscoveryConfig()
    y = np.asarray(clean, dtype=float)
    ev = Evaluator()
    base = ModelSpec(start, None, BASE_FREE)
    screen = screen_spec(start, config.screen_nodes)
    fs = fit(screen, ev, designs, y, screen.encode(screen.start), max_nfev=config.fit_max_nfev)
    fb = fit(base, ev, designs, y, fs.x, max_nfev=config.polish_max_nfev) if screen != base else fs
    rss = float(np.sum((fb.predictions - y) ** 2))
    return {"rss_clean_mm2": rss, "mse_clean_mm2": rss / y.size, "solves": ev.calls}


def dataset_text(source: str | None, values=(), *, seed: int, noise: bool = True,
                 n_val: int = N_VAL, train_d=TRAIN_D_MM, train_fill=TRAIN_FILL,
                 material: Material = TRUE_MATERIAL, sigma_mm=SIGMA_MM, executor=None) -> str:
    """The CSV text (measured-data format, ``validation.measured``) of one synthetic dataset.
    The keyword arguments shrink it for tests (fewer designs, a coarser material, less noise)."""
    if source is not None and source not in LIBRARY and source not in SOURCES:
        raise InvalidInputError(f"source: {source!r} is not a library effect, "
                                f"{', '.join(SOURCES)} or none")
    if source not in (None, "fem_shell"):
        values = _source_effect(source).values(values)
    rng = np.random.default_rng(seed)
    train, val = paper_designs(rng, n_val, train_d, train_fill)
    kp, bad = true_keypoints(train + val, source, values, material, executor)
    if bad:
        raise InvalidInputError(f"{bad} synthetic design(s) of source {source!r} did not solve "
                                "to a certified minimum")
    sigma_mm = tuple(float(v) for v in sigma_mm)
    eps = rng.normal(0.0, 1.0, kp.shape) * np.array(sigma_mm)
    if noise:
        kp = kp + eps
    kp[:, [0, 2, 4]] = np.maximum(kp[:, [0, 2, 4]], 0.0)
    kp[:, [1, 3]] = np.maximum(kp[:, [1, 3]], 0.1)
    kp = np.round(kp, 2) + 0.0          # no negative zeros
    noise_text = ("noise sigma " + ", ".join(f"{q} {s:g}" for q, s in
                                             zip(("h", "r_a", "z_a", "r_b", "z_b"), sigma_mm))
                  + " mm") if noise else "NO noise"
    if source is None:
        truth = "none (the starting model's physics)"
    elif source == "fem_shell":
        truth = f"fem_shell (shell reference, hoop bending on, Poisson {FEM_POISSON:g})"
    else:
        names = [p.name for p in _source_effect(source).parameters]
        truth = source + " " + ", ".join(f"{n}={v:g}" for n, v in zip(names, values))
    if source not in SOURCES:
        flip = bistable_designs(train + val, source, values, material, executor)
        truth += (f"; {len(flip)} design(s) bistable at round-off: "
                  + " ".join(f"({d:g}, {p:g})" for d, p in flip)) if flip else ""
    if material != TRUE_MATERIAL:
        truth += "; material changed: " + ", ".join(
            f"{k}={v:g}" for k, v in material.as_dict().items()
            if k != "label" and v != getattr(TRUE_MATERIAL, k))
    lines = [
        f"# source: SYNTHETIC discovery dataset (scripts/make_discovery_dataset.py, seed {seed}, "
        f"model with one hidden source, {noise_text}); NOT measured",
        f"# hidden truth (not read by the workflow): {truth}; base material = default with "
        f"{describe(TRUE_MATERIAL)}",
        "sample_id,d_mm,fill,h_mm,r_a_mm,z_a_mm,r_b_mm,z_b_mm,split",
    ]
    n_tr = len(train)
    for k, (d, p) in enumerate(train + val):
        split = "train" if k < n_tr else "val"
        sid = f"{split[0]}{(k if k < n_tr else k - n_tr) + 1:02d}"
        lines.append(f"{sid},{d:g},{p:g}," + ",".join(f"{v:.2f}" for v in kp[k]) + f",{split}")
    return "\n".join(lines) + "\n"
