"""The runner's velocity field (bearingfe.geometry.runner) through the Reynolds solvers.

References: the exact infinite-width optima of the inclined slider and the Rayleigh step (closed forms,
e.g. Hamrock, Fundamentals of Fluid Film Lubrication, ch. 8-9), a polar finite-difference solution of a
sector pad (bearingfe.film.polar_fd, Richardson-extrapolated), and the package's own original path
(uniform sliding along phi), which a Translating(0) runner must reproduce bit for bit.
"""

import math

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.film.polar_fd import solve_sector_fd
from bearingfe.film.thickness import PlaneFilm, PolarProfileFilm
from bearingfe.geometry.runner import Rotating, Translating, velocity_at
from bearingfe.geometry.surface import AnnularSector

SECTOR = AnnularSector(0.5, 1.0, start=0.0, extent=math.radians(40))


def _tilted_sector_film():
    """A flat pad tilted to converge along the rotation (no rupture: p > 0 everywhere)."""
    a = 0.6 * SECTOR.extent
    t, r = np.array([-math.sin(a), math.cos(a)]), np.array([math.cos(a), math.sin(a)])
    return PlaneFilm(1.0, (0.75 * math.cos(a), 0.75 * math.sin(a)), tuple(-2.0 * t + 0.3 * r))


@pytest.mark.parametrize("cavitation", ["none", "reynolds", "jfo"])
def test_translating_along_phi_is_the_original_path(cavitation):
    """Translating(0) is the package's original runner: same numbers to the bit on every path."""
    film = \
        bf.TaperFilm(2.0, 0.8, start=-0.5, end=0.5)
    plain = bf.mesh_surface(bf.Surface(), 0.1)
    explicit = bf.mesh_surface(bf.Surface(runner=Translating(0.0)), 0.1)
    a = bf.solve_reynolds(plain, film, formulation="direct", cavitation=cavitation, wedge=-1.0)
    b = bf.solve_reynolds(explicit, film, formulation="direct", cavitation=cavitation, wedge=-1.0)
    assert np.array_equal(a.pressure, b.pressure)
    assert a.friction == b.friction and dict(a.flows) == dict(b.flows)
    assert b.runner is None


def test_velocity_fields():
    """Rotating: u = sense (-(y - yc), x - xc), speed r; Translating(a): (cos a, sin a)."""
    x = np.array([[1.0, 0.0, 2.0], [0.0, 1.0, 1.0]])
    u = velocity_at(Rotating((0.0, 1.0), -1), x)
    assert np.allclose(u[0], [-1.0, 0.0, 0.0]) and np.allclose(u[1], [-1.0, 0.0, -2.0])
    v = velocity_at(Translating(math.pi / 2), x)
    assert np.allclose(v[0], 0.0, atol=1e-16) and np.allclose(v[1], 1.0)
    assert velocity_at(Translating(0.0), x) is None
    with pytest.raises(ValueError, match="Rotating.sense"):
        Rotating((0, 0), 2)
    with pytest.raises(ValueError, match="Surface.runner"):
        bf.Surface(runner="rotating")


def test_compiled_and_reference_assemblies_agree_on_a_rotating_runner():
    """The production (compiled) and oracle (form assembly) paths give one answer to round-off."""
    from bearingfe.film.mesh_operators import operators
    from bearingfe.film.superposition import superpose
    mesh = bf.mesh_surface(bf.Surface(outer=SECTOR, runner=Rotating()), 0.08)
    film = _tilted_sector_film()
    out = []
    for assembly in ("compiled", "reference"):
        mesh._cache.clear()
        ops = operators(mesh, "P1")
        ops._lazy.clear()
        sup = superpose(mesh, film, formulation="direct", assembly=assembly)
        out.append(sup.combine(1.0, (0.3, -0.2)))
    a, b = out
    assert a.integral == pytest.approx(b.integral, rel=1e-12)
    assert a.friction == pytest.approx(b.friction, rel=1e-12)
    for k in a.flows:
        assert a.flows[k] == pytest.approx(b.flows[k], rel=1e-10, abs=1e-13)


def test_rotating_far_axis_is_a_translating_runner():
    """A collar turning about an axis 1000 lengths away slides uniformly to within ~(0.5/1000)^2."""
    film = bf.TaperFilm(2.0, 1.0, start=-0.5, end=0.5)
    near = bf.solve_reynolds(bf.mesh_surface(bf.Surface(), 0.1), film, formulation="direct")
    far = bf.solve_reynolds(bf.mesh_surface(bf.Surface(runner=Rotating((0.0, -1000.0), -1)), 0.1), film,
                            formulation="direct", wedge=1e-3)
    assert far.integral == pytest.approx(near.integral, rel=1e-6)
    assert far.friction * 1e-3 == pytest.approx(near.friction, rel=1e-6)


