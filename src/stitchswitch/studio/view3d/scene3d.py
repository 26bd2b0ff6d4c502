"""The 3D view's geometry: the design's scene built by ``preview3d.scene.SceneBuilder`` (the one
scene builder of ``stitchswitch preview``, at a lighter resolution), as a few pyvista actors:
one per piece, one per group of patch surfaces (``group_of``), the outlines by check status;
an edit changes only the actors holding the parts it rebuilt, and the browser view (trame's
VTK local view, which sends an array only when its checksum is new) receives only their
arrays.

Surfaces are coloured by height over the scene's actual range of heights, the flat fabric (0)
included (``view_scale``): the preview's diverging map, white at the flat fabric, cut to the
part the heights reach, so a height has the colour the canvas gives it. The outlines show the
constraint check: a patch's embroidery boundary, or a piece's
outline for a problem of the piece itself, is drawn red for an error and orange for a warning
(``preview3d.colours.STATUS_RGB``), thicker than the plain outlines.
"""
from __future__ import annotations

import zlib

import numpy as np

from stitchswitch.preview3d import colours
from stitchswitch.preview3d.render import polylines
from stitchswitch.preview3d.scene import SceneBuilder
from stitchswitch.preview3d.spec import spec_from_design

HEIGHT = "height (mm)"
#: the view's resolution: half the points around a patch and every second profile node of
#: ``stitchswitch preview``'s (the same builder), a quarter of its triangles: the browser's
#: software WebGL and trame-vtk's checksums of every array on every update scale with it
VIEW_N_THETA = 32
VIEW_RING_STEP = 6
#: patch surfaces are drawn by this many actors, a patch always in the same one (by its id):
#: trame-vtk serializes every actor on every update (about 1 ms of CPU each), so one actor per
#: patch costs more than resending a few patches' arrays with the edited one
SURFACE_GROUPS = 8
#: the view's points and heights are sent as float32, what WebGL draws with: float64 arrays
#: doubled the bytes trame-vtk hashes and sends and vtk.js decodes, for precision the view
#: drops anyway (vtk.js converts them to float32 for the GPU)
VIEW_DTYPE = np.float32
LINE_STYLE = {"piece": ("black", 2.0), "patch": ("#404040", 1.0)}
FLAGGED_WIDTH = 4.0


def _hex(rgb) -> str:
    return "#" + "".join(f"{int(c):02x}" for c in rgb)


class Scene3D:
    """The current scene of a design; ``update`` rebuilds only what an edit changed."""

    def __init__(self):
        self.builder = SceneBuilder(VIEW_N_THETA, VIEW_RING_STEP)
        self.scene = None
        self.clim = (-1.0, 1.0)
        self.cmap_range = (0.0, 1.0)

    def update(self, design) -> None:
        self.scene = self.builder.build(spec_from_design(design))
        self.cmap_range, self.clim = view_scale([p.height_mm for p in self.scene.patches])

    def parts(self, violations=()) -> dict:
        """{actor name: (kind, content, style)}: one "surface" per piece and per group of patches
        (``group_of``; content: a tuple of parts), and the outlines as few "lines" actors, one
        per kind and check status (content: a tuple of lines; style: (colour, width))."""
        if self.scene is None:
            return {}
        out = {f"piece:{p.name}": ("surface", (p,), None) for p in self.scene.pieces}
        chunks: dict = {}
        for p in self.scene.patches:
            chunks.setdefault(group_of(p.id), []).append(p)
        out |= {f"patches:{k}": ("surface", tuple(ps), None) for k, ps in sorted(chunks.items())}
        by_status = dict(zip(("patch", "piece"), colours.status_from_violations(violations)))
        groups: dict = {}
        for ln in self.scene.lines:
            groups.setdefault((ln.kind, by_status[ln.kind].get(ln.name, "ok")), []).append(ln)
        for (kind, status), lines in groups.items():
            colour, width = LINE_STYLE[kind]
            if status != "ok":
                colour, width = _hex(colours.STATUS_RGB[status]), FLAGGED_WIDTH
            out[f"lines:{kind}:{status}"] = ("lines", tuple(lines), (colour, width))
        return out


