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

