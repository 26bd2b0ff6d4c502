"""Benchmark: one converged shell-reference solve per design (target: <= 10 s).

Nine designs (d 25, 50, 90 mm x p 0.6, 0.8, 1.0), 80 Hermite elements on the patch, solved two
ways: Newton from the reduced equilibrium (whose time is reported separately), and the prestretch
continuation from the flat sheet (``fem_reference/continuation.py``, independent of the reduced
model). For the continuation the table also gives the largest relative keypoint difference to
the reduced start and the energy difference (negative: the continuation found a lower minimum).

    python benchmarks/bench_fem.py [--elements 80] [--designs D,P;D,P] [--json]
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class Row:
    """One design: the shell solve from the reduced start and by continuation (times in s,
    relative keypoint differences of the continuation against the reduced start)."""

    diameter_mm: float
    fill: float
    fem_s: float
    reduced_s: float
    converged: bool
    iterations: int
    dofs: int
    continuation_s: float
    continuation_converged: bool
    continuation_iterations: int
    continuation_stages: int
    continuation_rejected_stages: int
    continuation_max_rel_keypoint: float
    continuation_h_rel: float
    continuation_energy_diff: float
    continuation_lowest_eigenvalue: float

    def as_dict(self) -> dict:
        """The fields, in order, with the diameter under the output's key ``d_mm``."""
        out = asdict(self)
        return {"d_mm": out.pop("diameter_mm"), **out}


def _designs(text):
    from stitchswitch.fem_reference.check import DEFAULT_DESIGNS

    if not text:
        return DEFAULT_DESIGNS
    return tuple(tuple(float(v) for v in item.split(",")) for item in text.split(";"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, default=80)
    ap.add_argument("--designs", default=None, metavar="D,P;D,P")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    from stitchswitch import Patch, solve
    from stitchswitch.fem_reference.check import KEYS
    from stitchswitch.fem_reference.continuation import prestretch_continuation
    from stitchswitch.fem_reference.shell import ShellModel
    from stitchswitch.reduced.model.keypoints import keypoints_from_profile

    solve(Patch(40, 0.8))
    rows = []
    for d, p in _designs(args.designs):
        patch = Patch(d, p)
        t = time.perf_counter()
        red = solve(patch)
        t_red = time.perf_counter() - t
        t = time.perf_counter()
        model = ShellModel(patch, red.material, elements_inside=args.elements,
                           growth=1.0 + 3.2 / args.elements)
        sol = model.solve(model.start_from_profile(red.R_mm, red.r_mm, red.z_mm), max_iter=300)
        t_fem = time.perf_counter() - t
        t = time.perf_counter()
        cont = prestretch_continuation(model)
        t_cont = time.perf_counter() - t
        kp, kc = keypoints_from_profile(*sol.sample()), keypoints_from_profile(*cont.solution.sample())
        rel = max(abs(getattr(kc, k) - getattr(kp, k)) / abs(getattr(kp, k)) for k in KEYS)
        rows.append(Row(diameter_mm=d, fill=p, fem_s=t_fem, reduced_s=t_red,
                        converged=bool(sol.converged), iterations=int(sol.iterations),
                        dofs=int(2 * model.n), continuation_s=t_cont,
                        continuation_converged=bool(cont.converged),
                        continuation_iterations=int(cont.solution.iterations),
                        continuation_stages=len(cont.stages),
                        continuation_rejected_stages=sum(not s.accepted for s in cont.stages),
                        continuation_max_rel_keypoint=float(rel),
                        continuation_h_rel=float((kc.h_mm - kp.h_mm) / kp.h_mm),
                        continuation_energy_diff=float(cont.solution.energy - sol.energy),
                        continuation_lowest_eigenvalue=cont.lowest_eigenvalue))
    worst = max(r.fem_s for r in rows)
    worst_cont = max(r.continuation_s for r in rows)
    ok = worst <= 10.0 and all(r.converged for r in rows)
    ok_cont = worst_cont <= 10.0 and all(r.continuation_converged for r in rows)
    same = sum(r.continuation_max_rel_keypoint <= 5e-3 for r in rows)
    if args.json:
        print(json.dumps({"rows": [r.as_dict() for r in rows], "worst_s": worst, "target_le_10s": ok,
                          "worst_continuation_s": worst_cont, "continuation_target_le_10s": ok_cont,
                          "continuation_same_equilibrium": same}, indent=1))
    else:
        for r in rows:
            print(f"d {r.diameter_mm:5g} p {r.fill:4g}: from reduced {r.fem_s:.2f} s ({r.iterations} "
                  f"it, {r.dofs} dofs, conv {r.converged}; reduced solve "
                  f"{1e3 * r.reduced_s:.0f} ms) | continuation {r.continuation_s:.2f} s "
                  f"({r.continuation_iterations} it, {r.continuation_stages} stages, "
                  f"{r.continuation_rejected_stages} rejected, conv {r.continuation_converged}; "
                  f"max keypoint diff {100 * r.continuation_max_rel_keypoint:.3f} %, h "
                  f"{100 * r.continuation_h_rel:+.3f} %, dE {r.continuation_energy_diff:+.1e})")
        print(f"worst solve from the reduced start {worst:.2f} s (target <= 10 s)  {'PASS' if ok else 'FAIL'}")
        print(f"worst continuation {worst_cont:.2f} s (target <= 10 s)  {'PASS' if ok_cont else 'FAIL'}; "
              f"same equilibrium (keypoints within 0.5 %) on {same} of {len(rows)} designs")
    return 0 if ok and ok_cont else 1


if __name__ == "__main__":
    sys.exit(main())
