"""Shared fixtures of the test suite and the ``slow`` marker.

Fixtures (session-scoped: the objects are frozen parameter objects and meshes
that no test mutates, so one copy serves every file):

``root``           the repository root (``Path``)
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

ROOT = Path(__file__).resolve().parents[1]
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
