"""The constraint panel: the same library check the CLI's ``stitchswitch check`` runs
(``layout.check.constraints.check_design``), as rows for the panel and per-patch status."""
from __future__ import annotations

from stitchswitch.layout.check.constraints import CheckLimits, check_design


def run_check(design, limits: CheckLimits | None = None) -> list:
    """The violations of ``design`` (``layout.check.violation.Violation``) under ``limits``
    (default: the CLI's defaults)."""
    return list(check_design(design, limits or CheckLimits()))


def rows(violations) -> list[dict]:
    """One dict per violation for the panel (rule, severity, patches, message)."""
    return [{"index": k, "rule": v.rule, "severity": v.severity, "patches": list(v.patches),
             "pieces": list(v.pieces), "message": v.message} for k, v in enumerate(violations)]


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
