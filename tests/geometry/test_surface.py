"""Support-surface geometry: areas, point tests and layout validation.

Expected areas are closed forms of elementary plane figures; every invalid
layout below must raise ValueError naming the culprit.
"""

import math

import numpy as np
import pytest

from bearingfe import Circle, Ellipse, Polygon, Rectangle, Slot, Surface


def test_shape_areas_match_closed_forms():
    # pi r^2, pi a b, w h, stadium L w + pi (w/2)^2, shoelace of a unit right triangle
    assert Circle((0.1, 0.0), 0.2).area == pytest.approx(math.pi * 0.04, rel=1e-15)
    assert Ellipse((0, 0), (0.3, 0.1), 0.4).area == pytest.approx(math.pi * 0.03, rel=1e-15)
    assert Rectangle((0, 0), (0.3, 0.2), angle=0.7).area == pytest.approx(0.06, rel=1e-12)
    assert Slot((0, 0), 0.4, 0.1).area == pytest.approx(0.04 + math.pi * 0.0025, rel=1e-15)
    assert Polygon(((0, 0), (0, 1), (1, 0))).area == pytest.approx(0.5, rel=1e-15)


def test_boundary_polylines_enclose_the_stated_area():
    # a fine polyline of a smooth curve has the curve's area up to O(1/n^2)
    from bearingfe.geometry.surface import _signed_area

    for shape in (Circle((0, 0), 0.2), Ellipse((0.1, 0), (0.3, 0.1), 0.5), Slot((0, 0), 0.4, 0.1, 0.3)):
        xy = shape.boundary(4000)
        assert _signed_area(xy) == pytest.approx(shape.area, rel=1e-5)  # positive: counter-clockwise


def test_polygon_is_stored_counter_clockwise_and_contains_is_strict():
    clockwise = Polygon(((0, 0), (0, 1), (1, 1), (1, 0)))
    from bearingfe.geometry.surface import _signed_area

    assert _signed_area(np.array(clockwise.points).T) > 0
    assert clockwise.contains(np.array([0.5, 1.5, 0.999]), np.array([0.5, 0.5, 0.001])).tolist() == [True, False, True]


def test_contains_rotated_shapes():
    e = Ellipse((0, 0), (0.3, 0.1), angle=math.pi / 2)  # long axis along z
    assert e.contains(0.0, 0.25) and not e.contains(0.25, 0.0)
    s = Slot((0, 0), 0.4, 0.1, angle=math.pi / 2)
    assert s.contains(0.0, 0.24) and not s.contains(0.0, 0.26) and not s.contains(0.06, 0.0)


def test_surface_properties():
    inlets = (Circle((0.0, 0.0), 0.1), Rectangle((0.3, 0.0), (0.1, 0.2)))
    s = Surface(arc=(-0.5, 0.5), half_width=0.4, inlets=inlets)
    area = 1.0 * 0.8
    pockets = math.pi * 0.01 + 0.02
    assert s.area == pytest.approx(area, rel=1e-12)
    assert s.inlet_area == pytest.approx(pockets, rel=1e-12)
    assert s.inlet_fraction == pytest.approx(pockets / area, rel=1e-12)
    assert s.film_area == pytest.approx(area - pockets, rel=1e-12)
    assert s.bounds == pytest.approx((-0.5, 0.5, -0.4, 0.4), abs=1e-12)
    assert s.is_rectangular and not Surface(outer=Circle((0, 0), 1.0)).is_rectangular
    mask = s.in_pocket(np.array([0.0, 0.3, 0.15, 0.3]), np.array([0.05, 0.09, 0.0, 0.11]))
    assert mask.tolist() == [True, True, False, False]
    # the gap between the circle (edge at 0.1) and the rectangle (edge at 0.25)
    assert s.min_gap() == pytest.approx(0.15, abs=2e-3)


def test_single_shape_is_accepted_as_inlets():
    s = Surface(inlets=Circle((0, 0), 0.1))
    assert len(s.inlets) == 1


# -- invalid inputs ------------------------------------------------------------

