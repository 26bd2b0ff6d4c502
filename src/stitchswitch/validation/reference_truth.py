"""The hidden "true" material of the SYNTHETIC reference datasets.

The shipped measured-keypoint dataset (scripts/make_measured_dataset.py) and the discovery
datasets (``validation.discovery.synthetic``) are generated from the model with a material that
differs from the default, so that a calibration started from the default has something to
find. It is the default material with each parameter of ``TRUE_FACTORS`` multiplied by its
factor. The discovery datasets apply only the factors of the coefficients their fits free
(``validation.discovery.space.BASE_FREE``), without hardening, so that the one hidden effect is
the only thing their model lacks. Nothing here is measured.
"""
from __future__ import annotations

from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Material

__all__ = ["TRUE_FACTORS", "true_material"]

#: Parameter -> factor applied to the default material's value.
TRUE_FACTORS = {"w_b_emb": 1.4, "w_b_fab": 1.25, "k_r_emb": 1.6, "k_r_fab": 1.2, "k_theta_emb": 0.8,
                "w_log": 1.25, "c_emb": 1.5, "c_fab": 0.7, "jam": 1.1, "c_jam": 1.3, "gamma_mm": 1.2}


def true_material(base: Material = DEFAULT_MATERIAL, names=None) -> Material:
    """``base`` with the factors of ``TRUE_FACTORS`` applied (those of ``names`` only, if
    given), labelled as synthetic."""
    changes = {k: f * getattr(base, k) for k, f in TRUE_FACTORS.items() if names is None or k in names}
    return base.replace(**changes, label="SYNTHETIC true material of the reference datasets: the default "
                                         "material times validation.reference_truth.TRUE_FACTORS")


def describe(material: Material) -> str:
    """The changed parameters of ``material`` against the default, as ``name=value`` (4 digits)."""
    return ", ".join(f"{k}={getattr(material, k):.4g}" for k in TRUE_FACTORS
                     if getattr(material, k) != getattr(DEFAULT_MATERIAL, k))