def _sector_reference() -> float:
    """Load of the tilted sector pad: polar finite differences at 64 and 128 cells, Richardson (order 2)."""
    film = _tilted_sector_film()
    coarse, fine = (solve_sector_fd(SECTOR, film, n, n).load for n in (64, 128))
    return fine + (fine - coarse) / 3.0


def test_sector_pad_against_polar_finite_differences():
    """P2 on curved sector meshes meets the polar FD reference to 3e-5 (measured 1.2e-5 at size 0.02) and
    converges at an observed order above 2.5 (measured 3.9)."""
    reference = _sector_reference()
    surface = bf.Surface(outer=SECTOR, runner=Rotating())
    film = _tilted_sector_film()
    errors = []
    for size in (0.04, 0.02):
        res = bf.solve_reynolds(bf.mesh_surface(surface, size, order=2), film, formulation="direct", element="P2")
        errors.append(abs(res.integral / reference - 1.0))
    assert errors[-1] < 3e-5
    assert math.log2(errors[0] / errors[1]) > 2.5


def test_sector_pad_p1_converges_at_second_order_and_conserves_mass():
    """P1: the load error against the FD reference falls by ~4 per halving (5.3e-3 at size 0.02); the edge
    flows balance."""
    reference = _sector_reference()
    surface = bf.Surface(outer=SECTOR, runner=Rotating())
    errors = []
    for size in (0.04, 0.02):
        res = bf.solve_reynolds(bf.mesh_surface(surface, size), _tilted_sector_film(), formulation="direct")
        errors.append(abs(res.integral / reference - 1.0))
        f = res.flows
        assert -f["arc_start"] == pytest.approx(f["arc_end"] + f["inner_rim"] + f["outer_rim"], rel=1e-10)
    order = math.log2(errors[0] / errors[1])
    assert 1.6 < order < 2.6, errors
    assert errors[-1] < 8e-3


def _wide_pad_load(film, size: float) -> float:
    """Load per unit width of an infinitely wide pad: periodic across the sliding, the runner along z."""
    surface = bf.Surface(arc=(-math.pi, math.pi), half_width=0.5, periodic=True, runner=Translating(math.pi / 2))
    res = bf.solve_reynolds(bf.mesh_surface(surface, size), film, formulation="direct")
    return res.integral / (2 * math.pi)


def _extrapolated(film) -> float:
    coarse, fine = _wide_pad_load(film, 0.1), _wide_pad_load(film, 0.05)
    return fine + (fine - coarse) / 3.0


def test_wide_inclined_slider_optimum():
    """Inclined slider at its optimum K = h_in/h_out = 2.1887: W h_out^2/(mu U L^2 B) =
    6/(K-1)^2 (ln K - 2 (K-1)/(K+1)) = 0.16024 (closed form)."""
    K = 2.1887
    exact = 6.0 / (K - 1) ** 2 * (math.log(K) - 2 * (K - 1) / (K + 1))
    assert exact == pytest.approx(0.16024, abs=1e-5)
    film = bf.TaperFilm(K, 1.0, start=-0.5, end=0.5, direction=math.pi / 2)
    assert _extrapolated(film) == pytest.approx(exact, rel=1e-3)


def test_wide_rayleigh_step_optimum():
    """Rayleigh step at its optimum (inlet land 0.7182 of the length, film ratio 1.8660):
    W h2^2/(mu U L^2 B) = 3 (h1 - h2) h2^2 L1 L2/(L (h1^3 L2 + h2^3 L1)) = 0.20627 (closed form)."""
    L1, ratio = 0.7182, 1.8660
    L2 = 1.0 - L1
    exact = 3 * (ratio - 1) * L1 * L2 / (ratio**3 * L2 + L1)
    assert exact == pytest.approx(0.20627, abs=2e-5)
    step = -0.5 + L1
    film = bf.ProfileFilm(((-0.5, ratio), (step, ratio), (step, 1.0), (0.5, 1.0)), direction=math.pi / 2)
    assert _extrapolated(film) == pytest.approx(exact, rel=2e-3)


