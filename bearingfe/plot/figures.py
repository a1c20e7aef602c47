"""Fixed figure layout and saving, shared by the picture modules (matplotlib object API).

The pictures place their axes with margins and gaps given in inches
(:func:`frame`) instead of a layout engine: matplotlib's constrained or tight
layout measures every tick label and title before it draws, which cost more
than the physics of the main scene. :func:`save` writes with the package's
resolution, PNGs with light compression (files a little larger, several
times faster to write).
"""

from __future__ import annotations

from contextlib import contextmanager
from pathlib import Path

import numpy as np

__all__ = ["DPI", "PNG_COMPRESSION", "frame", "title", "ruled_table", "save", "write_png", "drawn_ticks",
           "ticks_in_view"]

#: Resolution of the saved pictures [dots per inch].
DPI = 100
#: zlib level of the saved PNGs (0 none ... 9 smallest; 6, PIL's default, takes several times longer).
PNG_COMPRESSION = 1


def frame(fig, *, top: float, bottom: float, left: float = 0.8, right: float = 0.25, nrows: int = 1, ncols: int = 1,
          wgap: float = 0.0, hgap: float = 0.0, **kwargs):
    """A :class:`~matplotlib.gridspec.GridSpec` of ``fig`` whose margins and gaps are given in inches.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    top, bottom, left, right : float
        Distance of the grid from the figure's edges [in] (room for titles, labels, tick labels).
    nrows, ncols : int
    wgap, hgap : float
        Gaps between the columns and between the rows [in].
    **kwargs
        Passed on (e.g. ``height_ratios``).
    """
    w, h = fig.get_size_inches()
    width = (w - left - right - (ncols - 1) * wgap) / ncols
    height = (h - top - bottom - (nrows - 1) * hgap) / nrows
    if width <= 0 or height <= 0:
        raise ValueError(f"figure of {w:.3g} x {h:.3g} in too small for its margins and gaps")
    return fig.add_gridspec(nrows, ncols, left=left / w, right=1.0 - right / w, top=1.0 - top / h,
                            bottom=bottom / h, wspace=wgap / width, hspace=hgap / height, **kwargs)


def title(ax, text: str, **kwargs):
    """Title ``ax`` with ``text`` at the top edge of the axes (matplotlib's default place), fixed there.

    Matplotlib otherwise moves an axes title above whatever is drawn over the axes at every draw, which
    measures the tick labels of the axes (and of its twins) first; the pictures here have nothing above
    their axes (no top ticks, no offset text), so the fixed title lands where the measured one would,
    without the measuring. ``kwargs`` go to ``ax.set_title``.
    """
    return ax.set_title(text, y=1.0, **kwargs)


def ruled_table(ax, rows, col_labels, col_widths, *, fontsize: float = 9, row_height: float = 0.235,
                pad: float = 0.012, emphasis=None):
    """A ruled table at the top of ``ax`` (its frame and ticks hidden): one text per cell and the rules as one line.

    Matplotlib's ``Axes.table`` makes a rectangle and a text per cell and measures every text at each draw to
    place it (a quarter of the main scene's summary page); here a cell's text is placed at its row's middle,
    left-aligned in the first column and centred in the others, and measured only to be drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    rows : sequence of sequences of str
        The body, row by row.
    col_labels : sequence of str
        The header row.
    col_widths : sequence of float
        Column widths as fractions of the axes' width (the table is centred).
    fontsize : float
        [pt]
    row_height : float
        [in]
    pad : float
        Space left of a left-aligned cell, fraction of the axes' width.
    emphasis : callable, optional
        ``emphasis(text) -> dict`` of text properties for a body cell (e.g. red for a violated limit), or None.

    Returns
    -------
    list of matplotlib.text.Text
        The cells' texts, header first, row by row.
    """
    ax.axis("off")
    fig = ax.get_figure()
    dy = row_height / (ax.get_position().height * fig.get_size_inches()[1])  # a row, fraction of the axes
    left = 0.5 * (1.0 - sum(col_widths))
    edges = [left]
    for w in col_widths:
        edges.append(edges[-1] + w)
    table = [list(col_labels), *(list(r) for r in rows)]
    texts = []
    for i, row in enumerate(table):
        y = 1.0 - (i + 0.5) * dy
        for j, cell in enumerate(row):
            props = emphasis(cell) if (emphasis is not None and i > 0) else None
            x, ha = (edges[j] + pad, "left") if j == 0 else (0.5 * (edges[j] + edges[j + 1]), "center")
            texts.append(ax.text(x, y, cell, ha=ha, va="center", fontsize=fontsize, transform=ax.transAxes,
                                 **(props or {})))
    bottom = 1.0 - len(table) * dy
    xs, ys = [], []
    for i in range(len(table) + 1):  # the rules: rows, then columns, as one polyline broken by NaNs
        xs += [edges[0], edges[-1], float("nan")]
        ys += [1.0 - i * dy] * 2 + [float("nan")]
    for x in edges:
        xs += [x, x, float("nan")]
        ys += [1.0, bottom, float("nan")]
    ax.plot(xs, ys, color="k", lw=0.8, transform=ax.transAxes, clip_on=False)
    return texts


