"""The real shoe body (bearingfe.elastic.shoe): gmsh tetrahedra, linear elasticity, compliance on the film dofs.

Expected values: the flat block clamped at its back is the problem of the tensor-mesh model
(bearingfe.elastic.block_compliance), which it must match within that model's own mesh error; a body growing
in depth and width approaches the elastic half-space (Love's rectangle, bearingfe.elastic.half_space)
from below; reciprocity (``M C`` symmetric: the load and the read-out are adjoint) holds to round-off;
a conforming displacement model is too stiff, so the compliance energy under uniform pressure grows
under refinement towards its limit with shrinking steps (measured sequences quoted at each test).
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe import Circle, Material, Scale, Surface, mesh_surface, solve_reynolds
from bearingfe.elastic import half_space, block_compliance
from bearingfe.elastic.shoe import ShoeBody
from bearingfe.reynolds import operators
from bearingfe.core.schema import SchemaError
from bearingfe.elastic.shoe import mesh_shoe, overlay, shoe_compliance
from tests.helpers import ROOT

SCALE = Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08)  # the shipped pump
STEEL = Material("steel", 210e9, poisson_ratio=0.3)
BRONZE = Material("bronze", 110e9, poisson_ratio=0.34)
PLAIN = Surface(arc=(-0.6, 0.6), half_width=0.4)
POCKET = Surface(arc=(-0.6, 0.6), half_width=0.4, inlets=[Circle((0.0, 0.0), 0.1748)])


@pytest.fixture(scope="module")
def plain_mesh():
    return mesh_surface(PLAIN, 0.1)


def _norm(ops, v):
    return math.sqrt(v @ ops.mass @ v)


def test_clamped_block_matches_the_tensor_mesh_body(plain_mesh):
    # the same problem (a flat 15 mm steel block under a flat film, clamped over its back, uniform
    # pressure): the tensor-mesh P1 body converges slowly (its field moves by 0.85 % of its norm from
    # size 0.1 to 0.05, measured, most at the free corners); the gmsh P2 body lies 1.85 % from the
    # finer one: within 2.5 such steps (a first-order method's remaining error is about one step)
    ops = operators(plain_mesh, "P1")
    ones = np.ones(ops.basis.N)
    coarse, fine = (block_compliance(plain_mesh, SCALE, STEEL, 0.015, size=h).deflection(ones) for h in (0.1, 0.05))
    gmsh = shoe_compliance(plain_mesh, SCALE, STEEL, ShoeBody(0.015), flat_film=True)
    assert gmsh.model == "shoe" and gmsh.matrix.shape == (ops.basis.N, ops.basis.N)
    w = gmsh.deflection(ones)
    step = _norm(ops, coarse - fine)
    assert 0.005 < step / _norm(ops, w) < 0.012
    assert _norm(ops, w - fine) < 2.5 * step
    k = int(np.argmin(ops.basis.doflocs[0] ** 2 + ops.basis.doflocs[1] ** 2))
    assert w[k] == pytest.approx(fine[k], rel=0.005)  # the centre: 0.3 % apart (measured)


def test_reciprocity_to_round_off_with_pocket_lining_and_frictionless_seat():
    # M C = F^T K^-1 F: symmetric to round-off for any body; positive definite (K and M are)
    mesh = mesh_surface(POCKET, 0.2, order=2)
    body = ShoeBody(0.015, back="concentric", seat="frictionless", seat_radius=0.0125, lining=BRONZE,
                    lining_thickness=0.002)
    C = shoe_compliance(mesh, SCALE, STEEL, body, element="P2", film_size=0.15)
    S = operators(mesh, "P2").mass @ C.matrix
    assert np.abs(S - S.T).max() < 1e-12 * np.abs(S).max()
    assert np.linalg.eigvalsh(0.5 * (S + S.T)).min() > 0
    # the pocket column is the uniform load on the pocket: with a uniform film pressure it makes the
    # uniform load on the whole shoe, which pushes the film open everywhere
    w = C.deflection(np.ones(C.n_dofs), 1.0)
    assert w.min() > 0
    # a softer lining opens the film more (same mesh sizes, the lining replaced by steel)
    steel = shoe_compliance(mesh, SCALE, STEEL, ShoeBody(0.015, back="concentric", seat="frictionless",
                                                         seat_radius=0.0125, lining=STEEL, lining_thickness=0.002),
                            element="P2", film_size=0.15)
    assert np.mean(w) > np.mean(steel.deflection(np.ones(C.n_dofs), 1.0))


def test_body_approaches_the_half_space_as_it_grows(plain_mesh):
    # uniform pressure on the 60 x 40 mm shoe, a flat steel block clamped at its back growing in depth
    # and width: the opening at the centre grows towards the half-space's (Love) from below; measured
    # gaps 0.842 -> 0.658 -> 0.411 of the half-space value for 10 / 20 / 40 mm (the last 20 mm wider
    # on every side), as the tensor-mesh body does (tests/elastic/test_coupled.py)
    basis = operators(plain_mesh, "P1").basis
    k = int(np.argmin(basis.doflocs[0] ** 2 + basis.doflocs[1] ** 2))
    ones = np.ones(basis.N)
    half = half_space(plain_mesh, SCALE, STEEL).deflection(ones)[k]
    gaps = []
    for depth, margin in ((0.01, 0.0), (0.02, 0.0), (0.04, 0.02)):
        body = shoe_compliance(plain_mesh, SCALE, STEEL, ShoeBody(depth), flat_film=True, margin=margin,
                               size=0.3, film_size=0.15)
        gaps.append((half - body.deflection(ones)[k]) / half)
    assert 0 < gaps[2] < gaps[1] < gaps[0] < 1
    assert gaps[2] < 0.7 * gaps[1] and gaps[1] < 0.85 * gaps[0]
    # the eccentric as a half-space on top: the compliances add
    both = shoe_compliance(plain_mesh, SCALE, STEEL, ShoeBody(0.01), counterpart=STEEL, flat_film=True,
                           size=0.3, film_size=0.15)
    alone = shoe_compliance(plain_mesh, SCALE, STEEL, ShoeBody(0.01), flat_film=True, size=0.3, film_size=0.15)
    np.testing.assert_allclose(both.matrix, alone.matrix + half_space(plain_mesh, SCALE, STEEL).matrix,
                               rtol=1e-9, atol=1e-12)


def test_deflection_under_uniform_pressure_converges():
    # the curved shoe (bore R0, flat back 15 mm behind its apex, clamped over the back), uniform pressure,
    # body mesh sizes 0.2 / 0.14 / 0.1 R0 on the film: the compliance energy int w (film mass matrix)
    # grows 0.17776 -> 0.17988 -> 0.18131 with shrinking steps (0.07 R0: 0.18237, measured)
    mesh = mesh_surface(PLAIN, 0.2)
    ops = operators(mesh, "P1")
    ones = np.ones(ops.basis.N)
    energy = [ones @ ops.mass @ shoe_compliance(mesh, SCALE, STEEL, ShoeBody(0.015), film_size=h,
                                                size=2 * h).deflection(ones) for h in (0.2, 0.14, 0.1)]
    steps = np.diff(energy)
    assert np.all(steps > 0)
    assert steps[1] < 0.8 * steps[0]
    assert energy[-1] == pytest.approx(0.1813, rel=0.01)


def test_overlay_covers_both_triangulations():
    # the pieces of two unrelated triangulations of the same square have the square's area, and each
    # triangle's pieces its own area
    a = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.5), 0.3).mesh
    b = mesh_surface(Surface(arc=(-0.5, 0.5), half_width=0.5), 0.17).mesh
    ta, tb = a.p[:, a.t], b.p[:, b.t]
    pieces, ia, ib = overlay(ta, tb)
    area = lambda t: 0.5 * np.abs((t[0, 1] - t[0, 0]) * (t[1, 2] - t[1, 0])  # noqa: E731
                                  - (t[0, 2] - t[0, 0]) * (t[1, 1] - t[1, 0]))
    assert area(pieces).sum() == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_allclose(np.bincount(ia, area(pieces), ta.shape[2]), area(ta), rtol=1e-10)
    np.testing.assert_allclose(np.bincount(ib, area(pieces), tb.shape[2]), area(tb), rtol=1e-10)


def test_solve_reynolds_on_the_shoe_body():
    # the coupled film on the real shoe: the returned deflection is the compliance's answer to the
    # returned pressure (the fixed point, to the solver's tolerance 1e-8 c)
    mesh = mesh_surface(POCKET, 0.2)
    body = ShoeBody(0.015, seat="frictionless", seat_radius=0.0125)
    C = shoe_compliance(mesh, SCALE, STEEL, body, counterpart=STEEL, film_size=0.2)
    ps = SCALE.from_pressure(32e6)
    res = solve_reynolds(mesh, bf.CosineFilm(0.5, math.pi), inlet_pressure=ps, elastic=C)
    assert np.abs(C.deflection(res.pressure, ps) - res.deflection).max() < 1e-7
    assert res.max_deflection > 0.05


def test_bad_shoe_inputs_are_named(tmp_path):
    with pytest.raises(ValueError, match="seat_radius must be in"):
        mesh_shoe(PLAIN, 0.05, ShoeBody(0.015, seat_radius=0.019), 0.2)
    with pytest.raises(ValueError, match="back must be one of"):
        ShoeBody(0.015, back="round")
    with pytest.raises(ValueError, match="seat_radius must be given"):
        ShoeBody(0.015, seat="frictionless")
    with pytest.raises(ValueError, match=r"lining_thickness must be in \[0, thickness"):
        ShoeBody(0.015, lining=BRONZE, lining_thickness=0.02)
    with pytest.raises(ValueError, match="lining and lining_thickness go together"):
        ShoeBody(0.015, lining=BRONZE)
    with pytest.raises(ValueError, match="size must be a finite element size"):
        mesh_shoe(PLAIN, 0.05, ShoeBody(0.015), -1.0)
    with pytest.raises(ValueError, match="order must be one of"):
        shoe_compliance(mesh_surface(PLAIN, 0.3), SCALE, STEEL, ShoeBody(0.015), order=3)
    with pytest.raises(bf.MeshSizeError, match="tetrahedra"):
        mesh_shoe(PLAIN, 0.05, ShoeBody(0.015), 0.2, film_size=1e-4)
    # the machine file: the fields of [shoe], [shoe.seat] and [shoe.lining] are checked and named
    text = ROOT / "mechanisms" / "eccentric_pump.toml"
    base = open(text).read()
    for old, new, message in (
            ('kind = "frictionless"', 'kind = "glued"', r"\[shoe.seat\] kind: must be one of 'clamped'"),
            ("radius = 0.0175 ", "radius = -0.01 ", r"\[shoe\] seat_radius must be > 0"),
            ('back = "flat"', 'back = "round"', r"\[shoe\] back: must be one of 'flat', 'concentric'"),
            ("[shoe.seat]", "[shoe.lining]\nthickness = 0.002\n\n[shoe.seat]",
             r"\[shoe.lining\] youngs_modulus: missing")):
        assert old in base
        path = tmp_path / "pump.toml"
        path.write_text(base.replace(old, new, 1))
        with pytest.raises(SchemaError, match=message):
            bf.load_mechanism(path)


def test_the_shipped_pump_describes_its_shoe():
    pump = bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")
    assert pump.shoe_body == ShoeBody(0.015, back="flat", seat="frictionless", seat_radius=0.0175)
    assert pump.shoe_thickness == 0.015


def test_machine_file_lining_and_concentric_back(tmp_path):
    # [shoe.lining] and back = "concentric" reach the ShoeBody with their SI values
    base = open(ROOT / "mechanisms" / "eccentric_pump.toml").read()
    text = base.replace('back = "flat"', 'back = "concentric"', 1).replace(
        "[shoe.seat]", '[shoe.lining]\nthickness = 0.002\nname = "bronze"\nyoungs_modulus = 110e9\n'
                       "poisson_ratio = 0.34\n\n[shoe.seat]", 1)
    path = tmp_path / "pump.toml"
    path.write_text(text)
    body = bf.load_mechanism(path).shoe_body
    assert body == ShoeBody(0.015, back="concentric", seat="frictionless", seat_radius=0.0175,
                            lining=Material("bronze", 110e9, poisson_ratio=0.34), lining_thickness=0.002)
