"""Tilting-pad journal bearings: equilibrium, the coefficients over shaft and pads, Lund's reduction.

Published reference: T. Someya (ed.), Journal-Bearing Databook, Springer 1989, four-pad tilting-pad
bearing, L/D = 0.5, zero preload, as transcribed in the task that asked for this module (three rows,
three significant digits). The transcription gives no pad arc or pivot position; the assumed ones
are the databook's and ISO 31657-3's four-pad bearing: 80-degree pads, centred pivots (offset 0.5),
Reynolds (Swift-Stieber) film rupture, rigid pivots, massless pads, synchronous coefficients, the
databook's x along the load (the package's -y). docs/tilting_pad_validation.md has the comparison and where the
package and the table differ.

Independent references of the other tests: the fixed-pad bearing of
:mod:`bearingfe.bearings.journal` (pads locked), the bearing's symmetry (no cross-coupling with
massless pads), the static stiffness as the change of the equilibria under a change of load, and
Lund's per-pad closed form of the reduction.
"""

import math

import numpy as np
import pytest

from bearingfe.bearings import journal
from bearingfe.bearings.tilting_pad import (TiltingPadBearing, TiltingPadConvergenceError, TiltingPadGeometry,
                                            pad_assembly_coefficients, tilting_pad_equilibrium, tilting_pad_meshes)

SOMEYA = TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), offset=0.5, preload=0.0)


def _at_eps(geometry, eps, meshes):
    """Equilibrium at a given eccentricity: the secant method on log(load) (loads along -y), warm-started."""
    logs, values, eq = [], [], None
    for log_w in (math.log(0.5), 0.0):
        eq = tilting_pad_equilibrium(geometry, (0.0, -math.exp(log_w)), meshes=meshes, start=eq, tol=1e-10)
        logs.append(log_w)
        values.append(eq.eps - eps)
    for _ in range(20):
        if abs(values[-1]) < 1e-9:
            return eq
        log_w = logs[-1] - values[-1] * (logs[-1] - logs[-2]) / (values[-1] - values[-2])
        log_w = min(max(log_w, logs[-1] - 1.0), logs[-1] + 1.0)
        eq = tilting_pad_equilibrium(geometry, (0.0, -math.exp(log_w)), meshes=meshes, start=eq, tol=1e-10)
        logs.append(log_w)
        values.append(eq.eps - eps)
    raise AssertionError("no load found for the eccentricity")


# -- parameters -----------------------------------------------------------------------------------

@pytest.mark.parametrize("kwargs", [dict(length_ratio=0.0), dict(n_pads=1), dict(n_pads=4.0), dict(n_pads=True),
                                    dict(arc=math.radians(91)), dict(offset=1.0), dict(preload=1.0),
                                    dict(preload=-0.1), dict(load_on_pad="yes")])
def test_geometry_refuses_what_is_no_bearing(kwargs):
    with pytest.raises(ValueError):
        TiltingPadGeometry(**{"length_ratio": 0.5, **kwargs})


def test_pads_are_placed_by_the_load_orientation():
    on = TiltingPadGeometry(0.5, n_pads=4, load_on_pad=True)
    between = TiltingPadGeometry(0.5, n_pads=5, offset=0.6, arc=math.radians(60))
    assert on.pivots[0] == pytest.approx(-math.pi / 2)
    assert between.pivots[0] == pytest.approx(-math.pi / 2 + math.pi / 5)
    start, end = between.arcs[0]
    assert end - start == pytest.approx(math.radians(60))
    assert (between.pivots[0] - start) / (end - start) == pytest.approx(0.6)  # offset from the leading edge


