"""JFO on structured grids: ``grid_mesh`` and the grid Couette flux (``solve_jfo(..., couette="grid")``)."""

import numpy as np
import pytest

from bearingfe import Circle, CosineFilm, Recess, Rectangle, Surface, grid_mesh, mesh_surface, solve_reynolds
from bearingfe.film.thickness import UniformFilm
from bearingfe.film.finite_volume import COUETTE_FLUXES, solve_jfo
from bearingfe.geometry.meshing import periodic_pairs, strip_mesh

from bearingfe.validation import PocketSlider


def _dimpled(n_side=3, radius=0.1, depth=0.8, **kw):
    pitch = 1.0 / n_side
    dimples = [Recess(Circle((pitch * (i + 0.5), pitch * (j + 0.5) - 0.5), radius), depth)
               for i in range(n_side) for j in range(n_side)]
    return Surface(arc=(0.0, 1.0), half_width=0.5, recesses=dimples, **kw)


def _assert_same_solution(a, b) -> None:
    """The same complementarity solution to the solver tolerance: the same cavity, pressures within 1e-10 of
    the largest, fill fractions within 1e-10."""
    assert np.array_equal(a.cavitated, b.cavitated)
    assert np.abs(a.pressure - b.pressure).max() < 1e-10 * np.abs(b.pressure).max()
    assert np.abs(a.theta - b.theta).max() < 1e-10


# -- the mesh ------------------------------------------------------------------------------------

def test_grid_mesh_layout_and_boundaries():
    mesh = grid_mesh(Surface(arc=(0.0, 1.0), half_width=0.25), 0.1)
    assert mesh.source == "grid" and mesh.n_nodes == 11 * 6 and mesh.n_elements == 2 * 10 * 5
    assert np.allclose(sorted(set(mesh.mesh.p[0].round(12))), np.linspace(0.0, 1.0, 11))
    bnd = mesh.boundaries
    assert {"outer", "arc_start", "arc_end", "side"} <= set(bnd)
    assert len(bnd["arc_start"]) == len(bnd["arc_end"]) == 5 and len(bnd["side"]) == 20
    assert len(bnd["outer"]) == 30
    # cells of at most `size`: 0.35 long over 0.1 -> 4 cells of 0.0875
    assert grid_mesh(Surface(arc=(0.0, 0.35), half_width=0.25), 0.1, size_z=0.5).n_nodes == 5 * 2


def test_periodic_grid_mesh_has_a_matching_seam():
    mesh = grid_mesh(Surface(arc=(0.0, 2 * np.pi), half_width=0.5, periodic=True), 0.2)
    start, end = periodic_pairs(mesh)
    assert start.size == end.size == 6
    assert np.allclose(mesh.mesh.p[0, end] - mesh.mesh.p[0, start], 2 * np.pi)
    assert "arc_start" not in mesh.boundaries and len(mesh.boundaries["outer"]) == 2 * 32


def test_grid_mesh_refuses_what_it_cannot_carry():
    with pytest.raises(ValueError, match="pockets"):
        grid_mesh(Surface(inlets=[Circle((0.0, 0.0), 0.1)]), 0.1)
    with pytest.raises(ValueError, match="rectangular outline"):
        grid_mesh(Surface(outer=Circle((0.0, 0.0), 0.5)), 0.1)
    with pytest.raises(ValueError, match="size"):
        grid_mesh(Surface(), 0.0)
    with pytest.raises(ValueError, match="surface"):
        grid_mesh("surface", 0.1)


def test_couette_option_is_checked():
    mesh = grid_mesh(_dimpled(), 0.1)
    with pytest.raises(ValueError, match="couette must be one of"):
        solve_jfo(mesh, UniformFilm(1.0), couette="upwind")
    gmsh_mesh = mesh_surface(Surface(arc=(0.0, 1.0), half_width=0.5), 0.2)
    with pytest.raises(ValueError, match="tensor-grid"):
        solve_jfo(gmsh_mesh, UniformFilm(1.0), couette="grid")
    assert COUETTE_FLUXES == ("auto", "median", "grid", "limited", "streamline")


# -- the closed-form pocket slider with the grid flux ---------------------------------------------

