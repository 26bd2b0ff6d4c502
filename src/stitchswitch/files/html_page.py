"""Self-contained HTML pages: one stylesheet, every text escaped, figures embedded as data URIs.

A page is a title and a sequence of blocks (``Section``, ``Paragraph``, ``ItemList``,
``Table``, ``Figure``, ``Gallery``); ``page`` renders them into one document that needs no
other file and no network (no links, scripts or external images). Plain strings are always
escaped; inline markup is built with ``code``, ``strong`` and ``inline``, which return
``Markup`` (HTML that is already safe). The output depends on the input only (no timestamps),
so equal input gives an equal page.
"""
from __future__ import annotations

import base64
import html
from dataclasses import dataclass

from stitchswitch.errors import StitchSwitchError

__all__ = ["STYLESHEET", "Markup", "code", "strong", "inline", "Section", "Paragraph", "ItemList",
           "Table", "Figure", "Gallery", "page"]

STYLESHEET = """
*{box-sizing:border-box}
body{margin:0;background:#f4f5f7;color:#1d232b;font:15px/1.45 system-ui,-apple-system,"Segoe UI",
Roboto,"Helvetica Neue",Arial,sans-serif}
main{max-width:1160px;margin:0 auto;padding:24px 28px 40px;background:#fff;min-height:100vh}
h1{font-size:26px;margin:4px 0 14px}
h2{font-size:19px;margin:30px 0 10px;padding-bottom:4px;border-bottom:1px solid #dde1e6}
h3{font-size:16px;margin:22px 0 8px}
table{border-collapse:collapse;margin:8px 0;font-size:14px;font-variant-numeric:tabular-nums}
th,td{border:1px solid #d4dae1;padding:4px 8px;text-align:left;vertical-align:top}
th{background:#f0f2f5;font-weight:600}
table.numbers th,table.numbers td{text-align:right;white-space:nowrap}
table.numbers td:first-child,table.numbers th:first-child{text-align:left}
table.keys th{background:none;white-space:nowrap}
table.keys td{overflow-wrap:anywhere}
table.small{font-size:13px}
td.paper,th.paper{color:#5b6573;background:#f8f9fb}
tr.bad td{background:#fde8e8}
.scroll{overflow-x:auto;max-width:100%}
.note{color:#4a5361;font-size:13.5px;max-width:900px}
.warn{background:#fff4e5;border-left:4px solid #e67e22;padding:6px 10px}
.banner{padding:12px 16px;border-radius:6px;font-weight:600;margin:0 0 18px}
.banner.synthetic{background:#fff1d6;border:2px solid #e09a00;color:#6b4500}
.banner.unspecified{background:#eef0f3;border:2px solid #8a94a3;color:#2c3440}
.banner.measured{background:#e6f4ea;border:2px solid #3a9a5b;color:#1e5631}
img{max-width:100%;height:auto;border:1px solid #e1e5ea;margin:6px 0}
img.wide{display:block;margin:6px auto}
.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(330px,1fr));gap:14px}
figure{margin:0;text-align:center}
figure img{width:100%}
code{font-size:13px;background:#f0f2f5;padding:1px 4px;border-radius:3px}
footer{margin-top:30px;color:#6b7480;font-size:12.5px}
"""

_MIME = {"png": ("image/png", b"\x89PNG\r\n\x1a\n"), "svg": ("image/svg+xml", None)}


class Markup(str):
    """HTML that is safe to insert as it is (made by ``code``, ``strong``, ``inline``)."""


def _html(content) -> str:
    """``content`` as HTML: ``Markup`` kept, anything else escaped as text."""
    return content if isinstance(content, Markup) else html.escape(str(content))


def _attr(name: str, value) -> str:
    return "" if not value else f' {name}="{html.escape(str(value))}"'


def inline(*parts) -> Markup:
    """The parts one after the other: strings escaped, ``Markup`` kept."""
    return Markup("".join(_html(p) for p in parts))


def code(text) -> Markup:
    return Markup(f"<code>{_html(text)}</code>")


def strong(text) -> Markup:
    return Markup(f"<strong>{_html(text)}</strong>")


@dataclass(frozen=True)
class Paragraph:
    content: object
    cls: str | None = None

    def html(self) -> str:
        return f"<p{_attr('class', self.cls)}>{_html(self.content)}</p>"


