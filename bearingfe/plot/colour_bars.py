"""Colour bars drawn as a few artists of the figure instead of an axes of their own.

A matplotlib colour bar (``fig.colorbar``) is an axes: its tick objects, four spines, a mesh of 256 cells and
the grid juggling that makes room for it cost about 11 ms a bar, half of a field map's cost in the main scene.
:func:`colour_bar` makes the same room beside a map (the same share of its grid cell, the same gap, length and
aspect as ``fig.colorbar(mappable, ax=ax, shrink=0.9)``) and adds one :class:`ColourBar` artist that draws the
colour map as an image, its outline, tick marks and labels (matplotlib's tick size, pad and fonts) and the label.
"""

from __future__ import annotations

import numpy as np
from matplotlib.artist import Artist

from .figures import ticks_in_view

__all__ = ["BAR_FRACTION", "BAR_PAD", "BAR_SHRINK", "BAR_ASPECT", "colour_bar", "ColourBar"]

#: A colour bar's share of its map's cell, the gap between them, its length and its aspect (matplotlib's defaults
#: for a bar right of an axes, the length the package's maps use).
BAR_FRACTION, BAR_PAD, BAR_SHRINK, BAR_ASPECT = 0.15, 0.05, 0.9, 20.0


def colour_bar(ax, mappable, label: str, locator):
    """A vertical colour bar right of ``ax``, drawn by a few artists of the figure (:class:`ColourBar`), in the
    place and the looks of ``fig.colorbar(mappable, ax=ax, shrink=BAR_SHRINK)``: ``ax`` gives up the same share
    of its cell; ``locator`` (e.g. a ``MaxNLocator``) places the ticks; ``label`` beside them. Returns the bar
    (also ``mappable.colorbar``). An axes that no grid placed (``fig.add_axes``) has no cell to share: it gets
    matplotlib's own colour bar (``fig.colorbar``), which is returned.

    A matplotlib colour bar is an axes of its own (its tick objects, spines, a mesh of 256 cells and a layout
    pass: about 11 ms each, half of a field map's cost)."""
    fig = ax.get_figure()
    if ax.get_subplotspec() is None:  # an axes placed by hand (add_axes): matplotlib's bar takes its room
        bar = fig.colorbar(mappable, ax=ax, shrink=BAR_SHRINK, ticks=locator)
        bar.set_label(label)
        return bar
    grid = ax.get_subplotspec().subgridspec(3, 2, wspace=2 * BAR_PAD / (1 - BAR_PAD), hspace=0,
                                            height_ratios=[0.5 * (1 - BAR_SHRINK), BAR_SHRINK, 0.5 * (1 - BAR_SHRINK)],
                                            width_ratios=[1 - BAR_FRACTION - BAR_PAD, BAR_FRACTION])
    ax.set_subplotspec(grid[:, 0])
    ax.set_anchor((1.0, 0.5))
    box = grid[1, 1].get_position(fig)
    w, h = fig.get_size_inches()
    width = box.width
    height = width * BAR_ASPECT * w / h  # box aspect BAR_ASPECT in inches, anchored left and centred
    if height > box.height:
        height, width = box.height, box.height * h / (w * BAR_ASPECT)
    rect = (box.x0, box.y0 + 0.5 * (box.height - height), width, height)
    bar = ColourBar(rect, mappable.cmap, mappable.norm, label, locator)
    fig.add_artist(bar)
    mappable.colorbar = bar
    return bar


