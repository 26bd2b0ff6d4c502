"""``stitchswitch studio``: the interactive design tool in the browser (``stitchswitch.studio``)."""
from __future__ import annotations

import logging
import os

import click

from stitchswitch.cli import options
from stitchswitch.errors import InvalidInputError
from stitchswitch.studio.view3d import render_mode

log = logging.getLogger("stitchswitch")


def _source(source, rectangle, output, size=None):
    """(Document, Design, pattern) to edit: a design file, or a new design from a pattern (of
    ``size``, default its first; ``pattern`` is then every piece of it, for the size picker) or
    a rectangle, saved to ``output``."""
    from stitchswitch.cli.design.import_cmd import parse_rectangle
    from stitchswitch.layout.garment.design import VERSION, Design
    from stitchswitch.layout.garment.piece_select import rectangle_piece, select_pieces
    from stitchswitch.studio.persist import Document, source_pattern

    if (source is None) == (rectangle is None):
        raise InvalidInputError("give either a DESIGN.json or PATTERN.dxf, or --rectangle WxH (not both)")
    if source is not None and not source.lower().endswith(".dxf"):
        if output is not None and os.path.abspath(output) != os.path.abspath(source):
            raise InvalidInputError(f"--output {output!r}: a design file is saved to itself ({source!r})")
        if size is not None:
            raise InvalidInputError("--size: only a pattern (PATTERN.dxf) has sizes")
        document, design = Document.open(source)
        pattern, note = source_pattern(design, source)     # the sizes of the pattern it came from
        if note:
            log.warning(f"{source}: {note}")
        return document, design, pattern
    if output is None:
        raise InvalidInputError("--output DESIGN.json is needed to save a design started from "
                                + (f"the pattern {source!r}" if source else "--rectangle"))
    if os.path.exists(output):
        raise InvalidInputError(f"--output {output!r} exists; open it as DESIGN.json instead")
    pattern = None
    if rectangle is not None:
        if size is not None:
            raise InvalidInputError("--size: only a pattern (PATTERN.dxf) has sizes")
        pieces = (rectangle_piece(*parse_rectangle(rectangle)),)
    else:
        from stitchswitch.layout.garment.dxf.reader import import_dxf

        pattern = import_dxf(source)
        first = next(iter(dict.fromkeys(p.size for p in pattern)), None)
        # the pieces name the pattern relative to the design file, where reopening looks for it
        pieces = select_pieces(pattern, size if size is not None else first, source=os.path.relpath(
            os.path.abspath(source), os.path.dirname(os.path.abspath(output))))
    design = Design(VERSION, pieces, (), path=output)
    return Document(output, design), design, pattern


@click.command(cls=options.Command)
@click.argument("source", required=False, type=click.Path(dir_okay=False, exists=True))
@click.option("--rectangle", default=None, metavar="WxH", help="Start from one rectangular piece, WIDTHxHEIGHT mm.")
@click.option("-o", "--output", default=None, type=options.OutputFile((".json",), as_str=True),
              metavar="FILE", help="Where a design started from a pattern or --rectangle is saved.")
@click.option("--port", default=8765, show_default=True, type=click.IntRange(1, 65535), metavar="N",
              help="Local port of the web page, in [1, 65535].")
@click.option("--host", default="127.0.0.1", show_default=True, metavar="ADDRESS",
              help="Address to bind (anything but 127.0.0.1 exposes the studio to the network).")
@click.option("--size", default=None, metavar="SIZE",
              help="The size of a graded PATTERN.dxf to start from (default: its first; the "
                   "page switches sizes).")
@click.option("--view", "view_mode", default="auto", show_default=True,
              type=click.Choice(render_mode.MODES),
              help="Where the 3D view is drawn: by the browser's WebGL, or rendered on the "
                   "server and sent as images; auto renders on the server when this "
                   "machine's OpenGL is a software one (no GPU), where that is faster.")
@click.option("--no-browser", is_flag=True, help="Do not open a browser.")
@click.option("--recover", is_flag=True, help="Open the autosaved edits of DESIGN.json instead of the file.")
def studio(source, rectangle, output, port, host, size, view_mode, no_browser, recover):
    """Edit a design in the browser: place and tune patches with a live readout and 3D view,
    inverse design, the constraint check, hoop grouping and export. Ctrl-C stops it."""
    try:
        from stitchswitch.studio.app import serve
    except ImportError as exc:
        raise InvalidInputError(f"the studio needs its extra: pip install 'stitchswitch[studio]' ({exc})") from None
    from stitchswitch.reduced.design_space.cache import default_map
    from stitchswitch.studio.session import Session
    from stitchswitch.studio.view3d.scene3d import Scene3D

    document, design, pattern = _source(source, rectangle, output, size)
    recovered = document.recover()
    if recovered is not None and recover:
        design = recovered
    elif recovered is not None:
        log.warning(f"{document.path}: autosaved edits exist; --recover opens them")
    if host != "127.0.0.1":
        log.warning(f"--host {host}: the studio is reachable from the network")
    session = Session(document, design, default_map(), Scene3D(), pattern)
    click.echo(f"stitchswitch studio: http://{host}:{port}/ (Ctrl-C stops it)")
    serve(session, port=port, host=host, open_browser=not no_browser, view_mode=view_mode)
    click.echo("stitchswitch studio: stopped")