@dataclass(frozen=True)
class ItemList:
    """A bulleted (or, ``ordered``, numbered) list."""

    items: tuple
    ordered: bool = False
    cls: str | None = None

    def html(self) -> str:
        tag = "ol" if self.ordered else "ul"
        return (f"<{tag}{_attr('class', self.cls)}>"
                + "".join(f"<li>{_html(i)}</li>" for i in self.items) + f"</{tag}>")


@dataclass(frozen=True)
class Table:
    """``rows`` of cells under an optional ``head``. ``keys``: the first cell of each row is
    its header (a two-column summary). ``column_classes``: {column index: class} of head and
    body cells; ``row_classes``: one class (or None) per row; ``scroll``: a horizontal scroll
    box around a wide table."""

    rows: tuple
    head: tuple | None = None
    cls: str | None = None
    keys: bool = False
    column_classes: tuple = ()
    row_classes: tuple = ()
    scroll: bool = False

    def _cell(self, tag: str, j: int, value) -> str:
        return f"<{tag}{_attr('class', dict(self.column_classes).get(j))}>{_html(value)}</{tag}>"

    def html(self) -> str:
        cls = " ".join(c for c in (self.cls, "keys" if self.keys else None) if c)
        out = f"<table{_attr('class', cls)}>"
        if self.head is not None:
            out += ("<thead><tr>" + "".join(self._cell("th", j, h) for j, h in enumerate(self.head))
                    + "</tr></thead>")
        body = []
        for i, row in enumerate(self.rows):
            rc = self.row_classes[i] if i < len(self.row_classes) else None
            cells = "".join(self._cell("th" if self.keys and j == 0 else "td", j, c)
                            for j, c in enumerate(row))
            body.append(f"<tr{_attr('class', rc)}>{cells}</tr>")
        out += "<tbody>" + "".join(body) + "</tbody></table>"
        return f'<div class="scroll">{out}</div>' if self.scroll else out


@dataclass(frozen=True)
class Figure:
    """An image embedded as a data URI: ``data`` the bytes of a PNG or SVG file (``kind``)."""

    data: bytes
    alt: str
    kind: str = "png"
    cls: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in _MIME:
            raise StitchSwitchError(f"figure {self.alt!r}: kind {self.kind!r} is not one of "
                                    + ", ".join(_MIME))
        signature = _MIME[self.kind][1]
        if signature is not None and not self.data.startswith(signature):
            raise StitchSwitchError(f"figure {self.alt!r}: the data are not a PNG file")
        if self.kind == "svg" and b"<svg" not in self.data[:1000]:
            raise StitchSwitchError(f"figure {self.alt!r}: the data are not an SVG file")

    def html(self) -> str:
        uri = f"data:{_MIME[self.kind][0]};base64," + base64.b64encode(self.data).decode("ascii")
        return f'<img{_attr("class", self.cls)} src="{uri}" alt="{html.escape(self.alt)}">'


@dataclass(frozen=True)
class Gallery:
    """Figures side by side in a grid."""

    figures: tuple

    def html(self) -> str:
        return ('<div class="grid">' + "".join(f"<figure>{f.html()}</figure>" for f in self.figures)
                + "</div>")


@dataclass(frozen=True)
class Section:
    """A heading (``<h2>``, or ``<h3>`` with ``level=3``) and the blocks under it."""

    title: object
    blocks: tuple = ()
    level: int = 2

    def html(self) -> str:
        h = f"h{self.level}"
        return f"<{h}>{_html(self.title)}</{h}>\n" + "\n".join(b.html() for b in self.blocks)


def page(title: str, blocks, *, heading=None, footer=None) -> str:
    """The whole document: ``title`` in the browser tab, ``heading`` (default: the title) as
    ``<h1>``, then ``blocks`` and an optional ``footer`` line."""
    body = "\n".join(b.html() for b in blocks)
    foot = "" if footer is None else f"\n<footer>{_html(footer)}</footer>"
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)}</title>
<style>{STYLESHEET}</style>
</head>
<body>
<main>
<h1>{_html(title if heading is None else heading)}</h1>
{body}{foot}
</main>
</body>
</html>
"""
