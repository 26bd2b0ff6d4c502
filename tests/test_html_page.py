"""``files.html_page``: text is escaped, figures are embedded, the page is deterministic and
self-contained."""
import base64
import re

import pytest

from stitchswitch.errors import StitchSwitchError
from stitchswitch.files.html_page import (
    Figure,
    Gallery,
    ItemList,
    Paragraph,
    Section,
    Table,
    code,
    inline,
    page,
    strong,
)
from stitchswitch.files.jsonsafe import json_safe

PNG = b"\x89PNG\r\n\x1a\n" + bytes(range(40))
SVG = b'<?xml version="1.0"?>\n<svg xmlns="http://www.w3.org/2000/svg"><rect/></svg>'


def sample() -> str:
    return page("A <b>&", (
        Paragraph("x < y & 'q'", cls="note"),
        Section("Table", (Table((("<td>", 1), ("b", inline("k ", code("a<b")))), head=("h&", "v"),
                                column_classes=((1, "paper"),), row_classes=("bad",)),)),
        Section("Figures", (Figure(PNG, 'a "png"'), Gallery((Figure(SVG, "svg", kind="svg"),))),
                level=3),
        ItemList(("one", strong("two")), ordered=True),
    ), footer="made by <me>")


def test_text_is_escaped_everywhere():
    html = sample()
    assert "<title>A &lt;b&gt;&amp;</title>" in html and "<h1>A &lt;b&gt;&amp;</h1>" in html
    assert "<p class=\"note\">x &lt; y &amp; &#x27;q&#x27;</p>" in html
    assert "<td>&lt;td&gt;</td>" in html and "<th>h&amp;</th>" in html
    assert 'alt="a &quot;png&quot;"' in html
    assert "<footer>made by &lt;me&gt;</footer>" in html
    assert "<b>" not in html and "<me>" not in html


def test_markup_is_kept_and_its_text_escaped():
    html = sample()
    assert '<td class="paper">k <code>a&lt;b</code></td>' in html
    assert "<li><strong>two</strong></li>" in html
    assert '<tr class="bad"><td>&lt;td&gt;</td><td class="paper">1</td></tr>' in html
    assert str(inline("a&", strong("<b>"))) == "a&amp;<strong>&lt;b&gt;</strong>"


def test_figures_are_embedded_as_data_uris():
    html = sample()
    uris = re.findall(r'<img [^>]*src="([^"]*)"', html)
    assert uris == ["data:image/png;base64," + base64.b64encode(PNG).decode("ascii"),
                    "data:image/svg+xml;base64," + base64.b64encode(SVG).decode("ascii")]
    assert base64.b64decode(uris[0].split(",", 1)[1]) == PNG
    assert '<div class="grid"><figure><img' in html


def test_page_is_self_contained_and_deterministic():
    html = sample()
    assert html == sample()
    assert html.startswith("<!DOCTYPE html>") and html.rstrip().endswith("</html>")
    assert html.count("<style>") == 1
    for forbidden in ("<script", "<link", "url(", 'src="http', 'src="file'):
        assert forbidden not in html


def test_key_tables_put_the_key_in_a_header_cell():
    html = Table((("design", "d.json"),), keys=True).html()
    assert html == '<table class="keys"><tbody><tr><th>design</th><td>d.json</td></tr></tbody></table>'
    assert Table((("a",),), cls="numbers", scroll=True).html().startswith(
        '<div class="scroll"><table class="numbers">')


def test_figure_bytes_must_match_the_kind():
    with pytest.raises(StitchSwitchError, match="not a PNG"):
        Figure(SVG, "x")
    with pytest.raises(StitchSwitchError, match="not an SVG"):
        Figure(PNG, "x", kind="svg")
    with pytest.raises(StitchSwitchError, match="kind 'gif'"):
        Figure(PNG, "x", kind="gif")


def test_json_safe_converts_numpy_and_non_finite_values():
    np = pytest.importorskip("numpy")
    out = json_safe({"a": np.float64(1.5), "b": (np.int64(2), float("nan")),
                     "c": {"d": float("inf"), "e": [np.bool_(True), "s", None]}})
    assert out == {"a": 1.5, "b": [2, None], "c": {"d": None, "e": [True, "s", None]}}
    assert type(out["a"]) is float and type(out["b"][0]) is int and type(out["c"]["e"][0]) is bool
