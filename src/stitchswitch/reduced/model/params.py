"""Typed, frozen, validated parameter objects of the reduced model.

``Material`` holds the seven coefficients of the paper (Eqs. 3-5), the hardening limit, the
compressive response, the discretization constants and a numerical floor. The coefficients are
dimensionless: the energy is written with lengths in units of the node spacing dR (see
``docs/model.md``); the bending weights are those at the spacing ``dr_max_mm`` and the
hardening limit ``gamma_mm`` is a length, both converted to the design's spacing by
``discretization.make_grid``.

``Patch`` is one design: its diameter on the pre-stretched fabric (mm) and its fill fraction.
"""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, fields

from stitchswitch.errors import InvalidInputError
from stitchswitch.files.shown import clip

#: The solvers of ``reduced.solvers.solve`` (here, so that the CLI can list them without loading them).
SOLVERS = ("newton", "adam")

#: Longest ``Material.label``.
MAX_LABEL = 300

#: Supported patch diameters, measured on the pre-stretched fabric (mm).
DIAMETER_RANGE_MM = (10.0, 150.0)


def _shown(value) -> str:
    """A bad value as a message shows it: its repr, shortened (a huge number or a long text)."""
    try:
        text = repr(value)
    except ValueError:                    # an int too long for repr
        return f"an integer of more than {sys.get_int_max_str_digits()} digits"
    return clip(text)


def _finite(name: str, value: float) -> float:
    if isinstance(value, bool):
        raise InvalidInputError(f"{name}: {_shown(value)} is not a number")
    try:
        v = float(value)
    except (TypeError, ValueError, OverflowError):
        raise InvalidInputError(f"{name}: {_shown(value)} is not a number") from None
    if not math.isfinite(v):
        raise InvalidInputError(f"{name}: {_shown(value)} is not a finite number")
    return v


def _integer(name: str, value) -> int:
    if isinstance(value, bool) or not isinstance(value, int) and not (
            isinstance(value, float) and value.is_integer()):
        raise InvalidInputError(f"{name}: {_shown(value)} is not an integer")
    return int(value)


@dataclass(frozen=True)
class Patch:
    """One circular patch: ``diameter_mm`` on the pre-stretched fabric, ``fill`` in (0, 1]."""

    diameter_mm: float
    fill: float

    def __post_init__(self) -> None:
        d = _finite("diameter_mm", self.diameter_mm)
        p = _finite("fill", self.fill)
        lo, hi = DIAMETER_RANGE_MM
        if d <= 0:
            raise InvalidInputError(f"diameter_mm: {self.diameter_mm!r} must be > 0")
        if not lo <= d <= hi:
            raise InvalidInputError(
                f"diameter_mm: {self.diameter_mm!r} is outside the supported range [{lo:g}, {hi:g}] mm")
        if not 0.0 < p <= 1.0:
            raise InvalidInputError(f"fill: {self.fill!r} is outside (0, 1]")
        object.__setattr__(self, "diameter_mm", d)
        object.__setattr__(self, "fill", p)