@pytest.mark.parametrize("along, points", [("angle", ((0.0, 1.0), (0.3, 0.0))),
                                           ("radius", ((0.5, 0.0), (0.7, 0.0), (0.7, 0.5), (1.0, 0.5)))])
def test_polar_profile_gradient(along, points):
    """PolarProfileFilm's gradient equals central differences of its thickness (inside each piece)."""
    film = PolarProfileFilm(points, along=along)
    x, y = np.array([0.6, 0.55, 0.9]), np.array([0.1, 0.12, 0.3])
    e = 1e-7
    gx = (film.thickness(x + e, y) - film.thickness(x - e, y)) / (2 * e)
    gy = (film.thickness(x, y + e) - film.thickness(x, y - e)) / (2 * e)
    g = film.gradient(x, y)
    assert np.allclose(g[0], gx, atol=1e-6) and np.allclose(g[1], gy, atol=1e-6)


def _cavitating_sector():
    """A sector pad whose film converges to the middle of its angle and diverges after: the second half
    ruptures under every cavitation model."""
    film = PlaneFilm(0.6, (0.0, 0.0), (0.0, 0.0)) + PolarProfileFilm(
        ((0.0, 1.0), (0.5 * SECTOR.extent, 0.0), (SECTOR.extent, 1.0)), along="angle")
    return bf.mesh_surface(bf.Surface(outer=SECTOR, runner=Rotating()), 0.04), film


def test_every_cavitation_model_takes_the_rotating_runner():
    """Swift-Stieber, Gumbel and JFO on a ruptured sector pad: Gumbel's clipped full-film pressure carries less
    than Swift-Stieber's (whose positive zone is not pulled down by a negative lobe), the JFO film is mass-conserving to round-off and its load within 10 % of
    Swift-Stieber's (the two rupture models differ by the reformation the JFO film carries)."""
    mesh, film = _cavitating_sector()
    ss, gumbel, jfo = (bf.solve_reynolds(mesh, film, formulation="direct", cavitation=c)
                       for c in ("reynolds", "gumbel", "jfo"))
    assert np.mean(ss.cavitated) > 0.2 and jfo.cavitated_fraction > 0.2
    assert ss.integral > gumbel.integral > 0
    assert abs(jfo.mass_balance) < 1e-12 * abs(jfo.flows["arc_start"])
    assert jfo.integral == pytest.approx(ss.integral, rel=0.1)


def test_pockets_on_a_pad_count_in_its_load():
    """A parallel sector pad fed through a circular pocket (no sliding): the pad's load from bearings.thrust
    (film plus pocket pressure times its area, by the pocket's polygon) equals the solver's int p."""
    from bearingfe.bearings.thrust import ThrustPad, solve_pad
    from bearingfe.core.scales import Scale

    pocket = bf.Circle((0.75 * math.cos(0.35), 0.75 * math.sin(0.35)), 0.08)
    pad = ThrustPad(0.05, 0.1, 0.7, pockets=(pocket,))
    scale = Scale(0.1, 20e-6, 0.03, 100.0)
    sol = solve_pad(pad, pad.mesh(0.04), pad.state(scale, 20e-6), scale=scale, inlet_pressure=0.5, wedge=0.0)
    assert sol.load == pytest.approx(sol.result.integral, rel=1e-12)  # the same pocket (the mesh's hole)
    assert sol.load > 0.5 * pocket.area * 0.95  # at least the pocket pressure over the pocket (its polygon)


def test_error_estimate_and_adaptivity_take_a_thrust_pad():
    """The once-refined load estimate of a sector pad matches its true error (polar FD reference), and
    adapt() refines for int p (the load normal to the plane) to within its estimate."""
    import warnings

    reference = _sector_reference()
    surface = bf.Surface(outer=SECTOR, runner=Rotating())
    film = _tilted_sector_film()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", bf.ResolutionWarning)
        res = bf.solve_reynolds(bf.mesh_surface(surface, 0.04), film, formulation="direct", estimate_error=True)
        adapted = bf.adapt(surface, film, size=0.1, formulation="direct", tol=1e-3)
    true = abs(res.integral / reference - 1.0)
    assert res.load_error.relative == pytest.approx(true, rel=0.05)
    assert res.load_error.extrapolated_integral == pytest.approx(reference, rel=3e-4)
    assert adapted.load == pytest.approx(adapted.result.integral, rel=1e-15)
    assert abs(adapted.load / reference - 1.0) < 2 * adapted.error_estimate < 2e-3
