"""Fabrication mode (paper, section 5 and Fig. 11): from a design to a folder of machine files.

``fabricate(design, outdir, options)``:

1. the machine and its hoops from the catalogue (``machines``; the design's ``machine.hoop`` or
   ``options.hoop`` restricts the grouping to one hoop);
2. footprints on the fabric stretched by the material's eta (``hoop_footprints``);
3. hoop grouping, garment or free mode (``hoop_grouping``), then the stitching order
   (``hoop_order``);
4. per hooping: the stitch plan (``hoop_plan``, patch geometry from
   ``patch_design.geometry_for``), the embroidery file through the export registry
   (``export.encode``, with the hooping's hoop for the JEF code) and the layout as PNG and SVG
   (``hoop_layout_plot``); in garment mode the 1:1 templates (PDF, A4 and Letter: ``template``)
   and the same marks as DXF (``marks_dxf``);
5. an overview (PNG, SVG), ``fabrication.json``, and the sheet as ``fabrication.md`` and
   ``fabrication.html`` (``fabrication_sheet``).

Everything is built in memory and written as one directory (``files.outdir``): nothing is
left behind on an error, and a non-empty target is refused unless ``force``. The output holds no
timestamps or timings, so the same input gives byte-identical files (a time limit that stops
HiGHS can make the grouping depend on the machine's speed; the report says when it did).
"""
from __future__ import annotations

import hashlib
import json
from dataclasses import dataclass

import numpy as np

from stitchswitch import __version__
from stitchswitch.errors import InvalidInputError
from stitchswitch.files.outdir import check_outdir, write_outdir
from stitchswitch.layout.embroidery import export
from stitchswitch.layout.embroidery.jef_palette import is_jef, jef_threads
from stitchswitch.layout.embroidery.machines import catalogue
from stitchswitch.layout.embroidery.stitches import StitchParams
from stitchswitch.layout.fabrication.document import (
    Conflict,
    DesignFile,
    FabricationDoc,
    GroupingInfo,
    HoopingDoc,
    HoopingFiles,
    MachineInfo,
    PlacedPatch,
    StretchInfo,
    Thread,
    Totals,
)
from stitchswitch.layout.fabrication.grouping.footprints import stretch
from stitchswitch.layout.fabrication.grouping.group import MODES, group
from stitchswitch.layout.fabrication.grouping.result import Grouping
from stitchswitch.layout.fabrication.hoop_outline import relaxed_outline
from stitchswitch.layout.fabrication.hoop_reason import hoop_reason
from stitchswitch.layout.fabrication.layout_plot import hooping_figure, overview_figure
from stitchswitch.layout.fabrication.marks_dxf import marks_dxf
from stitchswitch.layout.fabrication.order import StitchingOrder, order_hoopings
from stitchswitch.layout.fabrication.plan import audit_hooping, plan_hooping
from stitchswitch.layout.fabrication.sheet import html_page, markdown
from stitchswitch.layout.fabrication.template import PAPERS, template_pdf

GENERATOR = "stitchswitch fabricate"


@dataclass(frozen=True)
class FabricateOptions:
    machine: str | None = None        # default: the design's machine
    machines_file: str | None = None  # the user's catalogue, added to the built-in one
    hoop: str | None = None           # one hoop only (default: the design's, else all)
    fmt: str | None = None            # default: the machine's default format
    mode: str = "garment"
    time_limit_s: float | None = 10.0
    spacing_mm: float = 10.0          # free mode: gap between patches
    resolution_mm: float = 5.0        # triangle side of the patch tessellation
    force: bool = False
    blank_margin_mm: float | None = None  # uncut blank past each piece (default: the design's)


@dataclass(frozen=True, eq=False)
class FabricationResult:
    outdir: str
    grouping: Grouping
    order: StitchingOrder
    files: tuple[str, ...]
    doc: FabricationDoc


def _r(v, digits: int = 3):
    if isinstance(v, (list, tuple, np.ndarray)):
        return tuple(_r(x, digits) for x in v)
    return round(float(v), digits) + 0.0


