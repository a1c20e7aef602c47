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

__all__ = ["DPI", "PNG_COMPRESSION", "frame", "title", "save", "preload"]

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


def save(fig, path):
    """Save ``fig`` at :data:`DPI` (format from the suffix; PNGs at :data:`PNG_COMPRESSION`); returns ``fig``."""
    if path is not None:
        png = Path(path).suffix.lower() == ".png"
        fig.savefig(path, dpi=DPI, **({"pil_kwargs": {"compress_level": PNG_COMPRESSION}} if png else {}))
    return fig
