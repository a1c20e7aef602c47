"""Off-screen pyvista pictures of pressure and film: files exist and show a field.

A picture counts as non-blank when it has many distinct colours (a colour
map, not just background and text) and at least a tenth of it is not white.
"""

import math
import subprocess
import sys

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.plot import fields
from tests.helpers import ROOT


def _check_picture(path, min_colours=50):
    import matplotlib.image as mpimg

    assert path.is_file() and path.stat().st_size > 2000
    img = mpimg.imread(path)[..., :3]
    colours = np.unique((img.reshape(-1, 3) * 255).round().astype(int), axis=0)
    assert len(colours) >= min_colours
    assert np.mean(np.any(img < 0.95, axis=-1)) > 0.1
    return img


@pytest.fixture(scope="module")
def shoe():
    return bf.Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=[bf.Circle((0.0, 0.0), 0.16)])


@pytest.fixture(scope="module")
def result_p2(shoe):
    mesh = bf.mesh_surface(shoe, 0.1, order=2)
    return bf.solve_reynolds(mesh, bf.CosineFilm(0.6, 0.3), inlet_pressure=2.0, element="P2")


@pytest.fixture(scope="module")
def result_signed():
    # plain shoe, thinnest film inside the arc: pressure positive upstream, negative downstream
    mesh = bf.mesh_surface(bf.Surface(arc=(-0.5, 0.5), half_width=0.4), 0.1)
    return bf.solve_reynolds(mesh, bf.CosineFilm(0.6, math.pi))


def test_import_bearingfe_loads_no_plotting_library():
    code = ("import os, sys, bearingfe, bearingfe.plot, bearingfe.cli, bearingfe.io.writers; "
            "bad = [m for m in ('pyvista', 'vtk', 'matplotlib.pyplot') if m in sys.modules]; "
            "assert not bad, bad; assert 'VTK_DEFAULT_OPENGL_WINDOW' not in os.environ")
    env = {k: v for k, v in __import__("os").environ.items() if k != "VTK_DEFAULT_OPENGL_WINDOW"}
    subprocess.run([sys.executable, "-c", code], check=True, env=env, cwd=str(ROOT))


def test_grid_carries_vertex_values_of_p2(result_p2):
    grid = fields.field_grid(result_p2)
    m = result_p2.basis.mesh
    assert grid.n_points == m.nvertices and grid.n_cells == m.nelements
    # scikit-fem numbers vertex dofs first: the grid holds exactly those values
    np.testing.assert_array_equal(grid.point_data["p"], result_p2.pressure[: m.nvertices])
    np.testing.assert_allclose(grid.points[:, :2], m.p[:, : m.nvertices].T)


def test_wrapped_grid_lies_on_the_cylinder_and_warps_by_pressure(result_p2):
    plain = fields.field_grid(result_p2, view="wrapped")
    np.testing.assert_allclose(np.hypot(plain.points[:, 0], plain.points[:, 1]), 1.0, atol=1e-12)
    warped = fields.field_grid(result_p2, view="wrapped", warp=0.2)
    r = np.hypot(warped.points[:, 0], warped.points[:, 1])
    p = warped.point_data["p"]
    # radius 1 + warp * p / max|p| exactly
    np.testing.assert_allclose(r, 1.0 + 0.2 * p / np.abs(p).max(), atol=1e-12)


def test_pocket_outline_and_patch_follow_the_pocket(result_p2, shoe):
    lines = fields.outline_lines(result_p2, boundary="inlet")
    rr = np.hypot(lines.points[:, 0], lines.points[:, 1])
    np.testing.assert_allclose(rr, 0.16, rtol=1e-9)  # mesh nodes sit on the circle
    patch = fields.pocket_patches(result_p2, value=2.0)
    # area of the inscribed polygon: below pi r^2, within the chord error of the mesh
    assert 0.9 * math.pi * 0.16**2 < patch.area < math.pi * 0.16**2
    np.testing.assert_allclose(np.hypot(patch.points[:, 0], patch.points[:, 1]), 0.16, rtol=1e-9)
    assert np.all(patch.point_data["p"] == 2.0)
    exact = fields.pocket_patches(result_p2, surface=shoe, value=2.0)
    assert exact.area == pytest.approx(math.pi * 0.16**2, rel=1e-3)  # 360-gon


def test_zero_contour_where_pressure_changes_sign(result_signed):
    grid = fields.field_grid(result_signed)
    p = grid.point_data["p"]
    assert p.min() < 0 < p.max()
    line = fields._zero_contour(result_signed, grid, "p", p)
    # h = 1 - 0.6 cos(phi) is symmetric about phi = 0 and the wedge source odd: p = 0 on phi = 0
    assert np.abs(line.points[:, 0]).max() < 0.01  # nodal values on an unsymmetric mesh, h = 0.1
    assert np.ptp(line.points[:, 1]) > 0.79  # runs across the whole width 2a = 0.8


@pytest.mark.parametrize("view, warp", [("unwrapped", 0.0), ("wrapped", 0.0), ("wrapped", 0.2)])
def test_pressure_picture_is_non_blank(tmp_path, result_p2, view, warp):
    path = fields.pressure_picture(result_p2, tmp_path / f"p_{view}.png", view=view, warp=warp)
    _check_picture(path)


def test_pressure_picture_with_exact_outlines_and_cavitation_line(tmp_path, result_signed, shoe):
    img = _check_picture(fields.pressure_picture(result_signed, tmp_path / "p.png"))
    # the p = 0 contour is drawn in pure red
    red = (img[..., 0] > 0.9) & (img[..., 1] < 0.1) & (img[..., 2] < 0.1)
    assert red.sum() > 100


def test_film_picture_is_non_blank(tmp_path, result_p2, shoe):
    _check_picture(fields.film_picture(result_p2, tmp_path / "h.png", surface=shoe))
    _check_picture(fields.film_picture(result_p2, tmp_path / "hw.png", view="wrapped"))


def test_bad_view_and_warp_are_rejected(tmp_path, result_p2):
    with pytest.raises(ValueError, match="view must be one of"):
        fields.pressure_picture(result_p2, tmp_path / "x.png", view="side")
    with pytest.raises(ValueError, match="warp"):
        fields.pressure_picture(result_p2, tmp_path / "x.png", view="wrapped", warp=-1.0)
    assert not (tmp_path / "x.png").exists()


def test_scaled_pressure_picture_changes_only_the_labels(tmp_path, result_p2):
    # p shown in MPa: the colour map follows the scaled range, so the field's colours are identical and
    # only the scalar bar's numbers and title differ (a few per cent of the pixels, measured ~1 %)
    plain = _check_picture(fields.pressure_picture(result_p2, tmp_path / "p.png"))
    scaled = _check_picture(fields.pressure_picture(result_p2, tmp_path / "p_mpa.png", scale=12.5, unit="MPa"))
    differ = np.any(np.abs(plain.astype(float) - scaled.astype(float)) > 1e-6, axis=-1)
    assert 0 < differ.mean() < 0.05
    with pytest.raises(ValueError, match="scale"):
        fields.pressure_picture(result_p2, tmp_path / "x.png", scale=0.0)
    with pytest.raises(ValueError, match="unit"):
        fields.film_picture(result_p2, tmp_path / "x.png", scale=1.0, unit="")