def _hoops(machine, design, options):
    name = options.hoop or (design.machine.hoop if design.machine.name.lower()
                            == machine.name.lower() else None)
    return (machine.hoop(name),) if name else machine.hoops


def grouping_hoops(design, options: FabricateOptions = FabricateOptions()) -> tuple:
    """The hoops ``fabricate`` groups ``design`` into under ``options``: ``options.hoop``, else
    the design's ``machine.hoop`` when the machine is the design's, else every hoop of the
    machine (``options.machine`` or the design's, from the catalogue)."""
    machine = catalogue(options.machines_file, export.supported_formats()).machine(
        options.machine or design.machine.name)
    return _hoops(machine, design, options)


def _design_info(design) -> DesignFile:
    import os
    if design.path is None:
        return DesignFile("(in memory)", None)
    with open(design.path, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()
    return DesignFile(os.path.basename(design.path), digest)


def _instructions(mode: str, eta: float, blank_mm: float = 0.0) -> list[str]:
    pct = f"{100 * eta:.0f} %"
    common = (f"Place the fabric over one sheet of water-soluble stabilizer and stretch it "
              f"uniformly to {eta:g}x in both directions ({pct} of its relaxed size; paper, "
              "appendix A); a drawn grid and pins keep the stretch even.")
    if mode == "garment":
        blank = ([f"Cut every piece as an uncut blank reaching {blank_mm:g} mm past its outline "
                  "(relaxed fabric) and draw the outline on it: hoop frames may clamp the "
                  "blank outside the outline. Cut the piece out after the last hooping."]
                 if blank_mm > 0 else [])
        return blank + [
            "Before stretching, draw the alignment marks of every hooping on the relaxed piece "
            "at the garment coordinates listed below (the hoop template's centre and side "
            f"marks divided by {eta:g}), and a reference grid.",
            common,
            "Hoop each hooping so that its five marks meet the hoop template's centre and side "
            "marks; a hooping noted 'turned 90 degrees' has the hoop a quarter turn "
            "counter-clockwise on the piece (the hoop's x axis along the piece's y axis).",
            "Stitch the hoopings in the order given (it keeps the frame off stitched patches "
            "where possible); re-stretch and re-mark for every hooping.",
            "Release the fabric and rinse away the stabilizer; the patches deform on release.",
        ]
    return [
        "Every hooping is a separate piece of fabric, large enough for the hoop and its frame.",
        common,
        "Hoop it centred on the hoop template; stitch the hooping's file.",
        "Release, rinse away the stabilizer, cut each patch out with a seam allowance and sew "
        "it onto the garment at the garment centre listed for it.",
    ]


def _limits(doc_hoops, fmt: str, mode: str, grouping: Grouping) -> list[str]:
    out = ["Hoop margins and frame widths come from the machine catalogue; the built-in "
           "Janome 550E values are estimates, not measured on a real hoop (give yours with "
           "--machines).",
           "Times count stitching at the machine's top speed plus 6 s per trim and 60 s per "
           "colour change; bobbin changes and hooping add to them."]
    if fmt == "jef" and any(h.jef_code is None for h in doc_hoops):
        out.append("A hoop without a published JEF code (the RE36b) gets, in the file header, "
                   "the smallest published hoop field that holds its stitches "
                   "(docs/embroidery.md).")
    if mode == "garment":
        out.append("Garment coordinates times eta are taken as hoop coordinates: this assumes a "
                   "uniform stretch; check the marks after stretching.")
    else:
        out.append("The grouping is optimal over the generated hoop loads at most; the lower "
                   f"bound of {grouping.report.hoopings_lower_bound} hooping(s) holds for any "
                   "packing.")
    if grouping.report.method != "mip":
        out.append("HiGHS was stopped by the time limit: a greedy grouping is used.")
    return out


def fabricate(design, outdir, options: FabricateOptions = FabricateOptions(),
              geometry=None) -> FabricationResult:
    """Write the fabrication folder of ``design`` to ``outdir`` (see the module docstring).
    ``geometry``: spec -> PatchGeometry (default ``patch_design.geometry_for`` at
    ``options.resolution_mm``)."""
    check_outdir(outdir, options.force)
    if options.mode not in MODES:
        raise InvalidInputError(f"unknown mode {options.mode!r}; the modes are "
                                + ", ".join(MODES))
    machine = catalogue(options.machines_file, export.supported_formats()).machine(
        options.machine or design.machine.name)
    hoops = _hoops(machine, design, options)
    fmt = export.get_format(options.fmt or machine.default_format)
    eta = float(design.material_object().eta)
    feet, pieces = stretch(design, eta, options.blank_margin_mm)
    grouping = group(feet, pieces, hoops, options.mode, options.time_limit_s, options.spacing_mm)
    order = order_hoopings(grouping.hoopings, feet)
    if geometry is None:
        from stitchswitch.layout.embroidery.patch_design import geometry_for
        geometry = lambda spec: geometry_for(spec, options.resolution_mm)  # noqa: E731
    specs = {p.id: p for p in design.patches}
    cache: dict = {}

    def cached(spec):                       # each patch's geometry is built once
        if spec.id not in cache:
            cache[spec.id] = geometry(spec)
        return cache[spec.id]

    prm = StitchParams(stitches_per_minute=machine.stitches_per_minute)
    files: dict[str, bytes] = {}
    images: dict[str, bytes] = {}
    doc_hoops = []
    total = len(order.hoopings)
    stitched: set[str] = set()
    width = max(2, len(str(total)))
    for k, h in enumerate(order.hoopings, start=1):
        stem = f"hoop{k:0{width}d}"
        hplan = plan_hooping(h, specs, cached, prm)
        names = {"embroidery": f"{stem}.{fmt.name}", "png": f"{stem}.png", "svg": f"{stem}.svg"}
        if h.piece is not None:                 # garment mode: 1:1 templates and DXF marks
            outline = design.piece(h.piece).outline_mm
            mine = [specs[p] for p in h.patch_ids]
            for paper in PAPERS:
                name = f"{stem}-template-{paper}.pdf"
                names[f"template_{paper}"] = name
                files[name] = template_pdf(k, h, outline, mine, eta, paper)
            names["marks_dxf"] = f"{stem}-marks.dxf"
            files[names["marks_dxf"]] = marks_dxf(k, h, outline, mine, eta)
        files[names["embroidery"]] = export.encode(hplan.plan, fmt.name, h.hoop,
                                                   label=_label(design, stem))
        threads = audit_hooping(hplan, h, options.resolution_mm, prm.min_stitch_mm)
        conflict_ids = {c.patch for c in order.conflicts if c.hooping == k - 1}
        figs = hooping_figure(k, total, h, hplan, specs, feet, pieces, stitched, conflict_ids)
        files[names["png"]], files[names["svg"]] = figs["png"], figs["svg"]
        images[names["png"]] = files[names["png"]]
        stitched |= set(h.patch_ids)
        doc_hoops.append(_hooping_doc(k, h, hplan, specs, eta, names, threads,
                                      hoop_reason(h, hoops, feet, pieces)))
    for kind, data in overview_figure(order.hoopings, feet, pieces).items():
        files[f"overview.{kind}"] = data
    images["overview.png"] = files["overview.png"]
    doc = _doc(design, machine, fmt.name, options, eta, grouping, order, doc_hoops)
    files["fabrication.json"] = (json.dumps(doc.as_dict(), indent=2, allow_nan=False)
                                 + "\n").encode("utf-8")
    files["fabrication.md"] = markdown(doc).encode("utf-8")
    files["fabrication.html"] = html_page(doc, images).encode("utf-8")
    write_outdir(outdir, dict(sorted(files.items())), options.force)
    return FabricationResult(str(outdir), grouping, order, tuple(sorted(files)), doc)


def _blank(design, options) -> float:
    return float(design.blank_margin_mm if options.blank_margin_mm is None
                 else options.blank_margin_mm)


def _label(design, stem: str) -> str:
    """The design label in the file header: the design file's name and the hooping."""
    import os
    base = "design" if design.path is None else os.path.splitext(os.path.basename(design.path))[0]
    return f"{base} {stem}"


def _hooping_doc(k, h, hplan, specs, eta, names, threads, reason) -> HoopingDoc:
    plan = hplan.plan
    garment = h.piece is not None
    marks = relaxed_outline(h, eta).marks_mm if garment else None
    return HoopingDoc(
        number=k, hoop=h.hoop.name, field_mm=_r([h.hoop.width_mm, h.hoop.height_mm]),
        margin_mm=_r(h.hoop.margin_mm), frame_width_mm=_r(h.hoop.frame_width_mm),
        jef_code=h.hoop.jef_code, orientation_deg=h.orientation_deg, piece=h.piece,
        centre_stretched_mm=_r(h.centre_mm) if garment else None,
        centre_garment_mm=_r(np.array(h.centre_mm) / eta) if garment else None,
        alignment_marks_garment_mm=_r(marks) if garment else None,
        files=HoopingFiles(**names),
        patches=tuple(PlacedPatch(order=n, id=pid, position_hoop_mm=_r(xy),
                                  centre_garment_mm=_r(specs[pid].centre_mm),
                                  diameter_mm=_r(specs[pid].diameter_mm),
                                  fill=_r(specs[pid].fill, 4), conductive=specs[pid].conductive)
                      for n, (pid, xy) in enumerate(zip(h.patch_ids, h.positions_mm), start=1)),
        threads=_threads(hplan.threads, names["embroidery"]),
        stitches=plan.stitch_count, trims=plan.trim_count, jumps=plan.jump_count,
        colour_changes=plan.color_changes, thread_length_m=_r(plan.thread_length_mm / 1000),
        time_min=_r(plan.sewing_time_min, 2), gap_crossings=threads.gap_crossings,
        gap_crossing_mm=_r(threads.gap_crossing_mm), hoop_reason=reason,
        small_pieces=plan.small_pieces)


def _threads(uses, embroidery_file) -> tuple[Thread, ...]:
    """The hooping's colour blocks, each with the palette thread a JEF file stores for it."""
    jefs = (jef_threads([t.colour for t in uses]) if is_jef(embroidery_file)
            else (None,) * len(uses))
    return tuple(Thread(t.role, t.colour, tuple(t.patches), j) for t, j in zip(uses, jefs))


def _doc(design, machine, fmt, options, eta, grouping, order, doc_hoops) -> FabricationDoc:
    rep = grouping.report
    g = GroupingInfo(
        method=rep.method, status=rep.status, optimal=rep.optimal,
        mip_gap=None if rep.mip_gap is None else _r(rep.mip_gap, 6),
        hoopings=grouping.count, hoop_types=grouping.hoop_types,
        hoopings_lower_bound=rep.hoopings_lower_bound,
        first_fit_decreasing_hoopings=rep.greedy_hoopings, candidates=rep.candidates,
        time_limit_s=options.time_limit_s, note=rep.note,
        spacing_mm=_r(options.spacing_mm) if grouping.mode == "free" else None,
        fewest_hoopings=rep.fewest_hoopings, fewest_hoopings_conflicts=rep.fewest_hoopings_conflicts,
        conflicts_exact=bool(rep.conflicts_exact))
    return FabricationDoc(
        generator=GENERATOR, version=__version__, design=_design_info(design),
        mode=grouping.mode,
        machine=MachineInfo(machine.name, machine.label, machine.stitches_per_minute,
                            machine.source),
        embroidery_format=fmt,
        stretch=StretchInfo(_r(eta), tuple(_instructions(
            grouping.mode, eta, _blank(design, options)))),
        grouping=g, order_exact=order.exact,
        conflicts=tuple(Conflict(c.hooping + 1, c.patch, c.stitched_in + 1)
                        for c in order.conflicts),
        hoopings=tuple(doc_hoops),
        totals=Totals(hoopings=len(doc_hoops), patches=sum(len(h.patches) for h in doc_hoops),
                      stitches=sum(h.stitches for h in doc_hoops),
                      time_min=_r(sum(h.time_min for h in doc_hoops), 2)),
        overview_png="overview.png", overview_svg="overview.svg",
        limits=tuple(_limits(doc_hoops, fmt, grouping.mode, grouping)))
