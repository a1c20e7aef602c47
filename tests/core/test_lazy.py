"""Packages that import a public name's module on first use (bearingfe.core.lazy)."""
from __future__ import annotations

import subprocess
import sys

import pytest

from bearingfe.core.lazy import lazy_names


def test_a_name_loads_its_module_once_and_stays():
    namespace: dict = {}
    getattr_, dir_, names = lazy_names("bearingfe.core", {"scales": ("Scale",), "limits": ("check_limit",)}, namespace)
    from bearingfe.core.scales import Scale

    assert names == ["Scale", "check_limit"]
    assert getattr_("Scale") is Scale and namespace["Scale"] is Scale
    assert set(dir_()) >= {"Scale", "check_limit"}
    with pytest.raises(AttributeError, match="no attribute 'Nope'"):
        getattr_("Nope")


def test_a_name_under_two_modules_is_refused():
    with pytest.raises(ValueError, match="'Scale' is listed under 'scales' and 'limits'"):
        lazy_names("bearingfe.core", {"scales": ("Scale",), "limits": ("Scale",)}, {})


def test_the_pump_shoe_does_not_import_the_journal_solvers():
    # the reason for the lazy tables: asking for the pump does not load the journal or tilting-pad code
    code = ("import sys, bearingfe.bearings as b; b.EccentricPump; "
            "print(int('bearingfe.bearings.journal' in sys.modules), int('bearingfe.bearings.tilting_pad' in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["0", "0"]


def test_without_collections_keeps_the_collector_off_inside_and_restores_its_state():
    import gc

    from bearingfe.core.lazy import without_collections

    assert gc.isenabled()  # pytest runs with the collector on
    with pytest.raises(RuntimeError):
        with without_collections():
            assert not gc.isenabled()
            raise RuntimeError  # an import that fails restores it too
    assert gc.isenabled()
    gc.disable()
    try:  # a collector that was off stays off
        with without_collections():
            assert not gc.isenabled()
        assert not gc.isenabled()
    finally:
        gc.enable()


def test_the_command_line_leaves_the_collector_on_after_its_imports():
    # bearingfe.cli loads the package with the collector off and turns it back on
    out = subprocess.run([sys.executable, "-c", "import gc, bearingfe.cli; print(gc.isenabled())"],
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "True"