def save(fig, path):
    """Save ``fig`` at :data:`DPI` (format from the suffix); returns ``fig``.

    The ticks of plain axes are drawn by :func:`drawn_ticks` while the file is written (the figure returned
    keeps matplotlib's own ticks). A PNG is the Agg canvas's pixels written by :func:`write_png` (what
    ``savefig`` writes, in half the time); other formats go through ``savefig``."""
    if path is None:
        return fig
    if Path(path).suffix.lower() != ".png":
        with drawn_ticks(fig):
            fig.savefig(path, dpi=DPI)
        return fig
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    dpi = fig.get_dpi()
    fig.set_dpi(DPI)
    try:
        canvas = fig.canvas if isinstance(fig.canvas, FigureCanvasAgg) else FigureCanvasAgg(fig)
        with drawn_ticks(fig):
            canvas.draw()
        write_png(np.asarray(canvas.buffer_rgba()), path, DPI)
    finally:
        fig.set_dpi(dpi)
    return fig


def write_png(rgba: np.ndarray, path, dpi: float = DPI) -> None:
    """Write an image ``(height, width, 4)`` of 8-bit RGBA as a PNG file (RGB when every pixel is opaque).

    Every row is stored with PNG's "Sub" filter (each byte less the one a pixel before) and compressed by zlib
    at level :data:`PNG_COMPRESSION`: about half of PIL's time for its adaptive filters, the file a tenth larger.
    The resolution ``dpi`` [dots per inch] goes into the file (``pHYs``), as matplotlib writes it.
    """
    import struct
    import zlib

    image = np.asarray(rgba)
    if image.ndim != 3 or image.shape[2] != 4 or image.dtype != np.uint8:
        raise ValueError(f"rgba must be an (height, width, 4) uint8 array, got {image.dtype} {image.shape}")
    opaque = bool(image[:, :, 3].min() == 255)
    pixels = image[:, :, :3] if opaque else image
    height, width, channels = pixels.shape
    rows = np.empty((height, 1 + width * channels), dtype=np.uint8)  # the one buffer: filter byte, then bytes
    rows[:, 0] = 1  # Sub
    body = rows[:, 1:].reshape(height, width, channels)
    body[:, 0] = pixels[:, 0]
    np.subtract(pixels[:, 1:], pixels[:, :-1], out=body[:, 1:])  # modulo 256

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    per_metre = int(round(dpi / 0.0254))
    with open(path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n")
        out.write(chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2 if opaque else 6, 0, 0, 0)))
        out.write(chunk(b"pHYs", struct.pack(">IIB", per_metre, per_metre, 1)))
        out.write(chunk(b"IDAT", zlib.compress(memoryview(rows), PNG_COMPRESSION)))
        out.write(chunk(b"IEND", b""))


#: Tick parameters :func:`drawn_ticks` draws itself (an axis given any other keeps matplotlib's ticks).
_PLAIN_TICK_PARAMS = frozenset({"bottom", "top", "left", "right", "labelbottom", "labeltop", "labelleft",
                                "labelright", "gridOn", "grid_alpha", "grid_color", "grid_linewidth",
                                "grid_linestyle"})


