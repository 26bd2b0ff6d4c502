"""Which buttons stay switched and which spring back: the shell's bistability verdict for the
button designs of a demo (``fem_reference.snap.bistability``; docs/fem-reference.md, "Bistable
or spring-back").

The paper (section 7) makes spring-back buttons by sewing with unbalanced top and bobbin thread
tension, which curves the embroidered layer and biases the patch to one state; with balanced
tension the patch is bistable. In the shell of revolution that bias is the natural curvature
kappa_0 of the embroidered layer. ``settle`` goes through an inverse step's candidates (best
first) and the natural curvatures it may use (smallest first) and takes the first design whose
verdict is the one wanted. When none is, it keeps the best candidate and reports the verdict the
shell gives, so a demo never claims a behaviour that was not found.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from functools import lru_cache

from stitchswitch.demos.demo import InverseStep

BEHAVIOURS = ("bistable", "spring-back")


@dataclass(frozen=True)
class ButtonBehaviour:
    """The verdict for one tier of buttons. ``verdict`` is the shell's: bistable, spring-back,
    flat or uncertain (a solve not certified); ``candidate`` indexes the inverse step's
    candidates; the apex heights (mm, in the frame of the switching experiment) are the pop-up
    state's and that of its mirror image after relaxing without load."""

    label: str
    wanted: str
    verdict: str
    candidate: int
    diameter_mm: float
    fill: float
    kappa0_per_mm: float
    popup_apex_mm: float
    relaxed_apex_mm: float

    @property
    def ok(self) -> bool:
        return self.verdict == self.wanted

    def note(self) -> str:
        tension = ("balanced thread tension (natural curvature 0)" if self.kappa0_per_mm == 0.0
                   else f"unbalanced thread tension, natural curvature {self.kappa0_per_mm:g} /mm")
        found = (f"the shell finds {self.verdict}" if self.ok
                 else f"wanted {self.wanted}, but the shell finds {self.verdict}")
        return (f"{self.label} (d {self.diameter_mm:g} mm, p {self.fill:g}), {tension}: {found} "
                f"(pop-up apex {self.popup_apex_mm:.2f} mm; its mirror image relaxes to "
                f"{self.relaxed_apex_mm:.2f} mm).")

    def as_dict(self) -> dict:
        return {"label": self.label, "wanted": self.wanted, "verdict": self.verdict,
                "d_mm": self.diameter_mm, "fill": self.fill, "kappa0_per_mm": self.kappa0_per_mm,
                "popup_apex_mm": self.popup_apex_mm, "relaxed_apex_mm": self.relaxed_apex_mm}


@lru_cache(maxsize=64)
def _verdict(diameter_mm: float, fill: float, kappa0_per_mm: float):
    """(verdict, pop-up apex, relaxed mirror apex) of one design; cached, since a demo's
    inverse steps and reruns ask for the same designs."""
    from stitchswitch.fem_reference.revolution.params import ShellParams
    from stitchswitch.fem_reference.snap.regions import cell_verdict
    from stitchswitch.fem_reference.snap.states import bistability
    from stitchswitch.reduced.model.params import DEFAULT_MATERIAL, Patch

    b = bistability(Patch(diameter_mm, fill), DEFAULT_MATERIAL, ShellParams(kappa0_per_mm=kappa0_per_mm))
    return cell_verdict(b), b.popup.apex_mm, b.inverted.apex_mm


def settle(step: InverseStep, wanted: str, kappa0s_per_mm=(0.0,)) -> tuple[InverseStep, ButtonBehaviour]:
    """The step with its chosen design replaced by the first candidate whose verdict is
    ``wanted`` (at the first natural curvature of ``kappa0s_per_mm`` that gives it), and that
    design's behaviour; the step unchanged and the best candidate's verdict at the first
    curvature when no candidate is ``wanted``."""
    if wanted not in BEHAVIOURS:
        raise ValueError(f"wanted: {wanted!r} is not one of {', '.join(BEHAVIOURS)}")
    first = None
    for k, cand in enumerate(step.candidates):
        d, p = round(cand["d_mm"], 2), round(cand["fill"], 4)      # as placed in the design
        for kappa0 in kappa0s_per_mm:
            verdict, up, down = _verdict(d, p, float(kappa0))
            b = ButtonBehaviour(step.label, wanted, verdict, k, d, p, float(kappa0), up, down)
            if first is None:
                first = b
            if b.ok:
                return replace(step, chosen=cand), b
    return step, first