def _slider_grid(n):
    case = PocketSlider()
    mesh = strip_mesh(n)
    width = float(np.ptp(mesh.mesh.p[1]))
    res = solve_jfo(mesh, case.film(), cavitation_pressure=(case.p_cav - case.p_edge) / case.pressure_scale,
                    couette="grid")
    return res, res.integral / width * case.pressure_scale * case.length, \
        res.flows["arc_end"] / width * case.speed * case.h_out


def test_grid_flux_on_the_pocket_slider_is_exact_and_converges():
    ex = PocketSlider().exact()
    errors = []
    for n in (80, 160, 320, 640):
        res, load, flow = _slider_grid(n)
        # the step fluxes are exact (film integrated exactly over each face): flow to round-off
        assert flow == pytest.approx(ex.flow, rel=1e-10), n
        assert abs(res.mass_balance) < 1e-11 * abs(res.flows["arc_end"])   # round-off (measured <= 1.2e-12)
        errors.append(abs(load / ex.load - 1))
    # on a strip the grid flux is the median-dual flux (theta is uniform across): the same errors as
    # tests/film/test_finite_volume.py's slider (measured 7.7e-4, 3.2e-4, 9.2e-5, 1.4e-5), fitted order about 1.9
    order = -np.polyfit(np.log([80, 160, 320, 640]), np.log(errors), 1)[0]
    assert errors[-1] < 5e-5 and order > 1.3, (errors, order)


def _exact_slider_friction(case):
    """Shear force per unit width [N/m] of the closed-form pocket slider (docs/jfo.md): mu U theta/h over
    the four zones (full film on the lands and behind the reformation point, theta_c in the cavity) plus
    the pressure part h/2 dp over each zone (linear pressures, none in the cavity)."""
    ex = case.exact()
    mu, U, ho, hi, a, b, L = case.viscosity, case.speed, case.h_out, case.h_in, case.start, case.end, case.length
    xr, pb, pe, pc = ex.reformation, ex.peak_pressure, case.p_edge, case.p_cav
    shear = mu * U * (a / ho + (xr - a) * ex.theta_cavity / hi + (b - xr) / hi + (L - b) / ho)
    return shear + ho / 2 * (pc - pe) + hi / 2 * (pb - pc) + ho / 2 * (pe - pb)


def test_grid_friction_keeps_the_full_film_before_the_rupture_step():
    # the box of the node on the rupture step is half land (full film) and half pocket (cavity): the grid
    # result fills it from the flux through its downstream face, the median-dual result smears theta_c over
    # the land; measured relative errors 6.5e-4, 3.3e-4, 1.6e-4, 8.1e-5 (grid) against
    # -5.8e-3, -2.9e-3, -1.5e-3, -7.3e-4 (median)
    case = PocketSlider()
    exact = _exact_slider_friction(case)
    assert exact == pytest.approx(172.92096, rel=1e-6)
    p_c = (case.p_cav - case.p_edge) / case.pressure_scale
    errors = {}
    for n in (80, 160, 320, 640):
        mesh = strip_mesh(n)
        width = float(np.ptp(mesh.mesh.p[1]))
        for couette in ("grid", "median"):
            res = solve_jfo(mesh, case.film(), cavitation_pressure=p_c, couette=couette)
            force = res.friction / width * case.viscosity * case.speed * case.length / case.h_out
            errors[n, couette] = abs(force / exact - 1)
    grid = [errors[n, "grid"] for n in (80, 160, 320, 640)]
    assert all(errors[n, "grid"] < errors[n, "median"] / 5 for n in (80, 160, 320, 640)), errors
    order = -np.polyfit(np.log([80, 160, 320, 640]), np.log(grid), 1)[0]
    assert grid[-1] < 1e-4 and order > 0.9, (grid, order)


# -- conservation, complementarity, no-rupture limit ------------------------------------------------

def test_dimpled_grid_conserves_mass_and_satisfies_complementarity():
    res = solve_jfo(grid_mesh(_dimpled(), 1 / 40), UniformFilm(1.0), cavitation_pressure=-0.05)
    assert res.cavitated.any() and res.theta.min() > 0.0 and res.theta.max() <= 1.0
    scale = np.abs(res.pressure).max()
    assert res.pressure.min() >= -0.05 - 1e-12 * scale
    assert np.abs((res.pressure + 0.05) * (1 - res.theta)).max() <= 1e-12 * scale
    inflow = abs(res.flows["arc_start"])
    assert abs(res.mass_balance) < 1e-12 * inflow   # measured 1e-16
    # what enters at the leading edge leaves through the trailing edge and the sides
    assert abs(res.flows["arc_start"] + res.flows["arc_end"] + res.flows["side"]) < 1e-12 * inflow


