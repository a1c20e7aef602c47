"""The cavitation-cost section of the benchmark page says what its own table says.

``docs/benchmarks_parts/cavitation.md`` is written by ``benchmarks/run_all.py`` (part
``cavitation``, :mod:`benchmarks.cavitation_cost`) from the measured rows; the ratio columns,
the worst ratio and the 3x verdict are re-derived here from the times in the same table
(timings themselves are never asserted).
"""

import re

import pytest
from tests.helpers import ROOT

PART = ROOT / "docs" / "benchmarks_parts" / "cavitation.md"


def test_ratios_and_verdict_follow_the_table():
    text = PART.read_text()
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| element | unknowns"))
    worst = {}
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        if cells[-1].startswith("FAILED"):
            continue
        element, linear, reynolds, ratio = cells[0], float(cells[3]), float(cells[4]), float(cells[5])
        # the times are printed to 3 significant digits, the ratio from the unrounded times
        assert ratio == pytest.approx(reynolds / linear, rel=2e-2)
        worst[element] = max(worst.get(element, 0.0), ratio)
    assert worst, "the table has no measured row"
    said = dict(re.findall(r"(P\d) ([\d.]+)", re.search(r"Worst Reynolds / linear ratio: (.*)\.", text)[1]))
    for element, value in worst.items():
        assert float(said[element]) == pytest.approx(value, abs=0.011)
    verdicts = dict(re.findall(r"(P\d) (yes|NO)", re.search(r"at every measured size: (.*)\.", text)[1]))
    for element, value in worst.items():
        assert verdicts[element] == ("yes" if float(said[element]) <= 3.0 else "NO")