def test_si_bearing_gives_the_nondimensional_currency():
    b = TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=75e-6, n_pads=5, arc=math.radians(60),
                          preload=0.3, pad_inertia=2e-4, pad_thickness=0.01)
    assert b.geometry.length_ratio == 0.5 and b.geometry.preload == 0.3
    mu, omega = 0.02, 1000.0
    assert b.force_scale(mu, omega) == pytest.approx(mu * omega * 0.05**4 / 75e-6**2)
    # I_p / R_piv^2 is the pad's mass at the film; times c omega^2 / (force scale / c) per unit rotation
    assert b.pad_mass(mu, omega) == pytest.approx(2e-4 / 0.06**2 * 75e-6**3 * omega / (mu * 0.05**4))
    with pytest.raises(ValueError):
        TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=1e-3)  # not a thin film
    with pytest.raises(ValueError):
        TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=75e-6, pad_inertia=-1.0)
    flexible = TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=75e-6, pivot_stiffness=5e8)
    assert flexible.pivot_stiffness_parameter(mu, omega) == pytest.approx(5e8 * 75e-6**3 / (mu * omega * 0.05**4))
    assert b.pivot_stiffness_parameter(mu, omega) == math.inf
    with pytest.raises(ValueError):
        TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=75e-6, pivot_stiffness=0.0)


def test_meshes_are_one_pad_turned():
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    assert len({m.n_nodes for m in meshes}) == 1
    for m, (start, end) in zip(meshes, SOMEYA.arcs):
        assert m.mesh.p[0].min() == pytest.approx(start) and m.mesh.p[0].max() == pytest.approx(end)
    assert tilting_pad_meshes(SOMEYA, 0.1, refine=1)[0].n_elements == 4 * meshes[0].n_elements


# -- equilibrium ----------------------------------------------------------------------------------

@pytest.mark.parametrize("n_pads, arc, on_pad", [(4, 80, False), (4, 80, True), (5, 60, False), (5, 60, True)])
def test_equilibrium_from_a_cold_start_at_light_to_heavy_loads(n_pads, arc, on_pad):
    g = TiltingPadGeometry(0.5, n_pads=n_pads, arc=math.radians(arc), offset=0.5, load_on_pad=on_pad)
    meshes = tilting_pad_meshes(g, 0.1)
    _, t = g.normals()
    eps = []
    for w in (0.05, 0.4, 1.5, 4.0, 15.0):
        eq = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes)  # cold start every time
        assert eq.residual <= 1e-8
        np.testing.assert_allclose(eq.force, (0.0, -w), atol=1e-8 * w)
        # every pad carries its load through its pivot: no moment
        assert np.abs(np.einsum("ij,ij->i", eq.pad_forces, t)).max() <= 1e-8 * w
        assert eq.attitude < 1e-3  # symmetric about the load line: the shaft moves along the load
        eps.append(eq.eps)
    assert np.all(np.diff(eps) > 0) and eps[0] < 0.2 and eps[-1] > 0.88


def test_warm_start_takes_fewer_newton_steps():
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    cold = tilting_pad_equilibrium(SOMEYA, (0.0, -1.0), meshes=meshes)
    warm = tilting_pad_equilibrium(SOMEYA, (0.0, -1.05), meshes=meshes, start=cold)
    again = tilting_pad_equilibrium(SOMEYA, (0.0, -1.05), meshes=meshes)
    assert warm.newton_iterations <= 3 < cold.newton_iterations
    np.testing.assert_allclose(warm.position, again.position, atol=1e-8)
    np.testing.assert_allclose(warm.tilts, again.tilts, atol=1e-6)


def test_oblique_load_and_preload_and_offset():
    # a load 30 degrees off the axis on a preloaded five-pad bearing with offset pivots: every force and
    # moment balances, the preload keeps every pad loaded, and massless pads, each pushing through its
    # pivot, make a force field with a potential: the static stiffness is symmetric
    g = TiltingPadGeometry(0.75, n_pads=5, arc=math.radians(60), offset=0.6, preload=0.3)
    load = 0.8 * np.array([math.sin(math.radians(30)), -math.cos(math.radians(30))])
    eq = tilting_pad_equilibrium(g, load, meshes=tilting_pad_meshes(g, 0.1))
    _, t = g.normals()
    np.testing.assert_allclose(eq.force, load, atol=1e-8)
    assert np.abs(np.einsum("ij,ij->i", eq.pad_forces, t)).max() <= 1e-8
    assert not eq.idle.any()
    K0 = pad_assembly_coefficients(eq).reduced(0.0).K
    assert abs(K0[0, 1] - K0[1, 0]) <= 1e-7 * np.abs(K0).max() and abs(K0[0, 1]) > 1e-4 * np.abs(K0).max()


