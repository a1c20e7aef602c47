"""The orderings section of the benchmark page says what its own table says.

``docs/benchmarks_parts/orderings.md`` is written by ``benchmarks/run_all.py`` (part ``orderings``,
:mod:`benchmarks.orderings`) from the measured rows; the fill ratios against minimum degree and
the sentence naming from which size nested dissection fills less are re-derived here from the
fills in the same table (timings themselves are never asserted).
"""

import re

from tests.helpers import ROOT, markdown_table

PART = ROOT / "docs" / "benchmarks_parts" / "orderings.md"


def _table():
    return markdown_table(PART.read_text(), "| mesh | dofs | order")[1]


def test_fill_ratios_and_crossovers_follow_the_table():
    rows = [r for r in _table() if r[5] != "-"]
    assert rows, "the table has no measured row"
    fill = {(r[0], int(r[1]), r[2]): int(r[5]) for r in rows}
    ratios: dict = {}
    for (mesh, dofs, order), value in fill.items():
        row = next(r for r in rows if (r[0], int(r[1]), r[2]) == (mesh, dofs, order))
        base = fill.get((mesh, dofs, "mmd"))
        if base is None:
            assert row[6] == "-"
            continue
        assert abs(float(row[6]) - value / base) <= 5e-4  # printed to three decimals
        ratios.setdefault((mesh, order), []).append((dofs, value / base))
    said = re.search(r"Fills less than `mmd` at this and every larger measured size: (.*)\.", PART.read_text())[1]
    claims = dict(re.findall(r"(\w+ P\d \w+) (from ~[\de.+-]+|never)", said))
    for (mesh, order), series in ratios.items():
        if order == "mmd":
            continue
        start = None
        for dofs, ratio in sorted(series, reverse=True):
            if ratio >= 1.0:
                break
            start = dofs
        claim = claims[f"{mesh} {order}"]
        if start is None:
            assert claim == "never"
        else:  # the page names the target size (1e4, 1e5, ...), the table the unknowns it gave
            assert claim.startswith("from ~") and 0.7 <= start / float(claim[6:]) <= 1.3
