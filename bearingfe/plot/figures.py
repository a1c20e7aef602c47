"""Fixed figure layout and saving, shared by the picture modules (matplotlib object API).

The pictures place their axes with margins and gaps given in inches
(:func:`frame`) instead of a layout engine: matplotlib's constrained or tight
layout measures every tick label and title before it draws, which cost more
than the physics of the main scene. :func:`save` writes with the package's
resolution, PNGs with light compression (files a little larger, several
times faster to write).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["DPI", "PNG_COMPRESSION", "frame", "title", "ruled_table", "save"]

#: Resolution of the saved pictures [dots per inch].
DPI = 100
#: zlib level of the saved PNGs (0 none ... 9 smallest; PIL's default 6 takes several times longer).
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
    """Save ``fig`` at :data:`DPI` (format from the suffix; PNGs at :data:`PNG_COMPRESSION`); returns ``fig``."""
    if path is not None:
        png = Path(path).suffix.lower() == ".png"
        fig.savefig(path, dpi=DPI, **({"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if png else {}))
    return fig