def test_mass_conserving_film_agrees_with_swift_stieber_on_flooded_pads():
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    ss = tilting_pad_equilibrium(SOMEYA, (0.0, -0.4), meshes=meshes)
    jfo = tilting_pad_equilibrium(SOMEYA, (0.0, -0.4), meshes=meshes, cavitation="jfo")
    assert jfo.residual <= 1e-8
    # pads fed at zero pressure at every edge: the two rupture models differ by the reformation only
    assert jfo.eps == pytest.approx(ss.eps, rel=1e-3)
    red_ss, red_jfo = pad_assembly_coefficients(ss).reduced(), pad_assembly_coefficients(jfo).reduced()
    np.testing.assert_allclose(red_jfo.K, red_ss.K, atol=3e-3 * np.abs(red_ss.K).max())
    np.testing.assert_allclose(red_jfo.C, red_ss.C, atol=3e-3 * np.abs(red_ss.C).max())


def test_named_errors():
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    with pytest.raises(TiltingPadConvergenceError):
        tilting_pad_equilibrium(SOMEYA, (0.0, -1.0), meshes=meshes, max_newton=1)
    with pytest.raises(ValueError, match="cavitation"):
        tilting_pad_equilibrium(SOMEYA, (0.0, -1.0), meshes=meshes, cavitation="none")
    with pytest.raises(ValueError, match="load"):
        tilting_pad_equilibrium(SOMEYA, (0.0, 0.0), meshes=meshes)


# -- coefficients ---------------------------------------------------------------------------------

@pytest.mark.parametrize("on_pad", [False, True])
def test_locked_pads_are_the_fixed_pad_journal_bearing(on_pad):
    # pads held at zero rotation without preload are JournalBearing(pads=arcs): same position, same
    # eight coefficients, on the same meshes, to round-off
    g = TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), load_on_pad=on_pad)
    bearing = g.fixed_pads
    load = (0.3, -1.2)
    fixed = journal.equilibrium(bearing, load, size=0.1, min_size=0.1)
    reference = journal.dynamic_coefficients(journal.equilibrium(bearing, (0.0, -1.2), size=0.1, min_size=0.1))
    meshes = journal.journal_mesh(bearing, 0.1, min_size=0.1)
    eq = tilting_pad_equilibrium(g, load, meshes=meshes, locked_tilts=np.zeros(4))
    np.testing.assert_allclose(eq.position, fixed.position, atol=1e-9)
    locked = pad_assembly_coefficients(tilting_pad_equilibrium(g, (0.0, -1.2), meshes=meshes,
                                                               locked_tilts=np.zeros(4))).locked()
    np.testing.assert_allclose(locked.K, reference.K, atol=1e-9 * np.abs(reference.K).max())
    np.testing.assert_allclose(locked.C, reference.C, atol=1e-9 * np.abs(reference.C).max())


@pytest.mark.parametrize("n_pads, arc, on_pad", [(4, 80, False), (4, 80, True), (5, 60, False), (5, 60, True)])
def test_massless_pads_have_no_cross_coupling(n_pads, arc, on_pad):
    # each massless pad carries its force through its pivot, so its reduced impedance is z n n^T:
    # symmetric, and diagonal in the load frame by the bearing's symmetry about the load line
    g = TiltingPadGeometry(0.5, n_pads=n_pads, arc=math.radians(arc), load_on_pad=on_pad)
    eq = tilting_pad_equilibrium(g, (0.0, -0.8), meshes=tilting_pad_meshes(g, 0.1))
    full = pad_assembly_coefficients(eq)
    for nu in (0.5, 1.0, 2.0):
        red = full.reduced(nu)
        for M in (red.K, red.C):
            assert abs(M[0, 1]) <= 1e-7 * np.abs(M).max() and abs(M[1, 0]) <= 1e-7 * np.abs(M).max()
    # with heavy pads the reduced stiffness is no longer symmetric: the pads' lag couples x and y
    heavy = full.reduced(1.0, pad_mass=50.0)
    assert abs(heavy.K[0, 1] - heavy.K[1, 0]) > 1e-3 * np.abs(heavy.K).max() or on_pad