def test_no_rupture_grid_flux_equals_galerkin_reynolds():
    # converging film over the whole arc (phi - phi0 in (0.1, 1.1)): p > 0 inside, no cavity
    film = CosineFilm(0.6, -0.6)
    diffs = []
    for size in (0.1, 0.05, 0.025):
        mesh = grid_mesh(Surface(arc=(-0.5, 0.5), half_width=0.4), size)
        ref = solve_reynolds(mesh, film, formulation="direct")
        jfo = solve_jfo(mesh, film, couette="grid")
        assert np.all(jfo.theta == 1.0) and jfo.iterations == 1 and not jfo.cavitated.any()
        diffs.append(abs(jfo.integral / ref.integral - 1))
    # on right triangles the Galerkin wedge term of node i is the film averaged over the rectangles between
    # i and its phi-neighbours, which is what the grid flux puts through the box faces: the two
    # discretizations coincide up to the quadrature of the film (measured 2.5e-12, 4e-14, 1.6e-14)
    assert max(diffs) < 1e-9, diffs


def test_recess_edges_move_continuously_through_the_grid():
    # the film is integrated exactly over the faces and cut cells, so moving a recess edge across a grid
    # line changes the solution continuously (a cell-wise, staircased film would jump by a whole cell)
    loads = []
    for top in (0.15 - 1e-7, 0.15 + 1e-7):   # 0.15 is a node line of the 0.05 grid
        shape = Rectangle(((0.3 + 0.55) / 2, (top - 0.2) / 2), (0.25, top + 0.2))
        surface = Surface(arc=(0.0, 1.0), half_width=0.5, recesses=[Recess(shape, 1.0)])
        res = solve_jfo(grid_mesh(surface, 0.05), UniformFilm(1.0), cavitation_pressure=-0.05)
        loads.append(res.integral)
    assert loads[1] == pytest.approx(loads[0], rel=1e-4), loads


def test_auto_picks_the_grid_flux_on_grid_meshes_only():
    mesh = grid_mesh(_dimpled(), 1 / 20)
    auto = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    grid = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05, couette="grid")
    median = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05, couette="median")
    assert auto.integral == grid.integral and auto.integral != median.integral
    # solve_reynolds takes the finite-volume path for the recessed grid mesh, with the grid flux
    via = solve_reynolds(mesh, UniformFilm(1.0), cavitation="jfo", cavitation_pressure=-0.05)
    assert via.integral == pytest.approx(grid.integral, rel=1e-12)


def test_periodic_grid_carries_the_flux_across_the_seam():
    # a full film ring fed through its sides only (p_c < 0): the seam nodes are one unknown, so the oil
    # crosses the seam like any other face; mass balance to round-off and the seam is invisible:
    # shifting the dimples by one cell along phi shifts the solution and leaves the load unchanged
    import math

    def ring(shift):
        dimples = [Recess(Circle((1.0 + shift + k * math.pi / 2, 0.0), 0.3), 1.0) for k in range(4)]
        return Surface(arc=(0.0, 2 * math.pi), half_width=0.5, periodic=True, recesses=dimples)

    size = 2 * math.pi / 64
    loads = []
    for shift in (0.0, size):
        res = solve_jfo(grid_mesh(ring(shift), size), UniformFilm(1.0), cavitation_pressure=-0.05)
        assert res.cavitated.any() and res.theta.min() > 0.0
        # the net side flow vanishes (no other outlet): balance against the Couette flow round the ring, 1/2
        assert abs(res.mass_balance) < 1e-12 * 0.5 and abs(res.flows["side"]) < 1e-12 * 0.5
        loads.append(res.integral)
    assert loads[1] == pytest.approx(loads[0], rel=1e-9), loads


