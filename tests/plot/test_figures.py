"""Fixed layouts and saving (bearingfe.plot.figures)."""

from __future__ import annotations

import pytest

from bearingfe.plot import figures


def test_frame_places_the_grid_with_margins_in_inches():
    """A 10 x 5 in figure with 1 in left, 0.5 in right, 0.5 in top and bottom margins and a 1 in gap
    between two columns: each axes is (10 - 1.5 - 1) / 2 = 3.75 in wide, 4 in high (arithmetic)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 5.0))
    axes = figures.frame(fig, ncols=2, top=0.5, bottom=0.5, left=1.0, right=0.5, wgap=1.0).subplots()
    boxes = [ax.get_position().bounds for ax in axes]
    assert boxes[0][0] * 10 == pytest.approx(1.0) and boxes[1][0] * 10 == pytest.approx(1.0 + 3.75 + 1.0)
    for x, y, w, h in boxes:
        assert (w * 10, h * 5, y * 5) == pytest.approx((3.75, 4.0, 0.5))
    with pytest.raises(ValueError, match="too small"):
        figures.frame(fig, top=3.0, bottom=3.0)


def test_save_writes_a_png_at_the_package_resolution(tmp_path):
    """A 2 x 1 in figure saved at DPI is 2 DPI x DPI pixels (PNG header)."""
    from matplotlib.figure import Figure
    from PIL import Image

    fig = Figure(figsize=(2.0, 1.0))
    fig.subplots().plot([0, 1], [0, 1])
    assert figures.save(fig, tmp_path / "a.png") is fig
    assert Image.open(tmp_path / "a.png").size == (2 * figures.DPI, figures.DPI)



def test_ruled_table_places_one_text_per_cell_on_its_row():
    """Rows of 0.25 in in an axes 2.5 in high: row i's middle at 1 - (i + 1/2) / 10 of the axes (arithmetic);
    the first column left-aligned at its edge plus the pad, the others centred; emphasis on body cells only."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4.0, 3.0))
    ax = fig.add_subplot(figures.frame(fig, top=0.25, bottom=0.25, left=0.5, right=0.5)[0, 0])
    texts = figures.ruled_table(ax, [["a", "1", "x"], ["b", "bad", "y"]], ["", "v", "u"], [0.5, 0.25, 0.25],
                                row_height=0.25, pad=0.01,
                                emphasis=lambda t: {"color": "red"} if t in ("bad", "v") else None)
    assert [t.get_text() for t in texts] == ["", "v", "u", "a", "1", "x", "b", "bad", "y"]
    for k, t in enumerate(texts):
        row, col = divmod(k, 3)
        x, y = t.get_position()
        assert y == pytest.approx(1.0 - (row + 0.5) * 0.1)
        assert (x, t.get_ha()) == ((pytest.approx(0.01), "left") if col == 0 else
                                   (pytest.approx((0.5, 0.625, 0.875)[col]), "center"))
    assert texts[7].get_color() == "red" and texts[1].get_color() != "red"  # the header keeps its colour
    (rules,) = ax.lines  # one polyline: 4 row rules and 4 column rules, each 2 points and a break
    assert len(rules.get_xdata()) == 3 * (4 + 4)
    assert not ax.axison


def _figure_with_every_kind_of_axis():
    """Stacked axes sharing x (inner labels hidden), a grid, a colour bar on the right, an axis label on each
    side, a log axis and an axis whose labels need an offset text (the last two keep matplotlib's ticks)."""
    import numpy as np
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 7.0))
    top, middle, bottom = figures.frame(fig, nrows=3, top=0.3, bottom=0.6, left=0.9, right=1.2,
                                        hgap=0.4).subplots(sharex=True)
    x = np.linspace(0.0, 360.0, 50)
    top.plot(x, np.sin(np.radians(x)))
    top.grid(True, alpha=0.3)
    top.set_ylabel("sin [-]")
    mesh = middle.pcolormesh(x, [0.0, 1.0, 2.0], np.outer([1.0, 2.0], x[:-1]), shading="flat")
    bar = fig.colorbar(mesh, ax=middle)
    bar.set_label("value [W]")
    middle.set_yscale("log")
    bottom.plot(x, 1e-5 + 1e-9 * x)  # labels with an offset text
    bottom.set_xlabel("angle [deg]")
    bottom.set_xticks(np.arange(0, 361, 90))
    return fig


