"""The model-error table as text (``stitchswitch fem-check`` and docs/fem-reference.md)."""
from __future__ import annotations

from stitchswitch.fem_reference.model_error.budget import BUDGET, KEYS
from stitchswitch.fem_reference.model_error.table import ModelErrorTable
from stitchswitch.fem_reference.revolution.params import SWITCHES

SHORT = {"hoop_bending": "hoop", "poisson": "nu", "relaxed_membrane": "relax",
         "natural_curvature": "k0"}


def table_text(result: ModelErrorTable) -> str:
    head = (f"{'d_mm':>5} {'fill':>4} {'key':>4} {'shell':>7} {'reduced':>7} {'gap':>7} {'gap%':>7} | "
            + " ".join(f"{SHORT[s]:>6}" for s in SWITCHES) + f" {'rest':>6} {'inter':>6} | budget")
    lines = [head]
    for r in result.rows:
        for k in KEYS:
            ref = r.shell.keypoints_mm[k]
            gap = r.gap_mm(k)
            pct = f"{100 * gap / ref:+6.1f}%" if abs(ref) > 1e-3 else f"{'-':>7}"
            attr = " ".join(f"{r.attribution_mm(s, k):+6.2f}" for s in SWITCHES)
            ok = "ok" if r.within_budget(k) else "OVER"
            lines.append(f"{r.diameter_mm:5g} {r.fill:4g} {k[:-3]:>4} {ref:7.2f} {r.reduced_mm[k]:7.2f} "
                         f"{gap:+7.2f} {pct} | {attr} {r.remainder_mm(k):+6.2f} "
                         f"{r.interaction_mm(k):+6.2f} | {ok}")
        if not r.certified:
            lines.append(f"      d {r.diameter_mm:g}, p {r.fill:g}: a solve is not certified "
                         "(not converged or not a strict minimum)")
    p = result.params
    lines.append("mm; gap = reduced (N = 300) - shell; switch columns: the shell's keypoint with "
                 "that physics off minus with it on; rest = reduced - shell with all four off; "
                 "inter = gap - rest - switches (interaction)")
    lines.append(f"shell: nu {p.nu:g}, kappa0 {p.kappa0_per_mm:g} /mm, "
                 f"{'thickness ' + format(p.thickness_mm, 'g') + ' mm' if p.thickness_mm else 'bending from w_b'}, "
                 f"{p.elements_inside} elements on the patch")
    for k in KEYS:
        lim = BUDGET[k]
        worst = max(abs(r.gap_mm(k)) for r in result.rows)
        lines.append(f"{'PASS' if result.passed(k) else 'FAIL'}  {k[:-3]:>4} within "
                     f"{100 * lim.rel:.1f} % or {lim.abs_mm:.2f} mm on every design "
                     f"(largest gap {worst:.2f} mm)")
    return "\n".join(lines)
