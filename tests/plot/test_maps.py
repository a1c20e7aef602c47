"""Field maps with matplotlib: P2 fields sampled on a refined display mesh, panels with titles and colour bars.

Stand-in results carry only what the maps read (``basis``, ``pressure``, ``film``, ``inlet_pressure``).
"""

from dataclasses import dataclass

import numpy as np
import pytest
from skfem import Basis, ElementTriP1, ElementTriP2, MeshTri

import bearingfe as bf
from bearingfe.plot.colour_bars import ColourBar
from bearingfe.plot.maps import DISPLAY_TRIANGLES, Panel, field_panels, refinements, sampled


@dataclass(frozen=True)
class Stand:
    basis: object
    pressure: np.ndarray
    film: object
    inlet_pressure: float = 0.0
    cavitated: object = None


def _quadratic(x, y):
    return 1.0 - 2.0 * x**2 + 0.5 * x * y - y**2


def _result(element=ElementTriP2, n=2):
    mesh = MeshTri.init_tensor(np.linspace(-0.5, 0.5, n + 1), np.linspace(-0.4, 0.4, n + 1))
    basis = Basis(mesh, element())
    d = basis.doflocs
    return Stand(basis, _quadratic(d[0], d[1]), bf.CosineFilm(0.6, 0.3))


def test_p2_field_is_sampled_with_its_quadratic_variation():
    # P2 interpolation reproduces a quadratic exactly, so the display samples equal the function at
    # every display point, midway between the nodes too (a vertex-only P1 picture cannot)
    res = _result()
    xy, t, v = sampled(res, nrefs=2)
    assert xy.shape[1] > res.basis.mesh.p.shape[1] and t.shape[1] == 16 * res.basis.mesh.t.shape[1]
    np.testing.assert_allclose(v, _quadratic(xy[0], xy[1]), atol=1e-12)
    # the film is evaluated exactly at the display points: h = 1 + 0.6 cos(phi - 0.3)
    xy, _, h = sampled(res, kind="film", nrefs=1)
    np.testing.assert_allclose(h, 1 + 0.6 * np.cos(xy[0] - 0.3), rtol=1e-14)


def test_refinements_follow_the_element_and_the_mesh_size():
    assert refinements(_result(ElementTriP1)) == 0  # linear: nothing between the vertices to show
    coarse = _result(n=2)  # 8 triangles: split 3 times (8 * 4^3 = 512 display triangles)
    assert refinements(coarse) == 3
    fine = _result(n=40)  # 3200 triangles: once (12800 <= DISPLAY_TRIANGLES < 51200)
    assert refinements(fine) == 1 and 3200 * 4 <= DISPLAY_TRIANGLES < 3200 * 16


def test_panels_have_titles_units_colour_bars_and_the_zero_line(tmp_path):
    res = _result(n=6)
    # 0.5 at the centre, -0.06 at the corners (0.5 - 2 0.25 + 0.5 0.2 - 0.16): a p = 0 line is drawn
    signed = Stand(res.basis, res.pressure - 0.5, res.film)
    scale = bf.Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=50 * np.pi)
    p_mpa = (scale.pressure / 1e6, "MPa")
    rows = [[Panel(signed, "pressure", *p_mpa, radius=0.05, title=f"design {j}, beta = {10 * j} deg")
             for j in range(2)],
            [Panel(signed, "film", scale.clearance * 1e6, "um", radius=0.05, title="film"), None]]
    fig = field_panels(rows, tmp_path / "maps.png", title="comparison")
    assert (tmp_path / "maps.png").stat().st_size > 5000
    maps = [ax for ax in fig.axes if ax.get_title()]
    bars = [a for a in fig.artists if isinstance(a, ColourBar)]
    assert fig.axes == maps  # the colour bars are artists of the figure, not axes
    assert [ax.get_title() for ax in maps] == ["design 0, beta = 0 deg", "design 1, beta = 10 deg", "film"]
    assert [b.label for b in bars] == ["p [MPa]", "p [MPa]", "h [um]"]
    assert all(ax.get_xlabel() == "phi [deg]" and ax.get_ylabel() == "z [mm]" for ax in maps)
    # the pressure colours span the scaled field: its largest value, 0.5 at the centre, times 29.45 MPa
    lo, hi = maps[0].collections[0].get_clim()
    assert hi == pytest.approx(0.5 * scale.pressure / 1e6, rel=1e-9) and lo < 0
    # axes in degrees and mm: the arc -0.5..0.5 rad is -28.6..28.6 deg, the width +-0.4 R0 = +-20 mm
    x, y = maps[0].collections[0]._triangulation.x, maps[0].collections[0]._triangulation.y
    assert (x.min(), x.max()) == pytest.approx((-np.degrees(0.5), np.degrees(0.5)))
    assert (y.min(), y.max()) == pytest.approx((-20.0, 20.0))
    legend = maps[0].get_legend()
    assert legend is not None and [t.get_text() for t in legend.get_texts()] == ["p = 0"]
    assert fig._suptitle.get_text() == "comparison"


def test_map_axes_and_colour_bars_draw_a_few_ticks_at_round_steps():
    """At most MAP_TICKS intervals on each axis and colour bar, spaced 1, 2, 2.5 or 5 times a power of ten
    (matplotlib's MaxNLocator): the map of -28.6..28.6 deg by -20..20 mm draws -20, 0, 20 on both axes."""
    from bearingfe.plot.maps import MAP_TICKS

    from matplotlib.backends.backend_agg import FigureCanvasAgg

    res = _result(n=6)
    fig = field_panels([[Panel(res, "pressure", 29.45, "MPa", radius=0.05, title="p")]])
    FigureCanvasAgg(fig).draw()
    (ax,), (bar,) = fig.axes, [a for a in fig.artists if isinstance(a, ColourBar)]
    for axis in (ax.xaxis, ax.yaxis, bar):
        if axis is bar:
            ticks = list(bar.ticks)
        else:
            lo, hi = sorted(axis.get_view_interval())
            ticks = [t for t in axis.get_ticklocs() if lo - 1e-9 <= t <= hi + 1e-9]
        assert 2 <= len(ticks) <= MAP_TICKS + 1
        step = np.diff(ticks)[0] / 10.0 ** np.floor(np.log10(np.diff(ticks)[0]))
        assert any(step == pytest.approx(s) for s in (1, 2, 2.5, 5))
    assert list(ax.get_xticks()[(ax.get_xticks() >= -28.6) & (ax.get_xticks() <= 28.6)]) == [-20.0, 0.0, 20.0]
