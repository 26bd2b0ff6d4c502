"""The constraint panel: the same library check the CLI's ``stitchswitch check`` runs
(``layout.check.constraints``: its ``RULES`` with the CLI's default ``CheckLimits``), as rows for
the panel and per-patch status.

``LiveCheck`` runs it incrementally. Every rule but ``spacing`` judges each patch on its own
(the patch, its piece, the machine, the blank margin, the material and the limits decide its
verdict), so its violations for an unchanged patch are kept from the previous run and the
rule runs again only on the patches an edit changed (on a design holding just that patch);
``spacing`` compares patches pairwise and runs on the whole design every time. The result is
the list ``check_design`` returns, in its order (rule by rule, patches in design order);
tests/test_studio_scene.py checks that on edit sequences.

Beside the violations, ``LiveCheck.small`` holds the small-pieces warnings ``stitchswitch check``
prints (``layout.check.small_pieces.small_piece_warnings``: a patch's count depends on the
patch alone), kept per patch the same way.
"""
from __future__ import annotations

from stitchswitch.layout.check.constraints import RULES, CheckLimits, check_design
from stitchswitch.layout.check.small_pieces import small_piece_warnings

#: rules whose verdict on a patch depends on other patches: always run on the whole design
PAIRWISE = ("spacing",)


def _name(rule) -> str:
    return rule.__name__.rsplit(".", 1)[-1]


#: the per-patch verdict's entry for the small-pieces warnings (not a rule's name)
SMALL = "small pieces"
#: per-patch verdicts kept between runs (those of the last run are always kept)
CACHE_SIZE = 4096


def run_check(design, limits: CheckLimits | None = None) -> list:
    """The violations of ``design`` (``layout.check.violation.Violation``) under ``limits``
    (default: the CLI's defaults), from scratch."""
    return list(check_design(design, limits or CheckLimits()))


def _array_key(a):
    return None if a is None else (a.shape, a.tobytes())


def _patch_key(p) -> tuple:
    return (p.id, p.piece, p.centre_mm, p.diameter_mm, p.fill, p.composite,
            _array_key(p.outline_mm), p.conductive, p.threads, p.state)


def _context_key(design, limits) -> tuple:
    pieces = tuple((pc.name, pc.size, _array_key(pc.outline_mm)) for pc in design.pieces)
    return (pieces, design.material, design.machine, design.blank_margin_mm, design.path,
            limits)


class LiveCheck:
    """``run(design)``: the check of a validated design (``StudioState`` keeps it validated),
    rerunning the per-patch rules only on changed patches. ``rechecked`` is how many patches
    the last run judged afresh; ``small`` the last run's small-pieces warnings, in design
    order."""

    def __init__(self, limits: CheckLimits | None = None):
        self.limits = limits or CheckLimits()
        self._context = None
        self._verdicts: dict = {}
        self.rechecked = 0
        self.small: list = []

    def run(self, design) -> list:
        context = _context_key(design, self.limits)
        if context != self._context:
            self._context, self._verdicts = context, {}
        eta = design.material_object().eta
        keys = [_patch_key(p) for p in design.patches]
        fresh = [p for p, k in zip(design.patches, keys) if k not in self._verdicts]
        for p, k in zip(design.patches, keys):
            if k not in self._verdicts:
                alone = design.with_patches([p])
                self._verdicts[k] = {_name(rule): rule.check(alone, self.limits, eta)
                                     for rule in RULES if _name(rule) not in PAIRWISE}
                self._verdicts[k][SMALL] = small_piece_warnings(alone, self.limits)
        self.rechecked = len(fresh)
        out: list = []
        for rule in RULES:
            if _name(rule) in PAIRWISE:
                out.extend(rule.check(design, self.limits, eta))
            else:
                for k in keys:
                    out.extend(self._verdicts[k][_name(rule)])
        self.small = [w for k in keys for w in self._verdicts[k][SMALL]]
        if len(self._verdicts) > CACHE_SIZE:
            self._verdicts = {k: self._verdicts[k] for k in keys}
        return out


def rows(violations) -> list[dict]:
    """One dict per violation for the panel (rule, severity, patches, message)."""
    return [{"index": k, "rule": v.rule, "severity": v.severity, "patches": list(v.patches),
             "pieces": list(v.pieces), "message": v.message} for k, v in enumerate(violations)]


def small_rows(small) -> list[str]:
    """The panel's lines for the small-pieces warnings, worded as ``stitchswitch check``."""
    return [w.line for w in small]


def patch_status(violations) -> dict:
    """{patch id: "error" | "warning"} of the worst violation naming each patch."""
    out: dict[str, str] = {}
    for v in violations:
        for pid in v.patches:
            if out.get(pid) != "error":
                out[pid] = "error" if v.severity == "error" else "warning"
    return out


def errors(violations) -> int:
    return sum(1 for v in violations if v.severity == "error")