def test_static_reduction_is_the_stiffness_of_the_equilibria():
    # K(Omega = 0) = dW/dx with the pads re-balanced: central differences of equilibria under changed loads
    g = TiltingPadGeometry(0.5, n_pads=5, arc=math.radians(60), offset=0.6, preload=0.2)
    meshes = tilting_pad_meshes(g, 0.1)
    w = 0.8
    eq = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes, tol=1e-12)
    K0 = pad_assembly_coefficients(eq).reduced(0.0).K * w
    d = 1e-5 * w
    compliance = np.zeros((2, 2))
    for j in range(2):
        step = np.zeros(2)
        step[j] = d
        up = tilting_pad_equilibrium(g, np.array([0.0, -w]) + step, meshes=meshes, start=eq, tol=1e-12)
        down = tilting_pad_equilibrium(g, np.array([0.0, -w]) - step, meshes=meshes, start=eq, tol=1e-12)
        compliance[:, j] = (up.position - down.position) / (2 * d)
    np.testing.assert_allclose(np.linalg.inv(compliance), K0, atol=1e-6 * np.abs(K0).max())


def _lund(full, nu, mass, geometry):
    """Lund's per-pad closed form: Z = sum_i [Z_i - (Z_i t_i)(t_i^T Z_i) / (t_i^T Z_i t_i - nu^2 M)] with Z_i the
    pad's 2x2 film impedance in the shaft's coordinates (read off the full matrices: its shaft block is
    the sum of the pads', and its pad row is t_i^T Z_i)."""
    _, t = geometry.normals()
    Z = full.K + 1j * nu * full.C
    out = Z[:2, :2].copy()
    for i in range(geometry.n_pads):
        zq = Z[2 + i, 2 + i] - nu**2 * mass / full.load
        out -= np.outer(Z[:2, 2 + i], Z[2 + i, :2]) / zq
        # the pad's row is t^T Z_i and its column Z_i t: the assembly T_i^T Z_i T_i
        assert Z[2 + i, 2 + i] == pytest.approx(t[i] @ Z[:2, 2 + i])
    return out.real, out.imag / nu


@pytest.mark.parametrize("mass", [0.0, 0.05, 0.5])
def test_frequency_dependence_is_lunds_pad_reduction(mass):
    g = TiltingPadGeometry(0.5, n_pads=5, arc=math.radians(60), offset=0.6, preload=0.25)
    eq = tilting_pad_equilibrium(g, (0.0, -0.6), meshes=tilting_pad_meshes(g, 0.1))
    full = pad_assembly_coefficients(eq)
    for nu in (0.2, 1.0, 3.0):
        K, C = _lund(full, nu, mass, g)
        red = full.reduced(nu, pad_mass=mass)
        np.testing.assert_allclose(red.K, K, atol=1e-10 * np.abs(K).max())
        np.testing.assert_allclose(red.C, C, atol=1e-10 * np.abs(C).max())
    # Omega -> 0 is continuous, and very heavy pads do not follow the shaft: the locked coefficients
    slow = full.reduced(1e-4)
    np.testing.assert_allclose(slow.C, full.reduced(0.0).C, atol=1e-6 * np.abs(slow.C).max())
    locked = full.locked().K
    np.testing.assert_allclose(full.reduced(1.0, pad_mass=1e9).K, locked, atol=1e-6 * np.abs(locked).max())


# -- Someya's tables ------------------------------------------------------------------------------

#: Someya's four-pad rows as transcribed: (load on pad, eps) -> quantities in the databook's frame
#: (x along the load). The package's (yy, xx) are the databook's (xx, yy).
SOMEYA_ROWS = {(False, 0.5): dict(S=0.756, K=1.94, B=3.33), (False, 0.8): dict(S=0.259, K=3.15, B=3.01),
               (True, 0.5): dict(S=0.316, Kxx=3.45, Kyy=0.0132, Bxx=4.67, Byy=1.98)}


