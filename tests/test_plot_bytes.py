"""files.figures.plot_bytes: stampless, reproducible figure bytes, the figure closed after."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from stitchswitch.files.figures import plot_bytes  # noqa: E402


def _figure():
    fig, ax = plt.subplots(figsize=(2, 2), dpi=50)
    ax.plot([0, 1, 2], [0, 1, 4])
    return fig


@pytest.mark.parametrize("fmt, stamp", [("png", b"Software"), ("svg", b"<dc:date>"),
                                        ("pdf", b"/CreationDate")])
def test_no_stamp_and_the_same_bytes_twice(fmt, stamp):
    a, b = plot_bytes(_figure(), fmt), plot_bytes(_figure(), fmt)
    assert a == b
    assert stamp not in a


def test_closes_the_figure_unless_asked_not_to():
    fig = _figure()
    plot_bytes(fig, "png", close=False)
    assert plt.fignum_exists(fig.number)
    plot_bytes(fig, "png")
    assert not plt.fignum_exists(fig.number)


def test_unknown_format_is_refused_and_the_figure_closed():
    fig = _figure()
    with pytest.raises(ValueError, match="'bmp'"):
        plot_bytes(fig, "bmp")
    plt.close(fig)
