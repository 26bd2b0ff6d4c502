"""The inverse-design panel: candidates for a target height (and r_a) from
``reduced.design_space.inverse.inverse_design``, each with its feasibility under the check
rules when applied to the selected patch, and applying one.
"""
from __future__ import annotations

from dataclasses import dataclass

from stitchswitch.layout.check.constraints import check_design
from stitchswitch.reduced.design_space.inverse import InverseTarget, inverse_design


@dataclass(frozen=True)
class PanelCandidate:
    candidate: object           # inverse.Candidate
    check_errors: int | None    # errors naming the selected patch with this design (None: no patch)

    def as_dict(self) -> dict:
        c = self.candidate
        return {"d_mm": round(c.diameter_mm, 3), "fill": round(c.fill, 4), "h_mm": round(c.h_mm, 3),
                "r_a_mm": round(c.r_a_mm, 3), "force_N": round(c.force_N, 3),
                "check_errors": self.check_errors,
                "feasible": self.check_errors is None or self.check_errors == 0}


def candidates(target: InverseTarget, dmap, state) -> list[PanelCandidate]:
    """The inverse candidates for ``target``, best first, each checked on the selected patch."""
    result = inverse_design(target, dmap)
    patch = state.selected_patch()
    out = []
    for c in result.candidates:
        n = None
        if patch is not None:
            trial = patch.replace(diameter_mm=round(c.diameter_mm, 6), fill=round(c.fill, 6))
            design = state.design.with_patches([trial if p.id == patch.id else p
                                                for p in state.design.patches])
            n = sum(1 for v in check_design(design) if v.severity == "error" and patch.id in v.patches)
        out.append(PanelCandidate(c, n))
    return out


def apply(state, candidate, centre_mm=None) -> str:
    """Give the selected patch the candidate's design, or, with ``centre_mm``, place a new patch
    with it there. Returns the patch id."""
    d, p = round(candidate.diameter_mm, 6), round(candidate.fill, 6)
    if centre_mm is not None or state.selected is None:
        if centre_mm is None:
            raise ValueError("no patch selected and no place given")
        return state.add_patch(centre_mm, d, p)
    state.edit_patch(state.selected, own_step=True, diameter_mm=d, fill=p)
    return state.selected
