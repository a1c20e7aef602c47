"""Regression: slot pockets keep their rounded ends when meshed.

gmsh bends a 180-degree circle arc given by three points (start, centre,
end) into the slot; the ends are drawn as quarter arcs instead. Expected
value: the analytic slot area ``L w + pi (w/2)^2``; the meshed hole is an
inscribed polygon, so it may be smaller by at most the chord segments
(size 0.02 on radius 0.05: below 0.5 %).
"""

import numpy as np
import pytest

from bearingfe import Slot, Surface, mesh_surface


@pytest.mark.parametrize("angle", [0.0, 0.3])
def test_slot_hole_area(angle):
    slot = Slot((0.0, 0.0), 0.4, 0.1, angle)
    surface = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=(slot,))
    mesh = mesh_surface(surface, 0.02)
    p, t = mesh.mesh.p, mesh.mesh.t
    d1, d2 = p[:, t[1]] - p[:, t[0]], p[:, t[2]] - p[:, t[0]]
    film_area = 0.5 * np.abs(d1[0] * d2[1] - d1[1] * d2[0]).sum()
    hole = surface.area - film_area
    assert hole <= slot.area + 1e-12
    assert hole == pytest.approx(slot.area, rel=5e-3)
