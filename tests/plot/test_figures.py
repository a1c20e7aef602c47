"""Fixed layouts, saving and pictures drawn in forked processes (bearingfe.plot.figures)."""

from __future__ import annotations

import os

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


def _job(path, text):
    def job():
        path.write_text(f"{text} {os.getpid()}")
        return [path.name]
    return job


def test_jobs_run_in_two_processes_and_keep_their_order(tmp_path):
    """Four jobs on two workers: this process draws the 1st and 3rd, a forked child the others; the
    results come back in the jobs' order."""
    jobs = [_job(tmp_path / f"{k}.txt", k) for k in range(4)]
    assert figures.draw_in_parallel(jobs, processes=2) == [["0.txt"], ["1.txt"], ["2.txt"], ["3.txt"]]
    pids = [int((tmp_path / f"{k}.txt").read_text().split()[1]) for k in range(4)]
    assert pids[0] == pids[2] == os.getpid() and pids[1] == pids[3] != os.getpid()
    figures.draw_in_parallel(jobs, processes=1)
    assert all(int((tmp_path / f"{k}.txt").read_text().split()[1]) == os.getpid() for k in range(4))


def test_an_error_in_a_child_is_raised_here(tmp_path):
    def bad():
        raise ValueError("no such design")

    with pytest.raises(ValueError, match="no such design"):
        figures.draw_in_parallel([_job(tmp_path / "a.txt", 0), bad], processes=2)