@dataclass(frozen=True)
class Material:
    """Material and discretization of the reduced model.

    Calibrated coefficients (paper, section 4, "Calibration procedure"), all dimensionless:
    ``w_b_emb, w_b_fab`` bending weights (Eq. 4), ``k_r_emb, k_r_fab`` radial and
    ``k_theta_emb, k_theta_fab`` circumferential membrane stiffnesses (Eq. 3), ``w_log`` the
    weight of the hardening term (Eq. 5, with the sign corrected, see ``terms/hardening.py``).

    Compressive response (``terms/compression.py``, docs/model.md "Compression as physics"):
    ``c_emb`` and ``c_fab`` are the ratios of compressive to tensile radial stiffness of the
    stitched mats and of the bare knit (mixed by fill like the other coefficients; the bare knit
    wrinkles, so c_fab is small), ``jam`` the stretch l / lambda at which the knit's loops jam,
    ``c_jam`` the jammed knit's compressive stiffness as a ratio of its tensile one, and
    ``compression_floor`` a purely numerical weight added to c that keeps the energy defined
    where c = 0 (the keypoints converge as it goes to 0; tested).

    ``gamma_mm``: limit of the circumferential strain (Eq. 2, a length), where the fabric
    hardens; calibrated. ``eta``: pre-stretch in the hoop. ``n_nodes``: N. ``dr_max_mm``: largest
    node spacing. ``domain_max_rb``: the fabric domain (N - 1) dR extends at most this many patch
    radii R_b; a small patch gets a finer spacing instead of a larger domain, i.e.
    N_in >= (N - 1) / domain_max_rb (``discretization.n_inside``; docs/design-map.md).
    ``label``: what the material is (where its values come from), free text kept in the file.
    """

    w_b_emb: float
    w_b_fab: float
    k_r_emb: float
    k_r_fab: float
    k_theta_emb: float
    k_theta_fab: float
    w_log: float
    c_emb: float = 1e-2
    c_fab: float = 1e-2
    jam: float = 0.5
    c_jam: float = 1.0
    gamma_mm: float = 3.0
    eta: float = 1.7
    n_nodes: int = 300
    dr_max_mm: float = 0.5
    compression_floor: float = 1e-6
    domain_max_rb: float = 7.5
    label: str = ""

    def __post_init__(self) -> None:
        for f in fields(self):
            if f.name in ("n_nodes", "label"):
                continue
            object.__setattr__(self, f.name, _finite(f.name, getattr(self, f.name)))
        for name in ("w_b_emb", "w_b_fab", "k_r_emb", "k_r_fab", "k_theta_emb", "k_theta_fab"):
            if getattr(self, name) <= 0:
                raise InvalidInputError(f"{name}: {getattr(self, name)!r} must be > 0")
        if self.w_log < 0:
            raise InvalidInputError(f"w_log: {self.w_log!r} must be >= 0")
        if self.gamma_mm <= 0:
            raise InvalidInputError(f"gamma_mm: {self.gamma_mm!r} must be > 0")
        if not 1.0 < self.eta <= 3.0:
            raise InvalidInputError(f"eta: {self.eta!r} is outside (1, 3]")
        if self.dr_max_mm <= 0:
            raise InvalidInputError(f"dr_max_mm: {self.dr_max_mm!r} must be > 0")
        for name in ("c_emb", "c_fab"):
            if not 0.0 <= getattr(self, name) < 1.0:
                raise InvalidInputError(f"{name}: {getattr(self, name)!r} is outside [0, 1)")
        if not 0.0 <= self.jam < 1.0:
            raise InvalidInputError(f"jam: {self.jam!r} is outside [0, 1)")
        if not 0.0 < self.compression_floor < 1.0:
            raise InvalidInputError(f"compression_floor: {self.compression_floor!r} is outside (0, 1)")
        if not 0.0 <= self.c_jam <= 100.0:
            raise InvalidInputError(f"c_jam: {self.c_jam!r} is outside [0, 100]")
        if (self.jam == 0.0 or self.c_jam == 0.0) and self.c_fab == 0.0:
            raise InvalidInputError(f"jam: {self.jam!r} with c_jam {self.c_jam!r} and c_fab 0 lets a bare "
                                    "segment collapse (no minimizer); give jam and c_jam > 0 or c_fab > 0")
        if not isinstance(self.label, str) or len(self.label) > MAX_LABEL or not self.label.isprintable():
            raise InvalidInputError(f"label: must be printable text of at most {MAX_LABEL} characters")
        n = _integer("n_nodes", self.n_nodes)
        if not 20 <= n <= 20000:
            raise InvalidInputError(f"n_nodes: {_shown(n)} is outside [20, 20000]")
        object.__setattr__(self, "n_nodes", n)
        if not 2.0 <= self.domain_max_rb <= 1000.0:
            raise InvalidInputError(f"domain_max_rb: {self.domain_max_rb!r} is outside [2, 1000]")

    def replace(self, **changes) -> "Material":
        """A copy with some fields changed (validated again)."""
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        unknown = set(changes) - set(values)
        if unknown:
            raise InvalidInputError(f"unknown material field(s): {', '.join(sorted(unknown))}")
        values.update(changes)
        return Material(**values)

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


#: Default material: the PAPER-MAGNITUDE fit (scripts/fit_default_material.py,
#: ``reduced.calibration.magnitudes``) to the mean keypoints the paper's Table 1 implies and to
#: its qualitative findings; NOT fitted to fabricated samples. See docs/model.md.
DEFAULT_MATERIAL = Material(
    w_b_emb=2.692647593449125,
    w_b_fab=1.4845294350780582,
    k_r_emb=0.32145883141682646,
    k_r_fab=0.12165910595471167,
    k_theta_emb=0.8668297055569069,
    k_theta_fab=0.5,
    w_log=0.760060215739572,
    c_emb=0.0032719193810795285,
    c_fab=0.00527687672883796,
    jam=0.23183198195438287,
    gamma_mm=7.68956875517933,
    label=(
        "paper-magnitude default: fitted by stitchswitch's calibration "
        "(scripts/fit_default_material.py) to the mean keypoints implied by the paper's "
        'Table 1 over its 25 calibration designs (h 9.8, r_a 19.3, z_a 5.3, r_b 17.2, z_b '
        '4.1 mm) and to its qualitative findings; NOT fitted to fabricated samples'
    ),
)