@pytest.mark.slow
@pytest.mark.parametrize("eps, tol_S, tol_K, tol_B", [(0.5, 0.005, 0.02, 0.03), (0.8, 0.02, 0.06, 0.02)])
def test_someya_four_pads_load_between_pads(eps, tol_S, tol_K, tol_B):
    # size 0.025 (converged to 0.1 %, see the convergence test). The table's three digits would allow
    # 0.07 to 0.3 %; the package and the table differ by 0.3 % (S), 1.5 % (K), 2.4 % (B) at eps 0.5 and
    # by 1.8 %, 5.5 %, 1.7 % at eps 0.8 (docs/tilting_pad_validation.md): the tolerances are those differences
    # rounded up, the table's own discretization (1980s finite differences) and its assumed geometry
    ref = SOMEYA_ROWS[(False, eps)]
    eq = _at_eps(SOMEYA, eps, tilting_pad_meshes(SOMEYA, 0.1, refine=2))
    red = pad_assembly_coefficients(eq).reduced()
    assert eq.sommerfeld == pytest.approx(ref["S"], rel=tol_S)
    # load between pads: four-fold symmetry makes the reduced matrices isotropic
    for M, value, tol in ((red.K, ref["K"], tol_K), (red.C, ref["B"], tol_B)):
        assert M[0, 0] == pytest.approx(value, rel=tol) and M[1, 1] == pytest.approx(value, rel=tol)
        assert M[0, 0] == pytest.approx(M[1, 1], rel=1e-9)


@pytest.mark.slow
def test_someya_four_pads_load_on_pad():
    # the stiffness and damping along the load agree within 5.4 % and 7.7 %; the side pads, exactly
    # unloaded (a uniform film), give no stiffness (table 0.0132, i.e. zero to its precision relative to
    # Kxx) and the damping of their full film, 14 % below the table's. The table's S = 0.316 is not
    # reproduced (the package gives 0.517): see the next test and docs/tilting_pad_validation.md
    ref = SOMEYA_ROWS[(True, 0.5)]
    g = TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), offset=0.5, load_on_pad=True)
    eq = _at_eps(g, 0.5, tilting_pad_meshes(g, 0.1, refine=2))
    red = pad_assembly_coefficients(eq).reduced()
    assert red.K[1, 1] == pytest.approx(ref["Kxx"], rel=0.06)
    assert red.C[1, 1] == pytest.approx(ref["Bxx"], rel=0.08)
    assert abs(red.K[0, 0]) < 0.02 * red.K[1, 1] and ref["Kyy"] < 0.02 * ref["Kxx"]
    assert red.C[0, 0] == pytest.approx(ref["Byy"], rel=0.15)
    assert list(eq.idle) == [False, True, True, True]  # only the bottom pad carries load


def test_load_on_pad_is_the_loaded_pad_of_load_between_pads():
    # with no preload only the pads the shaft moves towards carry load, each by its distance s = x . n:
    # on pad at eps, the bottom pad has s = eps; between pads at eps sqrt(2), both lower pads have it,
    # each carrying W / sqrt(2). So S_on(eps) = sqrt(2) S_between(sqrt(2) eps) exactly (same pad mesh).
    # The table's rows (S 0.756 at 0.5, 0.259 at 0.8, log-interpolated: 0.361 at 0.707) then predict
    # S_on(0.5) = 0.51, not its 0.316
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    on = TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), offset=0.5, load_on_pad=True)
    eq_on = _at_eps(on, 0.5, tilting_pad_meshes(on, 0.1))
    eq_between = _at_eps(SOMEYA, 0.5 * math.sqrt(2), meshes)
    assert eq_on.sommerfeld == pytest.approx(math.sqrt(2) * eq_between.sommerfeld, rel=1e-7)
    interpolated = math.exp(np.interp(0.5 * math.sqrt(2), [0.5, 0.8], [math.log(0.756), math.log(0.259)]))
    assert math.sqrt(2) * interpolated == pytest.approx(eq_on.sommerfeld, rel=0.05)
    assert not SOMEYA_ROWS[(True, 0.5)]["S"] == pytest.approx(eq_on.sommerfeld, rel=0.3)