def test_low_rank_tail_of_the_active_set_matches_fresh_factorizations(monkeypatch):
    # the last active-set steps switch a few dofs; they are solved by Sherman-Morrison-Woodbury on the
    # previous factorization: same sets, same iterations and the same solution to round-off
    import bearingfe.film.finite_volume as jfo

    mesh = grid_mesh(_dimpled(), 1 / 60)
    fast = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    monkeypatch.setattr(jfo, "LOW_RANK_SWITCHES", 0)
    slow = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    assert fast.iterations == slow.iterations
    _assert_same_solution(fast, slow)
    assert fast.cost["active_set_residual"] < 1e-12


def test_band_iteration_gives_the_plain_active_sets_solution_in_fewer_factorizations(monkeypatch):
    # a set change too large for Woodbury is first iterated on a band around the switched dofs (the rest
    # held at the last global solve): the proposal only changes which sets are factorized on the way, the
    # global solve still decides convergence, so the answer is the plain method's complementarity solution
    # (to the solver tolerance: the last step is a Woodbury solve accepted at a 1e-11 residual), in fewer
    # fine factorizations (measured 2 against 3 on these dimples at 1.7e4 nodes, as at 1e4 .. 1.6e5)
    import bearingfe.film.finite_volume as jfo

    mesh, options = grid_mesh(_dimpled(), 1 / 130), dict(cavitation_pressure=-0.05)
    monkeypatch.setattr(jfo, "TWO_GRID_FROM", 10**9)   # the nested start's own band would leave no set change
    monkeypatch.setattr(jfo, "TWO_GRID_BANDED_FROM", 10**9)
    monkeypatch.setattr(jfo, "BAND_FROM", 0)
    band = solve_jfo(mesh, UniformFilm(1.0), **options)
    monkeypatch.setattr(jfo, "BAND_FROM", 10**9)
    plain = solve_jfo(mesh, UniformFilm(1.0), **options)
    assert plain.cavitated.any()
    _assert_same_solution(band, plain)
    assert band.cost["factorizations"] < plain.cost["factorizations"]
    assert abs(band.mass_balance) < 1e-12 and band.cost["active_set_residual"] < 1e-11


@pytest.mark.parametrize("case", ["dimples", "grooved journal"])
def test_two_grid_band_start_gives_the_plain_solution_in_fewer_fine_factorizations(monkeypatch, case):
    # from TWO_GRID_FROM unknowns a nested start's set is iterated on a band around its fronts, corrected by
    # the coarse level's factorization, before the first fine factorization: the global solves still decide
    # convergence, so the answer is the plain method's complementarity solution (to the solver tolerance:
    # a last Woodbury step is accepted at a 1e-11 residual), in fewer fine factorizations (measured 2
    # against 3 on the dimples at 1.7e4 nodes, 1 against 2 on the grooved journal with its fed pocket and seam)
    import bearingfe.film.finite_volume as jfo

    mesh, film, options = _nested_case(case)
    calls = []
    band = jfo._two_grid_set
    monkeypatch.setattr(jfo, "_two_grid_set", lambda *a, **k: calls.append(1) or band(*a, **k))
    monkeypatch.setattr(jfo, "TWO_GRID_FROM", 0)
    fast = solve_jfo(mesh, film, **options)
    monkeypatch.setattr(jfo, "TWO_GRID_FROM", 10**9)
    monkeypatch.setattr(jfo, "TWO_GRID_BANDED_FROM", 10**9)
    plain = solve_jfo(mesh, film, **options)
    assert len(calls) == 1 and fast.cost["nested_levels"] >= 1
    assert plain.cavitated.any()
    _assert_same_solution(fast, plain)
    assert fast.cost["factorizations"] < plain.cost["factorizations"]
    assert abs(fast.mass_balance) < 1e-12 and fast.cost["active_set_residual"] < 1e-11