@contextmanager
def drawn_ticks(fig):
    """Within the block, the major ticks, tick labels and grid lines of ``fig``'s plain axes are a few
    artists per axis instead of matplotlib's tick objects; restored after.

    Matplotlib makes one tick object per tick (three lines with markers and two texts, about a millisecond
    each) and measures their labels at every draw: in the main scene's pictures that was a third of their
    cost. Here each plain axis gets one marker line for its marks, one line for its grid and one text per
    shown label, placed as matplotlib places them (the tick size and pad, the labels' alignment, the
    axis label moved clear of the labels by its pad), with the locator's and formatter's values. An axis is
    plain when it is linear with default tick styles (only the sides, labels and grid style set), no minor
    ticks and no offset text (e.g. ``1e-5``); any other axis, and every axis sharing its ticker, keeps
    matplotlib's ticks. Drawn through the figure's Agg canvas (made if the figure has none).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    renderer = fig.canvas.get_renderer()
    axes = [axis for ax in fig.axes for axis in (ax.xaxis, ax.yaxis)]
    plans = [_tick_plan(axis) for axis in axes]
    # a ticker shared by several axes (``sharex``) is replaced for all of them or for none
    kept = {id(axis.major) for axis, plan in zip(axes, plans) if plan is None}
    plain = [plan for axis, plan in zip(axes, plans) if plan is not None and id(axis.major) not in kept]
    undo = []
    try:
        for p in plain:
            undo.append(_draw_plan(p, renderer))
        yield fig
    finally:
        for restore in reversed(undo):
            restore()


def ticks_in_view(locs, labels, lo: float, hi: float) -> list[tuple[float, str]]:
    """The ``(value, label)`` pairs of the ticks ``locs`` that lie in the view ``lo``..``hi`` (either order), as
    matplotlib decides it (inside, or outside by at most 1e-10 of the view's length)."""
    lo, hi = sorted((float(lo), float(hi)))
    slack = 1e-10 * (hi - lo)
    return [(float(v), t) for v, t in zip(locs, labels) if lo - slack <= v <= hi + slack]


def _tick_plan(axis) -> dict | None:
    """What :func:`drawn_ticks` draws for ``axis`` (ticks in view, labels, sides, grid), or None (not plain)."""
    import matplotlib as mpl
    from matplotlib.ticker import FixedFormatter, FuncFormatter, NullLocator, ScalarFormatter, StrMethodFormatter

    ax = axis.axes
    name = axis.axis_name
    params = axis.get_tick_params()
    if (ax.name != "rectilinear" or not ax.axison or not axis.get_visible() or axis.get_scale() != "linear"
            or not set(params) <= _PLAIN_TICK_PARAMS or not isinstance(axis.get_minor_locator(), NullLocator)
            or mpl.rcParams[f"{name}tick.direction"] != "out" or mpl.rcParams[f"{name}tick.minor.visible"]):
        return None
    formatter = axis.get_major_formatter()
    if not isinstance(formatter, (ScalarFormatter, FixedFormatter, FuncFormatter, StrMethodFormatter)):
        return None
    sides = ("bottom", "top") if name == "x" else ("left", "right")
    marks = [params.get(s, mpl.rcParams[f"{name}tick.{s}"]) for s in sides]
    labels = [params.get(f"label{s}", mpl.rcParams[f"{name}tick.label{s}"]) for s in sides]
    locs = np.asarray(axis.get_majorticklocs(), dtype=float)  # the locator's values, as matplotlib draws them
    texts = formatter.format_ticks(locs) if locs.size else []
    if isinstance(formatter, ScalarFormatter) and formatter.get_offset():
        return None
    shown = ticks_in_view(locs, texts, *axis.get_view_interval())
    return {"axis": axis, "name": name, "sides": sides, "marks": marks, "labels": labels, "shown": shown,
            "grid": params.get("gridOn", False), "grid_style": {k[5:]: v for k, v in params.items()
                                                              if k.startswith("grid_")}}


def _draw_plan(p: dict, renderer):
    """Draw plan ``p`` of :func:`_tick_plan` into its axes; returns the function that undoes it."""
    import matplotlib as mpl
    from matplotlib.lines import TICKDOWN, TICKLEFT, TICKRIGHT, TICKUP, Line2D
    from matplotlib.text import Text
    from matplotlib.ticker import NullLocator
    from matplotlib.transforms import Bbox, ScaledTranslation

    axis, name = p["axis"], p["name"]
    ax, fig = axis.axes, axis.axes.get_figure(root=True)
    rc = mpl.rcParams
    size, pad, width = rc[f"{name}tick.major.size"], rc[f"{name}tick.major.pad"], rc[f"{name}tick.major.width"]
    color = rc[f"{name}tick.color"]
    label_color = rc[f"{name}tick.labelcolor"]
    label_color = color if label_color == "inherit" else label_color
    fontsize = rc[f"{name}tick.labelsize"]
    zorder = axis.get_zorder()
    values = [v for v, _ in p["shown"]]
    artists, texts = [], {}
    locator, default_locator, labelpad = axis.get_major_locator(), axis.isDefault_majloc, axis.labelpad
    axis.set_major_locator(NullLocator())  # no tick objects; the spine no longer pads for them
    axis.isDefault_majloc = default_locator
    for k, side in enumerate(p["sides"]):
        where = "tick1" if k == 0 else "tick2"
        base = ax.get_xaxis_transform(which=where) if name == "x" else ax.get_yaxis_transform(which=where)
        if p["marks"][k] and values:
            marker = ((TICKDOWN, TICKUP) if name == "x" else (TICKLEFT, TICKRIGHT))[k]
            xy = (values, [k] * len(values)) if name == "x" else ([k] * len(values), values)
            artists.append(Line2D(*xy, transform=base, linestyle="none", marker=marker, markersize=size,
                                  markeredgewidth=width, color=color, zorder=zorder, clip_on=False))
        if p["labels"][k]:
            shift = (size + pad) / 72.0 * (-1 if k == 0 else 1)
            offset = ScaledTranslation(0, shift, fig.dpi_scale_trans) if name == "x" else \
                ScaledTranslation(shift, 0, fig.dpi_scale_trans)
            if name == "x":
                align = {"va": "top" if k == 0 else "bottom", "ha": rc["xtick.alignment"]}
            else:
                align = {"va": rc["ytick.alignment"], "ha": "right" if k == 0 else "left"}
            texts[side] = [Text(*((v, k) if name == "x" else (k, v)), s, transform=base + offset,
                                fontsize=fontsize, color=label_color, zorder=zorder, clip_on=False, **align)
                           for v, s in p["shown"] if s]
            artists += texts[side]
    if p["grid"] and values:
        style = {"color": rc["grid.color"], "linewidth": rc["grid.linewidth"], "linestyle": rc["grid.linestyle"],
                 "alpha": rc["grid.alpha"], **p["grid_style"]}
        nan = [np.nan] * len(values)
        across = np.ravel(np.column_stack([np.zeros(len(values)), np.ones(len(values)), nan]))
        along = np.ravel(np.column_stack([values, values, nan]))
        grid = ax.get_xaxis_transform(which="grid") if name == "x" else ax.get_yaxis_transform(which="grid")
        artists.append(Line2D(*((along, across) if name == "x" else (across, along)), transform=grid,
                              zorder=zorder, **style))
    for artist in artists:  # marks and labels unclipped (made so), the grid clipped to the axes
        ax.add_artist(artist)
    side = axis.get_label_position()
    if axis.get_label_text() and side in p["sides"]:
        # matplotlib puts the label ``labelpad`` beyond the tick labels (or the marks): as far from the spine
        k = p["sides"].index(side)
        spine = ax.spines.get(side, ax).get_window_extent(renderer)
        edge = [spine.y0, spine.y1, spine.x0, spine.x1][("bottom", "top", "left", "right").index(side)]
        reach = size / 72.0 * fig.dpi if p["marks"][k] and values else 0.0
        shown = texts.get(side, [])
        if shown:
            box = Bbox.union([t.get_window_extent(renderer) for t in shown])
            far = [box.y0, box.y1, box.x0, box.x1][("bottom", "top", "left", "right").index(side)]
            reach = max(reach, abs(edge - far))
        axis.labelpad = labelpad + reach * 72.0 / fig.dpi

    def undo() -> None:
        for artist in artists:
            artist.remove()
        axis.set_major_locator(locator)
        axis.isDefault_majloc = default_locator
        axis.labelpad = labelpad

    return undo
