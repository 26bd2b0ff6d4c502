"""Write a SYNTHETIC measured-data CSV with one hidden effect, for the discovery workflow.

Nothing in it is measured. The keypoints come from the reduced model with ``TRUE_MATERIAL``
(the synthetic reference dataset's true coefficients, without hardening) plus one hidden source,
plus Gaussian noise with the reference dataset's sigma, on the paper's 25 train + 28 validation
designs (``stitchswitch.validation.discovery.synthetic`` documents every choice). The file's
``# source:`` line says SYNTHETIC and names no effect; the truth is on a separate
``# hidden truth`` comment line, which the loader and the workflow do not read.

    python scripts/make_discovery_dataset.py OUT.csv --source tension_asymmetry [--values -0.05]
        [--seed 7] [--noise-free]

``--source``: a library effect (``stitchswitch.validation.discovery.effects``), ``gravity_sag`` (a control
effect that is not in the library), ``fem_shell`` (the finite-element shell reference with hoop
bending and Poisson coupling) or ``none``. Without ``--values`` the strength is drawn from the
effect's documented hidden range with the same seed. Same arguments, same bytes (the file is
written atomically).
"""
from __future__ import annotations

import argparse

import numpy as np

from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.validation.discovery.synthetic import dataset_text, draw_values


def build(source: str, values=None, seed: int = 7, noise: bool = True) -> str:
    src = None if source == "none" else source
    if src not in (None, "fem_shell") and not values:
        # a separate stream, so the drawn strength does not shift the dataset's own draws
        values = draw_values(src, np.random.default_rng([seed, 1]))
    return dataset_text(src, tuple(values or ()), seed=seed, noise=noise)


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--source", required=True)
    ap.add_argument("--values", type=float, nargs="*", default=None)
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--noise-free", action="store_true")
    args = ap.parse_args(argv)
    atomic_write_text(args.out, build(args.source, args.values, args.seed, not args.noise_free))


if __name__ == "__main__":
    main()