def view_scale(heights) -> tuple[tuple[float, float], tuple[float, float]]:
    """((a, b), (lo, hi)): the colour range (lo, hi) mm, the heights' actual range with the flat
    fabric's 0 in it, and the part [a, b] of ``colours.HEIGHT_CMAP`` (0..1) it is drawn with:
    the map runs from -H to H (H the largest |height|) so that 0 stays white and a height has
    the colour of the canvas's symmetric map, and only the part the heights reach is used."""
    lo = float(min([0.0, *heights]))
    hi = float(max([0.0, *heights]))
    h = max(-lo, hi, 1e-3)
    lo, hi = (lo, hi) if hi > lo else (-h, h)
    return (0.5 + 0.5 * lo / h, 0.5 + 0.5 * hi / h), (lo, hi)


def _lookup_table(pv, cmap_range):
    import matplotlib
    from matplotlib.colors import ListedColormap

    full = matplotlib.colormaps[colours.HEIGHT_CMAP]
    return pv.LookupTable(cmap=ListedColormap(full(np.linspace(*cmap_range, 256))))


def group_of(patch_id: str) -> int:
    """The surface actor of a patch: fixed by its id, so adding or removing a patch leaves
    the other groups as they are."""
    return zlib.crc32(patch_id.encode("utf-8")) % SURFACE_GROUPS


def _surface_mesh(pv, parts):
    meshes = [(p.surface.points, p.surface.triangles) if hasattr(p, "surface")
              else (p.points, p.triangles) for p in parts]
    meshes = [m for m in meshes if len(m[1])]
    if not meshes:
        return pv.PolyData()
    offsets = np.cumsum([0] + [len(m[0]) for m in meshes[:-1]])
    points = np.vstack([m[0] for m in meshes]).astype(VIEW_DTYPE)
    tris = np.vstack([m[1] + o for m, o in zip(meshes, offsets)])
    mesh = pv.PolyData.from_regular_faces(points, tris)
    mesh.point_data[HEIGHT] = points[:, 2].copy()
    return mesh


def _line_mesh(pv, lines):
    mesh = polylines(pv, lines)
    if mesh.n_points:
        mesh.points = mesh.points.astype(VIEW_DTYPE)
    return mesh


def _same(a: tuple, b: tuple) -> bool:
    """The same parts or lines (by identity): nothing to resend."""
    return len(a) == len(b) and all(x is y for x, y in zip(a, b))


class PlotterSync:
    """Keeps a pyvista ``Plotter`` showing a ``Scene3D``: adds, rebuilds and removes actors by
    part identity, so unchanged parts keep their arrays (and their checksums). ``sync``
    returns how many actors it added, rebuilt, removed and kept."""

    def __init__(self, plotter):
        import pyvista as pv

        self._pv = pv
        self.plotter = plotter
        self.actors: dict = {}        # name -> [content, actor, mesh]
        self._lut_range = None
        self._lut = None

    def sync(self, scene3d: Scene3D, violations=()) -> dict:
        pv, pl = self._pv, self.plotter
        counts = {"added": 0, "rebuilt": 0, "removed": 0, "kept": 0}
        parts = scene3d.parts(violations)
        if scene3d.cmap_range != self._lut_range:     # one colour table for every surface
            self._lut, self._lut_range = _lookup_table(pv, scene3d.cmap_range), scene3d.cmap_range
        for name in [n for n in self.actors if n not in parts]:
            pl.remove_actor(self.actors.pop(name)[1], render=False)
            counts["removed"] += 1
        for name, (kind, content, style) in parts.items():
            entry = self.actors.get(name)
            if entry is not None and _same(entry[0], content):
                counts["kept"] += 1
            else:
                mesh = _surface_mesh(pv, content) if kind == "surface" else _line_mesh(pv, list(content))
                if entry is None:
                    if kind == "surface":
                        actor = pl.add_mesh(mesh, scalars=HEIGHT if mesh.n_points else None,
                                            cmap=self._lut, clim=scene3d.clim,
                                            show_scalar_bar=False, name=name, render=False)
                    else:
                        actor = pl.add_mesh(mesh, color=style[0], line_width=style[1], name=name,
                                            render=False, lighting=False)
                    self.actors[name] = [content, actor, mesh]
                    counts["added"] += 1
                else:
                    entry[2].copy_from(mesh)
                    entry[0] = content
                    counts["rebuilt"] += 1
            if kind == "surface":
                mapper = self.actors[name][1].mapper
                mapper.lookup_table = self._lut
                mapper.scalar_range = scene3d.clim
        return counts