@pytest.mark.slow
def test_mesh_convergence_of_the_coefficients_is_second_order():
    # nested meshes (sizes 0.1, 0.05, 0.025), a fixed load: successive changes of the eccentricity and of
    # the synchronous K and C fall
    # by four, the order of P1 elements on a smooth film whose rupture front is resolved to the same order
    values = []
    eq = None
    for refine in range(3):
        eq = tilting_pad_equilibrium(SOMEYA, (0.0, -0.42), meshes=tilting_pad_meshes(SOMEYA, 0.1, refine=refine),
                                     start=eq, tol=1e-10)
        red = pad_assembly_coefficients(eq).reduced()
        values.append([eq.eps, red.K[0, 0], red.C[0, 0]])
    values = np.array(values)
    d = np.abs(np.diff(values, axis=0))
    order = np.log2(d[0] / d[1])
    assert np.all((order > 1.7) & (order < 2.3)), order
    assert np.all(d[1] / values[2] < 3e-3)  # the finest step changes them by less than 0.3 %


# -- ROSS tables ----------------------------------------------------------------------------------

def test_ross_table_over_speed_and_whirl_frequency():
    # SI: the table's entries are the reduced coefficients at (speed, frequency) in N/m and N s/m, the
    # synchronous ones the default reduction; every entry comes from the equilibrium at its own speed
    bearing = TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=75e-6, n_pads=5, arc=math.radians(60),
                                preload=0.2, pad_inertia=1e-4, pad_thickness=0.01)
    load, mu = 2000.0, 0.02
    speeds, frequencies = [300.0, 600.0], [150.0, 300.0, 600.0]
    from bearingfe.bearings.tilting_pad import ross_table
    table = ross_table(bearing, load, mu, speeds, frequencies, size=0.1)
    assert table["speed"] == speeds and table["frequency"] == frequencies
    assert np.shape(table["kxx"]) == (2, 3) and np.shape(table["cyx"]) == (2, 3)
    g = bearing.geometry
    speed = 600.0
    eq = tilting_pad_equilibrium(g, (0.0, -load / bearing.force_scale(mu, speed)),
                                 meshes=tilting_pad_meshes(g, 0.1))
    red = pad_assembly_coefficients(eq).reduced(1.0, pad_mass=bearing.pad_mass(mu, speed))
    K, C = red.to_si(viscosity=mu, speed=speed, radius=0.05, clearance=75e-6)
    assert table["kyy"][1][2] == pytest.approx(K[1, 1], rel=1e-6)
    assert table["cxx"][1][2] == pytest.approx(C[0, 0], rel=1e-6)
    assert table["kxy"][1][2] == pytest.approx(K[0, 1], rel=1e-6, abs=1e-6 * abs(K[1, 1]))
    # dimensions: K = K c/W * W / c
    assert K[1, 1] == pytest.approx(red.K[1, 1] * load / 75e-6)
    with pytest.raises(ValueError):
        ross_table(bearing, load, mu, [600.0, 300.0], frequencies)


# -- flexible pivots ------------------------------------------------------------------------------

def test_flexible_pivot_moves_the_shaft_by_the_pad_load_over_its_stiffness():
    # load on pad without preload: the bottom pad alone carries W; on a pivot of stiffness k it moves out
    # by W/k with the same film, so the shaft sits W/k lower with the loaded pad's rotation unchanged
    g = TiltingPadGeometry(0.5, n_pads=4, arc=math.radians(80), load_on_pad=True)
    meshes = tilting_pad_meshes(g, 0.1)
    w, k = 0.6, 3.0
    rigid = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes)
    flexible = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes, pivot_stiffness=k)
    np.testing.assert_allclose(flexible.position, rigid.position + np.array([0.0, -w / k]), atol=1e-8)
    assert flexible.tilts[0] == pytest.approx(rigid.tilts[0], abs=1e-7)  # (the unloaded pads follow the shaft)
    np.testing.assert_allclose(flexible.pad_forces, rigid.pad_forces, atol=1e-8)
    assert flexible.deflections[0] == pytest.approx(w / k, rel=1e-7)
    stiff = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes, pivot_stiffness=1e9)
    np.testing.assert_allclose(stiff.position, rigid.position, atol=1e-8)


