"""Plots of the machine models render to PNG with visible content."""

import numpy as np
import pytest

from bearingfe.mechanisms.files import load_mechanism
from bearingfe.plot.mechanisms import plot_crank_kinematics, plot_efficiency, plot_natural_frequencies
from tests.helpers import ROOT


def _check_png(path):
    import matplotlib.image as mpimg

    assert path.exists() and path.stat().st_size > 1000
    img = mpimg.imread(path)
    assert img.ndim == 3 and np.ptp(img[..., :3]) > 0.5  # non-uniform pixels
    return img


@pytest.mark.parametrize(
    "func, file",
    [
        (plot_crank_kinematics, "snt32.toml"),
        (plot_efficiency, "hpt_mill.toml"),
        (plot_natural_frequencies, "converter_tilt_d816.toml"),
    ],
)
def test_plot_to_png(tmp_path, func, file):
    out = tmp_path / f"{func.__name__}.png"
    fig = func(load_mechanism(ROOT / "mechanisms" / file), path=out)
    _check_png(out)
    assert fig.axes and all(len(ax.lines) > 0 for ax in fig.axes)


def test_plot_into_given_axes(tmp_path):
    from matplotlib.figure import Figure

    fig = Figure()
    ax = fig.add_subplot()
    back = plot_crank_kinematics(load_mechanism(ROOT / "mechanisms" / "snt32.toml"), ax=ax)
    assert back is fig and len(ax.lines) == 6
    fig.savefig(tmp_path / "k.png")
    _check_png(tmp_path / "k.png")