@pytest.mark.parametrize("make, words", [
    (lambda: Circle((0, 0), 0.0), "Circle.radius"),
    (lambda: Circle((0, 0), -0.1), "Circle.radius"),
    (lambda: Circle((math.nan, 0), 0.1), "Circle.center"),
    (lambda: Circle((0, 0, 0), 0.1), "Circle.center"),
    (lambda: Ellipse((0, 0), (0.1, 0.0)), "Ellipse.semi_axes"),
    (lambda: Ellipse((0, 0), (0.1, 0.1), math.inf), "Ellipse.angle"),
    (lambda: Rectangle((0, 0), (0.1, -0.1)), "Rectangle.size"),
    (lambda: Rectangle((0, 0), (0.0, 0.1)), "Rectangle.size"),
    (lambda: Slot((0, 0), 0.0, 0.1), "Slot.length"),
    (lambda: Slot((0, 0), 0.2, -0.1), "Slot.width"),
    (lambda: Slot((0, 0), 0.2, 0.1, math.nan), "Slot.angle"),
    (lambda: Polygon(((0, 0), (1, 0))), "at least 3"),
    (lambda: Polygon(((0, 0), (1, 0), (2, 0))), "zero area"),
    (lambda: Polygon(((0, 0), (1, 0), (1, 0), (0, 1))), "repeated"),
    (lambda: Polygon(((0, 0), (1, 1), (1, 0), (0, 1))), "self-intersecting"),
    (lambda: Polygon(5), "Polygon.points"),
])
def test_degenerate_shapes_are_rejected(make, words):
    with pytest.raises(ValueError, match=words):
        make()


@pytest.mark.parametrize("kwargs, words", [
    (dict(arc=(0.5, -0.5)), "Surface.arc"),
    (dict(arc=(0.0, 7.0)), "Surface.arc"),
    (dict(arc=(0.0, math.nan)), "Surface.arc"),
    (dict(half_width=0.0), "Surface.half_width"),
    (dict(half_width=-1.0), "Surface.half_width"),
    (dict(inlets=("circle",)), r"Surface.inlets\[0\]"),
    (dict(outer=3.0), "Surface.outer"),
    # pocket fully outside the rectangle [-0.5, 0.5] x [-0.5, 0.5]
    (dict(inlets=(Circle((0.7, 0.0), 0.1),)), r"inlets\[0\].*not inside"),
    # pocket crossing the edge phi = 0.5
    (dict(inlets=(Circle((0.45, 0.0), 0.1),)), r"inlets\[0\].*not inside"),
    # pocket touching the edge exactly (tangent at (0.5, 0))
    (dict(inlets=(Circle((0.4, 0.0), 0.1),)), r"inlets\[0\]"),
    # pocket inside but closer than the tolerance 1e-4 * extent
    (dict(inlets=(Circle((0.4 - 1e-6, 0.0), 0.1),)), "touches the outer contour"),
    (dict(inlets=(Rectangle((0.0, 0.45), (0.2, 0.1 + 1e-7)),)), r"inlets\[0\]"),
    # overlapping, tangent and nested pockets
    (dict(inlets=(Circle((0, 0), 0.1), Circle((0.1, 0), 0.1))), "overlap or touch"),
    (dict(inlets=(Circle((0, 0), 0.1), Circle((0.2, 0), 0.1))), "overlap or touch"),
    (dict(inlets=(Circle((0, 0), 0.2), Circle((0, 0), 0.05))), "overlap or touch"),
    (dict(inlets=(Circle((0, 0), 0.05), Circle((0, 0), 0.2))), "overlap or touch"),
    (dict(inlets=(Slot((0, 0), 0.3, 0.1), Rectangle((0, 0.1), (0.1, 0.1)))), "overlap or touch"),
    # a custom outline: pocket outside a circular pad
    (dict(outer=Circle((0, 0), 0.5), inlets=(Circle((0.6, 0), 0.05),)), "not inside"),
])
def test_invalid_layouts_are_rejected(kwargs, words):
    with pytest.raises(ValueError, match=words):
        Surface(**kwargs)


def test_valid_layout_close_to_the_tolerance_is_accepted():
    # a gap of 1e-3 (ten times the 1e-4 tolerance) to the edge and between pockets
    s = Surface(inlets=(Circle((0.399, 0.0), 0.1), Circle((0.198, 0.0), 0.1)))
    assert s.min_gap() == pytest.approx(1e-3, rel=0.05)
