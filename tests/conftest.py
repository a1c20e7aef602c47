"""Shared fixtures of the test suite and the ``slow`` marker.

Fixtures (session-scoped: the objects are frozen parameter objects and meshes
that no test mutates, so one copy serves every file):

``root``           the repository root (``Path``; module-level code imports ``ROOT`` from ``tests/helpers.py``)
``pump``           the shipped eccentric pump, ``mechanisms/eccentric_pump.toml`` (10 % central pocket)
``plain_pump``     the same pump with the pocket removed (same arc and width)
``pocket_mesh``    ``pump_mesh(pump, 0.15)``: the coarse P1 shoe mesh (~90 nodes) of the pump tests
``plain_mesh``     ``pump_mesh(plain_pump, 0.15)``
``snt32``          paper 000's crank-slider pump, ``mechanisms/snt32.toml``
``d816``           paper 002's rotor on an elastic frame, ``mechanisms/converter_tilt_d816.toml``
``mill``           paper 003's assumed mill drive, ``mechanisms/hpt_mill.toml``
``results_agree``  ``results_agree(a, b, rtol)``: two film results (pressure, loads, integrals,
                   friction, every flow and the mass balance) agree to ``rtol`` of each quantity's
                   largest value (the flows and mass balance: of the largest flow)
``scene_file``     ``scene_file(kind, *layers, **overrides)``: writes a scene file built from the shipped
                   scene of that kind into the test's ``tmp_path`` and returns its path (see :func:`scene_file`)

Marker ``slow`` (registered in ``pyproject.toml``): a test that takes more
than about 5 s on an idle 2-core machine (whole examples, README blocks, the
generated docs page). CI runs every test, slow ones included
(``scripts/run-tests.sh`` passes no ``-m``); while developing, deselect them
with ``pytest -m "not slow"``.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

import bearingfe as bf
from bearingfe.transient.quasi_static import pump_mesh
from tests.helpers import ROOT, scene_data, toml_text

#: Element size [R0] of the shared pump meshes.
PUMP_MESH_SIZE = 0.15


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def pump() -> bf.EccentricPump:
    return bf.load_mechanism(ROOT / "mechanisms" / "eccentric_pump.toml")


@pytest.fixture(scope="session")
def plain_pump(pump) -> bf.EccentricPump:
    return dataclasses.replace(pump, surface=bf.Surface(arc=pump.surface.arc, half_width=pump.surface.half_width))


@pytest.fixture(scope="session")
def pocket_mesh(pump) -> bf.SupportMesh:
    return pump_mesh(pump, PUMP_MESH_SIZE)


@pytest.fixture(scope="session")
def plain_mesh(plain_pump) -> bf.SupportMesh:
    return pump_mesh(plain_pump, PUMP_MESH_SIZE)


@pytest.fixture(scope="session")
def snt32():
    return bf.load_mechanism(ROOT / "mechanisms" / "snt32.toml")


@pytest.fixture(scope="session")
def d816():
    return bf.load_mechanism(ROOT / "mechanisms" / "converter_tilt_d816.toml")


@pytest.fixture(scope="session")
def mill():
    return bf.load_mechanism(ROOT / "mechanisms" / "hpt_mill.toml")


def _assert_results_agree(a, b, rtol: float) -> None:
    def close(x, y, scale=None):
        x, y = np.asarray(x, float), np.asarray(y, float)
        scale = np.max(np.abs(y)) if scale is None else scale
        assert np.max(np.abs(x - y)) <= rtol * scale

    for name in ("pressure", "force", "integral", "friction"):
        close(getattr(a, name), getattr(b, name))
    assert set(a.flows) == set(b.flows)
    flow_scale = max(abs(v) for v in b.flows.values())
    for name in b.flows:
        close(a.flows[name], b.flows[name], flow_scale)
    close(a.mass_balance, b.mass_balance, flow_scale)


@pytest.fixture(scope="session")
def results_agree():
    return _assert_results_agree


@pytest.fixture
def scene_file(tmp_path):
    """``scene_file(kind, *layers, name=None, text=None, **overrides) -> Path``: a scene file in ``tmp_path``.

    ``kind`` (``"reynolds"``, ``"pump"``, ``"journal"``) names the shipped scene the file starts from
    (``scenes/default.toml``, ``scenes/pump.toml``, ``scenes/journal.toml``, read with ``tomllib``; the
    pump's relative ``mechanism`` path made absolute). Each override is a top-level key of the scene:
    a table merges into the shipped table (nested tables too), ``None`` removes a key, a dict with
    integer keys edits the items of an array of tables by position, any other value replaces
    (``scene_file("pump", run={"revolutions": 0.25}, output={"pictures": []})``;
    :func:`tests.helpers.apply_overrides`). ``layers`` are dicts of such overrides applied first, in
    order (a test file's small scene, then a parametrized row's change). ``text`` writes that text as
    it is instead (no kind, no overrides), for a file that must not be a valid scene. ``name`` is the
    file's path relative to ``tmp_path`` (default ``<kind>.toml``); its folder is created. Writing the
    same name again replaces the file.
    """

    def write(kind: str | None = None, /, *layers, name: str | None = None, text: str | None = None,
              **overrides) -> Path:
        if text is None:
            text = toml_text(scene_data(kind, *layers, **overrides))
        elif kind is not None or layers or overrides:
            raise TypeError("scene_file: text= is written as it is; give no kind and no overrides with it")
        path = tmp_path / (name or f"{kind or 'scene'}.toml")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        return path

    return write