@pytest.mark.parametrize("case", ["dimples", "grooved journal"])
def test_narrow_two_grid_band_gives_the_wide_bands_answer_in_no_more_fine_factorizations(monkeypatch, case):
    # below TWO_GRID_WIDE_FROM unknowns the nested start's band is TWO_GRID_NARROW_RINGS rings wide (the carried
    # cavity is wrong almost only on its front nodes): the global solves still decide convergence, so the answer
    # is the wide band's and the plain start's complementarity solution to the solver tolerance, in no more fine
    # factorizations than the wide band and fewer than without a band (measured 2, 2 and 3 on the 130 x 130
    # dimples; 1, 1 and 2 on the grooved journal)
    import bearingfe.film.finite_volume as jfo

    mesh, film, options = _nested_case(case)
    assert jfo.TWO_GRID_FROM <= mesh.n_nodes < jfo.TWO_GRID_WIDE_FROM
    narrow = solve_jfo(mesh, film, **options)
    monkeypatch.setattr(jfo, "TWO_GRID_WIDE_FROM", 0)
    wide = solve_jfo(mesh, film, **options)
    monkeypatch.setattr(jfo, "TWO_GRID_FROM", 10**9)
    monkeypatch.setattr(jfo, "TWO_GRID_BANDED_FROM", 10**9)
    plain = solve_jfo(mesh, film, **options)
    assert narrow.cost["factorizations"] <= wide.cost["factorizations"] < plain.cost["factorizations"]
    for other in (wide, plain):
        _assert_same_solution(narrow, other)
    assert abs(narrow.mass_balance) < 1e-12 and narrow.cost["active_set_residual"] < 1e-11


@pytest.mark.parametrize("case", ["dimples", "grooved journal"])
def test_two_grid_start_below_its_size_takes_a_thin_band(monkeypatch, case):
    # below TWO_GRID_FROM unknowns (from TWO_GRID_BANDED_FROM) a nested start iterates its set on the band around
    # its fronts where that band factors by banded LU: the global solves still decide convergence, so the answer is
    # the plain start's complementarity solution to the solver tolerance (a last Woodbury step is accepted at a
    # 1e-11 residual), in fewer fine factorizations (measured 1 against 3 on the 3 x 3 dimples at 70 x 70 cells,
    # 1 against 2 on the grooved journal at 100 x 40)
    import bearingfe.film.finite_volume as jfo

    if case == "dimples":
        mesh, film, options = grid_mesh(_dimpled(), 1 / 70), UniformFilm(1.0), dict(cavitation_pressure=-0.05)
    else:
        surface, film, options = _pocketed_journal()
        mesh = grid_mesh(surface, 2 * np.pi / 100, size_z=1 / 40)
    calls = []
    band = jfo._band_set
    monkeypatch.setattr(jfo, "_band_set", lambda *a, **k: calls.append(a[4].size) or band(*a, **k))
    thin = solve_jfo(mesh, film, **options)
    assert len(calls) == 1 and jfo.TWO_GRID_BANDED_FROM <= calls[0] < jfo.TWO_GRID_FROM   # the band's unknowns
    monkeypatch.setattr(jfo, "TWO_GRID_BANDED_FROM", 10**9)
    plain = solve_jfo(mesh, film, **options)
    assert len(calls) == 1 and thin.cost["nested_levels"] >= 1 and plain.cavitated.any()
    _assert_same_solution(thin, plain)
    assert thin.cost["factorizations"] < plain.cost["factorizations"]
    assert abs(thin.mass_balance) < 1e-12 and thin.cost["active_set_residual"] < 1e-11


def test_two_grid_start_below_its_size_refuses_a_wide_band(monkeypatch):
    # the 25 dimples of docs/jfo_dimples.md at 70 x 70 cells: their fronts' band (3,136 of 4,761 unknowns) is too
    # wide for banded LU, so the carried set is factorized as it is: the plain start's solve, bit for bit
    from benchmarks.jfo_dimples import P_C, surface

    import bearingfe.film.finite_volume as jfo

    mesh = grid_mesh(surface(), 1 / 70)
    sets = []
    two_grid = jfo._two_grid_set
    monkeypatch.setattr(jfo, "_two_grid_set", lambda *a: sets.append((a[4], two_grid(*a))) or sets[-1][1])
    refused = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=P_C)
    monkeypatch.setattr(jfo, "TWO_GRID_BANDED_FROM", 10**9)
    plain = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=P_C)
    assert len(sets) == 1 and np.array_equal(sets[0][0], sets[0][1])
    assert refused.cost["factorizations"] == plain.cost["factorizations"]
    assert np.array_equal(refused.pressure, plain.pressure) and np.array_equal(refused.theta, plain.theta)


