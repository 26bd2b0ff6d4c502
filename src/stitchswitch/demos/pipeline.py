"""Run a demo end to end into one output directory.

Steps (each printed with its time; step 1 also prints the demo's notes): 1 inverse design and
placement (the demo's ``build``), 2 constraint check, 3 3D preview, 4 hoop grouping and JEF
export (``layout.fabrication.fabricate``), 5 the one-page HTML summary. The directory is built
next to its target and renamed into place at the end (``files.outdir.building``): on any error
nothing is left behind.
Files hold no timestamps or timings, so a rerun gives identical files.

Output directory::

    design.json          the design (docs/design-file.md)
    check.json           the constraint check (docs/design-file.md, "Constraint check")
    preview.png          3D preview of the garment piece, popped patches coloured by height
    patch.png            the first patch's profile with its keypoints and dimensions
    preview.vtu          the preview surface (open in ParaView)
    fabrication/         one JEF per hooping, layouts, fabrication sheet (docs/fabrication.md)
    summary.html         one self-contained page with all of the above
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path

from stitchswitch.files.atomic import atomic_write_text
from stitchswitch.layout.garment.design_io import load_design, save_design

STEPS = ("inverse design and placement", "constraint check", "3D preview",
         "hoop grouping and JEF export", "summary")


@dataclass(frozen=True)
class DemoRun:
    outdir: str
    files: tuple[str, ...]
    hoopings: int
    violations: int
    elapsed_s: float


def run_demo(demo, outdir, *, force: bool = False, echo=print, time_limit_s: float = 10.0) -> DemoRun:
    from stitchswitch.files.outdir import building

    t_start = time.perf_counter()
    with building(outdir, force) as tmp:
        timer = _Timer(echo)
        with timer(1):
            built = demo.build()
            for note in built.notes:
                echo(f"      {note}")
            save_design(built.design, tmp / "design.json")
            design = load_design(tmp / "design.json")      # as a user's file: named, hashed
        with timer(2):
            from stitchswitch.layout.check.report import check_report

            report = check_report(design)
            violations = report.violations
            atomic_write_text(tmp / "check.json", _json(report.as_dict()))
        with timer(3):
            _preview(design, tmp, demo.preview_view)
        with timer(4):
            fab = _fabricate(design, tmp / "fabrication", time_limit_s)
        with timer(5):
            from stitchswitch.demos.summary import summary_html

            page = summary_html(demo, built, violations, fab.doc, tmp)
            atomic_write_text(tmp / "summary.html", page)
        files = tuple(sorted(str(p.relative_to(tmp)) for p in tmp.rglob("*") if p.is_file()))
    return DemoRun(str(outdir), files, len(fab.doc.hoopings), len(violations),
                   time.perf_counter() - t_start)


class _Timer:
    def __init__(self, echo):
        self.echo = echo

    def __call__(self, k: int):
        return _Step(self.echo, k)


class _Step:
    def __init__(self, echo, k):
        self.echo, self.k = echo, k

    def __enter__(self):
        self.t = time.perf_counter()
        self.echo(f"[{self.k}/{len(STEPS)}] {STEPS[self.k - 1]} ...")

    def __exit__(self, kind, value, tb):
        if kind is None:
            self.echo(f"      done in {time.perf_counter() - self.t:.1f} s")
        return False


def _json(obj) -> str:
    return json.dumps(obj, indent=2, allow_nan=False) + "\n"


def _preview(design, tmp: Path, view: str) -> None:
    from stitchswitch.preview3d.mesh_io import write_scene_mesh
    from stitchswitch.preview3d.profiles import single_profile
    from stitchswitch.preview3d.render import RenderOptions, render_to_png
    from stitchswitch.preview3d.scene import build_scene
    from stitchswitch.preview3d.single import write_figure
    from stitchswitch.preview3d.spec import spec_from_design

    scene = build_scene(spec_from_design(design))
    render_to_png(tmp / "preview.png", scene, RenderOptions(view=view, size=(1000, 700)))
    write_scene_mesh(tmp / "preview.vtu", scene)
    first = design.patches[0]
    material = design.material_object()
    write_figure(tmp / "patch.png", single_profile(first.diameter_mm, first.fill, material),
                 state=first.state, eta=material.eta)


def _fabricate(design, outdir: Path, time_limit_s: float):
    from stitchswitch.layout.fabrication.fabricate import FabricateOptions, fabricate

    return fabricate(design, outdir, FabricateOptions(fmt="jef", time_limit_s=time_limit_s))