def _pixels(fig, drawn: bool):
    import io

    import numpy as np
    from PIL import Image

    buffer = io.BytesIO()
    if drawn:
        figures.save(fig, None)  # nothing written without a path
        with figures.drawn_ticks(fig):
            fig.savefig(buffer, format="png", dpi=figures.DPI)
    else:
        fig.savefig(buffer, format="png", dpi=figures.DPI)
    return np.asarray(Image.open(buffer))


def test_drawn_ticks_give_the_same_picture_as_matplotlibs_ticks():
    """The marks, labels, grid lines and axis labels drawn by drawn_ticks land on the same pixels as
    matplotlib's own ticks (reference: the same figure drawn with matplotlib's tick objects), the shared and
    the hidden labels, a colour bar's right-hand labels and the axes kept on matplotlib's ticks included."""
    import numpy as np

    reference = _pixels(_figure_with_every_kind_of_axis(), drawn=False)
    drawn = _pixels(_figure_with_every_kind_of_axis(), drawn=True)
    assert reference.shape == drawn.shape
    assert np.array_equal(reference, drawn)


def test_drawn_ticks_replace_only_plain_axes_and_restore_them():
    """Within the block the plain axes have no tick locator (their marks are artists of the axes) while the log
    axis, the offset-text axis and every axis sharing its ticker with them keep theirs; after it every axis has
    its own locator back and the added artists are gone."""
    from matplotlib.ticker import NullLocator

    fig = _figure_with_every_kind_of_axis()
    top, middle, bottom, bar = fig.axes
    before = {id(a): (a.get_major_locator(), len(a.axes.get_children())) for ax in fig.axes
              for a in (ax.xaxis, ax.yaxis)}
    with figures.drawn_ticks(fig):
        assert isinstance(top.yaxis.get_major_locator(), NullLocator)  # plain
        assert isinstance(bar.yaxis.get_major_locator(), NullLocator)  # a colour bar: plain
        assert not isinstance(middle.yaxis.get_major_locator(), NullLocator)  # log
        assert not isinstance(bottom.yaxis.get_major_locator(), NullLocator)  # offset text
        # the shared x ticker: the bottom axes is plain in x, and so are the others sharing it
        assert isinstance(top.xaxis.get_major_locator(), NullLocator)
        assert len(top.get_children()) > before[id(top.yaxis)][1]
    for ax in fig.axes:
        for a in (ax.xaxis, ax.yaxis):
            assert a.get_major_locator() is before[id(a)][0]
            assert len(ax.get_children()) == before[id(a)][1]


def test_write_png_round_trips_through_pil(tmp_path):
    """The file read back by PIL (an independent decoder) gives the same pixels: an opaque image as RGB, one with
    transparent pixels as RGBA, every byte value and the Sub filter's wrap-around included; the resolution is
    the one given (pHYs, in dots per metre: 100 dpi reads back within its rounding, 1e-5)."""
    import numpy as np
    from PIL import Image

    rng = np.random.default_rng(3)
    image = rng.integers(0, 256, size=(37, 53, 4), dtype=np.uint8)
    opaque = image.copy()
    opaque[:, :, 3] = 255
    for name, rgba, mode in (("opaque.png", opaque, "RGB"), ("alpha.png", image, "RGBA")):
        figures.write_png(rgba, tmp_path / name, 100)
        back = Image.open(tmp_path / name)
        assert back.mode == mode and back.info["dpi"] == pytest.approx((100, 100), rel=1e-5)
        np.testing.assert_array_equal(np.asarray(back), rgba[:, :, :3] if mode == "RGB" else rgba)
    with pytest.raises(ValueError, match="rgba must be"):
        figures.write_png(np.zeros((4, 4, 3), np.uint8), tmp_path / "bad.png")


def test_save_writes_the_pixels_savefig_writes(tmp_path):
    """save's PNG against matplotlib's own ``savefig`` of the same figure at the same resolution: the same pixels."""
    import numpy as np
    from matplotlib.figure import Figure
    from PIL import Image

    def figure():
        fig = Figure(figsize=(3.0, 2.0))
        ax = fig.subplots()
        ax.plot([0, 1, 2], [0, 1, 0.5], label="a")
        ax.legend()
        ax.set_title("t")
        return fig

    figures.save(figure(), tmp_path / "ours.png")
    figure().savefig(tmp_path / "theirs.png", dpi=figures.DPI)
    ours = np.asarray(Image.open(tmp_path / "ours.png").convert("RGB"))
    theirs = np.asarray(Image.open(tmp_path / "theirs.png").convert("RGB"))
    np.testing.assert_array_equal(ours, theirs)
