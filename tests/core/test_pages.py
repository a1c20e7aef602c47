"""NumPy's huge-page advice switched off while a large solve runs (:mod:`bearingfe.core.pages`)."""

import numpy as np
import pytest

from bearingfe import Circle, Recess, Surface, grid_mesh
from bearingfe.core import pages
from bearingfe.film import finite_volume as fv
from bearingfe.film.thickness import UniformFilm


def _dimpled():
    """Two circular dimples on a unit slider: a cavitating JFO case."""
    return Surface(arc=(0.0, 1.0), half_width=0.5,
                   recesses=[Recess(Circle((0.3, 0.0), 0.15), 0.5), Recess(Circle((0.7, 0.0), 0.15), 1.0)])


class _Switch:
    """A stand-in for NumPy's switch: records the settings it is given and returns the previous one."""

    def __init__(self, setting: bool):
        self.setting, self.calls = setting, []

    def __call__(self, new: bool) -> bool:
        self.calls.append(new)
        previous, self.setting = self.setting, bool(new)
        return previous


def _switch_and_spy(monkeypatch, module, name: str) -> tuple[_Switch, list]:
    """A stand-in switch (the advice on) installed for :mod:`bearingfe.core.pages`, and ``module.name`` wrapped to
    record the switch's setting at each call: the list it records into."""
    switch, seen = _Switch(True), []
    monkeypatch.setattr(pages, "_advice_switch", lambda: switch)
    original = getattr(module, name)

    def spy(*args, **kwargs):
        seen.append(switch.setting)
        return original(*args, **kwargs)

    monkeypatch.setattr(module, name, spy)
    return switch, seen


@pytest.mark.parametrize("before", [True, False])
def test_small_pages_switches_the_advice_off_and_restores_it(monkeypatch, before):
    switch = _Switch(before)
    monkeypatch.setattr(pages, "_advice_switch", lambda: switch)
    with pages.small_pages():
        assert switch.setting is False
        with pages.small_pages():   # nested: still off, and off again after the inner exit
            assert switch.setting is False
        assert switch.setting is False
    assert switch.setting is before


def test_small_pages_restores_the_advice_after_an_error(monkeypatch):
    switch = _Switch(True)
    monkeypatch.setattr(pages, "_advice_switch", lambda: switch)
    with pytest.raises(RuntimeError), pages.small_pages():
        raise RuntimeError("inside")
    assert switch.setting is True


def test_small_pages_off_or_without_numpys_switch_changes_nothing(monkeypatch):
    switch = _Switch(True)
    monkeypatch.setattr(pages, "_advice_switch", lambda: switch)
    monkeypatch.setattr(pages, "SMALL_PAGES", False)   # read at call time
    with pages.small_pages():
        assert switch.setting is True
    assert switch.calls == []
    monkeypatch.setattr(pages, "SMALL_PAGES", True)
    monkeypatch.setattr(pages, "_advice_switch", lambda: None)
    with pages.small_pages():
        pass


def test_this_numpy_has_the_switch():
    """The switch is found on the NumPy this project runs on (else the context would silently do nothing)."""
    assert callable(pages._advice_switch())


def test_jfo_solve_runs_on_small_pages_with_the_same_answer(monkeypatch):
    """:func:`solve_jfo` assembles, solves and postprocesses with the advice off and restores it; the pages an
    array lies on change no value: pressure and theta equal bit for bit to a solve with the advice left on."""
    mesh = grid_mesh(_dimpled(), 1 / 20)
    want = fv.solve_jfo(mesh, UniformFilm(1.0), cavitation_pressure=-0.05)
    switch, seen = _switch_and_spy(monkeypatch, fv, "_assemble")
    got = fv.solve_jfo(grid_mesh(_dimpled(), 1 / 20), UniformFilm(1.0), cavitation_pressure=-0.05)
    assert seen and not any(seen)
    assert switch.setting is True and switch.calls == [False, True]
    assert np.array_equal(got.pressure, want.pressure) and np.array_equal(got.theta, want.theta)


@pytest.mark.parametrize("before", [True, False])
def test_interleaved_contexts_leave_the_advice_as_before_the_first(monkeypatch, before):
    """Two contexts that close in the order they opened (as two threads' solves may: A opens, B opens, A closes,
    B closes) keep the advice off until the last closes, then restore the setting before the first; a context
    that restored its own previous setting would leave it off for good (B's previous is A's "off")."""
    switch = _Switch(before)
    monkeypatch.setattr(pages, "_advice_switch", lambda: switch)
    a, b = pages.small_pages(), pages.small_pages()
    a.__enter__()
    b.__enter__()
    a.__exit__(None, None, None)
    assert switch.setting is False   # B still open
    b.__exit__(None, None, None)
    assert switch.setting is before and pages._OPEN["count"] == 0


@pytest.mark.parametrize("cavitation", ["none", "reynolds", "gumbel"])
def test_finite_element_solve_runs_on_small_pages_with_the_same_answer(monkeypatch, cavitation):
    """:func:`bearingfe.solve_reynolds` on the finite-element path assembles and solves its model with the advice
    off and restores it; the pressure (and the rupture set) equal bit for bit to a solve with the advice left on
    (the pages an array lies on change no value)."""
    from bearingfe import CosineFilm, mesh_surface, reynolds, solve_reynolds

    surface, film = Surface(arc=(0.0, 2.0), half_width=0.5), CosineFilm(0.6, 3.4)
    mesh = mesh_surface(surface, 0.1)
    want = solve_reynolds(mesh, film, cavitation=cavitation)
    switch, seen = _switch_and_spy(monkeypatch, reynolds, "solve_model")
    got = solve_reynolds(mesh, film, cavitation=cavitation)
    assert seen == [False]
    assert switch.setting is True and switch.calls == [False, True]
    assert np.array_equal(got.pressure, want.pressure)
    if cavitation != "none":
        assert got.cavitated is not None and np.array_equal(got.cavitated, want.cavitated)


def test_elastic_solve_runs_on_small_pages_with_the_same_answer(monkeypatch):
    """:func:`bearingfe.elastic.solve_elastic` runs its Newton iteration (a film solve and a Jacobian a step) with
    the advice off and restores it; pressure and deflection equal bit for bit to a solve with the advice left on.
    The case: the kinds benchmark's film on two steel half-spaces at the pump's scale (its largest opening is
    a fraction of the clearance, so the coupling matters), Swift-Stieber cavitation, a coarse grid."""
    from bearingfe import CosineFilm, Material, Scale
    from bearingfe.elastic import coupled, half_space_fft, solve_elastic

    mesh, film = grid_mesh(Surface(arc=(-1.0, 1.0), half_width=0.5), 1 / 10), CosineFilm(0.6, 3.44)
    steel = Material("steel", 210e9, poisson_ratio=0.3)
    compliance = half_space_fft(mesh, Scale(radius=0.05, clearance=20e-6, viscosity=0.03, speed=157.08),
                                (steel, steel))
    want = solve_elastic(mesh, film, compliance, cavitation="reynolds")
    switch, seen = _switch_and_spy(monkeypatch, coupled, "newton")
    got = solve_elastic(mesh, film, compliance, cavitation="reynolds")
    assert seen == [False] and want.max_deflection > 0
    assert switch.setting is True and switch.calls == [False, True]
    assert np.array_equal(got.result.pressure, want.result.pressure)
    assert np.array_equal(got.deflection, want.deflection)
