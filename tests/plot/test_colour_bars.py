"""Colour bars drawn as artists of the figure (bearingfe.plot.colour_bars) against matplotlib's own."""

from __future__ import annotations

import numpy as np
import pytest

from bearingfe.plot import colour_bars


def _map(fig, cell):
    ax = fig.add_subplot(cell)
    x, y = np.meshgrid(np.linspace(-30.0, 30.0, 7), np.linspace(-20.0, 20.0, 5))
    mesh = ax.pcolormesh(x, y, x + 0.1 * y, vmin=-33.0, vmax=31.0)
    ax.set_aspect(1.0)
    return ax, mesh


def _drawn(fig):
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    return canvas.get_renderer()


def test_the_bar_takes_the_place_of_matplotlibs_and_its_ticks():
    """Reference: ``fig.colorbar(mappable, ax=ax, shrink=0.9, ticks=locator)`` on a twin figure: the map gives up
    the same share of its cell (its drawn box equal to 1e-9 of the figure), the bar has matplotlib's rectangle and
    the same ticks in view, with the same labels; its label stands right of the tick labels, within the figure."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    locator = dict(nbins=4, steps=(1, 2, 2.5, 5, 10))
    ours, theirs = Figure(figsize=(6.0, 3.5)), Figure(figsize=(6.0, 3.5))
    ax, mesh = _map(ours, ours.add_gridspec(1, 1, left=0.12, right=0.9)[0, 0])
    bar = colour_bars.colour_bar(ax, mesh, "p [MPa]", MaxNLocator(**locator))
    ref_ax, ref_mesh = _map(theirs, theirs.add_gridspec(1, 1, left=0.12, right=0.9)[0, 0])
    ref = theirs.colorbar(ref_mesh, ax=ref_ax, shrink=0.9, ticks=MaxNLocator(**locator))
    ref.set_label("p [MPa]")
    renderer, _ = _drawn(ours), _drawn(theirs)
    assert ax.get_position().bounds == pytest.approx(ref_ax.get_position().bounds, abs=1e-9)
    assert bar.rect == pytest.approx(ref.ax.get_position().bounds, abs=1e-9)
    assert mesh.colorbar is bar and ours.artists == [bar]
    lo, hi = ref.ax.get_ylim()
    ticks = [t for t in ref.ax.get_yticks() if lo - 1e-9 <= t <= hi + 1e-9]
    assert list(bar.ticks) == ticks == [-30.0, -15.0, 0.0, 15.0, 30.0] or list(bar.ticks) == ticks
    assert [t.get_text() for t in bar.tick_labels] == [t.get_text() for t in ref.ax.get_yticklabels()
                                                       if lo - 1e-9 <= t.get_position()[1] <= hi + 1e-9]
    box = bar.get_window_extent(renderer)
    label = bar.label_text.get_window_extent(renderer)
    assert label.x0 > max(t.get_window_extent(renderer).x1 for t in bar.tick_labels)
    assert box.x1 <= ours.bbox.x1 and bar.label_text.get_text() == "p [MPa]"


def test_the_bar_looks_like_matplotlibs():
    """Reference: the same figure with ``fig.colorbar``. Outside the bar's rectangle (one pixel of margin) the two
    pictures are the same to the pixel (the map, the marks, the labels, the label); inside, the colour map as an
    image against matplotlib's mesh of 256 cells differs by at most 4 of 255 levels (at the outline's corners,
    antialiased over the image in one and over the mesh in the other, by less than a fifth of the range)."""
    import io

    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator
    from PIL import Image

    pictures, bar = [], None
    for ours in (True, False):
        fig = Figure(figsize=(6.0, 3.5))
        ax, mesh = _map(fig, fig.add_gridspec(1, 1, left=0.12, right=0.9)[0, 0])
        if ours:
            bar = colour_bars.colour_bar(ax, mesh, "p [MPa]", MaxNLocator(4))
        else:
            fig.colorbar(mesh, ax=ax, shrink=0.9, ticks=MaxNLocator(4)).set_label("p [MPa]")
        buffer = io.BytesIO()
        fig.savefig(buffer, format="png", dpi=100)
        pictures.append(np.asarray(Image.open(buffer).convert("RGB"), dtype=int))
    difference = np.abs(pictures[0] - pictures[1]).max(axis=2)
    assert difference.shape == (350, 600)
    x0, y0, w, h = bar.rect
    rows = slice(int(350 * (1 - y0 - h)) - 1, int(350 * (1 - y0)) + 2)
    cols = slice(int(600 * x0) - 1, int(600 * (x0 + w)) + 2)
    inside = difference[rows, cols].copy()
    difference[rows, cols] = 0
    assert difference.max() == 0
    assert inside[3:-3, 3:-3].max() <= 4  # the colours (the outline's antialiased corners may round apart)
    assert inside.max() <= 48


def test_an_axes_placed_by_hand_gets_matplotlibs_bar():
    """``fig.add_axes`` leaves no grid cell to share: the bar is matplotlib's own, labelled and ticked as asked."""
    from matplotlib.colorbar import Colorbar
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator

    fig = Figure(figsize=(6.0, 3.5))
    ax = fig.add_axes((0.1, 0.1, 0.6, 0.8))
    mesh = ax.pcolormesh(np.arange(4.0), np.arange(3.0), np.arange(6.0).reshape(2, 3))
    bar = colour_bars.colour_bar(ax, mesh, "h [um]", MaxNLocator(4))
    assert isinstance(bar, Colorbar) and bar.ax.get_ylabel() == "h [um]" and mesh.colorbar is bar
    _drawn(fig)
    expected = [t for t in MaxNLocator(4).tick_values(0.0, 5.0) if 0.0 <= t <= 5.0]  # the locator's own values
    assert [t for t in bar.get_ticks() if 0.0 <= t <= 5.0] == expected and len(expected) >= 3


def test_labels_that_need_an_offset_show_it_above_the_bar():
    """Values 20.001 .. 20.004 label as matplotlib's ScalarFormatter does, with the common offset "+2e1" that
    makes them readable: the offset is shown above the bar, the labels alone would read 0.001 .. 0.004."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import MaxNLocator, ScalarFormatter

    fig = Figure(figsize=(6.0, 3.5))
    ax, mesh = _map(fig, fig.add_gridspec(1, 1, left=0.12, right=0.9)[0, 0])
    mesh.set_clim(20.001, 20.004)
    bar = colour_bars.colour_bar(ax, mesh, "h [um]", MaxNLocator(4))
    renderer = _drawn(fig)
    reference = ScalarFormatter()
    reference.create_dummy_axis()
    reference.axis.set_view_interval(20.001, 20.004)
    reference.format_ticks(MaxNLocator(4).tick_values(20.001, 20.004))
    assert bar.offset_text == reference.get_offset() != ""
    assert bar.get_window_extent(renderer).y1 <= fig.bbox.y1