def test_sliding_backwards_mirrors_the_solution():
    # the dimple layout is symmetric about phi = 1/2, so wedge = -1 gives the mirror image: same cavity
    # area, friction of opposite sign (the fill of each box is taken from its downstream face, here the
    # one towards smaller phi); the load differs only by discretization error, the grid's diagonals not
    # being mirror-symmetric (measured 0.6 % at 40 cells, friction 1.3e-6)
    mesh = grid_mesh(_dimpled(), 1 / 40)
    fwd = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05, wedge=1.0)
    back = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05, wedge=-1.0)
    assert back.cavitated_fraction == pytest.approx(fwd.cavitated_fraction, rel=1e-9)
    assert back.friction == pytest.approx(-fwd.friction, rel=1e-5)
    assert back.integral == pytest.approx(fwd.integral, rel=0.02)


def _pocketed_journal():
    import math

    from bearingfe.bearings.journal import Groove, JournalBearing

    bearing = JournalBearing(1.0, periodic=True, grooves=(Groove(math.pi / 2, math.radians(20.0), 0.8),))
    (surface,) = bearing.surfaces()
    return surface, CosineFilm(0.6, 0.0), dict(inlet_pressure=0.2)


def _nested_case(case: str):
    """The mesh, film and solve options of the nested-start tests: 130 x 130 dimples, or the grooved journal
    (a fed pocket, a hole of the grid, and a seam) on a 160 x 64 grid."""
    if case == "dimples":
        return grid_mesh(_dimpled(), 1 / 130), UniformFilm(1.0), dict(cavitation_pressure=-0.05)
    surface, film, options = _pocketed_journal()
    return grid_mesh(surface, 2 * np.pi / 160, size_z=1 / 64), film, options


@pytest.mark.parametrize("case", ["dimples", "grooved journal"])
def test_nested_start_from_coarser_grids_gives_the_cold_solution(monkeypatch, case):
    # a cold grid solve above NESTED_MIN unknowns starts from the cavity of the grid on every other line
    # (recursively): the active set converges to the same complementarity solution as from the
    # full-film start, to round-off (the solution of the discrete LCP does not depend on the start), in
    # no more fine factorizations; the grooved journal has a fed pocket (a hole of the grid) and a seam
    import bearingfe.film.finite_volume as jfo

    mesh, film, options = _nested_case(case)
    nested = solve_jfo(mesh, film, **options)
    monkeypatch.setattr(jfo, "NESTED_MIN", 10**9)
    cold = solve_jfo(mesh, film, **options)
    assert nested.cost["nested_levels"] >= 1 and "nested_levels" not in cold.cost
    assert cold.cavitated.any()
    _assert_same_solution(nested, cold)
    # fine-level factorizations (the cold start pays one more for its full-film guess); measured 3 against
    # 3 on the dimples, 3 against 7 on the journal
    assert nested.cost["factorizations"] <= cold.cost["factorizations"]
    assert abs(nested.mass_balance) < 1e-12 and nested.cost["active_set_residual"] < 1e-12



def test_coarse_levels_kept_per_mesh_give_the_same_repeated_solve():
    # the coarser grids of a nested start are kept per mesh: a repeated cold solve on the mesh takes the same
    # coarse meshes (and what is cached on them) and gives the first solve's answer bit for bit; the kept grid
    # is the one built afresh (same nodes and triangles)
    from bearingfe.film import finite_volume as fv

    mesh = grid_mesh(_dimpled(), 1 / 70)
    first = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    coarse = fv._coarser_grid(mesh)
    assert first.cost["nested_levels"] >= 1 and first.cavitated.any()
    assert fv._coarser_grid(mesh) is coarse
    again = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    assert fv._coarser_grid(mesh) is coarse
    for name in ("pressure", "theta", "cavitated", "force"):
        assert np.array_equal(getattr(first, name), getattr(again, name))
    assert first.friction == again.friction and first.cost["factorizations"] == again.cost["factorizations"]
    fresh = fv._coarser_lines(mesh)
    assert np.array_equal(fresh.mesh.p, coarse.mesh.p) and np.array_equal(fresh.mesh.t, coarse.mesh.t)