def test_flexible_pivots_are_springs_in_series_with_the_pads():
    # load between pads: both loaded pads carry the same film, so the reduced impedance of the bearing is
    # isotropic, z I on rigid pivots, and each pad's pivot spring k in series with it: z k / (z + k), at
    # any whirl frequency (massless pads and pivots)
    meshes = tilting_pad_meshes(SOMEYA, 0.1)
    w, k = 0.5, 2.0
    rigid = pad_assembly_coefficients(tilting_pad_equilibrium(SOMEYA, (0.0, -w), meshes=meshes))
    flexible = pad_assembly_coefficients(tilting_pad_equilibrium(SOMEYA, (0.0, -w), meshes=meshes,
                                                                 pivot_stiffness=k))
    assert flexible.K.shape == (10, 10) and flexible.pivots
    for nu in (0.0, 0.5, 1.0, 2.0):
        r, f = rigid.reduced(nu), flexible.reduced(nu)
        z = complex(r.K[0, 0], nu * r.C[0, 0]) * w  # the pads' impedance along one pivot line, not normalized
        # two pads, each along its own pivot line with the whole z (their n n^T sum to the identity)
        series = z * k / (z + k) / w
        assert f.K[0, 0] == pytest.approx(series.real, rel=1e-6)
        assert nu == 0 or f.C[0, 0] == pytest.approx(series.imag / nu, rel=1e-6)
        assert abs(f.K[0, 1]) <= 1e-7 * abs(f.K[0, 0])


def _soft_bearing(n_pads, on_pad, pivot_stiffness):
    """The scene's five-pad bearing (scenes/journal_tilting.toml: D 100 mm, L 50 mm, C_p 80 um, 60 %
    offset, preload 0.25) or a four-pad one with 80-degree pads, on pivots of the given stiffness [N/m]."""
    arc = 60.0 if n_pads == 5 else 80.0
    return TiltingPadBearing(radius=0.05, length=0.05, pad_clearance=80e-6, n_pads=n_pads, arc=math.radians(arc),
                             offset=0.6, preload=0.25, load_on_pad=on_pad, pivot_stiffness=pivot_stiffness)


@pytest.mark.parametrize("n_pads, on_pad", [(4, False), (4, True), (5, False), (5, True)])
def test_soft_pivots_from_a_cold_start(n_pads, on_pad):
    # 5e8 and 1e9 N/m at 6000 rpm, 0.015 Pa s, loads 1, 4 and 12 kN, every solve from a cold start: the shaft
    # carries the load, every loaded pad has no moment about its pivot, and each pivot spring carries its
    # pad's radial film force (k xi = F . n) unless the film out-pushes it right up to the pad's unloaded
    # edge, where the pad sits (xi = s0 = n . x + m to 1e-6) carrying k xi; softer pivots let the shaft sink
    mu, omega = 0.015, 6000 * math.pi / 30
    n, t = _soft_bearing(n_pads, on_pad, 5e8).geometry.normals()
    meshes = tilting_pad_meshes(_soft_bearing(n_pads, on_pad, 5e8).geometry, 0.15)
    eps = {}
    for k_si in (5e8, 1e9):
        bearing = _soft_bearing(n_pads, on_pad, k_si)
        k = bearing.pivot_stiffness_parameter(mu, omega)
        for load in (1000.0, 4000.0, 12000.0):
            w = load / bearing.force_scale(mu, omega)
            eq = tilting_pad_equilibrium(bearing.geometry, (0.0, -w), meshes=meshes, pivot_stiffness=k)
            assert eq.residual <= 1e-8
            np.testing.assert_allclose(eq.force, (0.0, -w), atol=1e-8 * w)
            assert np.abs(np.einsum("ij,ij->i", eq.pad_forces, t)).max() <= 1e-8 * w
            radial = np.einsum("ij,ij->i", eq.pad_forces, n)
            s0 = n @ eq.position + bearing.preload
            loaded = s0 > 0
            np.testing.assert_allclose(radial[loaded], k * eq.deflections[loaded], rtol=1e-7, atol=1e-9 * w)
            assert np.all(eq.deflections[~loaded] == 0) and np.all(eq.deflections[loaded] > 0)
            assert np.all(eq.deflections[loaded] <= s0[loaded] + 1e-12)
            eps[k_si, load] = eq.eps
    for load in (1000.0, 4000.0, 12000.0):
        assert eps[5e8, load] > eps[1e9, load]
    for k_si in (5e8, 1e9):
        assert eps[k_si, 1000.0] < eps[k_si, 4000.0] < eps[k_si, 12000.0]


