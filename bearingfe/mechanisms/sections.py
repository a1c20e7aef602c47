"""Beam sections as data: Soviet hot-rolled I-beams No. 20 ... 24a.

The table lives in ``bearingfe/data/ibeams_gost8239.csv`` (package data), in
the standard's own units (cm^2, cm^4, kg/m); :func:`ibeam` converts to SI.
Source: GOST 8239 hot-rolled I-beams (paper 002 cites GOST 8239-89; the
"a" sizes are listed in the 1972 edition of the same table).
"""

from __future__ import annotations

import csv
import io
from functools import lru_cache
from importlib import resources

from .machines import Section

__all__ = ["IBEAM_SOURCE", "ibeam", "ibeams", "ibeam_names"]

IBEAM_SOURCE = "GOST 8239 hot-rolled I-beams (cited in paper 002 as GOST 8239-89)"
_DATA = "ibeams_gost8239.csv"


@lru_cache(maxsize=1)
def ibeams() -> dict:
    """All tabulated I-beams, name -> :class:`~bearingfe.mechanisms.machines.Section` (SI)."""
    text = resources.files("bearingfe").joinpath("data", _DATA).read_text(encoding="utf-8")
    rows = [line for line in text.splitlines() if line and not line.startswith("#")]
    table = {}
    for row in csv.DictReader(io.StringIO("\n".join(rows))):
        table[row["name"]] = Section(
            name=row["name"],
            area=float(row["area_cm2"]) * 1e-4,
            ix=float(row["ix_cm4"]) * 1e-8,
            iy=float(row["iy_cm4"]) * 1e-8,
            mass_per_length=float(row["mass_kg_per_m"]),
            source=IBEAM_SOURCE,
        )
    return table


def ibeam_names() -> tuple:
    """Designations in table order, e.g. ``('20', '20a', ...)``."""
    return tuple(ibeams())


def ibeam(name: str) -> Section:
    """I-beam section by designation (``"20a"``, ``"No. 20a"``, ``"24"`` ...).

    Raises
    ------
    ValueError
        If the designation is not in the table.
    """
    key = str(name).lower().replace("no.", "").replace("№", "").strip()
    table = ibeams()
    if key not in table:
        raise ValueError(f"section must be one of {sorted(table)}, got {name!r}")
    return table[key]