def test_rough_coarse_levels_give_the_converged_answer_in_fewer_coarse_steps(monkeypatch):
    # a nested start's coarse levels stop once a step switches at most NESTED_ROUGH of their nodes: the
    # fine level still converges to the same complementarity solution (to round-off: the discrete LCP's
    # solution does not depend on the start), with fewer coarse steps (measured 2 against 3 here)
    import bearingfe.film.finite_volume as jfo

    mesh, options = grid_mesh(_dimpled(), 1 / 130), dict(cavitation_pressure=-0.05)
    rough = solve_jfo(mesh, UniformFilm(1.0), **options)
    monkeypatch.setattr(jfo, "NESTED_ROUGH", 0.0)
    converged = solve_jfo(mesh, UniformFilm(1.0), **options)
    assert rough.cost["nested_levels"] >= 1 and converged.cost["nested_levels"] == rough.cost["nested_levels"]
    assert rough.cost["coarse_iterations"] < converged.cost["coarse_iterations"]
    _assert_same_solution(rough, converged)


def test_circle_contours_crossed_in_closed_form_as_bisection_finds_them(monkeypatch):
    # the face film of a grid's box faces across circular dimple contours: the chord ends (closed form)
    # against the bracketing search every other shape takes (to 2**-30 of an eighth of a cell): the same
    # line integrals to that search's resolution, and a square recess (a Polygon) still bisected
    from bearingfe.film import finite_volume as fv

    surface = Surface(arc=(0.0, 1.0), half_width=0.5,
        recesses=[Recess(Circle((0.3, 0.1), 0.17), 0.8), Recess(Circle((0.72, -0.2), 0.11), 1.3),
                  Recess(Rectangle((0.7, 0.25), (0.2, 0.1)), 0.5)])
    g = fv._grid_faces(grid_mesh(surface, 1 / 37))
    closed = fv._face_recess(surface, g.x0, g.x1, g.lo, g.hi)

    class NotACircle:   # every recess bisected
        pass

    monkeypatch.setattr(fv, "Circle", NotACircle)
    bisected = fv._face_recess(surface, g.x0, g.x1, g.lo, g.hi)
    # the search ends within 2**-31 of an eighth of a cell of each crossing, at most a few per face, each
    # weighing the depth step (1.3): 4 * 1.3 * (1/37/8) * 2**-31 = 8e-12
    assert np.count_nonzero(closed) > 100 and np.abs(closed - bisected).max() <= 1e-11
    # a chord end lies where the circle's test changes: just below it inside, just above outside
    c = fv._circle_crossing(Circle((0.3, 0.1), 0.17), np.array([0.3, 0.4]), np.array([True, False]))
    assert np.allclose(c, [0.27, 0.1 - np.sqrt(0.17**2 - 0.1**2)], rtol=0, atol=1e-15)


def test_coarse_levels_without_sub_cell_means_start_the_same_fine_solve(monkeypatch):
    # a nested start's coarse levels take h^3 at the quadrature points on the cells a dimple contour cuts
    # (no sub-cell means): their cavity only starts the finer level, whose answer is the LCP's solution
    # whatever the start (to round-off) and here in as many fine factorizations
    from bearingfe.film import finite_volume as fv

    mesh = grid_mesh(_dimpled(), 1 / 100)
    plain = solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    monkeypatch.setattr(fv, "NESTED_CELL_MEANS", True)
    means = solve_jfo(grid_mesh(_dimpled(), 1 / 100), UniformFilm(1.0), cavitation_pressure=-0.05)
    assert plain.cost["nested_levels"] >= 1 and plain.cavitated.any()
    assert np.array_equal(plain.cavitated, means.cavitated)
    assert np.abs(plain.pressure - means.pressure).max() <= 1e-10 * np.abs(means.pressure).max()
    assert plain.cost["factorizations"] == means.cost["factorizations"]
    # the coarse system differs from the one with the means where the contours cut the cells
    coarse = fv._coarser_grid(mesh)
    ops = fv.operators(coarse)
    rough = fv._assemble(ops, coarse, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid", rough=True)
    exact = fv._assemble(ops, coarse, UniformFilm(1.0), 1.0, (0.0, 0.0), None, None, "grid")
    assert abs(rough.K - exact.K).max() > 1e-6 * abs(exact.K).max()