@pytest.mark.parametrize("n_pads, on_pad", [(4, True), (5, False)])
def test_stiff_pivots_reach_the_rigid_result(n_pads, on_pad):
    # the pads move out by F/k: at 1e15 N/m (C_p 80 um, k C_p^3/(mu omega R^4) = 8.7e6) that is below
    # 1e-7 C_p, and the shaft's position, the rotations and the pad forces agree with rigid pivots to that order
    mu, omega, load = 0.015, 6000 * math.pi / 30, 4000.0
    bearing = _soft_bearing(n_pads, on_pad, 1e15)
    g = bearing.geometry
    meshes = tilting_pad_meshes(g, 0.15)
    w = load / bearing.force_scale(mu, omega)
    rigid = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes)
    stiff = tilting_pad_equilibrium(g, (0.0, -w), meshes=meshes,
                                    pivot_stiffness=bearing.pivot_stiffness_parameter(mu, omega))
    assert 0 < stiff.deflections.max() < 1e-7
    np.testing.assert_allclose(stiff.position, rigid.position, atol=1e-6)
    np.testing.assert_allclose(stiff.tilts, rigid.tilts, atol=1e-5)
    np.testing.assert_allclose(stiff.pad_forces, rigid.pad_forces, atol=1e-5 * w)


def test_soft_pivot_pushes_a_pad_to_its_unloaded_edge():
    # the scene's bearing at its load (3.92 kN) on 5e8 N/m pivots: the top pad's film, with its pivot 60 %
    # along the arc, carries F(0+) ~ 0.17 [mu omega R^4/C_p^2] by its tilt alone however little the shaft
    # closes it, more than its spring carries at the deflection that empties it (k s0); so the pad sits at
    # the edge of its loaded range (x' . n + m = EDGE_GAP) with the spring's force k xi < F(0+), and the
    # bearing still carries the load. At 3 kN the same pad is loaded in the ordinary way (k xi = F(s) > F(0+)).
    from bearingfe.bearings.tilting_pad import EDGE_GAP
    mu, omega = 0.015, 6000 * math.pi / 30
    bearing = _soft_bearing(5, False, 5e8)
    n, _ = bearing.geometry.normals()
    k = bearing.pivot_stiffness_parameter(mu, omega)
    meshes = tilting_pad_meshes(bearing.geometry, 0.15)
    top = []
    for load in (3000.0, 3924.0):
        w = load / bearing.force_scale(mu, omega)
        eq = tilting_pad_equilibrium(bearing.geometry, (0.0, -w), meshes=meshes, pivot_stiffness=k)
        assert eq.residual <= 1e-8
        gap = float(n[2] @ eq.position) + bearing.preload - eq.deflections[2]
        film = float(eq.pads.states[2].force @ n[2])  # the film's own force at that gap
        top.append((gap, float(eq.pad_forces[2] @ n[2]), film))
    (gap3, carried3, film3), (gap4, carried4, film4) = top
    assert gap3 > 1e-3 and carried3 == pytest.approx(film3, rel=1e-8)
    assert gap4 == pytest.approx(EDGE_GAP, rel=1e-6)
    assert carried4 == pytest.approx(k * eq.deflections[2], rel=1e-12) and 0 < carried4 < 0.8 * film4
    assert film4 < film3  # F(s) rises with s: the edge's film force is the least