class ColourBar(Artist):
    """A vertical colour bar at ``rect`` (left, bottom, width, height in figure fractions): the colour map as an
    image, a black outline, tick marks and labels on the right (matplotlib's tick size, pad and label font),
    ``label`` beside the labels, and the labels' common offset or power of ten above the bar when the formatter
    needs one (``offset_text``). Its pieces are made when it is drawn (their places need the renderer), and kept
    as ``ticks`` (values), ``tick_labels`` and ``label_text`` (texts) for a reader."""

    def __init__(self, rect, cmap, norm, label: str, locator) -> None:
        super().__init__()
        self.rect, self.cmap, self.norm, self.label, self.locator = rect, cmap, norm, label, locator
        self.ticks: np.ndarray = np.empty(0)
        self.tick_labels: list = []
        self.label_text = None
        self.offset_text = ""
        self._extent = None

    def _ticks(self):
        from matplotlib.ticker import ScalarFormatter

        lo, hi = float(self.norm.vmin), float(self.norm.vmax)
        locs = np.asarray(self.locator.tick_values(lo, hi), dtype=float)
        formatter = ScalarFormatter()
        formatter.create_dummy_axis()
        formatter.axis.set_view_interval(lo, hi)
        formatter.axis.set_data_interval(lo, hi)
        texts = formatter.format_ticks(locs)
        return ticks_in_view(locs, texts, lo, hi), formatter.get_offset()

    def draw(self, renderer) -> None:
        import matplotlib as mpl
        from matplotlib.image import BboxImage
        from matplotlib.lines import TICKRIGHT, Line2D
        from matplotlib.patches import Rectangle
        from matplotlib.text import Text
        from matplotlib.transforms import Bbox, TransformedBbox

        if not self.get_visible():
            return
        fig = self.get_figure(root=True)
        rc = mpl.rcParams
        x0, y0, w, h = self.rect
        box = TransformedBbox(Bbox.from_bounds(x0, y0, w, h), fig.transFigure)
        colours = self.cmap(np.linspace(0.0, 1.0, self.cmap.N))[::-1, None, :]  # top row: the largest value
        image = BboxImage(box, interpolation="nearest", origin="upper")
        image.set_data(colours)
        outline = Rectangle((x0, y0), w, h, transform=fig.transFigure, fill=False, edgecolor=rc["axes.edgecolor"],
                            linewidth=rc["axes.linewidth"])
        shown, offset = self._ticks()
        lo, hi = float(self.norm.vmin), float(self.norm.vmax)
        ys = [y0 + h * (v - lo) / (hi - lo) for v, _ in shown] if hi > lo else []
        size, pad = rc["ytick.major.size"], rc["ytick.major.pad"]
        marks = Line2D([x0 + w] * len(ys), ys, transform=fig.transFigure, linestyle="none", marker=TICKRIGHT,
                       markersize=size, markeredgewidth=rc["ytick.major.width"], color=rc["ytick.color"])
        dx = (size + pad) / 72.0 * fig.dpi / fig.bbox.width  # the labels' distance from the bar [figure fraction]
        labels = [Text(x0 + w + dx, y, s, transform=fig.transFigure, fontsize=rc["ytick.labelsize"],
                       va=rc["ytick.alignment"], ha="left") for y, (_, s) in zip(ys, shown)]
        pieces = [image, outline, marks, *labels]
        extras = []
        if offset:  # the labels' common offset or power of ten (e.g. "1e-5"), above the bar as matplotlib puts it
            extras.append(Text(x0 + w, y0 + h + pad / 72.0 * fig.dpi / fig.bbox.height, offset,
                               transform=fig.transFigure, fontsize=rc["ytick.labelsize"], va="bottom", ha="left"))
            pieces += extras
        for piece in pieces:
            piece.set_figure(fig)
        right = box.x1 + (size / 72.0 * fig.dpi if ys else 0.0)
        if labels:
            right = max(right, Bbox.union([t.get_window_extent(renderer) for t in labels]).x1)
        x = (right + rc["axes.labelpad"] / 72.0 * fig.dpi) / fig.bbox.width
        title = Text(x, y0 + 0.5 * h, self.label, transform=fig.transFigure, fontsize=rc["axes.labelsize"],
                     rotation=90, rotation_mode="anchor", va="top", ha="center")
        title.set_figure(fig)
        for piece in (*pieces, title):
            piece.draw(renderer)
        self.ticks = np.array([v for v, _ in shown])
        self.tick_labels, self.label_text, self.offset_text = labels, title, offset
        self._extent = Bbox.union([box, *(t.get_window_extent(renderer) for t in (*labels, title, *extras))])
        self.stale = False

    def get_window_extent(self, renderer=None):
        """The bar, its labels and its label [display units] as last drawn."""
        from matplotlib.transforms import Bbox

        return self._extent if self._extent is not None else Bbox.null()

    def get_tightbbox(self, renderer=None):
        return self.get_window_extent(renderer)
